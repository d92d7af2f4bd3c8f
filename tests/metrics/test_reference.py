"""The reference optimum reproduces MovingAI's published optimal lengths and handles odd endpoints."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pathzoo import Scenario, load_scenarios
from pathzoo.grid.reference import reference_length, reference_path
from pathzoo.rules import validate_path


def test_dijkstra_matches_movingai_optimal_lengths(shared_data):
    problems = load_scenarios(shared_data / "movingai" / "grid" / "dao" / "arena.map.scen")
    assert len(problems) > 100
    for sc in problems:
        ref = reference_path(sc)
        assert ref is not None
        # .scen files print 4 decimals
        assert ref.length == pytest.approx(sc.reference_length, abs=1e-3), sc.id
        assert validate_path(sc, ref.path), sc.id
        assert reference_length(sc) == sc.reference_length


def test_large_room_map(shared_data):
    problems = load_scenarios(shared_data / "movingai" / "grid" / "rooms" / "8room_000.map.scen")
    for sc in problems[-3:]:  # the longest problems
        assert reference_path(sc).length == pytest.approx(sc.reference_length, abs=1e-3)


def test_unreachable_and_off_centre_endpoints():
    occ = np.zeros((3, 5), bool)
    occ[:, 2] = True
    sealed = Scenario(id="sealed", kind="grid2d", occupancy=occ, cell_size=1.0, start=(0.5, 0.5), goal=(4.5, 0.5))
    assert reference_path(sealed) is None and math.isnan(reference_length(sealed))

    off = Scenario(id="off", kind="grid2d", occupancy=np.zeros((3, 5), bool), cell_size=2.0, start=(0.3, 0.4),
                   goal=(9.0, 1.0))
    ref = reference_path(off)
    assert np.array_equal(ref.path[0], off.start) and np.array_equal(ref.path[-1], off.goal)
    # connectors to the start and goal cell centres (1, 1) and (9, 1), then 4 straight moves of 2 m
    assert ref.length == pytest.approx(math.hypot(0.7, 0.6) + 8.0 + 0.0)
    assert reference_path(off) is ref  # cached per scenario
