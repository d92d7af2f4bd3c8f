"""The individual conformance checks a planner must pass (see ``docs/register-a-planner.md``).

Every check is a function ``check_*(planner, **options)`` that returns nothing
and raises :class:`ConformanceError` (an ``AssertionError``) naming the
planner, the scenario and what went wrong. Checks that plan take the scenario
``kind`` to use and the planning ``budget``; they run on the tiny scenarios of
:mod:`pathzoo.core.tiny_scenarios`.

Every check that plans has a hard limit (:mod:`pathzoo.testing.bounded`): it
runs in a forked process that is killed after :data:`CHECK_LIMIT_S`, so a
planner that ignores its budget fails the check instead of hanging the suite.
The untimed warm-up before it (JIT compilation) is bounded the same way, by
:data:`WARM_UP_LIMIT_S`, and the timed call of :func:`check_budget_time` by
``TIME_BUDGET_S + TIME_TOLERANCE_S``.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import pickle
import random
import re
from typing import Any, Callable, Mapping

import numpy as np

from pathzoo.core.budget import Budget
from pathzoo.core.errors import InvalidParameterError, UnsupportedScenarioError
from pathzoo.core.planner import Param, Planner
from pathzoo.core.results import PlanResult
from pathzoo.core.scenario import SCENARIO_KINDS, Scenario
from pathzoo.core.status import Status
from pathzoo.rules import validate_path
from pathzoo.core.tiny_scenarios import check_scenario
from pathzoo.core.warmup import is_warm, warm_up
from pathzoo.testing.bounded import BoundedTimeout, run_bounded

__all__ = [
    "ConformanceError",
    "DEFAULT_BUDGET",
    "TIME_BUDGET_S",
    "TIME_TOLERANCE_S",
    "check_declaration",
    "check_rejects_unknown_parameter",
    "check_rejects_out_of_range",
    "check_solves",
    "check_same_seed_same_path",
    "check_budget_iterations",
    "check_budget_evaluations",
    "check_budget_time",
    "check_unreachable_goal",
    "check_scenario_unchanged",
    "check_picklable",
    "check_history_improves",
    "check_leaves_global_rng_alone",
    "check_unsupported_kinds",
    "check_budget_default",
    "CheckTimeout",
    "CHECK_LIMIT_S",
    "WARM_UP_LIMIT_S",
    "WARM_UP_PLAN_LIMIT_S",
]

DEFAULT_BUDGET = Budget(iterations=5, time_s=2.0)
"""Budget of the checks that plan: a few iterations, with a time cap as a safety net."""

TIME_BUDGET_S = 0.3
"""Planning time given in :func:`check_budget_time`."""

TIME_TOLERANCE_S = 1.0
"""How far past :data:`TIME_BUDGET_S` a planner may return (stopping granularity, loaded CI machines)."""

CHECK_LIMIT_S = 60.0
"""Hard limit on one check after its warm-up: a check plans at most three times with :data:`DEFAULT_BUDGET`."""

WARM_UP_LIMIT_S = 180.0
"""Hard limit on the untimed warm-up of a planner on one scenario kind (its first numba compilation included)."""

WARM_UP_PLAN_LIMIT_S = 30.0
"""Limit on the warm-up's wall time outside numba's compilation: a planner that ignores the warm-up's budget
(``Budget(iterations=5, time_s=2)``) is stopped here, not after :data:`WARM_UP_LIMIT_S`."""

SEED = 20240611
"""Seed of the generator handed to ``plan()`` by the checks."""

_ID_PATTERN = re.compile(r"^[a-z0-9_]+\.[a-z0-9_.\-]+$")


class ConformanceError(AssertionError):
    """A planner broke the planner contract; the message says which rule, where."""


class CheckTimeout(ConformanceError, BoundedTimeout):
    """A bounded call of the planner ran past its limit; the kit calls that planner no more."""


_TIMED_OUT: dict[int, tuple[Planner, str]] = {}
"""Planners (by ``id``, the planner kept so the id stays its own) that timed out, with the message."""


def _run_planner_bounded(planner: Planner, fn: Callable[[], object], limit_s: float, what: str,
                         compile_limit_s: float | None = None) -> None:
    """:func:`run_bounded` for a call of ``planner``: none after a first timeout, which is remembered.

    Raises
    ------
    CheckTimeout
        This call ran past its limit, or an earlier one of this planner did
        (then ``fn`` is not run).
    """
    earlier = _TIMED_OUT.get(id(planner))
    if earlier is not None and earlier[0] is planner:
        raise CheckTimeout(f"{planner.id}: not run: an earlier call timed out ({earlier[1]})")
    try:
        run_bounded(fn, limit_s, what, _failure(planner), compile_limit_s)
    except BoundedTimeout as exc:
        message = str(exc)
        _TIMED_OUT[id(planner)] = (planner, message)
        raise CheckTimeout(message if message.startswith(f"{planner.id}: ") else f"{planner.id}: {message}") from None


class _Progress:
    """Records every ``progress(iteration, evaluations, best_cost)`` call."""

    def __init__(self) -> None:
        self.calls: list[tuple[Any, Any, Any]] = []

    def __call__(self, iteration: int, evaluations: int, best_cost: float) -> None:
        self.calls.append((iteration, evaluations, best_cost))


def _fail(planner: Planner, message: str) -> ConformanceError:
    return ConformanceError(f"{planner.id}: {message}")


def _failure(planner: Planner) -> Callable[[str], ConformanceError]:
    """The error for a message from a bounded call, prefixed with the planner's id unless it has it."""
    prefix = f"{planner.id}: "
    return lambda message: ConformanceError(message if message.startswith(prefix) else prefix + message)


