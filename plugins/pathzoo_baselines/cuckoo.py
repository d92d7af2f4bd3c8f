"""``swarm.cuckoo``: cuckoo search via Lévy flights (Yang & Deb 2009) over waypoint paths, in numpy."""

from __future__ import annotations

import math
from typing import ClassVar, Mapping

import numpy as np

from pathzoo.core import Budget, Param, PlanResult, ProgressCallback, Scenario
from pathzoo_baselines.base import BaselinePlanner
from pathzoo_baselines.params import ENCODING_PARAMS

__all__ = ["CuckooPlanner", "mantegna_steps"]


def mantegna_steps(rng: np.random.Generator, shape: tuple[int, ...], beta: float) -> np.ndarray:
    """Lévy-stable step lengths by Mantegna's algorithm (1994).

    ``s = u / |v|^(1/beta)`` with ``v ~ N(0, 1)`` and ``u ~ N(0, sigma_u^2)``,
    ``sigma_u = [Γ(1+β) sin(πβ/2) / (Γ((1+β)/2) β 2^((β-1)/2))]^(1/β)``.
    """
    numerator = math.gamma(1 + beta) * math.sin(math.pi * beta / 2)
    sigma_u = (numerator / (math.gamma((1 + beta) / 2) * beta * 2 ** ((beta - 1) / 2))) ** (1 / beta)
    u = rng.normal(0.0, sigma_u, size=shape)
    v = rng.normal(0.0, 1.0, size=shape)
    return u / np.abs(v) ** (1 / beta)


class CuckooPlanner(BaselinePlanner):
    """Cuckoo search (Yang & Deb 2009) over the shared waypoint encoding.

    ``nests`` host nests hold candidate paths. Each generation:

    1. **Lévy flights.** Every nest lays a cuckoo egg
       ``x' = x + alpha * L * (x - best) * N(0, 1)`` with Lévy steps ``L``
       (:func:`mantegna_steps`, exponent ``beta``); the egg replaces its nest
       when it is cheaper.
    2. **Discovery.** Each component of each nest is discovered with
       probability ``pa``; discovered components move by a random fraction of
       the difference of two randomly permuted nests,
       ``x' = x + r (x_p1 - x_p2)``, and the new nest is kept when cheaper.

    So each generation costs ``2 * nests`` evaluations. Positions are clipped
    to the map. The paper's pseudo-code compares an egg with a randomly
    chosen nest and leaves the step form open; we follow the authors'
    reference implementation (Yang's published MATLAB code, also NiaPy's),
    which compares the egg with its own nest and uses the step forms above,
    with one exception: that code moves a component when ``rand > pa``, i.e.
    with probability ``1 - pa``, whereas we discover it with probability
    ``pa`` as the paper defines ``pa``.
    Defaults are the paper's: 25 nests, ``pa = 0.25``, ``beta = 1.5``,
    ``alpha = 0.01``. We evaluated NiaPy's CuckooSearch: it is faithful but
    evaluates candidates one by one and has no time limit, so this numpy
    version draws everything from the run's ``rng`` instead (no global
    state). See ``docs/planners/swarm.cuckoo.md``.
    """

    id: ClassVar[str] = "swarm.cuckoo"
    version: ClassVar[str] = "4"
    summary: ClassVar[str] = "Cuckoo search (Yang & Deb) with Mantegna Lévy flights over K straight-segment waypoints"
    params: ClassVar[Mapping[str, Param]] = {
        **ENCODING_PARAMS,
        "nests": Param(25, "number of host nests n", low=2, high=100_000),
        "pa": Param(0.25, "discovery probability p_a of an alien egg", low=0.0, high=1.0),
        "beta": Param(1.5, "Lévy exponent beta (Mantegna's algorithm)", low=0.3, high=1.99),
        "alpha": Param(0.01, "Lévy step scale alpha", low=0.0, low_open=True, high=100.0),
    }

    def plan(
        self,
        scenario: Scenario,
        *,
        budget: Budget,
        rng: np.random.Generator,
        progress: ProgressCallback | None = None,
    ) -> PlanResult:
        """Run cuckoo search until the budget is spent; see the class docstring."""
        encoding, search = self._start(scenario, budget, progress)
        low, high = encoding.low, encoding.high
        nests = np.asarray(search.initial(rng, self.nests))  # a fixed-length encoding: already an array
        fitness = search.evaluate(nests)
        search.report()

        def keep_better(candidates: np.ndarray) -> None:
            candidates = np.clip(candidates, low, high)
            new = search.evaluate(candidates)
            better = new < fitness
            nests[better] = candidates[better]
            fitness[better] = new[better]

        while not search.exhausted():
            best = nests[int(np.argmin(fitness))]
            steps = mantegna_steps(rng, nests.shape, self.beta)
            keep_better(nests + self.alpha * steps * (nests - best) * rng.standard_normal(nests.shape))
            discovered = rng.random(nests.shape) < self.pa
            shift = rng.random() * (nests[rng.permutation(self.nests)] - nests[rng.permutation(self.nests)])
            keep_better(nests + shift * discovered)
            search.next_iteration()
        return search.result()
