"""``swarm.coa``: the Cuckoo Optimization Algorithm (Rajabioun 2011) over waypoint paths, as FGDACO's COA rival.

FGDACO's Table 7 compares against "COA", its reference [16]: Hosseinienejad &
Dadkhah, *Mobile robot path planning in dynamic environment based on cuckoo
optimization algorithm*, Int. J. Advanced Robotic Systems 16(2), 2019. That
paper applies Rajabioun's COA (R. Rajabioun, *Cuckoo Optimization
Algorithm*, Applied Soft Computing 11 (2011) 5508-5518) to a path of
waypoints among moving obstacles. COA is not Yang & Deb's cuckoo search
(``swarm.cuckoo``): it has no Lévy flights and no discovery probability, but
a population of habitats that lay eggs within a radius, lose their worst
eggs, are capped in number, and migrate toward the best group's best habitat.

One generation, with the functions below (Rajabioun's steps):

1. every habitat (cuckoo) gets a random number of eggs in
   ``[min_eggs, max_eggs]`` (:func:`egg_counts`);
2. its egg-laying radius is ``ELR_i = alpha * eggs_i / sum(eggs) *
   (var_hi - var_lo)`` (Rajabioun's eq. 2; :func:`egg_laying_radii`), one
   radius per variable;
3. the eggs are laid at random points within that radius around the
   habitat (:func:`lay_eggs`) and evaluated;
4. the ``kill_fraction`` worst eggs are found and killed (:func:`surviving_eggs`);
5. habitats and surviving eggs form the new population, of which at most
   ``max_cuckoos`` (the best) survive (:func:`limit_population`);
6. the habitats are grouped by k-means into ``clusters`` groups; the goal is
   the best habitat of the group with the best mean profit (:func:`goal_habitat`);
7. every habitat but the best migrates toward the goal,
   ``x <- x + F (x_goal - x)`` with ``F = motion_coeff * U(0, 1)`` drawn per
   variable (Rajabioun's immigration; :func:`immigrate`), and is evaluated.

See ``docs/planners/swarm.coa.md`` for the sources and what was reconstructed.
"""

from __future__ import annotations

import warnings
from typing import Any, ClassVar, Mapping

import numpy as np

from pathzoo.core import Budget, InvalidParameterError, Param, PlanResult, ProgressCallback, Scenario
from pathzoo_baselines.base import BaselinePlanner
from pathzoo_baselines.params import ENCODING_PARAMS

__all__ = [
    "CoaPlanner",
    "egg_counts",
    "egg_laying_radii",
    "lay_eggs",
    "surviving_eggs",
    "limit_population",
    "goal_habitat",
    "immigrate",
]


def egg_counts(rng: np.random.Generator, n: int, min_eggs: int, max_eggs: int) -> np.ndarray:
    """Step 1: a number of eggs for each of ``n`` habitats, uniform in ``[min_eggs, max_eggs]``."""
    return rng.integers(min_eggs, max_eggs + 1, size=n)


def egg_laying_radii(eggs: np.ndarray, alpha: float, span: np.ndarray) -> np.ndarray:
    """Step 2 (Rajabioun's eq. 2): ``ELR_i = alpha * eggs_i / sum(eggs) * (var_hi - var_lo)``, shape (n, d)."""
    eggs = np.asarray(eggs, dtype=np.float64)
    return alpha * (eggs / eggs.sum())[:, None] * np.asarray(span, dtype=np.float64)[None, :]


