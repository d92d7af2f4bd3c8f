"""Every usage error of the pathzoo command is one line with exit code 2, and typos get the closest name first."""

from __future__ import annotations

import pytest

from pathzoo.cli.main import main
from pathzoo.core.suggest import closest

USAGE_ERRORS = [
    [],                                               # no command
    ["run", "--bogus"],                               # unknown option
    ["run", "a.toml", "b.toml"],                      # one experiment only
    ["run", "--jobs", "0"],
    ["run", "--jobs", "many"],
    ["run", "--executor", "proces"],
    ["run", "--retry", "crash,bogus"],
    ["run", "--seeds"],                               # option without its value
    ["list", "widgets"],
    ["list"],
    ["leaderboard"],
    ["leaderboard", "x.sqlite", "--format", "yaml"],
    ["report", "x.sqlite"],                           # -o is required
    ["export-ompl", "x.sqlite"],
    ["show", "gant.fig7"],
    ["tune"],
    ["reproduce", "ggaco", "--iterations", "-3"],
    ["completion", "fish"],
]


@pytest.mark.parametrize("argv", USAGE_ERRORS, ids=lambda a: " ".join(a) or "(nothing)")
def test_usage_error_is_one_line(argv, capsys):
    assert main(argv) == 2
    captured = capsys.readouterr()
    assert captured.out == ""
    lines = captured.err.splitlines()
    assert len(lines) == 1, captured.err
    assert lines[0].startswith("pathzoo: error: ") and "usage:" not in lines[0]


def test_usage_error_names_the_subcommand_and_the_option(capsys):
    assert main(["run", "--jobs", "0"]) == 2
    assert capsys.readouterr().err == (
        "pathzoo: error: run: argument --jobs: must be a positive integer, got '0' (see 'pathzoo run --help')\n")


def test_invalid_choice_suggests_the_closest(capsys):
    assert main(["run", "--executor", "proces"]) == 2
    assert "invalid choice 'proces'; did you mean 'process'?" in capsys.readouterr().err


def test_help_still_prints_usage_and_exits_0(capsys):
    assert main(["run", "--help"]) == 0
    assert capsys.readouterr().out.startswith("usage: pathzoo run")


def test_closest_match_comes_first():
    # the old registry hint listed the family's ids in registration order: aco.acs before aco.mmas
    assert closest("aco.mmsa", ["aco.as", "aco.acs", "aco.mmas", "aco.gant"])[0] == "aco.mmas"
    assert closest("lenght", ["energy", "length_ratio", "length"])[0] == "length"


def test_unknown_planner_suggests_the_closest_first():
    from pathzoo.core.errors import UnknownPluginError
    from pathzoo.plugins.manager import get_registry

    with pytest.raises(UnknownPluginError, match=r"unknown planner 'aco.mmsa'; did you mean (one of )?'aco.mmas'"):
        get_registry().get("planners", "aco.mmsa")


def test_mistyped_metric_gets_did_you_mean(tmp_path, capsys):
    from pathzoo.analysis.frame import metric_info
    from pathzoo.core.errors import UnknownPluginError

    with pytest.raises(UnknownPluginError, match=r"unknown metric 'lenght'; did you mean (one of )?'length'"):
        metric_info("lenght")
