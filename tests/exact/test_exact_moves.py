"""The move-table A* kernel: built only when it describes the graph exactly, and bit-identical to the CSR kernel."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import pathzoo
from pathzoo.core import Budget, Scenario
from pathzoo.generators import random_obstacles
from pathzoo.core.tiny_scenarios import check_scenario
from pathzoo_exact.problem import H_EUCLID, H_OCTILE, H_ZERO, search_problem
from pathzoo_exact.search_loop import astar_batch, astar_moves_batch
from pathzoo_exact.search_state import FOUND, HEAP_FULL, RUNNING, SearchState, run_batch
from pathzoo_exact.moves import move_table


def random_grid(seed: int, shape=(37, 53), cell_size: float = 0.5) -> Scenario:
    occ = random_obstacles(shape, seed=seed, density=0.25)
    occ[0, 0] = occ[-1, -1] = False
    h, w = shape
    return Scenario(id=f"random{seed}", kind="grid2d", occupancy=occ, cell_size=cell_size,
                    start=(0.25 * cell_size, 0.25 * cell_size), goal=((w - 0.5) * cell_size, (h - 0.5) * cell_size))


def search(kernel, args: tuple, max_degree: int, n_nodes: int, source: int, batch: int, heap: int) -> tuple[SearchState, int]:
    """Run a whole search in batches of ``batch`` expansions from a heap of ``heap`` slots."""
    state = SearchState.start(n_nodes, source, heap)
    while True:
        status = run_batch(kernel, args, max_degree, state, batch)
        if status == HEAP_FULL:
            state.grow_heap()
        elif status != RUNNING:
            return state, status


def both_kernels(scenario: Scenario, cost: str, mode: int, scale: float, batch: int = 1 << 30, heap: int = 4096):
    graph = scenario.graph
    table = move_table(graph, cost)
    assert table is not None
    dims = np.array((1,) * (3 - len(graph.shape)) + tuple(graph.shape), dtype=np.int64)
    sizes = scenario.cell_sizes
    steps = np.array([sizes[0], sizes[1], sizes[2] if len(sizes) == 3 else 0.0])
    target = scenario.goal_node
    problem = search_problem(target, dims, steps, mode, scale)
    csr = search(astar_batch, (graph.indptr, graph.indices, graph.weights(cost), *problem), len(graph.offsets),
                 graph.n_nodes, scenario.start_node, batch, heap)
    moves = search(astar_moves_batch, (table.mask, table.shift, table.weight, table.cell, *problem), table.n_moves,
                   graph.n_nodes, scenario.start_node, batch, heap)
    return csr, moves


def assert_same_search(csr: tuple[SearchState, int], moves: tuple[SearchState, int]) -> None:
    (a, status_a), (b, status_b) = csr, moves
    assert status_a == status_b
    assert a.expanded == b.expanded
    np.testing.assert_array_equal(a.g, b.g)  # exact, not approximate: inf and every float bit
    seen = np.isfinite(a.g)
    np.testing.assert_array_equal(a.parent[seen], b.parent[seen])  # parents of unseen nodes are never written
    np.testing.assert_array_equal(a.closed, b.closed)


@pytest.mark.parametrize("seed", [0, 1, 3, 4])
@pytest.mark.parametrize("cost", ["length", "energy"])
@pytest.mark.parametrize("mode", [H_OCTILE, H_ZERO])
def test_moves_kernel_is_bit_identical_to_the_csr_kernel_on_grids(seed: int, cost: str, mode: int) -> None:
    scenario = random_grid(seed)
    graph = scenario.graph
    scale = 1.0 if cost == "length" else float(np.min(graph.energy / graph.length))
    csr, moves = both_kernels(scenario, cost, mode, scale)
    assert csr[1] == FOUND
    assert_same_search(csr, moves)


def test_moves_kernel_is_bit_identical_when_resumed_and_when_the_heap_grows() -> None:
    scenario = random_grid(5)
    whole = both_kernels(scenario, "length", H_OCTILE, 1.0)
    pieces = both_kernels(scenario, "length", H_OCTILE, 1.0, batch=7, heap=2)
    assert_same_search(whole[0], pieces[1])
    assert_same_search(pieces[0], pieces[1])


@pytest.mark.parametrize("cost", ["length", "energy"])
def test_moves_kernel_is_bit_identical_in_air_volumes(cost: str) -> None:
    scenario = check_scenario("air3d")  # 26 moves, so a uint32 mask and the 3-D cell decoding
    assert move_table(scenario.graph, cost).mask.dtype == np.uint32
    scale = 1.0 if cost == "length" else float(np.min(scenario.graph.energy / scenario.graph.length))
    csr, moves = both_kernels(scenario, cost, H_EUCLID, scale)
    assert csr[1] == FOUND
    assert_same_search(csr, moves)


def test_unreachable_goal_exhausts_both_kernels_alike() -> None:
    csr, moves = both_kernels(check_scenario("grid2d", reachable=False), "length", H_OCTILE, 1.0)
    assert csr[1] == moves[1] != FOUND
    assert_same_search(csr, moves)


def test_no_table_when_edge_costs_vary_per_edge_or_there_are_too_many_moves() -> None:
    assert move_table(check_scenario("terrain").graph, "length") is None  # 3-D lengths differ per edge
    assert move_table(pathzoo.load_scenario("dsaco.complex").graph, "length") is None  # 74 moves


def test_no_table_when_one_edge_breaks_a_rule() -> None:
    graph = random_grid(0).graph
    assert move_table(graph, "length") is not None
    length = graph.length.copy()
    length[len(length) // 2] = np.nextafter(length[len(length) // 2], np.inf)  # one ulp off its move's cost
    assert move_table(dataclasses.replace(graph, length=length), "length") is None
    u = int(np.flatnonzero(np.diff(graph.indptr) >= 2)[0])
    lo = graph.indptr[u]
    order = np.arange(graph.n_edges)
    order[[lo, lo + 1]] = order[[lo + 1, lo]]  # two edges of one node out of move order
    swapped = dataclasses.replace(graph, indices=graph.indices[order], length=graph.length[order],
                                  slope=graph.slope[order], offset_id=graph.offset_id[order])
    assert move_table(swapped, "length") is None
    indices = graph.indices.copy()
    indices[lo] = indices[lo + 1]  # an edge whose target is not where its move leads
    assert move_table(dataclasses.replace(graph, indices=indices), "length") is None


def test_table_is_built_once_per_graph_and_cost() -> None:
    graph = random_grid(0).graph
    assert move_table(graph, "length") is move_table(graph, "length")
    assert move_table(graph, "energy") is not move_table(graph, "length")


@pytest.mark.parametrize("planner_id", ["exact.astar", "exact.dijkstra"])
def test_planners_use_the_table_and_match_the_csr_kernel(planner_id: str, monkeypatch: pytest.MonkeyPatch) -> None:
    scenario = random_grid(4)
    fast = pathzoo.make_planner(planner_id).plan(scenario, budget=Budget(), rng=np.random.default_rng(0))
    monkeypatch.setattr("pathzoo_exact.astar.move_table", lambda graph, cost: None)
    slow = pathzoo.make_planner(planner_id).plan(scenario, budget=Budget(), rng=np.random.default_rng(0))
    assert fast.solved and slow.solved
    np.testing.assert_array_equal(fast.path, slow.path)
    assert fast.evaluations == slow.evaluations
    assert fast.extras == slow.extras
