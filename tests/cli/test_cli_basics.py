"""The pathzoo command: --help, --version, ``list``, ``show`` and the one-line error contract."""

from __future__ import annotations

import importlib.metadata as md
import subprocess
import sys
from pathlib import Path

import pytest

import pathzoo
from pathzoo.cli import cmd_list
from pathzoo.cli.main import main
from pathzoo.plugins import manager

PATHZOO = Path(sys.executable).parent / "pathzoo"
COMMANDS = ("list", "run", "tune", "reproduce", "leaderboard", "report", "export-ompl", "show", "compare", "merge", "completion")


def error_lines(stderr: str) -> list[str]:
    """Stderr lines other than the registry's warnings about plugins that failed to load."""
    return [ln for ln in stderr.splitlines() if not ln.startswith("pathzoo: plugin '")]


def test_console_script_is_installed_and_prints_version():
    out = subprocess.run([str(PATHZOO), "--version"], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == f"pathzoo {md.version('pathzoo')}"


@pytest.mark.parametrize("command", COMMANDS)
def test_every_subcommand_has_help(command, capsys):
    assert main([command, "--help"]) == 0
    out = capsys.readouterr().out
    assert out.startswith(f"usage: pathzoo {command}")


def test_top_level_help_lists_subcommands(capsys):
    assert main(["--help"]) == 0
    out = capsys.readouterr().out
    for command in COMMANDS:
        assert command in out


@pytest.mark.parametrize("kind", ["planners", "scenarios", "metrics"])
def test_list_shows_each_entry_with_its_distribution_and_version(kind, capsys):
    assert main(["list", kind]) == 0
    out = capsys.readouterr().out.splitlines()
    entries = pathzoo.list_plugins(kind)
    if not entries:
        assert out == [f"no {kind} registered"]
        return
    header = out[0]
    assert header.split()[0] == "id" and "distribution" in header and "summary" in header
    col = header.index("distribution")
    vcol = header.index("version")
    rows = {ln.split()[0]: ln for ln in out[2:]}
    assert sorted(rows) == [e.id for e in entries]
    for e in entries:
        row = rows[e.id]
        assert row[col:].split()[0] == e.distribution  # aligned under its header
        assert row[vcol:].split()[0] == e.version
        assert row.rstrip().endswith(e.summary)


def test_list_reports_skipped_plugins_at_the_end_on_stderr(monkeypatch, capsys):
    group = manager.KIND_GROUPS["planners"]
    real = list(md.entry_points(group=group))
    broken = md.EntryPoint("broken", "pathzoo_no_such_module_xyz", group)
    original = manager.discover
    monkeypatch.setattr(manager, "discover", lambda entry_points=None, kinds=manager.KINDS: original([*real, broken],
                                                                                                      kinds))
    assert main(["list", "planners"]) == 0
    captured = capsys.readouterr()
    lines = captured.err.strip().splitlines()
    assert all(ln.startswith("skipped: ") for ln in lines)
    assert "skipped: broken: import failed: ModuleNotFoundError: No module named 'pathzoo_no_such_module_xyz'" in lines
    assert "broken" not in captured.out


def test_list_table_columns_are_aligned():
    entries = [
        pathzoo.PluginEntry("a.b", "short", type("P", (), {"kinds": {"grid2d"}}), "x", "dist-one", "1.0"),
        pathzoo.PluginEntry("family.longer_name", "a longer summary", type("P", (), {"kinds": {"air3d", "terrain"}}),
                            "x", "d", "10.2.3"),
    ]
    lines = cmd_list.list_table(entries, "planners").splitlines()
    starts = [[i for i in range(1, len(ln)) if ln[i - 1] == " " and ln[i] != " " and ln[i - 2:i] == "  "]
              for ln in lines[:1] + lines[2:]]
    assert starts[0] == starts[1] == starts[2]
    assert lines[3].split() == ["family.longer_name", "air3d,terrain", "d", "10.2.3", "a", "longer", "summary"]


@pytest.mark.slow
def test_show_writes_a_png_of_the_scenario(tmp_path, capsys):
    scenario = tmp_path / "hill.toml"
    scenario.write_text(
        'id = "cli.hill"\nkind = "terrain"\ncell_size = 10.0\nstart_cell = [2, 2]\ngoal_cell = [20, 25]\n'
        '[elevation]\ngenerator = "fractal"\nseed = 3\nshape = [24, 30]\nrelief = 20.0\n'
    )
    out = tmp_path / "map.png"
    assert main(["show", str(scenario), "-o", str(out)]) == 0
    assert capsys.readouterr().out.strip() == f"wrote {out}"
    from matplotlib.image import imread

    image = imread(out)
    assert image.ndim == 3 and image.shape[0] > 100 and image.shape[1] > 100
    assert image[..., :3].std() > 0.05  # not a blank canvas


def _one_error(capsys) -> str:
    captured = capsys.readouterr()
    lines = error_lines(captured.err)
    assert len(lines) == 1, captured.err
    assert lines[0].startswith("pathzoo: error: ")
    assert "Traceback" not in captured.err
    return lines[0]


def test_unknown_scenario_is_one_line(capsys, tmp_path):
    assert main(["show", "no.such.scenario", "-o", str(tmp_path / "x.png")]) == 2
    assert "unknown scenario 'no.such.scenario'" in _one_error(capsys)


def test_show_into_missing_directory_is_one_line(capsys, tmp_path):
    assert main(["show", "whatever", "-o", str(tmp_path / "nope" / "x.png")]) == 2
    assert _one_error(capsys) == f"pathzoo: error: {tmp_path / 'nope'}: output directory does not exist"


def test_leaderboard_of_missing_file_is_one_line(capsys, tmp_path):
    missing = tmp_path / "missing.sqlite"
    assert main(["leaderboard", str(missing)]) == 2
    assert _one_error(capsys) == f"pathzoo: error: {missing}: no such results database"
    assert not missing.exists()  # never created by a read


def test_run_of_missing_experiment_is_one_line(capsys, tmp_path):
    assert main(["run", str(tmp_path / "nope.toml"), "--db", str(tmp_path / "r.sqlite")]) == 2
    assert _one_error(capsys) == f"pathzoo: error: {tmp_path / 'nope.toml'}: no such experiment file"


def test_dask_address_needs_dask_executor(capsys, tmp_path):
    assert main(["run", "--dask-address", "tcp://127.0.0.1:1", "--db", str(tmp_path / "r.sqlite")]) == 2
    assert _one_error(capsys) == "pathzoo: error: --dask-address needs --executor dask"


@pytest.mark.parametrize(
    ("exc", "message"),
    [
        (KeyboardInterrupt(), "interrupted"),
        (pathzoo.InvalidParameterError("planner x: parameter 'a' must be int in [1, inf), got 0"),
         "planner x: parameter 'a' must be int in [1, inf), got 0"),
        (pathzoo.InvalidScenarioError("two\nlines", source="f.toml"), "f.toml: two lines"),
        (PermissionError(13, "Permission denied", "/root/x"), "/root/x: Permission denied"),
    ],
)
def test_handled_errors_become_one_line_with_exit_2(monkeypatch, capsys, exc, message):
    def boom(args):
        raise exc

    monkeypatch.setattr(cmd_list, "_run", boom)
    assert main(["list", "planners"]) == 2
    assert _one_error(capsys) == f"pathzoo: error: {message}"


def test_unexpected_errors_are_not_hidden(monkeypatch):
    def bug(args):
        raise ZeroDivisionError("a bug")

    monkeypatch.setattr(cmd_list, "_run", bug)
    with pytest.raises(ZeroDivisionError):
        main(["list", "planners"])


@pytest.mark.slow
def test_error_through_the_console_script_has_no_traceback(tmp_path):
    proc = subprocess.run(
        [str(PATHZOO), "show", "no.such.scenario", "-o", str(tmp_path / "x.png")], capture_output=True, text=True
    )
    assert proc.returncode == 2
    lines = error_lines(proc.stderr)
    assert len(lines) == 1 and lines[0].startswith("pathzoo: error: unknown scenario 'no.such.scenario'")
