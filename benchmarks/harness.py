"""Issue 12's harness targets: each figure measured and printed beside its target, in one run.

Run from the repository root::

    python benchmarks/harness.py             # everything (the cold default experiment takes a minute or more)
    python benchmarks/harness.py --quick     # without the cold default experiment
    python benchmarks/harness.py --first-only   # only the first result of `pathzoo run`
    python benchmarks/harness.py --write-docs   # also rewrite the table in docs/harness.md (after a full run)

Every measurement runs in a child process (``pathzoo run`` or a short Python
script) and is reported as wall seconds *and* CPU seconds of the whole
process tree (the harness, the forkserver, every worker and the judge), read
with psutil every 0.05 s, so a process that ends between two readings loses
at most its last 0.05 s. On a machine shared with other work the wall times
are inflated and the jobs=2 / jobs=1 ratio means little; the load average is
printed first, and the CPU figures are the ones to compare.

- *first result*: from the start of ``pathzoo run`` (the default experiment)
  to the first run stored in its database, then the run is stopped; also the
  same time from the call of ``run_experiment`` in a Python process that has
  already imported pathzoo and read the experiment (the harness's own part).
  Measured on a fresh numba cache, empty once, then warmed by that attempt
  (``--first-repeats`` times: the target's figure, the minimum). The
  reference is ``python -c "import numpy, scipy, numba"`` timed in the same
  run, as often, between the attempts (its minimum); the target is a ratio to
  it. Printed with the CPU seconds the command's process tree had used by its
  first stored run: the harness, the fork server (numpy, numba, scipy and
  pathzoo's shared code, numba's start-up) and the judge forked from it, the
  child that describes the planners, and the sandboxed workers (each a new
  interpreter that imports its own planner).
- *default experiment, cold*: ``pathzoo run`` of the bundled default
  experiment with an empty ``NUMBA_CACHE_DIR``, so every numba function is
  compiled during the run.
- *tiny runs*: (CPU read from a cgroup of the run's own where cgroups are
  writable, so no process's time is missed) ``--tiny`` runs of ``exact.astar`` (one iteration) on a 32x32
  MovingAI problem at jobs=1 and jobs=2: runs per wall second, their ratio,
  and the harness's cost per run (wall and CPU per run, minus the planner's
  own ``plan()`` time as stored). A tiny run costs the harness (worker,
  judge, store) more than the planner, and at jobs=1 the judge and the
  store already work beside the worker, so this ratio stays well below 2
  even on an idle machine: with a worker's cost per run W and the harness
  process's and the judge's S, jobs=1 runs at about 1/max(W, S) on two
  cores and jobs=2 at most 2/(W + S), a ratio of 2 max(W, S)/(W + S), which
  reaches 1.8 only when S <= W/9.
- *external planners*: ``--external`` runs each of three planners that spin
  for 1 ms and return a straight line on the same problem (``inline``
  executor, stored wall times of ``plan()``): a Python planner (the
  reference), a C program behind the JSON protocol (a process per run) and
  an Octave function file (one Octave process, started in the warm-up).
  The medians' differences from the reference are the protocol's cost per
  run; the largest Octave run shows that Octave's start-up is in no run.
- *sandbox*: the per-run overhead above, measured again with the workers
  in the OS sandbox (``docs/sandbox.md``) and without it: the difference
  is the sandbox's fixed cost per run (target: under 20 CPU ms), and the
  unsandboxed overhead is the harness's own cost per run (target: 2 CPU ms); the
  sandboxed worker's start (a new interpreter in bubblewrap, once per
  planner configuration and worker) is part of the start-up, not of it.
- *scenario integrity check*: in this process, on a 512x512 MovingAI map
  (``movingai.8room_000``), the worker's check after each run
  (:meth:`pathzoo.harness.sealed.ScenarioSeal.intact` on the sealed
  scenario) against ``exact.astar``'s ``plan()`` on the same scenario
  (CPU time, minimum of repeats), with the full byte digest the check
  replaces beside it for information.
- *short runs*: ``--short`` runs of ``aco.as`` (2000 iterations, about 0.1 CPU s each) on the same
  problem at jobs=1 and jobs=2, where the planner's time dominates: the
  throughput ratio the target is about.
"""

from __future__ import annotations

import argparse
import os
import shutil
import sqlite3
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import psutil

from pathzoo.cli.cmd_run import positive_int

