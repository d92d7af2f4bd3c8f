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

from pathzoo_aco.engine.pheromone import Pheromone
from pathzoo_aco.engine.problem import ColonyProblem
from pathzoo_aco.engine.rules import WalkRules

__all__ = ["Walks", "WalkEngine", "REACHED", "STUCK", "STEP_CAP", "EXHAUSTED", "ABORTED", "OUTRUN"]

REACHED, STUCK, STEP_CAP, EXHAUSTED, ABORTED = 0, 1, 2, 3, 4
"""Walk outcomes: reached the goal; dead end without backtracking; step cap;
backtracked to an empty walk (component exhausted); stopped by the time
budget or never started."""

_DONE, _NEED_SPACE = 0, 1


@numba.njit(cache=True)
def _seed(seed):
    np.random.seed(seed)


_MOVED, _BACKED = -1, -2
"""Outcomes of one step besides the walk outcomes: moved forward, stepped back."""

_RUNNING, OUTRUN = -1, 5
"""Race walks: still walking; stopped because another ant reached the goal first."""


@numba.njit(cache=True, inline="always")
def _step(indptr, indices, offset_id, horizontal, turn, x, scale, lo, hi, on_nodes,
          tau_exp, lo_pow, w_mul, w_add, q0, local_keep, local_add, pre_add, backtrack,
          start, stamp, wid, stack_e, stack_prev, cand_e, cand_w, cur, depth, prev):
    """Move one ant one step; return ``(outcome, cur, depth, prev)``.

    ``outcome`` is ``_MOVED``, ``_BACKED``, ``STUCK`` (dead end, no
    backtracking) or ``EXHAUSTED`` (backtracked to the start with nothing left).
    """
    use_turn = turn.shape[0] > 0
    has_add = w_add.size > 0
    has_pre = pre_add.size > 0
    bounded = lo > 0.0 or hi < np.inf
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
        if tau_exp == 1.0:
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
            return STUCK, cur, depth, prev
        if depth == 0:
            return EXHAUSTED, cur, depth, prev
        depth -= 1
        cur = indices[stack_e[depth - 1]] if depth > 0 else start
        if use_turn:
            prev = stack_prev[depth - 1] if depth > 0 else turn.shape[0] - 1
        return _BACKED, cur, depth, prev
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
    if local_keep != 1.0 or local_add != 0.0:
        k = cur if on_nodes else sel
        t = local_keep * min(max(scale * x[k], lo), hi) + local_add
        x[k] = min(max(t, lo), hi) / scale
    return _MOVED, cur, depth, prev


@numba.njit(cache=True)
def _walk(indptr, indices, offset_id, horizontal, turn,
          x, scale, lo, hi, on_nodes,
          tau_exp, w_mul, w_add, q0, local_keep, local_add, pre_add,
          start, goal, backtrack, max_steps, allowance,
          first_ant, n_ants, pending, walk_base,
          stamp, stack_e, stack_prev, cand_e, cand_w,
          flat, offsets, flags, steps_out, total):
    """Ants one after another, each from the start until it reaches the goal or stops."""
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
        prev = turn.shape[0] - 1
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
            out, cur, depth, prev = _step(indptr, indices, offset_id, horizontal, turn, x, scale, lo, hi,
                                          on_nodes, tau_exp, lo_pow, w_mul, w_add, q0, local_keep, local_add,
                                          pre_add, backtrack, start, stamp, wid, stack_e, stack_prev, cand_e,
                                          cand_w, cur, depth, prev)
            if out >= 0:
                flag = out
                break
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
        if flag == ABORTED or (flag == EXHAUSTED and turn.shape[0] == 0):
            break
    for b in range(a, n_ants):  # never started
        flags[b] = ABORTED
        steps_out[b] = 0
        offsets[b + 1] = offsets[a]
    return _DONE, a, total, -1


