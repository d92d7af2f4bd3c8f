"""The colony's walks: one compiled kernel that moves every ant of an iteration from start to goal.

Each ant keeps a tabu list (a per-walk stamp on every node it has entered), so
its walk is a simple path and never needs loop removal. At a dead end (no
allowed neighbour) it either steps back along its walk, the dead end staying
tabu, or is dropped (:attr:`WalkRules.backtrack`). A walk that backtracks to
the start with nothing left has searched the start's whole component: without
a turn rule that proves the goal unreachable.

Ants walk one after another (each to the goal or until it stops), or, when
:attr:`WalkRules.race` is set, in lock step (one step each per round) until
the first of them reaches the goal; the others are then marked :data:`OUTRUN`.

Random numbers come from numba's generator, seeded from the planner's
``rng`` at every iteration, so one seed gives one path.
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np

from pathzoo_aco.engine.outcomes import (ABORTED, DONE, EXHAUSTED, FRESH, NEED_SPACE, OUTRUN, REACHED, RUNNING,
                                         STEP_CAP, STUCK, stop_before_step)
from pathzoo_aco.engine.pheromone import Pheromone
from pathzoo_aco.engine.prefetch import AHEAD, prefetch
from pathzoo_aco.engine.problem import ColonyProblem
from pathzoo_aco.engine.rules import WalkRules
from pathzoo_aco.engine.walk_sequential import Adjacency, choose, local_colony, unsigned_lists, weighted_colony

__all__ = ["Walks", "WalkEngine", "REACHED", "STUCK", "STEP_CAP", "EXHAUSTED", "ABORTED", "OUTRUN"]


@numba.njit(cache=True)
def _seed(seed):
    np.random.seed(seed)


@numba.njit(cache=True, inline="always")
def _trail_weight(t, mul, tau_exp, lo, lo_pow):
    """``t ** tau_exp * mul`` for a trail value ``t`` already within its bounds (``lo_pow`` is ``lo ** tau_exp``)."""
    if tau_exp == 1.0:
        return t * mul
    if t <= lo:  # trails resting on the floor share one power
        return lo_pow * mul
    return t**tau_exp * mul


@numba.njit(cache=True, inline="always")
def _add_candidate(e, w, cand_e, cand_w, nc, total_w):
    """Append edge ``e`` of weight ``w`` to the candidates if ``w > 0``; return the new count and total."""
    if w > 0.0:
        cand_e[nc] = e
        cand_w[nc] = w
        return nc + 1, total_w + w
    return nc, total_w


@numba.njit(cache=True)
def _colony(indices, offset_id, adj_ptr, adj_node, adj_edge, adj_offset, w_mul, w_add, weights, horizontal, turn,
            x, scale, lo, hi, on_nodes,
            tau_exp, q0, local_keep, local_add, pre_add,
            start, goal, backtrack, max_steps, allowance, race, walk_base,
            stamps, stacks, prevs, cand_e, cand_w,
            cur, depth, prev, steps, flags, counters, flat, offsets):
    """Move the colony's ants; return ``DONE`` or ``NEED_SPACE`` (grow ``stacks`` or ``flat``, call again).

    One after another (``race`` False: an ant walks until it stops, then the
    next starts; one stamp row and one stack row serve them all), or in lock
    step (``race`` True: one step per ant per round, a stamp and stack row
    per ant, until the first reaches the goal; every ant stamps its own row
    with ``walk_base``, which may then be a byte). All state lives in the
    arrays; ``counters`` holds (next ant, ants started, steps taken, a
    finished walk waiting for room in ``flat``), so a call resumes where the
    previous one stopped.

    ``indices`` and ``offset_id`` are the graph's per-edge target node and
    move; ``adj_ptr``/``adj_node`` list, per node, the edges an ant may ever
    take and their targets (CSR), ``adj_offset``, ``w_mul``, ``w_add`` their
    moves and weights in the same order (:meth:`WalkEngine.adjacency`).
    Position ``q`` of that list is graph edge ``adj_edge[q]`` (edges of
    weight 0 left out), or edge ``q`` when ``adj_edge`` is None (numba then
    compiles the kernel without the lookup). ``weights``, when not None,
    holds each position's weight before the turn factor, filled by
    :func:`_fill_weights` for a trail that no ant changes while it walks.
    """
    n_ants = flags.size
    use_turn = turn.shape[0] > 0
    no_prev = turn.shape[0] - 1
    has_add = w_add.size > 0
    has_pre = pre_add.size > 0
    do_local = local_keep != 1.0 or local_add != 0.0
    bounded = lo > 0.0 or hi < np.inf
    lo_pow = lo**tau_exp
    a = counters[0]
    total = counters[2]
    if counters[3] > 0:  # copy the walk that waited for room in ``flat``
        base = offsets[a]
        for p in range(depth[a]):
            flat[base + p] = stacks[0, p]
        offsets[a + 1] = base + depth[a]
        counters[3] = 0
        a += 1
    while True:
        if a >= n_ants:
            if not race:
                break
            a = 0
            running = False
            for b in range(n_ants):
                running = running or flags[b] == RUNNING
            if not running:
                break
        if flags[a] >= 0:  # a race walk that has stopped
            a += 1
            continue
        row = a if race else 0
        stamp = stamps[row]
        stack_e = stacks[row]
        stack_prev = prevs[row]
        wid = walk_base if race else walk_base + a  # racing ants have a stamp row each
        if flags[a] == FRESH:
            flags[a] = RUNNING
            counters[1] += 1
            cur[a] = start
            depth[a] = 0
            prev[a] = no_prev
            steps[a] = 0
            stamp[start] = wid
        c = cur[a]
        d = depth[a]
        pv = prev[a]
        n = steps[a]
        flag = RUNNING
        full = False  # stopped before a step for want of room on the stack (not after a race step that filled it)
        while True:
            flag = stop_before_step(c, goal, n, max_steps, total, allowance)
            if flag != RUNNING:
                break
            if d >= stack_e.size:
                full = True
                break  # no room on the stack: the caller grows it
            # ---------------------------------------------------------- one step
            e0 = adj_ptr[c]
            e1 = adj_ptr[c + 1]
            nc = 0
            n_open = 0  # allowed neighbours, whatever their weight
            total_w = 0.0
            for q in range(e0, e1):
                if adj_edge is None:  # pruned at compile time: one specialisation per case
                    e = q
                else:
                    e = adj_edge[q]
                j = adj_node[q]
                if weights is not None:  # the colony's weights, computed before it started
                    if stamp[j] == wid:
                        continue
                    f = 1.0
                    if use_turn:
                        f = turn[pv, adj_offset[q]]
                        if f <= 0.0:
                            continue
                    n_open += 1
                    nc, total_w = _add_candidate(e, weights[q] * f if use_turn else weights[q], cand_e, cand_w, nc,
                                                 total_w)
                    continue
                k = j if on_nodes else e
                if has_pre:  # added to every edge leaving the cell, tabu or not, before the choice
                    t = min(max(min(max(scale * x[k], lo), hi) + pre_add[q], lo), hi)
                    x[k] = t / scale
                    if stamp[j] == wid:
                        continue
                elif stamp[j] == wid:  # most neighbours on a long walk: test before touching the trail
                    continue
                f = 1.0
                if use_turn:  # the turn table is small: test it before reading the trail too
                    f = turn[pv, adj_offset[q]]
                    if f <= 0.0:
                        continue
                if not has_pre:
                    t = scale * x[k]
                    if bounded:
                        t = min(max(t, lo), hi)
                n_open += 1
                w = _trail_weight(t, w_mul[q], tau_exp, lo, lo_pow)
                if has_add:
                    w += w_add[q]
                if use_turn:
                    w *= f
                nc, total_w = _add_candidate(e, w, cand_e, cand_w, nc, total_w)
            if nc == 0 and n_open > 0:  # maybe every trail is 0: weigh the allowed edges by the heuristic alone
                for q in range(e0, e1):
                    if stamp[adj_node[q]] == wid:
                        continue
                    f = turn[pv, adj_offset[q]] if use_turn else 1.0
                    w = f * (w_mul[q] + (w_add[q] if has_add else 0.0))
                    if w > 0.0:
                        if adj_edge is None:
                            cand_e[nc] = q
                        else:
                            cand_e[nc] = adj_edge[q]
                        cand_w[nc] = w
                        total_w += w
                        nc += 1
            if nc == 0:  # dead end
                if not backtrack:
                    flag = STUCK
                    break
                if d == 0:
                    flag = EXHAUSTED
                    break
                d -= 1
                c = indices[stack_e[d - 1]] if d > 0 else start
                if use_turn:
                    pv = stack_prev[d - 1] if d > 0 else no_prev
            else:
                sel = cand_e[choose(cand_w, nc, total_w, q0)]
                c = indices[sel]
                stamp[c] = wid
                stack_e[d] = sel
                if use_turn:
                    o = offset_id[sel]
                    if horizontal[o]:
                        pv = o
                    stack_prev[d] = pv
                d += 1
                if do_local:
                    k = c if on_nodes else sel
                    t = local_keep * min(max(scale * x[k], lo), hi) + local_add
                    x[k] = min(max(t, lo), hi) / scale
            n += 1
            total += 1
            if race:
                if c == goal:
                    flag = REACHED
                break
        cur[a] = c
        depth[a] = d
        prev[a] = pv
        steps[a] = n
        counters[2] = total
        if full:  # resume with this ant, which has not stepped yet (a racing ant's step waits until then)
            counters[0] = a
            return NEED_SPACE
        if flag == RUNNING:  # a race ant that took its step
            a += 1
            continue
        flags[a] = flag
        stop = flag == ABORTED or (flag == EXHAUSTED and not use_turn) or (race and flag == REACHED)
        if not race:
            if flag == REACHED:
                if offsets[a] + d > flat.size:
                    counters[0] = a
                    counters[3] = 1
                    return NEED_SPACE
                for p in range(d):
                    flat[offsets[a] + p] = stack_e[p]
            offsets[a + 1] = offsets[a] + (d if flag == REACHED else 0)
        if stop:
            for b in range(n_ants):  # the others: never started, stopped, or outrun in a race
                if flags[b] == FRESH or (flags[b] == RUNNING and flag != REACHED):
                    flags[b] = ABORTED
                elif flags[b] == RUNNING:
                    flags[b] = OUTRUN
                if not race and b > a:
                    offsets[b + 1] = offsets[a + 1]
            break
        a += 1
    counters[0] = a
    return DONE


@numba.njit(cache=True)
def _fill_weights(out, adj_node, adj_edge, w_mul, w_add, x, scale, lo, hi, on_nodes, tau_exp):
    """Each listed edge's weight ``τ ** tau_exp * w_mul (+ w_add)`` into ``out``, as :func:`_colony` computes it.

    The same operations in the same order, so the doubles are identical; the
    walks of a colony whose trail does not change while it walks (no
    ``pre_add``, no local update) then read one array per edge instead of the
    trail, both factors and a power.
    """
    has_add = w_add.size > 0
    bounded = lo > 0.0 or hi < np.inf
    lo_pow = lo**tau_exp
    for q in range(out.size):
        if adj_edge is None:
            e = q
        else:
            e = adj_edge[q]
        k = adj_node[q] if on_nodes else e
        t = scale * x[k]
        if bounded:
            t = min(max(t, lo), hi)
        w = _trail_weight(t, w_mul[q], tau_exp, lo, lo_pow)
        if has_add:
            w += w_add[q]
        out[q] = w


@dataclass(frozen=True, eq=False)
class Walks:
    """The walks of one iteration.

    Attributes
    ----------
    flat : ndarray of int64
        Edge ids of every walk that reached the goal, concatenated.
    offsets : ndarray of int64, shape (n + 1,)
        Walk ``a`` is ``flat[offsets[a]:offsets[a + 1]]`` (empty unless it reached the goal).
    flags : ndarray of int8, shape (n,)
        Outcome per walk (:data:`REACHED`, :data:`STUCK`, :data:`STEP_CAP`, :data:`EXHAUSTED`,
        :data:`ABORTED`, :data:`OUTRUN`).
    steps : ndarray of int64, shape (n,)
        Steps each ant took, backtracking moves included.
    started : int
        Walks actually started (the evaluation count).
    """

    flat: np.ndarray
    offsets: np.ndarray
    flags: np.ndarray
    steps: np.ndarray
    started: int

    @property
    def reached(self) -> np.ndarray:
        """Boolean mask of the walks that reached the goal."""
        return self.flags == REACHED

    @property
    def exhausted(self) -> bool:
        """True when some ant searched the start's whole component without reaching the goal."""
        return bool(np.any(self.flags == EXHAUSTED))

    def edges(self, ant: int) -> np.ndarray:
        """Edge ids of one walk."""
        return self.flat[self.offsets[ant] : self.offsets[ant + 1]]

    def totals(self, per_edge: np.ndarray) -> np.ndarray:
        """Sum of a per-edge quantity over each walk; ``inf`` for walks that did not reach the goal."""
        out = _walk_sums(np.asarray(per_edge, dtype=np.float64), self.flat, self.offsets, True)
        return np.where(self.reached, out, np.inf)

    def sums(self, per_step: np.ndarray) -> np.ndarray:
        """As :meth:`totals`, from values given per entry of :attr:`flat` (computed for the walked edges only)."""
        out = _walk_sums(np.asarray(per_step, dtype=np.float64), self.flat, self.offsets, False)
        return np.where(self.reached, out, np.inf)


