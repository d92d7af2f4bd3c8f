"""The example third-party plugin installs with pip, shows up in ``pathzoo list`` and runs in an experiment."""

from __future__ import annotations

import importlib.metadata as md
import importlib.util
import os
import shutil
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from pathzoo.harness.store import read_runs
from installed_by_tests import environment_lock, mark_installed_by_tests

EXAMPLE = Path(__file__).resolve().parents[1] / "examples" / "pathzoo-greedy"
PATHZOO = Path(sys.executable).parent / "pathzoo"
DIST = "pathzoo-greedy"

SCENARIO = """
id = "example.rooms"
kind = "grid2d"
description = "24x24 rooms"
endpoint_seed = 2

[map]
generator = "rooms"
seed = 5
shape = [24, 24]
room_size = 6
"""

EXPERIMENT = """
[experiment]
name = "greedy-vs-astar"
seeds = 2
budget = { time_s = 5.0 }
scenarios = ["rooms.toml"]

[[planner]]
id = "greedy.best_first"

[[planner]]
id = "exact.astar"
"""


def _installed() -> bool:
    try:
        md.distribution(DIST)
    except md.PackageNotFoundError:
        return False
    return True


def _build_isolation_flags() -> list[str]:
    """Build offline with the environment's setuptools when it can make wheels, else let pip fetch it.

    setuptools makes wheels itself from 70.1 on; older ones need the ``wheel``
    package (a fresh Python 3.11 venv has setuptools 65 and no ``wheel``).
    """
    if importlib.util.find_spec("setuptools") is None:
        return []
    version = tuple(int(p) for p in md.version("setuptools").split(".")[:2] if p.isdigit())
    if version >= (70, 1) or importlib.util.find_spec("wheel") is not None:
        return ["--no-build-isolation"]
    return []


def _clean_env() -> dict[str, str]:
    """The environment without pytest/xdist variables, for nested commands."""
    return {k: v for k, v in os.environ.items() if not k.startswith(("PYTEST_", "COV_"))}


@pytest.fixture(scope="module")
def greedy_copy(tmp_path_factory):
    """The example distribution, pip-installed from a copy (the source tree stays clean).

    Under ``pytest -n`` several workers may need the plugin at once, so the
    install happens once per environment under a file lock, and only the end
    of the whole session uninstalls it (``tests/conftest.py``): a worker that
    finishes early must not remove it while another worker's experiment runs.
    """
    copy = tmp_path_factory.mktemp("example") / "pathzoo-greedy"
    shutil.copytree(EXAMPLE, copy, ignore=shutil.ignore_patterns("build", "*.egg-info", "__pycache__"))
    with environment_lock():
        if not _installed():
            cmd = [sys.executable, "-m", "pip", "install", "--quiet", "--no-deps", *_build_isolation_flags(), str(copy)]
            proc = subprocess.run(cmd, capture_output=True, text=True, env=_clean_env())
            assert proc.returncode == 0, proc.stdout + proc.stderr
            mark_installed_by_tests(DIST)
    return copy


@pytest.mark.slow
def test_list_shows_the_plugin_with_its_distribution_and_version(greedy_copy):
    version = tomllib.loads((greedy_copy / "pyproject.toml").read_text())["project"]["version"]
    proc = subprocess.run([str(PATHZOO), "list", "planners"], capture_output=True, text=True, env=_clean_env())
    assert proc.returncode == 0, proc.stderr
    rows = [ln.split() for ln in proc.stdout.splitlines() if ln.startswith("greedy.best_first ")]
    assert len(rows) == 1
    assert rows[0][1:4] == ["grid2d,terrain", DIST, version]
    assert "skipped: greedy" not in proc.stderr


@pytest.mark.slow
def test_the_plugin_runs_in_an_experiment(greedy_copy, tmp_path):
    (tmp_path / "rooms.toml").write_text(SCENARIO)
    (tmp_path / "exp.toml").write_text(EXPERIMENT)
    db = tmp_path / "results.sqlite"
    cmd = [str(PATHZOO), "run", str(tmp_path / "exp.toml"), "--db", str(db), "--jobs", "1", "--no-progress"]
    proc = subprocess.run(cmd, capture_output=True, text=True, env=_clean_env())
    assert proc.returncode == 0, proc.stderr
    assert "greedy.best_first" in proc.stdout and "example.rooms" in proc.stdout
    runs = read_runs(db, "greedy-vs-astar")
    greedy = runs[runs["planner"] == "greedy.best_first"]
    optimal = runs[runs["planner"] == "exact.astar"]
    assert len(greedy) == 2 and len(optimal) == 2
    assert (greedy["status"] == "solved").all() and greedy["valid"].all(), greedy["message"].tolist()  # validated by the harness
    assert (greedy["length"] >= optimal["length"].min() - 1e-9).all()  # greedy is never shorter than optimal


@pytest.mark.slow
def test_the_plugins_own_suite_passes_with_the_conformance_kit(greedy_copy):
    cmd = [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", str(greedy_copy / "tests")]
    proc = subprocess.run(cmd, capture_output=True, text=True, cwd=greedy_copy, env=_clean_env())
    assert proc.returncode == 0, proc.stdout[-3000:]
    last = proc.stdout.strip().splitlines()[-1]
    assert " passed" in last and "failed" not in last
    assert int(last.split()[0]) > 20  # the kit's parametrized checks ran
