"""Values kept per route and segment verdicts kept per segment: answers from what was kept are the computed ones."""

from __future__ import annotations

import numpy as np
import pytest

import pathzoo
from pathzoo_rivals.route_kernels import pull_string_free, segment_free, via_route
from pathzoo_rivals.route_memo import RouteMemo
from pathzoo_rivals.route_moves import leap
from pathzoo_rivals.routes import RouteProblem


@pytest.fixture(scope="module")
def hugo() -> pathzoo.Scenario:
    return pathzoo.load_scenario("ggaco.hugo")


def candidates(problem: RouteProblem, seed: int = 0) -> list[np.ndarray]:
    """Random routes and leaps between them, each twice: what a frog population evaluates."""
    rng = np.random.default_rng(seed)
    found = [r for r in (problem.random_route(rng) for _ in range(15)) if r is not None]
    leaps = [leap(problem, a, b, rng) for a, b in zip(found[:-1], found[1:])]
    out = found + [r for r in leaps if r is not None]
    return out + out[::-1]


@pytest.mark.parametrize("rule", ["energy", "length"])
def test_kept_measures_are_the_computed_ones(hugo, rule):
    problem = RouteProblem(hugo)
    routes = candidates(problem)
    for route in routes:
        f, cost = problem.measure(route, rule)
        f_new, cost_new = RouteProblem(hugo).measure(route, rule)  # a fresh problem: computed, nothing kept
        assert f.tobytes() == f_new.tobytes() and cost == cost_new
        f[0] = -1.0  # a caller's change does not reach what was kept
    assert len(problem._measured[rule].kept) <= len(routes) // 2  # the second half was answered from the memo


def test_a_full_memo_starts_again(hugo):
    problem = RouteProblem(hugo)
    routes = candidates(problem, seed=1)
    memo: RouteMemo[tuple[np.ndarray, float]] = RouteMemo(capacity=3 * (len(routes[0]) * 8 + 400))
    for route in routes:
        known = memo.get(route)
        value = RouteProblem(hugo).measure(route, "energy")
        if known is not None:
            assert known[0].tobytes() == value[0].tobytes() and known[1] == value[1]
        else:
            memo.keep(route, value)
        assert memo.bytes <= memo.capacity
    assert len(memo.kept) < len(set(r.tobytes() for r in routes))


def test_kept_outline_is_the_polyline_and_its_length(hugo):
    problem = RouteProblem(hugo)
    for route in candidates(problem, seed=2):
        points, length = problem.outline(route)
        expected = problem.polyline(route)
        assert points.tobytes() == expected.tobytes()
        assert length == float(np.hypot(*np.diff(expected, axis=0).T).sum())


def reference_pull(problem: RouteProblem, nodes: np.ndarray) -> np.ndarray:
    """The greedy string-pulling of RouteProblem.pull_string, every segment walked."""
    keep, anchor, i = [int(nodes[0])], 0, 1
    while i < len(nodes):
        j = i
        while j + 1 < len(nodes) and segment_free(problem.blocked, problem.cell_size, nodes[anchor], nodes[j + 1]):
            j += 1
        keep.append(int(nodes[j]))
        anchor, i = j, j + 1
    return np.array(keep, dtype=np.int64)


@pytest.mark.parametrize("slots", [1 << 4, 1 << 12])
def test_kept_segment_verdicts_pull_the_same_string(hugo, slots):
    # the collision test on hugo's map; a small table: segments keep replacing each other in their slots, and every
    # answer must still be the walk's
    problem = RouteProblem(hugo)
    from_start, to_goal, d_start, d_goal = problem._trees()
    vias = np.flatnonzero(d_start + d_goal <= 1.2 * d_goal[problem.start])
    scratch = np.full(len(d_start), -1, dtype=np.int64)
    seen = np.full(slots, -1, dtype=np.int64)
    for via in np.random.default_rng(3).choice(vias, size=40):
        nodes = via_route(from_start, to_goal, int(via), problem.goal, scratch)
        assert pull_string_free(problem.blocked, problem.cell_size, nodes, seen).tobytes() == \
            reference_pull(problem, nodes).tobytes()
    assert np.count_nonzero(seen >= 0) >= min(slots, 500)
