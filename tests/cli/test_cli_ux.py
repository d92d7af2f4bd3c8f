"""The pathzoo command's conveniences: list patterns, "did you mean", completion, a light parser."""

from __future__ import annotations

import subprocess
import sys
from importlib import resources

import pytest

from pathzoo.cli import cmd_list, cmd_reproduce
from pathzoo.cli.main import main


def test_list_pattern_keeps_only_matching_ids(capsys):
    assert main(["list", "scenarios", "fgdaco.*"]) == 0
    ids = [line.split()[0] for line in capsys.readouterr().out.splitlines()[2:]]
    assert ids and all(i.startswith("fgdaco.") for i in ids)


def test_list_patterns_work_for_planners_and_report_no_match(capsys):
    assert main(["list", "planners", "exact.*", "aco.mmas"]) == 0
    ids = [line.split()[0] for line in capsys.readouterr().out.splitlines()[2:]]
    assert "aco.mmas" in ids and all(i.startswith("exact.") or i == "aco.mmas" for i in ids)
    assert main(["list", "metrics", "no-such-*"]) == 0
    assert capsys.readouterr().out.strip() == "no metrics match no-such-*"


@pytest.mark.parametrize(("entry", "patterns", "expected"), [
    ("fgdaco.scenario1", [], True), ("fgdaco.scenario1", ["fgdaco.*"], True),
    ("ggaco.map", ["fgdaco.*"], False), ("ggaco.map", ["x", "*map"], True), ("A.b", ["a.*"], False)])
def test_matches(entry, patterns, expected):
    assert cmd_list.matches(entry, patterns) is expected


def test_mistyped_command_gets_one_line_suggestion(capsys):
    assert main(["rn", "x.toml"]) == 2
    err = capsys.readouterr().err
    assert err == "pathzoo: error: unknown command 'rn'; did you mean 'run'?\n"


def test_unrelated_word_lists_the_commands(capsys):
    assert main(["frobnicate"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("pathzoo: error: unknown command 'frobnicate'; choose one of list, run")
    assert "\n" not in err


@pytest.mark.parametrize("shell", ["bash", "zsh"])
def test_completion_script_names_the_subcommands(shell, capsys):
    assert main(["completion", shell]) == 0
    script = capsys.readouterr().out
    for command in ("leaderboard", "export-ompl", "reproduce", "completion"):
        assert command in script


def test_reproduce_paper_names_match_the_analysis_and_data_files():
    from pathzoo.analysis.reproduction import PAPERS

    assert cmd_reproduce.PAPER_NAMES == PAPERS
    files = {p.name.removesuffix(".toml") for p in (resources.files("pathzoo_scenarios") / "papers").iterdir()
             if p.name.endswith(".toml")}
    assert set(cmd_reproduce.PAPER_NAMES) == files


def test_building_the_parser_imports_nothing_heavy():
    code = ("import sys; from pathzoo.cli.main import build_parser; build_parser(); "
            "print(sorted(m for m in ('pandas', 'scipy', 'numba', 'matplotlib', 'optuna') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, check=True).stdout
    assert out.strip() == "[]"
