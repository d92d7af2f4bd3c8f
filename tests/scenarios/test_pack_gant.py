"""G-Ant pack: Table 3 vehicle, Fig. 7 and ACO/PSO spaces, the 500 x 500 spaces with Table 5's pairs."""

from __future__ import annotations

import math

import numpy as np
import pytest

import pathzoo
from pathzoo.rules import validate_path
from pathzoo_scenarios import gant

LARGE_IDS = [f"gant.{space}.{pair}" for space in ("simple", "moderate", "complex") for pair in (1, 2, 3)]

# Table 5 of the paper, read directly: start, goal (column, row) per column of the table
PAPER_PAIRS = [((5, 50), (400, 450)), ((20, 55), (460, 455)), ((30, 65), (465, 460))]
PAPER_GANT = {"simple": (562.58, 626.67, 619.55), "moderate": (910.4, 700.44, 667.72),
              "complex": (913.82, 710.06, 674.95)}


def test_table3_vehicle():
    s = pathzoo.load_scenario("gant.fig7")
    assert (s.vehicle.mass_kg, s.vehicle.cruise_speed, s.vehicle.onboard_power_w) == (30.0, 2.0, 0.0)


def test_fig7_space(shortest):
    s = pathzoo.load_scenario("gant.fig7")
    assert s.shape == (10, 10) and s.cell_size == 1.0
    assert int(s.occupancy.sum()) == 16
    np.testing.assert_array_equal(s.start, [0.5, 0.5])
    np.testing.assert_array_equal(s.goal, [9.5, 9.5])
    cost, _ = shortest(s)
    # the obstacles block the straight diagonal, and Table 4's best length (15.4225) stays reachable
    assert 9 * math.sqrt(2) + 1e-9 < cost <= 15.4225


def test_fig7_seed_is_the_first_that_fits(shortest):
    spec = gant.SMALL_SPACES["fig7"]
    for seed in range(int(spec["seed"])):
        occ = gant.small_layout(10, 16, ((0, 0), (9, 9)), seed)
        s = pathzoo.Scenario(id="t", kind="grid2d", occupancy=occ, cell_size=1.0, start=[0.5, 0.5], goal=[9.5, 9.5])
        cost, _ = shortest(s)
        assert not (9 * math.sqrt(2) + 1e-9 < cost <= 15.4225)


def test_acopso_space(shortest):
    s = pathzoo.load_scenario("gant.acopso")
    np.testing.assert_array_equal(s.start, [0.5, 0.5])
    np.testing.assert_array_equal(s.goal, [8.5, 8.5])
    assert int(s.occupancy.sum()) == 16
    cost, _ = shortest(s)
    assert 8 * math.sqrt(2) + 1e-9 < cost < math.inf


@pytest.mark.parametrize("sid", LARGE_IDS)
def test_large_spaces_pairs_and_reachability(sid, shortest_points):
    _, space, pair = sid.split(".")
    s = pathzoo.load_scenario(sid)
    assert s.shape == (500, 500)
    (sc, sr), (gc, gr) = PAPER_PAIRS[int(pair) - 1]
    np.testing.assert_array_equal(s.start, [sc + 0.5, sr + 0.5])
    np.testing.assert_array_equal(s.goal, [gc + 0.5, gr + 0.5])
    path = shortest_points(s)
    assert validate_path(s, path)
    assert s.metadata["pack_version"] == gant.PACK_VERSION


@pytest.mark.parametrize("space", ["simple", "moderate", "complex"])
def test_large_spaces_character(space, shortest):
    """Detours (optimum / straight line) track the ratios of G-Ant's Table 5 lengths."""
    ratios, paper = [], []
    for pair, ((sc, sr), (gc, gr)) in enumerate(PAPER_PAIRS, start=1):
        s = pathzoo.load_scenario(f"gant.{space}.{pair}")
        cost, _ = shortest(s)
        straight = math.hypot(gc - sc, gr - sr)
        ratios.append(cost / straight)
        paper.append(PAPER_GANT[space][pair - 1] / straight)
    assert np.linalg.norm(np.subtract(ratios, paper)) < 0.3
    occ = pathzoo.load_scenario(f"gant.{space}.1").occupancy.mean()
    assert occ > 0.05


def test_large_spaces_share_one_graph():
    a = pathzoo.load_scenario("gant.moderate.1")
    b = pathzoo.load_scenario("gant.moderate.2")
    assert a.graph is b.graph


def test_difficulty_grows_with_rectangle_count():
    counts = [gant.LARGE_SPACES[s]["rectangles"] for s in ("simple", "moderate", "complex")]
    assert counts == sorted(counts) and len(set(counts)) == 3