sys.path.insert(0, str(Path(__file__).resolve().parent))
from doc_table import add_write_docs_option, docs_table  # noqa: E402  (a sibling script)

FIRST_RESULT_TARGET_RATIO = 1.5
IMPORT_REFERENCE = "import numpy, scipy, numba"
DEFAULT_COLD_TARGET_S = 60.0
JOBS_RATIO_TARGET = 1.8
TINY_SCENARIO = "movingai.random-32-32-20.b10.13"
SHORT_ITERATIONS = 2000
SANDBOX_COST_TARGET_MS = 20.0
HARNESS_COST_TARGET_MS = 2.0
INTEGRITY_SCENARIO = "movingai.8room_000.b144.1430"
INTEGRITY_TARGET = 0.05

_TINY_SCRIPT = """
import sys, time
import pathzoo
from pathzoo import Budget
from pathzoo.harness import Experiment, run_experiment
from pathzoo.harness.executors import ProcessExecutor
from pathzoo.harness.cgroup import CGROUP_ROOT, _own_groups
from pathzoo.plugins.manager import get_registry
usage = CGROUP_ROOT / "cpuacct" / _own_groups().get("cpuacct", "/").lstrip("/") / "cpuacct.usage"
marks = []  # after each stored run: the tree's CPU seconds (its cgroup's) and the run's stored plan() CPU

class Marks:
    @pathzoo.hookimpl
    def pathzoo_run_finished(self, record):
        try:
            marks.append((int(usage.read_text()) / 1e9, record.cpu_time_s))
        except (OSError, ValueError):
            pass

get_registry().add_plugin(Marks(), "benchmark-marks")
exp = Experiment.build(name="tiny", planners=[{planner!r}], scenarios=[{scenario!r}], seeds={n},
                       budget=Budget(iterations={iterations}, time_s=5.0))
t0 = time.perf_counter()
runs = run_experiment(exp, db={db!r}, executor=ProcessExecutor({jobs}, sandbox={sandbox}), progress=False)
wall = time.perf_counter() - t0
assert len(runs) == {n} and (runs["status"] == "solved").all(), runs["status"].value_counts()
import datetime, sqlite3
done = sorted(datetime.datetime.fromisoformat(r[0]).timestamp()
              for r in sqlite3.connect({db!r}).execute("SELECT finished_at FROM runs"))
skip = {n} // 4  # steady state: runs stored after the first quarter (start-up and warm-up excluded)
steady = ({n} - 1 - skip) / (done[-1] - done[skip])
# the tree's CPU per run after the first quarter, minus the stored plan() CPU of those runs (NaN without a cgroup)
per_run = ((marks[-1][0] - marks[skip][0] - sum(c for _, c in marks[skip + 1:])) / ({n} - 1 - skip)
           if len(marks) == {n} else float("nan"))
print(per_run, steady, wall, runs["wall_time_s"].sum(), runs["cpu_time_s"].sum())
"""

_FIRST_SCRIPT = """
import importlib.resources, os, sqlite3, sys, threading, time
from pathzoo.harness import Experiment, run_experiment
exp = Experiment.from_toml(importlib.resources.files("pathzoo") / "experiments" / "default.toml")
def watch(t0):
    while True:
        try:
            with sqlite3.connect({db!r}, timeout=0.1) as con:
                if con.execute("select count(*) from runs").fetchone()[0]:
                    print(time.perf_counter() - t0, flush=True)
                    os._exit(0)  # the workers and the judge die with this process
        except sqlite3.Error:
            pass
        time.sleep(0.01)
threading.Thread(target=watch, args=(time.perf_counter(),), daemon=True).start()
run_experiment(exp, db={db!r}, progress=False)
"""


@dataclass
class TreeUsage:
    """Wall and CPU seconds of a child process and all its descendants."""

    wall_s: float
    cpu_s: float
    stdout: str
    steady_rate: float = float("nan")
    steady_cpu_per_run: float = float("nan")
    """CPU seconds of the whole tree per run after the first quarter, minus ``plan()``'s (from its cgroup)."""