def _bounded_warm_up(planner: Planner, kind: str, budget: Budget) -> None:
    """:func:`warm_up` in this process, after a forked rehearsal has shown it returns within :data:`WARM_UP_LIMIT_S`."""
    if is_warm(planner, kind):
        return
    _run_planner_bounded(planner, lambda: warm_up(planner, kind, budget), min(WARM_UP_PLAN_LIMIT_S, WARM_UP_LIMIT_S),
                         f"the untimed warm-up plan() on {kind} with {budget}", compile_limit_s=WARM_UP_LIMIT_S)
    warm_up(planner, kind, budget)


def _bounded(check: Callable[..., None]) -> Callable[..., None]:
    """Run ``check`` in a forked process killed after :data:`CHECK_LIMIT_S` (the warm-up first, bounded too).

    Once a bounded call of a planner has timed out, every later bounded
    check of it fails at once with :class:`CheckTimeout` instead of waiting
    out its own limit.
    """

    @functools.wraps(check)
    def bounded(planner: Planner, **options: Any) -> None:
        kinds = [k for k in SCENARIO_KINDS if k in planner.kinds]
        kind = options.get("kind", kinds[0] if kinds else None)
        if kind in kinds:
            _bounded_warm_up(planner, kind, options.get("budget", DEFAULT_BUDGET))

        _run_planner_bounded(planner, lambda: check(planner, **options), CHECK_LIMIT_S, check.__name__)

    return bounded


def _plan(
    planner: Planner,
    scenario: Scenario,
    budget: Budget,
    progress: Callable[[int, int, float], None] | None = None,
    seed: int = SEED,
) -> PlanResult:
    """Call ``plan()`` (after a warm-up) and check that it returned a well-formed :class:`PlanResult`."""
    warm_up(planner, scenario.kind, budget)
    result = planner.plan(scenario, budget=budget, rng=np.random.default_rng(seed), progress=progress)
    if not isinstance(result, PlanResult):
        raise _fail(planner, f"plan() returned {type(result).__name__}, not a PlanResult, on {scenario.id}")
    if not isinstance(result.status, Status):
        raise _fail(planner, f"PlanResult.status must be a Status, got {result.status!r} on {scenario.id}")
    for name in ("iterations", "evaluations"):
        value = getattr(result, name)
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 0:
            raise _fail(planner, f"PlanResult.{name} must be an int >= 0, got {value!r} on {scenario.id}")
    return result


def _first_kind(planner: Planner) -> str:
    return next(k for k in SCENARIO_KINDS if k in planner.kinds)


# ------------------------------------------------------------------ declaration
def check_declaration(planner: Planner) -> None:
    """Class attributes are well formed and the defaults build a planner."""
    if not isinstance(planner.id, str) or not _ID_PATTERN.match(planner.id):
        raise _fail(planner, f"id must read 'family.name' in lower case, got {planner.id!r}")
    if not isinstance(planner.version, str) or not planner.version:
        raise _fail(planner, f"version must be a non-empty string, got {planner.version!r}")
    if not isinstance(planner.summary, str) or not planner.summary.strip() or "\n" in planner.summary:
        raise _fail(planner, "summary must be one non-empty line")
    kinds = set(planner.kinds)
    if not kinds or not kinds <= set(SCENARIO_KINDS):
        raise _fail(planner, f"kinds must be a non-empty subset of {SCENARIO_KINDS}, got {sorted(kinds)}")
    if not isinstance(planner.params, Mapping) or not all(isinstance(p, Param) for p in planner.params.values()):
        raise _fail(planner, "params must map parameter names to pathzoo.Param")
    default = type(planner)()
    if set(default.get_params()) != set(planner.params):
        raise _fail(planner, "get_params() must return exactly the declared params")


