"""After a plain ``pip install .`` (no extras) every planner listed as available really plans.

The optional packages of every extra are made unimportable in a fresh
interpreter (``sys.modules[name] = None``, as if never installed).
"""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap

import pytest

EXTRAS_MODULES = ("ompl", "pyswarms", "deap", "networkx", "pymoo", "dask", "distributed", "rasterio", "pyproj",
                  "optuna")

_PRELUDE = f"import sys\nfor _m in {EXTRAS_MODULES!r}:\n    sys.modules[_m] = None\n"


def without_extras(code: str, *argv: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-c", _PRELUDE + textwrap.dedent(code), *argv], capture_output=True,
                          text=True, timeout=600)


def test_planners_needing_an_extra_are_listed_unavailable():
    done = without_extras("from pathzoo.cli.main import main\nsys.exit(main(['list', 'planners']))")
    assert done.returncode == 0, done.stderr
    rows = {line.split()[0]: line for line in done.stdout.splitlines()[2:] if line.strip()}
    ompl = [pid for pid in rows if pid.startswith("ompl.")]
    assert len(ompl) == 7
    for pid in ompl:
        assert 'unavailable, needs ompl: pip install "pathzoo[ompl]"' in rows[pid], rows[pid]
    for pid in ("swarm.mosfla", "search.movns"):  # their NSGA-II order is compiled in pathzoo_rivals.pareto, not pymoo's
        assert "unavailable" not in rows[pid], rows[pid]


@pytest.mark.slow
def test_every_planner_listed_as_available_plans_without_the_extras():
    """The bug: ompl.* and swarm.mosfla were listed as available, and every run crashed with ModuleNotFoundError."""
    done = without_extras("""
        import json
        import numpy as np
        from pathzoo import Budget, make_planner
        from pathzoo.plugins.manager import get_registry
        from pathzoo.testing import check_scenario

        report = {}
        for pid, entry in sorted(get_registry().planners.items()):
            if entry.unavailable:
                report[pid] = "unavailable"
                continue
            kinds = entry.declared("kinds") or entry.obj.kinds
            scenario = check_scenario("grid2d" if "grid2d" in kinds else sorted(kinds)[0])
            try:
                result = make_planner(pid).plan(scenario, budget=Budget(iterations=2, evaluations=20),
                                                rng=np.random.default_rng(0))
                report[pid] = str(result.status.value)
            except ImportError as exc:
                report[pid] = f"ImportError: {exc}"
        print(json.dumps(report))
    """)
    assert done.returncode == 0, done.stderr[-2000:]
    report = json.loads(done.stdout.strip().splitlines()[-1])
    broken = {pid: r for pid, r in report.items() if r.startswith("ImportError")}
    assert broken == {}
    unavailable = {pid for pid, r in report.items() if r == "unavailable"}
    assert {"swarm.pso", "evo.ga"} <= unavailable
    assert report["swarm.mosfla"] == report["search.movns"] == "solved"  # no pymoo needed (pathzoo_rivals.pareto)
    assert {p for p in report if p.startswith("ompl.")} <= unavailable
    assert "exact.astar" not in unavailable
