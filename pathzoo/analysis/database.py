"""Reading one stored experiment for analysis: its runs, history and settings."""

from __future__ import annotations

from dataclasses import dataclass, fields
from pathlib import Path
from typing import Any, Mapping

import pandas as pd

from pathzoo.core.errors import InvalidParameterError

__all__ = ["ExperimentInfo", "StoredExperiment", "experiment_info", "load_experiment"]


@dataclass(frozen=True)
class ExperimentInfo:
    """One stored experiment's settings (not its runs).

    Attributes
    ----------
    db : Path
        The results database.
    name : str
        Experiment name.
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
    seed: int
    budget: Mapping[str, Any]
    timeout_s: float
    created: str
    config: Mapping[str, Any]

    @property
    def budget_text(self) -> str:
        """The budget as ``"iterations=30, time_s=2"`` (``"default"`` when nothing is set)."""
        return ", ".join(f"{k}={v}" for k, v in self.budget.items() if v is not None) or "default"


@dataclass(frozen=True)
class StoredExperiment(ExperimentInfo):
    """One experiment as stored by the harness: its settings, runs and history.

    Attributes
    ----------
    runs : DataFrame
        ``read_runs`` of this experiment.
    history : DataFrame
        ``read_history`` of this experiment.
    """

    runs: pd.DataFrame
    history: pd.DataFrame


def experiment_info(db: str | Path, experiment: str | None = None) -> ExperimentInfo:
    """The settings of one experiment of a results database (its runs are not read).

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
    from pathzoo.harness.store import read_experiments
    from pathzoo.harness.store_file import ResultsDatabaseError

    exps = read_experiments(db)
    names = [str(n) for n in exps["name"]]
    if experiment is None:
        if len(names) != 1:
            raise InvalidParameterError(
                f"{db} holds {len(names)} experiments ({', '.join(sorted(names)) or 'none'}); choose one "
                "(experiment= in Python, --experiment on the command line)"
            )
        experiment = names[0]
    if experiment not in names:
        stored = ", ".join(sorted(names)) or "none"
        raise ResultsDatabaseError(f"{db}: no experiment named '{experiment}' (stored: {stored})")
    row = exps[exps["name"] == experiment].iloc[0]
    return ExperimentInfo(db=Path(db), name=experiment, seed=int(row["seed"]), budget=dict(row["budget"]),
                          timeout_s=float(row["timeout_s"]), created=str(row["created"]), config=dict(row["config"]))


def load_experiment(db: str | Path, experiment: str | None = None) -> StoredExperiment:
    """Read one experiment of a results database: :func:`experiment_info` (same parameters and errors), runs, history.

    Every run is read into one frame; :func:`pathzoo.analysis.report_data.gather_from_db`
    and :func:`pathzoo.analysis.leaderboard.leaderboard_from_db` read a large database in bounded memory.
    """
    from pathzoo.harness.store import read_history, read_runs

    info = experiment_info(db, experiment)
    settings = {f.name: getattr(info, f.name) for f in fields(info)}
    return StoredExperiment(**settings, runs=read_runs(db, info.name), history=read_history(db, info.name))
