"""What crosses the process boundary: planner and scenario references, and the run task.

A worker receives a :class:`RunTask` and rebuilds everything else: the
planner from its registered id and parameters (:func:`pathzoo.make_planner`),
the scenario from its registered id or file. Scenario *objects* given in
Python have no such reference, so they travel pickled inside the task, as
the bytes the harness pickled once (they are pathzoo's own frozen objects,
so unpickling them is trusted); a process that already holds those bytes
gets the spec without them (:meth:`ScenarioSpec.by_reference`), and a
planner class defined in ``__main__`` (a script, a notebook) travels by value,
pickled with cloudpickle as Dask and loky do, since workers do not import the
parent's main module. Both are pickled by the harness process itself; nothing
pickled by a worker or read from a file is ever unpickled.
"""

from __future__ import annotations

import functools
import hashlib
import pickle
import sys
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal, Mapping

from pathzoo.core.budget import Budget
from pathzoo.core.errors import InvalidExperimentError
from pathzoo.core.planner import Planner, params_hash
from pathzoo.harness.planner_info import PlannerInfo, info_of

if TYPE_CHECKING:
    from pathzoo.core.scenario import Scenario

__all__ = ["PlannerSpec", "ScenarioSpec", "RunTask", "HeldScenarios", "run_key", "run_seed", "ScenarioSource", "planner_by_value"]

ScenarioSource = Literal["registry", "file", "object"]


def run_key(planner_id: str, params_hash_: str, scenario_id: str, seed_index: int) -> str:
    """The deterministic key of one run: ``"<planner>|<params hash>|<scenario>|<seed index>"``.

    Examples
    --------
    >>> run_key("exact.astar", "0123456789ab", "demo.rooms", 3)
    'exact.astar|0123456789ab|demo.rooms|3'
    """
    return f"{planner_id}|{params_hash_}|{scenario_id}|{seed_index}"


def run_seed(experiment_seed: int, key: str) -> int:
    """The seed of one run: 63 bits of SHA-256 of the experiment seed and the run key.

    The run's generator is ``numpy.random.default_rng(run_seed(...))``, so a
    run's randomness depends only on the experiment seed and its own key, not
    on the order or the process it runs in.
    """
    digest = hashlib.sha256(f"{int(experiment_seed)}:{key}".encode()).digest()
    return int.from_bytes(digest[:8], "little") >> 1


def planner_by_value(cls: type) -> bytes:
    """The class pickled by value when workers could not import it by name, else ``b""``.

    That is a class defined in ``__main__``, or one made at run time whose
    module does not hold it under its qualified name (the planner classes
    of external planners, :mod:`pathzoo.plugins.external`).
    """
    module = sys.modules.get(cls.__module__)
    if (cls.__module__ not in ("__main__", "__mp_main__") and getattr(module, "__spec__", None) is not None
            and _attribute_path(module, cls.__qualname__) is cls):
        return b""
    import cloudpickle

    return cloudpickle.dumps(cls)


def _attribute_path(obj: Any, qualname: str) -> Any:
    """``obj.a.b`` for ``qualname`` ``"a.b"``, or ``None``."""
    for part in qualname.split("."):
        obj = getattr(obj, part, None)
    return obj


