"""Frozen result types: what a planner returns and what the harness records."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any, Mapping

import numpy as np

from pathzoo.core.budget import CLOCK_STOPS
from pathzoo.core.status import RunStatus, Status

__all__ = ["PlanResult", "HistoryPoint", "RunRecord"]


@dataclass(frozen=True, init=False)
class PlanResult:
    """A planner's answer.

    Parameters
    ----------
    status : Status
        Whether the planner believes it solved the problem.
    path : ndarray of shape (N, d), optional
        Waypoints in world coordinates (metres). ``d`` is 2 for ``grid2d``,
        ``terrain`` and ``dynamic`` scenarios (elevation is implied by the DEM)
        and 3 for ``air3d``. Required when ``status`` is ``SOLVED``.
    times : ndarray of shape (N,), optional
        Arrival time at each waypoint (seconds, starting at 0). Only meaningful
        on ``dynamic`` scenarios, where it lets a planner wait. When omitted the
        harness assumes the vehicle drives at cruise speed without stopping.
    iterations : int
        Iterations the planner used.
    evaluations : int
        Candidate evaluations the planner used.
    message : str
        Free-form note (why it failed, ...).
    extras : Mapping
        JSON-serialisable extra information. Never used for metrics.
    """

    status: Status
    path: np.ndarray | None = None
    times: np.ndarray | None = None
    iterations: int = 0
    evaluations: int = 0
    message: str = ""
    extras: Mapping[str, Any] = field(default_factory=dict)

    def __init__(
        self,
        status: Status,
        path: np.ndarray | None = None,
        times: np.ndarray | None = None,
        iterations: int = 0,
        evaluations: int = 0,
        message: str = "",
        extras: Mapping[str, Any] | None = None,
    ) -> None:
        # The fields go straight into the instance's dict: a frozen dataclass's generated
        # ``__init__`` sets each through ``object.__setattr__``, about 1 us per result, as
        # long as a whole search on a small map. ``extras=None`` gives a new empty dict.
        fields = self.__dict__
        fields["status"] = status
        fields["path"] = path
        fields["times"] = times
        fields["iterations"] = iterations
        fields["evaluations"] = evaluations
        fields["message"] = message
        fields["extras"] = {} if extras is None else extras

    @property
    def solved(self) -> bool:
        """True when the planner claims a solution."""
        return self.status is Status.SOLVED


@dataclass(frozen=True)
class HistoryPoint:
    """One point of a convergence curve, timed by the harness."""

    iteration: int
    evaluations: int
    best_cost: float
    time_s: float


@dataclass(frozen=True)
class RunRecord:
    """Everything the harness stores about one run.

    The metrics are computed by the harness from ``path``; planners never
    report their own length, energy or turns.
    """

    run_key: str
    experiment: str
    planner_id: str
    planner_version: str
    params: Mapping[str, Any]
    params_hash: str
    scenario_id: str
    seed_index: int
    seed: int
    status: RunStatus
    valid: bool
    invalid_reason: str
    message: str
    wall_time_s: float
    cpu_time_s: float
    iterations: int
    evaluations: int
    path: np.ndarray | None
    times: np.ndarray | None
    history: tuple[HistoryPoint, ...]
    metrics: Mapping[str, float]
    versions: Mapping[str, str]
    started_at: str
    isolated: bool = True
    """False when the planner ran in the harness's own process (the ``inline`` executor), for debugging only."""
    sandboxed: bool = False
    """True when the planner ran in an OS sandbox (``docs/sandbox.md``)."""
    stopped_by: str = "none"
    """The limit that ended the run (:data:`pathzoo.core.budget.STOP_REASONS`, ``"none"`` when the planner
    finished by itself; a timeout is ``"wall_time"``). A clock stop makes the result machine-dependent."""

    @property
    def machine_dependent(self) -> bool:
        """True when a clock ended the run (``stopped_by`` is ``cpu_time`` or ``wall_time``)."""
        return self.stopped_by in CLOCK_STOPS

    @property
    def success(self) -> bool:
        """True when the harness validated a solved path."""
        return self.status is RunStatus.SOLVED and self.valid
