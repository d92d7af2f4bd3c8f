"""Baselines against the exact planners: median planning time and length ratio to the optimum.

Run from the repository root (the scenario packs must be installed)::

    python benchmarks/baselines.py                    # 3 seeds, 2 s per run, 2 worker processes
    python benchmarks/baselines.py --seeds 5 --time 5 --jobs 4
    python benchmarks/baselines.py --quick            # 1 seed, 1 s, small scenarios only
    python benchmarks/baselines.py --ompl             # OMPL motion checks/s, rrtconnect on 8room, any-angle bound

Planners: every baseline (``swarm.pso``, ``swarm.cuckoo``, ``evo.ga``,
``evo.fuzzy_ga`` and the seven ``ompl.*``) and the exact planners
(``exact.dijkstra``, ``exact.astar``, ``exact.thetastar``), all with default
parameters and the same time budget.

Scenarios: the G-Ant pack (``gant.*``: two 10 x 10 spaces and the nine
500 x 500 problems), the static variants of the FGDACO pack
(``fgdaco.*_static``, 100 x 100) and one problem on each of two MovingAI maps
(``arena``, 49 x 49, and ``8room_000``, 512 x 512; the problem at the 75th
percentile of each map's buckets).

The experiment goes through :func:`pathzoo.run`, so the harness validates
every returned path: a "success" is a run the harness judged ``solved``.
For each planner the script prints the success rate, the median planning
time of the successful runs and their median ``length_ratio`` (path length
over the exact 8-connected optimum, or the ``.scen`` optimum; any-angle paths
may score below 1), overall and per scenario group. It also checks that no
reported success has an invalid path and exits with status 1 otherwise.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import pandas as pd

import pathzoo
from pathzoo.rules import validate_path
from pathzoo.plugins.manager import get_registry

BASELINES = (
    "swarm.pso", "swarm.cuckoo", "evo.ga", "evo.fuzzy_ga",
    "ompl.rrt", "ompl.rrtconnect", "ompl.rrtstar", "ompl.informed_rrtstar", "ompl.prmstar", "ompl.bitstar", "ompl.fmt",
)
EXACT = ("exact.dijkstra", "exact.astar", "exact.thetastar")
MOVINGAI_MAPS = ("arena", "8room_000")


def movingai_problem(map_stem: str) -> str:
    """The registered problem at the 75th percentile of the map's (bucket, index) order."""
    ids = get_registry().match("scenarios", f"movingai.{map_stem}.*")

    def order(sid: str) -> tuple[int, int]:
        bucket, index = sid.split(".")[-2:]
        return int(bucket.lstrip("b")), int(index)

    ids = sorted(ids, key=order)
    return ids[int(0.75 * (len(ids) - 1))]


def scenario_groups(quick: bool) -> dict[str, list[str]]:
    """Scenario ids by group; ``quick`` keeps the small ones."""
    reg = get_registry()
    gant = reg.match("scenarios", "gant.*")
    groups = {
        "gant 10x10": [s for s in gant if s.count(".") == 1],
        "gant 500x500": [s for s in gant if s.count(".") == 2],
        "fgdaco static": reg.match("scenarios", "fgdaco.*_static"),
        "movingai": [movingai_problem(m) for m in MOVINGAI_MAPS],
    }
    if quick:
        groups = {"gant 10x10": groups["gant 10x10"], "fgdaco static": groups["fgdaco static"],
                  "movingai": groups["movingai"][:1]}
    return groups


def summarise(runs: pd.DataFrame, groups: dict[str, list[str]]) -> pd.DataFrame:
    """Success rate, median time and median length ratio per planner, overall and per group."""
    group_of = {sid: name for name, ids in groups.items() for sid in ids}
    runs = runs.assign(group=runs["scenario"].map(group_of), ok=runs["status"].eq("solved") & runs["valid"])
    rows = []
    for planner, sub in runs.groupby("planner", sort=False):
        solved = sub[sub["ok"]]
        row = {
            "planner": planner,
            "success": sub["ok"].mean(),
            "median time (s)": solved["planning_time"].median(),
            "median length ratio": solved["length_ratio"].median(),
        }
        for name in groups:
            part = solved[solved["group"] == name]
            row[f"ratio: {name}"] = part["length_ratio"].median()
        rows.append(row)
    table = pd.DataFrame(rows).set_index("planner")
    return table.reindex([p for p in (*BASELINES, *EXACT) if p in table.index])