def run_tree(cmd: list[str], *, env: dict[str, str] | None = None, cwd: str | None = None,
             stop_when: "Callable[[float], bool] | None" = None, timeout_s: float = 1800.0,
             exact: bool = False) -> TreeUsage:
    """Run ``cmd`` and add up the CPU time of its process tree (sampled every 0.05 s).

    ``stop_when`` is polled too, with the tree's CPU seconds so far; when it
    returns True the command gets SIGINT (as Ctrl-C would) and the
    measurement ends when it has exited. With ``exact`` (where cgroups are
    writable) the total is read from a cgroup the command starts in
    (``cpuacct.usage``: every process of the tree, ended ones and the
    sandboxed workers' nested groups included) instead of the samples.
    """
    from pathzoo.harness.cgroup import ProcessGroup, cgroup_problem

    group = ProcessGroup(f"bench{time.monotonic_ns()}", memory_bytes=1 << 40, max_tasks=1 << 20) \
        if exact and not cgroup_problem() else None

    def join_group() -> None:
        for path in group.procs_files if group is not None else ():
            with open(path, "w") as f:
                f.write(str(os.getpid()))

    last: dict[int, float] = {}
    t0 = time.perf_counter()
    proc = subprocess.Popen(cmd, env=env, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True,
                            preexec_fn=join_group if group is not None else None)
    out: list[str] = []
    reader = threading.Thread(target=lambda: out.append(proc.stdout.read()), daemon=True)  # type: ignore[union-attr]
    reader.start()
    root = psutil.Process(proc.pid)
    stopped = False
    while proc.poll() is None:
        try:
            for p in [root, *root.children(recursive=True)]:
                try:
                    t = p.cpu_times()
                    last[p.pid] = t.user + t.system
                except psutil.Error:
                    pass
        except psutil.Error:
            pass
        if stop_when is not None and not stopped and stop_when(sum(last.values())):
            proc.send_signal(2)
            stopped = True
        if time.perf_counter() - t0 > timeout_s:
            proc.kill()
            raise TimeoutError(f"{cmd} took over {timeout_s} s")
        time.sleep(0.05)
    wall = time.perf_counter() - t0
    reader.join()
    cpu = sum(last.values())
    if group is not None:
        cpu = group.cpu_seconds()
        group.remove()
    return TreeUsage(wall, cpu, "".join(out))


def stored_runs(db: Path) -> int:
    """Rows in the runs table (0 while the database does not exist yet)."""
    try:
        with sqlite3.connect(db, timeout=0.1) as con:
            return int(con.execute("select count(*) from runs").fetchone()[0])
    except sqlite3.Error:
        return 0


def pathzoo_cli() -> str:
    """The ``pathzoo`` script beside this interpreter."""
    return str(Path(sys.executable).with_name("pathzoo"))


def first_result(tmp: Path, attempt: str) -> tuple[float, float, float]:
    """Seconds from the start of ``pathzoo run`` to its first stored run, and from ``run_experiment``'s call.

    Also the CPU seconds the command's process tree had used by its first
    stored run (sampled every 0.05 s), which other load inflates much less
    than the wall time. Both use the numba cache ``tmp/numba-first``: empty
    at the first attempt, filled by it for the next.
    """
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp / "numba-first")}
    db = tmp / f"first-{attempt}.sqlite"
    t0 = time.perf_counter()
    seen: list[float] = []

    def stop(cpu_s: float) -> bool:
        if not seen and stored_runs(db):
            seen.extend((time.perf_counter() - t0, cpu_s))
        return bool(seen)

    run_tree([pathzoo_cli(), "run", "--db", str(db), "--no-progress"], env=env, cwd=str(tmp), stop_when=stop)
    api = run_tree([sys.executable, "-c", _FIRST_SCRIPT.format(db=str(tmp / f"first-api-{attempt}.sqlite"))],
                   env=env, cwd=str(tmp))
    wall, cpu = seen if seen else (float("nan"), float("nan"))
    return wall, float(api.stdout.split()[-1]), cpu


def import_reference(tmp: Path) -> TreeUsage:
    """Wall and CPU seconds of ``python -c "import numpy, scipy, numba"`` (the first result's reference)."""
    return run_tree([sys.executable, "-c", IMPORT_REFERENCE], cwd=str(tmp))


