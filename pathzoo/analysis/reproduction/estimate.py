"""The expected CPU time of a paper's full rerun, from a short pilot (``pathzoo reproduce PAPER --estimate``).

The pilot runs every available planner :data:`PILOT_SEEDS` times (seed
indices 0 and 1) on every chosen scenario with the iteration count capped at
:data:`PILOT_ITERATIONS` ``[0]``, then runs the planners whose pilot runs
were ended by that cap once again at the
next cap, and the next, until each of its runs took at least
:data:`PILOT_GROWTH` times the CPU of its first run (or ended before its
cap): a planner whose iterations are cheap beside its set-up climbs the
ladder, one whose iterations are dear stops at the second cap, so the pilot
stays short. From the CPU seconds the harness measured for the first and the
last of these runs it fits
``cpu = fixed + per_iteration x iterations`` per planner and scenario (the
fixed part: building graphs and tables; both parts clipped at zero), and
evaluates it at the iterations the full run would make:
the smallest of the planner's ``iterations`` parameter (its default filled
in), the paper's iteration budget and ``--iterations``. A planner whose pilot
run ended by itself (an exact search, a converged colony), or that made no
more iterations at the higher cap, is not iterative at this budget: its
pilot run is its full run. Each scenario's figure is then
multiplied by the rerun's seed count.

A worker charges the loading of a scenario (its shared geometry included)
to its first run there (``docs/timing.md``), which a rerun pays once per
worker and scenario, not once per seed. The two runs at the first cap
measure it: the dearer one's CPU beyond the cheaper one's is the set-up
(:func:`setup_cpu`). The fit goes through the dearer run and the higher
cap's (a fresh worker's first run, which carries the load too), and each
scenario's figure is the set-up once plus the seeds times the fitted run
less the set-up. Where both runs carried a load (two workers of one
configuration) the set-up reads as zero and the load is counted with every
seed, as an upper bound.

The figure is an estimate of this machine under its present load: a run
that converges early, or whose iterations grow dearer as its search narrows,
costs less or more. The pilot's runs go to a temporary database, never to
the rerun's.
"""

from __future__ import annotations

import math
import tempfile
from dataclasses import dataclass, replace
from pathlib import Path

import pandas as pd

from pathzoo.analysis.formatting import format_number, render_table
from pathzoo.analysis.reproduction.paper_data import PaperData, PaperPlanner
from pathzoo.analysis.reproduction.runs import (
    RerunOptions,
    experiment_name,
    paper_budget,
    planner_groups,
    planner_status,
    run_labelled,
    selected_scenarios,
)

__all__ = ["PILOT_ITERATIONS", "PILOT_GROWTH", "PILOT_SEEDS", "PlannerEstimate", "full_iterations", "fit_run",
           "setup_cpu", "rerun_cpu", "estimate_paper", "format_estimate"]

PILOT_ITERATIONS = (1, 3, 10, 30, 100)
"""The pilot's iteration caps, tried in turn until a planner's higher run is dear enough to fit (:data:`PILOT_GROWTH`)."""

PILOT_GROWTH = 2.0
"""The pilot stops raising a planner's cap once its run there took this many times the CPU of its first run."""

PILOT_SEEDS = 2
"""Runs per planner and scenario at the first cap: a worker's first run there carries the scenario's load."""


@dataclass(frozen=True)
class PlannerEstimate:
    """One planner's share of a full rerun.

    Attributes
    ----------
    planner : str
        The paper's key of the planner.
    label : str
        The paper's label of the planner.
    runs : int
        Runs of the full rerun (seeds x scenarios).
    iterations : int or None
        Iterations per run of the full rerun; None when the pilot's runs
        ended by themselves (not iterative at this budget).
    pilot_cpu_s : float
        CPU seconds of its pilot runs.
    cpu_s : float
        Expected CPU seconds of its runs in the full rerun.
    """

    planner: str
    label: str
    runs: int
    iterations: int | None
    pilot_cpu_s: float
    cpu_s: float


