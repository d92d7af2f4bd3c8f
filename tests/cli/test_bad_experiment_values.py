"""Experiment values the database or a planner cannot hold are refused up front: one line naming the field, exit 2."""

from __future__ import annotations

import textwrap

import pytest

from pathzoo.cli.main import main

ARENA = "movingai.arena.b0.1"


def run_error(tmp_path, capsys, experiment: str, planner: str = "exact.astar", params: str = "") -> str:
    exp = tmp_path / "e.toml"
    exp.write_text(textwrap.dedent(f"""\
        [experiment]
        {experiment}
        scenarios = ["{ARENA}"]
        [[planner]]
        id = "{planner}"
        """) + (f"params = {{ {params} }}\n" if params else ""))
    db = tmp_path / "r.sqlite"
    assert main(["run", str(exp), "--db", str(db), "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("pathzoo: error: ") and err.count("\n") == 1 and "Traceback" not in err, err
    assert not db.exists()  # refused before anything ran
    return err


@pytest.mark.parametrize(("line", "field"), [
    ("seeds = [18446744073709551617]", "experiment.seeds"),       # 2**64 + 1
    ("seeds = [0, 9223372036854775808]", "experiment.seeds"),      # 2**63
    ("seed = 9223372036854775808", "experiment.seed"),
    ("budget = { iterations = 1180591620717411303424 }", "experiment.budget"),  # 2**70
    ("budget = { evaluations = 9223372036854775808 }", "experiment.budget"),
])
def test_numbers_beyond_64_bits_are_refused(tmp_path, capsys, line, field):
    err = run_error(tmp_path, capsys, line)
    assert f"field '{field}'" in err


def test_a_colony_too_large_to_hold_is_refused(tmp_path, capsys):
    err = run_error(tmp_path, capsys, "seeds = 1", planner="aco.as", params="n_ants = 9223372036854775807")
    assert "parameter 'n_ants' must be int in [1, 10000]" in err


def test_an_integer_parameter_beyond_64_bits_is_refused(tmp_path, capsys):
    err = run_error(tmp_path, capsys, "seeds = 1", planner="aco.as", params="iterations = 1180591620717411303424")
    assert "parameter 'iterations' must fit in 64 bits" in err


def test_an_experiment_with_nothing_to_run_says_so(tmp_path, capsys):
    """Every pair unsupported: the old harness stored 0 runs and failed with "runs: missing column 'length'"."""
    exp = tmp_path / "e.toml"
    exp.write_text(textwrap.dedent("""\
        [experiment]
        seeds = 1
        scenarios = ["dsaco.simple"]
        [[planner]]
        id = "exact.thetastar"
        """))
    assert main(["run", str(exp), "--db", str(tmp_path / "r.sqlite"), "--no-progress"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "missing column" not in err
    assert "nothing to run: no planner supports any of the scenarios" in err
    assert "the scenarios are air3d" in err
