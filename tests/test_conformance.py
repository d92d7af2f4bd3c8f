"""Every registered planner passes the conformance kit (planners added later are covered automatically)."""

import pathzoo
from pathzoo.testing import parametrize_with_checks

PLANNERS = [entry.obj for entry in pathzoo.list_plugins("planners")]


def test_planners_are_registered():
    # guards against the parametrized test below silently collecting nothing
    assert PLANNERS, "no planner is registered; the conformance tests would run on nothing"


@parametrize_with_checks(PLANNERS)
def test_planner_conforms(planner, check):
    check(planner)
