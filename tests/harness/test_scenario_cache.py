"""The scenario caches, bounded by map cells: the judge's keeps many small problems (each loaded once), a worker's
keeps large maps one at a time (its sandbox's memory holds one, not four)."""

from __future__ import annotations

import pytest

from pathzoo.harness import Experiment
from pathzoo.harness import scenario_cache
from pathzoo.harness.scenario_cache import SCENARIO_CACHE_SIZE, load_cached, load_unsealed
from pathzoo.plugins.manager import get_registry


@pytest.fixture()
def specs():
    """Twelve problems of one 32 x 32 MovingAI map (1,024 cells each), with an empty cache around the test."""
    problems = sorted(k for k in get_registry().scenarios if k.startswith("movingai.random-32-32-20."))[:12]
    tasks = Experiment.build(planners=["exact.astar"], scenarios=problems, seeds=1).tasks()
    saved = dict(scenario_cache._unsealed), dict(scenario_cache._scenarios)
    scenario_cache._unsealed.clear()
    scenario_cache._scenarios.clear()
    yield [task.scenario for task in tasks]
    for cache, kept in zip((scenario_cache._unsealed, scenario_cache._scenarios), saved):
        cache.clear()
        cache.update(kept)


def test_scenarios_within_the_cell_budget_are_loaded_once(specs):
    first = [load_unsealed(spec, cells=12 * 1024) for spec in specs]
    again = [load_unsealed(spec, cells=12 * 1024) for spec in specs]
    assert all(a is b for a, b in zip(first, again))  # the same objects: no reload, references derived once
    assert len(scenario_cache._unsealed) == 12


def test_the_oldest_go_beyond_the_cell_budget(specs):
    first = [load_unsealed(spec, cells=6 * 1024) for spec in specs]
    assert list(scenario_cache._unsealed) == [spec.cache_key for spec in specs[6:]]
    assert load_unsealed(specs[-1], cells=6 * 1024) is first[-1]
    assert load_unsealed(specs[0], cells=6 * 1024) is not first[0]  # evicted: loaded afresh


def test_at_least_the_scenario_count_is_kept_whatever_their_size(specs):
    for spec in specs:
        load_unsealed(spec, cells=1)
    assert len(scenario_cache._unsealed) == SCENARIO_CACHE_SIZE
    assert list(scenario_cache._unsealed) == [spec.cache_key for spec in specs[-SCENARIO_CACHE_SIZE:]]


def test_a_worker_keeps_at_most_the_scenario_count_and_the_cell_budget(specs):
    keys = [spec.cache_key for spec in specs]
    for spec in specs[:6]:
        load_cached(spec, cells=100 * 1024)
    assert list(scenario_cache._scenarios) == keys[6 - SCENARIO_CACHE_SIZE:6]  # the count binds
    for spec in specs[6:]:
        load_cached(spec, cells=2 * 1024)
    assert list(scenario_cache._scenarios) == keys[-2:]  # the cells bind
    kept = load_cached(specs[-1], cells=2 * 1024)
    assert load_cached(specs[-1], cells=2 * 1024) is kept
    load_cached(specs[0], cells=1)
    assert list(scenario_cache._scenarios) == keys[:1]  # the last one stays, whatever its size