@numba.njit(cache=True)
def _walk_sums(values, flat, offsets, by_edge):
    """Per walk, the difference of one running sum over all walks at its two ends.

    The running sum is taken entry by entry in ``flat`` order (of
    ``values[flat[p]]`` when ``by_edge``, else of ``values[p]``), exactly as
    ``np.cumsum`` does, so the results equal ``cum[end] - cum[start]`` of it.
    """
    n = offsets.size - 1
    out = np.empty(n)
    acc = 0.0
    p = 0
    start = 0.0
    last = offsets[n] - 1
    for a in range(n):
        while p < offsets[a]:
            acc += values[flat[p]] if by_edge else values[p]
            p += 1
        start = acc
        while p < offsets[a + 1]:
            if by_edge:  # the walk's edges follow no stride: ask for the value a few edges ahead
                prefetch(values, flat[min(p + AHEAD, last)])
            acc += values[flat[p]] if by_edge else values[p]
            p += 1
        out[a] = acc - start
    return out


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
        self.cand_e = np.zeros(max(kmax, 1), dtype=np.int64)
        self.cand_w = np.zeros(max(kmax, 1))
        self.flat = np.zeros(1024, dtype=np.int64)
        self.offset_id = problem.offset_id_small  # moves: compact
        self.indices = problem.indices32  # half the memory traffic of the int64 CSR arrays
        self.weights = np.zeros(0)  # per-colony weights of the listed edges (see :func:`_fill_weights`)
        self.powers = np.zeros(0)  # trail powers kept by :func:`local_colony`, valid where stamped with the colony
        self.power_stamp = np.zeros(0, dtype=np.int32)
        self.colony = 0
        self.lists: tuple = (None, ())  # an adjacency and its lists as the specialised kernels read them
        self.total_steps = 0

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
        the colony, and :func:`_fill_weights` computes it once, with the
        kernel's own expression, into a buffer kept between colonies (one
        float64 per listed edge).
        """
        if rules.pre_add.size or rules.local_update:
            return None
        adj_ptr, adj_node, adj_edge, _, w_mul, w_add = self.adjacency(rules)
        if self.weights.size != adj_node.size:
            self.weights = np.empty(adj_node.size)
        _fill_weights(self.weights, adj_node, adj_edge, w_mul, w_add, trail.x, trail.scale, trail.lo, trail.hi,
                      trail.on_nodes, rules.tau_exp)
        return self.weights

    def _number_colony(self, entries: int) -> None:
        """A new number for the coming colony of :func:`local_colony`, so the powers it keeps start invalid."""
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
        weights = self.colony_weights(rules, trail)
        weighted = weights is not None and not rules.race  # the common case (walk_sequential.py)
        local = weights is None and not rules.race and rules.pre_add.size == 0  # local updates (walk_sequential.py)
        if weighted or local:
            if self.lists[0] is not adjacency:  # the same lists serve every colony of a run
                self.lists = (adjacency, unsigned_lists(p, self.indices, adjacency))
            lists = self.lists[1]
        else:  # the generic kernel keeps each ant's node and heading between calls
            cur = np.zeros(n_ants, dtype=np.int64)
            prev = np.zeros(n_ants, dtype=np.int64)
        if local and rules.tau_exp != 1.0:  # powers are kept only for another exponent than 1
            self._number_colony(trail.x.size)
        _seed(seed)
        while True:
            if weighted or local:
                status = (weighted_colony if weighted else local_colony)(
                    *lists, weights, p.horizontal_offsets, rules.turn, trail.x, trail.scale, trail.lo, trail.hi,
                    trail.on_nodes, rules.tau_exp, rules.q0, rules.local_keep, rules.local_add,
                    self.powers, self.power_stamp, self.colony,
                    p.start, p.goal, rules.backtrack, rules.max_steps, allowance, self.walk_base,
                    self.stamps[0], stacks[0], prevs[0], self.cand_w, depth, steps, flags, counters,
                    self.flat, offsets,
                )
            else:
                status = _colony(
                    self.indices, self.offset_id, *adjacency, weights, p.horizontal_offsets, rules.turn,
                    trail.x, trail.scale, trail.lo, trail.hi, trail.on_nodes,
                    rules.tau_exp, rules.q0, rules.local_keep, rules.local_add,
                    rules.pre_add, p.start, p.goal, rules.backtrack, rules.max_steps, allowance, rules.race,
                    self.race_colony if rules.race else self.walk_base, self.race_stamps if rules.race else self.stamps,
                    stacks, prevs, self.cand_e, self.cand_w,
                    cur, depth, prev, steps, flags, counters, self.flat, offsets,
                )
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
        if rules.race:
            lengths = np.where(flags == REACHED, depth, 0)
            offsets = np.concatenate([[0], np.cumsum(lengths)])
            flat = np.concatenate([stacks[a, : lengths[a]] for a in range(n_ants)] + [np.zeros(0, np.int64)],
                                  dtype=np.int64)
        else:
            flat = self.flat[: int(offsets[-1])].copy()
        return Walks(flat, offsets, flags, steps, int(counters[1]))
