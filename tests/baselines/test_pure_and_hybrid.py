"""Pure metaheuristics run no global search, on every kind; hybrids are declared and marked as such (issue 21)."""

import numpy as np
import pytest

import pathzoo
from pathzoo import Budget, make_planner
from pathzoo.analysis.leaderboard import format_leaderboard, leaderboard
from pathzoo.analysis.synthetic import make_runs
from pathzoo.cli.cmd_list import list_table
from pathzoo.plugins.manager import get_registry
from pathzoo.rules import validate_path
from pathzoo.testing import check_scenario
from pathzoo_baselines import routing
from pathzoo_baselines.cost import PathCost
from pathzoo_baselines.local_repair import repair_polylines, window_route
from pathzoo_baselines.margin import MARGIN_CELLS, polylines_clear

PURE = ["swarm.pso", "swarm.cuckoo", "swarm.coa", "evo.ga", "evo.fuzzy_rate_ga"]
HYBRID = ["swarm.pso_astar", "swarm.cuckoo_astar", "evo.ga_astar", "evo.fuzzy_rate_ga_astar"]
KINDS = ["grid2d", "terrain", "dynamic", "air3d"]


class GlobalSearchCalled(AssertionError):
    """Raised by the patched router: a configuration ran the global shortest-path search."""


@pytest.fixture
def no_global_search(monkeypatch):
    """Make the A* router (every global shortest-path search the baselines have) raise when built or used."""

    def forbidden(*args, **kwargs):
        raise GlobalSearchCalled("the global shortest-path search was called")

    monkeypatch.setattr(routing.CellRouter, "__init__", forbidden)
    monkeypatch.setattr(routing.CellRouter, "route", forbidden)
    monkeypatch.setattr(routing, "route_kernel", forbidden)


@pytest.mark.parametrize("kind", KINDS)
@pytest.mark.parametrize("pid", PURE)
def test_pure_configurations_never_call_the_global_search(pid, kind, no_global_search):
    result = make_planner(pid).plan(check_scenario(kind), budget=Budget(iterations=3), rng=np.random.default_rng(0))
    assert result.status is not None  # it ran to the end without touching the router


@pytest.mark.parametrize("pid", HYBRID)
def test_the_patch_bites_the_hybrids(pid, no_global_search):
    """The same patch stops every hybrid: the test above could fail."""
    with pytest.raises(GlobalSearchCalled):
        make_planner(pid).plan(check_scenario("grid2d"), budget=Budget(iterations=3), rng=np.random.default_rng(0))


def test_declarations_say_which_planners_are_hybrid():
    table = get_registry().table("planners")
    for pid in PURE:
        assert table[pid].declared("hybrid") is False and table[pid].obj.hybrid is False
        assert set(table[pid].declared("kinds")) == set(KINDS)
    for pid in HYBRID:
        assert table[pid].declared("hybrid") is True and table[pid].obj.hybrid is True
        assert set(table[pid].declared("kinds")) == {"grid2d", "terrain"}


def test_pathzoo_list_marks_hybrids_only():
    table = get_registry().table("planners")
    lines = list_table([table[p] for p in PURE + HYBRID], "planners").splitlines()
    for pid in PURE + HYBRID:
        (line,) = [ln for ln in lines if ln.startswith(pid + " ")]
        assert ("[hybrid]" in line) == (pid in HYBRID), line


def test_leaderboard_marks_hybrids():
    runs = make_runs({"s": {"evo.ga_astar": [1.0, 1.0], "evo.ga": [2.0, 2.0]}})
    text = format_leaderboard(leaderboard(runs), "text")
    assert "evo.ga_astar [hybrid]" in text
    assert "evo.ga [hybrid]" not in text
    assert "a hybrid planner" in text
    assert "[hybrid]" not in format_leaderboard(leaderboard(make_runs({"s": {"evo.ga": [1.0]}})), "text")


