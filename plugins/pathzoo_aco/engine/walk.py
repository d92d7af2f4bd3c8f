"""The colony's walks: :class:`WalkEngine` sends a colony of ants from the start and returns their walks.

It picks the compiled kernel a colony needs (:func:`~pathzoo_aco.engine.walk_kernel.colony_kernel`: weights
fixed before the colony or read from the trail at each step, ants one after another or racing and pre-choice
additions, ants that keep time among moving obstacles when :meth:`WalkEngine.timing` gives their tables), keeps
their buffers between colonies and grows them when a kernel asks. Weights are fixed before a
colony only when no ant changes the trail as it walks and the colony is expected to take enough steps to repay
the pass over every listed edge (:meth:`WalkEngine.weights_pay`).

Random numbers come from numba's generator, seeded from the planner's
``rng`` at every iteration, so one seed gives one path.
"""

from __future__ import annotations

import numba
import numpy as np

from pathzoo_aco.engine.outcomes import ABORTED, DONE, EXHAUSTED, FRESH, OUTRUN, REACHED, STEP_CAP, STUCK
from pathzoo_aco.engine.pheromone import Pheromone
from pathzoo_aco.engine.problem import ColonyProblem
from pathzoo_aco.engine.rules import WalkRules
from pathzoo_aco.engine.walk_kernel import KERNELS, Adjacency, fill_weights, unsigned_lists
from pathzoo_aco.engine.walk_result import Walks

__all__ = ["WalkEngine", "FILL_STEPS_PER_NODE", "REACHED", "STUCK", "STEP_CAP", "EXHAUSTED", "ABORTED", "OUTRUN"]

FILL_STEPS_PER_NODE = {True: 0.25, False: 2.5}
"""Steps per graph node a colony must be expected to take for filling its weights first to pay, by whether the
trail exponent is 1.

Filling costs one weight per listed edge; a step then saves, on each
candidate it reads, the trail read, the factors (and with another exponent
the kept power) of the kernel that weighs edges at each step. A step reads
about a node's degree of candidates, so the fill pays once the steps exceed
``fill cost per edge / saving per read`` times the nodes. Measured on
``dsaco.complex`` and ``gant.complex.1``: a fill costs 0.6-0.8 ns per edge
and saves 2-6 ns per read with an exponent of 1; 22-30 ns per edge (a
``pow``) against about 10 ns saved per read with another exponent.
"""


@numba.njit(cache=True)
def _seed(seed):
    np.random.seed(seed)


def _grown(stacks: np.ndarray, depth: np.ndarray) -> np.ndarray:
    """Racing ants' stacks with rows twice as long; only each ant's live entries (``:depth``) are copied.

    The new array comes zeroed from the operating system, so the rows' unused
    tails take no memory: the stacks cost what the ants' walks hold, not
    ``n_ants`` times the deepest walk (0.4 GB when one ant of
    ``ggaco.case1`` went two million edges deep).
    """
    grown = np.zeros((stacks.shape[0], 2 * stacks.shape[1]), dtype=stacks.dtype)
    for a, d in enumerate(depth.tolist()):
        grown[a, :d] = stacks[a, :d]
    return grown


