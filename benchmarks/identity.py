"""Bit-identity check of the ant-colony and exact planners: record fingerprints once, compare after a change.

Run from the repository root (``../shared`` must sit beside it)::

    python benchmarks/identity.py --record fingerprints.json   # on the untouched code
    python benchmarks/identity.py --check fingerprints.json    # after each change (exit 1 on a difference)
    python benchmarks/identity.py --check f.json --only aco.fgdaco,exact.astar

Every case is one ``plan()`` of a planner on a scenario with a seed and an
iteration budget. Its fingerprint is the status, iterations, evaluations,
ant-steps, the path's points (SHA-256 of their float64 bytes), the path length
and the planner's best cost, all exact (``repr`` of the floats). A speed-up
must leave every fingerprint unchanged. Timings are not fingerprinted.
"""

from __future__ import annotations

import argparse
import hashlib
import json
import sys
from pathlib import Path

import numpy as np

import pathzoo
from pathzoo import Budget, Scenario
from pathzoo.generators import random_obstacles

ACO = ("aco.as", "aco.mmas", "aco.acs", "aco.ggaco", "aco.gant", "aco.iaca", "aco.fgdaco", "aco.dsaco")
EXACT = ("exact.astar", "exact.dijkstra", "exact.thetastar")
SCENARIOS = (  # scenario id, iterations per ACO run
    ("random60", 6), ("gant.fig7", 10), ("gant.acopso", 10), ("gant.simple.1", 2), ("iaca.offroad", 8),
    ("ggaco.hugo", 6), ("ggaco.frontrange", 3), ("fgdaco.scenario1", 6), ("fgdaco.scenario2", 4),
    ("fgdaco.scenario3", 3), ("fgdaco.scenario1_static", 4), ("dsaco.complex", 6), ("dsaco.simple", 6),
    ("movingai.8room_000.b60.593", 2),
)
SEEDS = (0, 1, 7)
EXTRA = (  # planner, scenario id, parameters: non-default settings that take other kernel paths
    ("aco.ggaco", "ggaco.hugo", {"colony": "complete"}),
    ("aco.as", "random60", {"dead_end": "die"}),
    ("aco.mmas", "gant.fig7", {"n_ants": 3}),
    ("aco.dsaco", "dsaco.complex", {"step_rule": "longitude"}),
    ("exact.astar", "gant.simple.1", {"cost": "energy"}),
    ("exact.dijkstra", "gant.fig7", {"cost": "energy"}),
    ("exact.astar", "iaca.offroad", {"cost": "energy"}),
    ("exact.astar", "movingai.8room_000.b99.989", {}),
    ("exact.astar", "movingai.8room_000.b194.1939", {}),
    ("exact.dijkstra", "movingai.8room_000.b194.1939", {}),
    ("exact.thetastar", "movingai.8room_000.b194.1939", {}),
    ("exact.astar", "movingai.8room_000.b69.680", {}),  # problems of benchmarks/speed.py's A* rows
    ("exact.astar", "movingai.8room_000.b144.1430", {}),
    ("exact.dijkstra", "movingai.8room_000.b119.1180", {}),
    ("exact.astar", "movingai.arena.b15.150", {}),
    ("exact.thetastar", "movingai.arena.b15.150", {}),
    ("exact.zstar", "iaca.offroad", {}),  # Z*'s reduced costs can round below zero: negative heap keys
    ("exact.zstar", "ggaco.hugo", {}),
    ("exact.zstar", "gant.simple.1", {"max_climb_deg": 10.0}),
    ("aco.dsaco", "dsaco.simple", {"step_rule": "longitude", "n_ants": 3}),
    ("aco.dsaco", "dsaco.complex", {"alpha": 1.5, "q0_initial": 0.0}),
    ("aco.dsaco", "random60", {"dead_end": "die"}),
    ("aco.dsaco", "dsaco.complex", {"l_max": 60.0, "l_min": 2.0}),
    ("aco.dsaco", "dsaco.complex", {"max_steps": 30, "dead_end": "die"}),
    ("aco.as", "gant.fig7", {"n_ants": 100}),  # 400 walks one by one: the byte tabu stamps wrap after 255
    ("aco.gant", "gant.fig7", {"n_ants": 300}),  # more ants in a colony than byte stamps can tell apart
    ("aco.ggaco", "ggaco.case1", {"n_ants": 5}),  # a memory-mapped graph: pages released, walk geometry from cells
    ("aco.as", "gant.fig7", {"alpha": 0.5}),  # precomputed colony weights with a power of the trail
    ("aco.mmas", "random60", {"alpha": 1.5}),  # precomputed weights: power, floor and ceiling of the trail
    ("aco.iaca", "iaca.offroad", {"decr": 0.0}),  # precomputed weights of a node trail (no local update)
    ("aco.as", "gant.fig7", {"max_steps": 20}),  # the weighted kernel (walk_kernel.py): step caps,
    ("aco.gant", "gant.fig7", {"dead_end": "die"}),  # ants dropped at dead ends,
    ("aco.as", "dsaco.complex", {"dead_end": "die"}),  # the same under a turn limit,
    ("aco.mmas", "enclosed60", {}),  # a walled-off goal: the first ant exhausts the component, no other starts
    ("swarm.mosfla", "ggaco.hugo", {}),  # the route rivals of GGACO's table: random routes (noisy A*), leaps,
    ("search.movns", "ggaco.hugo", {}),  # neighbourhoods and objectives on terrain
    ("swarm.mosfla", "gant.simple.1", {}),  # and on a 500 x 500 grid
)
LONG = (  # planner, scenario id, parameters, iterations: whole runs (schedules, evaporation, p decay)
    ("aco.dsaco", "dsaco.complex", {}, 500),
    ("aco.dsaco", "dsaco.complex", {"step_rule": "longitude"}, 500),
    ("aco.dsaco", "dsaco.simple", {"rho": 0.9}, 300),
    ("aco.dsaco", "dsaco.complex", {"l_min": 1.01, "step_rule": "longitude"}, 100),
    ("aco.dsaco", "dsaco.complex", {"l_max": 70.0, "step_rule": "longitude"}, 60),
    ("aco.dsaco", "dsaco.complex", {"step_rule": "longitude", "q0_initial": 0.0, "alpha": 2.0}, 40),  # roulette only
    ("aco.dsaco", "dsaco.simple", {"step_rule": "longitude", "n_ants": 30}, 120),  # many steps back
    ("aco.dsaco", "dsaco.simple", {"n_ants": 20, "beta": 1.0}, 50),  # weak heuristic: long walks, deep levels
    ("aco.fgdaco", "fgdaco.scenario1", {}, 100),
    ("aco.fgdaco", "fgdaco.scenario3", {}, 100),
    ("aco.fgdaco", "fgdaco.trap", {}, 30),
    ("aco.fgdaco", "fgdaco.scenario2", {"sensing_m": 25.0, "alpha": 1.0}, 30),
    ("aco.fgdaco", "fgdaco.scenario3", {"n_ants": 3, "beta": 2.0}, 30),
    ("aco.fgdaco", "fgdaco.scenario3", {"rho": 0.3}, 30),  # an evaporation scale that is not a power of two
    ("aco.fgdaco", "fgdaco.scenario1", {"rho": 0.7, "tau_floor": 0.05}, 30),
)


