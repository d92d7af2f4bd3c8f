"""``exact.sipp`` against a brute-force time-expanded search on small dynamic maps, and its safe intervals."""

from __future__ import annotations

import math

import numpy as np
import pytest

import pathzoo
from pathzoo.core import Budget, MovingObstacle, Scenario, Status, VehicleModel
from pathzoo.core.tolerances import TOUCH_EPS_CELLS
from pathzoo.rules import validate_path
from pathzoo.grid.safe_intervals import obstacle_arrays, safe_intervals, stationary_unsafe_times

STEP = 0.05
"""Departure times of the brute force: multiples of this (seconds)."""


def _scenario(occ: np.ndarray, start, goal, movers, speed: float = 1.0) -> Scenario:
    return Scenario(id="test.sipp", kind="dynamic", occupancy=occ, cell_size=1.0, start=np.array(start, float),
                    goal=np.array(goal, float), vehicle=VehicleModel(cruise_speed=speed), moving_obstacles=tuple(movers))


def _clear(sc: Scenario, p0: np.ndarray, p1: np.ndarray, t0: np.ndarray, t1: np.ndarray) -> np.ndarray:
    """Whether each timed segment keeps clear of every obstacle, by the judge's distance function."""
    ok = np.ones(len(p0), dtype=bool)
    for ob in sc.moving_obstacles:
        ok &= ob.min_distances(p0, p1, t0, t1) >= ob.radius + TOUCH_EPS_CELLS * sc.cell_size
    return ok


def brute_force_arrival(sc: Scenario, horizon: float) -> float:
    """Earliest arrival of a time-expanded search: depart from cell centres only at multiples of :data:`STEP`.

    Every path it considers is a path of SIPP's model (full-speed moves
    between centres, waits at centres), checked with the judge's distance
    function, so SIPP may never arrive later than this.
    """
    g = sc.graph
    speed = sc.vehicle.cruise_speed
    src, dst = sc.start_node, sc.goal_node
    centres = sc.point_of(np.arange(g.n_nodes))
    n_layers = int(horizon / STEP)
    reach = np.zeros((n_layers + 1, g.n_nodes), dtype=bool)
    if not _clear(sc, centres[[src]], centres[[src]], np.zeros(1), np.zeros(1))[0]:
        return math.inf
    reach[0, src] = True
    best = 0.0 if src == dst else math.inf
    u_all = np.repeat(np.arange(g.n_nodes), np.diff(g.indptr))
    for k in range(n_layers):
        t = k * STEP
        if t >= best:
            break
        here = np.flatnonzero(reach[k])
        waits = _clear(sc, centres[here], centres[here], np.full(len(here), t), np.full(len(here), t + STEP))
        reach[k + 1, here[waits]] = True
        edges = np.flatnonzero(reach[k][u_all])
        u, v = u_all[edges], g.indices[edges]
        arrive = t + g.length[edges] / speed
        ok = _clear(sc, centres[u], centres[v], np.full(len(u), t), arrive)
        for e, a, vv in zip(edges[ok], arrive[ok], v[ok]):
            if vv == dst:
                best = min(best, a)
            k2 = math.ceil(a / STEP - 1e-9)
            if k2 <= n_layers and _clear(sc, centres[[vv]], centres[[vv]], np.array([a]), np.array([k2 * STEP]))[0]:
                reach[k2, vv] = True
    return best


def _sipp(sc: Scenario):
    return pathzoo.make_planner("exact.sipp", horizon_s=60.0).plan(sc, budget=Budget(), rng=np.random.default_rng(0))


def _gate() -> tuple[np.ndarray, MovingObstacle]:
    """A 7 x 7 room cut by a wall with a one-cell gap, and a disc that sweeps through the gap."""
    occ = np.zeros((7, 7), dtype=bool)
    occ[3, :] = True
    occ[3, 3] = False
    mover = MovingObstacle(radius=0.8, waypoints=np.array([[0.5, 3.5], [6.5, 3.5]]), speed=1.0, phase_s=1.0)
    return occ, mover


def test_sipp_waits_for_the_gate_and_matches_the_brute_force():
    occ, mover = _gate()
    sc = _scenario(occ, (3.5, 0.5), (3.5, 6.5), [mover])
    result = _sipp(sc)
    assert result.status is Status.SOLVED, result.message
    assert validate_path(sc, result.path, result.times)
    static = 6.0  # six straight moves at 1 m/s
    arrival = float(result.times[-1])
    assert arrival > static + 0.1  # the disc is in the gap when a non-stop drive would pass it
    brute = brute_force_arrival(sc, 30.0)
    assert arrival <= brute + 1e-6
    assert brute - arrival < 1.0  # the lattice of departures costs the brute force at most a little time here


