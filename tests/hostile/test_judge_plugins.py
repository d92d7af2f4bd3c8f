"""A third-party planner plugin whose import has a side effect: the judge process never imports it.

A fake distribution ``evil-plugin`` is installed on ``PYTHONPATH`` (a
``.dist-info`` folder with its entry points) with three modules, each of
which appends ``<module> <process name>`` to a marker file when imported:

- ``evil_plugin.planners`` under ``pathzoo.planners`` (planner ``evil.astar``);
- ``evil_plugin.legacy`` under the old single group ``pathzoo`` (planner
  ``evil.legacy``; its scenario hook is ignored);
- ``evil_plugin.scenarios`` under ``pathzoo.scenarios`` (scenario ``evil.wall``),
  the positive control: the judge does import it, so the marker works there.

An experiment runs both planners on ``evil.wall`` in a fresh interpreter; the
judge process (named ``pathzoo-judge``) must appear in the marker file for
the scenario module and never for the planner modules.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

_MARK = """\
import multiprocessing, os
with open(os.environ["EVIL_PLUGIN_MARKER"], "a") as _f:
    _f.write(f"{__name__} {multiprocessing.current_process().name}\\n")
"""


def _planner_module(planner_id: str, summary: str, extra: str = "") -> str:
    """Source of a plugin module that records its import and registers an A* under ``planner_id``."""
    return _MARK + f"""
import pathzoo
from pathzoo_exact.astar import AStarPlanner


class Evil(AStarPlanner):
    id = "{planner_id}"
    summary = "{summary}"


@pathzoo.hookimpl
def pathzoo_register_planners():
    return [Evil]
{extra}"""


_PLANNERS = _planner_module("evil.astar", "A* from a plugin with an import-time side effect")
_LEGACY = _planner_module("evil.legacy", "A* from a plugin of the old single entry-point group", """
@pathzoo.hookimpl
def pathzoo_register_scenarios():
    raise AssertionError("the scenarios hook of a 'pathzoo' group plugin is never called")
""")

_SCENARIOS = _MARK + """
import pathzoo
from evil_plugin.wall import wall


@pathzoo.hookimpl
def pathzoo_register_scenarios():
    return [pathzoo.ScenarioEntry("evil.wall", "6 x 6 wall with a gap", wall, "grid2d")]
"""

_WALL = _MARK + """
import multiprocessing, os, sys
import numpy as np
from pathzoo import Scenario


def wall():
    held = ",".join(sorted(m for m in sys.modules if m.startswith("evil_plugin")))
    with open(os.environ["EVIL_PLUGIN_MARKER"], "a") as f:
        f.write(f"holds:{held} {multiprocessing.current_process().name}\\n")
    occ = np.zeros((6, 6), bool)
    occ[1:, 3] = True
    return Scenario(id="evil.wall", kind="grid2d", occupancy=occ, cell_size=1.0, start=(0.5, 5.5), goal=(5.5, 5.5))
"""

_ENTRY_POINTS = """\
[pathzoo.planners]
evil = evil_plugin.planners

[pathzoo]
evil_legacy = evil_plugin.legacy

[pathzoo.scenarios]
evil = evil_plugin.scenarios
"""

_RUN = """
import json, sys
import pathzoo
runs = pathzoo.run(["evil.astar", "evil.legacy", "exact.astar"], ["evil.wall"], seeds=1, db=sys.argv[1],
                   executor=sys.argv[2], jobs=1, progress=False)
print(json.dumps(dict(zip(runs.planner, runs.status))))
"""


def _install(root: Path) -> None:
    package = root / "evil_plugin"
    package.mkdir()
    for name, text in {"__init__": "", "planners": _PLANNERS, "legacy": _LEGACY, "scenarios": _SCENARIOS,
                       "wall": _WALL}.items():
        (package / f"{name}.py").write_text(text)
    info = root / "evil_plugin-1.0.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: evil-plugin\nVersion: 1.0\n")
    (info / "entry_points.txt").write_text(_ENTRY_POINTS)


@pytest.mark.parametrize("executor", ["process", pytest.param("inline", marks=pytest.mark.slow)])
def test_the_judge_never_imports_a_planner_plugin(tmp_path, executor):
    site = tmp_path / "site"
    site.mkdir()
    _install(site)
    marker = tmp_path / "imports.txt"
    env = {**os.environ, "EVIL_PLUGIN_MARKER": str(marker),
           "PYTHONPATH": os.pathsep.join([str(site), *filter(None, [os.environ.get("PYTHONPATH")])])}
    done = subprocess.run([sys.executable, "-c", textwrap.dedent(_RUN), str(tmp_path / "r.sqlite"), executor],
                          env=env, cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    statuses = json.loads(done.stdout.strip().splitlines()[-1])
    assert statuses == {"evil.astar": "solved", "evil.legacy": "solved", "exact.astar": "solved"}, done.stderr
    lines = [line.split(" ", 1) for line in marker.read_text().splitlines()]
    imports = [(module, process) for module, process in lines if not module.startswith("holds:")]
    held = {module for module, process in lines if module.startswith("holds:") and process == "pathzoo-judge"}
    judged = {module for module, process in imports if process == "pathzoo-judge"}
    # the control: the judge's own imports are recorded
    assert judged == {"evil_plugin.scenarios", "evil_plugin.wall"}, imports
    # and nothing it inherited holds planner code (a judge forked from a server that imported them would)
    assert held == {"holds:evil_plugin,evil_plugin.scenarios,evil_plugin.wall"}, lines
    assert {module for module, _ in imports} == {"evil_plugin.planners", "evil_plugin.legacy",
                                                "evil_plugin.scenarios", "evil_plugin.wall"}
