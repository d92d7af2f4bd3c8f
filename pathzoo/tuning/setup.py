"""A tuning setup: an experiment file with training and test scenarios and per-planner search spaces.

An experiment file for ``pathzoo tune`` is an ordinary experiment file
(:mod:`pathzoo.harness.experiment`) whose ``scenarios`` are replaced by two
disjoint lists, plus optional search tables and settings::

    train = ["movingai.room.*"]     # scenarios the planners are tuned on
    test = ["movingai.maze.*"]      # scenarios default and tuned configurations are compared on

    [experiment]
    seeds = 5
    budget = { iterations = 50 }

    [tuning]
    trials = 30                     # per planner (default 20; --trials overrides)

    [[planner]]
    id = "aco.mmas"
    [planner.search]                # optional; default: the parameters that declare a tuning range
    alpha = [0.5, 3.0]

Everything but ``train``, ``test``, ``[tuning]`` and ``[planner.search]`` is
read by :meth:`pathzoo.harness.experiment.Experiment.from_mapping`.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Mapping

from pathzoo.core.errors import InvalidExperimentError
from pathzoo.harness.experiment import Experiment
from pathzoo.harness.experiment_file import read_toml
from pathzoo.harness.specs import PlannerSpec, ScenarioSpec
from pathzoo.tuning.space import SearchRange, default_space, parse_space

__all__ = ["TuningSetup", "DEFAULT_TRIALS", "load_tuning"]

DEFAULT_TRIALS = 20
"""Trials per planner when neither the file nor the command line sets them."""

_TUNING_KEYS = ("trials",)


@dataclass(frozen=True)
class TuningSetup:
    """What ``pathzoo tune`` reads from an experiment file.

    Attributes
    ----------
    experiment : Experiment
        The experiment as written, with ``train + test`` as its scenarios
        (its planners are the default configurations).
    train, test : tuple of ScenarioSpec
        Disjoint training and test scenarios.
    spaces : tuple of dict
        One search space per planner, in the experiment's planner order.
    trials : int
        Trials per planner.
    """

    experiment: Experiment
    train: tuple[ScenarioSpec, ...]
    test: tuple[ScenarioSpec, ...]
    spaces: tuple[Mapping[str, SearchRange], ...]
    trials: int = DEFAULT_TRIALS

    @property
    def planners(self) -> tuple[PlannerSpec, ...]:
        """The default configurations."""
        return self.experiment.planners

    def stage(self, stage: str, planners: tuple[PlannerSpec, ...]) -> Experiment:
        """The experiment of one stage: ``"tune"`` runs ``planners`` on the training scenarios, ``"test"`` on the test ones."""
        scenarios = self.train if stage == "tune" else self.test
        return dataclasses.replace(
            self.experiment, name=f"{self.experiment.name}.{stage}", planners=planners, scenarios=scenarios
        )


def _scenario_list(data: Mapping[str, Any], key: str, src: str) -> list[str]:
    value = data.get(key)
    if value is None:
        raise InvalidExperimentError(f"{src}: field '{key}': missing; list the {key}ing scenarios")
    if not isinstance(value, list) or not value or not all(isinstance(s, str) for s in value):
        raise InvalidExperimentError(f"{src}: field '{key}': must be a non-empty list of strings")
    return value


def _stage_experiment(data: Mapping[str, Any], key: str, scenarios: list[str], path: Path) -> Experiment:
    """The experiment with ``scenarios`` as its scenario list; errors about them name ``key``, not 'scenarios'."""
    try:
        return Experiment.from_mapping({**data, "scenarios": scenarios}, path)
    except InvalidExperimentError as exc:
        raise InvalidExperimentError(str(exc).replace("field 'scenarios", f"field '{key}", 1)) from None


def load_tuning(path: str | Path, *, trials: int | None = None) -> TuningSetup:
    """Read a tuning experiment file (format in the module docstring).

    Parameters
    ----------
    path : path
        The TOML file.
    trials : int, optional
        Override the file's ``[tuning] trials``.

    Raises
    ------
    InvalidExperimentError
        One line naming the file and field: missing or overlapping
        ``train``/``test``, a ``scenarios`` key (use train and test), bad
        search ranges, and everything the experiment parser rejects.
    """
    path = Path(path)
    src = str(path)
    data = dict(read_toml(path))
    if "scenarios" in data or "scenarios" in data.get("experiment", {}):
        raise InvalidExperimentError(f"{src}: field 'scenarios': a tuning file lists 'train' and 'test' instead")
    train, test = _scenario_list(data, "train", src), _scenario_list(data, "test", src)
    settings = data.pop("tuning", {})
    if not isinstance(settings, dict) or set(settings) - set(_TUNING_KEYS):
        raise InvalidExperimentError(f"{src}: field 'tuning': must be a table with the key(s) {', '.join(_TUNING_KEYS)}")
    n_trials = settings.get("trials", DEFAULT_TRIALS) if trials is None else trials
    if isinstance(n_trials, bool) or not isinstance(n_trials, int) or n_trials < 1:
        raise InvalidExperimentError(f"{src}: field 'tuning.trials': must be a positive integer, got {n_trials!r}")
    tables = data.get("planner")
    searches: list[Any] = []
    if isinstance(tables, list):
        tables = [dict(t) if isinstance(t, dict) else t for t in tables]
        searches = [t.pop("search", None) if isinstance(t, dict) else None for t in tables]
        data["planner"] = tables
    del data["train"], data["test"]
    train_exp = _stage_experiment(data, "train", train, path)
    train_specs = train_exp.scenarios
    test_specs = _stage_experiment(data, "test", test, path).scenarios
    overlap = sorted({s.id for s in train_specs} & {s.id for s in test_specs})
    if overlap:
        raise InvalidExperimentError(
            f"{src}: fields 'train' and 'test' overlap in {len(overlap)} scenario(s): {', '.join(overlap[:5])}"
            + (" ..." if len(overlap) > 5 else "")
        )
    experiment = dataclasses.replace(train_exp, scenarios=train_specs + test_specs)
    for i, spec in enumerate(experiment.planners):
        for stage, specs in (("train", train_specs), ("test", test_specs)):
            if not any(s.kind in spec.kinds for s in specs):
                raise InvalidExperimentError(
                    f"{src}: field 'planner[{i}]': {spec.id} supports none of the {stage} scenarios' kinds"
                )
    spaces = []
    for i, (spec, search) in enumerate(zip(experiment.planners, searches or [None] * len(experiment.planners))):
        declared = spec.info.declared  # described in the sandbox: tuning imports no planner here
        where = f"{src}: field planner[{i}].search"
        spaces.append(default_space(spec.id, declared) if search is None
                      else parse_space(search, spec.id, declared, where))
    return TuningSetup(experiment, train_specs, test_specs, tuple(spaces), n_trials)
