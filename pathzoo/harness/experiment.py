"""An experiment: planners x scenarios x seeds with one budget, from Python or a TOML file.

TOML format (every key but the planners and scenarios is optional)::

    [experiment]
    name = "arena"              # default: the file's stem
    seed = 0                    # experiment seed; each run's seed derives from it
    seeds = 10                  # seed indices 0..9, or an explicit list [0, 4, 7]
    budget = { cpu_s = 2.0 }    # iterations, evaluations, cpu_s, time_s (default: none, each planner's own count)
    timeout_s = 60              # hard wall limit per run, never a budget (default time_s + 30 s, else 300 s)
    jobs = 4                    # worker processes (default: number of CPUs)
    db = "results.sqlite"       # result database, relative to this file
    scenarios = ["movingai.arena.*", "maps/my_scenario.toml"]

    [[planner]]
    id = "exact.astar"

    [[planner]]
    id = "aco.gant"
    params = { n_ants = 40 }
    label = "gant-40"           # optional name in tables and plots

    [[planner]]                 # an external planner (docs/external-planners.md)
    command = ["./my_planner", "--fast"]   # or: octave = "planners/aco_variant.m"
    label = "my-planner"        # its id is external.my-planner
    kinds = ["grid2d"]          # default ["grid2d"]
    params = { n_ants = 20 }    # sent to the program

Without a ``label`` a configuration is named ``id(param=value, ...)`` for the
parameters that differ from the defaults (docs/configurations.md).

Scenario entries are registered ids, glob patterns of registered ids
(``"movingai.arena.*"``) or file paths (anything with a ``/`` or a scenario
file suffix; relative paths are relative to the TOML file). A ``.scen`` file
gives all its problems; ``"maps/den312d.scen#12"`` gives the problem at the
0-based index 12 only, and ``"maps/den312d.scen#den312d.1?"`` those whose id
(or index) matches the glob. ``scenarios`` may also be written as a top-level
key before ``[experiment]``. A ``[cluster]`` table says where ``pathzoo run
--executor slurm`` (``pbs``, ``sge``) runs; it is not part of the experiment
(:mod:`pathzoo.harness.executors.cluster_options`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Iterable, Mapping, Sequence

from pathzoo.core.budget import Budget
from pathzoo.core.errors import InvalidExperimentError
from pathzoo.harness.experiment_checks import MAX_RUNS, check_budget, check_jobs, check_name, check_seed, check_timeout
from pathzoo.harness.experiment_checks import resolve_seeds
from pathzoo.harness.experiment_file import experiment_from_mapping, read_toml
from pathzoo.harness.planner_info import prefetch
from pathzoo.harness.scenario_entries import resolve_scenarios
from pathzoo.harness.specs import PlannerSpec, RunTask, ScenarioSpec, run_key, run_seed

if TYPE_CHECKING:
    from pathzoo.core.planner import Planner
    from pathzoo.core.scenario import Scenario

__all__ = ["Experiment", "DEFAULT_BUDGET", "TIMEOUT_MARGIN_S", "DEFAULT_TIMEOUT_NO_TIME_S"]

DEFAULT_BUDGET = Budget()
"""Budget when none is given: no limit, so every planner runs its own default count and every result repeats on
any machine and load (``docs/timing.md``). A clock here would be a budget for the anytime planners (they search
until it) and not for the others; the hard limit ``timeout_s`` is the only safety stop, and no planner sees it."""
TIMEOUT_MARGIN_S = 30.0
"""Default hard limit = ``budget.time_s`` + this margin."""
DEFAULT_TIMEOUT_NO_TIME_S = 300.0
"""Default hard limit when the budget has no time limit."""


@dataclass(frozen=True)
class Experiment:
    """Planners x scenarios x seeds, run under one budget.

    Build it with :meth:`build` (Python) or :meth:`from_toml` (file), then
    run it with :func:`pathzoo.harness.runner.run_experiment`.

    Attributes
    ----------
    name : str
        Names the experiment in the result database.
    seed : int
        Experiment seed; each run's seed is derived from it and the run key.
    planners : tuple of PlannerSpec
        Planner ids with complete validated parameters.
    scenarios : tuple of ScenarioSpec
        Resolved scenarios (globs expanded, files read).
    seeds : tuple of int
        Seed indices.
    budget : Budget
        Per-run planning budget.
    timeout_s : float
        Hard per-run wall-clock limit.
    jobs : int, optional
        Default number of workers for this experiment (from the TOML file).
    db : Path, optional
        Default result database (from the TOML file).
    source : str, optional
        The TOML file it was read from.
    """

    name: str
    seed: int
    planners: tuple[PlannerSpec, ...]
    scenarios: tuple[ScenarioSpec, ...]
    seeds: tuple[int, ...]
    budget: Budget = DEFAULT_BUDGET
    timeout_s: float = DEFAULT_TIMEOUT_NO_TIME_S
    jobs: int | None = None
    db: Path | None = None
    source: str | None = field(default=None, compare=False)

    @classmethod
    def build(
        cls,
        *,
        planners: Sequence[
            "str | Planner | tuple[str, Mapping[str, Any]] | tuple[str, Mapping[str, Any], str] | PlannerSpec"
        ],
        scenarios: Sequence["str | Path | Scenario | ScenarioSpec"],
        seeds: int | Iterable[int] = 5,
        budget: Budget | None = None,
        timeout_s: float | None = None,
        name: str = "default",
        seed: int = 0,
        jobs: int | None = None,
        db: str | Path | None = None,
        _source: str | None = None,
    ) -> "Experiment":
        """Validate and resolve an experiment given in Python.

        Parameters
        ----------
        planners : sequence
            Planner ids, ``(id, params)`` pairs, ``(id, params, label)``
            triples, :class:`PlannerSpec` objects or planner instances (kept
            as id + parameters; workers rebuild them). Labels name the
            configurations in tables and plots and must be distinct.
        scenarios : sequence
            Registered ids, glob patterns of ids, file paths or Scenario objects.
        seeds : int or iterable of int
            Count (indices ``0..n-1``) or explicit seed indices.
        budget : Budget, optional
            Default :data:`DEFAULT_BUDGET`, ``Budget()``: each planner's own count.
        timeout_s : float, optional
            Hard wall limit of a run, never a budget: a run past it is killed and stored as a timeout.
            Default ``budget.time_s + 30`` s (300 s without a time budget).
        name, seed : str, int
            Experiment name and seed.
        jobs : int, optional
            Default worker count for :func:`run_experiment`.
        db : path, optional
            Default result database for :func:`run_experiment`.

        Raises
        ------
        InvalidExperimentError
            Bad experiment-level values, duplicate planners or names, or conflicting scenario ids.
        UnknownPluginError, InvalidParameterError, InvalidScenarioError
            From resolving planners and scenarios.
        """
        check_name(name)
        check_seed(seed)
        check_jobs(jobs)
        if isinstance(planners, str):
            planners = [planners]
        prefetch([(p, {}) if isinstance(p, str) else (p.id, p.params) if isinstance(p, PlannerSpec) else (p[0], p[1])
                  for p in planners if isinstance(p, (str, PlannerSpec)) or (isinstance(p, tuple) and len(p) >= 2
                                                                             and isinstance(p[0], str)
                                                                             and isinstance(p[1], Mapping))])
        specs = [PlannerSpec.of(p) for p in planners]
        if not specs:
            raise InvalidExperimentError("no planners given")
        seen: dict[tuple[str, str], int] = {}
        for i, spec in enumerate(specs):
            key = (spec.id, spec.params_hash)
            if key in seen:
                raise InvalidExperimentError(
                    f"planner {i} ({spec.id}) repeats planner {seen[key]} with the same parameters"
                )
            seen[key] = i
        names: dict[str, int] = {}
        for i, spec in enumerate(specs):
            if spec.name in names:
                raise InvalidExperimentError(
                    f"planner {i} ({spec.id}) has the same name '{spec.name}' as planner {names[spec.name]}; "
                    "give them distinct labels"
                )
            names[spec.name] = i
        budget = DEFAULT_BUDGET if budget is None else budget
        if not isinstance(budget, Budget):
            raise InvalidExperimentError(f"budget must be a pathzoo.Budget, got {budget!r}")
        check_budget(budget)
        if timeout_s is None:
            timeout_s = DEFAULT_TIMEOUT_NO_TIME_S if budget.time_s is None else budget.time_s + TIMEOUT_MARGIN_S
        timeout_s = check_timeout(timeout_s)
        experiment = cls(
            name=name,
            seed=seed,
            planners=tuple(specs),
            scenarios=resolve_scenarios(scenarios, None),
            seeds=resolve_seeds(seeds),
            budget=budget,
            timeout_s=timeout_s,
            jobs=jobs,
            db=None if db is None else Path(db),
            source=_source,
        )
        if not experiment.pairs():
            supported = sorted({k for p in experiment.planners for k in p.kinds})
            given = sorted({s.kind for s in experiment.scenarios})
            raise InvalidExperimentError(
                f"nothing to run: no planner supports any of the scenarios (the planners support "
                f"{', '.join(supported) or 'no kind'}; the scenarios are {', '.join(given)})"
            )
        return experiment

    @classmethod
    def from_toml(cls, path: str | Path) -> "Experiment":
        """Read an experiment file (format in the module docstring).

        Raises
        ------
        InvalidExperimentError
            Naming the file and the field for every problem, including unknown
            planners, bad parameters and missing scenarios.
        """
        return cls.from_mapping(read_toml(path), path)

    @classmethod
    def from_mapping(cls, data: Mapping[str, Any], path: str | Path) -> "Experiment":
        """Build an experiment from the parsed contents of the experiment file ``path``.

        :meth:`from_toml` without the reading, for readers of extended files
        (``pathzoo tune`` takes its own keys out and passes the rest here).
        Errors name ``path``; relative paths in ``data`` are relative to it
        (:func:`pathzoo.harness.experiment_file.experiment_from_mapping`).
        """
        return experiment_from_mapping(data, path, cls.build)

    # ------------------------------------------------------------------ runs
    def pairs(self) -> list[tuple[PlannerSpec, ScenarioSpec]]:
        """Supported (planner, scenario) pairs, scenario-major so workers reuse loaded scenarios."""
        return [(p, s) for s in self.scenarios for p in self.planners if s.kind in p.kinds]

    def skipped(self) -> list[tuple[str, str, str]]:
        """``(planner id, scenario id, scenario kind)`` of every unsupported pair (not run)."""
        return [
            (p.id, s.id, s.kind) for s in self.scenarios for p in self.planners if s.kind not in p.kinds
        ]

    def tasks(self, plugin_modules: tuple[tuple[str, str], ...] = ()) -> list[RunTask]:
        """Every run of the experiment, in a deterministic order.

        Raises
        ------
        InvalidExperimentError
            More than :data:`MAX_RUNS` runs (checked before any is built).
        """
        pairs = self.pairs()
        if len(pairs) * len(self.seeds) > MAX_RUNS:
            raise InvalidExperimentError(
                f"experiment '{self.name}' has {len(pairs)} planner x scenario pairs x {len(self.seeds)} seeds = "
                f"{len(pairs) * len(self.seeds)} runs, more than the limit of {MAX_RUNS}; split it"
            )
        out = []
        for planner, scenario in pairs:
            version, phash = planner.version, planner.params_hash
            by_value = planner.by_value
            for index in self.seeds:
                key = run_key(planner.id, phash, scenario.id, index)
                out.append(
                    RunTask(
                        run_key=key,
                        experiment=self.name,
                        planner=planner,
                        planner_version=version,
                        params_hash=phash,
                        scenario=scenario,
                        seed_index=index,
                        seed=run_seed(self.seed, key),
                        budget=self.budget,
                        timeout_s=self.timeout_s,
                        plugin_modules=plugin_modules,
                        planner_class=by_value,
                    )
                )
        return out

    def config(self) -> dict[str, Any]:
        """The experiment as JSON-friendly data (stored with the results)."""
        return {
            "name": self.name,
            "seed": self.seed,
            "seeds": list(self.seeds),
            "budget": self.budget.to_dict(),
            "timeout_s": self.timeout_s,
            "planners": [
                {"id": p.id, "version": p.version, "params": dict(p.params), **({"label": p.label} if p.label else {})}
                for p in self.planners
            ],
            "scenarios": [s.describe() for s in self.scenarios],
            "source": self.source,
        }
