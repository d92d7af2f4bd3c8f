"""aco.dsaco's compiled colony: the same answers as the generic colony loop, and its move table."""

from __future__ import annotations

import numpy as np
import pytest

import pathzoo
from pathzoo import Budget, Scenario, VehicleModel
from pathzoo_aco.dsaco_tables import MoveTable, build_list
from pathzoo_aco.engine import AntColonyPlanner, ColonyProblem, WalkEngine


def _grid(turn_deg: float = 180.0, wall: bool = False) -> Scenario:
    """A 12 x 12 grid with a few blocks; ``wall`` cuts the goal off completely."""
    occ = np.zeros((12, 12), dtype=bool)
    occ[3:9, 5] = True
    occ[6, 2:5] = True
    if wall:
        occ[:, 8] = True
    return Scenario(id="grid12", kind="grid2d", occupancy=occ, cell_size=1.0, start=(0.5, 0.5), goal=(11.5, 10.5),
                    vehicle=VehicleModel(max_turn_deg=turn_deg))


def _both(planner, scenario, budget):
    """(compiled run, generic run, their progress reports, the rng states after each)."""
    reports = ([], [])
    results, states = [], []
    for k, plan in enumerate((planner.plan, lambda *a, **kw: AntColonyPlanner.plan(planner, *a, **kw))):
        rng = np.random.default_rng(11)
        results.append(plan(scenario, budget=budget, rng=rng, progress=lambda *r, k=k: reports[k].append(r)))
        states.append(rng.bit_generator.state)
    return results, reports, states


def _same(a, b):
    assert (a.status, a.iterations, a.evaluations, a.message) == (b.status, b.iterations, b.evaluations, b.message)
    assert a.extras["ant_steps"] == b.extras["ant_steps"]
    if a.solved:
        np.testing.assert_array_equal(a.path, b.path)


@pytest.mark.parametrize(("scenario_id", "params", "budget"), [
    ("dsaco.simple", {}, Budget(iterations=12)),
    ("dsaco.simple", {"step_rule": "longitude", "n_ants": 4}, Budget(iterations=15)),
    ("dsaco.simple", {"alpha": 1.5, "q0_initial": 0.0, "rho": 0.9}, Budget(iterations=8)),
    ("dsaco.simple", {"dead_end": "die", "max_steps": 40}, Budget(iterations=6)),
    ("dsaco.simple", {"n_ants": 3}, Budget(evaluations=8)),  # the last iteration sends 2 ants
    ("dsaco.simple", {"step_rule": "longitude", "l_max": 70.0}, Budget(iterations=8)),  # eq. 2, solved
    ("dsaco.simple", {"step_rule": "longitude", "l_min": 1.01}, Budget(iterations=8)),  # eq. 3, nothing feasible
    ("grid12", {"n_ants": 4}, Budget(iterations=10)),
    ("grid12-turn", {"n_ants": 4}, Budget(iterations=10)),
    ("grid12-wall", {"n_ants": 4}, Budget(iterations=10)),  # an ant proves the goal unreachable: early stop
    ("grid12-wall", {"n_ants": 4, "dead_end": "die"}, Budget(iterations=3)),
    ("grid12", {"n_ants": 30, "alpha": 1.5}, Budget(iterations=10)),  # lists read in place; 300 walks: stamps wrap
    ("grid12", {"n_ants": 3, "rho": 0.9}, Budget(iterations=20)),  # deposited, even and floored trails side by side
    ("grid12-turn", {"n_ants": 30, "alpha": 0.5, "rho": 0.5}, Budget(iterations=10)),  # the same through records
])
def test_compiled_colony_equals_the_generic_loop(scenario_id, params, budget):
    scenario = {"grid12": lambda: _grid(), "grid12-turn": lambda: _grid(turn_deg=45.0),
                "grid12-wall": lambda: _grid(wall=True)}.get(scenario_id, lambda: pathzoo.load_scenario(scenario_id))()
    planner = pathzoo.make_planner("aco.dsaco", **params)
    (fast, slow), (fast_reports, slow_reports), (fast_rng, slow_rng) = _both(planner, scenario, budget)
    _same(fast, slow)
    assert fast_reports == slow_reports and len(fast_reports) == fast.iterations
    assert fast_rng == slow_rng  # the planner's rng is left where the generic loop leaves it
    if scenario_id == "grid12-wall" and params.get("dead_end") != "die":
        assert fast.iterations == 1 and "unreachable" in fast.message