# ------------------------------------------------------------------ parameters
def check_rejects_unknown_parameter(planner: Planner) -> None:
    """An unknown keyword raises :class:`InvalidParameterError` naming it."""
    name = "no_such_parameter_xyz"
    try:
        type(planner)(**planner.get_params(), **{name: 1})
    except InvalidParameterError as exc:
        if name not in str(exc):
            raise _fail(planner, f"the error for an unknown parameter does not name it: {exc}") from None
        return
    raise _fail(planner, f"accepted the unknown parameter {name!r}")


def _outside(spec: Param) -> list[Any]:
    """Values that ``spec`` must reject, built from its declared type, range and choices."""
    bad: list[Any] = []
    if spec.choices is not None:
        bad.append(("not", "a", "choice"))
    elif spec.kind in (int, float):
        if spec.low is not None:
            value = spec.low if spec.low_open else spec.low - 1
            bad.append(math.floor(value) if spec.kind is int else float(value))
        if spec.high is not None:
            value = spec.high if spec.high_open else spec.high + 1
            bad.append(math.ceil(value) if spec.kind is int else float(value))
        if spec.kind is float:
            bad.append(float("nan"))
        bad.append("not a number")
    elif spec.kind is bool:
        bad.append("yes")
    elif spec.kind is str:
        bad.append(12345)
    if not spec.nullable:
        bad.append(None)
    return bad


def check_rejects_out_of_range(planner: Planner) -> None:
    """Each parameter rejects values outside its declared range, type or choices."""
    base = planner.get_params()
    for name, spec in planner.params.items():
        for value in _outside(spec):
            try:
                type(planner)(**{**base, name: value})
            except InvalidParameterError as exc:
                if name not in str(exc):
                    raise _fail(planner, f"the error for {name}={value!r} does not name the parameter: {exc}") from None
                continue
            raise _fail(planner, f"accepted {name}={value!r}, outside its declared {spec.describe_range()}")


# ------------------------------------------------------------------ solving
@_bounded
def check_solves(planner: Planner, *, kind: str, budget: Budget = DEFAULT_BUDGET) -> None:
    """The tiny reachable scenario is solved and the harness's validator accepts the path."""
    scenario = check_scenario(kind)
    result = _plan(planner, scenario, budget)
    if result.status is not Status.SOLVED:
        raise _fail(
            planner,
            f"did not solve the easy scenario {scenario.id} within {budget} "
            f"(status {result.status.value}: {result.message})",
        )
    if result.path is None:
        raise _fail(planner, f"status SOLVED without a path on {scenario.id}")
    verdict = validate_path(scenario, result.path, result.times)
    if not verdict:
        raise _fail(planner, f"invalid path on {scenario.id}: {verdict.reason}")


@_bounded
def check_same_seed_same_path(planner: Planner, *, kind: str, budget: Budget = DEFAULT_BUDGET) -> None:
    """Two calls with the same seed give the same answer.

    The global ``random`` and ``numpy.random`` states are set differently
    before each call, so a planner drawing from them is caught; the second
    call passes no progress callback, which must not change the result.
    """
    scenario = check_scenario(kind)
    warm_up(planner, kind, budget)
    saved = random.getstate(), np.random.get_state()
    try:
        random.seed(1)
        np.random.seed(1)
        first = _plan(planner, scenario, budget, progress=_Progress())
        random.seed(2)
        np.random.seed(2)
        second = _plan(planner, scenario, budget, progress=None)
    finally:
        random.setstate(saved[0])
        np.random.set_state(saved[1])
    _require_same(planner, scenario, first, second, "a second call with the same seed")


def _require_same(planner: Planner, scenario: Scenario, a: PlanResult, b: PlanResult, what: str) -> None:
    if a.status is not b.status:
        raise _fail(planner, f"{what} gave status {b.status.value}, the first {a.status.value}, on {scenario.id}")
    for name in ("path", "times"):
        x, y = getattr(a, name), getattr(b, name)
        if (x is None) != (y is None) or (x is not None and not np.array_equal(np.asarray(x), np.asarray(y))):
            raise _fail(planner, f"{what} gave a different {name} on {scenario.id}")