@dataclass(frozen=True)
class PlannerSpec:
    """A registered planner id and its complete, validated hyperparameters.

    Build it with :meth:`of`, which validates the parameters and fills in the
    defaults, so equal configurations get equal specs and equal hashes.

    ``label`` names the configuration wherever it appears (leaderboard, CSV,
    report, plots); it is not part of the run key, so relabelling a
    configuration re-uses its stored runs. Without a label, :attr:`name` is
    ``id(param=value, ...)`` for the parameters that differ from the defaults.
    """

    id: str
    params: Mapping[str, Any] = field(default_factory=dict)
    label: str = ""

    @classmethod
    def of(
        cls, obj: "str | Planner | tuple[str, Mapping[str, Any]] | tuple[str, Mapping[str, Any], str] | PlannerSpec"
    ) -> "PlannerSpec":
        """Normalise a planner id, ``(id, params)`` pair, ``(id, params, label)`` triple, planner instance or spec.

        Raises
        ------
        UnknownPluginError
            The id is not registered.
        InvalidParameterError
            A parameter is unknown or out of range.
        InvalidExperimentError
            The object is none of the above, an instance of a class that is
            not the one registered under its id (workers rebuild planners by
            id), or the planner needs an optional package that is not installed.
        """
        from pathzoo.plugins.manager import get_registry

        label = ""
        if isinstance(obj, PlannerSpec):
            planner_id, params, label = obj.id, dict(obj.params), obj.label
        elif isinstance(obj, str):
            planner_id, params = obj, {}
        elif isinstance(obj, Planner):
            registered = get_registry().get("planners", obj.id).obj
            if type(obj) is not registered:
                raise InvalidExperimentError(
                    f"planner instance of {type(obj).__qualname__} is not the class registered as '{obj.id}' "
                    f"({registered.__qualname__}); workers rebuild planners by id, so register it"
                )
            planner_id, params = obj.id, obj.get_params()
        elif isinstance(obj, tuple) and len(obj) == 2 and isinstance(obj[0], str) and isinstance(obj[1], Mapping):
            planner_id, params = obj[0], dict(obj[1])
        elif isinstance(obj, tuple) and len(obj) == 3 and isinstance(obj[0], str) and isinstance(obj[1], Mapping):
            planner_id, params, label = obj[0], dict(obj[1]), obj[2]
            if not isinstance(label, str) or not label or label != label.strip():
                raise InvalidExperimentError(
                    f"a planner label must be a non-empty string without outer spaces, got {label!r}"
                )
        else:
            raise InvalidExperimentError(
                "a planner must be an id, an (id, params) pair, an (id, params, label) triple or a Planner "
                f"instance, got {obj!r}"
            )
        unavailable = get_registry().get("planners", planner_id).unavailable
        if unavailable:
            raise InvalidExperimentError(f"planner '{planner_id}' is not available here: it {unavailable}")
        return cls(planner_id, info_of(planner_id, params).params, label)

    @functools.cached_property
    def info(self) -> PlannerInfo:
        """Version, kinds and default name, not importing the planner here (:mod:`~pathzoo.harness.planner_info`).

        Looked up once per spec (the look-up keys on the parameters' JSON) and
        kept on it; a pickled spec leaves it behind (:meth:`__getstate__`), so
        a worker describes the configuration itself.
        """
        return info_of(self.id, self.params)

    def __getstate__(self) -> dict[str, Any]:
        """The fields, without the cached :attr:`info`."""
        return {key: value for key, value in self.__dict__.items() if key != "info"}

    @property
    def name(self) -> str:
        """The label, else ``id(param=value, ...)`` for the parameters off their defaults."""
        return self.label or self.info.name

    @property
    def kinds(self) -> frozenset[str]:
        """The scenario kinds the planner supports."""
        return self.info.kinds

    @property
    def planner_class(self) -> type[Planner]:
        """The registered class (imports the planner's module: the harness itself never calls it)."""
        from pathzoo.plugins.manager import get_registry

        return get_registry().get("planners", self.id).obj

    @property
    def by_value(self) -> bytes:
        """The class pickled by value when it lives in ``__main__`` (:func:`planner_by_value`), else ``b""``.

        A planner declared lazily and never imported here is not in
        ``__main__``: it is not imported to find out.
        """
        from pathzoo.plugins.entries import LazyClass
        from pathzoo.plugins.manager import get_registry

        provided = get_registry().get("planners", self.id).provided
        if isinstance(provided, LazyClass) and provided.import_pending:
            return b""
        return planner_by_value(self.planner_class)

    @property
    def version(self) -> str:
        """The planner's version."""
        return self.info.version

    @property
    def params_hash(self) -> str:
        """Hash of id, version and parameters (:func:`pathzoo.core.planner.params_hash`)."""
        return params_hash(self.id, self.version, self.params)

    def build(self) -> Planner:
        """A fresh planner instance."""
        from pathzoo.plugins.lookup import make_planner

        return make_planner(self.id, **self.params)


