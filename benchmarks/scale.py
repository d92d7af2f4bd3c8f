"""Issue 38's "Done when" figures for a study on one machine, each printed beside its target.

Run from the repository root::

    python benchmarks/scale.py                      # every figure (1M-run database: a few minutes to build)
    python benchmarks/scale.py --only leaderboard   # one group: leaderboard, report, jobs, sweep
    python benchmarks/scale.py --large-runs 400000  # a smaller "large" database for a quick look

What it measures, each in the same run, as a ratio where the issue asks for one:

- **leaderboard memory**: peak RSS of ``pathzoo leaderboard DB`` (a child
  process, read with ``wait4``) on a synthetic database of 200,000 runs and
  on one of 1,000,000 runs. Both are built through the store's own API
  (:meth:`ResultStore.insert_batch` of :func:`pathzoo.analysis.synthetic.random_records`:
  4 configurations, 1,000 scenarios, 50 and 250 seeds). Targets: <= 400 MB at
  200,000 runs, and the same memory at 1,000,000 (printed as the ratio of
  the two peaks, target <= 1.10);
- **report time**: CPU time (user + system) of ``pathzoo report`` on 400
  synthetic runs over 200 scenarios against 400 runs over 2 scenarios
  (target <= 2x); wall times are printed beside it;
- **report memory**: peak RSS of ``pathzoo report`` on the databases of the
  leaderboard figure (one file each, built once): <= 400 MB at 200,000
  runs, and the same memory at ``--large-runs`` (ratio of the two peaks,
  target <= 1.10);
- **--jobs 2 against --jobs 1**: stored runs per second of the issue's
  sandboxed sweep (``exact.astar`` and ``aco.as`` with 3 iterations on 200
  MovingAI problems of one map, one seed) run with two and with one worker,
  each into a new database, alternated five times (``--jobs-repeats``). The
  target's figure is the steady state the issue measured "two jobs slower
  than one" in: the runs stored after the first quarter, the rule of
  ``benchmarks/harness.py`` (target: the ratio of the medians >= 1.6x). The
  ratio from the first stored run to the last is printed beside it: it also
  holds the start of the second configuration's worker, about a second of
  one-off work that a 400-run sweep cannot amortise. Also the CPU the
  harness's own process spends per stored run (its threads included; workers
  and judges are other processes);
- **sweep figures** of ``benchmarks/sweep.py`` (its ``figures()``).

Times are from a shared machine, so the load average is printed first;
CPU-time ratios are the steadier ones.
"""

from __future__ import annotations

import argparse
import importlib.util
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any, Callable, Iterator

from pathzoo.cli.cmd_run import positive_int

PLANNERS = ("exact.astar", "aco.as")
LEADERBOARD_MB_TARGET = 400.0
SAME_MEMORY_TARGET = 1.10
REPORT_TARGET = 2.0
REPORT_RUNS = 200_000
JOBS_TARGET = 1.6
CONFIGS = ("aco.as", "aco.eas", "aco.mmas", "exact.astar")
SCENARIOS = 1000
CLI = ("-c", "import sys; from pathzoo.cli.main import main; sys.exit(main())")

Figure = tuple[str, float, str]
"""(name, measured value, target as text) of one printed line."""


