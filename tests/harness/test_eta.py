"""The progress bar's time left: a cost model calibrated by the clock, after a pilot of every scenario and planner.

The end-to-end tests replay an experiment on a simulated clock: two workers
take the runs in the harness's order, each run costing a fixed overhead plus
its planning time, after a start-up delay. The planning times are either the
bundled default experiment's, as measured on a 2-core machine
(``default_run_times.csv``), or drawn from a planner x scenario model.
"""

from __future__ import annotations

import csv
from importlib import resources
from pathlib import Path

import numpy as np
import pytest

from pathzoo.harness.eta import PILOT_FRACTION, RunTimes, pilot_first

MEASURED = Path(__file__).with_name("default_run_times.csv")


class Clock:
    def __init__(self) -> None:
        self.now = 0.0

    def __call__(self) -> float:
        return self.now


def replay(order, plan_s, *, overhead_s, startup_s, workers=2):
    """``(fraction done, estimate, truth)`` after every finished run of ``order`` (``(planner, scenario, seed)``)."""
    tasks = pilot_first(order, lambda t: (t[0], t[1]))
    free = [startup_s] * workers
    finished = []
    for task in tasks:  # each run goes to the first free worker, as the executors do
        start = min(free)
        free.remove(start)
        end = start + overhead_s + plan_s[task]
        free.append(end)
        finished.append((end, task))
    finished.sort()
    total = finished[-1][0]
    clock = Clock()
    times = RunTimes(parallel=workers, clock=clock)
    out = []
    for k, (end, task) in enumerate(finished):
        clock.now = end
        times.add(task[0], task[1], plan_s[task])
        estimate = times.eta([(t[0], t[1]) for _, t in finished[k + 1:]])
        out.append(((k + 1) / len(finished), estimate, total - end))
    return out


def worst_ratio(trace, start=0.1, stop=0.9):
    """Largest factor between estimate and truth from ``start`` to ``stop`` of the runs done."""
    return max(max(e / t, t / e) for done, e, t in trace if start <= done <= stop)


def default_order():
    """The bundled default experiment's runs, in the harness's order."""
    from pathzoo.harness.experiment import Experiment

    with resources.as_file(resources.files("pathzoo.experiments") / "default.toml") as path:
        exp = Experiment.from_toml(path)
    return [(t.planner.name, t.scenario.id, t.seed_index) for t in exp.tasks()]


def measured_plan_s():
    with MEASURED.open() as fh:
        return {(r["planner"], r["scenario"], int(r["seed_index"])): float(r["plan_s"]) for r in csv.DictReader(fh)}


@pytest.mark.parametrize(("overhead_s", "startup_s"), [(0.05, 5.0), (0.3, 40.0), (1.0, 10.0)])
def test_default_experiment_estimate_is_within_2x_from_a_tenth_of_the_runs(overhead_s, startup_s):
    """The newcomer's bar showed 0m01s left with minutes to go: planning times alone, one scenario seen."""
    plan_s = measured_plan_s()
    order = default_order()
    assert set(order) == set(plan_s)  # the measurements cover the bundled experiment as it is
    trace = replay(order, plan_s, overhead_s=overhead_s, startup_s=startup_s)
    assert worst_ratio(trace) <= 2.0


@pytest.mark.parametrize("seed", range(5))
def test_estimate_of_a_planner_times_scenario_cost_model_is_within_2x_from_a_fifth_of_the_runs(seed):
    """Before that, the heaviest pilot runs may still be running: a model learns nothing from a run in flight."""
    rng = np.random.default_rng(seed)
    planner = np.exp(rng.uniform(np.log(1e-3), np.log(2.0), 10))  # planners over three decades
    scenario = np.exp(rng.uniform(0.0, np.log(50.0), 6))
    plan_s = {(f"p{p}", f"s{s}", i): planner[p] * scenario[s] * np.exp(rng.normal(0.0, 0.2))
              for s in range(6) for p in range(10) for i in range(5)}
    order = sorted(plan_s, key=lambda t: (t[1], t[0], t[2]))  # scenario by scenario, as experiments run
    assert worst_ratio(replay(order, plan_s, overhead_s=0.1, startup_s=20.0), start=0.2) <= 2.0


def test_no_estimate_before_two_runs_have_finished():
    clock = Clock()
    times = RunTimes(parallel=2, clock=clock)
    assert times.eta([("a", "x")]) is None
    times.add("a", "x", 1.0)
    assert times.eta([("a", "x")]) is None  # the first run carries the start-up: nothing to time yet
    clock.now = 2.0
    times.add("a", "x", 1.0)
    assert times.eta([("a", "x")] * 4) == pytest.approx(4 * (1.0 + 3.0) / 2)  # 2 s x 2 workers, 1 s planned
    assert times.eta([]) == 0.0


def test_overhead_is_what_the_clock_shows_beyond_planning():
    clock = Clock()
    times = RunTimes(parallel=1, clock=clock)
    times.add("a", "x", 0.5)
    for _ in range(4):
        clock.now += 0.75
        times.add("a", "x", 0.5)
    assert times.overhead_s() == pytest.approx(0.25)


def test_an_unseen_pair_costs_its_planner_and_scenario_effects():
    times = RunTimes(clock=Clock())
    for planner, scenario, seconds in [("fast", "small", 0.01), ("fast", "big", 1.0), ("slow", "small", 0.1)]:
        times.add(planner, scenario, seconds)
    predicted = times.predicted_plan_s([("slow", "big"), ("fast", "big")])
    assert predicted[("slow", "big")] == pytest.approx(10.0, rel=1e-6)  # 10x slower, on a 100x bigger scenario
    assert predicted[("fast", "big")] == 1.0  # a seen pair costs its own mean


def test_pilot_spreads_over_every_scenario_and_keeps_the_rest_in_order():
    order = [(p, s, i) for s in "ABCDE" for p in "pqrstuvw" for i in range(5)]  # 200 runs
    tasks = pilot_first(order, lambda t: (t[0], t[1]))
    k = next(i for i in range(len(tasks)) if tasks[i:] == [t for t in order if t not in tasks[:i]])
    pilot, rest = tasks[:k], tasks[k:]
    assert k >= PILOT_FRACTION * len(order) and len(set(pilot)) == k
    assert sorted(tasks) == sorted(order)
    assert {s for _, s, _ in pilot} == set("ABCDE") and {p for p, _, _ in pilot} == set("pqrstuvw")
    assert [s for _, s, _ in pilot] == sorted(s for _, s, _ in pilot)  # scenario by scenario: one load each
    assert rest == [t for t in order if t not in pilot]


def test_after_the_pilot_the_overhead_comes_from_the_later_runs_alone():
    """Pilot runs each meet a new pair (a sandboxed worker, a warm-up); the runs after it repeat pairs, cheaply."""
    clock = Clock()
    times = RunTimes(parallel=1, clock=clock)
    for k in range(6):  # the pilot: six new pairs, 5 s of overhead each beyond 1 s of planning
        clock.now += 6.0
        times.add(f"p{k}", "s", 1.0)
    assert times.overhead_s() == pytest.approx(5.0)
    for k in range(4):  # repeats: 0.5 s of overhead beyond 1 s of planning
        clock.now += 1.5
        times.add(f"p{k}", "s", 1.0)
    assert times.overhead_s() == pytest.approx(0.5)
