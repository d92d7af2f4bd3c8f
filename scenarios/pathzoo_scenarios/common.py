"""Helpers every scenario pack shares: package data, provenance metadata and reachability."""

from __future__ import annotations

from pathlib import Path
from typing import Any, Iterable

import numpy as np

from pathzoo.core.errors import InvalidParameterError

__all__ = ["DATA_DIR", "check_choice", "pack_metadata", "cell_centre", "largest_free_component", "nearest_cell"]

DATA_DIR = Path(__file__).resolve().parent / "data"
"""Folder of the bundled data files (MovingAI maps, DEMs) with their licences."""

# Under the no-corner-cutting rule a diagonal move needs both orthogonal
# neighbours free, so it can always be replaced by two orthogonal moves:
# 8-connected reachability equals 4-connected reachability.
_FOUR = np.array([[0, 1, 0], [1, 1, 1], [0, 1, 0]], dtype=bool)


def check_choice(value: Any, allowed: Iterable[Any], name: str) -> None:
    """Raise :class:`InvalidParameterError` naming ``name`` unless ``value`` is one of ``allowed``."""
    allowed = list(allowed)
    if value not in allowed:
        raise InvalidParameterError(f"{name} must be one of {', '.join(map(repr, allowed))}, got {value!r}")


def pack_metadata(pack: str, version: int, source: str, **extra: Any) -> dict[str, Any]:
    """Provenance every bundled scenario carries.

    Parameters
    ----------
    pack : str
        Pack name (the first part of the scenario ids), e.g. ``"gant"``.
    version : int
        The pack's ``PACK_VERSION``; bumped whenever a scenario would change.
    source : str
        Where the numbers come from (paper, table, equation, data file).
    **extra
        Pack-specific facts: seeds, interpretation choices, derived numbers.
    """
    return {"pack": pack, "pack_version": int(version), "source": source, **extra}


def cell_centre(row: int, col: int, cell_size: float) -> np.ndarray:
    """World coordinates ``(x, y)`` of a cell centre (see :mod:`pathzoo.core.scenario`)."""
    return np.array([(col + 0.5) * cell_size, (row + 0.5) * cell_size])


def largest_free_component(free: np.ndarray) -> np.ndarray:
    """The largest set of free cells mutually reachable by 8-connected moves that never cut a corner."""
    from scipy import ndimage

    labels, n = ndimage.label(free, structure=_FOUR)
    if n == 0:
        return np.zeros_like(free, dtype=bool)
    sizes = np.bincount(labels.ravel())
    sizes[0] = 0
    return labels == int(np.argmax(sizes))


def nearest_cell(mask: np.ndarray, row: float, col: float) -> tuple[int, int]:
    """The ``True`` cell of ``mask`` closest to ``(row, col)`` (ties: lowest row, then column)."""
    rows, cols = np.nonzero(mask)
    if len(rows) == 0:
        raise ValueError("mask has no True cell")
    k = int(np.argmin((rows - row) ** 2 + (cols - col) ** 2))
    return int(rows[k]), int(cols[k])
