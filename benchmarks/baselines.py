"""Baselines against the exact planners: median planning time and length ratio to the optimum.

Run from the repository root (the scenario packs must be installed)::

    python benchmarks/baselines.py                    # 3 seeds, 2 s per run, 2 worker processes
    python benchmarks/baselines.py --seeds 5 --time 5 --jobs 4
    python benchmarks/baselines.py --quick            # 1 seed, 1 s, small scenarios only

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
from pathlib import Path

import pandas as pd

import pathzoo
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
    args = parser.parse_args(argv)
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


if __name__ == "__main__":
    sys.exit(main())