def first_result_row(tmp: Path, repeats: int) -> str:
    """The first-result figure against its target: the warm attempts' minimum over the import line's minimum."""
    cli_cold, api_cold, cpu_cold = first_result(tmp, "cold")
    warm, refs = [], []
    for i in range(repeats):  # interleaved, so that a change in the machine's load reaches both alike
        refs.append(import_reference(tmp))
        warm.append(first_result(tmp, f"warm{i}"))
    ref_wall, ref_cpu = min(r.wall_s for r in refs), min(r.cpu_s for r in refs)
    cli, api, cpu = min(w[0] for w in warm), min(w[1] for w in warm), min(w[2] for w in warm)
    ratio = cli / ref_wall
    return (f"| first result of `pathzoo run`, numba cache warm (min of {repeats}) | {ratio:.2f}x the import line: "
            f"{cli:.2f} s from the command's start ({api:.2f} s from `run_experiment()`) against {ref_wall:.2f} s for "
            f"`python -c \"{IMPORT_REFERENCE}\"`; the process tree had used {cpu:.2f} CPU s by then "
            f"({cpu / ref_cpu:.1f}x the import line's {ref_cpu:.2f}); with an empty numba cache {cli_cold:.2f} s "
            f"({api_cold:.2f} s), {cpu_cold:.2f} CPU s | <= {FIRST_RESULT_TARGET_RATIO:g}x "
            f"| {verdict(ratio <= FIRST_RESULT_TARGET_RATIO)} |")


def default_cold(tmp: Path) -> TreeUsage:
    """``pathzoo run`` of the default experiment with an empty numba cache."""
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp / "numba-cold")}
    usage = run_tree([pathzoo_cli(), "run", "--db", str(tmp / "default.sqlite"), "--no-progress"], env=env,
                     cwd=str(tmp))
    runs = stored_runs(tmp / "default.sqlite")
    expected = default_run_count()
    if runs != expected:
        raise RuntimeError(f"the default experiment stored {runs} runs, not {expected}")
    return usage


def default_run_count() -> int:
    """How many runs the bundled default experiment has (supported pairs times seeds)."""
    from importlib import resources

    from pathzoo.harness.experiment import Experiment

    with resources.as_file(resources.files("pathzoo.experiments") / "default.toml") as path:
        exp = Experiment.from_toml(path)
    return len(exp.pairs()) * len(exp.seeds)


def tiny(tmp: Path, jobs: int, n: int, planner: str = "exact.astar", iterations: int = 1, name: str = "",
         sandbox: bool | None = None) -> tuple[TreeUsage, float, float]:
    """``n`` runs at ``jobs``: the tree's usage, and the summed stored wall and CPU time of ``plan()``.

    ``sandbox`` as for :class:`~pathzoo.harness.executors.ProcessExecutor` (default: where the system can).
    """
    db = tmp / f"{planner}-{jobs}{name}.sqlite"
    script = _TINY_SCRIPT.format(planner=planner, iterations=iterations, scenario=TINY_SCENARIO, n=n, db=str(db),
                                 jobs=jobs, sandbox=sandbox)
    usage = run_tree([sys.executable, "-c", script], cwd=str(tmp), exact=True)
    per_run, steady, wall, plan_wall, plan_cpu = map(float, usage.stdout.split()[-5:])
    usage.wall_s = wall  # the harness's part only: imports and the experiment's construction excluded
    usage.steady_rate = steady
    usage.steady_cpu_per_run = per_run
    return usage, plan_wall, plan_cpu


EXTERNAL_OVERHEAD_TARGET_S = {"command": 0.010, "octave": 0.020}
"""Targets for the protocol's cost per run on a 1 ms planner (median over the reference's)."""

_SPIN_C = r"""
#include <stdio.h>
#include <string.h>
#include <time.h>
static double now(void) { struct timespec t; clock_gettime(CLOCK_MONOTONIC, &t); return t.tv_sec + 1e-9 * t.tv_nsec; }
int main(void) {
    static char buf[1 << 22];
    size_t n = fread(buf, 1, sizeof buf - 1, stdin);
    buf[n] = 0;
    double t0 = now();
    while (now() - t0 < 1e-3) {}
    char *s = strstr(buf, "\"start\":"), *g = strstr(buf, "\"goal\":");
    double sx, sy, gx, gy;
    sscanf(s + 8, "[%lf,%lf]", &sx, &sy);
    sscanf(g + 7, "[%lf,%lf]", &gx, &gy);
    printf("{\"status\":\"solved\",\"path\":[[%.17g,%.17g],[%.17g,%.17g]]}\n", sx, sy, gx, gy);
    return 0;
}
"""

