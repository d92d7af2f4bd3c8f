"""``evo.ga``: a generational genetic algorithm on DEAP, over waypoint, spline or grid-move paths."""

from __future__ import annotations

import functools
from typing import Any, Callable, ClassVar, Mapping

import numpy as np

from pathzoo.core import Budget, InvalidParameterError, Param, PlanResult, ProgressCallback, Scenario
from pathzoo_baselines.base import BaselinePlanner
from pathzoo_baselines.encodings import Encoding
from pathzoo_baselines.params import ENCODING_PARAMS, PURE_ENCODINGS
from pathzoo_baselines.search import seeded_global_random

__all__ = ["GaPlanner", "RateControl", "GA_PARAMS", "CELLS_PARAMS"]

RateControl = Callable[[list, float], tuple[float, float]]
"""``rates(population, best_cost) -> (cxpb, mutpb)``, asked before every generation."""

GA_PARAMS: Mapping[str, Param] = {
    **ENCODING_PARAMS,
    "encoding": Param(
        "waypoints",
        "candidate encoding: 'waypoints', 'spline' (see swarm.pso) or 'grid' (a string of compass moves walked on "
        "the neighbourhood graph, grid2d and terrain only); none runs a graph search (the A*-routed encodings are "
        "evo.ga_astar's)",
        choices=(*PURE_ENCODINGS, "grid"),
    ),
    "moves_factor": Param(2.0, "grid encoding: moves per chromosome, as a multiple of H + W", low=0.05, high=100.0),
    "population": Param(50, "population size", low=2, high=100_000),
    "tournament": Param(3, "tournament size of the selection", low=1, high=1000),
    "elites": Param(1, "best individuals copied unchanged into the next generation", low=0, high=1000),
    "gene_rate": Param(
        1.0, "expected number of genes a mutation changes (per-gene probability gene_rate / n_genes)", low=0.0,
        low_open=True,
    ),
    "eta_cx": Param(15.0, "distribution index of simulated binary crossover (real genes)", low=0.0, high=1000.0),
    "eta_mut": Param(20.0, "distribution index of polynomial mutation (real genes)", low=0.0, high=1000.0),
}
"""Parameters shared by ``evo.ga`` and ``evo.fuzzy_rate_ga`` (the hybrids add the ``cells`` encoding's)."""

CELLS_PARAMS: Mapping[str, Param] = {
    "reroute_fraction": Param(
        0.3, "cells encoding: longest piece a mutation reroutes, as a share of the chain", low=0.0, low_open=True,
        high=1.0,
    ),
    "shortcut_rate": Param(
        0.5, "cells encoding: probability that a mutation replaces the piece by the shortest route between its "
        "ends (a local step) rather than by a detour through a random nearby cell", low=0.0, high=1.0,
    ),
}
"""Parameters of the ``cells`` encoding (the hybrids ``evo.ga_astar`` and ``evo.fuzzy_rate_ga_astar``)."""


@functools.lru_cache(maxsize=1)
def _deap_types() -> tuple[type, type]:
    """DEAP fitness (minimised) and individual (a list) classes, built on first use."""
    from deap import base

    class Fitness(base.Fitness):
        weights = (-1.0,)

    class Individual(list):
        def __init__(self, genes: Any) -> None:
            super().__init__(genes)
            self.fitness = Fitness()

    return Fitness, Individual


def _mate_chains(a: list, b: list, *, encoding: Any, rng: np.random.Generator) -> tuple[list, list]:
    """DEAP mate operator for chains: :func:`~pathzoo_baselines.cellpath.crossover_at_shared_node`, in place."""
    child_a, child_b = encoding.crossover(np.asarray(a), np.asarray(b), rng)
    a[:], b[:] = child_a.tolist(), child_b.tolist()
    return a, b


def _mutate_chain(a: list, *, encoding: Any, rng: np.random.Generator, stop: Callable[[], bool]) -> tuple[list]:
    """DEAP mutate operator for chains: :func:`~pathzoo_baselines.cellpath.reroute_mutation`, in place.

    Once ``stop()`` is true (the time limit), the chain is left as it is: a
    mutation runs graph searches, which on very large maps would overrun the
    budget by a whole generation.
    """
    if not stop():
        a[:] = encoding.mutate(np.asarray(a), rng).tolist()
    return (a,)


