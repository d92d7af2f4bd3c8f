"""The problem an external planner reads: a scenario, budget, seed and parameters as one JSON object.

Arrays are written as nested lists of rows (row-major), with ``null`` for
a missing elevation. An array of more than :data:`INLINE_CELLS` cells is
written to an ``.npy`` file in the run's scratch folder instead, and the
field holds that file's absolute path.
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict
from pathlib import Path
from typing import TYPE_CHECKING, Any, Mapping

import numpy as np

from pathzoo.core.budget import Budget
from pathzoo_external.program import PROTOCOL_VERSION

if TYPE_CHECKING:
    from pathzoo.core.scenario import Scenario

__all__ = ["problem_dict", "problem_json", "INLINE_CELLS", "SEED_LIMIT"]

INLINE_CELLS = 65_536
"""Largest array (cells) written into the JSON text; larger ones go to ``.npy`` files."""

SEED_LIMIT = 2**31
"""Seeds sent to external planners lie in ``[0, SEED_LIMIT)``: exact in doubles, valid for MATLAB's ``rng`` and C's ``int``."""


def _nulls(values: Any) -> Any:
    """Nested lists with NaN (and infinities) replaced by ``None``, which JSON writes as ``null``."""
    if isinstance(values, list):
        return [_nulls(v) for v in values]
    return None if isinstance(values, float) and not math.isfinite(values) else values


def _array(name: str, values: np.ndarray, scratch: Path) -> Any:
    """``values`` as nested row lists, or the path of an ``.npy`` file holding them when large."""
    if values.size > INLINE_CELLS:
        path = scratch / f"{name}.npy"
        np.save(path, np.ascontiguousarray(values))
        return str(path)
    rows = values.tolist()
    return _nulls(rows) if values.dtype.kind == "f" else rows


def problem_dict(scenario: "Scenario", *, budget: Budget, seed: int, params: Mapping[str, Any],
                 scratch: Path) -> dict[str, Any]:
    """The problem of one run (format in ``docs/external-planners.md``).

    ``occupancy`` marks every cell the vehicle may not enter (obstacles,
    cells without elevation, soil weaker than the vehicle needs) with 1.
    """
    problem: dict[str, Any] = {
        "protocol": PROTOCOL_VERSION,
        "scenario": scenario.id,
        "kind": scenario.kind,
        "shape": list(scenario.shape),
        "cell_size": float(scenario.cell_size),
        "occupancy": _array("occupancy", scenario.blocked.astype(np.uint8), scratch),
        "start": scenario.start.tolist(),
        "goal": scenario.goal.tolist(),
        "vehicle": asdict(scenario.vehicle),
        "budget": budget.to_dict(),
        "seed": int(seed),
        "params": dict(params),
        "scratch": str(scratch),
    }
    if scenario.kind == "air3d":
        problem["vertical_cell_size"] = float(scenario.vertical_cell_size or 0.0)
        problem["max_step"] = list(scenario.max_step)
    if scenario.elevation is not None:
        problem["elevation"] = _array("elevation", scenario.elevation, scratch)
    if scenario.kind == "terrain":
        rules = scenario.rules
        problem["rules"] = {
            "slope_weights": None if rules.slope_weights is None else rules.slope_weights.tolist(),
            "soil_strength": None if rules.soil_strength is None else _array(
                "soil_strength", np.asarray(rules.soil_strength, dtype=np.float64), scratch),
            "min_soil_strength": rules.min_soil_strength,
        }
    if scenario.kind == "dynamic":
        problem["obstacles"] = [
            {"radius": ob.radius, "waypoints": np.asarray(ob.waypoints).tolist(), "speed": ob.speed,
             "mode": ob.mode, "phase_s": ob.phase_s}
            for ob in scenario.moving_obstacles
        ]
    return problem


def problem_json(scenario: "Scenario", *, budget: Budget, seed: int, params: Mapping[str, Any],
                 scratch: Path) -> str:
    """:func:`problem_dict` as one line of JSON text (no newline inside)."""
    return json.dumps(problem_dict(scenario, budget=budget, seed=seed, params=params, scratch=scratch),
                      allow_nan=False, separators=(",", ":"))
