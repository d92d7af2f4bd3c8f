"""
Compare the ant-colony variants on a grid
=========================================

Every ant-colony planner that pathzoo has registered (``aco.*``) runs
against the exact optimum (``exact.astar``) on two grid maps: the 10 x 10
space of G-Ant's Fig. 7 and a 32 x 32 MovingAI map with random obstacles.
The harness stores every run in an SQLite file; the leaderboard, the box
plots and the convergence curves are read back from it.

The budget is tiny when the documentation is built. Set the environment
variable ``PATHZOO_DOCS_BUDGET=full`` to run more seeds and iterations.
"""

# %%
# Which planners?
# ---------------
# The list is read from the plugin registry when the example runs, so a
# variant registered later (by pathzoo or by an installed plugin) joins the
# comparison without editing this file. Only variants that declare the
# ``grid2d`` scenario kind can plan on these maps.

import os
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt

import pathzoo
from pathzoo.analysis import format_leaderboard, leaderboard
from pathzoo.harness import read_history
from pathzoo.plotting.boxplots import plot_metric_boxes
from pathzoo.plotting.convergence import plot_convergence

FULL = os.environ.get("PATHZOO_DOCS_BUDGET", "tiny") == "full"
SEEDS = 10 if FULL else 3
ITERATIONS = 200 if FULL else 15
BUDGET = pathzoo.Budget(iterations=ITERATIONS, time_s=30)

colonies = [e for e in pathzoo.list_plugins("planners") if e.id.startswith("aco.")]
aco = [e.id for e in colonies if "grid2d" in e.obj.kinds]
print("ant colonies for grid maps:", ", ".join(aco))
others = [e.id for e in colonies if e.id not in aco]
print("other ant colonies:", ", ".join(others) or "none")

# %%
# Run the experiment
# ------------------
# ``pathzoo.run`` builds the experiment (planners x scenarios x seeds), runs
# it, validates every path and returns one row per run (the table below
# shows the share of valid solutions). The ``inline``
# executor runs in this process: for runs this short, starting worker
# processes would take longer than the runs. A script that uses the default
# process executor must call ``pathzoo.run`` under
# ``if __name__ == "__main__":``.

scenarios = ["gant.fig7", "movingai.random-32-32-20.b7.0"]
db = Path(tempfile.mkdtemp()) / "aco.sqlite"
runs = pathzoo.run(
    ["exact.astar", *aco],
    scenarios,
    seeds=SEEDS,
    budget=BUDGET,
    db=db,
    experiment="aco-variants",
    executor="inline",
    progress=False,
)
runs.pivot_table(index="planner", columns="scenario", values="valid", aggfunc="mean")

# %%
# Leaderboard
# -----------
# Ranked within each scenario by the length ratio (path length over the
# exact optimum, so 1 is optimal). A run that did not succeed counts as worse
# than every successful one, so a planner cannot rank well by failing on the
# hard seeds. With a handful of seeds no difference is significant; the
# tests need more (see :doc:`/statistics`).

print(format_leaderboard(leaderboard(runs, "length_ratio")))

# %%
# Distributions
# -------------
# One box per planner and scenario, over the successful runs. A success rate
# below 100 % is printed above its box.

fig, ax = plt.subplots(figsize=(8, 4.5), layout="constrained")
plot_metric_boxes(runs, "length_ratio", ax=ax)

# %%
# Convergence
# -----------
# Each planner reports its best cost whenever it improves. The variants
# minimise different objectives (length, or costs that add energy or
# penalties), so each run's best cost is divided by its final value: the
# curves show how fast each variant settles, and they all end at 1.
# Median and interquartile band over seeds, on the MovingAI map.

history = read_history(db, "aco-variants")
history["best_cost"] /= history.groupby("run_key")["best_cost"].transform("min")
fig, ax = plt.subplots(figsize=(8, 5), layout="constrained")
plot_convergence(history, runs, scenarios[1], x="iteration", ax=ax)
ax.set_ylabel("best cost / final best cost")