_SPIN_M = """function [path, info] = spin (problem, params)
  t0 = tic ();
  while (toc (t0) < 1e-3)
  endwhile
  path = [problem.start(:)'; problem.goal(:)'];
  info.status = "solved";
endfunction
"""

_EXTERNAL_SCRIPT = """
import time
import numpy as np
import pathzoo
from pathzoo.harness import Experiment, run_experiment
from pathzoo.plugins.manager import get_registry

class Spin(pathzoo.Planner):
    id, version, summary, kinds = "bench.spin", "1", "spins 1 ms", frozenset({{"grid2d"}})

    def plan(self, scenario, *, budget, rng, progress=None):
        t0 = time.perf_counter()
        while time.perf_counter() - t0 < 1e-3:
            pass
        return pathzoo.PlanResult(pathzoo.Status.SOLVED, np.stack([scenario.start, scenario.goal]))

get_registry().add_plugin(type("plugin", (), {{"pathzoo_register_planners": staticmethod(lambda: [Spin])}})(), "spin")
exp = Experiment.from_toml({toml!r})
runs = run_experiment(exp, db={db!r}, executor="inline", progress=False)
for label, group in runs.groupby("label"):
    wall = group["wall_time_s"].to_numpy()
    print(label, len(wall), np.median(wall), wall.max())
"""


def external_overhead(tmp: Path, n: int) -> dict[str, tuple[int, float, float]]:
    """Per planner label: runs, median and largest stored wall time of ``plan()`` (see the module docstring)."""
    folder = tmp / "external"
    folder.mkdir()
    (folder / "spin.c").write_text(_SPIN_C)
    (folder / "spin.m").write_text(_SPIN_M)
    subprocess.run(["cc", "-O2", "-o", str(folder / "spin"), str(folder / "spin.c")], check=True)
    (folder / "spin.toml").write_text(
        f'[experiment]\nname = "spin"\nseeds = {n}\nbudget = {{ time_s = 10 }}\nscenarios = ["{TINY_SCENARIO}"]\n'
        '[[planner]]\nid = "bench.spin"\nlabel = "python"\n'
        '[[planner]]\ncommand = ["./spin"]\nlabel = "command"\n'
        '[[planner]]\noctave = "spin.m"\nlabel = "octave"\n')
    usage = run_tree([sys.executable, "-c", _EXTERNAL_SCRIPT.format(toml=str(folder / "spin.toml"),
                                                                    db=str(folder / "spin.sqlite"))], cwd=str(folder))
    out = {}
    for line in usage.stdout.splitlines():
        label, runs, median, largest = line.split()
        out[label] = (int(runs), float(median), float(largest))
    return out


def sandbox_cost(tmp: Path, n: int, few: int) -> None:
    """Print the per-run overhead at jobs=1 with and without the sandbox, and their difference against the target."""
    from pathzoo.harness.sandbox import sandbox_problem

    if sandbox_problem():
        print(f"| the sandbox's fixed cost per run | not measured, no sandbox here ({sandbox_problem()}) | - | - |")
        return
    per_run = {}
    for sandbox in (False, True):
        many, _, cpu_many = tiny(tmp, 1, n, name=f"sandbox-{sandbox}", sandbox=sandbox)
        some, _, cpu_some = tiny(tmp, 1, few, name=f"sandbox-{sandbox}-few", sandbox=sandbox)
        per_run[sandbox] = ((many.cpu_s - some.cpu_s - (cpu_many - cpu_some)) / (n - few) * 1e3,
                            (many.wall_s - some.wall_s) / (n - few) * 1e3, some.cpu_s)
    cost = per_run[True][0] - per_run[False][0]
    steady = {sandbox: tiny(tmp, 1, n, name=f"steady-{sandbox}", sandbox=sandbox)[0].steady_cpu_per_run * 1e3
              for sandbox in (False, True)}
    print(f"| harness CPU per run, sandbox apart (jobs=1, unsandboxed workers, {n} tiny runs: the CPU of the whole "
          f"process tree, read from its cgroup, per run after the first quarter, minus the runs' `plan()` CPU: "
          f"harness, judge and worker; {steady[True]:.1f} ms with sandboxed workers, so the sandbox's own cost is "
          f"{steady[True] - steady[False]:.1f} ms) | {steady[False]:.2f} CPU ms | <= {HARNESS_COST_TARGET_MS:g} ms "
          f"| {verdict(steady[False] <= HARNESS_COST_TARGET_MS)} |")
    print(f"| the sandbox's fixed cost per run (per-run overhead at jobs=1: {per_run[True][0]:.1f} CPU ms, "
          f"{per_run[True][1]:.1f} ms wall sandboxed; {per_run[False][0]:.1f} CPU ms, {per_run[False][1]:.1f} ms wall "
          f"not; {few} runs with start-up: {per_run[True][2]:.2f} CPU s sandboxed, {per_run[False][2]:.2f} not) "
          f"| {cost:.1f} CPU ms | < {SANDBOX_COST_TARGET_MS:g} ms | {verdict(cost < SANDBOX_COST_TARGET_MS)} |")


