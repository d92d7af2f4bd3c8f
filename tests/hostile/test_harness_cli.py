"""Malformed input and missing extras at the command line: one line on stderr, exit code 2, never a traceback.

Each case printed a traceback (or wrote ``DIR.png``, or ran a planner whose
dependency is missing at 0 % success) before issue 11.
"""

from __future__ import annotations

import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from pathzoo.cli.main import main

ARENA = "movingai.arena.b0.1"


def one_line_error(capsys, argv: list[str]) -> str:
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("pathzoo: error: ") and err.count("\n") == 1 and "Traceback" not in err, err
    return err


def scenario_toml(tmp_path: Path, table: str, data: bytes, name: str) -> Path:
    (tmp_path / name).write_bytes(data)
    path = tmp_path / "s.toml"
    path.write_text(f'id = "t.bad"\nkind = "{"terrain" if table == "elevation" else "grid2d"}"\n'
                    f'start_cell = [0, 1]\ngoal_cell = [1, 1]\n[{table}]\nfile = "{name}"\n')
    return path


def test_non_utf8_experiment_toml(tmp_path, capsys):
    path = tmp_path / "e.toml"
    path.write_bytes(b'[experiment]\nname = "\xff\xfe"\n')
    assert "e.toml: not UTF-8 text" in one_line_error(capsys, ["run", str(path), "--no-progress"])


def test_non_utf8_map_and_asc(tmp_path, capsys):
    path = scenario_toml(tmp_path, "map", b"type octile\nheight 2\nwidth 2\nmap\n\xff.\n..\n", "bad.map")
    assert "bad.map: not UTF-8 text" in one_line_error(capsys, ["show", str(path), "-o", str(tmp_path / "x.png")])
    path = scenario_toml(tmp_path, "elevation", b"ncols 2\n\xff\n", "bad.asc")
    assert "bad.asc: not UTF-8 text" in one_line_error(capsys, ["show", str(path), "-o", str(tmp_path / "x.png")])


def test_npz_that_is_not_a_zip(tmp_path, capsys):
    path = scenario_toml(tmp_path, "map", b"not a zip at all", "bad.npz")
    assert "not a NumPy file" in one_line_error(capsys, ["show", str(path), "-o", str(tmp_path / "x.png")])


def test_absurd_seed_count_fails_at_once_without_creating_the_database(tmp_path, capsys):
    path = tmp_path / "e.toml"
    path.write_text(f'[experiment]\nseeds = 100000000\nscenarios = ["{ARENA}"]\n[[planner]]\nid = "exact.astar"\n')
    assert "seeds must be between 1 and 100000" in one_line_error(capsys, ["run", str(path), "--db",
                                                                           str(tmp_path / "r.sqlite")])
    assert not (tmp_path / "r.sqlite").exists()


def test_bad_dask_address(tmp_path, capsys):
    path = tmp_path / "e.toml"
    path.write_text(f'[experiment]\nseeds = 1\nscenarios = ["{ARENA}"]\n[[planner]]\nid = "exact.astar"\n')
    err = one_line_error(capsys, ["run", str(path), "--executor", "dask", "--dask-address", "not-an-address",
                                  "--db", str(tmp_path / "r.sqlite"), "--no-progress"])
    assert "cannot connect to the Dask scheduler at 'not-an-address'" in err


@pytest.mark.parametrize("output, text", [("x.nope", "unknown image format '.nope'"), ("adir", "is a directory")])
def test_show_output_must_be_an_image_file(tmp_path, capsys, output, text):
    (tmp_path / "adir").mkdir()
    assert text in one_line_error(capsys, ["show", ARENA, "-o", str(tmp_path / output)])
    assert not (tmp_path / "adir.png").exists() and not (tmp_path / "x.nope").exists()


MISSING_PYSWARMS = ("import sys; sys.modules['pyswarms'] = None\n"
                    "from pathzoo.cli.main import main\nsys.exit(main({argv!r}))")


def cli_without_pyswarms(argv: list[str], cwd: Path) -> subprocess.CompletedProcess:
    """The CLI in a fresh interpreter where importing pyswarms fails, as if the 'evo' extra were not installed."""
    return subprocess.run([sys.executable, "-c", MISSING_PYSWARMS.format(argv=argv)], cwd=cwd, capture_output=True,
                          text=True, timeout=120)


def test_planner_with_a_missing_extra_is_listed_with_the_install_command_and_refused(tmp_path):
    listing = cli_without_pyswarms(["list", "planners"], tmp_path)
    line = next(l for l in listing.stdout.splitlines() if l.startswith("swarm.pso"))
    assert 'unavailable, needs pyswarms: pip install "pathzoo[evo]"' in line
    assert not any("unavailable" in l for l in listing.stdout.splitlines() if l.startswith("exact."))
    exp = tmp_path / "e.toml"
    exp.write_text(textwrap.dedent(f"""\
        [experiment]
        seeds = 1
        scenarios = ["{ARENA}"]
        [[planner]]
        id = "swarm.pso"
        """))
    run = cli_without_pyswarms(["run", str(exp), "--db", str(tmp_path / "r.sqlite")], tmp_path)
    assert run.returncode == 2 and "Traceback" not in run.stderr
    assert "planner 'swarm.pso' is not available here: it needs pyswarms: pip install \"pathzoo[evo]\"" in run.stderr
    assert not (tmp_path / "r.sqlite").exists()


def test_retry_flag_rejects_unknown_statuses(capsys):
    assert main(["run", "--retry", "crash,bogus"]) == 2
    assert "unknown status(es) ['bogus']" in capsys.readouterr().err