class GaPlanner(BaselinePlanner):
    """Generational GA with tournament selection, crossover, mutation and elitism (DEAP operators).

    Each generation: keep the ``elites`` best; fill the rest by tournament
    selection (``tournament`` individuals each); pair consecutive parents and
    mate each pair with probability ``cxpb``; mutate each child with
    probability ``mutpb`` (``deap.algorithms.varAnd``).

    - Real genes (``waypoints``, the default, and ``spline``; the hybrid's
      ``routed``): simulated binary crossover and polynomial mutation, both
      bounded to the map (``eta_cx``, ``eta_mut``).
    - Chains of cells (``cells``, the hybrid ``evo.ga_astar`` only):
      crossover at a shared cell and the A*-rerouting mutation of
      :mod:`pathzoo_baselines.cellpath`; every individual stays feasible.
    - Grid genes (``grid``): two-point crossover and uniform integer
      mutation of the moves.

    A DEAP logbook records each generation's best cost and the rates used;
    with ``elites >= 1`` its best column is the convergence curve the
    progress reports give (the best cost so far, once per generation), and
    the mean rates go to ``PlanResult.extras``. DEAP draws from Python's
    ``random`` module; ``plan()`` seeds it from ``rng`` and restores it after
    (see :mod:`pathzoo_baselines.search`). See ``docs/planners/evo.ga.md``.
    """

    id: ClassVar[str] = "evo.ga"
    version: ClassVar[str] = "4"
    summary: ClassVar[str] = "Genetic algorithm (DEAP) over K straight-segment waypoints (or grid moves), no graph search"
    preload: ClassVar[tuple[str, ...]] = ("deap.algorithms", "deap.base", "deap.tools")
    requires: ClassVar[Mapping[str, str]] = {"deap": "evo"}  # optional dependency -> extra
    params: ClassVar[Mapping[str, Param]] = {
        **GA_PARAMS,
        "cxpb": Param(0.9, "probability that a pair of parents is mated", low=0.0, high=1.0),
        "mutpb": Param(0.2, "probability that a child is mutated", low=0.0, high=1.0),
    }

    def _check_params(self, values: Mapping[str, Any]) -> None:
        if values["elites"] >= values["population"]:
            raise InvalidParameterError(
                f"{self.id}: parameter 'elites' must be below population={values['population']}, got {values['elites']}"
            )

    def _rate_control(self, encoding: Encoding) -> RateControl:
        """Crossover and mutation probabilities for each generation: here the fixed ``cxpb`` and ``mutpb``."""
        rates = (self.cxpb, self.mutpb)
        return lambda population, best_cost: rates

    def plan(
        self,
        scenario: Scenario,
        *,
        budget: Budget,
        rng: np.random.Generator,
        progress: ProgressCallback | None = None,
    ) -> PlanResult:
        """Evolve until the budget is spent; see the class docstring."""
        encoding, search = self._start(scenario, budget, progress)
        from deap import algorithms, base, tools

        rates = self._rate_control(encoding)
        _, individual = _deap_types()
        toolbox = base.Toolbox()
        variable = getattr(encoding, "variable_length", False)
        if variable:
            toolbox.register("mate", _mate_chains, encoding=encoding, rng=rng)
            toolbox.register("mutate", _mutate_chain, encoding=encoding, rng=rng, stop=search.out_of_time)
        elif encoding.integer:
            indpb = min(1.0, self.gene_rate / encoding.n_genes)
            toolbox.register("mate", tools.cxTwoPoint)
            toolbox.register("mutate", tools.mutUniformInt, low=0, up=7, indpb=indpb)
        else:
            indpb = min(1.0, self.gene_rate / encoding.n_genes)
            low, up = encoding.low.tolist(), encoding.high.tolist()
            toolbox.register("mate", tools.cxSimulatedBinaryBounded, eta=self.eta_cx, low=low, up=up)
            toolbox.register("mutate", tools.mutPolynomialBounded, eta=self.eta_mut, low=low, up=up, indpb=indpb)
        toolbox.register("select", tools.selTournament, tournsize=self.tournament)
        logbook = tools.Logbook()

        def assess(individuals: list) -> int:
            before = search.evaluations
            batch = [np.asarray(ind, dtype=np.int64) for ind in individuals] if variable else np.array(individuals)
            costs = search.evaluate(batch) if individuals else np.zeros(0)
            for ind, cost in zip(individuals, costs):
                ind.fitness.values = (float(cost),)
            return search.evaluations - before

        with seeded_global_random(rng):
            pop = [individual(row.tolist()) for row in search.initial(rng, self.population)]
            nevals = assess(pop)
            logbook.record(gen=0, nevals=nevals, min=min(ind.fitness.values[0] for ind in pop))
            search.report()
            while not search.exhausted():
                cxpb, mutpb = rates(pop, search.best_cost)
                elite = [toolbox.clone(ind) for ind in tools.selBest(pop, self.elites)]
                offspring = algorithms.varAnd(toolbox.select(pop, len(pop) - self.elites), toolbox, cxpb, mutpb)
                nevals = assess([ind for ind in offspring if not ind.fitness.valid])
                pop = elite + offspring
                search.iterations += 1
                logbook.record(
                    gen=search.iterations, nevals=nevals, min=min(ind.fitness.values[0] for ind in pop),
                    cxpb=cxpb, mutpb=mutpb,
                )
                search.report()
        used = logbook[1:]
        return search.result(
            {
                "mean_cxpb": float(np.mean([r["cxpb"] for r in used])) if used else None,
                "mean_mutpb": float(np.mean([r["mutpb"] for r in used])) if used else None,
            }
        )
