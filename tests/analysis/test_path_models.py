"""``model_ratio``: each planner against the optimum of its own path model, and the leaderboard naming it."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from pathzoo.analysis import format_leaderboard, leaderboard
from pathzoo.analysis.path_models import MODEL_RATIO, REFERENCE_COLUMN, path_models, with_model_ratio


def _runs() -> pd.DataFrame:
    rows = []
    for seed in range(3):
        # a static map: a grid planner and an any-angle planner, each with both ratios
        rows.append(dict(planner="exact.astar", scenario="static", length_ratio=1.0, length_ratio_anyangle=1.05,
                         arrival_ratio=math.nan))
        rows.append(dict(planner="exact.thetastar", scenario="static", length_ratio=0.97, length_ratio_anyangle=1.01,
                         arrival_ratio=math.nan))
        # a dynamic map: every planner is timed against SIPP
        rows.append(dict(planner="exact.sipp", scenario="moving", length_ratio=math.nan,
                         length_ratio_anyangle=math.nan, arrival_ratio=1.0))
        rows.append(dict(planner="aco.fgdaco", scenario="moving", length_ratio=math.nan,
                         length_ratio_anyangle=math.nan, arrival_ratio=1.2 + seed / 100))
    df = pd.DataFrame(rows)
    df["params_hash"] = "h"
    df["seed_index"] = np.repeat(np.arange(3), 4)
    df["status"] = "solved"
    df["valid"] = True
    return df


def test_declared_path_models():
    models = path_models(["exact.astar", "exact.thetastar", "exact.anyangle", "exact.sipp", "not.registered"])
    assert models == {"exact.astar": "grid", "exact.thetastar": "anyangle", "exact.anyangle": "anyangle",
                      "exact.sipp": "timed", "not.registered": "grid"}


def test_each_planner_takes_the_ratio_of_its_own_model():
    out = with_model_ratio(_runs())
    first = out.groupby("planner").first()
    assert first.loc["exact.astar", MODEL_RATIO] == 1.0  # length_ratio, not the any-angle 1.05
    assert first.loc["exact.thetastar", MODEL_RATIO] == 1.01  # the any-angle ratio, not 0.97 below the grid
    assert first.loc["aco.fgdaco", MODEL_RATIO] == 1.2
    assert first.loc["exact.astar", REFERENCE_COLUMN] == "graph optimum"
    assert first.loc["exact.thetastar", REFERENCE_COLUMN] == "any-angle optimum"
    assert first.loc["aco.fgdaco", REFERENCE_COLUMN] == "earliest arrival (SIPP)"


def test_missing_reference_is_named():
    runs = _runs()
    runs.loc[runs["planner"] == "exact.thetastar", "length_ratio_anyangle"] = math.nan
    out = with_model_ratio(runs)
    row = out[out["planner"] == "exact.thetastar"].iloc[0]
    assert math.isnan(row[MODEL_RATIO]) and row[REFERENCE_COLUMN] == "any-angle optimum (not computed here)"


def test_leaderboard_ranks_by_model_ratio_and_names_the_optimum():
    table = leaderboard(_runs(), "model_ratio")
    assert set(table["optimum"]) == {"graph optimum", "any-angle optimum", "earliest arrival (SIPP)"}
    static = table[table["scenario"] == "static"].set_index("config")
    assert static.loc["exact.astar", "median"] == 1.0 and static.loc["exact.thetastar", "median"] == 1.01
    text = format_leaderboard(table)
    assert "optimum" in text and "any-angle optimum" in text


def test_air_volumes_use_the_lazy_theta_bound_named_as_a_bound():
    runs = _runs()
    rows = runs["planner"] == "exact.thetastar"
    runs.loc[rows, "length_ratio_anyangle"] = math.nan  # no exact any-angle optimum in the air
    runs["length_ratio_anyangle_bound"] = math.nan
    runs.loc[rows, "length_ratio_anyangle_bound"] = 0.999
    row = with_model_ratio(runs)[rows].iloc[0]
    assert row[MODEL_RATIO] == 0.999 and row[REFERENCE_COLUMN] == "any-angle bound (Lazy Theta*, upper)"
