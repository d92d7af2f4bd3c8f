"""
Shortest or least energy on real terrain
========================================

On hilly ground the shortest path is rarely the cheapest to drive. Here
``exact.astar`` plans twice on a real elevation model (the Hugo site of the
GGACO paper, 10 m cells): once minimising 3-D length and once minimising the
energy of G-Ant's power model (eq. 4, see :doc:`/energy`). The harness
measures both paths with the same metrics, whatever each planner minimised,
so the two answers compare directly.

``PATHZOO_DOCS_BUDGET=full`` uses the larger Front Range DEM instead.
"""

# %%
# Run both configurations
# -----------------------
# A planner may appear several times with different parameters; each
# configuration gets its own parameter hash in the run key. The search is
# exact and deterministic, so one seed is enough.

import os
import tempfile
from pathlib import Path

import matplotlib.pyplot as plt

import pathzoo
from pathzoo.harness import read_path
from pathzoo.plotting.paths import plot_paths

FULL = os.environ.get("PATHZOO_DOCS_BUDGET", "tiny") == "full"
SCENARIO = "ggaco.frontrange" if FULL else "ggaco.hugo"

db = Path(tempfile.mkdtemp()) / "terrain.sqlite"
runs = pathzoo.run(
    [("exact.astar", {"cost": "length"}), ("exact.astar", {"cost": "energy"})],
    [SCENARIO],
    seeds=1,
    budget=pathzoo.Budget(time_s=30),
    db=db,
    experiment="energy-vs-length",
    executor="inline",
    progress=False,
)
runs["objective"] = runs["params"].map(lambda p: p["cost"])

# %%
# Length, energy and the rest
# ---------------------------
# Every metric is computed by the harness from the returned path: length
# and energy, the driving time at cruise speed, the number of turns and the
# smallest clearance to an untraversable cell.

columns = ["status", "length", "energy", "travel_time", "turns", "clearance_min"]
table = runs.set_index("objective")[columns]
table

# %%
# The least-energy path is longer but cheaper. In relative terms:

length_cost = table.loc["energy", "length"] / table.loc["length", "length"] - 1
energy_saved = 1 - table.loc["energy", "energy"] / table.loc["length", "energy"]
print(f"{length_cost:.1%} longer, {energy_saved:.1%} less energy")

# %%
# The two paths on the hillshaded terrain
# ---------------------------------------
# Blocked cells (too steep, or outside the DEM) are dark grey. The stored
# paths are read back from the database with
# :func:`pathzoo.harness.read_path`.

scenario = pathzoo.load_scenario(SCENARIO)
paths = {
    f"minimise {row.objective}": read_path(db, "energy-vs-length", row.run_key)[0]
    for row in runs.itertuples()
}
fig, ax = plt.subplots(figsize=(8, 6.5), layout="constrained")
plot_paths(scenario, paths, ax=ax)
