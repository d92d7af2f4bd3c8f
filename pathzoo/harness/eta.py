"""Time left in an experiment: a cost model of the runs, calibrated by the harness's own clock.

Planners and scenarios differ by orders of magnitude in planning time, and a
run costs more than its planning time (loading the scenario, judging,
storing). The estimate of :meth:`RunTimes.eta` has three parts:

1. the planning time of a remaining run of planner ``p`` on scenario ``s`` is
   ``exp(a_p + b_s)``, the two effects fitted by least squares to the log
   planning times of the finished runs (a planner or scenario not seen yet
   gets the mean effect);
2. the overhead of a run is what the harness's clock shows beyond the
   planning times: ``(parallel x elapsed - sum of planning times) / runs``,
   over the runs finished after the pilot once there are a few of them,
   else since the first run finished (the start-up before it, workers
   starting and compiling, is paid once). Pilot runs are costlier than the
   rest: each meets a new planner and scenario (a sandboxed worker of its
   own configuration, a warm-up), where most later runs repeat a pair;
3. the time left is the sum over the remaining runs of overhead plus
   predicted planning time, divided by the runs executing at once.

The model can only know scenarios and planners it has seen, so the harness
runs a pilot first (:func:`pilot_first`): about 7 % of the runs,
spread over every scenario and planner, before the rest in their usual order.
"""

from __future__ import annotations

import math
import time
from collections import Counter, defaultdict
from dataclasses import dataclass, field
from typing import Callable, Hashable, Iterable, Mapping, Sequence, TypeVar

__all__ = ["RunTimes", "pilot_first", "PILOT_FRACTION"]

PILOT_FRACTION = 0.07
"""Share of an experiment's runs put first by :func:`pilot_first`."""

STEADY_RUNS = 1
"""Runs per executing slot that must finish after the pilot before their clock alone gives the overhead.

The pilot is over, for this count, once a run of a pair already seen has
finished: the pilot holds each (planner, scenario) pair once."""

_FLOOR_S = 1e-3
"""Planning times are floored at this before taking logs (exact planners on tiny maps report ~0)."""

Pair = tuple[str, str]
"""(planner label, scenario id) of one run."""

T = TypeVar("T")


