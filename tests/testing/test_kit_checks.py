"""The conformance kit passes a correct planner and catches each kind of broken one."""

from __future__ import annotations

import pickle
import random
import time

import numpy as np
import pytest
from scipy.sparse.csgraph import dijkstra

import pathzoo
from pathzoo import Param, Planner, PlanResult, Status
from pathzoo.rules import validate_path
from pathzoo.testing import ConformanceError, check_planner, check_scenario, planner_checks
from pathzoo.testing import checks as C

KINDS = ("grid2d", "terrain", "air3d", "dynamic")


class Shortest(Planner):
    """A correct reference: Dijkstra on the scenario graph (ignores moving obstacles)."""

    id = "kit.shortest"
    summary = "Dijkstra on the grid graph"
    kinds = frozenset({"grid2d", "terrain", "air3d"})
    params = {"rounds": Param(1, "repeat the search", low=1, high=3), "mode": Param("a", "a mode", choices=("a", "b"))}

    @staticmethod
    def _path(scenario):
        _, pred = dijkstra(scenario.graph.to_sparse(), indices=scenario.start_node, return_predecessors=True)
        node, nodes = scenario.goal_node, []
        if pred[node] < 0 and node != scenario.start_node:
            return None
        while node >= 0:
            nodes.append(node)
            node = pred[node]
        centres = scenario.point_of(np.array(nodes[::-1]))
        return np.vstack([scenario.start, centres, scenario.goal])

    def plan(self, scenario, *, budget, rng, progress=None):
        self.check_supports(scenario)
        path = Shortest._path(scenario)
        if path is None:
            return PlanResult(Status.NO_PATH, iterations=1, evaluations=1)
        if progress is not None:
            progress(1, 1, float(np.linalg.norm(np.diff(path, axis=0), axis=1).sum()))
        return PlanResult(Status.SOLVED, path=path, iterations=1, evaluations=1)


def _variant(name, plan=None, **attrs):
    ns = dict(attrs, id=f"kit.{name.lower()}")
    if plan is not None:
        ns["plan"] = plan
    return type(name, (Shortest,), ns)


def _centres_only(self, scenario, *, budget, rng, progress=None):
    res = Shortest.plan(self, scenario, budget=budget, rng=rng, progress=progress)
    return PlanResult(res.status, path=None if res.path is None else res.path[1:-1], iterations=1, evaluations=1)


def _straight(self, scenario, *, budget, rng, progress=None):
    return PlanResult(Status.SOLVED, path=np.vstack([scenario.start, scenario.goal]), iterations=1, evaluations=1)


def _global_random(self, scenario, *, budget, rng, progress=None):
    res = Shortest.plan(self, scenario, budget=budget, rng=rng, progress=progress)
    return PlanResult(res.status, path=res.path + np.random.uniform(0, 1e-9), iterations=1, evaluations=1)


def _rng_dependent_ok(self, scenario, *, budget, rng, progress=None):
    res = Shortest.plan(self, scenario, budget=budget, rng=rng, progress=progress)
    return PlanResult(res.status, path=res.path, iterations=1, evaluations=int(rng.integers(1, 3)))


def _too_many_iterations(self, scenario, *, budget, rng, progress=None):
    res = Shortest.plan(self, scenario, budget=budget, rng=rng)
    for i in range(1, 11):
        if progress is not None:
            progress(i, i, 10.0)
    return PlanResult(res.status, path=res.path, iterations=10, evaluations=10)


def _slow(self, scenario, *, budget, rng, progress=None):
    time.sleep(0.5)
    return Shortest.plan(self, scenario, budget=budget, rng=rng, progress=progress)


def _raises_when_unreachable(self, scenario, *, budget, rng, progress=None):
    res = Shortest.plan(self, scenario, budget=budget, rng=rng, progress=progress)
    if res.status is Status.NO_PATH:
        raise RuntimeError("no path")
    return res


