"""Tune every planner with the same number of Optuna trials on the training scenarios, then test default and tuned.

The flow of ``pathzoo tune``::

    for round k = 0, 1, ... until every planner has `trials` completed trials:
        for each planner: take its unfinished trial (resume) or ask its study for one,
                          with a TPE sampler seeded by (experiment seed, planner, k)
        run all those configurations over train scenarios x seeds in one harness call
        tell each study its configuration's score (pathzoo.tuning.objective)
    run every planner's default and best configuration on the test scenarios

Trials are stored in an Optuna SQLite storage beside the results database
(:func:`pathzoo.analysis.tuning_report.optuna_storage_path`); runs are stored in the results database by run
key under the experiments ``<name>.tune`` and ``<name>.test``. Killed at any
point and started again, a tuning run re-uses finished trials and runs and
re-asks an interrupted trial with the same seed, so it ends with the same
tuned parameters (the TPE sampler sees the same completed trials and the same
seed; no state lives in memory only).
"""

from __future__ import annotations

import hashlib
import json
import logging
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Mapping

import pandas as pd

from pathzoo.analysis.tuning_report import optuna_storage_path, study_name
from pathzoo.core.errors import PathzooError
from pathzoo.harness.runner import DEFAULT_DB, run_experiment
from pathzoo.harness.specs import PlannerSpec
from pathzoo.harness.store import read_runs
from pathzoo.harness.store_file import ResultsDatabaseError
from pathzoo.tuning.objective import WORST_RATIO, trial_score
from pathzoo.tuning.setup import TuningSetup
from pathzoo.tuning.space import SearchRange, suggest

if TYPE_CHECKING:
    import optuna

    from pathzoo.harness.executors import RunExecutor

__all__ = ["PlannerTuning", "TuningResult", "tune"]

log = logging.getLogger("pathzoo.tuning")


@dataclass(frozen=True)
class PlannerTuning:
    """The outcome of tuning one planner.

    Attributes
    ----------
    name : str
        The planner's configuration name in the experiment file.
    default, tuned : PlannerSpec
        The configuration as written, and its best trial's configuration.
    space : mapping of str to SearchRange
        What was searched.
    trials : int
        Completed trials (equal for every planner).
    default_score, best_score : float
        Training score of the default configuration (NaN when it lies outside
        the search space and was not a trial) and of the best trial.
    study : str
        The Optuna study name.
    """

    name: str
    default: PlannerSpec
    tuned: PlannerSpec
    space: Mapping[str, SearchRange]
    trials: int
    default_score: float
    best_score: float
    study: str

    @property
    def kept_default(self) -> bool:
        """Whether tuning kept the default configuration."""
        return self.tuned.params_hash == self.default.params_hash

    @property
    def test_labels(self) -> tuple[str, str]:
        """Names of the default and tuned configurations on the test scenarios (the same when tuning kept the default)."""
        if self.kept_default:
            same = f"{self.name} default = tuned"
            return same, same
        return f"{self.name} default", f"{self.name} tuned"

    @property
    def tuned_text(self) -> str:
        """The searched parameters of the tuned configuration, ``alpha=1.23, beta=4``."""
        return ", ".join(f"{k}={_fmt(self.tuned.params[k])}" for k in self.space) or "(nothing to tune)"


@dataclass(frozen=True)
class TuningResult:
    """What :func:`tune` returns.

    Attributes
    ----------
    setup : TuningSetup
        The tuning setup.
    db : Path
        The results database.
    storage : Path
        The Optuna storage file.
    planners : tuple of PlannerTuning
        One per planner, in the experiment's order.
    test_runs : DataFrame
        The test runs of the default and tuned configurations, labelled
        ``<name> default`` and ``<name> tuned`` (``<name> default = tuned``
        when tuning kept the default).
    """

    setup: TuningSetup
    db: Path
    storage: Path
    planners: tuple[PlannerTuning, ...]
    test_runs: pd.DataFrame

    def table(self) -> pd.DataFrame:
        """One row per planner: trials, default and best training score, tuned parameters."""
        return pd.DataFrame({
            "planner": [p.name for p in self.planners],
            "trials": [p.trials for p in self.planners],
            "default score": [p.default_score for p in self.planners],
            "tuned score": [p.best_score for p in self.planners],
            "tuned parameters": [p.tuned_text for p in self.planners],
        })


