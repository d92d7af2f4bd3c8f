"""How the rules print points in their one-line reasons."""

from __future__ import annotations

import numpy as np

__all__ = ["fmt_point"]


def fmt_point(p: np.ndarray) -> str:
    """``(x, y[, z])`` with six significant digits per coordinate."""
    return "(" + ", ".join(f"{v:.6g}" for v in np.asarray(p, dtype=np.float64).reshape(-1)) + ")"
