"""Fractal terrain by spectral synthesis: filtered white noise with a power-law spectrum."""

from __future__ import annotations

import numpy as np

from pathzoo.generators.checks import check_number, check_seed, check_shape

__all__ = ["GENERATOR_VERSION", "fractal_terrain"]

GENERATOR_VERSION = 1
"""Bumped whenever the same arguments would give a different array."""


def fractal_terrain(
    shape: tuple[int, int], seed: int, *, hurst: float = 0.8, relief: float = 100.0, base: float = 0.0
) -> np.ndarray:
    """Fractional-Brownian-like elevation by spectral synthesis.

    Complex Gaussian white noise is shaped in the Fourier domain by the
    amplitude ``|f|^-(H + 1)`` (power spectrum ``|f|^-(2H + 2)``, the spectrum
    of a fractional Brownian surface with Hurst exponent ``H``), transformed
    back, and rescaled to span ``[base, base + relief]``. Larger ``hurst``
    gives smoother terrain. The surface is periodic: its opposite edges match.

    Parameters
    ----------
    shape : tuple of int
        ``(rows, cols)``, each >= 2.
    seed : int
        Seed of :func:`numpy.random.default_rng`.
    hurst : float
        Hurst exponent in ``(0, 1)``.
    relief : float
        Height difference between the lowest and the highest cell, metres (> 0).
    base : float
        Height of the lowest cell, metres.

    Returns
    -------
    ndarray of float64
        Elevation in metres at cell centres.
    """
    n_rows, n_cols = check_shape(shape, minimum=2)
    hurst = check_number(hurst, "hurst", low=0.0, high=1.0, low_open=True, high_open=True)
    relief = check_number(relief, "relief", low=0.0, low_open=True)
    base = check_number(base, "base")
    rng = np.random.default_rng(check_seed(seed))
    fy = np.fft.fftfreq(n_rows)[:, None]
    fx = np.fft.rfftfreq(n_cols)[None, :]
    freq = np.hypot(fx, fy)
    freq[0, 0] = np.inf  # no mean component
    spectrum_shape = (n_rows, n_cols // 2 + 1)
    noise = rng.standard_normal(spectrum_shape) + 1j * rng.standard_normal(spectrum_shape)
    surface = np.fft.irfft2(noise * freq ** -(hurst + 1.0), s=(n_rows, n_cols))
    surface -= surface.min()
    return base + relief * surface / surface.max()