def _claims_solved(self, scenario, *, budget, rng, progress=None):
    res = Shortest.plan(self, scenario, budget=budget, rng=rng, progress=progress)
    return PlanResult(Status.SOLVED, path=res.path if res.path is not None else np.vstack([scenario.start]))


def _caches_on_scenario(self, scenario, *, budget, rng, progress=None):
    scenario.__dict__["my_cache"] = 1
    return Shortest.plan(self, scenario, budget=budget, rng=rng, progress=progress)


def _edits_metadata(self, scenario, *, budget, rng, progress=None):
    scenario.metadata["touched"] = True
    return Shortest.plan(self, scenario, budget=budget, rng=rng, progress=progress)


class Counting(Shortest):
    """Keeps a call counter: state that survives between plan() calls."""

    id = "kit.counting"

    def plan(self, scenario, *, budget, rng, progress=None):
        self.__dict__["calls"] = self.__dict__.get("calls", 0) + 1
        return super().plan(scenario, budget=budget, rng=rng, progress=progress)


def _worsening(self, scenario, *, budget, rng, progress=None):
    res = Shortest.plan(self, scenario, budget=budget, rng=rng)
    progress(1, 1, 5.0)
    progress(2, 2, 6.0)
    return res


def _silent(self, scenario, *, budget, rng, progress=None):
    return Shortest.plan(self, scenario, budget=budget, rng=rng, progress=None)


def _no_kind_check(self, scenario, *, budget, rng, progress=None):
    return PlanResult(Status.FAILED)


class Lenient(Shortest):
    """Accepts any parameter (does not call Planner.__init__)."""

    id = "kit.lenient"

    def __init__(self, **params):
        self._values = {"rounds": 1, "mode": "a", **params}


class Unpicklable(Shortest):
    id = "kit.unpicklable"

    def __init__(self, **params):
        super().__init__(**params)
        self.hook = lambda: None


def test_correct_planner_passes_every_check():
    check_planner(Shortest)  # raises ConformanceError otherwise


def test_check_list_covers_kinds_and_contract():
    checks = list(planner_checks(Shortest()))
    names = [getattr(c, "func", c).__name__ for c in checks]
    for kind in ("grid2d", "terrain", "air3d"):
        assert {"check_solves", "check_unreachable_goal"} <= {
            getattr(c, "func", c).__name__ for c in checks if getattr(c, "keywords", {}).get("kind") == kind
        }
    assert "check_unsupported_kinds" in names and "check_picklable" in names and "check_budget_time" in names


@pytest.mark.parametrize("kind", KINDS)
def test_check_scenarios_are_solvable_and_unreachable_variants_are_not(kind):
    ok, walled = check_scenario(kind), check_scenario(kind, reachable=False)
    assert ok.kind == walled.kind == kind
    path = Shortest._path(ok)
    assert path is not None and validate_path(ok, path)
    assert Shortest._path(walled) is None
    # the start is deliberately off the cell centre
    assert not np.allclose(ok.start, ok.point_of([ok.start_node])[0])