class WalkEngine:
    """Runs colonies of walks on one problem, reusing its buffers between iterations.

    Parameters
    ----------
    problem : ColonyProblem
        The scenario's graph.
    """

    def __init__(self, problem: ColonyProblem) -> None:
        g = problem.graph
        self.problem = problem
        self.stamps = np.zeros((1, g.n_nodes), dtype=np.uint8)  # tabu stamps of ants walking one by one (1..255)
        self.walk_base = 1
        self.race_stamps = np.zeros((0, g.n_nodes), dtype=np.uint8)  # one row per racing ant, stamped 1..255
        self.race_colony = 1
        self.stack_e = np.zeros((1, problem.n_free + 1), dtype=np.int64)
        self.stack_prev = np.zeros((1, problem.n_free + 1), dtype=np.int64)
        kmax = int(g.degree.max()) if g.n_nodes else 0
        self.cand_w = np.zeros(max(kmax, 1))
        self.flat = np.zeros(1024, dtype=np.int64)
        self.offset_id = problem.offset_id_small  # moves: compact
        self.indices = problem.indices32  # half the memory traffic of the int64 CSR arrays
        self.weights = np.zeros(0)  # per-colony weights of the listed edges (see :meth:`colony_weights`)
        self.powers = np.zeros(0)  # trail powers kept by the local kernel, valid where stamped with the colony
        self.power_stamp = np.zeros(0, dtype=np.int32)
        self.colony = 0
        self.lists: tuple = (None, ())  # an adjacency and its lists as the kernels read them
        self.both_kernels = False
        """Whether the kernel this engine's colonies did not take has been called once (for no ant) with their
        argument types. A colony takes the filled-weights kernel or the other one (:meth:`weights_pay`), so a
        process's walks can need either; numba loads a kernel for a new set of types from its disk cache at the
        first call (tens of milliseconds). Called so in a worker's warm-up, both are loaded before any run's
        process is forked from it, instead of in the runs that take the other one (and charged to them)."""
        self.total_steps = 0
        self.steps_per_ant = -1.0  # of the last colony (-1 before the first)

    def adjacency(self, rules: WalkRules) -> Adjacency:
        """The edges an ant may take under ``rules``, per node, as the kernel reads them.

        Returns ``(adj_ptr, adj_node, adj_edge, adj_offset, weight_mul,
        weight_add)``: a CSR of the edges with their target nodes, graph edge
        ids, moves and weights in list order (one after another in memory).

        An edge whose ``weight_mul`` and ``weight_add`` are both 0 can never
        be chosen, so it is left out (an ant then never looks at it; the
        choices and the random numbers drawn stay the same). Without such
        edges, or with ``pre_add`` (which writes every edge's trail), the
        list is the whole graph, ``adj_edge`` is None and the arrays are the
        graph's and the rules' own. Computed once per
        set of weight arrays (O(edges)) and kept as long as those arrays
        live (rules cached on the problem share it across ``plan()`` calls);
        :func:`dataclasses.replace` on the rules keeps the arrays, so
        schedules of ``q0`` cost nothing here.
        """
        key = ("adjacency", id(rules.weight_mul), id(rules.weight_add), id(rules.pre_add))
        # the memo holds the arrays themselves, so their ids cannot be reused while the entry lives
        return self.problem.memo(key, lambda: (rules.weight_mul, rules.weight_add, rules.pre_add,
                                               self._adjacency(rules)))[3]

    def _adjacency(self, rules: WalkRules) -> Adjacency:
        g = self.problem.graph
        adjacency: Adjacency = (g.indptr, self.indices, None, self.offset_id, rules.weight_mul, rules.weight_add)
        if rules.pre_add.size == 0:
            live = rules.weight_mul != 0.0
            if rules.weight_add.size:
                live |= rules.weight_add != 0.0
            if not live.all():
                adj_edge = np.flatnonzero(live).astype(np.int32)
                adj_ptr = np.concatenate([[0], np.cumsum(live)])[g.indptr]
                add = rules.weight_add[adj_edge] if rules.weight_add.size else rules.weight_add
                adjacency = (adj_ptr, self.indices[adj_edge], adj_edge, self.offset_id[adj_edge],
                             rules.weight_mul[adj_edge], add)
        return adjacency

    def colony_weights(self, rules: WalkRules, trail: Pheromone) -> np.ndarray | None:
        """Every listed edge's weight for the coming colony (before turn factors), or None if the trail may change.

        Only when no ant changes the trail while it walks (no ``pre_add``, no
        local update): then each edge's weight is the same at every step of
        the colony, and :func:`~pathzoo_aco.engine.walk_kernel.fill_weights` computes it once, with the
        kernel's own expression, into a buffer kept between colonies (one
        float64 per listed edge).
        """
        if rules.pre_add.size or rules.local_update:
            return None
        adj_ptr, adj_node, adj_edge, _, w_mul, w_add = self.adjacency(rules)
        if self.weights.size != adj_node.size:
            self.weights = np.empty(adj_node.size)
        fill_weights(self.weights, adj_node, adj_edge, w_mul, w_add, trail.x, trail.scale, trail.lo, trail.hi,
                      trail.on_nodes, rules.tau_exp)
        return self.weights

    def weights_pay(self, rules: WalkRules, n_ants: int) -> bool:
        """Whether filling the coming colony's weights first (:meth:`colony_weights`) is expected to cost less than
        weighing edges at each step.

        The expected steps are the last colony's steps per ant times
        ``n_ants``; the fill pays from :data:`FILL_STEPS_PER_NODE` steps per
        graph node. Before the first colony nothing is known, and the
        weights are filled (at most one pass over the listed edges). Either
        way the walks are the same: the choice only changes their cost.
        """
        if self.steps_per_ant < 0.0:
            return True
        per_node = FILL_STEPS_PER_NODE[rules.tau_exp == 1.0]
        return self.steps_per_ant * n_ants >= per_node * self.problem.graph.n_nodes

    def timing(self) -> tuple | None:
        """What a timed kernel of :func:`~pathzoo_aco.engine.walk_kernel.colony_kernel` reads besides the
        walk's own arguments (its clock, the moving obstacles, the fuzzy priority and their buffers), or None for
        walks that keep no time."""
        return None

    def _number_colony(self, entries: int) -> None:
        """A new number for the coming colony of :func:`~pathzoo_aco.engine.walk_kernel.local_colony`, so the
        powers it keeps start invalid."""
        if self.power_stamp.size != entries or self.colony >= 2**31 - 1:
            self.powers = np.zeros(entries)
            self.power_stamp = np.zeros(entries, dtype=np.int32)
            self.colony = 0
        self.colony += 1

    def walk(self, rules: WalkRules, trail: Pheromone, n_ants: int, seed: int,
             allowance: int = 2**62) -> Walks:
        """Send ``n_ants`` ants from the start; the trail is changed in place by local rules.

        Parameters
        ----------
        rules : WalkRules
            How ants choose and mark edges (``rules.race`` selects lock-step ants).
        trail : Pheromone
            The colony's trail.
        n_ants : int
            Ants to send.
        seed : int
            Seed of numba's generator for this colony.
        allowance : int
            Stop (and mark the walks still going :data:`ABORTED`) once this
            many steps have been taken in this call.
        """
        p = self.problem
        if not rules.race:  # a byte per node (a quarter of the cache footprint of int32), int32 for > 255 ants
            dtype, largest = (np.uint8, 255) if n_ants <= 255 else (np.int32, 2**31 - 1)
            if self.stamps.dtype != dtype:
                self.stamps = np.zeros_like(self.stamps, dtype=dtype)
                self.walk_base = 1
            if self.walk_base + n_ants > largest + 1:  # the walk ids would overflow: start afresh
                self.stamps[:] = 0
                self.walk_base = 1
        if rules.race and len(self.race_stamps) < n_ants:
            self.race_stamps = np.zeros((n_ants, p.n_nodes), dtype=np.uint8)
            self.race_colony = 1
        if rules.race:  # a stack row per ant, grown when one outgrows it: int32 edge ids, headings only if turns count
            stacks = np.zeros((n_ants, 256), dtype=np.int32 if p.graph.n_edges < 2**31 else np.int64)
            prevs = np.zeros((n_ants, 256 if rules.turn.size else 1), dtype=np.int64)
        else:
            stacks, prevs = self.stack_e, self.stack_prev
        depth = np.zeros(n_ants, dtype=np.int64)
        steps = np.zeros(n_ants, dtype=np.int64)
        flags = np.empty(n_ants, dtype=np.int8)
        flags.fill(FRESH)
        counters = np.zeros(4, dtype=np.int64)
        offsets = np.zeros(n_ants + 1, dtype=np.int64)
        adjacency = self.adjacency(rules)
        weights = self.colony_weights(rules, trail) if self.weights_pay(rules, n_ants) else None
        general = rules.race or rules.pre_add.size > 0  # racing ants or pre-choice additions
        if self.lists[0] is not adjacency:  # the same lists serve every colony of a run
            self.lists = (adjacency, unsigned_lists(p, self.indices, adjacency))
        cur = np.zeros(n_ants, dtype=np.int64)
        prev = np.zeros(n_ants, dtype=np.int64)
        timing = self.timing()
        if weights is None and not general and rules.tau_exp != 1.0 and timing is None:  # see colony_kernel
            self._number_colony(trail.x.size)  # powers are kept only for another exponent, and not by timed ants
        kernel = KERNELS[weights is None, general, timing is not None]
        rest = (p.horizontal_offsets, rules.turn, trail.x, trail.scale, trail.lo, trail.hi, trail.on_nodes,
                rules.tau_exp, rules.q0, rules.local_keep, rules.local_add, rules.pre_add, self.powers,
                self.power_stamp, self.colony, p.start, p.goal, rules.backtrack, rules.max_steps, allowance, rules.race,
                self.race_colony if rules.race else self.walk_base, self.race_stamps if rules.race else self.stamps)
        if not self.both_kernels and timing is None:  # see :attr:`both_kernels` (timed walks have one kernel)
            KERNELS[weights is not None, general, False](*self.lists[1], None if weights is not None else self.weights,
                                                         *rest, stacks, prevs, self.cand_w, cur, depth, prev, steps,
                                                         flags[:0], np.zeros(4, dtype=np.int64), self.flat, offsets,
                                                         None)
            self.both_kernels = True
        _seed(seed)
        while True:  # the stacks are grown below: passed anew each time
            status = kernel(*self.lists[1], weights, *rest, stacks, prevs, self.cand_w, cur, depth, prev, steps,
                            flags, counters, self.flat, offsets, timing)
            if status == DONE:
                break
            if counters[3]:  # a finished walk needs room in ``flat``
                need = int(offsets[counters[0]] + depth[counters[0]])
                self.flat = np.concatenate([self.flat, np.zeros(max(self.flat.size, need), dtype=np.int64)])
            else:  # a race walk outgrew the stacks: every row doubles (the kernel resumes with the same ant)
                stacks = _grown(stacks, depth)
                if rules.turn.size:
                    prevs = _grown(prevs, depth)
        if rules.race:  # a byte per node and ant: the stamps are cleared once every 255 colonies
            self.race_colony += 1
            if self.race_colony > 255:
                self.race_stamps[:] = 0
                self.race_colony = 1
        else:
            self.walk_base += n_ants
        self.total_steps += int(counters[2])
        self.steps_per_ant = int(counters[2]) / n_ants if n_ants else self.steps_per_ant
        if rules.race:
            lengths = np.where(flags == REACHED, depth, 0)
            offsets = np.concatenate([[0], np.cumsum(lengths)])
            flat = np.concatenate([stacks[a, : lengths[a]] for a in range(n_ants)] + [np.zeros(0, np.int64)],
                                  dtype=np.int64)
        else:
            flat = self.flat[: int(offsets[-1])].copy()
        return Walks(flat, offsets, flags, steps, int(counters[1]))