def full_iterations(paper: PaperData, planner: PaperPlanner, cap: int | None) -> int | None:
    """Iterations of one run of ``planner`` in the full rerun, or None when nothing limits them.

    The smallest of the planner's ``iterations`` parameter (its default filled
    in, when it declares one), the paper's iteration budget and ``cap``.
    """
    from pathzoo.harness.planner_info import info_of

    limits = [int(v) for v in (paper.budget.get("iterations"), cap) if v is not None]
    own = info_of(planner.id, dict(planner.params)).params.get("iterations")
    if isinstance(own, int) and not isinstance(own, bool):
        limits.append(own)
    return min(limits) if limits else None


def fit_run(low: tuple[float, float], high: tuple[float, float] | None, iterations: int | None) -> float:
    """Expected CPU seconds of one full run from the pilot's ``(iterations done, CPU s)`` at its two caps.

    The low run is the full run when the planner is not iterative at this
    budget: ``high`` or ``iterations`` is None, or the high run made no more
    iterations than the low one (an exact search counts one). Otherwise the
    line through the two points, its slope and intercept clipped at zero, is
    read at ``iterations``.
    """
    it_low, cpu_low = low
    if high is None or iterations is None or high[0] <= it_low:
        return cpu_low
    it_high, cpu_high = high
    slope = max(0.0, (cpu_high - cpu_low) / (it_high - it_low))
    fixed = max(0.0, cpu_low - slope * it_low)
    return fixed + slope * iterations


def setup_cpu(cpus: list[float]) -> float:
    """The set-up CPU seconds a worker pays once, from the runs of one planner on one scenario at the first cap.

    The cheapest run is a run without the scenario's load; the set-up is
    what the dearest took beyond it (zero from a single run; NaN when a run
    has no CPU time).
    """
    if any(math.isnan(c) for c in cpus):
        return math.nan
    return max(cpus) - min(cpus)


def rerun_cpu(low: tuple[float, float], high: tuple[float, float] | None, iterations: int | None, setup: float,
              seeds: int) -> float:
    """Expected CPU seconds of ``seeds`` full runs on one scenario: ``setup`` once, and the fitted run less it per seed.

    ``low`` is the pilot's first-cap run that carried the load and ``high``
    its run at the higher cap (see :func:`fit_run`).
    """
    return setup + (fit_run(low, high, iterations) - setup) * seeds


def _resolved(low: tuple[float, float], high: tuple[float, float] | None, cap: int) -> bool:
    """Whether a scenario's pilot runs fit a line: the higher run ended early, or cost :data:`PILOT_GROWTH` x the first."""
    return high is None or high[0] <= low[0] or high[0] < cap or high[1] >= PILOT_GROWTH * low[1]


def _points(runs: pd.DataFrame, capped_only: bool = False) -> dict[tuple[str, str], list[tuple[float, float]]]:
    """Per (planner key, scenario): (iterations done, CPU s) of the pilot runs there (only runs their cap ended)."""
    out: dict[tuple[str, str], list[tuple[float, float]]] = {}
    for planner, scenario, its, cpu, stop in zip(runs["planner"], runs["scenario"], runs["iterations"],
                                                 runs["cpu_time_s"], runs["stopped_by"]):
        if capped_only and stop != "iterations":
            continue
        its = float(its) if pd.notna(its) else 0.0
        out.setdefault((str(planner), str(scenario)), []).append((its, float(cpu) if pd.notna(cpu) else math.nan))
    return out


