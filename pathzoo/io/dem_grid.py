"""The elevation grid that every DEM reader returns (:class:`DEM`)."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

__all__ = ["DEM"]


@dataclass(frozen=True, eq=False)
class DEM:
    """An elevation grid read from a file.

    Attributes
    ----------
    elevation : ndarray of float64, shape (H, W)
        Metres at cell centres; NaN where the file has no data. Read-only.
    cell_size : float or None
        Metres per cell, or ``None`` when the file does not say (``.npy``, or
        an ``.npz`` without ``dx``/``dy``).
    metadata : dict
        Provenance: file, SHA-256, header values, unit conversion.
    """

    elevation: np.ndarray
    cell_size: float | None
    metadata: dict[str, Any] = field(default_factory=dict)
