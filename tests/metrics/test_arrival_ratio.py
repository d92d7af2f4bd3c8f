"""``arrival_ratio``: arrival time over SIPP's earliest arrival on dynamic scenarios."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pathzoo import Budget, MovingObstacle, Scenario, VehicleModel, make_planner
from pathzoo.metrics import ArrivalRatio
from pathzoo.rules import validate_path
from .test_builtin_metrics import open_grid, record

METRIC = ArrivalRatio()


def _gate() -> Scenario:
    occ = np.zeros((7, 7), dtype=bool)
    occ[3, :] = True
    occ[3, 3] = False
    mover = MovingObstacle(radius=0.8, waypoints=np.array([[0.5, 3.5], [6.5, 3.5]]), speed=1.0, phase_s=1.0)
    return Scenario(id="gate", kind="dynamic", occupancy=occ, cell_size=1.0, start=(3.5, 0.5), goal=(3.5, 6.5),
                    vehicle=VehicleModel(cruise_speed=1.0), moving_obstacles=(mover,))


def test_sipp_scores_one_and_a_later_valid_path_scores_more():
    sc = _gate()
    best = make_planner("exact.sipp").plan(sc, budget=Budget(), rng=np.random.default_rng(0))
    assert METRIC.compute(sc, record(best.path, times=best.times)) == pytest.approx(1.0, abs=1e-12)
    later_path = np.vstack([best.path[:1], best.path])
    later_times = np.concatenate([[0.0], best.times + 20.0])  # wait 20 s longer at the start: a full period
    assert validate_path(sc, later_path, later_times)
    ratio = METRIC.compute(sc, record(later_path, times=later_times))
    assert ratio == pytest.approx((best.times[-1] + 20.0) / best.times[-1])


def test_untimed_path_is_timed_at_cruise_speed():
    sc = Scenario(id="empty", kind="dynamic", occupancy=np.zeros((4, 4), bool), cell_size=1.0, start=(0.5, 0.5),
                  goal=(3.5, 0.5), vehicle=VehicleModel(cruise_speed=2.0))
    assert METRIC.compute(sc, record([(0.5, 0.5), (3.5, 0.5)])) == pytest.approx(1.0)


def test_nan_on_static_kinds():
    sc = open_grid(start=(0.5, 0.5), goal=(3.5, 4.5))
    assert math.isnan(METRIC.compute(sc, record([(0.5, 0.5), (3.5, 4.5)])))
