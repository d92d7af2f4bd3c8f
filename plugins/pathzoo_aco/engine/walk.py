"""The colony's walks: one compiled kernel that moves every ant of an iteration from start to goal.

Each ant keeps a tabu list (a per-walk stamp on every node it has entered), so
its walk is a simple path and never needs loop removal. At a dead end (no
allowed neighbour) it either steps back along its walk, the dead end staying
tabu, or is dropped (:attr:`WalkRules.backtrack`). A walk that backtracks to
the start with nothing left has searched the start's whole component: without
a turn rule that proves the goal unreachable.

Random numbers come from numba's generator, seeded from the planner's
``rng`` at every iteration, so one seed gives one path.
"""

from __future__ import annotations

from dataclasses import dataclass

import numba
import numpy as np

from pathzoo_aco.engine.pheromone import Pheromone
from pathzoo_aco.engine.problem import ColonyProblem
from pathzoo_aco.engine.rules import WalkRules

__all__ = ["Walks", "WalkEngine", "REACHED", "STUCK", "STEP_CAP", "EXHAUSTED", "ABORTED"]

REACHED, STUCK, STEP_CAP, EXHAUSTED, ABORTED = 0, 1, 2, 3, 4
"""Walk outcomes: reached the goal; dead end without backtracking; step cap;
backtracked to an empty walk (component exhausted); stopped by the time
budget or never started."""

_DONE, _NEED_SPACE = 0, 1


@numba.njit(cache=True)
def _seed(seed):
    np.random.seed(seed)


@numba.njit(cache=True)
def _trail(x, scale, lo, hi, k):
    return min(max(scale * x[k], lo), hi)


