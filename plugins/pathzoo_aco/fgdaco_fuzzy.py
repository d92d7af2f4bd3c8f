"""FGDACO's Mamdani fuzzy inference: a node priority from three normalised inputs (Sangeetha et al. 2021, section 3.2).

The inputs, each normalised to ``[0, 1]``, are the relative distance to the
target, the angle to be turned and the distance to the nearest obstacle;
the output is the priority of the node in the ants' next-node choice. Each
variable has the terms low, medium and high, triangular (eq. 1) on the
supports of Table 3. The inference is Mamdani's: a rule fires with the
minimum of its three memberships (AND), clips its consequent at that level,
the clipped consequents are aggregated by maximum, and the centroid of the
aggregate (eq. 2) is the crisp priority.

Memberships and consequents are built with scikit-fuzzy's ``trimf`` and
``interp_membership`` (vectorised over nodes). ``skfuzzy.defuzz`` handles one
membership function at a time, so :func:`centroid` applies its centroid
formula (the exact centroid of the piecewise-linear aggregate on the
universe) to a whole batch at once; the tests check it against ``defuzz``
and the whole inference against ``skfuzzy.control``. Inside the compiled
walks, where a moving obstacle changes the obstacle input at the ant's
arrival time, :func:`priority_one` evaluates the same inference on the same
arrays for one node (tested equal to :func:`fuzzy_priority`).

Interpretations (see ``docs/planners/aco.fgdaco.md``):

- Table 3 gives each term's support ``(a, c)``; low is a left shoulder
  ``(a, a, c)``, medium peaks midway ``(a, (a + c) / 2, c)`` and high is a right
  shoulder ``(a, c, c)``, so every input in ``[0, 1]`` belongs to some term.
- The paper gives no universe for the priority; it uses the target-distance
  supports ``(0, 0.4)``, ``(0.3, 0.7)``, ``(0.6, 1)``.
- Table 4 lists 12 "sample" rules of the 27; :data:`RULES` completes them
  with the one additive score that reproduces all 12: a low obstacle
  distance always gives low priority; otherwise
  ``s = 1.5 g(target) + g(angle) + (0 if obstacle is medium else 3)`` with
  ``g(low) = 2, g(medium) = 1, g(high) = 0``, and the priority is low for
  ``s < 3``, medium for ``s < 4.5``, high otherwise.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import lru_cache

import numba
import numpy as np

__all__ = [
    "UNIVERSE",
    "defuzzify",
    "TERMS",
    "INPUT_SUPPORTS",
    "OUTPUT_SUPPORTS",
    "PAPER_RULES",
    "RULES",
    "triangle",
    "memberships",
    "centroid",
    "consequents",
    "fuzzy_priority",
    "CompiledPriority",
    "compiled_priority",
    "priority_one",
    "clipped_centroid",
    "rule_ceilings",
    "fired_strengths",
]

UNIVERSE = np.linspace(0.0, 1.0, 201)
"""Discrete universe of every variable (step 0.005: every triangle vertex lies on it)."""

TERMS = ("low", "medium", "high")

INPUT_SUPPORTS: dict[str, tuple[tuple[float, float], ...]] = {
    "target": ((0.0, 0.4), (0.3, 0.7), (0.6, 1.0)),  # relative distance to the target
    "angle": ((0.0, 0.4), (0.3, 0.7), (0.6, 1.0)),  # angle to be turned
    "obstacle": ((0.0, 0.3), (0.2, 0.7), (0.6, 1.0)),  # distance to the nearest obstacle
}
"""Supports ``(a, c)`` of the low, medium and high terms of each input (Table 3)."""

OUTPUT_SUPPORTS: tuple[tuple[float, float], ...] = ((0.0, 0.4), (0.3, 0.7), (0.6, 1.0))
"""Supports of the priority's terms (not in the paper; those of the target distance)."""

L, M, H = 0, 1, 2

PAPER_RULES: dict[tuple[int, int, int], int] = {
    # (target distance, angle to be turned, obstacle distance) -> priority: Table 4, in its order
    (M, H, L): L,
    (L, M, L): L,
    (L, H, L): L,
    (L, L, M): H,
    (L, M, M): M,
    (H, M, M): L,
    (L, L, H): H,
    (L, M, H): H,
    (H, M, H): M,
    (M, M, L): L,
    (H, H, H): M,
    (H, L, M): L,
}
"""The 12 rules of Table 4 (term indices 0 = low, 1 = medium, 2 = high)."""