@dataclass
class RunTimes:
    """Finished runs of one experiment, as the progress bar's estimate needs them.

    Parameters
    ----------
    parallel : int
        Runs executing at once (the executor's capacity).
    clock : callable
        Seconds of a monotonic clock (:func:`time.monotonic`; tests pass their own).
    """

    parallel: int = 1
    clock: Callable[[], float] = time.monotonic
    plan_s: dict[Pair, list[float]] = field(default_factory=lambda: defaultdict(list))
    first_finished: float | None = None
    finished_after_first: int = 0
    plan_s_after_first: float = 0.0
    pilot_finished: float | None = None
    finished_after_pilot: int = 0
    plan_s_after_pilot: float = 0.0

    def add(self, planner: str, scenario: str, plan_s: float) -> None:
        """Record a run of ``planner`` on ``scenario`` that finished now, having planned for ``plan_s`` seconds."""
        seconds = max(float(plan_s), 0.0) if math.isfinite(plan_s) else 0.0
        repeat = (planner, scenario) in self.plan_s
        self.plan_s[(planner, scenario)].append(seconds)
        now = self.clock()
        if self.first_finished is None:
            self.first_finished = now
        else:
            self.finished_after_first += 1
            self.plan_s_after_first += seconds
        if self.pilot_finished is not None:
            self.finished_after_pilot += 1
            self.plan_s_after_pilot += seconds
        elif repeat:  # the pilot runs each pair once: the first repeated pair starts the steady state
            self.pilot_finished = now

    @property
    def count(self) -> int:
        """Runs recorded."""
        return sum(len(v) for v in self.plan_s.values())

    def overhead_s(self) -> float:
        """Seconds a run costs beyond its planning time, from the clock since the pilot (else the first run) ended."""
        slots = max(int(self.parallel), 1)
        if self.pilot_finished is not None and self.finished_after_pilot >= STEADY_RUNS * slots:
            since, runs, planned = self.pilot_finished, self.finished_after_pilot, self.plan_s_after_pilot
        elif self.first_finished is not None and self.finished_after_first > 0:
            since, runs, planned = self.first_finished, self.finished_after_first, self.plan_s_after_first
        else:
            return 0.0
        return max(slots * (self.clock() - since) - planned, 0.0) / runs

    def effects(self) -> tuple[dict[str, float], dict[str, float], float]:
        """``(planner effects, scenario effects, mean)`` of the log planning time, fitted by alternating means."""
        logs = {pair: math.log(max(sum(v) / len(v), _FLOOR_S)) for pair, v in self.plan_s.items()}
        mean = sum(logs.values()) / len(logs)
        planner: dict[str, float] = defaultdict(float)
        scenario: dict[str, float] = defaultdict(float)
        for _ in range(20):  # converges in a few sweeps on these small tables
            by_planner: dict[str, list[float]] = defaultdict(list)
            for (p, s), y in logs.items():
                by_planner[p].append(y - mean - scenario[s])
            planner = defaultdict(float, {p: sum(r) / len(r) for p, r in by_planner.items()})
            by_scenario: dict[str, list[float]] = defaultdict(list)
            for (p, s), y in logs.items():
                by_scenario[s].append(y - mean - planner[p])
            scenario = defaultdict(float, {s: sum(r) / len(r) for s, r in by_scenario.items()})
        return dict(planner), dict(scenario), mean

    def predicted_plan_s(self, remaining: Iterable[Pair]) -> dict[Pair, float]:
        """The predicted planning time of one run of each pair in ``remaining`` (a seen pair costs its own mean)."""
        planner, scenario, mean = self.effects()
        out: dict[Pair, float] = {}
        for pair in set(remaining):
            seen = self.plan_s.get(pair)
            p, s = pair
            out[pair] = sum(seen) / len(seen) if seen else math.exp(mean + planner.get(p, 0.0) + scenario.get(s, 0.0))
        return out

    def eta(self, remaining: "Mapping[Pair, int] | Iterable[Pair]") -> float | None:
        """Estimated seconds until the ``remaining`` runs are done (pairs, or a count per pair); None until two runs
        have finished. Its cost grows with the pairs seen and left, not with the runs."""
        if self.finished_after_first == 0:
            return None
        counts = ({pair: n for pair, n in remaining.items() if n > 0} if isinstance(remaining, Mapping)
                  else Counter(remaining))
        if not counts:
            return 0.0
        overhead = self.overhead_s()
        each = {pair: overhead + t for pair, t in self.predicted_plan_s(counts).items()}
        work = sum(n * each[pair] for pair, n in counts.items())
        return work / max(int(self.parallel), 1)


def pilot_first(items: Sequence[T], pair: Callable[[T], tuple[Hashable, Hashable]],
                fraction: float = PILOT_FRACTION) -> list[T]:
    """``items`` with a pilot of about ``fraction`` of them first, then the others in their order.

    The pilot takes, scenario by scenario (so each worker loads each scenario
    once), the first run of planners in rotation, so that it holds every
    scenario and as many planners as it can: what :meth:`RunTimes.eta` needs
    to cost the rest. ``pair(item)`` is ``(planner, scenario)``.
    """
    n_pilot = math.ceil(fraction * len(items))
    if n_pilot == 0:
        return list(items)
    firsts: dict[Hashable, dict[Hashable, int]] = defaultdict(dict)  # scenario -> planner -> first index
    for i, item in enumerate(items):
        planner, scenario = pair(item)
        firsts[scenario].setdefault(planner, i)
    per_scenario = math.ceil(n_pilot / len(firsts))
    planners = list(dict.fromkeys(pair(item)[0] for item in items))
    chosen: list[int] = []
    turn = 0
    for scenario, by_planner in firsts.items():
        order = sorted(by_planner, key=lambda p: (planners.index(p) - turn) % len(planners))
        picked = order[:per_scenario]
        chosen.extend(by_planner[p] for p in picked)
        turn += len(picked)
    pilot = set(chosen)
    return [items[i] for i in chosen] + [item for i, item in enumerate(items) if i not in pilot]
