"""The ompl.* planners: valid paths, determinism, budgets, convergence reports, simplification, silence."""

import subprocess
import sys

import numpy as np
import pytest

from pathzoo import Budget, Scenario, Status, VehicleModel, make_planner
from pathzoo.rules import validate_path
from pathzoo.testing import check_scenario

IDS = [
    "ompl.rrt", "ompl.rrtconnect", "ompl.rrtstar", "ompl.informed_rrtstar", "ompl.prmstar", "ompl.bitstar", "ompl.fmt"
]
ANYTIME = {"ompl.rrtstar", "ompl.informed_rrtstar", "ompl.prmstar", "ompl.bitstar"}


def _rooms() -> Scenario:
    occ = np.zeros((20, 20), dtype=bool)
    occ[:14, 6] = True
    occ[6:, 13] = True
    return Scenario(id="rooms", kind="grid2d", occupancy=occ, cell_size=0.5, start=[0.6, 0.7], goal=[9.4, 9.3])


def _plan(pid, scenario, budget, seed=3, progress=None, **params):
    return make_planner(pid, **params).plan(scenario, budget=budget, rng=np.random.default_rng(seed), progress=progress)


@pytest.mark.parametrize("pid", IDS)
def test_solves_deterministically_with_monotone_progress(pid):
    scenario = _rooms()
    budget = Budget(iterations=20, time_s=30)
    calls = []
    first = _plan(pid, scenario, budget, progress=lambda *c: calls.append(c))
    assert first.status is Status.SOLVED, first.message
    assert validate_path(scenario, first.path)
    assert first.iterations <= 20 and calls and calls[-1][0] <= 20
    costs = [c[2] for c in calls]
    assert costs == sorted(costs, reverse=True)
    assert costs[-1] == pytest.approx(np.hypot(*np.diff(first.path, axis=0).T).sum())
    if pid in ANYTIME:
        assert len(calls) > 1  # an improving curve, not one point
    again = _plan(pid, scenario, budget)
    np.testing.assert_array_equal(again.path, first.path)
    other = _plan(pid, scenario, budget, seed=4)
    assert not np.array_equal(other.path, first.path)


@pytest.mark.parametrize("pid", IDS)
@pytest.mark.parametrize("limit", [1, 40])
def test_evaluation_budget_counts_motion_checks(pid, limit):
    calls = []
    result = _plan(pid, _rooms(), Budget(evaluations=limit, time_s=30), progress=lambda *c: calls.append(c))
    assert result.evaluations == limit
    assert all(c[1] <= limit for c in calls)


@pytest.mark.parametrize("pid", ["ompl.rrtstar", "ompl.prmstar"])
def test_iteration_budget_is_a_number_of_planner_steps(pid):
    small = _plan(pid, _rooms(), Budget(iterations=2, time_s=30), iteration_steps=10)
    large = _plan(pid, _rooms(), Budget(iterations=8, time_s=30), iteration_steps=10)
    assert small.iterations == 2 and small.extras["steps"] == 20
    assert large.iterations == 8 and large.extras["steps"] == 80
    assert large.evaluations > small.evaluations


@pytest.mark.parametrize("pid", ["ompl.rrt", "ompl.prmstar", "ompl.fmt"])
def test_simplification_keeps_validity_and_never_lengthens(pid):
    scenario = _rooms()
    budget = Budget(iterations=20, time_s=30)
    raw = _plan(pid, scenario, budget)
    short = _plan(pid, scenario, budget, simplify=True)
    assert short.status is Status.SOLVED and validate_path(scenario, short.path)
    assert short.extras["simplified"] is True
    length = lambda p: np.hypot(*np.diff(p, axis=0).T).sum()  # noqa: E731
    assert length(short.path) < length(raw.path)
    np.testing.assert_array_equal(short.path[[0, -1]], raw.path[[0, -1]])


@pytest.mark.parametrize("pid", IDS)
def test_unreachable_goal_fails_without_a_path(pid):
    result = _plan(pid, check_scenario("grid2d", reachable=False), Budget(iterations=3, time_s=30))
    assert result.status is Status.FAILED and result.path is None
    assert "no exact solution" in result.message


def test_a_path_breaking_a_turn_limit_is_reported_failed():
    base = _rooms()
    scenario = Scenario(id="stiff", kind="grid2d", occupancy=base.occupancy, cell_size=0.5, start=base.start,
                        goal=base.goal, vehicle=VehicleModel(max_turn_deg=10.0))
    result = _plan("ompl.rrtconnect", scenario, Budget(iterations=20, time_s=30))
    assert result.status is Status.FAILED and result.path is None
    assert "heading change" in result.message


def test_ompl_is_silent_and_the_log_level_is_restored(capfd):
    from ompl import util as ou

    ou.setLogLevel(ou.LogLevel.LOG_DEBUG)
    try:
        _plan("ompl.prmstar", _rooms(), Budget(iterations=4, time_s=30))
        _plan("ompl.bitstar", _rooms(), Budget(iterations=4, time_s=30))
        assert ou.getLogLevel() == ou.LogLevel.LOG_DEBUG
    finally:
        ou.setLogLevel(ou.LogLevel.LOG_WARN)
    out, err = capfd.readouterr()
    assert out == "" and err == ""


def test_listing_plugins_imports_no_heavy_library():
    code = (
        "import sys, pathzoo; pathzoo.list_plugins('planners'); "
        "print(sorted(m for m in ('ompl', 'pyswarms', 'deap', 'skfuzzy') if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"
