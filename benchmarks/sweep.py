"""Issue 38's sweep figure: runs per second over many distinct problems against the same number of runs on two.

Run from the repository root::

    python benchmarks/sweep.py               # 200 problems, --jobs 2, sandboxed where the system can
    python benchmarks/sweep.py --problems 50 # a shorter sweep

Both experiments run ``exact.astar`` and ``aco.as`` (a budget of 3 iterations: a
clock-only budget would make the colony search until its clock) with the
same number of runs, through :func:`pathzoo.harness.run_experiment` and the
process executor (``--jobs``): the *sweep* on ``--problems`` distinct
MovingAI problems of one map with one seed each, the *reference* on two of
those problems with ``--problems / 2`` seeds each, timed in the same run.
Throughput is stored runs per wall second from the first stored run to the
last (start-up excluded). The target (issue 38, "Done when"): the sweep
runs at >= 0.8x the reference's runs per second.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

MAP = "movingai.random-32-32-20.*"
"""The MovingAI problems the sweep draws from (409 problems of one 32x32 map)."""
PLANNERS = ["exact.astar", "aco.as"]
TARGET = 0.8


def stored_rate(scenarios: list[str], seeds: int, jobs: int, db: Path) -> float:
    """Stored runs per wall second, from the first stored run to the last."""
    stamps = stored_stamps(scenarios, seeds, jobs, db)
    return (len(stamps) - 1) / (stamps[-1] - stamps[0])


def stored_stamps(scenarios: list[str], seeds: int, jobs: int, db: Path) -> list[float]:
    """The ``time.perf_counter`` of each run's storing, in order, for the sweep's planners on ``scenarios``."""
    import pathzoo
    from pathzoo import Budget
    from pathzoo.harness import Experiment, run_experiment
    from pathzoo.plugins.manager import get_registry

    stamps: list[float] = []

    class Marks:
        @pathzoo.hookimpl
        def pathzoo_run_finished(self, record: object) -> None:
            stamps.append(time.perf_counter())

    registry = get_registry()
    marks = Marks()
    registry.add_plugin(marks, f"sweep-marks-{db.stem}")
    try:
        exp = Experiment.build(name=db.stem, planners=PLANNERS, scenarios=scenarios, seeds=seeds,
                               budget=Budget(iterations=3, time_s=30.0))
        runs = run_experiment(exp, db=db, jobs=jobs, progress=False)
    finally:
        registry.pm.unregister(marks)
    if len(runs) < 2 or len(stamps) < 2:
        raise SystemExit(f"sweep: only {len(runs)} runs stored")
    return stamps


def problem_ids(problems: int) -> list[str]:
    """The first ``problems`` scenario ids of :data:`MAP`, in sorted order."""
    from pathzoo.plugins.manager import get_registry

    return sorted(get_registry().match("scenarios", MAP))[:problems]


def figures(problems: int = 200, jobs: int = 2) -> list[tuple[str, float, float]]:
    """``[(name, value, target)]``: the sweep's runs per second as a ratio to the reference's (target 0.8)."""
    chosen = problem_ids(problems)
    with tempfile.TemporaryDirectory(prefix="pathzoo-sweep-") as tmp:
        reference = stored_rate(chosen[:2], problems // 2, jobs, Path(tmp) / "two.sqlite")
        sweep = stored_rate(chosen, 1, jobs, Path(tmp) / "many.sqlite")
    return [(f"runs/s over {problems} problems / over 2 ({sweep:.1f} / {reference:.1f}, --jobs {jobs})",
             sweep / reference, TARGET)]


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--problems", type=int, default=200, help="distinct problems in the sweep (default 200)")
    parser.add_argument("--jobs", type=int, default=2, help="worker processes (default 2)")
    args = parser.parse_args()
    for name, value, target in figures(args.problems, args.jobs):
        print(f"| {name} | {value:.2f}x | >= {target:g}x | {'met' if value >= target else 'NOT met'} |")


if __name__ == "__main__":
    main()