def main(argv: list[str] | None = None) -> int:
    """Run the experiment and print the table; exit status 1 if a success is not a validated path."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seeds", type=int, default=3)
    parser.add_argument("--time", type=float, default=2.0, help="planning time per run, seconds")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--db", type=Path, default=Path("benchmarks") / "baselines.sqlite")
    parser.add_argument("--quick", action="store_true", help="1 seed, 1 s, small scenarios only")
    parser.add_argument("--ompl", action="store_true", help="only the OMPL and any-angle section (issue 9)")
    args = parser.parse_args(argv)
    if args.ompl:
        return ompl_section()
    if args.quick:
        args.seeds, args.time = 1, 1.0
    groups = scenario_groups(args.quick)
    scenarios = [sid for ids in groups.values() for sid in ids]
    print(f"{len(BASELINES) + len(EXACT)} planners x {len(scenarios)} scenarios x {args.seeds} seeds, "
          f"{args.time:g} s per run: {', '.join(scenarios)}", flush=True)
    runs = pathzoo.run(
        [*BASELINES, *EXACT], scenarios, seeds=args.seeds, db=args.db, jobs=args.jobs,
        budget=pathzoo.Budget(time_s=args.time), experiment=f"baselines-{args.seeds}x{args.time:g}s"
        + ("-quick" if args.quick else ""),
    )
    table = summarise(runs, groups)
    with pd.option_context("display.width", 200, "display.max_columns", 20, "display.float_format", "{:.3f}".format):
        print(table)
    statuses = runs.groupby(["planner", "status"]).size().unstack(fill_value=0)
    print("\nrun statuses per planner:")
    print(statuses.reindex([p for p in (*BASELINES, *EXACT) if p in statuses.index]))
    # "invalid": the planner said SOLVED and the harness's validator rejected the path
    bad = runs[runs["status"].eq("invalid") | (runs["status"].eq("solved") & ~runs["valid"])]
    if len(bad):
        print(f"\n{len(bad)} claimed success(es) without a valid path:", file=sys.stderr)
        print(bad[["planner", "scenario", "seed_index", "invalid_reason"]].to_string(), file=sys.stderr)
        return 1
    print("\nevery success a planner claimed is a path the harness validated")
    return 0


# ============================================================== OMPL and the any-angle optimum (issue 9, parts 2-3)
# Own section: run with --ompl. Figures are CPU times (time.process_time) of this process.

OMPL_MOTION_TARGET = 1_000_000
"""Target: motion checks per CPU second of the OMPL motion validator."""
OMPL_8ROOM_SUCCESS_TARGET = 0.95
"""Target: ompl.rrtconnect success rate in 10 s on 8room_000 problems from buckets >= 100."""


def ompl_motion_checks_per_second(count: int = 50_000) -> dict[str, float]:
    """Motion checks per CPU second of :class:`pathzoo_ompl.engine.SegmentValidator` on ``8room_000``.

    ``count`` random motions up to 8 cells long, as OMPL calls them
    (``SpaceInformation.checkMotion``, through the nanobind trampoline into
    Python and one compiled call) and as a direct Python call.
    """
    import numpy as np
    from ompl import base as ob

    from pathzoo_ompl.engine import SegmentValidator, _Run, _state_checker

    scenario = pathzoo.load_scenario(movingai_problem("8room_000"))
    space = ob.RealVectorStateSpace(2)
    space.setBounds(0.0, float(scenario.extent.max()))
    si = ob.SpaceInformation(space)
    si.setStateValidityChecker(_state_checker(scenario))
    budget = pathzoo.Budget()
    validator = SegmentValidator(si, scenario, _Run(budget, budget.start(), 1, None))
    si.setMotionValidator(validator)
    si.setup()
    rng = np.random.default_rng(0)
    a = rng.uniform(0.0, 1.0, (count, 2)) * scenario.extent
    b = np.clip(a + rng.uniform(-8.0, 8.0, (count, 2)) * scenario.cell_size, 0.0, scenario.extent)
    pairs = []
    for p, q in zip(a, b):
        s1, s2 = si.allocState(), si.allocState()
        s1[0], s1[1], s2[0], s2[1] = float(p[0]), float(p[1]), float(q[0]), float(q[1])
        pairs.append((s1, s2))
    out = {}
    for name, check in (("through OMPL", si.checkMotion), ("direct", validator.checkMotion)):
        started = time.process_time()
        for s1, s2 in pairs:
            check(s1, s2)
        out[name] = count / (time.process_time() - started)
    return out


def ompl_8room_success(problems: int, time_s: float) -> pd.DataFrame:
    """``ompl.rrtconnect`` (default parameters) on ``problems`` 8room_000 problems from buckets >= 100, one seed each."""
    import numpy as np

    ids = [sid for sid in get_registry().match("scenarios", "movingai.8room_000.*")
           if int(sid.split(".")[-2].lstrip("b")) >= 100]
    ids = sorted(ids, key=lambda sid: (int(sid.split(".")[-2].lstrip("b")), int(sid.split(".")[-1])))
    chosen = [ids[int(k)] for k in np.linspace(0, len(ids) - 1, problems)]
    planner = pathzoo.make_planner("ompl.rrtconnect")
    rows = []
    for k, sid in enumerate(chosen):
        scenario = pathzoo.load_scenario(sid)
        started = time.process_time()
        result = planner.plan(scenario, budget=pathzoo.Budget(time_s=time_s), rng=np.random.default_rng(k))
        cpu = time.process_time() - started
        ok = result.status.value == "solved" and bool(validate_path(scenario, result.path))
        checks = int(result.extras.get("motion_checks", 0))
        rows.append({"scenario": sid, "solved": ok, "motion checks": checks, "cpu (s)": cpu,
                     "checks per cpu s": checks / cpu if cpu > 0 else float("nan")})
    return pd.DataFrame(rows)


def anyangle_lower_bound(per_map: int, time_s: float) -> pd.DataFrame:
    """``exact.anyangle``'s optimum against every valid path of several planners on the 32x32 MovingAI maps."""
    import numpy as np

    from pathzoo.grid.reference import anyangle_length

    planners = ("exact.astar", "exact.thetastar", "exact.anyangle", "ompl.rrtconnect", "ompl.rrtstar", "swarm.cuckoo")
    rows = []
    for name in ("random-32-32-20", "room-32-32-4", "maze-32-32-2"):
        ids = sorted(get_registry().match("scenarios", f"movingai.{name}.*"))
        for sid in [ids[int(k)] for k in np.linspace(0, len(ids) - 1, per_map)]:
            scenario = pathzoo.load_scenario(sid)
            ref = anyangle_length(scenario)
            for pid in planners:
                params = {"simplify": True} if pid.startswith("ompl.") else {}
                result = pathzoo.make_planner(pid, **params).plan(
                    scenario, budget=pathzoo.Budget(time_s=time_s), rng=np.random.default_rng(0)
                )
                if result.status.value != "solved" or not validate_path(scenario, result.path):
                    continue
                length = float(np.hypot(*np.diff(result.path, axis=0).T).sum())
                rows.append({"scenario": sid, "planner": pid, "ratio": length / ref, "below": length < ref - 1e-9})
    return pd.DataFrame(rows)


