"""Traversability rules on terrain: slope weights and soil strength."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Mapping

import numpy as np

from pathzoo.core.errors import InvalidScenarioError

__all__ = ["TerrainRules"]


@dataclass(frozen=True, eq=False)
class TerrainRules:
    """Optional rules that refine where and how a ground vehicle may drive.

    Slope *limits* belong to the :class:`~pathzoo.core.vehicle.VehicleModel`;
    these rules add what some planners and scenarios need on top.

    Parameters
    ----------
    slope_weights : ndarray of shape (K, 2), optional
        Rows ``(upper_slope_deg, weight)`` sorted by slope: a signed slope
        ``θ`` (degrees, uphill positive) gets the weight of the first row with
        ``θ <= upper_slope_deg``. Used by IACA's slopeW (its Table 1).
    soil_strength : ndarray of shape (H, W), optional
        Rating cone index (RCI) per cell.
    min_soil_strength : float, optional
        Vehicle cone index (VCI): cells with ``soil_strength`` below it are
        impassable.
    soil_types : ndarray of shape (H, W), optional
        Integer soil class per cell, with ``soil_names`` giving the labels.
    soil_names : tuple of str
        Names of the soil classes.
    """

    slope_weights: np.ndarray | None = None
    soil_strength: np.ndarray | None = None
    min_soil_strength: float | None = None
    soil_types: np.ndarray | None = None
    soil_names: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if self.slope_weights is not None:
            sw = np.array(self.slope_weights, dtype=np.float64)
            if sw.ndim != 2 or sw.shape[1] != 2 or not np.isfinite(sw).all() or np.any(np.diff(sw[:, 0]) <= 0):
                raise InvalidScenarioError(
                    "must be rows (upper_slope_deg, weight) with increasing slopes", field="rules.slope_weights"
                )
            sw.setflags(write=False)
            object.__setattr__(self, "slope_weights", sw)
        for name in ("soil_strength", "soil_types"):
            arr = getattr(self, name)
            if arr is not None:
                arr = np.array(arr)
                if arr.ndim != 2:
                    raise InvalidScenarioError("must be a 2-D array", field=f"rules.{name}")
                arr.setflags(write=False)
                object.__setattr__(self, name, arr)

    @classmethod
    def from_mapping(cls, data: Mapping[str, Any], *, source: str | None = None) -> "TerrainRules":
        """Build rules from a TOML table, rejecting unknown keys."""
        known = set(cls.__dataclass_fields__)
        unknown = sorted(set(data) - known)
        if unknown:
            raise InvalidScenarioError(f"unknown key(s) {unknown}; allowed: {sorted(known)}", source=source, field="rules")
        kwargs = dict(data)
        if "soil_names" in kwargs:
            kwargs["soil_names"] = tuple(kwargs["soil_names"])
        try:
            return cls(**kwargs)
        except InvalidScenarioError as exc:
            raise InvalidScenarioError(str(exc), source=source) from None

    def slope_weight(self, slope_deg: np.ndarray | float) -> np.ndarray:
        """Weight for signed slopes in degrees (1 where no table is set)."""
        s = np.asarray(slope_deg, dtype=np.float64)
        if self.slope_weights is None:
            return np.ones_like(s)
        idx = np.searchsorted(self.slope_weights[:, 0], s, side="left")
        idx = np.clip(idx, 0, len(self.slope_weights) - 1)
        return self.slope_weights[idx, 1]

    def soil_blocked(self, shape: tuple[int, int]) -> np.ndarray:
        """Cells too weak for the vehicle (all False when no soil data)."""
        if self.soil_strength is None or self.min_soil_strength is None:
            return np.zeros(shape, dtype=bool)
        if self.soil_strength.shape != shape:
            raise InvalidScenarioError(
                f"shape {self.soil_strength.shape} differs from the map {shape}", field="rules.soil_strength"
            )
        return self.soil_strength < self.min_soil_strength