@numba.njit(cache=True)
def _walk(indptr, indices, offset_id, horizontal, turn,
          x, scale, lo, hi, on_nodes,
          tau_exp, w_mul, w_add, q0, local_keep, local_add, pre_add,
          start, goal, backtrack, max_steps, allowance,
          first_ant, n_ants, pending, walk_base,
          stamp, stack_e, stack_prev, cand_e, cand_w,
          flat, offsets, flags, steps_out, total):
    use_turn = turn.shape[0] > 0
    no_prev = turn.shape[0] - 1
    has_add = w_add.size > 0
    has_pre = pre_add.size > 0
    do_local = local_keep != 1.0 or local_add != 0.0
    bounded = lo > 0.0 or hi < np.inf
    alpha_one = tau_exp == 1.0
    lo_pow = lo**tau_exp
    a = first_ant
    if pending >= 0:  # the previous call stopped to grow ``flat`` after this ant reached the goal
        base = offsets[a]
        for p in range(pending):
            flat[base + p] = stack_e[p]
        offsets[a + 1] = base + pending
        a += 1
    while a < n_ants:
        wid = walk_base + a
        cur = start
        depth = 0
        prev = no_prev
        steps = 0
        flag = REACHED
        stamp[start] = wid
        while cur != goal:
            if steps >= max_steps:
                flag = STEP_CAP
                break
            if total >= allowance:
                flag = ABORTED
                break
            e0 = indptr[cur]
            e1 = indptr[cur + 1]
            nc = 0
            total_w = 0.0
            for e in range(e0, e1):
                j = indices[e]
                k = j if on_nodes else e
                t = scale * x[k]
                if bounded:
                    t = min(max(t, lo), hi)
                if has_pre:  # added to every edge leaving the cell, before the choice
                    t = min(max(t + pre_add[e], lo), hi)
                    x[k] = t / scale
                if stamp[j] == wid:
                    continue
                f = 1.0
                if use_turn:
                    f = turn[prev, offset_id[e]]
                    if f <= 0.0:
                        continue
                if alpha_one:
                    w = t * w_mul[e]
                elif t <= lo:  # trails resting on the floor share one power
                    w = lo_pow * w_mul[e]
                else:
                    w = t**tau_exp * w_mul[e]
                if has_add:
                    w += w_add[e]
                if use_turn:
                    w *= f
                if w > 0.0:
                    cand_e[nc] = e
                    cand_w[nc] = w
                    total_w += w
                    nc += 1
            if nc == 0:  # maybe every trail is 0: weigh the allowed edges by the heuristic alone
                for e in range(e0, e1):
                    if stamp[indices[e]] == wid:
                        continue
                    f = turn[prev, offset_id[e]] if use_turn else 1.0
                    w = f * (w_mul[e] + (w_add[e] if has_add else 0.0))
                    if w > 0.0:
                        cand_e[nc] = e
                        cand_w[nc] = w
                        total_w += w
                        nc += 1
            if nc == 0:  # dead end
                if not backtrack:
                    flag = STUCK
                    break
                if depth == 0:
                    flag = EXHAUSTED
                    break
                depth -= 1
                cur = indices[stack_e[depth - 1]] if depth > 0 else start
                if use_turn:
                    prev = stack_prev[depth - 1] if depth > 0 else no_prev
                steps += 1
                total += 1
                continue
            sel = cand_e[nc - 1]
            if q0 > 0.0 and np.random.random() < q0:
                best = -1.0
                for c in range(nc):
                    if cand_w[c] > best:
                        best = cand_w[c]
                        sel = cand_e[c]
            else:
                r = np.random.random() * total_w
                acc = 0.0
                for c in range(nc):
                    acc += cand_w[c]
                    if r < acc:
                        sel = cand_e[c]
                        break
            cur = indices[sel]
            stamp[cur] = wid
            stack_e[depth] = sel
            if use_turn:
                o = offset_id[sel]
                if horizontal[o]:
                    prev = o
                stack_prev[depth] = prev
            depth += 1
            if do_local:
                k = cur if on_nodes else sel
                t = local_keep * _trail(x, scale, lo, hi, k) + local_add
                x[k] = min(max(t, lo), hi) / scale
            steps += 1
            total += 1
        flags[a] = flag
        steps_out[a] = steps
        base = offsets[a]
        if flag == REACHED:
            if base + depth > flat.size:
                return _NEED_SPACE, a, total, depth
            for p in range(depth):
                flat[base + p] = stack_e[p]
            offsets[a + 1] = base + depth
        else:
            offsets[a + 1] = base
        a += 1
        if flag == ABORTED or (flag == EXHAUSTED and not use_turn):
            break
    for b in range(a, n_ants):  # never started
        flags[b] = ABORTED
        steps_out[b] = 0
        offsets[b + 1] = offsets[a]
    return _DONE, a, total, -1


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
        Outcome per walk (:data:`REACHED`, :data:`STUCK`, :data:`STEP_CAP`, :data:`EXHAUSTED`, :data:`ABORTED`).
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
        cum = np.concatenate([[0.0], np.cumsum(per_edge[self.flat])])
        out = cum[self.offsets[1:]] - cum[self.offsets[:-1]]
        return np.where(self.reached, out, np.inf)


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
        self.stamp = np.full(g.n_nodes, -1, dtype=np.int32)
        self.walk_base = 0
        self.stack_e = np.zeros(problem.n_free + 1, dtype=np.int64)
        self.stack_prev = np.zeros(problem.n_free + 1, dtype=np.int64)
        kmax = int(g.degree.max()) if g.n_nodes else 0
        self.cand_e = np.zeros(max(kmax, 1), dtype=np.int64)
        self.cand_w = np.zeros(max(kmax, 1))
        self.flat = np.zeros(1024, dtype=np.int64)
        self.offset_id = g.offset_id.astype(np.int32)
        self.indices = g.indices.astype(np.int32)  # half the memory traffic of the int64 CSR arrays
        self.total_steps = 0

    def walk(self, rules: WalkRules, trail: Pheromone, n_ants: int, seed: int,
             allowance: int = 2**62) -> Walks:
        """Send ``n_ants`` ants from the start; the trail is changed in place by local rules.

        Parameters
        ----------
        rules : WalkRules
            How ants choose and mark edges.
        trail : Pheromone
            The colony's trail.
        n_ants : int
            Ants to send.
        seed : int
            Seed of numba's generator for this colony.
        allowance : int
            Stop (and mark the current walk :data:`ABORTED`) once this many
            steps have been taken in this call.
        """
        p = self.problem
        g = p.graph
        offsets = np.zeros(n_ants + 1, dtype=np.int64)
        flags = np.zeros(n_ants, dtype=np.int8)
        steps = np.zeros(n_ants, dtype=np.int64)
        if self.walk_base + n_ants >= 2**31 - 1:  # the int32 walk stamps would overflow: start afresh
            self.stamp[:] = -1
            self.walk_base = 0
        _seed(seed)
        first, pending, total = 0, -1, 0
        while True:
            status, first, total, pending = _walk(
                g.indptr, self.indices, self.offset_id, p.horizontal_offsets, rules.turn,
                trail.x, trail.scale, trail.lo, trail.hi, trail.on_nodes,
                rules.tau_exp, rules.weight_mul, rules.weight_add, rules.q0, rules.local_keep, rules.local_add,
                rules.pre_add, p.start, p.goal, rules.backtrack, rules.max_steps, allowance,
                first, n_ants, pending, self.walk_base,
                self.stamp, self.stack_e, self.stack_prev, self.cand_e, self.cand_w,
                self.flat, offsets, flags, steps, total,
            )
            if status == _DONE:
                break
            grown = np.zeros(max(2 * self.flat.size, int(offsets[first]) + pending), dtype=np.int64)
            grown[: self.flat.size] = self.flat
            self.flat = grown
        self.walk_base += n_ants
        self.total_steps += int(total)
        used = int(offsets[-1])
        return Walks(self.flat[:used].copy(), offsets, flags, steps, int(first))