def ompl_section(problems: int = 10, time_s: float = 10.0) -> int:
    """Print the OMPL and any-angle figures with their targets; exit status 1 if the lower bound is broken."""
    rates = ompl_motion_checks_per_second()
    for name, rate in rates.items():
        met = "met" if rate >= OMPL_MOTION_TARGET else "NOT met"
        print(f"OMPL motion checks per CPU second ({name}): {rate:,.0f}  (target >= {OMPL_MOTION_TARGET:,}: {met})")
    table = ompl_8room_success(problems, time_s)
    print(table.to_string(index=False))
    rate = table["solved"].mean()
    met = "met" if rate >= OMPL_8ROOM_SUCCESS_TARGET else "NOT met"
    print(f"ompl.rrtconnect on 8room_000 (buckets >= 100), {time_s:g} s: success {rate:.0%} "
          f"(target >= {OMPL_8ROOM_SUCCESS_TARGET:.0%}: {met}); "
          f"median motion checks per CPU s while planning {table['checks per cpu s'].median():,.0f}")
    bounds = anyangle_lower_bound(per_map=10, time_s=1.0)
    print(bounds.groupby("planner")["ratio"].agg(["count", "min", "median"]).to_string())
    broken = int(bounds["below"].sum())
    print(f"exact.anyangle never longer than a valid path: {'met' if broken == 0 else f'NOT met ({broken} shorter paths)'}")
    return 1 if broken else 0


if __name__ == "__main__":
    sys.exit(main())