def lay_eggs(
    rng: np.random.Generator, habitats: np.ndarray, eggs: np.ndarray, radii: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Step 3: ``eggs[i]`` points around habitat ``i``, each inside the ellipsoid of semi-axes ``radii[i]``.

    An egg is the habitat plus ``radii[i] * r * u``: ``u`` a uniformly random
    unit direction, ``r ~ U(0, 1)`` (a random distance below the radius).
    Returns the eggs (m, d) and the index of the habitat each belongs to.
    """
    owner = np.repeat(np.arange(len(habitats)), eggs)
    direction = rng.standard_normal((len(owner), habitats.shape[1]))
    direction /= np.maximum(np.linalg.norm(direction, axis=1, keepdims=True), 1e-300)
    distance = rng.random((len(owner), 1))
    return habitats[owner] + radii[owner] * distance * direction, owner


def surviving_eggs(costs: np.ndarray, kill_fraction: float) -> np.ndarray:
    """Step 4: a mask of the eggs kept when the ``round(kill_fraction * m)`` costliest are killed (ties by index)."""
    m = len(costs)
    killed = int(round(kill_fraction * m))
    keep = np.ones(m, dtype=bool)
    if killed > 0:
        keep[np.argsort(costs, kind="stable")[m - killed:]] = False
    return keep


def limit_population(habitats: np.ndarray, costs: np.ndarray, max_cuckoos: int) -> tuple[np.ndarray, np.ndarray]:
    """Step 5: the ``max_cuckoos`` cheapest habitats, cheapest first (all of them, sorted, when fewer)."""
    order = np.argsort(costs, kind="stable")[:max_cuckoos]
    return habitats[order], costs[order]


def goal_habitat(habitats: np.ndarray, costs: np.ndarray, labels: np.ndarray) -> np.ndarray:
    """Step 6: the cheapest habitat of the group whose mean cost is lowest (the best mean profit)."""
    groups = np.unique(labels)
    means = np.array([costs[labels == g].mean() for g in groups])
    members = np.flatnonzero(labels == groups[int(np.argmin(means))])
    return habitats[members[int(np.argmin(costs[members]))]]


def immigrate(rng: np.random.Generator, habitats: np.ndarray, goal: np.ndarray, motion_coeff: float) -> np.ndarray:
    """Step 7: ``x + F (goal - x)`` with ``F = motion_coeff * U(0, 1)`` drawn for every habitat and variable."""
    factor = motion_coeff * rng.random(habitats.shape)
    return habitats + factor * (goal[None, :] - habitats)


def _clusters(rng: np.random.Generator, habitats: np.ndarray, k: int) -> np.ndarray:
    """k-means labels of the habitats (scipy's ``kmeans2``, k-means++ start, drawn from ``rng``)."""
    from scipy.cluster.vq import kmeans2

    k = min(k, len(habitats))
    if k <= 1 or np.ptp(habitats, axis=0).max() == 0.0:
        return np.zeros(len(habitats), dtype=np.int64)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # an empty cluster is harmless here: its label is simply unused
        _, labels = kmeans2(habitats, k, minit="++", rng=rng)
    return labels


class CoaPlanner(BaselinePlanner):
    """Cuckoo Optimization Algorithm (Rajabioun 2011) over the shared waypoint encoding; see the module docstring.

    Habitats are candidate paths of the pure encodings (``waypoints`` by
    default: K points joined by straight segments, penalised for collisions,
    for moving obstacles met at the time of passage on ``dynamic`` maps, and
    for voxels and pitch in air volumes). Positions are clipped to the map.
    One iteration is one generation (steps 1-7), costing the eggs laid plus
    the habitats that migrate.
    """

    id: ClassVar[str] = "swarm.coa"
    version: ClassVar[str] = "2"
    summary: ClassVar[str] = "Cuckoo Optimization Algorithm (Rajabioun 2011; FGDACO's COA) over K straight-segment waypoints"
    preload: ClassVar[tuple[str, ...]] = ("scipy.cluster.vq",)
    params: ClassVar[Mapping[str, Param]] = {
        **ENCODING_PARAMS,
        "cuckoos": Param(20, "initial number of habitats N_pop", low=1, high=100_000),
        "max_cuckoos": Param(40, "most habitats alive after population control N_max", low=1, high=100_000),
        "min_eggs": Param(5, "fewest eggs a habitat lays in a generation (Rajabioun: 5)", low=1, high=1000),
        "max_eggs": Param(20, "most eggs a habitat lays in a generation (Rajabioun: 20)", low=1, high=1000),
        "alpha": Param(1.0, "egg-laying radius coefficient alpha of ELR (eq. 2)", low=0.0, low_open=True, high=100.0),
        "kill_fraction": Param(0.1, "share of the eggs, the worst, killed each generation (Rajabioun: 10 %)",
                               low=0.0, high=0.99),
        "clusters": Param(3, "k of the k-means grouping of habitats", low=1, high=100),
        "motion_coeff": Param(2.0, "immigration coefficient: F = motion_coeff * U(0, 1)", low=0.0, low_open=True,
                              high=10.0),
    }

    def _check_params(self, values: Mapping[str, Any]) -> None:
        if values["min_eggs"] > values["max_eggs"]:
            raise InvalidParameterError(
                f"{self.id}: parameter 'min_eggs' must be at most max_eggs={values['max_eggs']}, got {values['min_eggs']}"
            )

    def plan(
        self,
        scenario: Scenario,
        *,
        budget: Budget,
        rng: np.random.Generator,
        progress: ProgressCallback | None = None,
    ) -> PlanResult:
        """Run COA generations until the budget is spent; see the module docstring."""
        encoding, search = self._start(scenario, budget, progress)
        low, high = encoding.low, encoding.high
        span = high - low
        habitats = np.asarray(search.initial(rng, self.cuckoos), dtype=np.float64)
        costs = search.evaluate(habitats)
        search.report()
        while not search.exhausted():
            eggs = egg_counts(rng, len(habitats), self.min_eggs, self.max_eggs)
            laid, _ = lay_eggs(rng, habitats, eggs, egg_laying_radii(eggs, self.alpha, span))
            laid = np.clip(laid, low, high)
            egg_costs = search.evaluate(laid)
            keep = surviving_eggs(egg_costs, self.kill_fraction)
            habitats, costs = limit_population(
                np.vstack([habitats, laid[keep]]), np.concatenate([costs, egg_costs[keep]]), self.max_cuckoos
            )
            labels = _clusters(rng, habitats, self.clusters)
            goal = goal_habitat(habitats, costs, labels)
            moved = np.clip(immigrate(rng, habitats[1:], goal, self.motion_coeff), low, high)
            habitats = np.vstack([habitats[:1], moved])  # the best habitat stays (limit_population sorted them)
            costs = np.concatenate([costs[:1], search.evaluate(moved)])
            search.next_iteration()
        return search.result()
