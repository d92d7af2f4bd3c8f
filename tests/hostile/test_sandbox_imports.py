"""What the import system resolves is visible inside the sandbox: editable installs under /tmp included.

The sandbox mounts an empty ``/tmp``; an editable install's source folder is
not on ``sys.path`` (its finder maps package names to folders), so the
sandbox binds the folders the import system resolves
(:func:`pathzoo.harness.sandbox.import_roots`), and names the folder and the
cause in one line when a module still cannot be seen.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import sysconfig
import types
from pathlib import Path

import pytest

from pathzoo.harness.experiment import Experiment
from pathzoo.harness.sandbox import import_problem, import_roots, sandbox_problem, sandboxed_command
from pathzoo.harness.store import read_runs

PACKAGES = {"pathzoo": "pathzoo", "pathzoo_aco": "plugins/pathzoo_aco", "pathzoo_baselines": "plugins/pathzoo_baselines",
            "pathzoo_exact": "plugins/pathzoo_exact", "pathzoo_external": "plugins/pathzoo_external",
            "pathzoo_ompl": "plugins/pathzoo_ompl", "pathzoo_rivals": "plugins/pathzoo_rivals",
            "pathzoo_scenarios": "scenarios/pathzoo_scenarios"}

FINDER = '''
import sys
from importlib.machinery import PathFinder

MAPPING = {mapping!r}


class _EditableFinder:
    """setuptools' editable finder, reduced: a package name to its source folder, outside sys.path."""

    @classmethod
    def find_spec(cls, fullname, path=None, target=None):
        if fullname in MAPPING:
            return PathFinder.find_spec(fullname, [MAPPING[fullname].rsplit("/", 1)[0]])
        return None


def install():
    sys.meta_path.insert(0, _EditableFinder)  # first, so this copy wins over any other install
'''


def test_import_roots_include_the_folders_an_editable_finder_maps(tmp_path, monkeypatch):
    source = tmp_path / "src" / "probe_pkg"
    source.mkdir(parents=True)
    finder_module = types.ModuleType("__editable___probe_finder")
    finder_module.MAPPING = {"probe_pkg": str(source)}  # type: ignore[attr-defined]
    finder_module.NAMESPACES = {"probe_pkg.data": [str(tmp_path / "data")]}  # type: ignore[attr-defined]
    finder = type("_EditableFinder", (), {"__module__": "__editable___probe_finder"})
    monkeypatch.setitem(sys.modules, "__editable___probe_finder", finder_module)
    monkeypatch.setattr(sys, "meta_path", [*sys.meta_path, finder])
    roots = import_roots()
    assert str(source) in roots and str(tmp_path / "data") in roots
    assert str(source) not in sys.path
    if shutil.which("bwrap"):
        args = sandboxed_command(["/bin/true"], procs_files=(), scratch=tmp_path / "scratch",
                                 numba_cache=tmp_path / "numba")
        binds = {(args[i + 1], args[i + 2]) for i, a in enumerate(args) if a == "--ro-bind"}
        assert (os.path.realpath(source), os.path.realpath(source)) in binds


def test_a_module_the_sandbox_cannot_see_is_named_with_its_folder(tmp_path, monkeypatch):
    (tmp_path / "zzprobe_hidden").mkdir()
    (tmp_path / "zzprobe_hidden" / "__init__.py").write_text("")
    monkeypatch.syspath_prepend(str(tmp_path))
    message = import_problem("Traceback ...\nModuleNotFoundError: No module named 'zzprobe_hidden'\n")
    folder = os.path.realpath(tmp_path / "zzprobe_hidden")
    assert message.startswith(f"module 'zzprobe_hidden' is in {folder}, under ") and "which the sandbox hides" in message
    assert "\n" not in message
    assert import_problem("No module named 'zz_nowhere_at_all'") == (
        "module 'zz_nowhere_at_all' cannot be imported (not in this Python either)")
    assert import_problem("ValueError: bad parameter") == ""


@pytest.mark.slow
@pytest.mark.skipif(bool(sandbox_problem()), reason=f"no OS sandbox here: {sandbox_problem()}")
def test_an_editable_install_under_tmp_runs_the_default_experiment_sandboxed(tmp_path):
    """A venv and an editable finder under /tmp whose sources are a copy under /tmp: the default experiment's
    planners run sandboxed (on its first scenario, one seed, to keep the test short)."""
    repo = Path(__file__).resolve().parents[2]  # the checkout (pathzoo itself may be installed, not editable)
    src, venv = tmp_path / "src", tmp_path / "venv"
    for name, rel in PACKAGES.items():
        shutil.copytree(repo / rel, src / rel, ignore=shutil.ignore_patterns("__pycache__"))
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True)
    site = Path(subprocess.run([str(venv / "bin" / "python"), "-c", "import sysconfig; print(sysconfig.get_paths()"
                                "['purelib'])"], capture_output=True, text=True, check=True).stdout.strip())
    (site / "deps.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")  # numpy & co. and the entry points
    mapping = {name: str(src / rel) for name, rel in PACKAGES.items()}
    (site / "__editable___pathzoo_copy_finder.py").write_text(FINDER.format(mapping=mapping))
    (site / "__editable__.pathzoo_copy.pth").write_text(
        "import __editable___pathzoo_copy_finder; __editable___pathzoo_copy_finder.install()\n")
    default = (repo / "pathzoo" / "experiments" / "default.toml").read_text()
    first = re.search(r'^scenarios = \[\s*"([^"]+)"', default, re.M)
    assert first is not None
    experiment = tmp_path / "default1.toml"
    experiment.write_text(re.sub(r"^seeds = \d+", "seeds = 1",
                                 re.sub(r"^scenarios = \[.*?\]", f'scenarios = ["{first.group(1)}"]', default,
                                        flags=re.M | re.S), flags=re.M))
    python = str(venv / "bin" / "python")
    where = subprocess.run([python, "-c", "import pathzoo, pathzoo_aco; print(pathzoo.__file__, pathzoo_aco.__file__)"],
                           capture_output=True, text=True, check=True).stdout.split()
    assert all(w.startswith(str(src)) for w in where), where  # the copy under /tmp is what runs
    assert str(src) not in subprocess.run([python, "-c", "import sys; print(sys.path)"], capture_output=True,
                                          text=True, check=True).stdout  # reached through the finder only
    db = tmp_path / "r.sqlite"
    done = subprocess.run([python, "-c", "import sys; from pathzoo.cli.main import main; sys.exit(main())", "run",
                           str(experiment), "--require-sandbox", "--db", str(db), "--no-progress"],
                          capture_output=True, text=True, timeout=900, cwd=tmp_path)
    assert done.returncode == 0, done.stderr[-3000:]
    runs = read_runs(db)
    assert len(runs) == len(Experiment.from_toml(experiment).tasks())  # every planner that takes the scenario's kind
    assert runs["sandboxed"].all() and (runs["status"] == "solved").all()
