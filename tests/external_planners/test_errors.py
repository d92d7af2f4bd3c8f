"""The errors a researcher meets with external planners: one line naming the planner and the cause, a crash row, exit 0."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from pathzoo.harness import Experiment, read_runs, run_experiment

from .conftest import PROGRAMS, needs_octave

PATHZOO = Path(sys.executable).parent / "pathzoo"

COMMANDS = {
    "floods": "import sys\nwhile True: sys.stdout.write('x' * 65536)",
    "sleeps": "import time; time.sleep(600)",
    "wrong-shape": "print('{\"status\": \"solved\", \"path\": [[0.5, 0.5, 9.5], [0.5, 9.5, 9.5]]}')",
    "chatty": "print('planning...'); print('{\"status\": \"failed\"}')",
    "exits": "import sys; sys.stderr.write('out of ideas\\n'); sys.exit(3)",
    "bad-status": "print('{\"status\": \"done\", \"path\": []}')",
}
CAUSES = {
    "external.floods": "wrote more than 64 MiB on standard output; the program was stopped",
    "external.sleeps": "no answer within 1.75 s; the program was stopped",
    "external.wrong-shape": "'path' point 0 must be [x, y] (2 numbers), got 3 numbers; the path has 2 rows",
    "external.chatty": 'standard output is not one JSON object (Expecting value at line 1 column 1); it begins "planning',
    "external.exits": "exited with code 3",
    "external.bad-status": "'status' must be one of solved, no_path, failed, got \"done\"",
    "external.missing": "cannot start './no-such-planner': no such program",
    "external.no-octave": "GNU Octave is not installed here ('/nonexistent/octave-cli' not found on PATH)",
}


def _toml(tmp_path: Path) -> Path:
    tables = "".join(
        f"\n[[planner]]\ncommand = ['{sys.executable}', '-c', '''{code}''']\nlabel = '{label}'\n"
        for label, code in COMMANDS.items())
    tables += '\n[[planner]]\ncommand = ["./no-such-planner"]\nlabel = "missing"\n'
    tables += f'\n[[planner]]\noctave = "{PROGRAMS / "shortest.m"}"\nlabel = "no-octave"\n'
    path = tmp_path / "errors.toml"
    path.write_text('[experiment]\nname = "errors"\nseeds = 1\nbudget = { time_s = 0.5 }\njobs = 2\n'
                    'scenarios = ["gant.fig7"]\n' + tables)
    return path


def test_every_broken_program_gives_a_one_line_crash_and_the_experiment_goes_on(tmp_path):
    db = tmp_path / "errors.sqlite"
    env = {**os.environ, "PATHZOO_OCTAVE": "/nonexistent/octave-cli"}
    proc = subprocess.run([str(PATHZOO), "run", str(_toml(tmp_path)), "--db", str(db), "--no-progress"],
                          capture_output=True, text=True, timeout=600, env=env)
    assert proc.returncode == 0, proc.stderr
    runs = read_runs(db, "errors").set_index("planner")
    assert set(runs.index) == set(CAUSES)
    for planner, cause in CAUSES.items():
        row = runs.loc[planner]
        first = row["message"].splitlines()[0]
        assert row["status"] == "crash", (planner, row["message"])
        assert first.startswith(f"{planner}: ") and cause in first, (planner, first)
        assert "Traceback" not in row["message"]
    assert runs.loc["external.exits", "message"] == "external.exits: exited with code 3\nstandard error:\nout of ideas"


@needs_octave
def test_octave_functions_that_fail_are_crashes_and_octave_recovers(tmp_path):
    toml = tmp_path / "octave-errors.toml"
    tables = "".join(f'\n[[planner]]\noctave = "{PROGRAMS / name}.m"\n' for name in
                     ("raises", "transposed", "spins", "shortest"))
    toml.write_text('[experiment]\nname = "octave-errors"\nseeds = 1\nbudget = { time_s = 0.5 }\n'
                    'scenarios = ["gant.fig7"]\n' + tables)
    runs = run_experiment(Experiment.from_toml(toml), db=tmp_path / "o.sqlite", executor="inline",
                          progress=False).set_index("planner")
    first = runs["message"].map(lambda m: m.split("\n")[0])
    assert list(runs["status"]) == ["crash", "crash", "crash", "solved"], runs["message"].to_dict()
    assert first["external.raises"] == ("external.raises: raises.m raised an error: raises: the map has 100 cells "
                                        "(raises, line 5)")
    assert first["external.transposed"] == (
        "external.transposed: transposed.m: 'path' point 0 must be [x, y] (2 numbers), got 3 numbers; the path has "
        "2 rows (a matrix of one row per coordinate? give one row per point)")
    assert first["external.spins"] == "external.spins: no answer within 1.75 s; the program was stopped"
    assert runs.loc["external.shortest", "valid"]  # the next run starts a new Octave
