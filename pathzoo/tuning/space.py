"""Search spaces: which parameters of a planner ``pathzoo tune`` searches, over which ranges.

The default space of a planner is every parameter that declares a tuning
range (:attr:`pathzoo.core.planner.Param.tune`). An experiment file's
``[planner.search]`` table replaces it; each entry is one of::

    alpha = [0.5, 3.0]                        # numeric range, inclusive
    n_ants = { low = 5, high = 80, log = true }
    dead_end = ["backtrack", "die"]           # values of a categorical or boolean parameter
    q0 = "declared"                           # the parameter's declared range (or its finite bounds)
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Mapping

from pathzoo.core.errors import InvalidExperimentError, PathzooError
from pathzoo.core.planner import Param

if TYPE_CHECKING:
    import optuna

__all__ = ["SearchRange", "default_space", "parse_space", "suggest"]


@dataclass(frozen=True)
class SearchRange:
    """The values one parameter may take during tuning.

    Attributes
    ----------
    name : str
        Parameter name.
    low, high : float or int, optional
        Inclusive numeric range (``None`` for categorical ranges).
    log : bool
        Sample on a log scale.
    choices : tuple, optional
        The values of a categorical range.
    integer : bool
        Whether the parameter is an integer.
    """

    name: str
    low: float | None = None
    high: float | None = None
    log: bool = False
    choices: tuple[Any, ...] | None = None
    integer: bool = False

    def contains(self, value: Any) -> bool:
        """Whether ``value`` lies in the range (the default configuration is enqueued only when it does)."""
        if self.choices is not None:
            return value in self.choices
        return value is not None and self.low <= value <= self.high

    def describe(self) -> str:
        """``[0.5, 3] (log)`` or ``{'a', 'b'}`` for tables."""
        if self.choices is not None:
            return "{" + ", ".join(repr(c) for c in self.choices) + "}"
        return f"[{self.low:g}, {self.high:g}]" + (" (log)" if self.log else "")


def _numeric(name: str, param: Param, low: Any, high: Any, log: Any, where: str) -> SearchRange:
    if param.choices is not None or param.kind not in (int, float):
        raise InvalidExperimentError(f"{where}.{name}: a range needs a numeric parameter; list its values instead")
    for v in (low, high):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise InvalidExperimentError(f"{where}.{name}: range ends must be finite numbers, got {v!r}")
    if not isinstance(log, bool):
        raise InvalidExperimentError(f"{where}.{name}: log must be true or false, got {log!r}")
    integer = param.kind is int
    if integer and (int(low) != low or int(high) != high):
        raise InvalidExperimentError(f"{where}.{name}: an integer parameter needs integer range ends")
    if not low < high:
        raise InvalidExperimentError(f"{where}.{name}: range [{low}, {high}] must have low < high")
    if log and low <= 0:
        raise InvalidExperimentError(f"{where}.{name}: a log range needs low > 0, got {low}")
    for v in (low, high):
        try:
            param.validate(where, name, int(v) if integer else float(v))
        except PathzooError as exc:
            raise InvalidExperimentError(f"{where}.{name}: range end outside the parameter's bounds ({exc})") from None
    cast = int if integer else float
    return SearchRange(name, cast(low), cast(high), log, None, integer)


def _declared(name: str, param: Param, where: str) -> SearchRange:
    if param.tune is not None:
        return _numeric(name, param, param.tune[0], param.tune[1], param.tune_log, where)
    if param.choices is not None:
        return SearchRange(name, choices=tuple(param.choices))
    if param.kind is bool:
        return SearchRange(name, choices=(False, True))
    if param.kind in (int, float) and param.low is not None and param.high is not None:
        eps = 0.0 if param.kind is int else 1e-9 * (param.high - param.low)
        return _numeric(name, param, param.low + (eps if param.low_open else 0.0),
                        param.high - (eps if param.high_open else 0.0), False, where)
    raise InvalidExperimentError(
        f"{where}.{name}: the parameter declares no tuning range and has no finite bounds; give [low, high]"
    )


def default_space(planner_id: str, declared: Mapping[str, Param]) -> dict[str, SearchRange]:
    """The parameters among a planner's ``declared`` ones that declare a tuning range, with those ranges.

    ``declared`` is the planner's :attr:`~pathzoo.core.planner.Planner.params`, or, without importing
    the planner, :attr:`pathzoo.harness.planner_info.PlannerInfo.declared`.
    """
    return {name: _declared(name, p, planner_id) for name, p in declared.items() if p.tune is not None}


def parse_space(table: Any, planner_id: str, declared: Mapping[str, Param], where: str) -> dict[str, SearchRange]:
    """Read a ``[planner.search]`` table (format in the module docstring) for the planner's ``declared`` parameters.

    Raises
    ------
    InvalidExperimentError
        Naming ``where`` and the entry: unknown parameter, bad range, values
        outside the parameter's bounds.
    """
    if not isinstance(table, Mapping):
        raise InvalidExperimentError(f"{where}: must be a table of parameter ranges")
    out: dict[str, SearchRange] = {}
    for name, spec in table.items():
        param = declared.get(name)
        if param is None:
            allowed = ", ".join(sorted(declared)) or "none"
            raise InvalidExperimentError(f"{where}.{name}: {planner_id} has no such parameter; allowed: {allowed}")
        if spec == "declared":
            out[name] = _declared(name, param, where)
        elif isinstance(spec, Mapping):
            extra = sorted(set(spec) - {"low", "high", "log"})
            if extra or "low" not in spec or "high" not in spec:
                raise InvalidExperimentError(f"{where}.{name}: expected {{ low = ..., high = ..., log = false }}")
            out[name] = _numeric(name, param, spec["low"], spec["high"], spec.get("log", False), where)
        elif isinstance(spec, list) and param.kind in (int, float) and param.choices is None:
            if len(spec) != 2:
                raise InvalidExperimentError(f"{where}.{name}: a numeric range is [low, high], got {spec!r}")
            out[name] = _numeric(name, param, spec[0], spec[1], False, where)
        elif isinstance(spec, list) and spec:
            for value in spec:
                try:
                    param.validate(where, name, value)
                except PathzooError as exc:
                    raise InvalidExperimentError(f"{where}.{name}: {exc}") from None
            if len(set(map(repr, spec))) != len(spec):
                raise InvalidExperimentError(f"{where}.{name}: values repeat in {spec!r}")
            out[name] = SearchRange(name, choices=tuple(spec))
        else:
            raise InvalidExperimentError(
                f"{where}.{name}: expected [low, high], {{ low, high, log }}, a list of values or \"declared\", "
                f"got {spec!r}"
            )
    return out


def suggest(trial: "optuna.trial.BaseTrial", space: Mapping[str, SearchRange]) -> dict[str, Any]:
    """Draw every parameter of ``space`` from ``trial`` (all at once, before any run starts)."""
    out: dict[str, Any] = {}
    for name, r in space.items():
        if r.choices is not None:
            out[name] = trial.suggest_categorical(name, list(r.choices))
        elif r.integer:
            out[name] = trial.suggest_int(name, int(r.low), int(r.high), log=r.log)  # type: ignore[arg-type]
        else:
            out[name] = trial.suggest_float(name, float(r.low), float(r.high), log=r.log)  # type: ignore[arg-type]
    return out
