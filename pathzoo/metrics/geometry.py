"""Path geometry shared by the metrics: driven pieces, heading changes, clearance samples, travel.

Every function takes world coordinates in metres (see :mod:`pathzoo.core.scenario`)
and is exact for the piecewise-linear path the planner returned; the
definitions are collected in ``docs/metrics.md`` and ``docs/energy.md``.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from pathzoo.grid.paths import path_pieces
from pathzoo.metrics.path_memo import last_call

if TYPE_CHECKING:
    from pathzoo.core.scenario import Scenario
    from pathzoo.core.vehicle import VehicleModel

__all__ = [
    "TURN_EPS_RAD", "driven_pieces", "turn_angles", "clearance_samples", "travel_time_energy", "drive_time_energy",
]

TURN_EPS_RAD = 1e-6
"""Heading changes at or below this many radians are not turns."""


driven_pieces = last_call(path_pieces)
""":func:`pathzoo.grid.paths.path_pieces` (3-D lengths and slopes of the driven pieces), kept for the path being
judged (:mod:`~pathzoo.metrics.path_memo`; read-only arrays)."""


@last_call
def turn_angles(path: np.ndarray) -> np.ndarray:
    """Heading change (rad, in ``[0, π]``) at every waypoint joining two non-zero segments.

    The angle between the directions of consecutive segments, in the path's own
    dimension (the horizontal heading for ground paths, the 3-D angle for air
    paths); zero-length segments (repeated waypoints, waits) are skipped. The
    array is read-only: the metrics of one path share it (:mod:`~pathzoo.metrics.path_memo`).

    Examples
    --------
    >>> turn_angles(np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]))  # doctest: +ELLIPSIS
    array([1.5707...])
    """
    d = np.diff(np.asarray(path, dtype=np.float64), axis=0)
    norms = np.linalg.norm(d, axis=1) if len(d) else np.zeros(0)
    d = d[norms > 0]
    if len(d) < 2:
        return np.zeros(0)
    u = d / np.linalg.norm(d, axis=1, keepdims=True)
    a, b = u[:-1], u[1:]
    dot = np.einsum("ij,ij->i", a, b)
    if u.shape[1] == 2:
        cross = np.abs(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0])
    else:
        cross = np.linalg.norm(np.cross(a, b), axis=1)
    return np.arctan2(cross, dot)


@last_call
def clearance_samples(scenario: "Scenario", path: np.ndarray) -> np.ndarray:
    """Clearance (m) at points spaced evenly by arc length along the path (a read-only array).

    The path of 3-D length ``L`` (in the path's own coordinates) is sampled at
    ``n + 1`` points ``s_k = k L / n`` with ``n = max(1, ceil(2 L / c))`` and
    ``c`` the smallest cell size, i.e. at most half a cell apart, both ends
    included. Each sample takes the :attr:`Scenario.clearance` of the cell that
    contains it (no interpolation).
    """
    pts = np.asarray(path, dtype=np.float64)
    seg = np.linalg.norm(np.diff(pts, axis=0), axis=1) if len(pts) > 1 else np.zeros(0)
    cum = np.concatenate([[0.0], np.cumsum(seg)])
    total = float(cum[-1])
    n = max(1, math.ceil(2.0 * total / float(np.min(scenario.cell_sizes))))
    s = np.linspace(0.0, total, n + 1)
    samples = np.stack([np.interp(s, cum, pts[:, k]) for k in range(pts.shape[1])], axis=1)
    cells = scenario.cell_of(samples)
    cells = np.clip(cells, 0, np.array(scenario.shape) - 1)
    return scenario.clearance[tuple(cells.T)]


@last_call
def travel_time_energy(
    scenario: "Scenario", path: np.ndarray, times: np.ndarray | None = None
) -> tuple[float, float]:
    """Travel time (s) and energy (J) of driving a path with the scenario's vehicle.

    Untimed paths are driven at cruise speed ``v``, slowing down at each
    waypoint as :meth:`VehicleModel.turn_penalty` describes::

        T = Σ_pieces L / v + Σ_turns Δt(Δψ)
        E = Σ_pieces P(θ) L / v + Σ_turns ΔE(Δψ)

    with ``P(θ)`` eq. 4 of G-Ant (:meth:`VehicleModel.traction_power`). A timed
    path (``times`` given, e.g. with waits on a ``dynamic`` scenario) takes
    ``T = times[-1]``; traction energy depends only on the distance driven, so
    ``E = Σ (P(θ) - b) L / v + Σ_turns ½ m (v² - v_t²) + b T`` (the onboard load
    ``b`` is drawn for the whole mission). See ``docs/energy.md``.
    """
    pts = np.asarray(path, dtype=np.float64)
    lengths, slopes = driven_pieces(scenario, pts)
    return drive_time_energy(scenario.vehicle, lengths, slopes, turn_angles(pts), times)


def drive_time_energy(
    vehicle: "VehicleModel", lengths: np.ndarray, slopes: np.ndarray, turns: np.ndarray,
    times: np.ndarray | None = None,
) -> tuple[float, float]:
    """:func:`travel_time_energy` of a path given by its driven pieces and heading changes.

    ``lengths`` and ``slopes`` are :func:`driven_pieces`' of the path, ``turns``
    :func:`turn_angles`'; a caller that has them (a planner costing many
    paths) gets the same figures to the last bit without the path.
    """
    extra_t, extra_e = vehicle.turn_penalty(turns)
    drive_t = float(lengths.sum()) / vehicle.cruise_speed
    drive_e = float(vehicle.segment_energy(lengths, slopes).sum())
    if times is None:
        return drive_t + float(extra_t.sum()), drive_e + float(extra_e.sum())
    total_t = float(np.asarray(times, dtype=np.float64)[-1])
    b = vehicle.onboard_power_w
    kinetic = float(extra_e.sum()) - b * float(extra_t.sum())
    return total_t, drive_e - b * drive_t + kinetic + b * total_t
