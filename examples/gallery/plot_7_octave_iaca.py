"""
An ant colony written in Octave against pathzoo's own
=====================================================

The planners pathzoo compares were published as MATLAB code. Here one of
them joins the comparison as it would be written for MATLAB: an Octave
function file, ``examples/external/iaca.m``, written from the IACA paper
(Wang et al. 2018; eqs. 13-21, parameters of its section 4.1). An
experiment file declares it with one ``octave = ...`` line, and it runs
against pathzoo's compiled ``aco.iaca`` on the paper's terrain,
``iaca.offroad``: same seeds, same judge, same metrics. The protocol is in
:doc:`/external-planners`.

The budget is tiny when the documentation is built (3 seeds, 10 colony
iterations). With ``PATHZOO_DOCS_BUDGET=full`` it is the paper's setting
and the verdict below: 10 seeds of 100 iterations x 40 ants.
"""

# %%
# The experiment file
# -------------------
# ``octave`` names the function file (relative paths are relative to the
# experiment file); ``label`` names the planner in tables (its id becomes
# ``external.iaca-octave``) and ``kinds`` says which scenarios it plans on.
# One GNU Octave process per worker serves every run, so Octave starts once,
# not once per run; the shim seeds Octave's generators from each run's seed.

import os
import shutil
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt

import pathzoo
from pathzoo.analysis import format_leaderboard, leaderboard
from pathzoo.analysis.stats import pairwise_tests
from pathzoo.harness import Experiment, read_path, run_experiment
from pathzoo.plotting.boxplots import plot_metric_boxes
from pathzoo.plotting.paths import plot_paths

FULL = os.environ.get("PATHZOO_DOCS_BUDGET", "tiny") == "full"
SEEDS, ITERATIONS = (10, 100) if FULL else (3, 10)
# sphinx-gallery runs the examples in their folder, without __file__
GALLERY = Path(__file__).resolve().parent if "__file__" in globals() else Path.cwd()
IACA_M = GALLERY.parent / "external" / "iaca.m"
HAVE_OCTAVE = shutil.which("octave-cli") is not None

experiment_file = f"""
[experiment]
name = "iaca-octave"
seeds = {SEEDS}
budget = {{ iterations = {ITERATIONS}, time_s = 600 }}
scenarios = ["iaca.offroad"]

[[planner]]
id = "aco.iaca"
"""
if HAVE_OCTAVE:
    experiment_file += f"""
[[planner]]
octave = "{IACA_M}"
label = "iaca-octave"
kinds = ["terrain", "grid2d"]
"""
else:
    print("GNU Octave is not installed here (apt-get install octave): only aco.iaca runs")
print(experiment_file)

# %%
# Run it
# ------
# The ``inline`` executor runs everything in this process; ``pathzoo run
# iaca.toml`` would use worker processes, one Octave process each.

folder = Path(tempfile.mkdtemp())
(folder / "iaca.toml").write_text(experiment_file)
experiment = Experiment.from_toml(folder / "iaca.toml")
db = folder / "iaca.sqlite"
runs = run_experiment(experiment, db=db, executor="inline", progress=False)
runs[["label", "seed_index", "status", "valid", "length", "wall_time_s"]]

# %%
# The verdict
# -----------
# The two implementations draw different random numbers, so their runs are
# not paired by seed: Mann-Whitney U on the path length, with Vargha and
# Delaney's A12 (:doc:`/statistics`). In the full setting (10 seeds) the
# test finds no significant difference: p = 0.34, A12 = 0.37 (small), median
# length 331 m for ``aco.iaca`` and 315 m for the Octave file. Octave needs
# about 15 s per run where the compiled colony needs 0.07 s.

print(format_leaderboard(leaderboard(runs, "length")))
if runs["label"].nunique() == 2:
    print(pairwise_tests(runs, "length", paired=False)[["a", "b", "n_a", "n_b", "test", "p", "a12", "magnitude",
                                                         "winner"]].to_string(index=False))

# %%
# Lengths and the best paths
# --------------------------

fig, ax = plt.subplots(figsize=(6, 4), layout="constrained")
plot_metric_boxes(runs, "length", ax=ax)

best = runs[runs["valid"]].sort_values("length").groupby("label").head(1)
paths = {row.label: read_path(db, "iaca-octave", row.run_key)[0] for row in best.itertuples()}
fig, ax = plt.subplots(figsize=(6.5, 6.5), layout="constrained")
plot_paths(pathzoo.load_scenario("iaca.offroad"), paths, ax=ax)
