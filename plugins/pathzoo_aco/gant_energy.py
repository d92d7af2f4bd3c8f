"""G-Ant's energy prediction: the linear power model of eq. 7 fitted online by RLS with an EWMA residual chart.

G-Ant (Jabbarpour et al., 2017) rewrites the power model of eq. 4,
``P = (W sinθ + f W cosθ + m a + C_I) v + b + ε``, linearised for small
grades (eq. 5), as the regression ``y = b + C x + ε`` (eqs. 6-7) with
response ``y = P - m a v``, predictor ``x = v W`` and ``C = θ + f + C_I / W``.
``b`` and ``C`` are estimated sample by sample (interval ``Δt``) by
recursive least squares with forgetting factor ``λ_ff``; an EWMA of the
one-step residuals with weight ``λ_u`` (eq. 9) watches for sudden changes
and resets the RLS covariance when it leaves its control band. The fitted
model then predicts mission energy (eq. 11) and its variance (eq. 12).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from pathzoo.core.vehicle import VehicleModel

__all__ = ["RlsEwmaPredictor", "SyntheticDrive", "synthetic_drive"]


@dataclass
class RlsEwmaPredictor:
    """Online estimate of ``(b, C)`` in ``y = b + C x`` (G-Ant eqs. 7, 9).

    Parameters
    ----------
    lambda_ff : float
        RLS forgetting factor ``λ_ff`` (Table 3: 0.98).
    lambda_u : float
        EWMA weight ``λ_u`` of the residual chart (Table 3: 0.98).
    initial_cov : float
        The RLS covariance starts (and is reset to) ``initial_cov * I``.
    limit : float
        Control limit of the EWMA chart in standard deviations of the EWMA
        statistic (3, the usual Shewhart/EWMA choice).
    warmup : int
        Samples before the chart is armed (the residual scale is unknown before).
    """

    lambda_ff: float = 0.98
    lambda_u: float = 0.98
    initial_cov: float = 1e6
    limit: float = 3.0
    warmup: int = 10
    theta: np.ndarray = field(default_factory=lambda: np.zeros(2))
    cov: np.ndarray = field(init=False)
    z: float = 0.0
    resid_var: float = 0.0
    samples: int = 0
    resets: int = 0

    def __post_init__(self) -> None:
        self.cov = self.initial_cov * np.eye(2)

    @property
    def b(self) -> float:
        """Estimated onboard power ``b̂`` (W)."""
        return float(self.theta[0])

    @property
    def c(self) -> float:
        """Estimated composite coefficient ``Ĉ`` (grade + rolling + internal losses)."""
        return float(self.theta[1])

    def predict_power(self, x: float | np.ndarray) -> np.ndarray:
        """``ŷ = b̂ + Ĉ x``: the response expected for predictor ``x = v W``."""
        return self.theta[0] + self.theta[1] * np.asarray(x, dtype=np.float64)

    def power_variance(self, x: float | np.ndarray) -> np.ndarray:
        """Variance of a future response at ``x``: ``σ̂² (1 + φᵀ P φ)`` with ``φ = (1, x)``."""
        x = np.asarray(x, dtype=np.float64)
        quad = self.cov[0, 0] + 2.0 * self.cov[0, 1] * x + self.cov[1, 1] * x * x
        return self.resid_var * (1.0 + quad)

    def update(self, x: float, y: float) -> float:
        """Take one sample; return the one-step residual ``ê(k) = y(k) - ŷ(k)`` (eq. 9).

        The EWMA statistic ``z(k) = λ_u ê(k) + (1 - λ_u) z(k-1)`` is compared
        with ``limit · σ̂ · sqrt((1 + φᵀPφ) λ_u / (2 - λ_u))``, the band of an
        EWMA of residuals whose one-step variance is ``σ̂² (1 + φᵀPφ)``; outside
        it, the covariance is reset so the estimate re-adapts quickly (G-Ant,
        section IV-2). ``σ̂²`` is a forgetting average of the standardised
        residuals ``ê² / (1 + φᵀPφ)`` of in-control samples.
        """
        phi = np.array([1.0, x])
        spread = 1.0 + float(phi @ self.cov @ phi)
        resid = float(y - phi @ self.theta)
        self.z = self.lambda_u * resid + (1.0 - self.lambda_u) * self.z
        band = self.limit * math.sqrt(self.resid_var * spread * self.lambda_u / (2.0 - self.lambda_u))
        if self.samples >= self.warmup and abs(self.z) > band:
            self.cov = self.initial_cov * np.eye(2)
            self.z = 0.0
            self.resets += 1
        elif self.samples >= 2:  # two samples determine (b, C) exactly: no residual information before
            scaled = resid * resid / spread
            first = self.samples == 2
            self.resid_var = scaled if first else self.lambda_ff * self.resid_var + (1.0 - self.lambda_ff) * scaled
        gain = self.cov @ phi / (self.lambda_ff + phi @ self.cov @ phi)
        self.theta = self.theta + gain * resid
        self.cov = (self.cov - np.outer(gain, phi @ self.cov)) / self.lambda_ff
        self.samples += 1
        return resid

    def mission_energy(self, consumed_j: float, steps_left: float, x_next: float, dt: float) -> tuple[float, float]:
        """Eqs. 11-12: predicted total energy (J) and its variance after ``consumed_j`` J so far.

        ``steps_left`` is ``n̂ - k`` sampling intervals of ``dt`` seconds at the
        predicted predictor value ``x_next = W v̂``.
        """
        mean = consumed_j + steps_left * float(self.predict_power(x_next)) * dt
        var = steps_left * float(self.power_variance(x_next)) * dt * dt
        return mean, var


@dataclass(frozen=True)
class SyntheticDrive:
    """Samples of a simulated drive: speed ``v``, acceleration ``a``, measured power ``P``, ``x`` and ``y`` (eq. 7)."""

    v: np.ndarray
    a: np.ndarray
    power: np.ndarray
    x: np.ndarray
    y: np.ndarray


def synthetic_drive(vehicle: VehicleModel, rng: np.random.Generator, n: int, dt: float, v_max: float,
                    noise: float, grade_rad: float | np.ndarray = 0.0) -> SyntheticDrive:
    """Power data generated from eq. 4, as G-Ant generates its data (section V).

    The paper drives a scaled EPA US06 cycle; we have no copy, so the stand-in
    is equally aggressive: an independent uniform speed in ``[0, v_max]`` every
    ``dt`` seconds, with the mean acceleration between samples. The error term
    ``ε`` is Gaussian with a standard deviation of ``noise`` times the mean
    power (the paper: about 10 %).

    Parameters
    ----------
    vehicle : VehicleModel
        Mass, rolling and internal resistance, onboard power.
    rng : numpy.random.Generator
        Source of speeds and noise.
    n : int
        Number of samples.
    dt : float
        Sampling interval ``Δt`` in seconds.
    v_max : float
        Top speed ``φ`` in m/s.
    noise : float
        Noise standard deviation as a fraction of the mean power.
    grade_rad : float or ndarray
        Road grade ``θ`` per sample.
    """
    v = rng.uniform(0.0, v_max, n)
    a = np.diff(v, prepend=v[0]) / dt
    w = vehicle.weight_n
    theta = np.broadcast_to(np.asarray(grade_rad, dtype=np.float64), v.shape)
    force = w * np.sin(theta) + vehicle.rolling_resistance * w * np.cos(theta) + vehicle.mass_kg * a
    clean = (force + vehicle.internal_resistance_n) * v + vehicle.onboard_power_w
    power = clean + rng.normal(0.0, noise * abs(float(clean.mean())), n)
    return SyntheticDrive(v=v, a=a, power=power, x=v * w, y=power - vehicle.mass_kg * a * v)