@pytest.mark.parametrize(
    ("planner", "check", "kw", "message"),
    [
        (Lenient(), C.check_rejects_unknown_parameter, {}, "accepted the unknown parameter"),
        (Lenient(), C.check_rejects_out_of_range, {}, "accepted rounds=0"),
        (_variant("Straight", _straight)(), C.check_solves, {"kind": "grid2d"}, "invalid path"),
        (_variant("CentresOnly", _centres_only)(), C.check_solves, {"kind": "grid2d"}, "not at the start"),
        (_variant("NoDeclaredKinds", kinds=frozenset())(), C.check_declaration, {}, "kinds must be"),
        (_variant("GlobalRandom", _global_random)(), C.check_same_seed_same_path, {"kind": "grid2d"}, "different"),
        (_variant("TooMany", _too_many_iterations)(), C.check_budget_iterations, {}, "used 10 iterations"),
        (_variant("TooMany2", _too_many_iterations)(), C.check_budget_evaluations, {}, "used 10 evaluations"),
        (_variant("Raises", _raises_when_unreachable)(), C.check_unreachable_goal, {"kind": "terrain"}, "raised RuntimeError"),
        (_variant("Claims", _claims_solved)(), C.check_unreachable_goal, {"kind": "air3d"}, "returned status solved"),
        (_variant("Caches", _caches_on_scenario)(), C.check_scenario_unchanged, {"kind": "grid2d"}, "added attribute"),
        (_variant("EditsMeta", _edits_metadata)(), C.check_scenario_unchanged, {"kind": "grid2d"}, "changed the scenario's metadata"),
        (Counting(), C.check_picklable, {}, "changed the planner's state"),
        (Unpicklable(), C.check_picklable, {}, "cannot be pickled"),
        (_variant("Worse", _worsening)(), C.check_history_improves, {"kind": "grid2d"}, "best_cost increased"),
        (_variant("Silent", _silent)(), C.check_history_improves, {"kind": "grid2d"}, "without ever calling progress"),
        (_variant("NoKindCheck", _no_kind_check)(), C.check_unsupported_kinds, {}, "did not raise UnsupportedScenarioError"),
    ],
    ids=lambda v: v if isinstance(v, str) else None,
)
def test_each_check_catches_its_violation(planner, check, kw, message):
    with pytest.raises(ConformanceError, match=message):
        check(planner, **kw)


def test_same_seed_check_accepts_rng_driven_randomness():
    C.check_same_seed_same_path(_variant("RngOk", _rng_dependent_ok)(), kind="grid2d")


def test_time_check_uses_the_budget_and_tolerance(monkeypatch):
    monkeypatch.setattr(C, "TIME_BUDGET_S", 0.05)
    monkeypatch.setattr(C, "TIME_TOLERANCE_S", 0.1)
    with pytest.raises(ConformanceError, match=r"kit.slow: plan\(\) with Budget\(time_s=0.05\) on testing.grid2d "
                                               r"had not returned after 0.15 s; its process was killed"):
        C.check_budget_time(_variant("Slow", _slow)())
    C.check_budget_time(Shortest())


class IgnoresTime(Shortest):
    """Honours iteration and evaluation limits but never looks at the clock: loops forever on a time-only budget."""

    id = "kit.ignores_time"

    def plan(self, scenario, *, budget, rng, progress=None):
        res = super().plan(scenario, budget=budget, rng=rng, progress=progress)
        limit = budget.iterations or budget.evaluations
        i = 0
        while limit is None or i < limit:
            i += 1
        return PlanResult(res.status, path=res.path, iterations=1, evaluations=1)


def _hangs(self, scenario, *, budget, rng, progress=None):
    while True:
        pass


def _tie_break_with_global_random(self, scenario, *, budget, rng, progress=None):
    """A path that never depends on the draw: only the global generator's state shows it."""
    random.random()
    return Shortest.plan(self, scenario, budget=budget, rng=rng, progress=progress)


def test_a_planner_ignoring_its_time_budget_fails_the_time_check_instead_of_hanging():
    """The kit used to wait for such a planner forever (24 minutes before the newcomer stopped it)."""
    with pytest.raises(ConformanceError) as info:
        check_planner(IgnoresTime())
    failed = [line.strip() for line in str(info.value).splitlines()[1:]]
    assert failed == ["check_budget_time: CheckTimeout: kit.ignores_time: plan() with Budget(time_s=0.3) on "
                      "testing.grid2d had not returned after 1.3 s; its process was killed",
                      "not run after that timeout: check_budget_default, check_picklable, check_unsupported_kinds"]


