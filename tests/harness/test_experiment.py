"""Experiments from Python and TOML: resolution, run keys, seeds, skipped pairs and one-line errors."""

from __future__ import annotations

import hashlib
import pytest

from pathzoo import Budget, InvalidExperimentError, InvalidParameterError, UnknownPluginError
from pathzoo.harness.experiment import Experiment
from pathzoo.harness.specs import PlannerSpec, run_key, run_seed


def test_build_resolves_planners_scenarios_and_defaults(forged):
    exp = Experiment.build(planners=["test.honest", forged.Honest(delay_s=0.5), ("test.sabotage", {"how": "exit"})],
                           scenarios=["test.w*", forged.street_scenario()], seeds=3)
    assert [(p.id, dict(p.params)) for p in exp.planners] == [
        ("test.honest", {"delay_s": 0.0}), ("test.honest", {"delay_s": 0.5}), ("test.sabotage", {"how": "exit"})]
    assert [(s.id, s.source) for s in exp.scenarios] == [("test.wall", "registry"), ("test.street", "object")]
    assert exp.seeds == (0, 1, 2) and exp.budget == Budget() and exp.timeout_s == 300.0
    no_time = Experiment.build(planners=["test.honest"], scenarios=["test.wall"], budget=Budget(iterations=5))
    assert no_time.timeout_s == 300


def test_run_keys_and_seeds_are_deterministic(forged):
    exp = Experiment.build(planners=["test.honest"], scenarios=["test.wall"], seeds=[4, 7], seed=11)
    tasks = exp.tasks()
    phash = PlannerSpec.of("test.honest").params_hash
    assert [t.run_key for t in tasks] == [f"test.honest|{phash}|test.wall|4", f"test.honest|{phash}|test.wall|7"]
    assert tasks[0].run_key == run_key("test.honest", phash, "test.wall", 4)
    digest = hashlib.sha256(f"11:{tasks[0].run_key}".encode()).digest()
    assert tasks[0].seed == int.from_bytes(digest[:8], "little") >> 1 == run_seed(11, tasks[0].run_key)
    again = Experiment.build(planners=["test.honest"], scenarios=["test.wall"], seeds=[4, 7], seed=11).tasks()
    assert [t.seed for t in again] == [t.seed for t in tasks]
    other = Experiment.build(planners=["test.honest"], scenarios=["test.wall"], seeds=[4, 7], seed=12).tasks()
    assert [t.run_key for t in other] == [t.run_key for t in tasks]
    assert {t.seed for t in other}.isdisjoint(t.seed for t in tasks)
    # defaults spelled out give the same key; another parameter value gives another
    assert PlannerSpec.of(("test.honest", {"delay_s": 0.0})).params_hash == phash
    assert PlannerSpec.of(("test.honest", {"delay_s": 0.1})).params_hash != phash


def test_unsupported_pairs(forged):
    exp = Experiment.build(planners=["test.gridonly", "test.honest"], scenarios=["test.wall", "test.ramp"], seeds=1)
    assert exp.skipped() == [("test.gridonly", "test.ramp", "terrain")]
    assert {(t.planner.id, t.scenario.id) for t in exp.tasks()} == {
        ("test.gridonly", "test.wall"), ("test.honest", "test.wall"), ("test.honest", "test.ramp")}


@pytest.mark.parametrize("kwargs, error, text", [
    ({"planners": []}, InvalidExperimentError, "no planners"),
    ({"planners": ["nope.nothing"]}, UnknownPluginError, "unknown planner 'nope.nothing'"),
    ({"planners": [("test.honest", {"delay_s": -1.0})]}, InvalidParameterError, "delay_s"),
    ({"planners": ["test.honest", ("test.honest", {"delay_s": 0.0})]}, InvalidExperimentError, "repeats planner 0"),
    ({"planners": [42]}, InvalidExperimentError, "a planner must be"),
    ({"scenarios": []}, InvalidExperimentError, "no scenarios"),
    ({"scenarios": ["test.zzz*"]}, UnknownPluginError, "unknown scenario"),
    ({"seeds": 0}, InvalidExperimentError, "seeds must be between 1 and 100000"),
    ({"seeds": 100_000_000}, InvalidExperimentError, "seeds must be between 1 and 100000"),
    ({"seeds": [1, 1]}, InvalidExperimentError, "distinct"),
    ({"timeout_s": -3}, InvalidExperimentError, "timeout_s"),
    ({"name": ""}, InvalidExperimentError, "name"),
])
def test_build_errors(forged, kwargs, error, text):
    args = {"planners": ["test.honest"], "scenarios": ["test.wall"]} | kwargs
    with pytest.raises(error, match=None) as info:
        Experiment.build(**args)
    assert text in str(info.value) and "\n" not in str(info.value)


def test_instances_of_unregistered_classes_are_refused(forged):
    class Impostor(forged.Honest):
        pass

    with pytest.raises(InvalidExperimentError, match="not the class registered as 'test.honest'"):
        Experiment.build(planners=[Impostor()], scenarios=["test.wall"])


def test_two_scenarios_with_one_id_are_refused(forged):
    a, b = forged.wall_scenario(), forged.sealed_scenario()
    object.__setattr__(b, "id", a.id)
    with pytest.raises(InvalidExperimentError, match="share the id 'test.wall'"):
        Experiment.build(planners=["test.honest"], scenarios=[a, b])