def _fmt(value: Any) -> str:
    return f"{value:.4g}" if isinstance(value, float) else str(value)


def _sampler_seed(seed: int, planner: str, completed: int) -> int:
    digest = hashlib.sha256(f"{seed}:{planner}:{completed}".encode()).digest()
    return int.from_bytes(digest[:4], "little")


def _space_attr(space: Mapping[str, SearchRange]) -> str:
    return json.dumps({k: r.describe() for k, r in space.items()}, sort_keys=True)


def _open_study(storage: Any, name: str, spec: PlannerSpec, space: Mapping[str, SearchRange]) -> "optuna.Study":
    import optuna

    study = optuna.create_study(study_name=name, storage=storage, direction="minimize", load_if_exists=True)
    attrs = {"planner": spec.id, "params": json.dumps(dict(spec.params), sort_keys=True, default=str),
             "space": _space_attr(space)}
    stored = study.user_attrs
    if not stored:
        for key, value in attrs.items():
            study.set_user_attr(key, value)
    elif any(stored.get(k) != v for k, v in attrs.items()):
        raise ResultsDatabaseError(
            f"study '{name}' is stored with another planner, default parameters or search space; "
            "use another experiment name or database"
        )
    if not study.trials and all(r.contains(spec.params[k]) for k, r in space.items()):
        study.enqueue_trial({k: spec.params[k] for k in space})
    return study


def _completed(study: "optuna.Study") -> list["optuna.trial.FrozenTrial"]:
    from optuna.trial import TrialState

    return study.get_trials(deepcopy=False, states=(TrialState.COMPLETE,))


