"""The tuning objective: a scale-free, failure-penalised score of one configuration on the training scenarios.

For each run, the **length ratio** (path length over the scenario's exact
graph optimum, metric ``length_ratio``) if the harness validated the path,
capped at :data:`WORST_RATIO`; a failed run (no path, invalid path, crash,
timeout) scores :data:`WORST_RATIO`, the worst value the score can take, as
failures rank worst in the leaderboard. Per scenario the **median** over
seeds, then the **mean** over scenarios. Smaller is better.

Why this aggregate: ratios make maps of different sizes comparable (a 400 m
terrain does not outweigh a 60 m room); the median per scenario is the
leaderboard's own statistic and robust to one unlucky seed; the mean over
scenarios keeps every training scenario in the score (a median over
scenarios would ignore the hardest ones).
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from pathzoo.analysis.frame import success_mask
from pathzoo.core.errors import InvalidExperimentError

__all__ = ["WORST_RATIO", "penalized_ratios", "trial_score"]

WORST_RATIO = 10.0
"""Score of a failed run, and cap of a successful run's length ratio."""


def penalized_ratios(runs: pd.DataFrame) -> np.ndarray:
    """Per run: the length ratio capped at :data:`WORST_RATIO`, or :data:`WORST_RATIO` for a failed run.

    Raises
    ------
    InvalidExperimentError
        A successful run has no length ratio (its scenario has no reference
        length, e.g. a dynamic scenario without ``reference_length``).
    """
    ok = success_mask(runs).to_numpy()
    ratio = runs["length_ratio"].to_numpy(dtype=np.float64) if "length_ratio" in runs else np.full(len(runs), np.nan)
    missing = ok & np.isnan(ratio)
    if missing.any():
        sid = runs.loc[missing, "scenario"].iloc[0]
        raise InvalidExperimentError(
            f"training scenario '{sid}' has no reference length, so no length ratio to tune on; "
            "train on scenarios with one"
        )
    return np.where(ok, np.minimum(ratio, WORST_RATIO), WORST_RATIO)


def trial_score(runs: pd.DataFrame) -> float:
    """Mean over scenarios of the median penalised length ratio over seeds (smaller is better)."""
    if runs.empty:
        return math.nan
    values = pd.Series(penalized_ratios(runs), index=runs.index)
    return float(values.groupby(runs["scenario"].to_numpy()).median().mean())
