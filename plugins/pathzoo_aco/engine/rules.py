"""The rules an ant follows on one walk, as plain arrays and numbers the compiled kernel reads."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

__all__ = ["WalkRules", "EMPTY"]

EMPTY = np.zeros(0, dtype=np.float32)
"""Placeholder for an unused per-edge array (the kernel tests ``size > 0``)."""


@dataclass(frozen=True, eq=False)
class WalkRules:
    """How an ant at node ``i`` weighs, picks and marks the edge ``e = (i, j)`` it takes.

    The weight of an allowed edge (``j`` not yet visited by this ant) is::

        w(e) = τ(e) ** tau_exp * weight_mul[e] + weight_add[e]        (times turn[prev, move(e)])

    where ``τ(e)`` is the trail of the edge (or of node ``j`` for node
    trails). This covers both transition rules of the family:

    - product rule ``τ^α η^β F`` (AS, MMAS, ACS, GGACO eq. 15):
      ``tau_exp = α``, ``weight_mul = η^β F``, no ``weight_add``
      (:meth:`product`);
    - sum rule ``(α τ + β η) F`` (G-Ant eq. 13): ``tau_exp = 1``,
      ``weight_mul = α F``, ``weight_add = β η F`` (:meth:`additive`).

    ``F`` is an optional per-edge factor such as the neighbour count
    ``n_j / (n_j + 1)``. Edges of weight 0 are not allowed. If every allowed
    edge has weight 0 only because its trail is 0, the ant weighs them by the
    heuristic alone.

    Parameters
    ----------
    tau_exp : float
        Exponent on the trail.
    weight_mul, weight_add : ndarray of float, shape (E,)
        Per-edge factors (``weight_add`` may be :data:`EMPTY`); stored in
        single precision, like ``pre_add``.
    q0 : float
        Pseudo-random-proportional rule (ACS): with probability ``q0`` take
        the edge of largest weight, otherwise draw by roulette.
    local_keep, local_add : float
        Local update on the entry just crossed, ``τ <- keep τ + add``
        (ACS: ``keep = 1 - ξ``, ``add = ξ τ0``); ``local_keep = 1`` and
        ``local_add = 0`` switch it off.
    pre_add : ndarray of float, shape (E,)
        Added to the trail of every edge leaving the ant's node *before* it
        chooses (GGACO's gain, eq. 13); :data:`EMPTY` switches it off.
    backtrack : bool
        Dead ends: step back along the walk (the dead end stays tabu) when
        True; drop the ant when False.
    max_steps : int
        Steps (forward moves plus backtracking moves) after which the ant is
        dropped.
    turn : ndarray, shape (K + 1, K) or (0, 0)
        Factor per (previous move, next move); 0 forbids the turn. Empty:
        no turn rule.
    race : bool
        Ants move in lock step, one step each per round, and the colony stops
        as soon as one reaches the goal (GGACO's Algorithm 1); otherwise each
        ant walks to the goal before the next one starts.
    """

    tau_exp: float
    weight_mul: np.ndarray
    weight_add: np.ndarray = field(default_factory=lambda: EMPTY)
    q0: float = 0.0
    local_keep: float = 1.0
    local_add: float = 0.0
    pre_add: np.ndarray = field(default_factory=lambda: EMPTY)
    backtrack: bool = True
    max_steps: int = 2**62
    turn: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))
    race: bool = False

    def __post_init__(self) -> None:
        # single precision halves the memory traffic of the walks; weights only set ratios
        for name in ("weight_mul", "weight_add", "pre_add"):
            object.__setattr__(self, name, np.ascontiguousarray(getattr(self, name), dtype=np.float32))

    @property
    def local_update(self) -> bool:
        """Whether the local update is active."""
        return self.local_keep != 1.0 or self.local_add != 0.0

    @classmethod
    def product(cls, alpha: float, eta: np.ndarray, beta: float, factor: np.ndarray | None = None,
                **kw: object) -> "WalkRules":
        """Rules for the product rule ``τ^α η^β F``."""
        mul = np.power(np.asarray(eta, dtype=np.float64), beta)
        if factor is not None:
            mul = mul * factor
        return cls(tau_exp=float(alpha), weight_mul=mul, **kw)  # type: ignore[arg-type]

    @classmethod
    def additive(cls, alpha: float, eta: np.ndarray, beta: float, factor: np.ndarray | None = None,
                 **kw: object) -> "WalkRules":
        """Rules for the sum rule ``(α τ + β η) F``."""
        f = np.ones_like(eta, dtype=np.float64) if factor is None else np.asarray(factor, dtype=np.float64)
        return cls(tau_exp=1.0, weight_mul=alpha * f, weight_add=beta * np.asarray(eta, dtype=np.float64) * f,
                   **kw)  # type: ignore[arg-type]
