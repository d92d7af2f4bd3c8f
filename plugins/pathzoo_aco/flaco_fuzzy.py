"""FLACO's fuzzy impedance: a Mamdani inference that turns a node's dynamic and static hazards into a length factor.

Song et al. (IEEE Access 2020) fold dynamic factors that are hard to put in
numbers into a "virtual path length" by fuzzy logic; only their abstract
was reachable, so the inputs, terms and rules below are pathzoo's
reconstruction (``docs/planners/aco.flaco.md``), not the paper's:

- inputs, normalised to ``[0, 1]``: ``traffic`` -- the share of time a moving
  obstacle comes within sensing range of the node (:func:`traffic_share`) --
  and ``clearance`` -- the node's distance to the nearest static obstacle
  over the sensing range;
- terms low, medium, high on ``[0, 1]``: triangles ``(0, 0, 0.5)``,
  ``(0, 0.5, 1)``, ``(0.5, 1, 1)`` for both inputs and for the output, the
  impedance;
- :data:`RULES`: more traffic never lowers the impedance, more clearance
  never raises it;
- Mamdani inference (AND = min, clipping, aggregation by max) and centroid
  defuzzification, with scikit-fuzzy's ``trimf``/``interp_membership`` and
  the batched centroid of :func:`pathzoo_aco.fgdaco_fuzzy.centroid`; the tests
  check the result against ``skfuzzy.control``.
"""

from __future__ import annotations

from functools import lru_cache
from typing import Sequence

import numpy as np

from pathzoo.core.moving import MovingObstacle
from pathzoo_aco.fgdaco_fuzzy import defuzzify

__all__ = ["UNIVERSE", "TERM_VERTICES", "RULES", "impedance", "traffic_share", "memberships", "consequents"]

UNIVERSE = np.linspace(0.0, 1.0, 101)
"""Universe of both inputs and of the output."""

TERM_VERTICES: tuple[tuple[float, float, float], ...] = ((0.0, 0.0, 0.5), (0.0, 0.5, 1.0), (0.5, 1.0, 1.0))
"""Triangles ``(a, b, c)`` of the terms low, medium and high."""

L, M, H = 0, 1, 2

RULES: dict[tuple[int, int], int] = {
    (L, L): M, (L, M): L, (L, H): L,
    (M, L): H, (M, M): M, (M, H): M,
    (H, L): H, (H, M): H, (H, H): H,
}
"""``(traffic term, clearance term) -> impedance term`` (pathzoo's rule base; the paper's is not available)."""

SAMPLES_PER_CYCLE = 64
"""Times per obstacle cycle at which :func:`traffic_share` samples the obstacle's position."""


def memberships(values: np.ndarray) -> np.ndarray:
    """Membership of crisp ``values`` in low, medium and high, shape ``(3,) + values.shape``."""
    import skfuzzy

    return np.stack([skfuzzy.interp_membership(UNIVERSE, skfuzzy.trimf(UNIVERSE, list(v)), values)
                     for v in TERM_VERTICES])


@lru_cache(maxsize=1)
def consequents() -> np.ndarray:
    """The impedance's low, medium and high membership functions on :data:`UNIVERSE`, shape ``(3, U)``."""
    import skfuzzy

    out = np.stack([skfuzzy.trimf(UNIVERSE, list(v)) for v in TERM_VERTICES])
    out.setflags(write=False)
    return out


def impedance(traffic: np.ndarray, clearance: np.ndarray, *, chunk: int = 2048) -> np.ndarray:
    """Crisp impedance in ``[0, 1]`` per node: Mamdani inference over :data:`RULES`, centroid defuzzification.

    Parameters
    ----------
    traffic, clearance : array_like
        Normalised inputs in ``[0, 1]`` (broadcast together).
    chunk : int
        Nodes per vectorised batch (bounds the memory of the aggregates).
    """
    t, c = np.broadcast_arrays(np.asarray(traffic, dtype=np.float64), np.asarray(clearance, dtype=np.float64))
    mt, mc = memberships(t.ravel()), memberships(c.ravel())
    strength = np.zeros((3, mt.shape[1]))
    for (i, j), term in RULES.items():
        np.maximum(strength[term], np.minimum(mt[i], mc[j]), out=strength[term])
    return defuzzify(strength, consequents(), UNIVERSE, chunk).reshape(t.shape)


def traffic_share(points: np.ndarray, obstacles: Sequence[MovingObstacle], sensing_m: float,
                  *, chunk: int = 4096) -> np.ndarray:
    """Per point: summed share of each obstacle's cycle spent within ``sensing_m`` of it, clipped to 1.

    Each obstacle is sampled at :data:`SAMPLES_PER_CYCLE` equally spaced
    times over one period (a parked obstacle at its one position); the
    distance counted is from the point to the obstacle's rim.
    """
    share = np.zeros(len(points))
    for ob in obstacles:
        period = ob.period_s
        times = np.arange(SAMPLES_PER_CYCLE) * (period / SAMPLES_PER_CYCLE) if np.isfinite(period) else np.zeros(1)
        centres = ob.position(times)
        for lo in range(0, len(points), chunk):
            d = np.linalg.norm(points[lo : lo + chunk, None, :] - centres[None, :, :], axis=2) - ob.radius
            share[lo : lo + chunk] += np.mean(d < sensing_m, axis=1)
    return np.minimum(share, 1.0)