def child(args: list[str]) -> tuple[float, float, float]:
    """Run ``pathzoo ARGS`` in a child; its (wall s, CPU s, peak RSS MB), from ``wait4``. Raises if it fails."""
    t0 = time.perf_counter()
    proc = subprocess.Popen([sys.executable, *CLI, *args], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    assert proc.stderr is not None
    err = proc.stderr.read()
    _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    wall = time.perf_counter() - t0
    if proc.returncode != 0:
        raise SystemExit(f"scale.py: pathzoo {' '.join(args)} failed: {err.decode(errors='replace')[-2000:]}")
    return wall, usage.ru_utime + usage.ru_stime, usage.ru_maxrss / 1024


def synthetic_db(path: Path, n_scenarios: int, n_seeds: int, planners: tuple[str, ...]) -> Path:
    """A database of ``n_scenarios x len(planners) x n_seeds`` synthetic runs, written by the store's API."""
    from pathzoo.analysis.synthetic import random_records
    from pathzoo.harness.experiment import Experiment
    from pathzoo.harness.store import ResultStore

    experiment = Experiment.build(planners=["exact.astar"], scenarios=["dsaco.simple"], seeds=1, name="synthetic")
    batch: list[Any] = []
    with ResultStore(path) as store:
        store.add_experiment(experiment)
        for record in random_records(n_scenarios, n_seeds, planners):
            batch.append(record)
            if len(batch) == 20_000:
                store.insert_batch(batch)
                batch = []
        store.insert_batch(batch)
    return path


def study_db(folder: Path, runs: int) -> tuple[Path, int]:
    """The synthetic database of about ``runs`` runs (:data:`CONFIGS` x :data:`SCENARIOS` x seeds) and its run count.

    Built once per run of this script, so the leaderboard and the report read the same files.
    """
    seeds = max(1, runs // (SCENARIOS * len(CONFIGS)))
    path = folder / f"study{runs}.sqlite"
    if not path.exists():
        t0 = time.perf_counter()
        synthetic_db(path, SCENARIOS, seeds, CONFIGS)
        print(f"  built {SCENARIOS * len(CONFIGS) * seeds:,} runs in {time.perf_counter() - t0:.0f} s "
              f"({path.stat().st_size / 2**20:.0f} MB)", flush=True)
    return path, SCENARIOS * len(CONFIGS) * seeds


def leaderboard_figures(folder: Path, large_runs: int) -> Iterator[Figure]:
    """Peak RSS of ``pathzoo leaderboard`` at 200,000 runs and at ``large_runs``."""
    peaks = []
    for runs in (REPORT_RUNS, large_runs):
        db, stored = study_db(folder, runs)
        wall, cpu, peak = child(["leaderboard", str(db)])
        print(f"  pathzoo leaderboard on {stored:,} runs: {wall:.1f} s wall, {cpu:.1f} s CPU, peak RSS {peak:.0f} MB",
              flush=True)
        peaks.append(peak)
        yield (f"leaderboard peak RSS MB, {stored:,} runs", peak, f"<= {LEADERBOARD_MB_TARGET:.0f}")
    yield (f"leaderboard peak RSS {large_runs:,} / 200,000 runs", peaks[1] / peaks[0], f"<= {SAME_MEMORY_TARGET:.2f}")


def report_figures(folder: Path, large_runs: int) -> Iterator[Figure]:
    """CPU time of ``pathzoo report`` on 400 runs over 200 scenarios against 400 runs over 2; its peak RSS on
    :data:`REPORT_RUNS` runs and on ``large_runs``."""
    times = {}
    for scenarios, seeds in ((2, 100), (200, 1)):
        db = synthetic_db(folder / f"report{scenarios}.sqlite", scenarios, seeds, PLANNERS)
        wall, cpu, _ = child(["report", str(db), "-o", str(folder / f"report{scenarios}")])
        print(f"  pathzoo report, 400 runs over {scenarios} scenarios: {wall:.1f} s wall, {cpu:.1f} s CPU", flush=True)
        times[scenarios] = cpu
    yield ("report CPU, 200 scenarios / 2 (400 runs)", times[200] / times[2], f"<= {REPORT_TARGET:.1f}")
    peaks = []
    for runs in (REPORT_RUNS, large_runs):
        db, stored = study_db(folder, runs)
        wall, cpu, peak = child(["report", str(db), "-o", str(folder / f"report-{runs}")])
        print(f"  pathzoo report on {stored:,} runs: {wall:.1f} s wall, {cpu:.1f} s CPU, peak RSS {peak:.0f} MB",
              flush=True)
        peaks.append(peak)
        yield (f"report peak RSS MB, {stored:,} runs", peak, f"<= {LEADERBOARD_MB_TARGET:.0f}")
    yield (f"report peak RSS {large_runs:,} / 200,000 runs", peaks[1] / peaks[0], f"<= {SAME_MEMORY_TARGET:.2f}")


def _sweep_script() -> Any:
    """``benchmarks/sweep.py`` as a module (the issue's sweep: its problems and its steady-state rate)."""
    spec = importlib.util.spec_from_file_location("sweep", Path(__file__).with_name("sweep.py"))
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def steady_rate(stamps: list[float]) -> float:
    """Runs per second over the runs stored after the first quarter (start-up and warm-up excluded), the rule of
    ``benchmarks/harness.py``'s jobs figures."""
    skip = len(stamps) // 4
    return (len(stamps) - 1 - skip) / (stamps[-1] - stamps[skip])


def jobs_figures(folder: Path, problems: int, repeats: int) -> Iterator[Figure]:
    """Runs per second of the issue's sandboxed sweep with ``--jobs 2`` against ``--jobs 1`` (medians of
    ``repeats`` sweeps of each, alternated): in steady state (the target's figure) and from the first stored run
    to the last."""
    sweep = _sweep_script()
    chosen = sweep.problem_ids(problems)
    steady: dict[int, list[float]] = {1: [], 2: []}
    whole: dict[int, list[float]] = {1: [], 2: []}
    parent_ms: dict[int, list[float]] = {1: [], 2: []}
    for repeat in range(repeats):
        for jobs in (1, 2):
            c0 = time.process_time()
            stamps = sweep.stored_stamps(chosen, 1, jobs, folder / f"jobs{jobs}-{repeat}.sqlite")
            parent_ms[jobs].append(1000 * (time.process_time() - c0) / len(stamps))
            steady[jobs].append(steady_rate(stamps))
            whole[jobs].append((len(stamps) - 1) / (stamps[-1] - stamps[0]))
            print(f"  --jobs {jobs}: {steady[jobs][-1]:.1f} runs/s in steady state, {whole[jobs][-1]:.1f} from the "
                  f"first stored run to the last; the harness's own process {parent_ms[jobs][-1]:.1f} ms CPU per "
                  "stored run", flush=True)
    yield (f"--jobs 2 / --jobs 1 runs per second, {len(chosen)} problems, steady state (medians of {repeats})",
           statistics.median(steady[2]) / statistics.median(steady[1]), f">= {JOBS_TARGET:.1f}")
    yield ("the same from the first stored run to the last (start-up of the second worker included)",
           statistics.median(whole[2]) / statistics.median(whole[1]), "(for comparison)")
    yield ("harness process CPU ms per stored run, --jobs 2", statistics.median(parent_ms[2]),
           "small (the issue measured 11.8-14.1)")


def sweep_figures() -> Iterator[Figure]:
    """The figures of ``benchmarks/sweep.py`` (``figures() -> list[(name, value, target)]``), when it exists."""
    for name, value, target in _sweep_script().figures():
        yield (str(name), float(value), str(target))


def main(argv: list[str] | None = None) -> int:
    """Measure the chosen groups and print each figure beside its target."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    groups = ("leaderboard", "report", "jobs", "sweep")
    parser.add_argument("--only", choices=groups, action="append", help="measure only this group (repeatable)")
    parser.add_argument("--large-runs", type=positive_int, default=1_000_000,
                        help="runs of the large database of the leaderboard and report figures (default 1,000,000)")
    parser.add_argument("--problems", type=positive_int, default=200,
                        help="MovingAI problems of the --jobs sweep (default 200, the issue's; x 2 planners, 1 seed)")
    parser.add_argument("--jobs-repeats", type=positive_int, default=5,
                        help="sweeps of each --jobs setting, alternated; the figure is the ratio of the medians")
    args = parser.parse_args(argv)
    chosen = args.only or list(groups)
    print(f"load average: {' '.join(f'{x:.2f}' for x in os.getloadavg())} on {os.cpu_count()} cores", flush=True)
    folder = Path(tempfile.mkdtemp(prefix="pathzoo-scale-"))
    measure: dict[str, Callable[[], Iterator[Figure]]] = {
        "leaderboard": lambda: leaderboard_figures(folder, args.large_runs),
        "report": lambda: report_figures(folder, args.large_runs),
        "jobs": lambda: jobs_figures(folder, args.problems, args.jobs_repeats),
        "sweep": sweep_figures,
    }
    figures: list[Figure] = []
    try:
        for group in chosen:
            print(f"{group}:", flush=True)
            figures += measure[group]()
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    width = max((len(name) for name, _, _ in figures), default=0)
    print()
    for name, value, target in figures:
        print(f"  {name:<{width}}  {value:10.2f}   target {target}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
