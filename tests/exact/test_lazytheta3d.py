"""Lazy Theta* in air volumes: judge-accepted, between the straight line and the graph optimum, and its metric."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pathzoo import Scenario
from pathzoo.grid.lazy_theta3d import lazy_theta_path
from pathzoo.grid.reference import anyangle_bound_3d, reference_length
from pathzoo.rules import validate_path
from pathzoo.testing import check_scenario


def _length(path: np.ndarray) -> float:
    return float(np.linalg.norm(np.diff(path, axis=0), axis=1).sum())


def _volume(occ: np.ndarray, start, goal, pitch: float = 90.0) -> Scenario:
    from pathzoo import VehicleModel

    return Scenario(id="v", kind="air3d", occupancy=occ, cell_size=1.0, vertical_cell_size=1.0,
                    start=np.array(start, float), goal=np.array(goal, float), vehicle=VehicleModel(max_pitch_deg=pitch),
                    max_step=(2, 1))


def test_open_volume_gives_the_straight_segment():
    sc = _volume(np.zeros((3, 6, 6), bool), (0.5, 0.5, 0.5), (5.5, 3.5, 2.5))
    path = lazy_theta_path(sc)
    assert len(path) == 2
    assert _length(path) == pytest.approx(math.dist(sc.start, sc.goal))


def test_climbing_over_a_wall_is_accepted_and_bounded_both_ways():
    sc = check_scenario("air3d")
    path = lazy_theta_path(sc)
    assert validate_path(sc, path)
    assert math.dist(sc.start, sc.goal) < _length(path) <= reference_length(sc) + 1e-9
    assert anyangle_bound_3d(sc) == pytest.approx(_length(path))


def test_line_of_sight_respects_the_pitch_limit():
    occ = np.zeros((4, 8, 8), dtype=bool)
    occ[0:3, :, 4] = True
    sc = _volume(occ, (0.5, 4.5, 0.5), (7.5, 4.5, 0.5), pitch=30.0)
    path = lazy_theta_path(sc)
    assert validate_path(sc, path)  # every segment within 30 degrees
    steep = _volume(occ, (0.5, 4.5, 0.5), (7.5, 4.5, 0.5), pitch=90.0)
    assert _length(lazy_theta_path(steep)) < _length(path)  # the limit made it longer: it was enforced