@numba.njit(cache=True)
def _race(indptr, indices, offset_id, horizontal, turn,
          x, scale, lo, hi, on_nodes,
          tau_exp, w_mul, w_add, q0, local_keep, local_add, pre_add,
          start, goal, backtrack, max_steps, allowance, next_ant, walk_base,
          stamps, stacks, prevs, cand_e, cand_w, cur, depth, prev, steps, flags, total):
    """Ants in lock step, one step each per round, until the first one reaches the goal.

    All state lives in the arrays, so a call that returns ``_NEED_SPACE``
    (an ant's walk outgrew ``stacks``) resumes where it stopped.
    """
    lo_pow = lo**tau_exp
    n_ants = flags.size
    a = next_ant
    while True:
        while a < n_ants:
            if flags[a] == _RUNNING:
                if steps[a] >= max_steps:
                    flags[a] = STEP_CAP
                elif total >= allowance:
                    for b in range(n_ants):
                        if flags[b] == _RUNNING:
                            flags[b] = ABORTED
                    return _DONE, a, total
                elif depth[a] >= stacks.shape[1]:
                    return _NEED_SPACE, a, total
                else:
                    out, c, d, p = _step(indptr, indices, offset_id, horizontal, turn, x, scale, lo, hi, on_nodes,
                                         tau_exp, lo_pow, w_mul, w_add, q0, local_keep, local_add, pre_add,
                                         backtrack, start, stamps[a], walk_base + a, stacks[a], prevs[a], cand_e,
                                         cand_w, cur[a], depth[a], prev[a])
                    cur[a], depth[a], prev[a] = c, d, p
                    if out >= 0:
                        flags[a] = out
                        if out == EXHAUSTED and turn.shape[0] == 0:  # the goal is unreachable: stop them all
                            for b in range(n_ants):
                                if flags[b] == _RUNNING:
                                    flags[b] = ABORTED
                            return _DONE, a, total
                    else:
                        steps[a] += 1
                        total += 1
                        if c == goal:
                            flags[a] = REACHED
                            for b in range(n_ants):
                                if flags[b] == _RUNNING:
                                    flags[b] = OUTRUN
                            return _DONE, a, total
            a += 1
        a = 0
        running = False
        for b in range(n_ants):
            running = running or flags[b] == _RUNNING
        if not running:
            return _DONE, a, total


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
        self.race_stamps: np.ndarray | None = None  # one tabu stamp row per ant, made on the first race
        self.total_steps = 0

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
            Stop (and mark the current walks :data:`ABORTED`) once this many
            steps have been taken in this call.
        """
        if self.walk_base + n_ants >= 2**31 - 1:  # the int32 walk stamps would overflow: start afresh
            self.stamp[:] = -1
            if self.race_stamps is not None:
                self.race_stamps[:] = -1
            self.walk_base = 0
        _seed(seed)
        walks = (self._race if rules.race else self._one_by_one)(rules, trail, n_ants, allowance)
        self.walk_base += n_ants
        return walks

    def _args(self, rules: WalkRules, trail: Pheromone) -> tuple:
        p = self.problem
        return (p.graph.indptr, self.indices, self.offset_id, p.horizontal_offsets, rules.turn,
                trail.x, trail.scale, trail.lo, trail.hi, trail.on_nodes,
                rules.tau_exp, rules.weight_mul, rules.weight_add, rules.q0, rules.local_keep, rules.local_add,
                rules.pre_add, p.start, p.goal, rules.backtrack, rules.max_steps)

    def _one_by_one(self, rules: WalkRules, trail: Pheromone, n_ants: int, allowance: int) -> Walks:
        offsets = np.zeros(n_ants + 1, dtype=np.int64)
        flags = np.zeros(n_ants, dtype=np.int8)
        steps = np.zeros(n_ants, dtype=np.int64)
        first, pending, total = 0, -1, 0
        while True:
            status, first, total, pending = _walk(
                *self._args(rules, trail), allowance, first, n_ants, pending, self.walk_base,
                self.stamp, self.stack_e, self.stack_prev, self.cand_e, self.cand_w,
                self.flat, offsets, flags, steps, total,
            )
            if status == _DONE:
                break
            grown = np.zeros(max(2 * self.flat.size, int(offsets[first]) + pending), dtype=np.int64)
            grown[: self.flat.size] = self.flat
            self.flat = grown
        self.total_steps += int(total)
        return Walks(self.flat[: int(offsets[-1])].copy(), offsets, flags, steps, int(first))

    def _race(self, rules: WalkRules, trail: Pheromone, n_ants: int, allowance: int) -> Walks:
        p = self.problem
        if self.race_stamps is None or len(self.race_stamps) < n_ants:
            self.race_stamps = np.full((n_ants, p.n_nodes), -1, dtype=np.int32)
        stamps = self.race_stamps[:n_ants]
        ants = np.arange(n_ants)
        stamps[ants, p.start] = self.walk_base + ants
        stacks = np.zeros((n_ants, 256), dtype=np.int64)
        prevs = np.zeros_like(stacks)
        cur = np.full(n_ants, p.start, dtype=np.int64)
        depth = np.zeros(n_ants, dtype=np.int64)
        prev = np.full(n_ants, rules.turn.shape[0] - 1, dtype=np.int64)
        steps = np.zeros(n_ants, dtype=np.int64)
        flags = np.full(n_ants, _RUNNING, dtype=np.int8)
        next_ant, total = 0, 0
        while True:
            status, next_ant, total = _race(
                *self._args(rules, trail), allowance, next_ant, self.walk_base,
                stamps, stacks, prevs, self.cand_e, self.cand_w, cur, depth, prev, steps, flags, total,
            )
            if status == _DONE:
                break
            stacks = np.hstack([stacks, np.zeros_like(stacks)])
            prevs = np.hstack([prevs, np.zeros_like(prevs)])
        self.total_steps += int(total)
        lengths = np.where(flags == REACHED, depth, 0)
        offsets = np.concatenate([[0], np.cumsum(lengths)])
        flat = np.concatenate([stacks[a, : lengths[a]] for a in range(n_ants)]) if n_ants else np.zeros(0, np.int64)
        return Walks(flat.astype(np.int64), offsets, flags, steps, n_ants)
