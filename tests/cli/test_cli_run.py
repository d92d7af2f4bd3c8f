"""``pathzoo run`` and ``pathzoo leaderboard`` on real (tiny) experiments."""

from __future__ import annotations

import io
import logging
import tomllib
from importlib import resources

import pandas as pd
import pytest

from pathzoo.cli.main import main
from pathzoo.harness import runner
from pathzoo.harness.store import read_runs

SCENARIO = """
id = "cli.random"
kind = "grid2d"
description = "12x12 random obstacles"
endpoint_seed = 0

[map]
generator = "random"
seed = 1
shape = [12, 12]
density = 0.2
"""

EXPERIMENT = """
[experiment]
name = "{name}"
seeds = 2
budget = {{ time_s = 5.0 }}
scenarios = ["random.toml"]

[[planner]]
id = "exact.astar"

[[planner]]
id = "exact.thetastar"
"""


def one_error(capsys) -> str:
    captured = capsys.readouterr()
    lines = [ln for ln in captured.err.splitlines() if not ln.startswith("pathzoo: plugin '")]
    assert len(lines) == 1 and lines[0].startswith("pathzoo: error: "), captured.err
    return lines[0].removeprefix("pathzoo: error: ")


@pytest.fixture
def experiment(tmp_path):
    (tmp_path / "random.toml").write_text(SCENARIO)
    path = tmp_path / "tiny.toml"
    path.write_text(EXPERIMENT.format(name="tiny"))
    return path


def run_cli(capsys, *argv: str) -> str:
    assert main(list(argv)) == 0
    return capsys.readouterr().out


@pytest.mark.slow
def test_run_stores_validated_runs_and_prints_the_leaderboard(experiment, tmp_path, capsys):
    db = tmp_path / "r.sqlite"
    out = run_cli(capsys, "run", str(experiment), "--db", str(db), "--executor", "inline", "--no-progress")
    runs = read_runs(db, "tiny")
    assert len(runs) == 4
    assert runs["status"].eq("solved").all() and runs["valid"].all(), runs["message"].tolist()
    assert out.startswith("Leaderboard: length")
    rows = [ln.split() for ln in out.splitlines() if ln.startswith("cli.random")]
    medians = runs.groupby("planner")["length"].median().sort_values()
    assert medians["exact.thetastar"] < medians["exact.astar"]  # any-angle paths are shorter here
    assert [r[2] for r in rows] == list(medians.index)
    assert [r[3] for r in rows] == ["anyangle", "grid"]  # one section per path model, each ranked on its own
    assert [r[1] for r in rows] == ["1", "1"]
    assert [float(r[6]) for r in rows] == pytest.approx(list(medians), rel=1e-4)
    # the same table comes back from the database
    assert run_cli(capsys, "leaderboard", str(db)) == out


def test_run_resumes_and_seeds_override(experiment, tmp_path, capsys):
    db = tmp_path / "r.sqlite"
    args = ["run", str(experiment), "--db", str(db), "--executor", "inline", "--no-progress"]
    run_cli(capsys, *args)
    first = read_runs(db, "tiny")
    run_cli(capsys, *args)
    assert read_runs(db, "tiny")["run_key"].tolist() == first["run_key"].tolist()  # nothing re-run or doubled
    run_cli(capsys, *args, "--seeds", "3")
    again = read_runs(db, "tiny")
    assert len(again) == 6 and sorted(again["seed_index"].unique()) == [0, 1, 2]