def scenario(sid: str) -> Scenario:
    """A registered scenario, the generated 60 x 60 random grid ``random60`` (its start is walled in), or
    ``enclosed60``: an open 60 x 60 grid whose goal corner is walled off."""
    if sid in ("random60", "enclosed60"):
        if sid == "random60":
            occ = random_obstacles((60, 60), seed=3, density=0.25)
            occ[0, 0] = occ[-1, -1] = False
        else:
            occ = np.zeros((60, 60), dtype=bool)
            occ[-3, -3:] = occ[-3:, -3] = True
        return Scenario(id=sid, kind="grid2d", occupancy=occ, cell_size=1.0, start=(0.5, 0.5), goal=(59.5, 59.5))
    return pathzoo.load_scenario(sid)


def fingerprint(planner_id: str, s: Scenario, seed: int, iterations: int | None, params: dict) -> dict:
    """The exact outcome of one ``plan()`` call."""
    planner = pathzoo.make_planner(planner_id, **params)
    budget = Budget() if iterations is None else Budget(iterations=iterations)
    r = planner.plan(s, budget=budget, rng=np.random.default_rng(seed))
    path = np.ascontiguousarray(r.path, dtype=np.float64) if r.solved else np.zeros((0, 2))
    length = float(np.linalg.norm(np.diff(path, axis=0), axis=1).sum()) if len(path) > 1 else 0.0
    return {"status": str(r.status), "iterations": r.iterations, "evaluations": r.evaluations,
            "ant_steps": r.extras.get("ant_steps"), "points": len(path),
            "path_sha": hashlib.sha256(path.tobytes()).hexdigest(), "length": repr(length),
            "best_cost": repr(r.extras.get("best_cost"))}


def cases(only: set[str] | None):
    """(key, planner id, scenario id, seed, iterations, params) of every case."""
    for sid, iters in SCENARIOS:
        s = scenario(sid)
        for pid in ACO + EXACT:
            if only and pid not in only:
                continue
            if s.kind not in pathzoo.make_planner(pid).kinds:
                continue
            for seed in SEEDS if pid in ACO else (0,):
                yield f"{pid}|{sid}|{seed}|{iters}", pid, s, seed, iters if pid in ACO else None, {}
    for pid, sid, params in EXTRA:
        if only and pid not in only:
            continue
        s = scenario(sid)
        for seed in SEEDS:
            yield f"{pid}|{sid}|{seed}|{json.dumps(params, sort_keys=True)}", pid, s, seed, 4, params
    for pid, sid, params, iters in LONG:
        if only and pid not in only:
            continue
        s = scenario(sid)
        for seed in SEEDS:
            yield f"{pid}|{sid}|{seed}|{iters}|{json.dumps(params, sort_keys=True)}", pid, s, seed, iters, params


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    mode = parser.add_mutually_exclusive_group(required=True)
    mode.add_argument("--record", type=Path, help="write the fingerprints to this JSON file")
    mode.add_argument("--check", type=Path, help="compare with the fingerprints in this JSON file")
    parser.add_argument("--only", help="comma-separated planner ids")
    args = parser.parse_args(argv)
    only = set(args.only.split(",")) if args.only else None
    got = {key: fingerprint(pid, s, seed, iters, params) for key, pid, s, seed, iters, params in cases(only)}
    if args.record:
        args.record.write_text(json.dumps(got, indent=1, sort_keys=True))
        print(f"recorded {len(got)} cases in {args.record}")
        return 0
    want = json.loads(args.check.read_text())
    bad = [key for key in got if want.get(key) != got[key]]
    for key in bad:
        print(f"DIFFERS {key}\n  was {want.get(key)}\n  now {got[key]}")
    print(f"{len(got) - len(bad)} of {len(got)} cases identical")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