# ------------------------------------------------------------------ budget
def _check_count_limit(planner: Planner, counter: str, limit: int, time_s: float | None) -> None:
    """Plan with ``Budget(<counter>=limit)`` and require neither the result nor progress to exceed it."""
    scenario = check_scenario(_first_kind(planner))
    progress = _Progress()
    if counter == "iterations":
        budget = Budget(iterations=limit, time_s=time_s)
    else:
        budget = Budget(evaluations=limit, time_s=time_s)
    result = _plan(planner, scenario, budget, progress)
    position = 0 if counter == "iterations" else 1  # place of the count in progress(iteration, evaluations, cost)
    used = max([int(c[position]) for c in progress.calls] + [getattr(result, counter)])
    if used > limit:
        raise _fail(planner, f"used {used} {counter} with Budget({counter}={limit}) on {scenario.id}")


@_bounded
def check_budget_iterations(planner: Planner, *, budget: Budget = DEFAULT_BUDGET) -> None:
    """``Budget(iterations=2)`` is never exceeded, neither in the result nor in progress reports."""
    _check_count_limit(planner, "iterations", 2, budget.time_s)


@_bounded
def check_budget_evaluations(planner: Planner, *, budget: Budget = DEFAULT_BUDGET) -> None:
    """``Budget(evaluations=3)`` is never exceeded, neither in the result nor in progress reports."""
    _check_count_limit(planner, "evaluations", 3, budget.time_s)


@_bounded
def check_budget_time(planner: Planner, *, budget: Budget = DEFAULT_BUDGET) -> None:
    """With only a time limit, ``plan()`` returns within it (plus :data:`TIME_TOLERANCE_S`), or is killed then.

    The timed call follows the per-process warm-up (with ``budget``), so JIT
    compilation is not counted; it runs in its own forked process, killed
    ``TIME_BUDGET_S + TIME_TOLERANCE_S`` seconds after it starts.
    """
    scenario = check_scenario(_first_kind(planner))
    warm_up(planner, scenario.kind, budget)
    _run_planner_bounded(planner, lambda: _plan(planner, scenario, Budget(time_s=TIME_BUDGET_S)),
                         TIME_BUDGET_S + TIME_TOLERANCE_S, f"plan() with Budget(time_s={TIME_BUDGET_S}) on {scenario.id}")


@_bounded
def check_budget_default(planner: Planner, *, budget: Budget = DEFAULT_BUDGET) -> None:
    """With ``Budget()`` (no limit at all) ``plan()`` ends by the planner's own default count, within the check's limit.

    The rule of every family (``docs/timing.md``): no budget means the
    planner's own count, never an endless search. The bounded check fails a
    planner that has not returned after :data:`CHECK_LIMIT_S`.
    """
    scenario = check_scenario(_first_kind(planner))
    warm_up(planner, scenario.kind, budget)
    _plan(planner, scenario, Budget())


# ------------------------------------------------------------------ failure modes
@_bounded
def check_unreachable_goal(planner: Planner, *, kind: str, budget: Budget = DEFAULT_BUDGET) -> None:
    """A walled-in goal gives ``NO_PATH`` or ``FAILED``, not an exception and never ``SOLVED``."""
    scenario = check_scenario(kind, reachable=False)
    try:
        result = _plan(planner, scenario, budget)
    except ConformanceError:
        raise
    except Exception as exc:
        raise _fail(planner, f"raised {type(exc).__name__}: {exc} on the unreachable {scenario.id}") from exc
    if result.status not in (Status.NO_PATH, Status.FAILED):
        raise _fail(planner, f"returned status {result.status.value} on the unreachable {scenario.id}")


@_bounded
def check_unsupported_kinds(planner: Planner, *, budget: Budget = DEFAULT_BUDGET) -> None:
    """Every kind the planner does not declare raises :class:`UnsupportedScenarioError`."""
    for kind in SCENARIO_KINDS:
        if kind in planner.kinds:
            continue
        scenario = check_scenario(kind)
        try:
            planner.plan(scenario, budget=budget, rng=np.random.default_rng(SEED), progress=None)
        except UnsupportedScenarioError:
            continue
        raise _fail(planner, f"did not raise UnsupportedScenarioError on undeclared kind {kind!r}")