@pytest.mark.slow
def test_run_without_argument_runs_the_bundled_default(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    out = run_cli(capsys, "run", "--seeds", "1", "--executor", "inline", "--no-progress")
    runs = read_runs(tmp_path / runner.DEFAULT_DB, "default")
    bundled = tomllib.loads((resources.files("pathzoo.experiments") / "default.toml").read_text())
    assert set(runs["scenario"]) == set(bundled["experiment"]["scenarios"])
    assert set(runs["planner"]) == {p["id"] for p in bundled["planner"]}
    assert (runs["status"] == "solved").all() and runs["valid"].all()
    for scenario in bundled["experiment"]["scenarios"]:
        assert scenario in out


def test_leaderboard_formats_and_options(experiment, tmp_path, capsys):
    db = tmp_path / "r.sqlite"
    run_cli(capsys, "run", str(experiment), "--db", str(db), "--executor", "inline", "--no-progress")
    csv = pd.read_csv(io.StringIO(run_cli(capsys, "leaderboard", str(db), "--format", "csv")))
    assert list(csv["config"]) == ["exact.thetastar", "exact.astar"]
    assert {"median", "sd", "success_rate", "rank"} <= set(csv.columns)
    assert (csv["success_rate"] == 1.0).all()
    md = run_cli(capsys, "leaderboard", str(db), "--format", "markdown", "--metric", "turns")
    assert md.startswith("**Leaderboard: turns") and "| cli.random |" in md
    ref = run_cli(capsys, "leaderboard", str(db), "--reference", "exact.astar")
    assert "vs ref" in ref and "reference" in ref


def test_leaderboard_needs_experiment_when_db_holds_several(experiment, tmp_path, capsys):
    db = tmp_path / "r.sqlite"
    other = tmp_path / "other.toml"  # same folder, so it finds random.toml too
    other.write_text(EXPERIMENT.format(name="other"))
    for exp in (experiment, other):
        run_cli(capsys, "run", str(exp), "--db", str(db), "--executor", "inline", "--no-progress")
    assert main(["leaderboard", str(db)]) == 2
    assert one_error(capsys) == f"{db} holds experiments other, tiny; choose one with --experiment"
    out = run_cli(capsys, "leaderboard", str(db), "--experiment", "other")
    assert "exact.astar" in out
    assert main(["leaderboard", str(db), "--experiment", "nope"]) == 2
    assert one_error(capsys) == f"{db}: no experiment named 'nope' (stored: other, tiny)"


def test_leaderboard_of_a_file_that_is_not_a_database(tmp_path, capsys):
    bogus = tmp_path / "notes.sqlite"
    bogus.write_text("hello, this is not SQLite\n" * 100)
    assert main(["leaderboard", str(bogus)]) == 2
    assert one_error(capsys).startswith(f"{bogus}: not a results database")


def test_leaderboard_of_unknown_metric(experiment, tmp_path, capsys):
    db = tmp_path / "r.sqlite"
    run_cli(capsys, "run", str(experiment), "--db", str(db), "--executor", "inline", "--no-progress")
    assert main(["leaderboard", str(db), "--metric", "speediness"]) == 2
    assert one_error(capsys).startswith("unknown metric 'speediness'")


@pytest.mark.parametrize(
    ("body", "message"),
    [
        (EXPERIMENT.format(name="x").replace("exact.astar", "exact.nope"), "field 'planner[0]': unknown planner 'exact.nope'"),
        (EXPERIMENT.format(name="x").replace("seeds = 2", "seeds = 0"),
         "field 'experiment.seeds': seeds must be between 1 and 100000"),
        ("this is = not [toml", "not valid TOML"),
    ],
)
def test_bad_experiment_files_are_one_line(tmp_path, capsys, body, message):
    (tmp_path / "random.toml").write_text(SCENARIO)
    path = tmp_path / "bad.toml"
    path.write_text(body)
    assert main(["run", str(path), "--db", str(tmp_path / "r.sqlite"), "--no-progress"]) == 2
    line = one_error(capsys)
    assert line.startswith(str(path)) and message in line


def test_executor_options_reach_the_runner(experiment, tmp_path, capsys, monkeypatch):
    seen = {}

    def fake_run_experiment(exp, *, db, jobs, executor, progress, retry=(), require_sandbox=False, shard=None,
                            sandbox_limits=None):
        seen.update(db=db, jobs=jobs, executor=executor, progress=progress, seeds=exp.seeds,
                    require_sandbox=require_sandbox, shard=str(shard), sandbox_limits=sandbox_limits)
        raise KeyboardInterrupt

    monkeypatch.setattr(runner, "run_experiment", fake_run_experiment)
    db = tmp_path / "r.sqlite"
    argv = ["run", str(experiment), "--db", str(db), "--executor", "dask", "--dask-address", "tcp://10.0.0.1:8786",
            "--jobs", "3", "--seeds", "4", "--no-progress", "--require-sandbox", "--shard", "2/3"]
    assert main(argv) == 2
    assert seen == {"db": str(db), "jobs": 3, "executor": "dask:tcp://10.0.0.1:8786", "progress": False,
                    "seeds": (0, 1, 2, 3), "require_sandbox": True, "shard": "2/3", "sandbox_limits": None}
    assert one_error(capsys) == (
        f"interrupted; finished runs are stored in {db}, run the same command again to resume"
    )


def test_sandbox_memory_reaches_the_process_executors_workers(experiment, tmp_path, capsys, monkeypatch):
    seen = {}

    def fake_run_experiment(exp, *, executor, sandbox_limits=None, **kwargs):
        seen.update(executor_limits=getattr(executor, "limits", None), sandbox_limits=sandbox_limits)
        raise KeyboardInterrupt

    monkeypatch.setattr(runner, "run_experiment", fake_run_experiment)
    argv = ["run", str(experiment), "--db", str(tmp_path / "r.sqlite"), "--no-progress", "--jobs", "1",
            "--sandbox-memory", "1.5"]
    assert main(argv) == 2
    assert seen["sandbox_limits"].memory_bytes == 3 << 29
    if seen["executor_limits"] is not None:  # the process executor built early, while the experiment was read
        assert seen["executor_limits"].memory_bytes == 3 << 29


@pytest.mark.parametrize(("option", "message"), [
    (["--sandbox-memory", "0"], "--sandbox-memory: must be a positive number of GiB, got '0'"),
    (["--sandbox-memory", "lots"], "--sandbox-memory: must be a number of GiB, got 'lots'"),
    (["--sandbox-memory", "2", "--executor", "inline"],
     "--sandbox-memory applies to the process executor's workers, not to --executor inline"),
])
def test_a_bad_sandbox_memory_is_a_one_line_error(experiment, tmp_path, capsys, option, message):
    assert main(["run", str(experiment), "--db", str(tmp_path / "r.sqlite"), "--no-progress", *option]) == 2
    assert message in one_error(capsys)


def test_require_sandbox_refuses_the_inline_executor_in_one_line(experiment, tmp_path, capsys):
    argv = ["run", str(experiment), "--db", str(tmp_path / "r.sqlite"), "--executor", "inline", "--no-progress",
            "--require-sandbox"]
    assert main(argv) == 2
    assert one_error(capsys) == "the inline executor runs planners in the harness's own process, never sandboxed"
    assert not (tmp_path / "r.sqlite").exists() or not read_runs(tmp_path / "r.sqlite").shape[0]


def test_report_and_ompl_export_and_html_leaderboard(experiment, tmp_path, capsys):
    db = tmp_path / "r.sqlite"
    run_cli(capsys, "run", str(experiment), "--db", str(db), "--executor", "inline", "--no-progress")
    html = run_cli(capsys, "leaderboard", str(db), "--format", "html")
    assert "<table" in html and "exact.astar" in html
    out = run_cli(capsys, "report", str(db), "-o", str(tmp_path / "rep"))
    index = tmp_path / "rep" / "index.html"
    assert out.strip() == str(index) and index.stat().st_size > 1000
    assert "exact.thetastar" in index.read_text()
    logs = run_cli(capsys, "export-ompl", str(db), "-o", str(tmp_path / "ompl")).split()
    assert logs and all(p.endswith(".log") for p in logs)


def test_report_of_missing_database_is_one_line(tmp_path, capsys):
    assert main(["report", str(tmp_path / "nope.sqlite"), "-o", str(tmp_path / "rep")]) == 2
    assert "nope.sqlite" in one_error(capsys)


def test_unsupported_pairs_are_one_short_line_and_listed_with_verbose(tmp_path, capsys, caplog):
    (tmp_path / "random.toml").write_text(SCENARIO)
    path = tmp_path / "mixed.toml"
    path.write_text(EXPERIMENT.format(name="mixed").replace('["random.toml"]', '["random.toml", "fgdaco.scenario1"]'))
    db = tmp_path / "m.sqlite"
    run_cli(capsys, "run", str(path), "--db", str(db), "--executor", "inline", "--no-progress", "--seeds", "1")
    shown = [r.getMessage() for r in caplog.records if r.levelno >= logging.WARNING]
    short = [m for m in shown if "unsupported" in m]
    assert len(short) == 1 and len(short[0]) < 160 and "\n" not in short[0], shown
    assert "skipping 2 unsupported planner x scenario pair(s)" in short[0] and "dynamic 2" in short[0]
    assert short[0].endswith("; no planner runs fgdaco.scenario1")  # why it is a warning
    assert not any("exact.thetastar x fgdaco.scenario1" in r.getMessage() for r in caplog.records)
    caplog.clear()
    run_cli(capsys, "run", str(path), "--db", str(db), "--executor", "inline", "--no-progress", "--seeds", "1", "-v")
    listed = "\n".join(r.getMessage() for r in caplog.records if r.levelno == logging.INFO)
    assert "  exact.astar x fgdaco.scenario1 (dynamic)" in listed
    assert "  exact.thetastar x fgdaco.scenario1 (dynamic)" in listed


def test_a_directory_or_a_string_seed_count_is_a_one_line_error(tmp_path, capsys):
    from pathzoo.cli.main import main

    assert main(["run", str(tmp_path)]) == 2
    assert "is a directory; give an experiment TOML file" in capsys.readouterr().err
    bad = tmp_path / "bad.toml"
    bad.write_text('[experiment]\nseeds = "two"\nscenarios = ["gant.fig7"]\n[[planner]]\nid = "exact.astar"\n')
    assert main(["run", str(bad), "--db", str(tmp_path / "r.sqlite")]) == 2
    err = capsys.readouterr().err
    assert "field 'experiment.seeds'" in err and "got 'two'" in err and "['t'" not in err
