"""Time left from per-planner mean run times."""

from __future__ import annotations

import pytest

from pathzoo.harness.eta import RunTimes, eta_seconds


def test_no_estimate_before_any_run():
    assert eta_seconds(["a", "b"], RunTimes()) is None


def test_each_planner_costs_its_own_mean_and_unseen_ones_the_overall_mean():
    times = RunTimes()
    for s in (1.0, 3.0):
        times.add("fast", s)  # mean 2
    times.add("slow", 100.0)  # mean 100; overall mean (1 + 3 + 100) / 3
    remaining = ["fast"] * 10 + ["slow"] * 2 + ["new"]
    expected = 10 * 2.0 + 2 * 100.0 + 104.0 / 3
    assert eta_seconds(remaining, times) == pytest.approx(expected)
    assert eta_seconds(remaining, times, parallel=4) == pytest.approx(expected / 4)


def test_estimate_does_not_swing_with_the_last_finished_planner():
    times = RunTimes()
    times.add("fast", 0.01)
    times.add("slow", 10.0)
    before = eta_seconds(["fast"] * 100 + ["slow"] * 5, times)
    times.add("fast", 0.01)  # a fast run finishing does not make the slow runs look fast
    after = eta_seconds(["fast"] * 99 + ["slow"] * 5, times)
    assert after == pytest.approx(before - 0.01)
    assert eta_seconds([], times) == 0.0