@pytest.mark.parametrize("with_progress", [False, True])
def test_schedules_computed_in_chunks_give_the_same_answer(monkeypatch, with_progress):
    import pathzoo_aco.dsaco as dsaco

    monkeypatch.setattr(dsaco, "_SCHEDULE_CHUNK", 3)
    planner = pathzoo.make_planner("aco.dsaco", n_ants=4)
    for scenario, budget in ((_grid(turn_deg=45.0), Budget(evaluations=30)), (_grid(wall=True), Budget(iterations=8))):
        runs = []
        for plan in (planner.plan, lambda *a, **kw: AntColonyPlanner.plan(planner, *a, **kw)):
            rng = np.random.default_rng(5)
            reports = []
            report = (lambda *r: reports.append(r)) if with_progress else None
            runs.append((plan(scenario, budget=budget, rng=rng, progress=report), reports, rng.bit_generator.state))
        _same(runs[0][0], runs[1][0])
        assert runs[0][1:] == runs[1][1:]  # the same reports, the rng left in the same state


def test_a_huge_iteration_budget_with_few_evaluations_stays_small():
    result = pathzoo.make_planner("aco.dsaco", n_ants=4).plan(_grid(), budget=Budget(iterations=10**12, evaluations=10),
                                                              rng=np.random.default_rng(0))
    assert result.iterations == 3 and result.evaluations == 10


def test_without_progress_one_call_gives_the_same_answer():
    scenario = pathzoo.load_scenario("dsaco.simple")
    planner = pathzoo.make_planner("aco.dsaco", n_ants=5)
    a = planner.plan(scenario, budget=Budget(iterations=20), rng=np.random.default_rng(3))
    b = AntColonyPlanner.plan(planner, scenario, budget=Budget(iterations=20), rng=np.random.default_rng(3))
    _same(a, b)


class _StopAfter:
    """A clock stop (as the harness attaches) that reports the CPU limit spent from its ``n + 1``-th reading on."""

    def __init__(self, n: int) -> None:
        self.left = n

    def reason(self):
        self.left -= 1
        return "cpu_time" if self.left < 0 else None


def test_a_clock_limit_only_stops_the_compiled_colony_between_iterations():
    planner = pathzoo.make_planner("aco.dsaco", n_ants=4)
    timed = planner.plan(_grid(), budget=Budget(iterations=6, time_s=1e6, cpu_s=1e6), rng=np.random.default_rng(2))
    _same(timed, AntColonyPlanner.plan(planner, _grid(), budget=Budget(iterations=6), rng=np.random.default_rng(2)))
    runs = []
    for plan in (planner.plan, lambda *a, **kw: AntColonyPlanner.plan(planner, *a, **kw)):
        rng = np.random.default_rng(2)
        runs.append((plan(_grid(), budget=Budget(iterations=6, cpu_s=1.0, stop=_StopAfter(3)), rng=rng),
                     rng.bit_generator.state))
    assert runs[0][0].iterations == 3
    _same(runs[0][0], runs[1][0])
    assert runs[0][1] == runs[1][1]


def test_graded_turn_factors_take_the_generic_loop():
    import pathzoo_aco.dsaco as dsaco

    class Graded(type(pathzoo.make_planner("aco.dsaco"))):  # a turn table that weighs turns, not only forbids them
        def walk_rules(self, problem):
            rules = super().walk_rules(problem)
            return dsaco.replace(rules, turn=np.where(rules.turn > 0, 0.5, 0.0))

    result = Graded().plan(_grid(turn_deg=45.0), budget=Budget(iterations=2), rng=np.random.default_rng(0))
    assert result.solved