def estimate_paper(paper: PaperData, options: RerunOptions) -> tuple[list[PlannerEstimate], float]:
    """Run the pilot and estimate the CPU seconds of the full rerun ``options`` describes, per planner.

    ``options.seeds`` (default: the paper's run count), ``iterations`` and
    ``scenarios`` describe the full rerun; ``jobs``, ``executor`` and
    ``progress`` are the pilot's. Returns the estimates (planners in the
    paper's order) and the CPU seconds the pilot itself took.
    """
    from pathzoo.core.budget import Budget
    from pathzoo.harness.experiment import Experiment

    seeds = options.seeds if options.seeds is not None else paper.runs
    ids = list(selected_scenarios(paper, options.scenarios).values())
    low_cap = PILOT_ITERATIONS[0]
    with tempfile.TemporaryDirectory(prefix="pathzoo-estimate-") as tmp:
        pilot = replace(options, db=Path(tmp) / "pilot.sqlite", seeds=1)

        def run_level(cap: int, keys: set[str] | None, n_seeds: int = 1) -> pd.DataFrame:
            groups = planner_groups(paper, cap, keys=lambda p: keys is None or p.key in keys)
            frames = [run_labelled(paper, Experiment.build(
                planners=specs, scenarios=[sid + variant for sid in ids], seeds=n_seeds,
                budget=Budget(**paper_budget(paper, cap)),
                name=experiment_name(paper, n_seeds, cap) + variant.replace("_", ".") + ".pilot", db=pilot.db), pilot)
                for variant, specs in sorted(groups.items())]
            return pd.concat(frames, ignore_index=True)

        runs = [run_level(low_cap, None, PILOT_SEEDS)]
        low: dict[tuple[str, str], tuple[float, float]] = {}
        setup: dict[tuple[str, str], float] = {}
        for key, points in _points(runs[0]).items():
            setup[key] = setup_cpu([c for _, c in points])
            low[key] = max(points, key=lambda point: point[1])  # the run that carried the load
        capped_low = _points(runs[0], capped_only=True)
        high: dict[tuple[str, str], tuple[float, float]] = {}
        full = {p.key: full_iterations(paper, p, options.iterations) for p in paper.planners
                if any(k[0] == p.key for k in capped_low)}
        pending = set(full)
        for cap in PILOT_ITERATIONS[1:]:
            pending = {key for key in pending if (full[key] or cap) >= cap}  # None: nothing caps it
            if not pending:
                break
            runs.append(run_level(cap, pending))
            high.update({k: v[0] for k, v in _points(runs[-1]).items() if k in capped_low})
            pending = {key for key in pending
                       if not all(_resolved(low[k], high.get(k), cap) for k in capped_low if k[0] == key)}
    every = pd.concat(runs, ignore_index=True)
    pilot_cpu = float(pd.to_numeric(every["cpu_time_s"], errors="coerce").sum())
    estimates = []
    for p in paper.planners:
        if planner_status(p):
            continue
        cells = [(low[k], high.get(k), setup[k]) for k in low if k[0] == p.key]
        grows = any(hi is not None and hi[0] > lo[0] for lo, hi, _ in cells)
        iters = full[p.key] if grows else None  # grows: a higher run was fitted, so its cap ended the first one
        cpu = sum(rerun_cpu(lo, hi, iters, once, seeds) for lo, hi, once in cells)
        mine = every.loc[every["planner"] == p.key, "cpu_time_s"]
        estimates.append(PlannerEstimate(p.key, p.label, seeds * len(cells), iters,
                                         float(pd.to_numeric(mine, errors="coerce").sum()), cpu))
    return estimates, pilot_cpu


def format_estimate(paper: PaperData, estimates: list[PlannerEstimate], pilot_cpu_s: float, seeds: int) -> str:
    """The estimate as a text table: per planner its runs, iterations per run, pilot and expected CPU, and the total."""
    total = sum(e.cpu_s for e in estimates)
    display = pd.DataFrame({
        "planner": [f"{e.label} ({paper.planner(e.planner).id})" for e in estimates] + ["total"],
        "runs": [str(e.runs) for e in estimates] + [str(sum(e.runs for e in estimates))],
        "iterations per run": [("ends by itself" if e.iterations is None else str(e.iterations)) for e in estimates]
        + [""],
        "pilot CPU s": [format_number(e.pilot_cpu_s, 3) for e in estimates] + [format_number(pilot_cpu_s, 3)],
        "expected CPU-hours": [format_number(e.cpu_s / 3600.0, 3) for e in estimates]
        + [format_number(total / 3600.0, 3)],
    })
    notes = [
        f"Pilot: {PILOT_SEEDS} runs per planner and scenario at {PILOT_ITERATIONS[0]} iteration, and 1 again at "
        f"{', '.join(map(str, PILOT_ITERATIONS[1:]))} in turn for the planners that iterate, until a run costs "
        f"{PILOT_GROWTH:g}x the first; CPU = fixed + per iteration x iterations through the first and last, "
        f"times {seeds} run(s) per planner and scenario (the paper: {paper.runs}), the scenario's load (the dearer "
        "first-cap run's CPU beyond the cheaper one's) counted once.",
        "An estimate on this machine under its present load: runs that converge early cost less.",
    ]
    return render_table(display, "text", title=f"Expected CPU time of the full rerun: {paper.title}, {paper.table}",
                        notes=notes, left=("planner",))
