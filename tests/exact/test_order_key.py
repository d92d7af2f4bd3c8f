"""``order_key``: integer heap keys that, read as unsigned integers, compare exactly as the floats they stand for."""

from __future__ import annotations

import numpy as np
from pathzoo_exact.heap import heap_pop, heap_push, order_key


def floats(seed: int) -> np.ndarray:
    """Signed floats of every magnitude, with repeats, infinities, subnormals and +0.0 (no NaN, no -0.0)."""
    rng = np.random.default_rng(seed)
    x = np.concatenate([
        rng.normal(size=300),
        rng.normal(size=100) * 1e-310,  # subnormals
        np.sign(rng.normal(size=100)) * 10.0 ** rng.uniform(-300, 300, 100),
        np.round(rng.normal(size=200) * 4) / 4,  # many exact ties
        [0.0, 0.0, np.inf, -np.inf, np.nextafter(0.0, 1.0), -np.nextafter(0.0, 1.0), 1.0, np.nextafter(1.0, 2.0)],
    ])
    x[x == 0] = 0.0  # rounding makes some -0.0
    return rng.permutation(x)


def test_keys_compare_like_their_floats() -> None:
    x = floats(0)
    k = np.array([order_key(v) for v in x], dtype=np.int64).view(np.uint64)
    assert np.array_equal(k[:, None] < k[None, :], x[:, None] < x[None, :])
    assert np.array_equal(k[:, None] == k[None, :], x[:, None] == x[None, :])
    assert order_key(0.0) == -(1 << 63)  # what begin_batch stores for the source: the sign bit alone


def test_minus_zero_is_the_one_exception() -> None:
    # documented: -0.0 == +0.0 as floats, but its key is lower; the kernels never make a -0.0 key
    minus, plus = np.array([order_key(-0.0), order_key(0.0)], dtype=np.int64).view(np.uint64)
    assert minus < plus


def test_heap_pops_the_same_nodes_with_float_and_integer_keys() -> None:
    rng = np.random.default_rng(1)
    f = floats(2)
    g = np.round(rng.normal(size=len(f)) * 2) / 2
    g[g == 0] = 0.0
    n = len(f)
    heaps = [(np.empty(n, np.int64), np.empty(n), np.empty(n)),
             (np.empty(n, np.int64), np.empty(n, np.int64), np.empty(n, np.int64))]
    pops: list[list[int]] = [[], []]
    for which, (hn, hf, hg) in enumerate(heaps):
        size = 0
        for i in range(n):  # interleave pushes and pops so that sift-ups and sift-downs both meet ties
            fi, gi = (f[i], g[i]) if which == 0 else (order_key(f[i]), order_key(g[i]))
            size = heap_push(hn, hf, hg, size, i, fi, gi)
            if i % 3 == 2:
                pops[which].append(heap_pop(hn, hf, hg, size))
                size -= 1
        while size:
            pops[which].append(heap_pop(hn, hf, hg, size))
            size -= 1
    assert pops[0] == pops[1]
    assert sorted(pops[0]) == list(range(n))
