"""Declaring external planners: experiment-file tables, packages' entry points, versions, pickling."""

from __future__ import annotations

import importlib.metadata as md
import pickle
import shutil
import sys
from pathlib import Path

import pytest

import pathzoo
from pathzoo.core.errors import ExternalPlannerError, InvalidExperimentError
from pathzoo.harness import Experiment
from pathzoo.harness.specs import planner_by_value
from pathzoo.plugins.external import EXPERIMENT_FILES, ExternalPlanner, declare
from pathzoo.plugins.manager import discover, get_registry

from .conftest import PROGRAMS

HEAD = '[experiment]\nname = "x"\nseeds = 1\nscenarios = ["gant.fig7"]\n'


def _write(tmp_path: Path, planner: str) -> Path:
    path = tmp_path / "x.toml"
    path.write_text(HEAD + "\n[[planner]]\n" + planner)
    return path


@pytest.mark.parametrize(("table", "error"), [
    ('command = ["a"]\noctave = "b.m"\n', "give exactly one of command and octave"),
    ('octave = "missing.m"\n', "octave: no function file"),
    ('octave = "planner.py"\n', "octave must name a function file ending in .m"),
    ('command = []\n', "command must be a list of non-empty strings"),
    ('command = ["a"]\nkinds = ["grid3d"]\n', "kinds must be a non-empty list of grid2d, terrain, air3d, dynamic"),
    ('command = ["a"]\nparams = { when = 1979-05-27 }\n', "params ['when']: a value must be a string, number"),
    ('command = ["a"]\nid = "x.y"\n', "unknown key(s) ['id']; allowed with command or octave"),
    ('command = ["a"]\nlabel = " "\n', "label must be a non-empty string"),
    ('command = ["a"]\npath_model = "free"\n', "path_model must be one of grid, anyangle, timed, got 'free'"),
])
def test_bad_tables_name_the_file_and_the_planner(tmp_path, table, error):
    path = _write(tmp_path, table)
    with pytest.raises(InvalidExperimentError) as info:
        Experiment.from_toml(path)
    assert str(info.value).startswith(f"{path}: field 'planner[0]': ") and error in str(info.value)


def test_paths_are_relative_to_the_experiment_file_and_params_are_sent(tmp_path):
    (tmp_path / "bin").mkdir()
    program = tmp_path / "bin" / "plan.sh"
    program.write_text("#!/bin/sh\n")
    path = _write(tmp_path, 'command = ["bin/plan.sh", "--fast"]\nlabel = "My Planner"\nparams = { n = 3, w = 0.5 }\n')
    exp = Experiment.from_toml(path)
    spec = exp.planners[0]
    assert (spec.id, spec.name, dict(spec.params)) == ("external.my-planner", "My Planner", {"n": 3, "w": 0.5})
    declaration = get_registry().get("planners", spec.id).provided
    assert declaration.command == (str(program), "--fast") and declaration.path_model == "grid"
    cls = spec.planner_class
    assert cls.kinds == frozenset({"grid2d"}) and cls.program.files() == [program]
    assert planner_by_value(cls)  # workers cannot import a class made at run time: it travels by value
    old = cls.version
    program.write_text("#!/bin/sh\necho changed\n")
    with pytest.raises(ExternalPlannerError, match="external.my-planner: its files changed since the experiment"):
        cls.program.check_unchanged(cls.id, cls.version)
    assert Experiment.from_toml(path).planners[0].planner_class.version != old  # read again: a new version


def test_an_installed_planner_id_cannot_be_taken():
    registry = get_registry()
    taken = ExternalPlanner("exact.astar", "clash", command=("true",))
    with pytest.raises(InvalidExperimentError, match="'exact.astar' is the id of a planner of the plugin exact"):
        declare(registry, taken)
    declare(registry, ExternalPlanner("external.twice", "first", command=("true",)))
    declare(registry, ExternalPlanner("external.twice", "second", command=("false",)))  # a file read again
    assert registry.get("planners", "external.twice").summary == "second"
    assert registry.get("planners", "external.twice").plugin == EXPERIMENT_FILES


def test_a_package_declares_octave_planners_through_its_entry_point():
    ep = md.EntryPoint("octpkg", "external_planners.octave_package", "pathzoo.planners")
    registry = discover([ep], kinds=("planners",))
    assert not registry.failures
    entry = registry.get("planners", "octpkg.shortest")
    assert entry.declared("kinds") == frozenset({"grid2d"}) and entry.summary.startswith("Random-tie")
    cls = entry.obj
    assert cls.params["unused"].default == 1 and len(cls.version) == 12
    planner = cls(unused=4)
    copy = pickle.loads(pickle.dumps(planner))
    assert type(copy).id == "octpkg.shortest" and copy.get_params() == {"unused": 4}


@pytest.mark.skipif(shutil.which("octave-cli") is None, reason="GNU Octave is not installed (CI installs it)")
def test_the_conformance_kit_passes_an_octave_planner():
    from pathzoo.testing import check_planner

    declaration = ExternalPlanner.from_table({"octave": "shortest.m", "kinds": ["grid2d", "dynamic"]}, PROGRAMS)
    check_planner(declaration.load())


def test_a_python_command_planner_plans_in_this_process(tmp_path):
    script = tmp_path / "line.py"
    script.write_text(
        "import json, sys\n"
        "p = json.load(sys.stdin)\n"
        "print(json.dumps({'status': 'solved', 'path': [p['start'], p['goal']], 'iterations': 1,\n"
        "                  'history': [[1, 1, None]], 'message': str(p['params']['k'])}))\n"
        "print('hello', file=sys.stderr)\n")
    declaration = ExternalPlanner.from_table({"command": [sys.executable, "line.py"], "params": {"k": 7}}, tmp_path)
    planner = declaration.load()()
    scenario = pathzoo.load_scenario("gant.fig7")
    points = []
    result = planner.plan(scenario, budget=pathzoo.Budget(time_s=30), rng=__import__("numpy").random.default_rng(0),
                          progress=lambda i, e, c: points.append((i, e, c)))
    assert result.status.value == "solved" and result.path.tolist() == [[0.5, 0.5], [9.5, 9.5]]
    assert result.message == "7\nstandard error:\nhello"
    assert points == [(1, 1, float("inf"))]


@pytest.mark.skipif(shutil.which("octave-cli") is None, reason="GNU Octave is not installed (CI installs it)")
def test_one_octave_process_serves_every_run_and_the_seed_decides_the_path():
    import numpy as np

    from pathzoo_external.octave import octave_server

    planner = ExternalPlanner.from_table({"octave": "shortest.m"}, PROGRAMS).load()()
    scenario = pathzoo.load_scenario("gant.fig7")

    def path(seed: int) -> list[list[float]]:
        result = planner.plan(scenario, budget=pathzoo.Budget(time_s=30), rng=np.random.default_rng(seed))
        return result.path.tolist()

    first = path(0)
    pid = octave_server().proc.pid
    paths = [path(seed) for seed in range(1, 6)]
    assert octave_server().proc.pid == pid  # started once, not once per run
    assert path(0) == first  # same seed, same path, after other runs in the same Octave process
    assert len({str(p) for p in [first, *paths]}) > 1  # the seed picks among the shortest paths


def test_a_declared_path_model_picks_the_reference_of_the_analysis(tmp_path):
    from pathzoo.analysis.path_models import path_models

    path = _write(tmp_path, 'command = ["a"]\nlabel = "any"\npath_model = "anyangle"\n')
    spec = Experiment.from_toml(path).planners[0]
    assert path_models([spec.id]) == {spec.id: "anyangle"}
