"""``length_ratio_anyangle``: length over the exact any-angle optimum; never below 1 for a valid path."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pathzoo import Budget, RunStatus, Scenario, make_planner
from pathzoo.rules import validate_path
from pathzoo.metrics import BUILTIN_METRICS
from .test_builtin_metrics import open_grid, record

METRIC = next(cls for cls in BUILTIN_METRICS if cls.id == "length_ratio_anyangle")()


def test_straight_visible_segment_scores_one():
    sc = open_grid(start=(0.5, 0.5), goal=(3.5, 4.5))
    assert METRIC.compute(sc, record([(0.5, 0.5), (3.5, 4.5)])) == pytest.approx(1.0, abs=1e-12)


def test_detour_round_a_block_scores_above_one_and_by_hand():
    occ = np.zeros((5, 5), dtype=bool)
    occ[2, 2] = True
    sc = Scenario(id="block", kind="grid2d", occupancy=occ, cell_size=2.0, start=(1.0, 1.0), goal=(9.0, 9.0))
    path = np.array([(1.0, 1.0), (1.0, 9.0), (9.0, 9.0)])  # round the outside: 16 m
    assert validate_path(sc, path)
    optimum = 2.0 * 2 * math.hypot(2.5, 1.5)  # two legs touching a corner of the block, in metres
    assert METRIC.compute(sc, record(path)) == pytest.approx(16.0 / optimum)


def test_never_below_one_for_planners_paths():
    occ = np.zeros((16, 16), dtype=bool)
    occ[2:14, 5] = occ[2:14, 10] = True
    occ[7, 1:4] = True
    sc = Scenario(id="walls", kind="grid2d", occupancy=occ, cell_size=1.0, start=(0.5, 0.5), goal=(15.5, 15.5))
    for pid in ("exact.thetastar", "exact.astar", "exact.anyangle"):
        result = make_planner(pid).plan(sc, budget=Budget(), rng=np.random.default_rng(0))
        ratio = METRIC.compute(sc, record(result.path))
        assert 1.0 <= ratio, pid
    assert ratio <= 1.0 + 1e-5  # exact.anyangle itself


def test_computed_on_a_512_map_and_nan_when_not_computed():
    big = open_grid(512, 512, start=(0.5, 0.5), goal=(3.5, 4.5))
    assert METRIC.compute(big, record([(0.5, 0.5), (3.5, 4.5)])) == pytest.approx(1.0, abs=1e-12)
    # endpoints that are no fraction 1/2**k of a cell are searched only on maps of up to 256 x 256 cells
    off_lattice = open_grid(257, 256, start=(0.1, 0.5), goal=(3.5, 4.5))
    assert math.isnan(METRIC.compute(off_lattice, record([(0.1, 0.5), (3.5, 4.5)])))
    sc = open_grid(start=(0.5, 0.5), goal=(3.5, 4.5))
    assert math.isnan(METRIC.compute(sc, record(None, status=RunStatus.FAILED)))