class SleepsAMinute(Shortest):
    """Ignores every budget: each plan() takes 60 s (a sleep, so the test leaves the shared CPUs to others)."""

    id = "kit.sleeps_a_minute"

    def plan(self, scenario, *, budget, rng, progress=None):
        time.sleep(60.0)
        return super().plan(scenario, budget=budget, rng=rng, progress=progress)


def test_a_planner_that_ignores_its_budget_for_a_minute_is_reported_within_90_s():
    started = time.monotonic()
    with pytest.raises(ConformanceError) as info:
        check_planner(SleepsAMinute())
    elapsed = time.monotonic() - started
    failed = [line.strip() for line in str(info.value).splitlines()[1:]]
    assert failed[0].startswith("check_solves[grid2d]: CheckTimeout: kit.sleeps_a_minute: the untimed warm-up plan() "
                                "on grid2d with Budget(iterations=5")
    assert failed[1].startswith("not run after that timeout: check_same_seed_same_path[grid2d], ")
    assert len(failed) == 2 and elapsed < 90.0


def test_no_budget_means_the_planners_own_count():
    C.check_budget_default(Shortest())
    with pytest.raises(C.CheckTimeout, match=r"kit.ignores_time: check_budget_default had not returned after 0.5 s"):
        with pytest.MonkeyPatch.context() as mp:
            mp.setattr(C, "CHECK_LIMIT_S", 0.5)
            C.check_budget_default(IgnoresTime())


def test_a_planner_that_never_returns_fails_every_planning_check(monkeypatch):
    monkeypatch.setattr(C, "WARM_UP_LIMIT_S", 0.3)
    planner = _variant("Hangs", _hangs)()
    with pytest.raises(ConformanceError, match=r"kit.hangs: the untimed warm-up plan\(\) on grid2d with "
                                               r"Budget\(.*\) had not returned after 0.3 s; its process was killed"):
        C.check_solves(planner, kind="grid2d")
    with pytest.raises(C.CheckTimeout, match=r"kit.hangs: not run: an earlier call timed out"):
        C.check_unreachable_goal(planner, kind="grid2d")


def test_a_check_that_outlives_its_limit_is_killed(monkeypatch):
    planner = _variant("HangsAfterWarmUp", _hangs)()
    monkeypatch.setattr(C, "CHECK_LIMIT_S", 0.3)
    monkeypatch.setattr(C, "is_warm", lambda planner, kind: True)  # as if warmed up: the check itself hangs
    with pytest.raises(ConformanceError, match=r"kit.hangsafterwarmup: check_solves had not returned after 0.3 s"):
        C.check_solves(planner, kind="grid2d")


def test_use_of_the_global_random_generator_is_reported():
    planner = _variant("GlobalTieBreak", _tie_break_with_global_random)()
    C.check_same_seed_same_path(planner, kind="grid2d")  # the path does not show it
    with pytest.raises(ConformanceError, match=r"kit.globaltiebreak: plan\(\) drew from the global generator\(s\) "
                                               r"random on testing.grid2d; draw from the rng argument"):
        C.check_leaves_global_rng_alone(planner, kind="grid2d")
    with pytest.raises(ConformanceError, match="check_leaves_global_rng_alone"):
        check_planner(planner)


def test_check_planner_reports_every_failed_check():
    with pytest.raises(ConformanceError) as info:
        check_planner(_variant("Straight2", _straight)())
    text = str(info.value)
    assert text.startswith("kit.straight2 failed")
    assert "check_solves[grid2d]" in text and "check_solves[air3d]" in text
    assert "check_unreachable_goal[terrain]" in text


def test_as_planner_rejects_other_objects():
    with pytest.raises(pathzoo.InvalidParameterError, match="expected a planner id"):
        check_planner(42)  # type: ignore[arg-type]


def test_picklable_check_compares_the_unpickled_result():
    planner = Shortest(rounds=2)
    C.check_picklable(planner)
    assert pickle.loads(pickle.dumps(planner)).get_params() == {"rounds": 2, "mode": "a"}
