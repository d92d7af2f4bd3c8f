"""
A planner in C behind the protocol
==================================

Any program that reads one JSON problem on standard input and writes one
JSON answer on standard output is a planner (:doc:`/external-planners`).
``examples/external/astar.c`` is an A* in about 150 lines of C, compiled
here with the system's C compiler and compared with pathzoo's
``exact.astar``. Both search the same 8-connected grid without cutting
corners, so their path lengths must agree; the harness judges the C
program's paths like any other.
"""

# %%
# Compile it
# ----------

import shutil
import subprocess
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt

import pathzoo
from pathzoo.analysis import format_leaderboard, leaderboard
from pathzoo.harness import Experiment, read_path, run_experiment
from pathzoo.plotting.paths import plot_paths

# sphinx-gallery runs the examples in their folder, without __file__
GALLERY = Path(__file__).resolve().parent if "__file__" in globals() else Path.cwd()
ASTAR_C = GALLERY.parent / "external" / "astar.c"
folder = Path(tempfile.mkdtemp())
compiler = shutil.which("cc") or shutil.which("gcc")
program = None
if compiler is None:
    print("no C compiler (cc) here: this example is skipped")
else:
    subprocess.run([compiler, "-O2", "-o", str(folder / "astar"), str(ASTAR_C), "-lm"], check=True)
    program = folder / "astar"
    print("built", program)

# %%
# The experiment file
# -------------------
# ``command`` is the program and its arguments; an argument naming a file
# next to the experiment file is made absolute. ``gant.complex.1`` has
# 500 x 500 cells, more than a problem carries inline: its occupancy
# reaches the program as the path of an ``.npy`` file, which astar.c reads
# too.

experiment_file = """
[experiment]
name = "c-astar"
seeds = 1
budget = { time_s = 30 }
scenarios = ["gant.fig7", "movingai.random-32-32-20.b10.13", "gant.complex.1"]

[[planner]]
id = "exact.astar"

[[planner]]
command = ["./astar"]
label = "c-astar"
"""
(folder / "c-astar.toml").write_text(experiment_file)

# %%
# Run it
# ------
# The wall time of an external run includes starting the program and
# reading and writing the JSON (a few milliseconds here; see the
# per-run overhead in ``benchmarks/harness.py``).

if program is not None:
    runs = run_experiment(Experiment.from_toml(folder / "c-astar.toml"), db=folder / "c.sqlite", executor="inline",
                          progress=False)
    print(format_leaderboard(leaderboard(runs, "length")))
    print(runs[["scenario", "label", "valid", "length", "wall_time_s"]].to_string(index=False))

# %%
# Both paths on the 32 x 32 map: equally long, not necessarily the same
# (A* breaks ties between equally short paths in its own order).

if program is not None:
    scenario = "movingai.random-32-32-20.b10.13"
    rows = runs[runs["scenario"] == scenario]
    paths = {row.label: read_path(folder / "c.sqlite", "c-astar", row.run_key)[0] for row in rows.itertuples()}
    fig, ax = plt.subplots(figsize=(6.5, 6.5), layout="constrained")
    plot_paths(pathzoo.load_scenario(scenario), paths, ax=ax)
