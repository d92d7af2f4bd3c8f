"""A script without a main guard, with a planner class of its own, runs under the default (process) executor.

Before issue 11 every worker re-imported ``__main__`` and the harness stopped
with ``WorkerStartError``; planners defined in ``__main__`` were unknown to workers.
"""

from __future__ import annotations

import subprocess
import sys

import pytest

SCRIPT = '''
import sys
import numpy as np
import pathzoo
from pathzoo import PlanResult, Planner, Status, hookimpl
from pathzoo.grid.reference import reference_path
from pathzoo.plugins.manager import get_registry


class Mine(Planner):
    id = "script.mine"
    summary = "a planner defined in the script"
    kinds = frozenset({"grid2d"})

    def plan(self, scenario, *, budget, rng, progress=None):
        return PlanResult(Status.SOLVED, path=reference_path(scenario).path.copy(), iterations=1, evaluations=1)


class Plugin:
    @hookimpl
    def pathzoo_register_planners(self):
        return [Mine]


get_registry().add_plugin(Plugin(), "script-plugin")
runs = pathzoo.run(["exact.astar", "script.mine"], ["movingai.arena.b0.1"], seeds=2, db="r.sqlite", jobs=2)
print("RESULT", sorted(runs.status), runs.isolated.all())
'''


@pytest.mark.slow
@pytest.mark.parametrize("how", ["file", "stdin"])
def test_unguarded_script_with_its_own_planner(tmp_path, how):
    script = tmp_path / "script.py"
    script.write_text(SCRIPT)
    argv = [sys.executable, str(script)] if how == "file" else [sys.executable, "-"]
    done = subprocess.run(argv, input=None if how == "file" else SCRIPT, cwd=tmp_path, capture_output=True,
                          text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    assert "RESULT ['solved', 'solved', 'solved', 'solved'] True" in done.stdout
