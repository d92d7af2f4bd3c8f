"""Dijkstra and A* costs equal ``scipy.sparse.csgraph.dijkstra`` on the same graph, for length and energy.

Covered: MovingAI grids (a sample), a real DEM with slope limits (so the
graph is directed and some edges are gone), and a small air volume. The cost
of each returned path is recomputed here from its waypoints
(:func:`pathzoo.grid.terrain.segment_profile` and the vehicle's eq. 4 power
model), not read from the planner.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Callable

import numpy as np
import pytest
from scipy.sparse.csgraph import dijkstra

import pathzoo
from pathzoo.core import Budget, Scenario, Status, VehicleModel
from pathzoo.grid.terrain import segment_profile
from pathzoo.rules import validate_path
from pathzoo.io import read_asc

PLANNERS = ("exact.dijkstra", "exact.astar")
COSTS = ("length", "energy")
REL_TOL = 1e-9


def path_cost(scenario: Scenario, path: np.ndarray, cost: str) -> float:
    """Length or energy of a path, segment by segment, as the harness would measure it."""
    total = 0.0
    for p0, p1 in zip(path[:-1], path[1:]):
        if scenario.dim == 3:
            d = p1 - p0
            lengths = np.array([np.linalg.norm(d)])
            slopes = np.array([math.atan2(d[2], math.hypot(d[0], d[1]))])
        else:
            elevation = scenario.elevation if scenario.kind == "terrain" else None
            lengths, slopes = segment_profile(elevation, p0, p1, scenario.cell_size)
        total += lengths.sum() if cost == "length" else scenario.vehicle.segment_energy(lengths, slopes).sum()
    return float(total)


def check_against_scipy(scenarios: list[Scenario], planner_id: str, cost: str) -> int:
    """Plan every scenario (one shared graph) and compare with SciPy; returns how many were reachable."""
    graph = scenarios[0].graph
    matrix = graph.to_sparse(cost)
    sources = sorted({s.start_node for s in scenarios})
    dist = dijkstra(matrix, directed=True, indices=sources)
    row = {s: i for i, s in enumerate(sources)}
    planner = pathzoo.make_planner(planner_id, cost=cost)
    reachable = 0
    for scenario in scenarios:
        assert scenario.graph is graph
        expected = dist[row[scenario.start_node], scenario.goal_node]
        result = planner.plan(scenario, budget=Budget(), rng=np.random.default_rng(0))
        if not np.isfinite(expected):
            assert result.status is Status.NO_PATH, scenario.id
            continue
        reachable += 1
        assert result.status is Status.SOLVED, (scenario.id, result.message)
        verdict = validate_path(scenario, result.path)
        assert verdict, (scenario.id, verdict.reason)
        got = path_cost(scenario, result.path, cost)
        assert got == pytest.approx(expected, rel=REL_TOL, abs=1e-9), scenario.id
        assert result.extras["best_cost"] == pytest.approx(expected, rel=REL_TOL, abs=1e-9), scenario.id
    return reachable


@pytest.mark.parametrize("cost", COSTS)
@pytest.mark.parametrize("planner_id", PLANNERS)
@pytest.mark.parametrize(("scen", "step"), [("grid/dao/arena.map.scen", 8), ("grid/rooms/8room_000.map.scen", 388)])
def test_movingai_sample_matches_scipy(
    load_scen: Callable[[str], list[Scenario]], scen: str, step: int, planner_id: str, cost: str
) -> None:
    sample = load_scen(scen)[::step]
    assert check_against_scipy(sample, planner_id, cost) == len(sample)


def hugo_scenarios(shared_data: Path, vehicle: VehicleModel, n: int = 30) -> list[Scenario]:
    """Random problems between free cells of the hugo_site DEM (10 m cells, 2028 NODATA cells)."""
    dem = read_asc(shared_data / "dem" / "hugo_site.asc")
    free = np.flatnonzero(np.isfinite(dem.elevation))
    rng = np.random.default_rng(7)
    pairs = rng.choice(free, size=(n, 2))
    h, w = dem.elevation.shape
    centre = lambda node: ((node % w + 0.5) * dem.cell_size, (node // w + 0.5) * dem.cell_size)  # noqa: E731
    first = Scenario(
        id="hugo.0",
        kind="terrain",
        occupancy=np.zeros((h, w), dtype=bool),
        cell_size=dem.cell_size,
        elevation=dem.elevation,
        start=centre(pairs[0, 0]),
        goal=centre(pairs[0, 1]),
        vehicle=vehicle,
    )
    first.graph  # build once, shared by the copies
    return [first] + [first.with_endpoints(centre(a), centre(b), id=f"hugo.{i}") for i, (a, b) in enumerate(pairs[1:], 1)]


@pytest.mark.parametrize("cost", COSTS)
@pytest.mark.parametrize("planner_id", PLANNERS)
@pytest.mark.parametrize("onboard_power_w", [0.0, 40.0])
def test_terrain_with_slope_limits_matches_scipy(shared_data: Path, planner_id: str, cost: str, onboard_power_w: float) -> None:
    # with no onboard load, steep descents cost no energy and A*'s energy heuristic is 0; with it, it is not
    # the DEM is in whole metres, so edge slopes take few values: these limits fall between them
    limited = VehicleModel(max_climb_deg=10.0, max_descent_deg=14.0, onboard_power_w=onboard_power_w)
    scenarios = hugo_scenarios(shared_data, limited)
    unlimited = hugo_scenarios(shared_data, VehicleModel(onboard_power_w=onboard_power_w), n=1)[0]
    graph = scenarios[0].graph
    assert graph.n_edges < unlimited.graph.n_edges  # the slope limits removed edges
    matrix = graph.to_sparse(cost)
    assert (matrix != matrix.T).nnz > 0  # some moves are allowed one way only
    assert check_against_scipy(scenarios, planner_id, cost) >= len(scenarios) // 2


def air_scenarios(n: int = 12) -> list[Scenario]:
    rng = np.random.default_rng(3)
    occ = rng.random((5, 10, 10)) < 0.25
    free = np.flatnonzero(~occ)
    pairs = rng.choice(free, size=(n, 2))
    sizes = np.array([2.0, 2.0, 1.5])

    def centre(node: int) -> np.ndarray:
        z, y, x = np.unravel_index(node, occ.shape)
        return (np.array([x, y, z]) + 0.5) * sizes

    first = Scenario(
        id="air.0",
        kind="air3d",
        occupancy=occ,
        cell_size=2.0,
        vertical_cell_size=1.5,
        max_step=(2, 1),
        start=centre(pairs[0, 0]),
        goal=centre(pairs[0, 1]),
        vehicle=VehicleModel(max_pitch_deg=30.0),
    )
    first.graph  # build once, shared by the copies
    return [first] + [first.with_endpoints(centre(a), centre(b), id=f"air.{i}") for i, (a, b) in enumerate(pairs[1:], 1)]


@pytest.mark.parametrize("cost", COSTS)
@pytest.mark.parametrize("planner_id", PLANNERS)
def test_air_volume_matches_scipy(planner_id: str, cost: str) -> None:
    scenarios = air_scenarios()
    assert check_against_scipy(scenarios, planner_id, cost) >= len(scenarios) // 2


def test_astar_energy_heuristic_prunes_with_an_onboard_load(shared_data: Path) -> None:
    vehicle = VehicleModel(max_climb_deg=10.0, max_descent_deg=14.0, onboard_power_w=40.0)
    expanded = {}
    for planner_id in PLANNERS:
        planner = pathzoo.make_planner(planner_id, cost="energy")
        runs = [planner.plan(s, budget=Budget(), rng=np.random.default_rng(0)) for s in hugo_scenarios(shared_data, vehicle)]
        expanded[planner_id] = sum(r.evaluations for r in runs if r.solved)
    assert expanded["exact.astar"] < 0.9 * expanded["exact.dijkstra"]