RULES: dict[tuple[int, int, int], int] = {
    # obstacle distance low: always low priority
    **{(t, a, L): L for t in (L, M, H) for a in (L, M, H)},
    # obstacle distance medium
    (L, L, M): H, (L, M, M): M, (L, H, M): M,
    (M, L, M): M, (M, M, M): L, (M, H, M): L,
    (H, L, M): L, (H, M, M): L, (H, H, M): L,
    # obstacle distance high
    (L, L, H): H, (L, M, H): H, (L, H, H): H,
    (M, L, H): H, (M, M, H): H, (M, H, H): H,
    (H, L, H): H, (H, M, H): M, (H, H, H): M,
}
"""The complete rule base (27 rules) containing :data:`PAPER_RULES`; see the module docstring."""


def triangle(support: tuple[float, float], term: int) -> tuple[float, float, float]:
    """Vertices ``(a, b, c)`` of a term's triangle from its support: shoulders for low and high, midpoint for medium."""
    a, c = support
    return (a, a, c) if term == L else (a, c, c) if term == H else (a, 0.5 * (a + c), c)


def memberships(supports: tuple[tuple[float, float], ...], values: np.ndarray) -> np.ndarray:
    """Membership of crisp ``values`` in the low, medium and high terms, shape ``(3,) + values.shape``."""
    import skfuzzy  # scikit-fuzzy is imported only when FGDACO plans

    return np.stack([skfuzzy.interp_membership(UNIVERSE, skfuzzy.trimf(UNIVERSE, triangle(s, k)), values)
                     for k, s in enumerate(supports)])


def centroid(universe: np.ndarray, mf: np.ndarray,
             weights: tuple[np.ndarray, np.ndarray] | None = None) -> np.ndarray:
    """Centroid of each row of ``mf`` (shape ``(n, len(universe))``), as ``skfuzzy.defuzz(x, row, "centroid")``.

    The rows are piecewise linear between universe points, so each interval
    is a trapezoid with area ``dx (y1 + y2) / 2`` and moment about zero
    ``dx ((y1 + y2) x1 + dx (y1 + 2 y2) / 3) / 2``; both are linear in the
    memberships, so a batch is two matrix products. ``weights`` are
    ``_centroid_weights(universe)``, if already at hand.
    """
    area_w, moment_w = _centroid_weights(universe) if weights is None else weights
    return (mf @ moment_w) / np.fmax(mf @ area_w, np.finfo(float).eps)


