"""``swarm.pso``: global-best particle swarm optimisation of a waypoint path, on pyswarms' backend."""

from __future__ import annotations

from typing import ClassVar, Mapping

import numpy as np

from pathzoo.core import Budget, Param, PlanResult, ProgressCallback, Scenario
from pathzoo_baselines.base import BaselinePlanner
from pathzoo_baselines.params import ENCODING_PARAMS
from pathzoo_baselines.search import seeded_global_random

__all__ = ["PsoPlanner"]


class PsoPlanner(BaselinePlanner):
    """Global-best PSO (Kennedy & Eberhart 1995, inertia weight of Shi & Eberhart 1998) over waypoint paths.

    Each particle is a candidate path in the shared continuous encoding
    (:mod:`pathzoo_baselines.waypoints`) and its cost is the penalised length
    of :mod:`pathzoo_baselines.cost`. The update is pyswarms' star topology::

        v <- w v + c1 r1 (pbest - x) + c2 r2 (gbest - x),   x <- x + v

    with ``r1, r2 ~ U(0, 1)`` per dimension, velocities clamped to
    ``+-v_max * max(width, height)`` and positions clipped to the map
    (pyswarms' ``nearest`` boundary strategy). The defaults ``w = 0.7298``,
    ``c1 = c2 = 1.49618`` are Clerc's constriction values.

    pyswarms draws ``r1, r2`` and the initial velocities from ``numpy.random``;
    ``plan()`` seeds that global state from ``rng`` and restores it after
    (see :mod:`pathzoo_baselines.search`). See ``docs/planners/swarm.pso.md``.
    """

    id: ClassVar[str] = "swarm.pso"
    version: ClassVar[str] = "4"
    summary: ClassVar[str] = "Particle swarm optimisation (pyswarms) of K straight-segment waypoints, no graph search"
    preload: ClassVar[tuple[str, ...]] = ("pathzoo_baselines.pyswarms_backend",)
    requires: ClassVar[Mapping[str, str]] = {"pyswarms": "evo"}  # optional dependency -> extra
    params: ClassVar[Mapping[str, Param]] = {
        **ENCODING_PARAMS,
        "particles": Param(50, "swarm size", low=2, high=100_000),
        "w": Param(0.7298, "inertia weight", low=0.0, high=2.0),
        "c1": Param(1.49618, "cognitive coefficient (pull towards the particle's best)", low=0.0, high=5.0),
        "c2": Param(1.49618, "social coefficient (pull towards the swarm's best)", low=0.0, high=5.0),
        "v_max": Param(0.2, "velocity clamp, as a fraction of the larger map side", low=0.0, low_open=True, high=1.0),
    }

    def plan(
        self,
        scenario: Scenario,
        *,
        budget: Budget,
        rng: np.random.Generator,
        progress: ProgressCallback | None = None,
    ) -> PlanResult:
        """Run the swarm until the budget is spent; see the class docstring."""
        encoding, search = self._start(scenario, budget, progress)
        from pathzoo_baselines.pyswarms_backend import BoundaryHandler, Star, VelocityHandler, compute_pbest, create_swarm

        bounds = (encoding.low, encoding.high)
        vmax = self.v_max * float(np.max(scenario.extent))
        clamp = (-vmax, vmax)
        options = {"w": self.w, "c1": self.c1, "c2": self.c2}
        init = search.initial(rng, self.particles)
        with seeded_global_random(rng):
            swarm = create_swarm(
                n_particles=self.particles, dimensions=encoding.n_genes, options=options,
                bounds=bounds, init_pos=init, clamp=clamp,
            )
            topology = Star()
            bh = BoundaryHandler(strategy="nearest")
            vh = VelocityHandler(strategy="unmodified")
            swarm.current_cost = search.evaluate(swarm.position)
            swarm.pbest_pos, swarm.pbest_cost = swarm.position.copy(), swarm.current_cost.copy()
            swarm.best_pos, swarm.best_cost = topology.compute_gbest(swarm)
            search.report()
            while not search.exhausted():
                swarm.velocity = topology.compute_velocity(swarm, clamp=clamp, vh=vh, bounds=bounds)
                swarm.position = topology.compute_position(swarm, bounds=bounds, bh=bh)
                swarm.current_cost = search.evaluate(swarm.position)
                swarm.pbest_pos, swarm.pbest_cost = compute_pbest(swarm)
                swarm.best_pos, swarm.best_cost = topology.compute_gbest(swarm)
                search.next_iteration()
        return search.result()