def test_move_table_lists_the_allowed_moves_in_their_original_order():
    scenario = pathzoo.load_scenario("dsaco.complex")
    problem = ColonyProblem(scenario)
    planner = pathzoo.make_planner("aco.dsaco", step_rule="longitude")
    rules = planner.walk_rules(problem)
    adjacency = WalkEngine(problem).adjacency(rules)
    table = MoveTable.of(adjacency, rules.turn)
    adj_ptr, adj_node, adj_edge, adj_offset, weight = adjacency[:5]
    assert adj_edge is not None and len(adj_edge) < problem.graph.n_edges  # the rule's refused moves are left out
    n_classes = len(table.class_row)
    for c in (problem.start, problem.start + 7, int(np.flatnonzero(np.diff(adj_ptr) > 0)[-1])):
        e0, e1 = adj_ptr[c], adj_ptr[c + 1]
        for prev in (len(rules.turn) - 1, int(adj_offset[e0])):
            wanted = [q for q in range(e0, e1) if rules.turn[prev, adj_offset[q]] > 0]
            k = table.move_class[prev]
            h = c * n_classes + k
            build_list(c, k, h, table.adj_ptr, table.node, table.weight, table.move, rules.turn, table.class_row,
                        table.head, table.to_rec, table.to_move, table.to_next, table.filled)
            first, length = table.head[h, 0], table.head[h, 1] - 1
            records = slice(first, first + length)
            assert length == len(wanted) and table.filled[0] >= first + length
            np.testing.assert_array_equal(table.to_rec["place"][records], wanted)
            np.testing.assert_array_equal(table.to_rec["node"][records], adj_node[wanted])
            np.testing.assert_array_equal(table.to_rec["weight"][records], weight[wanted])
            np.testing.assert_array_equal(table.to_move[records], adj_offset[wanted])
            np.testing.assert_array_equal(table.edge[table.to_rec["place"][records]], adj_edge[wanted])
    assert table.filled[0] <= len(table.to_rec)  # the records allocated hold every list there could be


def test_levels_that_do_not_fit_are_read_again_with_the_same_answer(monkeypatch):
    import pathzoo_aco.dsaco_tables as tables

    monkeypatch.setattr(tables, "_LEVEL_ROOM", 1)  # room for about one node's candidates: most levels are not kept
    for scenario, params in ((pathzoo.load_scenario("dsaco.simple"), {"step_rule": "longitude", "n_ants": 4}),
                             (_grid(turn_deg=45.0), {"n_ants": 4}), (_grid(wall=True), {"n_ants": 2})):
        planner = pathzoo.make_planner("aco.dsaco", **params)
        (fast, slow), _, (fast_rng, slow_rng) = _both(planner, scenario, Budget(iterations=6))
        _same(fast, slow)
        assert fast_rng == slow_rng


def test_every_list_fits_in_the_records_allocated():
    scenario = _grid(turn_deg=45.0)
    problem = ColonyProblem(scenario)
    rules = pathzoo.make_planner("aco.dsaco").walk_rules(problem)
    table = MoveTable.of(WalkEngine(problem).adjacency(rules), rules.turn)
    n_classes = len(table.class_row)
    for c in range(len(table.adj_ptr) - 1):
        for k in range(n_classes):
            build_list(c, k, c * n_classes + k, table.adj_ptr, table.node, table.weight, table.move, rules.turn,
                        table.class_row, table.head, table.to_rec, table.to_move, table.to_next, table.filled)
    assert table.filled[0] == len(table.to_rec)  # the bound is exact: every record written, none beyond


def test_without_the_records_links_the_answer_is_the_same(monkeypatch):
    import dataclasses

    import pathzoo_aco.dsaco as dsaco

    class Unlinked(MoveTable):  # as a table whose lists' places would not fit in to_next
        @classmethod
        def of(cls, adjacency, turn):
            return dataclasses.replace(MoveTable.of(adjacency, turn), to_next=np.zeros(0, dtype=np.int64))

    monkeypatch.setattr(dsaco, "MoveTable", Unlinked)
    planner = pathzoo.make_planner("aco.dsaco", step_rule="longitude", n_ants=4)
    (fast, slow), _, (fast_rng, slow_rng) = _both(planner, pathzoo.load_scenario("dsaco.simple"), Budget(iterations=6))
    _same(fast, slow)
    assert fast_rng == slow_rng


def test_byte_stamps_are_cleared_when_they_come_round_again(monkeypatch):
    import pathzoo_aco.dsaco as dsaco

    planner = pathzoo.make_planner("aco.dsaco", n_ants=4)
    fresh = planner.plan(_grid(), budget=Budget(iterations=3), rng=np.random.default_rng(4))
    start = dsaco.ColonyRun.start

    def worn(*args):  # a run whose first iteration's stamps would pass 255, every node stamped with the first reused
        run = start(*args)
        run.counters[5] = 254
        run.stamps[:] = 1
        return run

    monkeypatch.setattr(dsaco.ColonyRun, "start", worn)
    again = planner.plan(_grid(), budget=Budget(iterations=3), rng=np.random.default_rng(4))
    assert again.evaluations == fresh.evaluations and again.extras["ant_steps"] == fresh.extras["ant_steps"]
    np.testing.assert_array_equal(again.path, fresh.path)
