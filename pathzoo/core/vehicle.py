"""The vehicle model: speed, slope limits and the G-Ant ground-vehicle power model."""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any, Mapping

import numpy as np

from pathzoo.core.errors import InvalidScenarioError

__all__ = ["VehicleModel", "GRAVITY"]

GRAVITY = 9.80665
"""Standard gravity in m/s²."""


@dataclass(frozen=True)
class VehicleModel:
    """Physical description of the vehicle a scenario is planned for.

    The power model is eq. 4 of the G-Ant paper (Jabbarpour et al., 2017),
    ``P = (W sinθ + f W cosθ + m a + C_I) v + b`` with ``W = m g`` and θ the
    slope of the segment being driven. Defaults follow G-Ant's Table 3
    (30 kg, 2 m/s, b = 0 W); the rolling and internal resistance, which the
    paper leaves open, are our choices (see ``docs/energy.md``).

    Parameters
    ----------
    mass_kg : float
        Vehicle mass ``m``.
    cruise_speed : float
        Speed ``v`` on straight segments, m/s (G-Ant's φ).
    rolling_resistance : float
        Rolling resistance coefficient ``f`` (dimensionless).
    internal_resistance_n : float
        Internal resistance ``C_I`` in newtons.
    onboard_power_w : float
        Power ``b`` drawn by onboard equipment, watts.
    max_acceleration : float
        Magnitude of acceleration and braking used at turns, m/s².
    max_climb_deg, max_descent_deg : float
        Steepest uphill and downhill slope the vehicle may drive, degrees.
        ``90`` disables the limit.
    max_turn_deg : float
        Largest heading change allowed at one waypoint, degrees (``180``
        disables the limit). For air vehicles this is the horizontal turn limit.
    max_pitch_deg : float
        Air vehicles only: steepest climb/dive angle of a segment, degrees.
    """

    mass_kg: float = 30.0
    cruise_speed: float = 2.0
    rolling_resistance: float = 0.05
    internal_resistance_n: float = 0.0
    onboard_power_w: float = 0.0
    max_acceleration: float = 1.0
    max_climb_deg: float = 90.0
    max_descent_deg: float = 90.0
    max_turn_deg: float = 180.0
    max_pitch_deg: float = 90.0

    def __post_init__(self) -> None:
        positive = ("mass_kg", "cruise_speed", "max_acceleration")
        for name, value in asdict(self).items():
            if not isinstance(value, (int, float)) or isinstance(value, bool) or not math.isfinite(value):
                raise InvalidScenarioError(f"must be a finite number, got {value!r}", field=f"vehicle.{name}")
            if name in positive and value <= 0:
                raise InvalidScenarioError(f"must be > 0, got {value!r}", field=f"vehicle.{name}")
            if value < 0:
                raise InvalidScenarioError(f"must be >= 0, got {value!r}", field=f"vehicle.{name}")
        for name in ("max_climb_deg", "max_descent_deg", "max_pitch_deg"):
            if not 0 < getattr(self, name) <= 90:
                raise InvalidScenarioError("must be in (0, 90] degrees", field=f"vehicle.{name}")
        if not 0 < self.max_turn_deg <= 180:
            raise InvalidScenarioError("must be in (0, 180] degrees", field="vehicle.max_turn_deg")

    @classmethod
    def from_mapping(cls, data: Mapping[str, Any], *, source: str | None = None) -> "VehicleModel":
        """Build a vehicle from a TOML table, rejecting unknown keys."""
        known = set(cls.__dataclass_fields__)
        unknown = sorted(set(data) - known)
        if unknown:
            raise InvalidScenarioError(
                f"unknown key(s) {unknown}; allowed: {sorted(known)}", source=source, field="vehicle"
            )
        try:
            return cls(**dict(data))
        except InvalidScenarioError as exc:
            raise InvalidScenarioError(str(exc), source=source) from None

    @property
    def weight_n(self) -> float:
        """Weight ``W = m g`` in newtons."""
        return self.mass_kg * GRAVITY

    def traction_power(self, slope_rad: np.ndarray | float, acceleration: np.ndarray | float = 0.0) -> np.ndarray:
        """Power drawn at cruise speed on a given slope, eq. 4 of G-Ant (watts).

        Negative traction power (steep descents, braking) is clipped to zero:
        the model has no regeneration, so the onboard load ``b`` is the floor.
        """
        theta = np.asarray(slope_rad, dtype=float)
        w = self.weight_n
        force = w * np.sin(theta) + self.rolling_resistance * w * np.cos(theta)
        force = force + self.mass_kg * np.asarray(acceleration, dtype=float) + self.internal_resistance_n
        return np.maximum(force * self.cruise_speed, 0.0) + self.onboard_power_w

    def segment_energy(self, length_3d: np.ndarray, slope_rad: np.ndarray) -> np.ndarray:
        """Energy in joules to drive segments of given 3-D length and slope at cruise speed."""
        return self.traction_power(slope_rad) * (np.asarray(length_3d, dtype=float) / self.cruise_speed)

    def turn_speed(self, turn_rad: np.ndarray) -> np.ndarray:
        """Speed through a waypoint with heading change ``turn_rad`` (0..π).

        The vehicle slows linearly with the turn angle, to a stop for a
        U-turn: ``v_turn = v (1 - |Δψ| / π)``.
        """
        turn = np.clip(np.abs(np.asarray(turn_rad, dtype=float)), 0.0, math.pi)
        return self.cruise_speed * (1.0 - turn / math.pi)

    def turn_penalty(self, turn_rad: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Extra time (s) and energy (J) of braking for and accelerating out of turns.

        Braking from ``v`` to ``v_t`` and accelerating back at ``a`` takes
        ``(v - v_t)² / (a v)`` seconds longer than cruising the same distance.
        Re-accelerating costs the kinetic energy ``½ m (v² - v_t²)`` (braking
        dissipates it; no regeneration) plus the onboard load over the extra time.
        """
        v = self.cruise_speed
        vt = self.turn_speed(turn_rad)
        extra_time = (v - vt) ** 2 / (self.max_acceleration * v)
        extra_energy = 0.5 * self.mass_kg * (v**2 - vt**2) + self.onboard_power_w * extra_time
        return extra_time, extra_energy
