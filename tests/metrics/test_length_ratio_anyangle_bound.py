"""The Lazy Theta* bound's length ratio on air volumes (``length_ratio_anyangle_bound``)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pathzoo import Budget, Status, make_planner
from pathzoo.metrics import LengthRatioAnyAngleBound
from pathzoo.testing import check_scenario

from .test_builtin_metrics import record


def test_metric_is_one_for_the_bound_and_may_not_exceed_the_grid_path():
    sc = check_scenario("air3d")
    metric = LengthRatioAnyAngleBound()
    planner = make_planner("exact.lazytheta3d").plan(sc, budget=Budget(), rng=np.random.default_rng(0))
    assert planner.status is Status.SOLVED
    assert metric.compute(sc, record(planner.path)) == pytest.approx(1.0)
    grid = make_planner("exact.astar").plan(sc, budget=Budget(), rng=np.random.default_rng(0))
    assert metric.compute(sc, record(grid.path)) >= 1.0
    assert math.isnan(metric.compute(check_scenario("grid2d"), record(planner.path[:, :2])))