def _min_cpu_s(call: "Callable[[], object]", repeats: int) -> float:
    """The least CPU time of ``repeats`` calls (the least disturbed by other load)."""
    best = float("inf")
    for _ in range(repeats):
        c0 = time.process_time()
        call()
        best = min(best, time.process_time() - c0)
    return best


def integrity_check(repeats: int = 30) -> None:
    """Print the per-run scenario check's CPU time as a fraction of A*'s ``plan()`` on a 512x512 map."""
    import numpy as np

    from pathzoo import Budget, make_planner
    from pathzoo.harness.digest import scenario_digest, warm
    from pathzoo.harness.sealed import seal
    from pathzoo.plugins.manager import get_registry

    scenario = warm(get_registry().get("scenarios", INTEGRITY_SCENARIO).obj.load())
    full = _min_cpu_s(lambda: scenario_digest(scenario), 3)
    sealed = seal(scenario)
    planner = make_planner("exact.astar")
    planner.plan(scenario, budget=Budget(), rng=np.random.default_rng(0))  # numba's code loaded
    plan = _min_cpu_s(lambda: planner.plan(scenario, budget=Budget(), rng=np.random.default_rng(0)), repeats)
    check = _min_cpu_s(sealed.intact, repeats * 10)
    ratio = check / plan
    print(f"| scenario integrity check per run ({INTEGRITY_SCENARIO}, {'x'.join(map(str, scenario.shape))}, "
          f"{sealed.sealed} arrays sealed: the check {check * 1e6:.0f} CPU us, `exact.astar` `plan()` "
          f"{plan * 1e3:.2f} CPU ms; the full byte digest it replaces {full * 1e3:.1f} ms) | {ratio:.1%} of `plan()` "
          f"| <= {INTEGRITY_TARGET:.0%} | {verdict(ratio <= INTEGRITY_TARGET)} |")


def short_runs(tmp: Path, n: int) -> None:
    """Print the throughput ratio of jobs=2 to jobs=1 on ``n`` short ``aco.as`` runs."""
    s1, _, scpu = tiny(tmp, 1, n, "aco.as", SHORT_ITERATIONS)
    s2, _, _ = tiny(tmp, 2, n, "aco.as", SHORT_ITERATIONS)
    print(throughput_row(f"{n} short runs (`aco.as`, {SHORT_ITERATIONS} iterations, `plan()` "
                         f"{scpu / n * 1e3:.0f} CPU ms each)", n, s1, s2))


def verdict(ok: bool) -> str:
    return "met" if ok else "not met"


