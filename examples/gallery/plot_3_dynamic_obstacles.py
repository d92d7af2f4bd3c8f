"""
Planning around moving obstacles
================================

``dynamic`` scenarios add moving obstacles to an occupancy map: discs that
drive back and forth along known routes, so their positions are functions
of time. A planner must return a path that no obstacle touches at the
moment the vehicle passes; the harness checks this exactly, segment by
segment, when it validates the path.

Here ``aco.fgdaco`` (the fuzzy gain-based dynamic ACO of Sangeetha et al.
2021) plans on scenario 1 of its paper. ``PATHZOO_DOCS_BUDGET=full`` runs
more seeds and iterations.
"""

# %%
# Run the planner
# ---------------
# ``length_ratio`` is undefined on dynamic scenarios (NaN): the shortest
# path of the static map ignores the moving obstacles, so it is only a lower
# bound. That bound still makes a yardstick: the same map without the moving
# obstacles is registered as ``fgdaco.scenario1_static``.

import os
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import Circle

import pathzoo
from pathzoo.harness import read_path
from pathzoo.grid.reference import reference_length
from pathzoo.rules import path_times
from pathzoo.plotting.scenario import plot_scenario

FULL = os.environ.get("PATHZOO_DOCS_BUDGET", "tiny") == "full"
SEEDS = 10 if FULL else 3
ITERATIONS = 100 if FULL else 10
BUDGET = pathzoo.Budget(iterations=ITERATIONS, time_s=60)
PLANNER = "aco.fgdaco"

db = Path(tempfile.mkdtemp()) / "dynamic.sqlite"
runs = pathzoo.run(
    [PLANNER],
    ["fgdaco.scenario1"],
    seeds=SEEDS,
    budget=BUDGET,
    db=db,
    experiment="dynamic",
    executor="inline",
    progress=False,
)
static_optimum = reference_length(pathzoo.load_scenario("fgdaco.scenario1_static"))
runs["over_static_optimum"] = runs["length"] / static_optimum
print(f"static optimum: {static_optimum:.2f} m")
runs[["seed_index", "status", "length", "over_static_optimum", "travel_time"]]

# %%
# The map, the obstacles' routes and the path
# -------------------------------------------
# The moving obstacles are drawn at ``t = 0`` with an arrow for their first
# heading; their routes are dashed. The path is the median-length
# successful run.

scenario = pathzoo.load_scenario("fgdaco.scenario1")
solved = runs[runs["valid"]].sort_values("length")
best = solved.iloc[len(solved) // 2]
path, times = read_path(db, "dynamic", best.run_key)
if times is None:  # the planner drove at cruise speed without waiting
    times = path_times(scenario, path)

fig, ax = plt.subplots(figsize=(7, 8), layout="constrained")
plot_scenario(scenario, path, ax=ax, title=f"{PLANNER}, seed {best.seed_index}")

# %%
# Where everything is along the way
# ---------------------------------
# Snapshots at four moments of the drive: the vehicle (red dot) and each
# obstacle at that same time (blue discs; the orange ones stay at their
# ``t = 0`` positions). ``MovingObstacle.position(t)`` gives an obstacle's
# centre at any time, and ``MovingObstacle.min_distance`` the exact closest
# approach to the vehicle over one straight segment of the path.

segments = list(zip(path[:-1], path[1:], times[:-1], times[1:]))
obstacles = scenario.moving_obstacles
closest = [min(obs.min_distance(*seg) for seg in segments) for obs in obstacles]
print("closest approach to each moving obstacle [m]:", np.round(closest, 2))
print("obstacle radii [m]:", [obs.radius for obs in obstacles])

fig, axes = plt.subplots(2, 2, figsize=(9, 9), layout="constrained")
for ax, t in zip(axes.ravel(), np.linspace(0.15, 0.85, 4) * times[-1]):
    plot_scenario(scenario, path, ax=ax, legend=False, title=f"t = {t:.0f} s")
    here = np.array([np.interp(t, times, path[:, 0]), np.interp(t, times, path[:, 1])])
    ax.plot(*here, "o", color="#d62728", mec="black", ms=9, zorder=9)
    for obs in obstacles:
        disc = Circle(obs.position(t), obs.radius, color="#1f77b4", alpha=0.8, zorder=8)
        ax.add_patch(disc)
