"""Mountain terrain as a sum of Gaussian peaks (eq. 1 of DSACO, Mai et al. 2023)."""

from __future__ import annotations

from typing import Sequence

import numpy as np

from pathzoo.core.errors import InvalidScenarioError
from pathzoo.generators.checks import check_number, check_seed, check_shape

__all__ = ["GENERATOR_VERSION", "gaussian_peaks", "peaks_elevation"]

GENERATOR_VERSION = 1
"""Bumped whenever the same arguments would give a different array."""

DEFAULT_N_PEAKS = 6
DEFAULT_MAX_HEIGHT = 100.0


def peaks_elevation(peaks: np.ndarray, shape: tuple[int, int], cell_size: float) -> np.ndarray:
    """Evaluate eq. 1 of DSACO at the cell centres.

    ``Z(x, y) = sum_i h_i exp(-((x - x0_i) / xs_i)^2 - ((y - y0_i) / ys_i)^2)``,
    with ``x = (col + 0.5) cell_size`` and ``y = (row + 0.5) cell_size``.

    Parameters
    ----------
    peaks : ndarray of shape (n, 5)
        Rows ``(x0, y0, h, xs, ys)`` in metres: centre, height and the two
        spreads (the paper's "slope" pair).
    shape : tuple of int
        ``(rows, cols)``.
    cell_size : float
        Metres per cell.
    """
    x = (np.arange(shape[1]) + 0.5) * cell_size
    y = (np.arange(shape[0]) + 0.5) * cell_size
    x0, y0, h, xs, ys = (peaks[:, k][:, None] for k in range(5))
    # each hill is separable: exp(-a(x) - b(y)) = exp(-a(x)) exp(-b(y)), so the sum is one matrix product
    along_x = np.exp(-(((x[None, :] - x0) / xs) ** 2))
    along_y = np.exp(-(((y[None, :] - y0) / ys) ** 2))
    return (h * along_y).T @ along_x


def _check_peaks(peaks: Sequence[Sequence[float]]) -> np.ndarray:
    rows = np.asarray(peaks, dtype=object)
    if rows.ndim != 2 or rows.shape[1] != 5:
        raise InvalidScenarioError("must be a list of [x0, y0, height, x_spread, y_spread] rows", field="peaks")
    for i, row in enumerate(rows):
        for name, value in zip(("x0", "y0", "height", "x_spread", "y_spread"), row):
            spread = name.endswith("spread")
            check_number(value, f"peaks[{i}].{name}", low=0.0 if spread else None, low_open=spread)
    return rows.astype(np.float64)


def gaussian_peaks(
    shape: tuple[int, int],
    seed: int,
    *,
    cell_size: float = 1.0,
    peaks: Sequence[Sequence[float]] | None = None,
    n_peaks: int | None = None,
    max_height: float | None = None,
) -> np.ndarray:
    """Elevation made of Gaussian hills, eq. 1 of DSACO.

    Either give the hills explicitly with ``peaks`` (DSACO's Tables 1-3, with
    kilometres converted to metres), or let ``seed`` draw ``n_peaks`` of them:
    centres uniform over the map, heights uniform in
    ``[0.3, 1] x max_height``, and spreads uniform in ``[0.05, 0.2]`` times the
    map's extent along each axis (our choice; the paper gives no
    distribution).

    Parameters
    ----------
    shape : tuple of int
        ``(rows, cols)``.
    seed : int
        Seed of :func:`numpy.random.default_rng` (unused with ``peaks``).
    cell_size : float
        Metres per cell; a scenario file passes its own ``cell_size``.
    peaks : list of [x0, y0, height, x_spread, y_spread], optional
        Explicit hills in metres; spreads > 0.
    n_peaks : int, optional
        Number of random hills (default 6); not with ``peaks``.
    max_height : float, optional
        Tallest possible random hill in metres (default 100); not with ``peaks``.

    Returns
    -------
    ndarray of float64
        Elevation in metres at cell centres; 0 far from every hill.
    """
    rows, cols = check_shape(shape)
    shape = (rows, cols)
    cell_size = check_number(cell_size, "cell_size", low=0.0, low_open=True)
    rng = np.random.default_rng(check_seed(seed))
    if peaks is not None:
        for name, value in (("n_peaks", n_peaks), ("max_height", max_height)):
            if value is not None:
                raise InvalidScenarioError("give either explicit 'peaks' or random ones, not both", field=name)
        return peaks_elevation(_check_peaks(peaks), shape, cell_size)
    n = int(check_number(DEFAULT_N_PEAKS if n_peaks is None else n_peaks, "n_peaks", low=0, integer=True))
    top = check_number(DEFAULT_MAX_HEIGHT if max_height is None else max_height, "max_height", low=0.0, low_open=True)
    extent = np.array([shape[1], shape[0]], dtype=np.float64) * cell_size
    centres = rng.random((n, 2)) * extent
    heights = rng.uniform(0.3, 1.0, n) * top
    spreads = rng.uniform(0.05, 0.2, (n, 2)) * extent
    drawn = np.column_stack([centres, heights, spreads])
    return peaks_elevation(drawn, shape, cell_size)