def _centroid_weights(universe: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per-point weights ``(w_area, w_moment)`` such that area = ``mf @ w_area`` and moment = ``mf @ w_moment``."""
    x1, x2 = universe[:-1], universe[1:]
    dx = x2 - x1
    area_w = np.zeros(universe.size)
    moment_w = np.zeros(universe.size)
    area_w[:-1] += 0.5 * dx  # y1 terms
    area_w[1:] += 0.5 * dx  # y2 terms
    moment_w[:-1] += 0.5 * dx * (x1 + dx / 3.0)
    moment_w[1:] += 0.5 * dx * (x1 + 2.0 * dx / 3.0)
    return area_w, moment_w


@lru_cache(maxsize=1)
def consequents() -> np.ndarray:
    """Membership functions of the priority's low, medium and high terms on :data:`UNIVERSE`, shape ``(3, U)``."""
    import skfuzzy

    out = np.stack([skfuzzy.trimf(UNIVERSE, triangle(s, k)) for k, s in enumerate(OUTPUT_SUPPORTS)])
    out.setflags(write=False)
    return out


def fuzzy_priority(target: np.ndarray, angle: np.ndarray, obstacle: np.ndarray, *, nodes: np.ndarray | None = None,
                   chunk: int = 1024) -> np.ndarray:
    """Crisp priority of every node: Mamdani inference over :data:`RULES` with centroid defuzzification.

    Parameters
    ----------
    target, angle, obstacle : array_like
        Normalised inputs in ``[0, 1]`` (broadcast together).
    nodes : ndarray of int, optional
        If given, ``target`` and ``obstacle`` are per-node inputs and the
        priority of value ``i`` of ``angle`` reads them at node ``nodes[i]``:
        the memberships are then computed once per node (they are elementwise,
        so the numbers are those of the gathered inputs).
    chunk : int
        Nodes per vectorised batch (bounds the memory of the aggregates).

    Returns
    -------
    ndarray
        Priorities in ``[0, 1]``, of the broadcast shape (of ``angle``'s shape with ``nodes``).
    """
    as_float = lambda v: np.asarray(v, dtype=np.float64)  # noqa: E731
    if nodes is None:
        t, a, o = np.broadcast_arrays(*(as_float(v) for v in (target, angle, obstacle)))
        mt, ma, mo = (memberships(INPUT_SUPPORTS[name], v.ravel()) for name, v in zip(INPUT_SUPPORTS, (t, a, o)))
        shape = t.shape
    else:
        a = as_float(angle)
        shape = a.shape
        mt = memberships(INPUT_SUPPORTS["target"], as_float(target).ravel())[:, nodes.ravel()]
        ma = memberships(INPUT_SUPPORTS["angle"], a.ravel())
        mo = memberships(INPUT_SUPPORTS["obstacle"], as_float(obstacle).ravel())[:, nodes.ravel()]
    strength = _fire_rules(mt, ma, mo, compiled_priority().rules)
    return defuzzify(strength, consequents(), UNIVERSE, chunk).reshape(shape)


def defuzzify(strength: np.ndarray, cons: np.ndarray, universe: np.ndarray, chunk: int) -> np.ndarray:
    """Crisp outputs from per-term firing strengths ``(T, n)``: clip, aggregate by max, centroid, in batches.

    Mamdani's implication (min with each consequent ``cons[t]`` on
    ``universe``), max aggregation and :func:`centroid`, ``chunk`` nodes at a
    time so the ``(chunk, U)`` aggregates stay small. Shared by FLACO's impedance.
    """
    out = np.empty(strength.shape[1])
    weights = _centroid_weights(universe)
    aggregate = np.empty((min(chunk, out.size), universe.size))
    support = np.array([(p.argmax(), p.size - p[::-1].argmax()) if p.any() else (0, 0) for p in cons > 0.0])
    for lo in range(0, out.size, chunk):
        rows = aggregate[: min(chunk, out.size - lo)]
        _clip_and_aggregate(strength[:, lo : lo + chunk], cons, support, rows)
        out[lo : lo + chunk] = centroid(universe, rows, weights)
    return out


@numba.njit(cache=True)
def _fire_rules(mt, ma, mo, rules):
    """Firing strength of each priority term per value: the largest ``min`` of the three memberships over its rules.

    ``rules`` rows are ``(target term, angle term, obstacle term, priority term)``; ``min`` and ``max`` are exact.
    """
    strength = np.zeros((3, mt.shape[1]))
    for r in range(rules.shape[0]):
        i, j, k, term = rules[r, 0], rules[r, 1], rules[r, 2], rules[r, 3]
        for n in range(mt.shape[1]):
            strength[term, n] = max(strength[term, n], min(mt[i, n], ma[j, n], mo[k, n]))
    return strength


@numba.njit(cache=True)
def _clip_and_aggregate(strength, cons, support, out):
    """``out[i, p] = max_t min(strength[t, i], cons[t, p])``: the clipped consequents' maximum (compiled; exact).

    Consequents and strengths are never negative, so a term adds nothing
    outside its support ``support[t, 0] <= p < support[t, 1]`` (where
    ``cons[t] > 0``): rows start at zero and each term is applied on its
    support only, which gives the same numbers with fewer operations.
    """
    for i in range(out.shape[0]):
        row = out[i]
        row[:] = 0.0
        for t in range(cons.shape[0]):
            s = strength[t, i]
            for p in range(support[t, 0], support[t, 1]):  # contiguous: vectorised
                row[p] = max(row[p], min(s, cons[t, p]))


@dataclass(frozen=True, eq=False)
class CompiledPriority:
    """The inference of :func:`fuzzy_priority` as plain arrays for :func:`priority_one` (inside compiled walks).

    Attributes
    ----------
    vertices : ndarray, shape (3, 3, 3)
        ``(input, term, vertex)``: the triangles of the target, angle and obstacle terms.
    rules : ndarray of int64, shape (27, 4)
        ``(target term, angle term, obstacle term, priority term)``.
    consequents : ndarray, shape (3, U)
        The priority's term memberships on :data:`UNIVERSE`.
    area_w, moment_w : ndarray, shape (U,)
        Centroid weights (:func:`centroid`).
    """

    vertices: np.ndarray
    rules: np.ndarray
    consequents: np.ndarray
    area_w: np.ndarray
    moment_w: np.ndarray


@lru_cache(maxsize=1)
def compiled_priority() -> CompiledPriority:
    """The arrays :func:`priority_one` needs, built once."""
    vertices = np.array([[triangle(s, k) for k, s in enumerate(INPUT_SUPPORTS[name])]
                         for name in ("target", "angle", "obstacle")])
    rules = np.array([(*ante, term) for ante, term in RULES.items()], dtype=np.int64)
    return CompiledPriority(vertices, rules, consequents(), *_centroid_weights(UNIVERSE))


@numba.njit(cache=True, inline="always")
def _membership(v, a, b, c):
    if v < a or v > c:
        return 0.0
    if v < b:  # then a < b: never a division by zero
        return (v - a) / (b - a)
    if v > b:
        return (c - v) / (c - b)
    return 1.0


@numba.njit(cache=True, fastmath=True)
def priority_one(target, angle, obstacle, vertices, rules, cons, area_w, moment_w, mu, strength):
    """Compiled twin of :func:`fuzzy_priority` for one node (the walks call it when a moving obstacle is near).

    Triangle memberships are evaluated in closed form, which equals
    ``interp_membership`` on :data:`UNIVERSE` because every vertex lies on it.
    ``mu`` (shape (3, 3)) and ``strength`` (shape (3,)) are scratch space.
    """
    for i in range(3):
        v = target if i == 0 else angle if i == 1 else obstacle
        for k in range(3):
            mu[i, k] = _membership(v, vertices[i, k, 0], vertices[i, k, 1], vertices[i, k, 2])
    strength[:] = 0.0
    for r in range(rules.shape[0]):
        s = min(mu[0, rules[r, 0]], mu[1, rules[r, 1]], mu[2, rules[r, 2]])
        if s > strength[rules[r, 3]]:
            strength[rules[r, 3]] = s
    return clipped_centroid(strength[0], strength[1], strength[2], cons, area_w, moment_w)


@numba.njit(cache=True, fastmath=True)
def clipped_centroid(s0, s1, s2, cons, area_w, moment_w):
    """Crisp priority from the firing strengths of the low, medium and high terms: clip, aggregate by max, centroid."""
    area = 0.0
    moment = 0.0
    for p in range(cons.shape[1]):
        y = max(min(s0, cons[0, p]), min(s1, cons[1, p]), min(s2, cons[2, p]))
        area += y * area_w[p]
        moment += y * moment_w[p]
    return moment / max(area, 2.220446049250313e-16)


@numba.njit(cache=True, fastmath=True, error_model="numpy")
def rule_ceilings(target, angle, vertices, rules, out, e):
    """How strongly each priority term can fire through each obstacle term, from move ``e``'s target and angle alone.

    Fills ``out[e, term, k]`` (the first 3 x 3 entries of record ``e``) with
    the largest ``min(μ_target, μ_angle)`` over the rules with obstacle term
    ``k`` and priority term ``term``. Since ``min`` and ``max`` only select
    values, the firing strength of ``term`` for an obstacle input with
    memberships ``μ_k`` is exactly ``max(0, max_k min(out[e, term, k], μ_k))``
    (:func:`fired_strengths`): the number :func:`priority_one` finds by going
    through all 27 rules. ``vertices`` and ``rules`` are those of
    :class:`CompiledPriority`. The walks pass their whole per-move table and
    an index rather than a view of one record, which would cost a reference count.
    """
    for term in range(3):
        for k in range(3):
            out[e, term, k] = 0.0
    for r in range(rules.shape[0]):
        i, j, k, term = rules[r, 0], rules[r, 1], rules[r, 2], rules[r, 3]
        s = min(_membership(target, vertices[0, i, 0], vertices[0, i, 1], vertices[0, i, 2]),
                _membership(angle, vertices[1, j, 0], vertices[1, j, 1], vertices[1, j, 2]))
        if s > out[e, term, k]:
            out[e, term, k] = s


@numba.njit(cache=True, fastmath=True, error_model="numpy")
def fired_strengths(ceilings, e, obstacle, vertices):
    """Firing strengths of the low, medium and high priority terms of move ``e``, whose :func:`rule_ceilings` are given.

    ``ceilings[e]`` holds the move's ceilings (as :func:`rule_ceilings` leaves
    them). ``clipped_centroid(*fired_strengths(ceilings, e, obstacle, vertices), ...)``
    is exactly :func:`priority_one` of that move: only the obstacle input is
    new, so the 27 rules reduce to nine ``min`` and three ``max``.
    """
    m0 = _membership(obstacle, vertices[2, 0, 0], vertices[2, 0, 1], vertices[2, 0, 2])
    m1 = _membership(obstacle, vertices[2, 1, 0], vertices[2, 1, 1], vertices[2, 1, 2])
    m2 = _membership(obstacle, vertices[2, 2, 0], vertices[2, 2, 1], vertices[2, 2, 2])
    c = ceilings
    return (max(0.0, min(c[e, 0, 0], m0), min(c[e, 0, 1], m1), min(c[e, 0, 2], m2)),
            max(0.0, min(c[e, 1, 0], m0), min(c[e, 1, 1], m1), min(c[e, 1, 2], m2)),
            max(0.0, min(c[e, 2, 0], m0), min(c[e, 2, 1], m1), min(c[e, 2, 2], m2)))
