"""Planning on a pathzoo scenario with OMPL 2.x geometric planners (nanobind bindings).

Problem
-------
The state space is ``RealVectorStateSpace(2)`` bounded by the map's extent
(x along columns, y along rows, metres), or ``RealVectorStateSpace(3)`` in
air volumes (z up). A state is valid when it lies in a free cell (voxel) of
:attr:`Scenario.blocked` (obstacles, missing elevation and weak soil). Motions are checked by :func:`segment_validator`, an OMPL
``MotionValidator`` making one compiled call per motion
(:mod:`pathzoo_ompl.checks`): the validator's closed-cell collision rule
and, on terrain, its slope limits (conservatively), so a motion OMPL accepts
is a segment the validator accepts, instead of OMPL's sampled discrete
check; in air volumes the check is the judge's voxel rule and the pitch limit
(:func:`~pathzoo_ompl.checks.motion_clear_3d`). The objective is path length
in the state space; on terrain the harness measures 3-D length. Turn limits are not modelled; a path breaking one is
rejected by the final check. ``range = 0`` means
:func:`pathzoo_ompl.planners.default_range`.

Budget
------
OMPL calls the termination condition once per step of its planning loop
(one tree extension, one roadmap sample, one BIT* queue step, one FMT*
sample or expansion). pathzoo counts these calls:

- ``iterations``: one iteration is ``iteration_steps`` steps; planning stops
  after ``iterations * iteration_steps`` steps;
- ``evaluations``: motion (segment) checks. When the limit is reached the
  validator refuses every further motion unchecked, so the count is never
  exceeded and no unchecked motion is ever accepted;
- ``cpu_s``, ``time_s``: read through the budget's clock
  (:meth:`~pathzoo.core.budget.BudgetClock.time_up`, set by the harness) at
  every step; they only stop the search (PRM* after its current roadmap
  search);
- no limit at all: :data:`DEFAULT_ITERATIONS` iterations (``Budget.or_default``); a clock-only
  budget lets every planner search until the clock.

With an iteration or evaluation limit a seed gives the same path; a clock
stop makes the amount of work, hence the path, depend on the machine.

Seeding, noise, convergence
---------------------------
``ompl.util.RNG.setSeed`` is set from the run's ``rng`` before any OMPL
object exists, which makes every OMPL sampler reproducible. OMPL's log level
is set to ``LOG_NONE`` during ``plan()`` and restored after. The
intermediate-solution callback of ``ProblemDefinition`` cannot be set from
Python with these bindings (no type caster for its ``std::function``), so
anytime planners (RRT*, Informed RRT*, BIT*) are polled: the termination
condition reads ``planner.bestCost()`` at every step and reports each
improvement. PRM* reports at geometrically spaced checkpoints (after 1, 2, 4,
... iterations) where the roadmap is searched. First-solution planners (RRT,
RRT-Connect, FMT*) report once, when they finish.

PRM*
----
OMPL's ``PRM::solve`` grows the roadmap in one thread while another looks
for solutions, and alternates growth with a random-bounce expansion on a
0.2 s timer, so its result depends on thread timing. pathzoo calls it once
with an always-true condition (which only inserts the start and goal as
milestones), then grows the roadmap with ``growRoadmap`` in the calling
thread, and takes the shortest start-goal path of the roadmap
(``PlannerData`` + SciPy's Dijkstra; every roadmap edge was checked by
:func:`segment_validator`).

Result
------
The path is the solution's states, from the exact start to the exact goal.
With ``simplify=True`` OMPL's ``PathSimplifier`` shortens it (its motions go
through the same validator); if the simplified path failed the final check,
the raw one is kept and ``extras['simplified']`` says so. The returned path
always passes :func:`~pathzoo.rules.validate_path`; otherwise
the status is ``FAILED`` with the validator's reason. Without an exact
solution (OMPL's approximate solutions are ignored) the status is ``FAILED``:
sampling-based planners cannot prove that no path exists.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, Callable

import numpy as np
from ompl import base as ob
from ompl import geometric as og
from ompl import util as ou
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import dijkstra

from pathzoo.core import Budget, BudgetClock, PlanResult, ProgressCallback, Scenario, Status
from pathzoo.rules import validate_path
from pathzoo_ompl.checks import CompiledChecks, entry_point, motion_clear, motion_clear_3d, point_free, point_free_3d

if TYPE_CHECKING:
    from pathzoo_ompl.planners import OmplPlanner

__all__ = ["DEFAULT_ITERATIONS", "compiled_checks", "segment_validator", "solve", "state_checker"]

_MOTION_CLEAR = entry_point(motion_clear)
_POINT_FREE = entry_point(point_free)
_MOTION_CLEAR_3D = entry_point(motion_clear_3d)
_POINT_FREE_3D = entry_point(point_free_3d)

DEFAULT_ITERATIONS = 200
"""Iterations (of ``iteration_steps`` steps) planned when the budget sets no limit at all; about 0.1-1.3 CPU s
for RRT*, PRM* and BIT* on the bundled 32-49-cell maps, the order of OMPL's own 1 s ``SimpleSetup.solve``."""


