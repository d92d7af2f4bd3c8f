"""The Planner interface and its validated hyperparameters."""

from __future__ import annotations

import abc
import hashlib
import json
import math
from dataclasses import asdict, dataclass, fields
from typing import TYPE_CHECKING, Any, Callable, ClassVar, Mapping, Sequence

import numpy as np

from pathzoo.core.budget import Budget
from pathzoo.core.errors import InvalidParameterError, UnsupportedScenarioError
from pathzoo.core.results import PlanResult

if TYPE_CHECKING:
    from pathzoo.core.scenario import Scenario

__all__ = ["Param", "Planner", "ProgressCallback", "params_hash", "config_name"]

ProgressCallback = Callable[[int, int, float], None]
"""``progress(iteration, evaluations, best_cost)``; the harness adds the time."""

_MISSING = object()


@dataclass(frozen=True)
class Param:
    """Declaration of one planner hyperparameter.

    Parameters
    ----------
    default : object
        Default value (the paper's value for the papers' planners).
    doc : str
        One-line meaning, with the paper's symbol and equation where relevant.
    low, high : float, optional
        Inclusive bounds for numeric parameters.
    low_open, high_open : bool
        Make the corresponding bound exclusive.
    choices : sequence, optional
        Allowed values for categorical parameters.
    nullable : bool
        Whether ``None`` is allowed.
    tune : (low, high), optional
        The range ``pathzoo tune`` searches by default (inclusive, inside the
        bounds). Declared only for the parameters that matter; without it a
        numeric parameter is searched only when both bounds are finite, and a
        categorical one over its ``choices``.
    tune_log : bool
        Search ``tune`` on a log scale (for ranges spanning decades).
    """

    default: Any
    doc: str = ""
    low: float | None = None
    high: float | None = None
    low_open: bool = False
    high_open: bool = False
    choices: Sequence[Any] | None = None
    nullable: bool = False
    tune: tuple[float, float] | None = None
    tune_log: bool = False

    @property
    def kind(self) -> type:
        """Python type of the default (``bool``, ``int``, ``float`` or ``str``)."""
        return type(self.default)

    def describe_range(self) -> str:
        """Human-readable allowed range, used in error messages."""
        if self.choices is not None:
            return "one of " + ", ".join(repr(c) for c in self.choices)
        lo = "-inf" if self.low is None else repr(self.low)
        hi = "inf" if self.high is None else repr(self.high)
        left = "(" if self.low_open or self.low is None else "["
        right = ")" if self.high_open or self.high is None else "]"
        return f"{self.kind.__name__} in {left}{lo}, {hi}{right}"

    def to_json(self) -> dict[str, Any]:
        """The declaration as JSON values (for a harness that knows the planner only by description)."""
        out = asdict(self)
        for key in ("choices", "tune"):
            if out[key] is not None:
                out[key] = list(out[key])
        return out

    @classmethod
    def from_json(cls, data: Any) -> "Param":
        """The declaration :meth:`to_json` wrote.

        Raises
        ------
        ValueError
            ``data`` is not such a declaration (unknown or missing fields, values of the wrong type).
        """
        plain = (bool, int, float, str, type(None))
        if not isinstance(data, Mapping) or set(data) != {f.name for f in fields(cls)}:
            raise ValueError("a parameter declaration with other fields")
        number = (int, float, type(None))
        choices, tune = data["choices"], data["tune"]
        if not (isinstance(data["default"], plain) and isinstance(data["doc"], str)
                and all(isinstance(data[k], number) and not isinstance(data[k], bool) for k in ("low", "high"))
                and all(isinstance(data[k], bool) for k in ("low_open", "high_open", "nullable", "tune_log"))
                and (choices is None or (isinstance(choices, list) and all(isinstance(c, plain) for c in choices)))
                and (tune is None or (isinstance(tune, list) and len(tune) == 2
                                      and all(isinstance(t, (int, float)) and not isinstance(t, bool) for t in tune)))):
            raise ValueError("a parameter declaration with a value of the wrong type")
        return cls(**{**data, "choices": None if choices is None else tuple(choices),
                      "tune": None if tune is None else (tune[0], tune[1])})

    def validate(self, owner: str, name: str, value: Any) -> Any:
        """Return ``value`` coerced to the parameter's type, or raise.

        Raises
        ------
        InvalidParameterError
            Naming the planner, the parameter, the allowed range and the value.
        """

        def fail() -> InvalidParameterError:
            shown = repr(value)
            shown = shown if len(shown) <= 60 else shown[:57] + "..."
            return InvalidParameterError(f"{owner}: parameter '{name}' must be {self.describe_range()}, got {shown}")

        if value is None:
            if self.nullable:
                return None
            raise fail()
        kind = self.kind
        if self.choices is not None:
            if value not in self.choices:
                raise fail()
            return value
        if kind is bool:
            if not isinstance(value, (bool, np.bool_)):
                raise fail()
            return bool(value)
        if kind is int:
            if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, np.integer)):
                raise fail()
            value = int(value)
            if not -(2**63) <= value < 2**63:  # planners compute with 64-bit integers (numpy, numba)
                raise InvalidParameterError(f"{owner}: parameter '{name}' must fit in 64 bits, got {value:.3e}")
        elif kind is float:
            if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
                raise fail()
            value = float(value)
            if not math.isfinite(value):
                raise fail()
        elif not isinstance(value, kind):
            raise fail()
        if self.low is not None and (value < self.low or (self.low_open and value == self.low)):
            raise fail()
        if self.high is not None and (value > self.high or (self.high_open and value == self.high)):
            raise fail()
        return value