@dataclass(frozen=True, eq=False)
class ScenarioSpec:
    """How a worker gets a scenario.

    Attributes
    ----------
    id : str
        The scenario id (part of every run key).
    kind : str
        The scenario kind, to skip planners that do not support it.
    source : {"registry", "file", "object"}
        Load by registered id, from a file (absolute path in ``location``), or
        unpickle ``payload``.
    location : str
        The registered id or the file path; empty for objects.
    payload : bytes
        The object pickled by the harness (``source == "object"`` only);
        empty in a spec sent :meth:`by_reference`.
    digest : str
        For objects, a hash of ``payload``, so processes can cache them.
    """

    id: str
    kind: str
    source: ScenarioSource
    location: str = ""
    payload: bytes = b""
    digest: str = ""

    @classmethod
    def of_object(cls, scenario: "Scenario") -> "ScenarioSpec":
        """Reference a Scenario object (it travels as these pickled bytes)."""
        payload = pickle.dumps(scenario, protocol=5)
        digest = hashlib.blake2b(payload, digest_size=12).hexdigest()
        return cls(scenario.id, scenario.kind, "object", "", payload, digest)

    def by_reference(self) -> "ScenarioSpec":
        """The spec without its payload, for a process that holds it already.

        That process loads the object from the bytes it kept
        (:func:`pathzoo.harness.scenario_cache.keep_payload`). Specs without a
        payload are returned as they are.
        """
        return replace(self, payload=b"") if self.payload else self

    @property
    def cache_key(self) -> tuple[str, str, str, str]:
        """Identifies the scenario's content within a process."""
        return (self.source, self.location, self.id, self.digest)

    def describe(self) -> dict[str, str]:
        """JSON-friendly description (for the experiments table), with :meth:`content_digest`."""
        return {"id": self.id, "kind": self.kind, "source": self.source, "location": self.location,
                "digest": self.content_digest()}

    def content_digest(self) -> str:
        """What the scenario's content is made from, hashed without loading it (``pathzoo merge`` compares it).

        An object's is the hash of its pickled bytes; a file scenario's the
        SHA-256 of the file (a map file that it names is not included); a
        registered scenario's the hash of the distribution, version and id
        that provide it, so two machines with different scenario packs differ.
        """
        if self.source == "object":
            return self.digest
        if self.source == "file":
            text = hashlib.sha256(Path(self.location).read_bytes()).hexdigest()
        else:
            from pathzoo.plugins.manager import get_registry

            entry = get_registry().get("scenarios", self.location)
            text = hashlib.sha256(f"{entry.distribution} {entry.version} {self.location}".encode()).hexdigest()
        return text[:24]

    def load(self) -> "Scenario":
        """Load the scenario (uncached; the worker and the runner cache it)."""
        if self.source == "object":  # a copy: no planner ever gets the caller's own object
            if not self.payload:
                raise InvalidExperimentError(f"scenario object '{self.id}' was sent by reference to a process "
                                             "that never received it")
            return pickle.loads(self.payload)
        if self.source == "registry":
            from pathzoo.plugins.manager import get_registry

            return get_registry().get("scenarios", self.location).obj.load()
        for scenario in _file_scenarios(self.location):
            if scenario.id == self.id:
                return scenario
        raise InvalidExperimentError(f"{self.location}: no scenario with id '{self.id}' any more")


@functools.lru_cache(maxsize=2)
def _file_scenarios(path: str) -> tuple["Scenario", ...]:
    from pathzoo.plugins.lookup import load_scenarios

    return tuple(load_scenarios(path))


@dataclass(frozen=True, eq=False)
class RunTask:
    """Everything a worker needs for one run, and nothing more.

    Attributes
    ----------
    run_key : str
        See :func:`run_key`.
    experiment : str
        The experiment name.
    planner : PlannerSpec
        Rebuilt in the worker with :func:`pathzoo.make_planner`.
    planner_version : str
        The version the parent saw; a worker with another version refuses the run.
    params_hash : str
        Hash of planner id, version and parameters.
    scenario : ScenarioSpec
        Loaded (and cached) by the worker.
    seed_index : int
        Index of the seed within the experiment.
    seed : int
        The run's seed (:func:`run_seed`).
    budget : Budget
        The planning budget.
    timeout_s : float
        Hard wall-clock limit; the executor kills the run after it.
    plugin_modules : tuple of (name, module)
        Plugins registered in the parent that are not entry points (e.g. test
        planners); workers import and register them before building the planner.
    planner_class : bytes
        The planner class pickled by value (:func:`planner_by_value`) when it
        is defined in ``__main__``; empty otherwise.
    """

    run_key: str
    experiment: str
    planner: PlannerSpec
    planner_version: str
    params_hash: str
    scenario: ScenarioSpec
    seed_index: int
    seed: int
    budget: Budget
    timeout_s: float
    plugin_modules: tuple[tuple[str, str], ...] = ()
    planner_class: bytes = b""

    def build_planner(self) -> Planner:
        """A fresh planner: from the class sent by value, else by its registered id."""
        if self.planner_class:
            cls = pickle.loads(self.planner_class)  # pickled by the harness process (see the module docstring)
            return cls(**self.planner.params)
        return self.planner.build()


@dataclass
class HeldScenarios:
    """The scenario objects one process (a worker, the judge) holds already, as the harness tracks them.

    A process keeps the payload of every scenario object it receives
    (:func:`pathzoo.harness.scenario_cache.keep_payload`); later tasks on that
    object go to it by reference. A sender asks :meth:`outgoing` for the
    task to send and, once it is sent, tells :meth:`sent`. A process that
    is replaced starts with a new, empty ledger.
    """

    digests: set[str] = field(default_factory=set)

    def outgoing(self, task: RunTask) -> RunTask:
        """``task`` with its scenario object by reference if the process holds it, else as it is."""
        spec = task.scenario
        return replace(task, scenario=spec.by_reference()) if spec.payload and spec.digest in self.digests else task

    def sent(self, task: RunTask) -> None:
        """Count ``task``'s scenario object as held by the process from now on."""
        if task.scenario.payload:
            self.digests.add(task.scenario.digest)