def _next_trial(study: "optuna.Study", space: Mapping[str, SearchRange], seed: int, planner: str,
                n_trials: int) -> tuple[int, dict[str, Any]]:
    """The number and parameters of the planner's next trial: an interrupted one, else a newly asked one."""
    import optuna
    from optuna.trial import TrialState

    for trial in study.get_trials(deepcopy=False, states=(TrialState.RUNNING,)):
        if set(trial.params) == set(space):
            return trial.number, dict(trial.params)
        study.tell(trial.number, state=TrialState.FAIL)  # killed while drawing: draw again, same seed
        fixed = trial.system_attrs.get("fixed_params")
        if fixed:  # it was the enqueued default configuration: enqueue it again
            study.enqueue_trial(fixed)
    done = len(_completed(study))
    study.sampler = optuna.samplers.TPESampler(
        seed=_sampler_seed(seed, planner, done), n_startup_trials=max(1, min(10, n_trials // 3))
    )
    asked = study.ask()
    return asked.number, suggest(asked, space)


def _runs_of(runs: pd.DataFrame, spec: PlannerSpec, scenarios: set[str], seeds: set[int]) -> pd.DataFrame:
    mask = (runs["planner"] == spec.id) & (runs["params_hash"] == spec.params_hash)
    return runs[mask & runs["scenario"].isin(scenarios) & runs["seed_index"].isin(seeds)]


def _best(study: "optuna.Study", spec: PlannerSpec, space: Mapping[str, SearchRange]) -> tuple[dict[str, Any], float, float]:
    trials = _completed(study)
    values = {t.number: float(t.value) for t in trials if t.value is not None}  # completed trials have a value
    best = min((t for t in trials if t.number in values), key=lambda t: (values[t.number], t.number))
    default = {k: spec.params[k] for k in space}
    default_scores = [values[t.number] for t in trials if t.params == default and t.number in values]
    return dict(best.params), values[best.number], default_scores[0] if default_scores else float("nan")


def tune(
    setup: TuningSetup,
    *,
    db: str | Path | None = None,
    jobs: int | None = None,
    executor: "str | RunExecutor" = "process",
    progress: bool = False,
    stop_after_rounds: int | None = None,
) -> TuningResult:
    """Tune every planner of ``setup`` with the same number of trials, then test default and tuned configurations.

    Parameters
    ----------
    setup : TuningSetup
        From :func:`pathzoo.tuning.load_tuning`.
    db : path, optional
        Results database (default: the experiment's ``db``, else
        ``pathzoo-results.sqlite``); the Optuna storage goes beside it.
    jobs : int, optional
        Parallel runs.
    executor : str or RunExecutor
        As for :func:`pathzoo.harness.runner.run_experiment`; tuned
        parameters do not depend on it.
    progress : bool
        Show the harness's progress bars.
    stop_after_rounds : int, optional
        Stop after this many tuning rounds without testing (for resumption
        tests); the result then has no test runs.

    Returns
    -------
    TuningResult
    """
    import optuna

    optuna.logging.set_verbosity(optuna.logging.WARNING)
    exp = setup.experiment
    db_path = Path(db if db is not None else exp.db if exp.db is not None else DEFAULT_DB)
    if not db_path.parent.is_dir():
        raise ResultsDatabaseError(f"{db_path}: directory {db_path.parent} does not exist")
    storage_path = optuna_storage_path(db_path)
    storage = optuna.storages.RDBStorage(f"sqlite:///{storage_path.resolve()}")
    names = [spec.name for spec in setup.planners]
    studies = [_open_study(storage, study_name(exp.name, n), spec, space)
               for n, spec, space in zip(names, setup.planners, setup.spaces)]
    train_ids, seeds = {s.id for s in setup.train}, set(exp.seeds)
    rounds = 0
    while stop_after_rounds is None or rounds < stop_after_rounds:
        batch: list[tuple[optuna.Study, int, PlannerSpec]] = []
        for name, spec, space, study in zip(names, setup.planners, setup.spaces, studies):
            if len(_completed(study)) >= setup.trials:
                continue
            number, params = _next_trial(study, space, exp.seed, name, setup.trials)
            try:
                candidate = PlannerSpec.of((spec.id, {**spec.params, **params}, f"{name} trial {number}"))
            except PathzooError as exc:  # a cross-parameter constraint: the worst score, like a failed run
                log.info("%s trial %d: invalid configuration (%s)", name, number, exc)
                study.tell(number, WORST_RATIO)
                continue
            batch.append((study, number, candidate))
        if not batch:
            if all(len(_completed(s)) >= setup.trials for s in studies):
                break
            continue
        unique = {(c.id, c.params_hash): c for _, _, c in batch}
        run_experiment(setup.stage("tune", tuple(unique.values())), db=db_path, jobs=jobs, executor=executor,
                       progress=progress)
        runs = read_runs(db_path, f"{exp.name}.tune")
        for study, number, candidate in batch:
            study.tell(number, trial_score(_runs_of(runs, candidate, train_ids, seeds)))
        rounds += 1
    tunings = []
    for name, spec, space, study in zip(names, setup.planners, setup.spaces, studies):
        done = _completed(study)
        if len(done) < setup.trials:
            continue
        params, best, default_score = _best(study, spec, space)
        tuned = PlannerSpec.of((spec.id, {**spec.params, **params}))
        tunings.append(PlannerTuning(name, spec, tuned, space, len(done), default_score, best, study.study_name))
    if len(tunings) < len(names):
        return TuningResult(setup, db_path, storage_path, tuple(tunings), pd.DataFrame())
    return TuningResult(setup, db_path, storage_path, tuple(tunings),
                        _test(setup, tunings, db_path, jobs, executor, progress))


def _test(setup: TuningSetup, tunings: list[PlannerTuning], db: Path, jobs: int | None,
          executor: "str | RunExecutor", progress: bool) -> pd.DataFrame:
    labels: dict[tuple[str, str], str] = {}
    for t in tunings:
        labels[(t.default.id, t.default.params_hash)], labels[(t.tuned.id, t.tuned.params_hash)] = t.test_labels
    specs = {(t.default.id, t.default.params_hash): t.default for t in tunings}
    specs.update({(t.tuned.id, t.tuned.params_hash): t.tuned for t in tunings})
    planners = tuple(PlannerSpec(s.id, s.params, labels[key]) for key, s in specs.items())
    stage = setup.stage("test", planners)
    run_experiment(stage, db=db, jobs=jobs, executor=executor, progress=progress)
    runs = read_runs(db, stage.name)
    known = pd.Series([k in labels for k in zip(runs["planner"], runs["params_hash"])], index=runs.index)
    keep = known & runs["scenario"].isin({s.id for s in setup.test}) & runs["seed_index"].isin(
        set(stage.seeds))
    runs = runs[keep].copy()
    # Labels are stored with the first run of a configuration; name them as they are now.
    runs["label"] = [labels[k] for k in zip(runs["planner"], runs["params_hash"])]
    return runs.reset_index(drop=True)