def params_hash(planner_id: str, version: str, params: Mapping[str, Any]) -> str:
    """Stable 12-hex-digit hash of a planner id, version and parameters."""
    blob = json.dumps({"id": planner_id, "version": version, "params": dict(params)}, sort_keys=True, default=str)
    return hashlib.sha256(blob.encode()).hexdigest()[:12]


def _format_value(value: Any) -> str:
    if isinstance(value, float):
        return f"{value:.6g}"
    return repr(value) if isinstance(value, str) else str(value)


def config_name(planner_id: str, params: Mapping[str, Any], declared: Mapping[str, Param]) -> str:
    """A readable name of a configuration: ``id(param=value, ...)`` for the parameters off their defaults.

    Parameters
    ----------
    planner_id : str
        The planner id.
    params : mapping
        The configuration's (validated) parameters.
    declared : mapping of str to Param
        The planner's declared parameters, whose defaults are left out.

    Examples
    --------
    >>> config_name("mine.wastar", {"weight": 5.0, "tie": "h"}, {"weight": Param(1.0), "tie": Param("h")})
    'mine.wastar(weight=5)'
    >>> config_name("mine.wastar", {"weight": 1.0}, {"weight": Param(1.0)})
    'mine.wastar'
    """
    changed = [
        f"{name}={_format_value(value)}"
        for name, value in params.items()
        if name not in declared or value != declared[name].validate(planner_id, name, declared[name].default)
    ]
    return f"{planner_id}({', '.join(changed)})" if changed else planner_id


class Planner(abc.ABC):
    """Base class of every planner.

    Subclasses declare class attributes and implement :meth:`plan`:

    - ``id``: ``"family.name"``, e.g. ``"exact.astar"``;
    - ``version``: bumped whenever results for the same seed would change;
    - ``summary``: one line for ``pathzoo list``;
    - ``kinds``: the scenario kinds supported (``grid2d``, ``terrain``,
      ``air3d``, ``dynamic``);
    - ``params``: a mapping of hyperparameter name to :class:`Param`.

    Hyperparameters are keyword-only and validated on construction. A planner
    keeps no state between ``plan()`` calls, so it can be pickled and sent to
    another process. All randomness comes from the ``rng`` argument.

    Examples
    --------
    >>> import pathzoo
    >>> planner = pathzoo.make_planner("exact.astar")
    >>> scenario = pathzoo.load_scenario("demo.rooms")  # doctest: +SKIP
    >>> result = planner.plan(scenario, budget=pathzoo.Budget(), rng=np.random.default_rng(0))  # doctest: +SKIP
    """

    id: ClassVar[str] = ""
    version: ClassVar[str] = "1"
    summary: ClassVar[str] = ""
    kinds: ClassVar[frozenset[str]] = frozenset()
    params: ClassVar[Mapping[str, Param]] = {}

    def __init__(self, **params: Any) -> None:
        unknown = sorted(set(params) - set(self.params))
        if unknown:
            allowed = ", ".join(sorted(self.params)) or "none"
            raise InvalidParameterError(f"{self.id}: unknown parameter(s) {unknown}; allowed: {allowed}")
        values: dict[str, Any] = {}
        for name, spec in self.params.items():
            values[name] = spec.validate(self.id, name, params.get(name, spec.default))
        self._values = values
        self._check_params(values)

    def _check_params(self, values: Mapping[str, Any]) -> None:
        """Hook for cross-parameter checks; raise :class:`InvalidParameterError`."""

    def __getattr__(self, name: str) -> Any:
        values = self.__dict__.get("_values")
        if values is not None and name in values:
            return values[name]
        raise AttributeError(f"{type(self).__name__!s} has no attribute {name!r}")

    def __repr__(self) -> str:
        args = ", ".join(f"{k}={v!r}" for k, v in self._values.items())
        return f"{type(self).__name__}({args})"

    def get_params(self) -> dict[str, Any]:
        """Return the validated hyperparameters as a dict."""
        return dict(self._values)

    @property
    def params_hash(self) -> str:
        """Hash of id, version and parameters; part of every run key."""
        return params_hash(self.id, self.version, self._values)

    @property
    def config_name(self) -> str:
        """``id(param=value, ...)`` listing the parameters that differ from the defaults (:func:`config_name`)."""
        return config_name(self.id, self._values, self.params)

    def check_supports(self, scenario: "Scenario") -> None:
        """Raise :class:`UnsupportedScenarioError` if ``scenario.kind`` is not supported."""
        if scenario.kind not in self.kinds:
            raise UnsupportedScenarioError(
                f"{self.id} does not support scenario kind '{scenario.kind}' "
                f"(supports: {', '.join(sorted(self.kinds))})"
            )

    @abc.abstractmethod
    def plan(
        self,
        scenario: "Scenario",
        *,
        budget: Budget,
        rng: np.random.Generator,
        progress: ProgressCallback | None = None,
    ) -> PlanResult:
        """Plan a path from ``scenario.start`` to ``scenario.goal``.

        Parameters
        ----------
        scenario : Scenario
            The problem. Must not be modified.
        budget : Budget
            Limits to respect.
        rng : numpy.random.Generator
            The only source of randomness.
        progress : callable, optional
            ``progress(iteration, evaluations, best_cost)``, called on every
            iteration or improvement.

        Returns
        -------
        PlanResult
            Finding no path is a status, never an exception.
        """