# ------------------------------------------------------------------ purity
def _snapshot(value: Any) -> Any:
    """A comparable deep image of a value: arrays by dtype, shape, flags and bytes."""
    if isinstance(value, np.ndarray):
        return ("ndarray", value.dtype.str, value.shape, bool(value.flags.writeable), value.tobytes())
    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        fields = tuple((f.name, _snapshot(getattr(value, f.name))) for f in dataclasses.fields(value))
        return (type(value).__qualname__, fields)
    if isinstance(value, Mapping):
        return ("mapping", tuple(sorted((repr(k), _snapshot(v)) for k, v in value.items())))
    if isinstance(value, (list, tuple)):
        return (type(value).__name__, tuple(_snapshot(v) for v in value))
    return ("value", repr(value))


def _scenario_image(scenario: Scenario) -> dict[str, Any]:
    """Every field and every cached geometry attribute of a scenario."""
    return {name: _snapshot(value) for name, value in vars(scenario).items()}


@_bounded
def check_scenario_unchanged(planner: Planner, *, kind: str, budget: Budget = DEFAULT_BUDGET) -> None:
    """``plan()`` changes neither the scenario's fields nor its cached geometry, and adds no attribute."""
    scenario = check_scenario(kind)
    for cached in ("blocked", "graph", "clearance"):  # build the shared caches so they are compared too
        getattr(scenario, cached)
    before = _scenario_image(scenario)
    _plan(planner, scenario, budget)
    after = _scenario_image(scenario)
    added = sorted(set(after) - set(before))
    if added:
        raise _fail(planner, f"plan() added attribute(s) {added} to the scenario {scenario.id}")
    changed = sorted(name for name in before if before[name] != after.get(name))
    if changed:
        raise _fail(planner, f"plan() changed the scenario's {', '.join(changed)} on {scenario.id}")


@_bounded
def check_picklable(planner: Planner, *, budget: Budget = DEFAULT_BUDGET) -> None:
    """The planner pickles, keeps no state across ``plan()`` and its copy gives the same answer."""
    scenario = check_scenario(_first_kind(planner))
    try:
        blob = pickle.dumps(planner)
    except Exception as exc:
        raise _fail(planner, f"cannot be pickled: {type(exc).__name__}: {exc}") from exc
    copy = pickle.loads(blob)
    if copy.get_params() != planner.get_params():
        raise _fail(planner, "the unpickled planner has different parameters")
    first = _plan(planner, scenario, budget)
    if pickle.dumps(planner) != blob:
        raise _fail(planner, "plan() changed the planner's state (a planner keeps no state between calls)")
    _require_same(planner, scenario, first, _plan(copy, scenario, budget), "the unpickled planner")


@_bounded
def check_leaves_global_rng_alone(planner: Planner, *, kind: str, budget: Budget = DEFAULT_BUDGET) -> None:
    """``plan()`` leaves the global ``random`` and ``numpy.random`` generators as it found them.

    All randomness must come from the ``rng`` argument. A planner that draws
    from a global generator changes its state (a library that needs one may
    seed it from ``rng`` and restore it before returning).
    """
    scenario = check_scenario(kind)
    random.seed(SEED)
    np.random.seed(SEED % 2**32)
    before = random.getstate(), np.random.get_state()
    _plan(planner, scenario, budget)
    used = [name for name, same in (("random", random.getstate() == before[0]),
                                    ("numpy.random", _same_numpy_state(np.random.get_state(), before[1])))
            if not same]
    if used:
        raise _fail(planner, f"plan() drew from the global generator(s) {' and '.join(used)} on {scenario.id}; "
                             "draw from the rng argument")


def _same_numpy_state(a: Any, b: Any) -> bool:
    return all(np.array_equal(x, y) if isinstance(x, np.ndarray) else x == y for x, y in zip(a, b))


@_bounded
def check_history_improves(planner: Planner, *, kind: str, budget: Budget = DEFAULT_BUDGET) -> None:
    """Progress reports never increase the best cost, and a solving run reports at least once."""
    scenario = check_scenario(kind)
    progress = _Progress()
    result = _plan(planner, scenario, budget, progress)
    if result.solved and not progress.calls:
        raise _fail(planner, f"solved {scenario.id} without ever calling progress()")
    previous = (-1, -1, math.inf)
    for call in progress.calls:
        iteration, evaluations, cost = call
        if not isinstance(cost, (int, float, np.integer, np.floating)) or math.isnan(cost):
            raise _fail(planner, f"progress() got best_cost={cost!r} on {scenario.id}; use inf before a solution")
        if iteration < previous[0] or evaluations < previous[1]:
            raise _fail(planner, f"progress() counts went backwards: {previous[:2]} then {call[:2]} on {scenario.id}")
        if cost > previous[2]:
            raise _fail(planner, f"best_cost increased from {previous[2]} to {cost} on {scenario.id}")
        previous = call