@dataclass
class _Run:
    """Counters and best cost of one ``plan()`` call, shared by the callbacks OMPL makes.

    OMPL calls :meth:`step` once per planner-loop step, so it reads plain
    attributes (limits are resolved once here). Motions are counted by the
    compiled motion check itself, in ``checks``; :meth:`spent` reads that
    count only when an evaluation limit is set (the compiled check already
    refuses every motion beyond it).
    """

    budget: Budget
    clock: BudgetClock
    steps_per_iteration: int
    progress: ProgressCallback | None
    checks: CompiledChecks
    steps: int = 0
    best: float = math.inf
    error: BaseException | None = None
    step_limit: float = field(init=False)
    motion_limited: bool = field(init=False)
    timed: bool = field(init=False)

    def __post_init__(self) -> None:
        b = self.budget
        self.step_limit = math.inf if b.iterations is None else b.iterations * self.steps_per_iteration
        self.motion_limited = b.evaluations is not None
        self.timed = b.timed

    @property
    def iteration(self) -> int:
        """Iterations begun so far (``ceil(steps / iteration_steps)``)."""
        return -(-self.steps // self.steps_per_iteration)

    @property
    def motions(self) -> int:
        """Motions checked so far."""
        return self.checks.motions

    def spent(self) -> bool:
        """True once a limit is reached (or a callback failed)."""
        return (
            self.steps >= self.step_limit
            or self.time_up()
            or self.error is not None
            or (self.budget.evaluations is not None and self.checks.motions >= self.budget.evaluations)
        )

    def time_up(self) -> bool:
        """True once a clock limit is spent."""
        return self.timed and self.clock.time_up() is not None

    def step(self) -> bool:
        """One termination-condition check: count a step and return False; True once spent."""
        if self.spent():
            return True
        self.steps += 1
        return False

    def improve(self, cost: float) -> None:
        """Report ``cost`` to the harness if it beats the best so far."""
        if cost < self.best:
            self.best = cost
            if self.progress is not None:
                self.progress(self.iteration, self.motions, cost)


def compiled_checks(scenario: Scenario, motion_limit: int | None = None) -> CompiledChecks:
    """The scenario's map (and, on terrain, elevation and slope limits) prepared for the compiled checks."""
    if scenario.kind == "air3d":
        return CompiledChecks(
            scenario.blocked, scenario.cell_size, motion_limit=motion_limit,
            vertical_cell_size=float(scenario.vertical_cell_size or 1.0),
            max_pitch_deg=scenario.vehicle.max_pitch_deg,
        )
    if scenario.kind != "terrain":
        return CompiledChecks(scenario.blocked, scenario.cell_size, motion_limit=motion_limit)
    v = scenario.vehicle
    return CompiledChecks(
        scenario.blocked, scenario.cell_size, scenario.elevation, v.max_climb_deg, v.max_descent_deg, motion_limit
    )


def segment_validator(si: Any, checks: CompiledChecks) -> Any:
    """An OMPL ``MotionValidator`` applying the harness's segment rule and the evaluation budget.

    Each motion costs one compiled call,
    :func:`~pathzoo_ompl.checks.motion_clear`: it counts the motion in
    ``checks`` (refusing it unchecked once the limit is reached), then
    applies the validator's closed-cell rule and, on terrain, the slope
    limits (conservatively). The class is built here so that
    ``checkMotion`` reads the block's address from its closure: attribute
    lookups on an OMPL (nanobind) object cost about 0.09 µs each, a tenth of
    the whole check.

    Parameters
    ----------
    si : ompl.base.SpaceInformation
        The space information it validates for.
    checks : CompiledChecks
        The map and the motion counter; kept alive by the validator.
    """
    address = checks.address

    class SegmentValidator(ob.MotionValidator):
        """Motion validator calling :func:`~pathzoo_ompl.checks.motion_clear` on one map."""

        def checkMotion(self, s1: Any, s2: Any) -> bool:  # noqa: N802 (OMPL's name)
            """True when the straight segment ``s1 -> s2`` passes the validator's segment rule."""
            return _MOTION_CLEAR(address, s1[0], s1[1], s2[0], s2[1])

    class VoxelValidator(ob.MotionValidator):
        """Motion validator calling :func:`~pathzoo_ompl.checks.motion_clear_3d` on one volume."""

        def checkMotion(self, s1: Any, s2: Any) -> bool:  # noqa: N802 (OMPL's name)
            """True when the straight segment ``s1 -> s2`` passes the voxel rule and the pitch limit."""
            return _MOTION_CLEAR_3D(address, s1[0], s1[1], s1[2], s2[0], s2[1], s2[2])

    validator = (VoxelValidator if checks.dim == 3 else SegmentValidator)(si)
    validator.checks = checks  # keeps the arrays whose addresses the check reads alive
    return validator


def state_checker(checks: CompiledChecks) -> Callable[[Any], bool]:
    """OMPL state validity: inside the map and in a free cell (:func:`~pathzoo_ompl.checks.point_free`)."""
    address = checks.address

    def valid(state: Any) -> bool:
        return _POINT_FREE(address, state[0], state[1])

    def valid_3d(state: Any) -> bool:
        return _POINT_FREE_3D(address, state[0], state[1], state[2])

    if checks.dim == 3:
        valid_3d.checks = checks  # type: ignore[attr-defined]  # keeps the arrays alive
        return valid_3d

    valid.checks = checks  # type: ignore[attr-defined]  # keeps the arrays whose addresses the check reads alive
    return valid


def _states(si: Any, points: np.ndarray) -> list[Any]:
    out = []
    for p in points:
        s = si.allocState()
        for axis, value in enumerate(p):
            s[axis] = float(value)
        out.append(s)
    return out


def _coords(state: Any, dim: int) -> tuple[float, ...]:
    return tuple(state[axis] for axis in range(dim))


def _array(path: Any, dim: int) -> np.ndarray:
    states = (path.getState(i) for i in range(path.getStateCount()))
    return np.array([_coords(s, dim) for s in states], dtype=np.float64).reshape(-1, dim)


def _length(points: np.ndarray) -> float:
    return float(np.linalg.norm(np.diff(points, axis=0), axis=1).sum()) if len(points) > 1 else 0.0


def _roadmap_path(planner: Any, si: Any, dim: int) -> np.ndarray | None:
    """Shortest start-goal path in a PRM roadmap, or None when they are not connected."""
    data = ob.PlannerData(si)
    planner.getPlannerData(data)
    if data.numStartVertices() == 0 or data.numGoalVertices() == 0:
        return None
    n = data.numVertices()
    xy = np.array([_coords(data.getVertex(i).getState(), dim) for i in range(n)], dtype=np.float64)
    src, dst = [], []
    for i in range(n):
        targets = data.getEdges(i)
        src.extend([i] * len(targets))
        dst.extend(targets)
    if not src:
        return None
    src_a, dst_a = np.array(src), np.array(dst)
    weights = np.linalg.norm(xy[dst_a] - xy[src_a], axis=1)
    graph = csr_matrix((weights, (src_a, dst_a)), shape=(n, n))
    start, goal = data.getStartIndex(0), data.getGoalIndex(0)
    dist, pred = dijkstra(graph, indices=start, return_predecessors=True)
    if not math.isfinite(dist[goal]):
        return None
    nodes = [goal]
    while nodes[-1] != start:
        nodes.append(int(pred[nodes[-1]]))
    return xy[nodes[::-1]]


def _plan_prm(planner: Any, si: Any, run: _Run, dim: int) -> np.ndarray | None:
    """Grow a PRM* roadmap in this thread until the budget is spent, searching it at checkpoints."""
    planner.solve(ob.plannerAlwaysTerminatingCondition())  # only inserts start and goal milestones
    best: np.ndarray | None = None
    checkpoint = run.steps_per_iteration
    while True:
        target = checkpoint

        def stop() -> bool:
            return run.steps >= target or run.step()

        planner.growRoadmapPtc(ob.PlannerTerminationCondition(stop))
        found = _roadmap_path(planner, si, dim)
        if found is not None and _length(found) < run.best:
            best = found
            run.improve(_length(found))
        if run.spent():
            return best
        checkpoint *= 2


def _plan_tree(spec: "OmplPlanner", planner: Any, pdef: Any, run: _Run, dim: int) -> np.ndarray | None:
    """Run a tree or batch planner once until it finishes or the budget is spent."""

    def stop_anytime() -> bool:
        try:
            run.improve(planner.bestCost().value())
        except BaseException as exc:  # surfaced after solve(); OMPL must not swallow it
            run.error = exc
        return run.step()

    planner.solve(ob.PlannerTerminationCondition(stop_anytime if spec.anytime else run.step))
    if run.error is not None:
        raise run.error
    if not pdef.hasExactSolution():
        return None
    return _array(pdef.getSolutionPath(), dim)


def solve(
    spec: "OmplPlanner",
    scenario: Scenario,
    *,
    budget: Budget,
    rng: np.random.Generator,
    progress: ProgressCallback | None,
) -> PlanResult:
    """Plan with the OMPL planner ``spec`` describes; see the module docstring."""
    seed = int(rng.integers(1, 2**31 - 1))
    budget = budget.or_default(DEFAULT_ITERATIONS)
    run = _Run(budget, budget.start(), spec.iteration_steps, progress, compiled_checks(scenario, budget.evaluations))
    if np.array_equal(scenario.start, scenario.goal):
        run.improve(0.0)
        return PlanResult(Status.SOLVED, path=scenario.start[None, :].copy())
    level = ou.getLogLevel()
    ou.setLogLevel(ou.LogLevel.LOG_NONE)
    try:
        return _solve(spec, scenario, seed, run)
    finally:
        ou.setLogLevel(level)


def _solve(spec: "OmplPlanner", scenario: Scenario, seed: int, run: _Run) -> PlanResult:
    ou.RNG.setSeed(seed)
    dim = scenario.dim
    space = ob.RealVectorStateSpace(dim)
    bounds = ob.RealVectorBounds(dim)
    for axis, size in enumerate(scenario.extent):
        bounds.setLow(axis, 0.0)
        bounds.setHigh(axis, float(size))
    space.setBounds(bounds)
    si = ob.SpaceInformation(space)
    si.setStateValidityChecker(state_checker(run.checks))
    validator = segment_validator(si, run.checks)  # referenced here too for as long as OMPL plans
    si.setMotionValidator(validator)
    si.setup()
    pdef = ob.ProblemDefinition(si)
    start, goal = _states(si, np.stack([scenario.start, scenario.goal]))
    pdef.setStartAndGoalStates(start, goal)
    pdef.setOptimizationObjective(ob.PathLengthOptimizationObjective(si))
    planner = getattr(og, spec.ompl_class)(si)
    spec.configure(planner, scenario)
    planner.setProblemDefinition(pdef)
    planner.setup()

    if spec.ompl_class == "PRMstar":
        raw = _plan_prm(planner, si, run, dim)
    else:
        raw = _plan_tree(spec, planner, pdef, run, dim)
    extras: dict[str, Any] = {"ompl_planner": planner.getName(), "steps": run.steps, "motion_checks": run.motions}
    counts: dict[str, Any] = dict(iterations=run.iteration, evaluations=run.motions)
    if raw is None:
        return PlanResult(
            Status.FAILED, message="OMPL found no exact solution within the budget", extras=extras, **counts
        )
    run.improve(_length(raw))
    path = raw
    if spec.simplify:
        path, extras["simplified"] = _simplified(si, raw, scenario, run)
        run.improve(_length(path))
        counts["evaluations"] = run.motions
        extras["motion_checks"] = run.motions
    verdict = validate_path(scenario, path)
    if not verdict:
        return PlanResult(
            Status.FAILED, message=f"OMPL's path fails the harness's check: {verdict.reason}", extras=extras, **counts
        )
    return PlanResult(Status.SOLVED, path=path, extras=extras, **counts)


def _simplified(si: Any, raw: np.ndarray, scenario: Scenario, run: _Run) -> tuple[np.ndarray, bool]:
    """OMPL's PathSimplifier on ``raw``; the raw path is kept if the result fails the validator."""
    geometric = og.PathGeometric(si, _states(si, raw))
    og.PathSimplifier(si).simplify(geometric, ob.PlannerTerminationCondition(run.time_up))
    shorter = _array(geometric, scenario.dim)
    if validate_path(scenario, shorter):
        return shorter, True
    return raw, False
