"""Conformance kit for planner authors: run pathzoo's planner contract checks in your own tests.

Use :func:`parametrize_with_checks` in a pytest suite, or :func:`check_planner`
anywhere::

    from pathzoo.testing import parametrize_with_checks

    @parametrize_with_checks(["myfamily.myplanner"])
    def test_conformance(planner, check):
        check(planner)

The checks are listed in :mod:`pathzoo.testing.checks`; the tiny scenarios
they plan on come from :func:`check_scenario`.
"""

from pathzoo.testing.checks import DEFAULT_BUDGET, CheckTimeout, ConformanceError
from pathzoo.testing.conformance import (
    PlannerLike,
    as_planner,
    check_id,
    check_planner,
    parametrize_with_checks,
    planner_checks,
)
from pathzoo.core.tiny_scenarios import check_scenario

__all__ = [
    "DEFAULT_BUDGET",
    "CheckTimeout",
    "ConformanceError",
    "PlannerLike",
    "as_planner",
    "check_id",
    "check_planner",
    "check_scenario",
    "parametrize_with_checks",
    "planner_checks",
]
