"""The step rules every compiled walk inlines (engine/steps.py), against plain Python on small cases."""

from __future__ import annotations

import numba
import numpy as np

from pathzoo_aco.engine.steps import (choose, heaviest, heuristic_candidates, kept_candidates, local_update, read_trail,
                                      roulette, trail_power)


@numba.njit
def _draws(seed, cand_w, first, nc, total_w, q0, n):
    """``n`` picks of :func:`roulette` (``q0 < 0``) or :func:`choose` after seeding numba's generator."""
    np.random.seed(seed)
    out = np.empty(n, dtype=np.int64)
    for i in range(n):
        out[i] = roulette(cand_w, first, nc, total_w) if q0 < 0.0 else choose(cand_w, nc, total_w, q0)
    return out


@numba.njit
def _uniforms(seed, n):
    np.random.seed(seed)
    return np.array([np.random.random() for _ in range(n)])


@numba.njit
def _heaviest(cand_w, first, nc):
    return heaviest(cand_w, first, nc)


@numba.njit
def _fallback(r0, r1, node, weight_mul, weight_add, move, turn, pv, stamp, wid, cand, cand_w, first):
    return heuristic_candidates(r0, r1, node, weight_mul, weight_add, move, turn, pv, stamp, wid, cand, cand_w, first)


@numba.njit
def _kept(cand, cand_w, first, count, node, stamp, wid):
    return kept_candidates(cand, cand_w, first, count, node, stamp, wid)


@numba.njit
def _trail(scale, stored, lo, hi, bounded, tau_exp):
    return trail_power(read_trail(scale, stored, lo, hi, bounded), tau_exp, lo, lo**tau_exp)


@numba.njit
def _local(x, k, scale, lo, hi, keep, add):
    local_update(x, k, scale, lo, hi, keep, add)


def test_roulette_picks_the_first_running_sum_above_the_draw():
    w = np.array([9.0, 1.0, 2.0, 3.0, 4.0])
    first, nc = 1, 4
    total = float(w[first:first + nc].sum())
    got = _draws(5, w, first, nc, total, -1.0, 200)
    sums = np.cumsum(w[first:first + nc])
    wanted = [first + int(np.argmax(u * total < sums)) for u in _uniforms(5, 200)]
    assert got.tolist() == wanted
    assert set(got.tolist()) == {1, 2, 3, 4}  # never the entry before ``first``


def test_roulette_takes_the_last_candidate_when_rounding_leaves_the_draw_past_every_sum():
    w = np.array([1.0, 1.0])
    assert set(_draws(0, w, 0, 2, 10.0, -1.0, 50).tolist()) == {0, 1}
    assert 1 in _draws(0, w, 0, 2, 10.0, -1.0, 50).tolist()  # draws in [2, 10) fall past both sums
    assert _draws(0, w, 0, 1, 1e300, -1.0, 20).tolist() == [0] * 20


def test_heaviest_is_the_first_of_the_heaviest():
    w = np.array([5.0, 1.0, 3.0, 3.0, 2.0])
    assert _heaviest(w, 1, 4) == 2
    assert _heaviest(w, 0, 5) == 0


def test_choose_with_q0_one_is_greedy_and_with_q0_zero_is_the_roulette():
    w = np.array([1.0, 4.0, 4.0, 2.0])
    assert _draws(3, w, 0, 4, 11.0, 1.0, 30).tolist() == [1] * 30
    assert _draws(3, w, 0, 4, 11.0, 0.0, 30).tolist() == _draws(3, w, 0, 4, 11.0, -1.0, 30).tolist()


def test_heuristic_candidates_skip_stamped_nodes_forbidden_turns_and_zero_weights():
    node = np.array([10, 11, 12, 13, 14])
    weight_mul = np.array([1.0, 2.0, 0.0, 4.0, 5.0], dtype=np.float32)
    weight_add = np.array([0.5, 0.5, 0.0, 0.5, 0.5], dtype=np.float32)
    move = np.array([0, 1, 0, 1, 0])
    turn = np.array([[1.0, 0.0], [2.0, 1.0]])
    stamp = np.zeros(20, dtype=np.uint8)
    stamp[13] = 7
    cand = np.full(8, -1, dtype=np.int64)
    cand_w = np.zeros(8)
    nc, total = _fallback(0, 5, node, weight_mul, weight_add, move, turn, 0, stamp, 7, cand, cand_w, 2)
    assert (nc, total) == (2, 1.5 + 5.5)  # 11: turn 0; 12: weight 0; 13: stamped
    assert cand[2:4].tolist() == [0, 4] and cand_w[2:4].tolist() == [1.5, 5.5]
    nc, total = _fallback(0, 5, node, weight_mul, weight_add[:0], move, turn[:0], 0, stamp, 7, cand, cand_w, 0)
    assert (nc, total) == (3, 1.0 + 2.0 + 5.0) and cand[:3].tolist() == [0, 1, 4]


def test_kept_candidates_drop_the_nodes_stamped_since_in_their_order():
    node = np.array([20, 21, 22, 23])
    stamp = np.zeros(30, dtype=np.int32)
    stamp[[21, 23]] = 4
    cand = np.array([9, 0, 1, 2, 3, 9])
    cand_w = np.array([0.0, 1.0, 8.0, 2.0, 5.0, 0.0])
    nc, total, best = _kept(cand, cand_w, 1, 4, node, stamp, 4)
    assert (nc, total, best) == (2, 3.0, 2)
    assert cand[1:3].tolist() == [0, 2] and cand_w[1:3].tolist() == [1.0, 2.0]
    stamp[:] = 4
    assert _kept(cand, cand_w, 1, 2, node, stamp, 4)[:2] == (0, 0.0)


def test_trail_reads_powers_and_local_updates_stay_within_the_bounds():
    assert _trail(2.0, 3.0, 0.5, 4.0, True, 1.0) == 4.0
    assert _trail(2.0, 3.0, 0.5, 4.0, False, 1.0) == 6.0
    assert _trail(1.0, 0.1, 0.5, 4.0, True, 3.0) == 0.5**3  # on the floor: the floor's power
    assert _trail(1.0, 2.0, 0.5, 4.0, True, 3.0) == 2.0**3
    x = np.array([1.0, 3.0])
    _local(x, 1, 2.0, 0.5, 5.0, 0.5, 0.25)  # 0.5 * min(6, 5) + 0.25 = 2.75, stored over the scale
    assert x.tolist() == [1.0, 2.75 / 2.0]