@pytest.mark.parametrize("seed", range(4))
def test_sipp_never_arrives_later_than_the_brute_force_on_random_maps(seed):
    rng = np.random.default_rng(seed)
    occ = rng.random((6, 6)) < 0.2
    occ[0, 0] = occ[5, 5] = False
    movers = []
    for _ in range(2):
        a, b = rng.uniform(0.5, 5.5, size=(2, 2))
        movers.append(MovingObstacle(radius=float(rng.uniform(0.4, 0.9)), waypoints=np.array([a, b]),
                                     speed=float(rng.uniform(0.5, 1.5)), phase_s=float(rng.uniform(0, 5))))
    sc = _scenario(occ, (0.5, 0.5), (5.5, 5.5), movers)
    brute = brute_force_arrival(sc, 30.0)
    result = _sipp(sc)
    if result.status is Status.SOLVED:
        assert validate_path(sc, result.path, result.times)
        assert float(result.times[-1]) <= brute + 1e-6
    else:  # SIPP finding nothing is only right when the brute force finds nothing either
        assert result.status in (Status.NO_PATH, Status.FAILED)
        assert math.isinf(brute), result.message


def test_a_path_that_ignores_the_obstacle_is_refused_and_sipp_is_not():
    # the static optimum driven without waiting meets the disc in the gap: the check above is not vacuous
    occ, mover = _gate()
    sc = _scenario(occ, (3.5, 0.5), (3.5, 6.5), [mover])
    straight = np.array([[3.5, 0.5], [3.5, 6.5]])
    assert not validate_path(sc, straight)
    assert validate_path(sc, _sipp(sc).path, _sipp(sc).times)


def test_off_centre_endpoints_use_connectors():
    occ, mover = _gate()
    sc = _scenario(occ, (3.2, 0.3), (3.7, 6.9), [mover])
    result = _sipp(sc)
    assert result.status is Status.SOLVED, result.message
    assert np.array_equal(result.path[0], sc.start) and np.array_equal(result.path[-1], sc.goal)
    assert validate_path(sc, result.path, result.times)


def test_start_covered_at_time_zero_is_a_stated_failure():
    occ = np.zeros((4, 4), dtype=bool)
    parked = MovingObstacle(radius=0.6, waypoints=np.array([[0.5, 0.5]]), speed=0.0)
    result = _sipp(_scenario(occ, (0.5, 0.5), (3.5, 3.5), [parked]))
    assert result.status is Status.FAILED and "covers the start" in result.message


def test_stationary_unsafe_times_match_sampled_distances():
    ob = MovingObstacle(radius=1.0, waypoints=np.array([[0.0, 0.0], [10.0, 0.0]]), speed=2.0, phase_s=3.0)
    obs = obstacle_arrays((ob,), 0.0)
    bad = stationary_unsafe_times(obs.cycles, obs.cums, 2.0, 3.0, 4.0, 0.5, 1.0, 30.0)
    ts = np.linspace(0.0, 30.0, 3001)
    near = np.linalg.norm(ob.position(ts) - np.array([4.0, 0.5]), axis=1) < 1.0
    inside = np.zeros_like(near)
    for lo, hi in bad:
        inside |= (ts >= lo) & (ts <= hi)
    assert np.array_equal(near, inside)
    assert len(bad) >= 5  # the disc passes (4, 0.5) twice per 10 s period


def test_safe_intervals_are_the_complement_of_the_unsafe_times():
    ob = MovingObstacle(radius=1.0, waypoints=np.array([[0.0, 0.0], [10.0, 0.0]]), speed=2.0, phase_s=3.0)
    safe = safe_intervals(obstacle_arrays((ob,), 0.0), np.array([4.0, 0.5]), 0.0, 30.0)
    ts = np.linspace(0.0, 30.0, 3001)
    clear = np.linalg.norm(ob.position(ts) - np.array([4.0, 0.5]), axis=1) >= 1.0
    covered = np.zeros_like(clear)
    for lo, hi in safe:
        covered |= (ts >= lo) & (ts <= hi)
    assert np.array_equal(clear, covered)


def test_the_harness_judges_sipp_valid_and_scores_arrival_ratio_one(tmp_path):
    occ, mover = _gate()
    sc = _scenario(occ, (3.5, 0.5), (3.5, 6.5), [mover])
    runs = pathzoo.run(["exact.sipp"], [sc], seeds=1, db=tmp_path / "r.sqlite", budget=Budget(time_s=30.0),
                       executor="inline", progress=False, experiment="sipp")
    row = runs.iloc[0]
    assert str(getattr(row["status"], "value", row["status"])) == "solved" and bool(row["valid"]), row["invalid_reason"]
    assert row["arrival_ratio"] == pytest.approx(1.0, abs=1e-12)