GOOD = """
[experiment]
name = "toml-demo"
seed = 3
seeds = [0, 2]
budget = {{ time_s = 0.5, iterations = 10 }}
timeout_s = 5
jobs = 2
db = "out/results.sqlite"
scenarios = ["test.wall", "{scen}"]

[[planner]]
id = "test.honest"

[[planner]]
id = "test.honest"
params = {{ delay_s = 0.01 }}
"""


def test_from_toml(forged, tmp_path, shared_data):
    scen = shared_data / "movingai" / "grid" / "dao" / "arena.map.scen"
    path = tmp_path / "exp.toml"
    path.write_text(GOOD.format(scen=scen))
    exp = Experiment.from_toml(path)
    assert exp.name == "toml-demo" and exp.seed == 3 and exp.seeds == (0, 2) and exp.jobs == 2
    assert exp.budget == Budget(iterations=10, time_s=0.5) and exp.timeout_s == 5.0
    assert exp.db == tmp_path / "out" / "results.sqlite" and exp.source == str(path)
    assert exp.scenarios[0].id == "test.wall" and exp.scenarios[1].id == "arena.0"
    assert all(s.source == "file" and s.location == str(scen.resolve()) for s in exp.scenarios[1:])
    assert len(exp.tasks()) == 2 * len(exp.scenarios) * 2
    # relative scenario files are relative to the experiment file
    (tmp_path / "sub").mkdir()
    rel = tmp_path / "sub" / "rel.toml"
    rel.write_text('[experiment]\nscenarios = ["../maps/a.scen"]\n[[planner]]\nid = "test.honest"\n')
    with pytest.raises(InvalidExperimentError) as info:
        Experiment.from_toml(rel)
    message = str(info.value)
    assert message.startswith(str(rel)) and "field 'experiment.scenarios[0]'" in message
    assert str(tmp_path / "sub" / ".." / "maps" / "a.scen") in message or str(tmp_path / "maps" / "a.scen") in message


@pytest.mark.parametrize("text, field", [
    ("[experiment\n", None),
    ('[experiment]\nscenarios = ["test.wall"]\ncolour = 1\n[[planner]]\nid = "test.honest"\n', "experiment"),
    ('[experiment]\nname = "x"\n[[planner]]\nid = "test.honest"\n', "experiment.scenarios"),
    ('[experiment]\nscenarios = ["test.wall"]\n', "planner"),
    ('[experiment]\nscenarios = ["test.wall"]\n[[planner]]\nid = "nope.none"\n', "planner[0]"),
    ('[experiment]\nscenarios = ["test.wall"]\n[[planner]]\nid = "test.honest"\n[[planner]]\nid = "test.honest"\n'
     'params = { delay_s = "slow" }\n', "planner[1]"),
    ('[experiment]\nscenarios = ["test.wall"]\n[[planner]]\nid = "test.honest"\nparams = 3\n', "planner[0].params"),
    ('[experiment]\nscenarios = ["test.wall", "test.nothing"]\n[[planner]]\nid = "test.honest"\n',
     "experiment.scenarios[1]"),
    ('[experiment]\nscenarios = "test.wall"\n[[planner]]\nid = "test.honest"\n', "experiment.scenarios"),
    ('[experiment]\nscenarios = ["test.wall"]\nseeds = -2\n[[planner]]\nid = "test.honest"\n', "experiment.seeds"),
    ('[experiment]\nscenarios = ["test.wall"]\nseed = 1.5\n[[planner]]\nid = "test.honest"\n', "experiment.seed"),
    ('[experiment]\nscenarios = ["test.wall"]\ntimeout_s = 0\n[[planner]]\nid = "test.honest"\n',
     "experiment.timeout_s"),
    ('[experiment]\nscenarios = ["test.wall"]\njobs = 0\n[[planner]]\nid = "test.honest"\n', "experiment.jobs"),
    ('[experiment]\nscenarios = ["test.wall"]\nbudget = { hours = 1 }\n[[planner]]\nid = "test.honest"\n',
     "experiment.budget"),
    ('[experiment]\nscenarios = ["test.wall"]\nbudget = { time_s = -1 }\n[[planner]]\nid = "test.honest"\n',
     "experiment.budget"),
    ('scenarios = ["test.wall"]\n[experiment]\nscenarios = ["test.wall"]\n[[planner]]\nid = "test.honest"\n',
     "scenarios"),
    ('[experiment]\nscenarios = ["test.wall"]\n[[planner]]\nid = "test.honest"\n[[planner]]\nid = "test.honest"\n',
     "planner"),
])
def test_toml_errors_name_file_and_field(forged, tmp_path, text, field):
    path = tmp_path / "bad.toml"
    path.write_text(text)
    with pytest.raises(InvalidExperimentError) as info:
        Experiment.from_toml(path)
    message = str(info.value)
    assert message.startswith(str(path)) and "\n" not in message
    if field is not None:
        assert f"field '{field}'" in message


def test_toml_missing_file(tmp_path):
    with pytest.raises(InvalidExperimentError, match="cannot read"):
        Experiment.from_toml(tmp_path / "none.toml")


def test_top_level_scenarios_key(forged, tmp_path):
    path = tmp_path / "top.toml"
    path.write_text('scenarios = ["test.wall"]\n[[planner]]\nid = "test.honest"\n')
    exp = Experiment.from_toml(path)
    assert exp.name == "top" and [s.id for s in exp.scenarios] == ["test.wall"] and exp.db is None
