"""``pathzoo tune`` and named configurations, on tiny maps with a budget of a few iterations."""

from __future__ import annotations

import sqlite3

import pytest

from pathzoo.analysis.frame import config_labels
from pathzoo.analysis.leaderboard import format_leaderboard, leaderboard
from pathzoo.cli.main import main
from pathzoo.core.errors import InvalidExperimentError
from pathzoo.harness.experiment import Experiment
from pathzoo.harness.runner import run_experiment
from pathzoo.harness.store import ResultStore, read_runs
from pathzoo.plugins.manager import get_registry
from pathzoo.testing import parametrize_with_checks
from pathzoo.tuning import load_tuning, parse_space, tune
from pathzoo.tuning.tuner import _next_trial  # noqa: PLC2701 (simulating a kill between ask and tell)

SCENARIO = """
id = "tune.random{i}"
kind = "grid2d"
description = "10x10 random obstacles"
endpoint_seed = {i}

[map]
generator = "random"
seed = {i}
shape = [10, 10]
density = 0.2
"""

TUNING = """
train = ["r1.toml", "r2.toml"]
test = [{test}]

[experiment]
name = "tiny"
seeds = 2
budget = {{ iterations = 3 }}

[tuning]
trials = 3

[[planner]]
id = "aco.as"
[planner.search]
alpha = [0.5, 3.0]
n_ants = {{ low = 5, high = 20, log = true }}

[[planner]]
id = "aco.mmas"
label = "mmas"
[planner.search]
beta = [1.0, 8.0]

[[planner]]
id = "exact.astar"
"""


@pytest.fixture
def tuning_file(tmp_path):
    for i in range(1, 5):
        (tmp_path / f"r{i}.toml").write_text(SCENARIO.format(i=i))

    def write(test: str = '"r3.toml", "r4.toml"') -> str:
        path = tmp_path / "tiny.toml"
        path.write_text(TUNING.format(test=test))
        return str(path)

    return write


def one_error(capsys) -> str:
    err = [ln for ln in capsys.readouterr().err.splitlines() if not ln.startswith("pathzoo: plugin '")]
    assert len(err) == 1 and err[0].startswith("pathzoo: error: "), err
    return err[0]


@pytest.mark.slow
def test_every_planner_gets_the_same_trials_and_default_and_tuned_rows(tuning_file, tmp_path):
    setup = load_tuning(tuning_file())
    assert [len(s) for s in setup.spaces] == [2, 1, 0]  # exact.astar declares nothing to tune
    result = tune(setup, db=tmp_path / "r.sqlite", executor="inline")
    assert [p.trials for p in result.planners] == [3, 3, 3]
    table = result.table()
    assert list(table["trials"]) == [3, 3, 3]
    mmas = result.planners[1]
    assert set(mmas.tuned.params) == set(mmas.default.params)
    assert mmas.best_score <= mmas.default_score  # the default is trial 0, so tuned is never worse on training
    assert mmas.tuned_text.startswith("beta=")
    configs = set(config_labels(result.test_runs))
    for p in result.planners:
        expected = {f"{p.name} default = tuned"} if p.kept_default else {f"{p.name} default", f"{p.name} tuned"}
        assert expected <= configs and set(p.test_labels) == expected
    assert "exact.astar default = tuned" in configs
    assert set(result.test_runs["scenario"]) == {"tune.random3", "tune.random4"}
    text = format_leaderboard(leaderboard(result.test_runs, "length"))
    assert "mmas default" in text and "exact.astar default = tuned" in text


@pytest.mark.slow
def test_resumed_tuning_ends_with_the_same_parameters(tuning_file, tmp_path):
    whole = tune(load_tuning(tuning_file()), db=tmp_path / "a.sqlite", executor="inline")
    setup = load_tuning(tuning_file())
    partial = tune(setup, db=tmp_path / "b.sqlite", executor="inline", stop_after_rounds=1)
    assert partial.planners == () and partial.test_runs.empty
    # a kill between asking the next trial and telling its score leaves it RUNNING with its parameters drawn
    import optuna

    storage = f"sqlite:///{tmp_path / 'b.optuna.sqlite'}"
    study = optuna.load_study(study_name="tiny:mmas", storage=storage)
    number, params = _next_trial(study, setup.spaces[1], setup.experiment.seed, "mmas", setup.trials)
    resumed = tune(load_tuning(tuning_file()), db=tmp_path / "b.sqlite", executor="inline")
    assert [p.tuned.params for p in resumed.planners] == [p.tuned.params for p in whole.planners]
    assert [p.best_score for p in resumed.planners] == [p.best_score for p in whole.planners]
    trial = optuna.load_study(study_name="tiny:mmas", storage=storage).trials[number]
    assert trial.params == params and trial.state.name == "COMPLETE"  # the interrupted trial was finished, not redrawn