def test_graph_encodings_refuse_moving_obstacles_and_volumes():
    for kind in ("dynamic", "air3d"):
        with pytest.raises(pathzoo.UnsupportedScenarioError):
            make_planner("evo.ga", encoding="grid").plan(
                check_scenario(kind), budget=Budget(iterations=1), rng=np.random.default_rng(0)
            )


def test_cost_counts_a_moving_obstacle_met_at_the_time_of_passage():
    """The conformance map's disc patrols the gap at y = 8.5: crossing the gap is free at some times only."""
    dynamic = check_scenario("dynamic")
    static = check_scenario("grid2d")
    ob = dynamic.moving_obstacles[0]
    # a path that waits for nothing: through the gap along y = 8.5, where the disc drives
    path = np.array([[dynamic.start, [1.5, 8.5], [9.0, 8.5], dynamic.goal]])
    _, on_static = PathCost(static, 1.0)(path)
    _, on_dynamic = PathCost(dynamic, 1.0)(path)
    assert on_static[0] == 0
    judged = validate_path(dynamic, path[0])
    assert (on_dynamic[0] > 0) == (not judged), judged.reason  # the cost agrees with the judge
    assert on_dynamic[0] > 0 and ob.radius > 0


def test_cost_counts_voxels_and_pitch_in_air_volumes():
    sc = check_scenario("air3d")
    z_top = sc.extent[2] - 0.5 * sc.vertical_cell_size
    through = np.array([[sc.start, [sc.goal[0], sc.goal[1], sc.start[2]], sc.goal]])
    over = np.array([[sc.start, [sc.start[0], sc.start[1], z_top], [sc.goal[0], sc.goal[1], z_top], sc.goal]])
    cost = PathCost(sc, 1.0)
    assert cost(through)[1][0] > 0
    assert cost(over)[1][0] == 0 and validate_path(sc, over[0])


def test_window_route_is_local_and_shortest():
    blocked = np.zeros((20, 20), dtype=bool)
    blocked[4:7, 5] = True  # a wall of three cells between (5, 3) and (5, 7); rows 3 and 7 are in the box
    route = window_route(blocked, 5, 3, 5, 7, 4)
    steps = np.abs(np.diff(route, axis=0))
    assert tuple(route[0]) == (5, 3) and tuple(route[-1]) == (5, 7) and np.all(steps.max(axis=1) == 1)
    assert not blocked[route[:, 0], route[:, 1]].any()
    diagonal = steps.sum(axis=1) == 2
    length = diagonal.sum() * np.sqrt(2) + (~diagonal).sum()
    sc = pathzoo.Scenario(id="t.wall", kind="grid2d", occupancy=blocked, cell_size=1.0,
                          start=np.array([3.5, 5.5]), goal=np.array([7.5, 5.5]))
    best = make_planner("exact.dijkstra").plan(sc, budget=Budget(), rng=np.random.default_rng(0))
    assert length == pytest.approx(np.hypot(*np.diff(best.path, axis=0).T).sum())
    assert len(window_route(blocked, 5, 3, 5, 12, 4)) == 0  # farther apart than the window: no repair
    blocked[0:20, 10] = True
    assert len(window_route(blocked, 5, 8, 5, 12, 4)) == 0  # no route inside the box: no repair


def test_repaired_polylines_are_clear_and_keep_their_ends():
    sc = pathzoo.load_scenario("movingai.random-32-32-20.b2.136")
    rng = np.random.default_rng(3)
    pts = rng.uniform(0, 32, (40, 6, 2))
    pts[:, 0], pts[:, -1] = sc.start, sc.goal
    out, lengths = repair_polylines(sc.blocked, pts, 8, MARGIN_CELLS)
    assert np.all(out[:, 0] == pts[:, 0])
    assert np.all(out[np.arange(40), lengths - 1] == pts[:, -1])
    before = polylines_clear(sc.blocked, pts, MARGIN_CELLS)
    after = polylines_clear(sc.blocked, np.ascontiguousarray(out), MARGIN_CELLS)
    assert np.all(after <= before) and after.sum() < before.sum()
