"""Each planner's length (or arrival) against the reference optimum of its own path model.

A planner declares its path model (:data:`pathzoo.plugins.entries.PATH_MODELS`):

- ``grid``: moves between neighbouring cells; reference: the graph optimum
  (``length_ratio``);
- ``anyangle``: straight segments in any direction; reference: the exact
  any-angle optimum (``length_ratio_anyangle``, ``grid2d``), or in air
  volumes the Lazy Theta* length, an upper bound on that optimum
  (``length_ratio_anyangle_bound``, named as a bound);
- ``timed``: timed moves with waits among moving obstacles.

On ``dynamic`` scenarios every path is timed, so every planner is measured by
``arrival_ratio`` (arrival over SIPP's earliest arrival); SIPP's model is the
8-connected graph, so that reference is exact for grid and timed planners and
only a yardstick for any-angle ones, which can arrive earlier. A run whose
reference is not computed gets NaN and says so in :data:`REFERENCE_COLUMN`.
"""

from __future__ import annotations

from typing import Iterable

import numpy as np
import pandas as pd

__all__ = ["MODEL_RATIO", "REFERENCE_COLUMN", "MODEL_COLUMN", "REFERENCES", "SOURCE_COLUMNS", "path_models", "with_model_ratio"]

MODEL_RATIO = "model_ratio"
"""Column: the ratio to the reference of the planner's own path model (1 = optimal in that model)."""

REFERENCE_COLUMN = "model_reference"
"""Column: which reference :data:`MODEL_RATIO` divides by."""

MODEL_COLUMN = "path_model"
"""Column: the planner's declared path model."""

REFERENCES: dict[str, tuple[str, str]] = {
    "grid": ("length_ratio", "graph optimum"),
    "anyangle": ("length_ratio_anyangle", "any-angle optimum"),
    "timed": ("arrival_ratio", "earliest arrival (SIPP)"),
}
"""Path model -> (metric column, name of its reference) on static scenarios; ``timed`` is used on dynamic ones."""

SOURCE_COLUMNS: tuple[str, ...] = (*dict.fromkeys(c for c, _ in REFERENCES.values()), "length_ratio_anyangle_bound")
"""The metric columns :func:`with_model_ratio` reads (a reader of a few columns asks for these)."""

_DYNAMIC_NAMES = {
    "grid": "earliest arrival (SIPP)",
    "timed": "earliest arrival (SIPP)",
    "anyangle": "earliest arrival (SIPP, a grid-model yardstick)",
}


def path_models(planners: Iterable[str]) -> dict[str, str]:
    """The declared path model of each planner id (``"grid"`` for ids the registry does not know)."""
    from pathzoo.plugins.manager import get_registry

    known = get_registry().planners
    return {p: str(known[p].declared("path_model", "grid") or "grid") if p in known else "grid" for p in planners}


def with_model_ratio(runs: pd.DataFrame) -> pd.DataFrame:
    """A copy of ``runs`` with :data:`MODEL_COLUMN`, :data:`MODEL_RATIO` and :data:`REFERENCE_COLUMN` added.

    A run on a ``dynamic`` scenario (one with an ``arrival_ratio``) takes it;
    any other run takes the column of its planner's path model.
    """
    out = runs.copy()
    planners = out["planner"].astype(str)
    model = planners.map(path_models(planners.unique()))
    arrival = out["arrival_ratio"].astype(float) if "arrival_ratio" in out else pd.Series(np.nan, index=out.index)
    timed = arrival.notna()
    ratio = pd.Series(np.nan, index=out.index, dtype=float)
    name = pd.Series("", index=out.index, dtype=object)
    for m, (column, label) in REFERENCES.items():
        rows = (model == m) & ~timed
        if column in out:
            ratio[rows] = out.loc[rows, column].astype(float)
        name[rows] = label
        name[(model == m) & timed] = _DYNAMIC_NAMES[m]
    bound = out["length_ratio_anyangle_bound"].astype(float) if "length_ratio_anyangle_bound" in out else None
    if bound is not None:
        use = (model == "anyangle") & ~timed & ratio.isna() & bound.notna()
        ratio[use] = bound[use]
        name[use] = "any-angle bound (Lazy Theta*, upper)"
    ratio[timed] = arrival[timed]
    solved = pd.Series([str(getattr(st, "value", st)) == "solved" for st in out["status"]], index=out.index)
    missing = ratio.isna() & solved & out["valid"].fillna(False).astype(bool)
    name[missing] = name[missing] + " (not computed here)"
    out[MODEL_COLUMN] = model
    out[MODEL_RATIO] = ratio
    out[REFERENCE_COLUMN] = name
    return out