@pytest.mark.slow
def test_cli_prints_trials_tuned_parameters_and_both_rows(tuning_file, tmp_path, capsys):
    db = tmp_path / "c.sqlite"
    argv = ["tune", tuning_file(), "--db", str(db), "--executor", "inline", "--no-progress", "--trials", "2"]
    assert main(argv) == 0
    out = capsys.readouterr().out
    rows = [ln.split() for ln in out.splitlines() if ln.split()[:1] in (["aco.as"], ["mmas"], ["exact.astar"])]
    assert [r[1] for r in rows[:3]] == ["2", "2", "2"]
    assert "alpha=" in out and "beta=" in out
    assert "mmas default" in out and "Leaderboard" in out
    assert "Test scenarios (" in out


def test_overlapping_train_and_test_is_a_one_line_error(tuning_file, capsys):
    path = tuning_file('"r2.toml", "r3.toml"')
    with pytest.raises(InvalidExperimentError, match="overlap in 1 scenario"):
        load_tuning(path)
    assert main(["tune", path, "--executor", "inline"]) == 2
    line = one_error(capsys)
    assert "tiny.toml" in line and "'train' and 'test' overlap" in line and "tune.random2" in line


def test_tuning_file_errors_name_the_field(tuning_file, tmp_path):
    path = tmp_path / "bad.toml"
    good = open(tuning_file()).read()
    cases = {
        good.replace('test = ["r3.toml", "r4.toml"]', ""): "field 'test': missing",
        good.replace("alpha = [0.5, 3.0]", "alpha = [3.0, 0.5]"): r"planner\[0\]\.search\.alpha: range",
        good.replace("alpha = [0.5, 3.0]", "gamma = [0.5, 3.0]"): "has no such parameter",
        good.replace("trials = 3", "trials = 0"): "tuning.trials",
        "scenarios = ['r1.toml']\n" + good: "field 'scenarios'",
    }
    for text, message in cases.items():
        path.write_text(text)
        with pytest.raises(InvalidExperimentError, match=message) as info:
            load_tuning(path)
        assert str(path) in str(info.value) and "\n" not in str(info.value)


def test_search_ranges_are_parsed_and_checked():
    mmas = get_registry().get("planners", "aco.mmas").obj
    space = parse_space({"alpha": [0.5, 2], "n_ants": {"low": 5, "high": 50, "log": True},
                         "dead_end": ["die", "backtrack"], "rho": "declared"}, mmas.id, mmas.params, "f")
    assert (space["alpha"].low, space["alpha"].high, space["alpha"].integer) == (0.5, 2.0, False)
    assert space["n_ants"].integer and space["n_ants"].log
    assert space["dead_end"].choices == ("die", "backtrack")
    assert (space["rho"].low, space["rho"].high) == mmas.params["rho"].tune
    bad = {
        "rho": [0.5, 1.5],  # above the parameter's bound
        "n_ants": [1.5, 4],  # not integers
        "alpha": {"low": 0, "high": 2, "log": True},  # log from 0
        "dead_end": ["sideways"],  # not a choice
        "dead_end": [0.1, 0.2],  # noqa: F601 (a range for a categorical parameter)
        "max_steps": "declared",  # no tuning range and no finite bounds
    }
    for name, spec in bad.items():
        with pytest.raises(InvalidExperimentError, match=f"f.{name}"):
            parse_space({name: spec}, mmas.id, mmas.params, "f")


