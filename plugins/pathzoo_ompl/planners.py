"""The OMPL planner classes ``ompl.<name>``: declarations only; ``plan()`` imports OMPL on first use."""

from __future__ import annotations

from typing import Any, ClassVar, Mapping

import numpy as np

from pathzoo.core import Budget, Param, Planner, PlanResult, ProgressCallback, Scenario

__all__ = [
    "OmplPlanner",
    "RRT",
    "RRTConnect",
    "RRTStar",
    "InformedRRTStar",
    "PRMStar",
    "BITStar",
    "FMTStar",
    "OMPL_PLANNERS",
    "DEFAULT_RANGE_CELLS",
    "default_range",
]



def _common(iteration_steps: int) -> dict[str, Param]:
    """The parameters every ``ompl.*`` planner has; ``iteration_steps`` defaults differ by planner."""
    return {
        "simplify": Param(
            False,
            "shorten the solution with OMPL's PathSimplifier (re-validated; off by default so the planner is "
            "compared as published)",
        ),
        "iteration_steps": Param(
            iteration_steps,
            "OMPL planner-loop steps (termination-condition checks) that make one pathzoo iteration",
            low=1,
            high=10**9,
        ),
    }

DEFAULT_RANGE_CELLS = 8.0
"""Longest default extension, in cells (see :func:`default_range`)."""

_RANGE = Param(
    0.0,
    "maximum extension length in metres; 0 = pathzoo's default: OMPL's 20% of the map's larger side, "
    f"capped at {DEFAULT_RANGE_CELLS:g} cells",
    low=0.0,
)


def default_range(scenario: Scenario) -> float:
    """The extension length ``range=0`` stands for: min(20 % of the larger map side, 8 cells), in metres.

    OMPL's own default (20 % of the space's largest extent) grows with the
    map, so on a 512 x 512 map every extension is about 100 cells long and
    almost none survives the walls of a map of small rooms. Capping it at
    :data:`DEFAULT_RANGE_CELLS` cells leaves maps up to 40 cells across
    unchanged and keeps extensions at the scale of corridors and rooms on
    large maps. The cap is one constant for every map, chosen from a sweep on
    ``8room_000`` (``docs/planners/ompl.md``), never tuned per map.
    """
    return min(0.2 * float(np.max(scenario.extent)), DEFAULT_RANGE_CELLS * float(scenario.cell_size))

_GOAL_BIAS = Param(0.05, "probability of sampling the goal", low=0.0, high=1.0)
_REWIRE = Param(
    1.1, "rewiring factor: multiplies the asymptotically optimal connection radius or k", low=0.0, low_open=True
)


class OmplPlanner(Planner):
    """Base of the ``ompl.*`` planners: an OMPL geometric planner in the continuous plane or air volume.

    Subclasses name the OMPL class (``ompl_class``), whether it improves its
    solution over time (``anytime``) and map their own parameters onto the
    OMPL object in :meth:`configure`. Everything else (state space, validity,
    the exact segment rule, budgets, seeding, convergence reports,
    simplification, the final check) lives in :mod:`pathzoo_ompl.engine`;
    ``docs/planners/ompl.md`` describes it. Building a planner imports OMPL
    (listing plugins does not), so timed ``plan()`` calls do not pay for it.
    """

    kinds: ClassVar[frozenset[str]] = frozenset({"grid2d", "terrain", "air3d"})
    path_model: ClassVar[str] = "anyangle"  # straight segments between sampled states (pathzoo.plugins.entries.PATH_MODELS)
    version: ClassVar[str] = "2"
    requires: ClassVar[Mapping[str, str]] = {"ompl": "ompl"}
    ompl_class: ClassVar[str] = ""
    anytime: ClassVar[bool] = False

    def __init__(self, **params: Any) -> None:
        super().__init__(**params)
        # import OMPL and compile the segment rule now: the harness builds planners before it times plan()
        try:
            import pathzoo_ompl.engine  # noqa: F401
        except ImportError:
            pass  # plan() raises it

    def configure(self, planner: Any, scenario: Scenario) -> None:
        """Apply this planner's parameters to the OMPL planner object (after construction, before setup)."""

    def plan(
        self,
        scenario: Scenario,
        *,
        budget: Budget,
        rng: np.random.Generator,
        progress: ProgressCallback | None = None,
    ) -> PlanResult:
        """Plan with OMPL; see :func:`pathzoo_ompl.engine.solve`."""
        self.check_supports(scenario)
        from pathzoo_ompl.engine import solve

        return solve(self, scenario, budget=budget, rng=rng, progress=progress)


class RRT(OmplPlanner):
    """RRT (LaValle 1998): a single tree grown towards random samples; stops at the first solution."""

    id: ClassVar[str] = "ompl.rrt"
    summary: ClassVar[str] = "OMPL RRT: rapidly-exploring random tree, first solution"
    ompl_class: ClassVar[str] = "RRT"
    params: ClassVar[Mapping[str, Param]] = {**_common(100), "range": _RANGE, "goal_bias": _GOAL_BIAS}

    def configure(self, planner: Any, scenario: Scenario) -> None:
        """Set range and goal bias."""
        planner.setRange(self.range if self.range > 0 else default_range(scenario))
        planner.setGoalBias(self.goal_bias)


