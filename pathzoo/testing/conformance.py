"""Running the conformance checks: one planner at once, or as pytest parameters.

In the manner of scikit-learn's ``parametrize_with_checks``::

    from pathzoo.testing import parametrize_with_checks

    @parametrize_with_checks(["greedy.best_first"])
    def test_planner(planner, check):
        check(planner)
"""

from __future__ import annotations

import functools
from typing import TYPE_CHECKING, Any, Callable, Iterable, Iterator

from pathzoo.core.budget import Budget
from pathzoo.core.errors import InvalidParameterError
from pathzoo.core.planner import Planner
from pathzoo.core.scenario import SCENARIO_KINDS
from pathzoo.testing import checks as _c

if TYPE_CHECKING:
    import pytest

__all__ = ["PlannerLike", "as_planner", "planner_checks", "check_id", "check_planner", "parametrize_with_checks"]

PlannerLike = str | type[Planner] | Planner
"""A registered planner id, a Planner subclass (built with its defaults) or an instance."""

Check = Callable[[Planner], None]

_PER_PLANNER = (_c.check_declaration, _c.check_rejects_unknown_parameter, _c.check_rejects_out_of_range)
_PER_KIND = (
    _c.check_solves,
    _c.check_same_seed_same_path,
    _c.check_unreachable_goal,
    _c.check_scenario_unchanged,
    _c.check_history_improves,
    _c.check_leaves_global_rng_alone,
)
_ON_FIRST_KIND = (
    _c.check_budget_iterations,
    _c.check_budget_evaluations,
    _c.check_budget_time,
    _c.check_budget_default,
    _c.check_picklable,
)


def as_planner(obj: PlannerLike) -> Planner:
    """Turn a planner id, class or instance into an instance.

    Raises
    ------
    UnknownPluginError
        ``obj`` is a string that is not a registered planner id.
    InvalidParameterError
        ``obj`` is neither an id, a Planner subclass nor a Planner.
    """
    if isinstance(obj, Planner):
        return obj
    if isinstance(obj, type) and issubclass(obj, Planner):
        return obj()
    if isinstance(obj, str):
        from pathzoo.plugins.lookup import make_planner

        return make_planner(obj)
    raise InvalidParameterError(f"planners: expected a planner id, Planner subclass or instance, got {obj!r}")


def planner_checks(planner: Planner, *, budget: Budget | None = None) -> Iterator[Check]:
    """Every check that applies to ``planner``, each a one-argument callable.

    Checks that plan run once per declared scenario kind (or on the first
    declared kind for budget and pickling checks). ``budget`` replaces
    :data:`pathzoo.testing.checks.DEFAULT_BUDGET` for planners that need more
    than five iterations to solve a 10x10 map.
    """
    options: dict[str, Any] = {} if budget is None else {"budget": budget}
    check: Callable[..., None]
    yield from _PER_PLANNER
    kinds = [k for k in SCENARIO_KINDS if k in planner.kinds]
    if not kinds:
        return  # check_declaration reports the missing kinds
    for kind in kinds:
        for check in _PER_KIND:
            yield functools.partial(check, kind=kind, **options)
    for check in _ON_FIRST_KIND:
        yield functools.partial(check, **options)
    if len(kinds) < len(SCENARIO_KINDS):
        yield functools.partial(_c.check_unsupported_kinds, **options)


def check_id(check: Check) -> str:
    """A short test id such as ``check_solves[grid2d]``."""
    func = getattr(check, "func", check)
    kind = getattr(check, "keywords", {}).get("kind")
    return func.__name__ + (f"[{kind}]" if kind else "")


def check_planner(planner: PlannerLike, *, budget: Budget | None = None) -> None:
    """Run every check on one planner.

    Every check runs until one of them times out (a planner that ignores
    its budget); the checks after it are listed as not run, so the kit
    answers within about one check's limit instead of waiting out each
    check's own.

    Raises
    ------
    ConformanceError
        Listing every failed check with its reason.
    """
    instance = as_planner(planner)
    failures: list[str] = []
    checks = list(planner_checks(instance, budget=budget))
    for i, check in enumerate(checks):
        try:
            check(instance)
        except _c.CheckTimeout as exc:
            failures.append(f"{check_id(check)}: {type(exc).__name__}: {exc}")
            if checks[i + 1:]:
                failures.append("not run after that timeout: " + ", ".join(check_id(c) for c in checks[i + 1:]))
            break
        except Exception as exc:  # one broken check must not hide the others
            failures.append(f"{check_id(check)}: {type(exc).__name__}: {exc}")
    if failures:
        raise _c.ConformanceError(
            f"{instance.id} failed {len(failures)} check(s):\n  " + "\n  ".join(failures)
        )


def parametrize_with_checks(
    planners: Iterable[PlannerLike], *, budget: Budget | None = None
) -> "pytest.MarkDecorator":
    """A ``pytest.mark.parametrize`` over every (planner, check) pair.

    The decorated test takes the arguments ``planner`` and ``check`` and
    should call ``check(planner)``. Test ids read ``<configuration>-<check id>``,
    where the configuration is ``id(param=value, ...)`` listing the parameters
    that differ from the defaults (:attr:`Planner.config_name`), so two
    configurations of one planner get distinct ids.

    Parameters
    ----------
    planners : iterable
        Planner ids, Planner subclasses or instances.
    budget : Budget, optional
        Planning budget of the checks (default ``Budget(iterations=5, time_s=2)``).
    """
    import pytest

    pairs: list[tuple[Planner, Check]] = []
    ids: list[str] = []
    for obj in planners:
        planner = as_planner(obj)
        for check in planner_checks(planner, budget=budget):
            pairs.append((planner, check))
            ids.append(f"{planner.config_name}-{check_id(check)}")
    return pytest.mark.parametrize(("planner", "check"), pairs, ids=ids)