EXPERIMENT = """
[experiment]
name = "labels"
seeds = 1
budget = {{ iterations = 2 }}
scenarios = ["r1.toml"]

[[planner]]
id = "aco.mmas"
label = "{label}"
params = {{ alpha = 2.0 }}

[[planner]]
id = "aco.mmas"
params = {{ alpha = 3.0, beta = 1.0 }}

[[planner]]
id = "aco.mmas"
"""


def test_labels_from_the_experiment_file_reach_the_store_leaderboard_and_csv(tuning_file, tmp_path, capsys):
    tuning_file()
    path = tmp_path / "labels.toml"
    path.write_text(EXPERIMENT.format(label="mmas-a2"))
    db = tmp_path / "l.sqlite"
    assert main(["run", str(path), "--db", str(db), "--executor", "inline", "--no-progress", "--format", "csv"]) == 0
    csv = capsys.readouterr().out
    runs = read_runs(db, "labels")
    assert list(runs["label"]) == ["mmas-a2", "aco.mmas(alpha=3, beta=1)", "aco.mmas"]
    assert set(config_labels(runs)) == {"mmas-a2", "aco.mmas(alpha=3, beta=1)", "aco.mmas"}
    for name in ("mmas-a2", "aco.mmas(alpha=3, beta=1)"):
        assert name in csv
    assert "@" not in csv
    stored = Experiment.from_toml(path).config()["planners"]
    assert stored[0]["label"] == "mmas-a2" and "label" not in stored[1]


def test_labels_must_be_distinct_and_non_empty(tuning_file, tmp_path):
    tuning_file()
    with pytest.raises(InvalidExperimentError, match="same name 'aco.mmas'"):
        Experiment.build(planners=[("aco.mmas", {"alpha": 2.0}, "aco.mmas"), "aco.mmas"],
                         scenarios=[str(tmp_path / "r1.toml")])
    path = tmp_path / "labels.toml"
    path.write_text(EXPERIMENT.format(label=" "))
    with pytest.raises(InvalidExperimentError, match=r"planner\[0\]'.*label must be a non-empty string"):
        Experiment.from_toml(path)


def test_a_database_from_before_labels_stays_readable(tuning_file, tmp_path):
    tuning_file()
    db = tmp_path / "old.sqlite"
    exp = Experiment.build(planners=[("aco.mmas", {"alpha": 2.0}), "aco.mmas"], scenarios=[str(tmp_path / "r1.toml")],
                           seeds=1, budget=__import__("pathzoo").Budget(iterations=2), name="old")
    run_experiment(exp, db=db, executor="inline", progress=False)
    with sqlite3.connect(db) as conn:
        conn.execute("ALTER TABLE runs DROP COLUMN label")  # the layout before labels
    runs = read_runs(db, "old")
    assert list(runs["label"]) == ["", ""]
    assert sorted(config_labels(runs))[0].startswith("aco.mmas@")  # the old names
    with ResultStore(db) as store:  # opening for writing adds the column back, keeping the rows
        assert store.count_runs("old") == 2
    with sqlite3.connect(db) as conn:
        assert "label" in {r[1] for r in conn.execute("PRAGMA table_info(runs)")}


@parametrize_with_checks([get_registry().get("planners", "exact.astar").obj()])
def test_conformance_ids_exist(planner, check):  # the kit still collects with the new ids
    assert planner.config_name == "exact.astar"


def test_conformance_ids_name_the_configuration():
    from pathzoo import make_planner

    mark = parametrize_with_checks([make_planner("aco.mmas"), make_planner("aco.mmas", alpha=2.0)])
    ids = mark.kwargs["ids"]
    assert len(ids) == len(set(ids))
    assert "aco.mmas-check_solves[grid2d]" in ids and "aco.mmas(alpha=2)-check_solves[grid2d]" in ids


def test_every_declared_tuning_range_is_valid_and_defaults_are_unchanged():
    from pathzoo.tuning import default_space

    registry = get_registry()
    declared = 0
    for pid in registry.planners:
        cls = registry.get("planners", pid).obj
        space = default_space(pid, cls.params)  # raises for a range outside the bounds
        declared += len(space)
        for name, r in space.items():
            assert cls.params[name].tune == (r.low, r.high)
    assert declared >= 4 * 8  # alpha, beta, rho and n_ants of every colony
    assert registry.get("planners", "aco.mmas").obj().get_params()["alpha"] == 1.0