class RRTConnect(OmplPlanner):
    """RRT-Connect (Kuffner & LaValle 2000): two trees grown towards each other; stops at the first solution."""

    id: ClassVar[str] = "ompl.rrtconnect"
    summary: ClassVar[str] = "OMPL RRT-Connect: bidirectional RRT, first solution"
    ompl_class: ClassVar[str] = "RRTConnect"
    params: ClassVar[Mapping[str, Param]] = {**_common(100), "range": _RANGE}

    def configure(self, planner: Any, scenario: Scenario) -> None:
        """Set range."""
        planner.setRange(self.range if self.range > 0 else default_range(scenario))


class RRTStar(OmplPlanner):
    """RRT* (Karaman & Frazzoli 2011): RRT with rewiring, asymptotically optimal, anytime."""

    id: ClassVar[str] = "ompl.rrtstar"
    summary: ClassVar[str] = "OMPL RRT*: asymptotically optimal RRT with rewiring (anytime)"
    ompl_class: ClassVar[str] = "RRTstar"
    anytime: ClassVar[bool] = True
    params: ClassVar[Mapping[str, Param]] = {
        **_common(50),
        "range": _RANGE,
        "goal_bias": _GOAL_BIAS,
        "rewire_factor": _REWIRE,
    }

    def configure(self, planner: Any, scenario: Scenario) -> None:
        """Set range, goal bias and rewiring factor."""
        planner.setRange(self.range if self.range > 0 else default_range(scenario))
        planner.setGoalBias(self.goal_bias)
        planner.setRewireFactor(self.rewire_factor)


class InformedRRTStar(RRTStar):
    """Informed RRT* (Gammell et al. 2014): RRT* sampling only the ellipse that can still improve the solution."""

    id: ClassVar[str] = "ompl.informed_rrtstar"
    summary: ClassVar[str] = "OMPL Informed RRT*: RRT* with ellipsoidal informed sampling (anytime)"
    ompl_class: ClassVar[str] = "InformedRRTstar"


class PRMStar(OmplPlanner):
    """PRM* (Karaman & Frazzoli 2011): a roadmap with k-nearest connections, k growing as e(1+1/d) log n.

    Only the roadmap's growth phase is used (OMPL's random-bounce expansion
    is timed, hence not reproducible), and the shortest start-goal path in
    the roadmap is extracted by Dijkstra; see ``docs/planners/ompl.md``.
    """

    id: ClassVar[str] = "ompl.prmstar"
    summary: ClassVar[str] = "OMPL PRM*: asymptotically optimal probabilistic roadmap (anytime)"
    ompl_class: ClassVar[str] = "PRMstar"
    anytime: ClassVar[bool] = True
    params: ClassVar[Mapping[str, Param]] = _common(25)


class BITStar(OmplPlanner):
    """BIT* (Gammell et al. 2015): batches of informed samples searched in order of estimated solution cost."""

    id: ClassVar[str] = "ompl.bitstar"
    summary: ClassVar[str] = "OMPL BIT*: batch informed trees (anytime)"
    ompl_class: ClassVar[str] = "BITstar"
    anytime: ClassVar[bool] = True
    params: ClassVar[Mapping[str, Param]] = {
        **_common(500),
        "samples_per_batch": Param(100, "samples added per batch", low=1, high=10**7),
        "rewire_factor": _REWIRE,
    }

    def configure(self, planner: Any, scenario: Scenario) -> None:
        """Set batch size and rewiring factor."""
        planner.setSamplesPerBatch(self.samples_per_batch)
        planner.setRewireFactor(self.rewire_factor)


class FMTStar(OmplPlanner):
    """FMT* (Janson et al. 2015): fast marching over a fixed batch of samples; one solution per run.

    OMPL's default extended mode adds samples when the first batch does not
    connect start and goal.
    """

    id: ClassVar[str] = "ompl.fmt"
    summary: ClassVar[str] = "OMPL FMT*: fast marching tree over a batch of samples"
    ompl_class: ClassVar[str] = "FMT"
    params: ClassVar[Mapping[str, Param]] = {
        **_common(1000),
        "num_samples": Param(1000, "samples in the batch", low=2, high=10**7),
        "radius_multiplier": Param(
            1.1, "multiplier of the asymptotically optimal connection radius", low=0.0, low_open=True
        ),
    }

    def configure(self, planner: Any, scenario: Scenario) -> None:
        """Set the number of samples, the radius multiplier and the free area (free cells x cell area)."""
        planner.setNumSamples(self.num_samples)
        free_cells = int(scenario.blocked.size - np.count_nonzero(scenario.blocked))
        planner.setFreeSpaceVolume(max(free_cells, 1) * scenario.cell_size**2)
        planner.setRadiusMultiplier(self.radius_multiplier)


OMPL_PLANNERS: tuple[type[OmplPlanner], ...] = (RRT, RRTConnect, RRTStar, InformedRRTStar, PRMStar, BITStar, FMTStar)
"""Every ``ompl.*`` planner, in the order ``pathzoo list`` shows them."""
