"""An experiment with an Octave planner, a command-line planner and exact.astar: valid, judged, timed, reproducible.

This is issue 23's acceptance test: ``pathzoo run`` (worker processes) on
gant.fig7 and fgdaco.scenario1 stores a solved, validated, timed run for
every supported pair, and the same experiment run again in this process
(the inline executor) gives the same path for every run key.
"""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import numpy as np

from pathzoo.harness import read_path, read_runs

from .conftest import PROGRAMS, needs_octave

PATHZOO = Path(sys.executable).parent / "pathzoo"

EXPERIMENT = """
[experiment]
name = "bring-your-own"
seeds = 2
budget = {{ time_s = 30 }}
jobs = 2
scenarios = ["gant.fig7", "fgdaco.scenario1"]

[[planner]]
id = "exact.astar"

[[planner]]
octave = "{octave}"
label = "octave-shortest"
kinds = ["grid2d", "dynamic"]

[[planner]]
command = ["{astar}"]
label = "c-astar"
kinds = ["grid2d", "dynamic"]
"""


@needs_octave
def test_octave_command_and_builtin_planners_store_valid_timed_reproducible_runs(tmp_path, astar_program):
    toml = tmp_path / "byo.toml"
    toml.write_text(EXPERIMENT.format(octave=PROGRAMS / "shortest.m", astar=astar_program))
    db = tmp_path / "process.sqlite"
    proc = subprocess.run([str(PATHZOO), "run", str(toml), "--db", str(db), "--no-progress"],
                          capture_output=True, text=True, timeout=600)
    assert proc.returncode == 0, proc.stderr
    runs = read_runs(db, "bring-your-own")
    pairs = {(p, s) for p, s in zip(runs["planner"], runs["scenario"])}
    assert pairs == {
        ("exact.astar", "gant.fig7"),  # exact.astar does not declare dynamic scenarios: that pair is skipped
        ("external.octave-shortest", "gant.fig7"), ("external.octave-shortest", "fgdaco.scenario1"),
        ("external.c-astar", "gant.fig7"), ("external.c-astar", "fgdaco.scenario1"),
    }
    assert len(runs) == 10
    assert runs["status"].eq("solved").all() and runs["valid"].all(), runs[["planner", "message"]].to_string()
    assert all(math.isfinite(t) and t > 0 for t in runs["wall_time_s"])
    assert set(runs["label"]) == {"exact.astar", "octave-shortest", "c-astar"}
    versions = runs.groupby("planner")["planner_version"].first()
    assert len(versions["external.octave-shortest"]) == 12  # the digest of the function's folder
    # the judge's lengths: each external planner's path is as short as A*'s on the static map
    fig7 = runs[runs["scenario"] == "gant.fig7"]
    assert np.allclose(fig7["length"], fig7.loc[fig7["planner"] == "exact.astar", "length"].iloc[0])

    # the same experiment, run again in this process, gives the same paths
    from pathzoo.harness import Experiment, run_experiment

    again = run_experiment(Experiment.from_toml(toml), db=tmp_path / "inline.sqlite", executor="inline",
                           progress=False)
    assert sorted(again["run_key"]) == sorted(runs["run_key"])
    for key in runs["run_key"]:
        first, _ = read_path(db, "bring-your-own", key)
        second, _ = read_path(tmp_path / "inline.sqlite", "bring-your-own", key)
        assert np.array_equal(first, second), key
