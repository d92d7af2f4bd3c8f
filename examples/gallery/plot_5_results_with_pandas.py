"""
Read results with pandas
========================

Everything the harness records goes to one SQLite file: one row per run
(with every metric as a column), the convergence history of every run, and
the experiments themselves. :mod:`pathzoo.harness` reads it all into pandas
DataFrames, so any question the built-in leaderboard does not answer is a
``groupby`` or a ``pivot_table`` away.
"""

# %%
# A small experiment to read
# --------------------------
# Two exact planners and two ant colonies on three small maps, a few seeds
# each. ``PATHZOO_DOCS_BUDGET=full`` runs more seeds and iterations.

import os
import sqlite3
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import pandas as pd

import pathzoo
from pathzoo.harness import read_experiments, read_history, read_runs

FULL = os.environ.get("PATHZOO_DOCS_BUDGET", "tiny") == "full"
db = Path(tempfile.mkdtemp()) / "results.sqlite"
runs = pathzoo.run(
    ["exact.astar", "exact.thetastar", "aco.as", "aco.mmas"],
    ["gant.fig7", "gant.acopso", "movingai.room-32-32-4.b5.0"],
    seeds=10 if FULL else 4,
    budget=pathzoo.Budget(iterations=100 if FULL else 10, time_s=30),
    db=db,
    experiment="pandas-demo",
    executor="inline",
    progress=False,
)

# %%
# The experiments in a file
# -------------------------
# An experiment name is bound to its seed, budget and time limit; the whole
# configuration is stored as JSON.

read_experiments(db)[["name", "seed", "budget", "timeout_s", "n_runs"]]

# %%
# One row per run
# ---------------
# ``pathzoo.run`` returned the runs of the experiment; ``read_runs`` reads
# the same frame from the file at any later time. The leading columns
# identify the run (planner, parameters and their hash, scenario, seed) and
# its outcome; one float column per metric follows. ``valid`` is true only
# for a solved run whose path the harness accepted.

runs = read_runs(db, "pandas-demo")
print(runs.columns.tolist())
columns = ["planner", "scenario", "seed_index", "status", "valid", "length"]
runs[columns].head(8)

# %%
# groupby: success rate and medians
# ---------------------------------
# Medians over successful runs only, always next to the success rate: a
# median of two lucky runs out of twenty is not a result.

ok = runs[runs["valid"]]
by_config = ["scenario", "planner"]
summary = pd.DataFrame(
    {
        "runs": runs.groupby(by_config).size(),
        "success": runs.groupby(by_config)["valid"].mean(),
        "median length": ok.groupby(by_config)["length"].median(),
        "median time [s]": ok.groupby(by_config)["planning_time"].median(),
    }
)
summary

# %%
# pivot_table: planners side by side
# ----------------------------------
# The median length ratio (1 = the grid optimum) with one column per
# planner. Theta* plans any-angle, off the grid's 8 directions, so it can
# score below 1.

ratio = ok.pivot_table(
    index="scenario", columns="planner", values="length_ratio", aggfunc="median"
)
ratio.round(3)

# %%
# A pandas plot of the same table.

fig, ax = plt.subplots(figsize=(8, 4), layout="constrained")
ratio.plot.bar(ax=ax, rot=0)
ax.axhline(1.0, color="black", lw=0.8, ls="--")
ax.set_ylabel("median length / grid optimum")
ax.set_xlabel("")
ax.legend(ncol=4, fontsize="small", loc="lower center", bbox_to_anchor=(0.5, 1.0))

# %%
# Convergence histories
# ---------------------
# ``read_history`` gives every improvement a planner reported: iteration,
# evaluations, best cost and the harness's clock. Joined with the runs on
# ``run_key``, it answers questions such as "after how many iterations was
# the final answer first found?".

history = read_history(db, "pandas-demo")
history = history.merge(runs[["run_key", "planner", "scenario"]], on="run_key")
final = history.groupby("run_key")["best_cost"].transform("min")
first_best = history[history["best_cost"] == final].groupby("run_key").first()
first_best.groupby(["scenario", "planner"])["iteration"].median().unstack()

# %%
# Plain SQL works too
# -------------------
# The ``runs`` table keeps each metric in a ``REAL`` column named
# ``metric:<id>``, so any SQLite client can read the results without pathzoo.

with sqlite3.connect(db) as conn:
    sql = pd.read_sql(
        'SELECT planner, COUNT(*) AS runs, AVG("metric:length") AS mean_length '
        "FROM runs WHERE valid GROUP BY planner ORDER BY mean_length",
        conn,
    )
sql