def throughput_row(label: str, n: int, one: TreeUsage, two: TreeUsage) -> str:
    """Throughput at jobs 1 and 2 as a table row: steady state (judged against the target) and over the whole call."""
    steady = two.steady_rate / one.steady_rate
    return (f"| jobs=2 / jobs=1, {label} | {steady:.2f} in steady state (runs stored after the first quarter: "
            f"{one.steady_rate:.1f} and {two.steady_rate:.1f} runs/s); {one.wall_s / two.wall_s:.2f} over the whole "
            f"call, start-up included ({n / one.wall_s:.1f} and {n / two.wall_s:.1f} runs/s) "
            f"| >= {JOBS_RATIO_TARGET:g} | {verdict(steady >= JOBS_RATIO_TARGET)} |")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="skip the cold default experiment")
    parser.add_argument("--tiny", type=positive_int, default=140, help="tiny runs per jobs setting (default 140)")
    parser.add_argument("--short", type=positive_int, default=40, help="short aco.as runs per jobs setting (default 40)")
    parser.add_argument("--external", type=positive_int, default=40,
                        help="runs of each 1 ms planner behind the external protocol (default 40)")
    parser.add_argument("--sandbox-only", action="store_true", help="only the sandbox's cost per run")
    parser.add_argument("--first-only", action="store_true", help="only the first result of `pathzoo run`")
    parser.add_argument("--first-repeats", type=positive_int, default=3,
                        help="warm first-result attempts, each with an import-line reference (default 3)")
    parser.add_argument("--integrity-only", action="store_true", help="only the scenario integrity check")
    parser.add_argument("--short-only", action="store_true", help="only the short runs at jobs=1 and jobs=2")
    add_write_docs_option(parser, "harness.md")
    args = parser.parse_args()
    if args.integrity_only:
        integrity_check()
        return
    if args.short_only:
        print(f"load average {os.getloadavg()[0]:.2f}", file=sys.stderr)
        with tempfile.TemporaryDirectory(prefix="pathzoo-harness-bench-") as name:
            short_runs(Path(name), args.short)
        return
    if args.sandbox_only:
        with tempfile.TemporaryDirectory(prefix="pathzoo-harness-bench-") as name:
            sandbox_cost(Path(name), args.tiny, max(1, args.tiny // 4))
        return
    print(f"load average {os.getloadavg()[0]:.2f} {os.getloadavg()[1]:.2f} on {os.cpu_count()} cores; "
          "wall times are inflated by other load, CPU times (whole process tree) much less", file=sys.stderr)
    with tempfile.TemporaryDirectory(prefix="pathzoo-harness-bench-") as name, \
            docs_table(args.write_docs, "harness.md", "harness.py"):
        tmp = Path(name)
        print("| figure | measured | target | verdict |\n|---|---|---|---|")
        print(first_result_row(tmp, args.first_repeats), flush=True)
        if args.first_only:
            return
        if not args.quick:
            cold = default_cold(tmp)
            print(f"| default experiment, cold (empty `NUMBA_CACHE_DIR`, {default_run_count()} runs) | {cold.wall_s:.1f} s wall, "
                  f"{cold.cpu_s:.1f} CPU s | <= {DEFAULT_COLD_TARGET_S:g} s wall on 2 cores "
                  f"| {verdict(cold.wall_s <= DEFAULT_COLD_TARGET_S)} |")
        one, wall1, cpu1 = tiny(tmp, 1, args.tiny)
        two, _, _ = tiny(tmp, 2, args.tiny)
        print(throughput_row(f"{args.tiny} tiny runs (`exact.astar`, 1 iteration, {TINY_SCENARIO})", args.tiny,
                             one, two))
        few = max(1, args.tiny // 4)
        base, wall0, cpu0 = tiny(tmp, 1, few, iterations=1, planner="exact.astar", name="few")
        extra = args.tiny - few
        print(f"| per-run harness overhead at jobs=1 (the cost of {extra} more tiny runs, start-up excluded) | "
              f"{(one.wall_s - base.wall_s - (wall1 - wall0)) / extra * 1e3:.1f} ms wall, "
              f"{(one.cpu_s - base.cpu_s - (cpu1 - cpu0)) / extra * 1e3:.1f} ms CPU of the whole tree "
              f"(`plan()` itself {(cpu1 - cpu0) / extra * 1e3:.1f} CPU ms; whole tree with start-up: "
              f"{one.cpu_s / args.tiny * 1e3:.1f} ms at jobs=1, {two.cpu_s / args.tiny * 1e3:.1f} ms at jobs=2) "
              f"| - | - |")
        if shutil.which("cc") and shutil.which("octave-cli"):
            ext = external_overhead(tmp, args.external)
            ref = ext["python"][1]
            for label in ("command", "octave"):
                runs, median, largest = ext[label]
                cost = median - ref
                target = EXTERNAL_OVERHEAD_TARGET_S[label]
                print(f"| external protocol cost per run, {label} ({runs} runs of a 1 ms planner: median stored "
                      f"`plan()` wall {median * 1e3:.2f} ms against {ref * 1e3:.2f} ms in-process Python, the "
                      f"reference; largest {largest * 1e3:.1f} ms) | {cost * 1e3:.2f} ms | <= {target * 1e3:g} ms "
                      f"| {verdict(cost <= target)} |")
        else:
            print("| external protocol cost per run | skipped: needs cc and octave-cli | - | - |")
        sandbox_cost(tmp, args.tiny, few)
        integrity_check()
        short_runs(tmp, args.short)


if __name__ == "__main__":
    main()
