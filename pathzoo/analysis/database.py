"""Reading one stored experiment for analysis: its runs, history and settings."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping

import pandas as pd

from pathzoo.core.errors import InvalidParameterError

__all__ = ["StoredExperiment", "load_experiment"]


@dataclass(frozen=True)
class StoredExperiment:
    """One experiment as stored by the harness.

    Attributes
    ----------
    db : Path
        The results database.
    name : str
        Experiment name.
    runs : DataFrame
        ``read_runs`` of this experiment.
    history : DataFrame
        ``read_history`` of this experiment.
    seed : int
        Experiment seed.
    budget : mapping
        Per-run budget (``iterations``, ``evaluations``, ``time_s``, and ``cpu_s`` when set; None when unset).
    timeout_s : float
        Hard per-run limit.
    created : str
        When the experiment was first stored.
    config : mapping
        The whole stored configuration (planners, scenarios, seeds).
    """

    db: Path
    name: str
    runs: pd.DataFrame
    history: pd.DataFrame
    seed: int
    budget: Mapping[str, Any]
    timeout_s: float
    created: str
    config: Mapping[str, Any]

    @property
    def budget_text(self) -> str:
        """The budget as ``"iterations=30, time_s=2"`` (``"default"`` when nothing is set)."""
        return ", ".join(f"{k}={v}" for k, v in self.budget.items() if v is not None) or "default"


def load_experiment(db: str | Path, experiment: str | None = None) -> StoredExperiment:
    """Read one experiment of a results database.

    Parameters
    ----------
    db : path
        Results database written by the harness.
    experiment : str, optional
        Experiment name; may be omitted when ``db`` holds exactly one.

    Raises
    ------
    InvalidParameterError
        ``db`` holds several experiments and none was chosen, or none at all.
    pathzoo.harness.store_file.ResultsDatabaseError
        ``db`` is missing or not a results database, or has no such experiment.
    """
    from pathzoo.harness.store import read_experiments, read_history, read_runs

    exps = read_experiments(db)
    names = [str(n) for n in exps["name"]]
    if experiment is None:
        if len(names) != 1:
            raise InvalidParameterError(
                f"{db} holds {len(names)} experiments ({', '.join(sorted(names)) or 'none'}); choose one "
                "(experiment= in Python, --experiment on the command line)"
            )
        experiment = names[0]
    runs = read_runs(db, experiment)  # raises for an unknown experiment
    row = exps[exps["name"] == experiment].iloc[0]
    return StoredExperiment(
        db=Path(db), name=experiment, runs=runs, history=read_history(db, experiment), seed=int(row["seed"]),
        budget=dict(row["budget"]), timeout_s=float(row["timeout_s"]), created=str(row["created"]),
        config=dict(row["config"]),
    )
