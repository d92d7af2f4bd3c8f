"""The Scenario: frozen map data plus the geometry queries planners and the harness share.

World coordinates
-----------------
All positions are in metres. The map's corner is the origin; ``x`` runs along
columns and ``y`` along rows (row 0 at the top of an image). The centre of cell
``(row, col)`` is ``((col + 0.5) * cell_size, (row + 0.5) * cell_size)``, so on
a 1 m grid the first cell's centre is ``(0.5, 0.5)``. Air volumes add ``z``:
voxel ``(layer, row, col)`` has centre height ``(layer + 0.5) * vertical_cell_size``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import cached_property
from typing import TYPE_CHECKING, Any, Literal, Mapping

import numpy as np

from pathzoo.core.errors import InvalidScenarioError
from pathzoo.core.moving import MovingObstacle
from pathzoo.core.rules import TerrainRules
from pathzoo.core.vehicle import VehicleModel

if TYPE_CHECKING:
    from pathzoo.grid.graph import GridGraph

__all__ = ["Scenario", "ScenarioKind", "SCENARIO_KINDS"]

ScenarioKind = Literal["grid2d", "terrain", "air3d", "dynamic"]
SCENARIO_KINDS: tuple[str, ...] = ("grid2d", "terrain", "air3d", "dynamic")


def _frozen_array(values: Any, dtype: type) -> np.ndarray:
    """A read-only array of ``dtype``; an array that is already one (and owns its data) is shared, not copied."""
    if isinstance(values, np.ndarray) and values.dtype == dtype and values.flags.owndata and not values.flags.writeable:
        return values
    arr: np.ndarray = np.array(values, dtype=dtype)
    arr.setflags(write=False)
    return arr


@dataclass(frozen=True, eq=False)
class Scenario:
    """One planning problem: a map, a start, a goal and a vehicle.

    Parameters
    ----------
    id : str
        Unique id, e.g. ``"movingai.arena.17"``.
    kind : {"grid2d", "terrain", "air3d", "dynamic"}
        What the map is.
    occupancy : ndarray of bool
        ``True`` for blocked cells; shape ``(H, W)``, or ``(L, H, W)`` for
        ``air3d``.
    cell_size : float
        Horizontal cell size in metres.
    start, goal : ndarray of shape (d,)
        World coordinates (``d`` = 3 for ``air3d``, 2 otherwise).
    vehicle : VehicleModel
        Speed, slope and turn limits and the power model.
    elevation : ndarray of shape (H, W), optional
        Ground height in metres at cell centres (``terrain``; optional ground
        for ``air3d``). NaN cells are blocked.
    rules : TerrainRules
        Slope weights and soil strength.
    moving_obstacles : tuple of MovingObstacle
        Only for ``dynamic`` scenarios.
    vertical_cell_size : float, optional
        Voxel height for ``air3d``.
    max_step : tuple of int, optional
        Air volumes: largest move in cells ``(horizontal, vertical)`` per
        step of the neighbourhood graph. Default ``(1, 1)``.
    reference_length : float, optional
        Known optimal length in metres (from a ``.scen`` file).
    description : str
        One line shown by ``pathzoo list scenarios``.
    metadata : Mapping
        Provenance: source files, pack version, how the map was made.
    """

    id: str
    kind: ScenarioKind
    occupancy: np.ndarray
    cell_size: float
    start: np.ndarray
    goal: np.ndarray
    vehicle: VehicleModel = field(default_factory=VehicleModel)
    elevation: np.ndarray | None = None
    rules: TerrainRules = field(default_factory=TerrainRules)
    moving_obstacles: tuple[MovingObstacle, ...] = ()
    vertical_cell_size: float | None = None
    max_step: tuple[int, int] = (1, 1)
    reference_length: float | None = None
    description: str = ""
    metadata: Mapping[str, Any] = field(default_factory=dict)

    # ------------------------------------------------------------------ checks
    def __post_init__(self) -> None:
        src = str(self.metadata.get("source", self.id))

        def bad(msg: str, fld: str) -> InvalidScenarioError:
            return InvalidScenarioError(msg, source=src, field=fld)

        if self.kind not in SCENARIO_KINDS:
            raise bad(f"unknown kind {self.kind!r}; allowed: {', '.join(SCENARIO_KINDS)}", "kind")
        if not isinstance(self.cell_size, (int, float)) or not math.isfinite(self.cell_size) or self.cell_size <= 0:
            raise bad(f"must be a positive number, got {self.cell_size!r}", "cell_size")
        occ = _frozen_array(self.occupancy, bool)
        want_ndim = 3 if self.kind == "air3d" else 2
        if occ.ndim != want_ndim or min(occ.shape, default=0) < 1:
            raise bad(f"must be a non-empty {want_ndim}-D array for kind {self.kind}, got shape {occ.shape}", "map")
        if self.kind == "air3d":
            vcs = self.vertical_cell_size
            if vcs is None or not math.isfinite(vcs) or vcs <= 0:
                raise bad(f"must be a positive number for air3d, got {vcs!r}", "vertical_cell_size")
            if len(self.max_step) != 2 or min(self.max_step) < 1:
                raise bad(f"must be two integers >= 1, got {self.max_step!r}", "max_step")
        elev = None
        if self.elevation is not None:
            elev = _frozen_array(self.elevation, np.float64)
            if elev.shape != occ.shape[-2:]:
                raise bad(f"shape {elev.shape} differs from the map {occ.shape[-2:]}", "elevation")
        elif self.kind == "terrain":
            raise bad("a terrain scenario needs an elevation grid", "elevation")
        if self.moving_obstacles and self.kind != "dynamic":
            raise bad("only 'dynamic' scenarios may have moving obstacles", "moving_obstacles")
        if self.reference_length is not None and not (self.reference_length >= 0):
            raise bad(f"must be >= 0, got {self.reference_length!r}", "reference_length")
        object.__setattr__(self, "occupancy", occ)
        object.__setattr__(self, "elevation", elev)
        object.__setattr__(self, "moving_obstacles", tuple(self.moving_obstacles))
        object.__setattr__(self, "max_step", tuple(int(s) for s in self.max_step))
        object.__setattr__(self, "metadata", dict(self.metadata))
        for name in ("start", "goal"):
            p = np.array(getattr(self, name), dtype=np.float64).reshape(-1)
            if p.shape != (self.dim,) or not np.isfinite(p).all():
                raise bad(f"must be {self.dim} finite coordinates, got {getattr(self, name)!r}", name)
            if not self.in_bounds(p[None, :])[0]:
                raise bad(f"{tuple(p.tolist())} lies outside the map (extent {tuple(self.extent.tolist())})", name)
            if self.blocked[tuple(self.cell_of(p[None, :])[0])]:
                raise bad(f"{tuple(p.tolist())} lies in an obstacle or untraversable cell", name)
            p.setflags(write=False)
            object.__setattr__(self, name, p)

    def __getstate__(self) -> dict[str, Any]:
        # cached geometry (graphs, clearance) is rebuilt, not shipped
        return {k: v for k, v in self.__dict__.items() if k in self.__dataclass_fields__}

    def __setstate__(self, state: dict[str, Any]) -> None:
        self.__dict__.update(state)

    # ------------------------------------------------------------- properties
    @property
    def dim(self) -> int:
        """Dimension of path coordinates: 3 for ``air3d``, else 2."""
        return 3 if self.kind == "air3d" else 2

    @property
    def shape(self) -> tuple[int, ...]:
        """Grid shape: ``(H, W)`` or ``(L, H, W)``."""
        return tuple(self.occupancy.shape)

    @property
    def cell_sizes(self) -> np.ndarray:
        """Per-axis cell size in world axis order (``x, y[, z]``)."""
        if self.kind == "air3d":
            return np.array([self.cell_size, self.cell_size, self.vertical_cell_size])
        return np.array([self.cell_size, self.cell_size])

    @property
    def extent(self) -> np.ndarray:
        """Map size in metres along ``x, y[, z]``."""
        return np.array(self.shape[::-1], dtype=np.float64) * self.cell_sizes

    @cached_property
    def blocked(self) -> np.ndarray:
        """Cells no vehicle may enter: obstacles, NaN elevation and too-weak soil."""
        b = self.occupancy.copy()
        if self.kind != "air3d":
            if self.elevation is not None:
                b |= ~np.isfinite(self.elevation)
            b |= self.rules.soil_blocked(b.shape)
        b.setflags(write=False)
        return b

    # ------------------------------------------------------------- conversions
    def in_bounds(self, points: np.ndarray) -> np.ndarray:
        """Whether each world point lies inside the map (closed on the low side)."""
        pts = np.asarray(points, dtype=np.float64).reshape(-1, self.dim)
        return np.all((pts >= 0) & (pts < self.extent), axis=1)

    def cell_of(self, points: np.ndarray) -> np.ndarray:
        """Grid index (``row, col`` or ``layer, row, col``) of world points, shape (N, ndim)."""
        pts = np.asarray(points, dtype=np.float64).reshape(-1, self.dim)
        idx = np.floor(pts / self.cell_sizes).astype(np.int64)
        return idx[:, ::-1]

    def node_of(self, points: np.ndarray) -> np.ndarray:
        """Flat node ids (row-major cell index) of world points."""
        return np.ravel_multi_index(tuple(self.cell_of(points).T), self.shape)

    def point_of(self, nodes: np.ndarray) -> np.ndarray:
        """World coordinates of node (cell) centres, shape (N, d)."""
        idx = np.stack(np.unravel_index(np.asarray(nodes, dtype=np.int64), self.shape), axis=-1)
        return (idx[:, ::-1].astype(np.float64) + 0.5) * self.cell_sizes

    @property
    def start_node(self) -> int:
        """Node id of the start cell."""
        return int(self.node_of(self.start)[0])

    @property
    def goal_node(self) -> int:
        """Node id of the goal cell."""
        return int(self.node_of(self.goal)[0])

    # ------------------------------------------------------------ geometry
    @cached_property
    def graph(self) -> "GridGraph":
        """Neighbourhood graph of the free cells, built once and shared (see :mod:`pathzoo.grid.graph`).

        Large graphs are kept on disk and memory-mapped by every process that
        needs them (:mod:`pathzoo.grid.graph_cache`).
        """
        from pathzoo.grid.graph_cache import cached_graph

        return cached_graph(self)

    @cached_property
    def clearance(self) -> np.ndarray:
        """Distance in metres from each cell centre to the nearest blocked cell centre.

        The map border counts as blocked (one ring of cells outside the map),
        so no cell has infinite clearance. For air volumes it is 3-D.
        """
        from pathzoo.grid.clearance import clearance_map

        return clearance_map(self.blocked, self.cell_sizes[::-1])

    def elevation_at(self, points: np.ndarray) -> np.ndarray:
        """Bilinear ground height at world points (0 where there is no DEM)."""
        from pathzoo.grid.terrain import bilinear_elevation

        pts = np.asarray(points, dtype=np.float64).reshape(-1, self.dim)
        if self.elevation is None:
            return np.zeros(len(pts))
        return bilinear_elevation(self.elevation, pts[:, :2] / self.cell_size)

    def is_free(self, points: np.ndarray, t: float | np.ndarray = 0.0) -> np.ndarray:
        """Whether world points are inside the map, in free cells and clear of moving obstacles at ``t``."""
        pts = np.asarray(points, dtype=np.float64).reshape(-1, self.dim)
        ok = self.in_bounds(pts)
        cells = self.cell_of(pts[ok])
        free = ok.copy()
        free[ok] = ~self.blocked[tuple(cells.T)]
        for ob in self.moving_obstacles:
            centres = ob.position(np.broadcast_to(np.asarray(t, dtype=np.float64), (len(pts),)))
            free &= np.linalg.norm(pts - centres, axis=1) >= ob.radius
        return free

    def segment_free(self, p0: np.ndarray, p1: np.ndarray, t0: float = 0.0, t1: float | None = None) -> bool:
        """Whether the validator would accept the straight segment on its own.

        Checks the closed-cell collision rule (no corner cutting), the slope
        limits on terrain, the pitch limit in air volumes and, for ``dynamic``
        scenarios, the moving obstacles while the vehicle leaves ``p0`` at
        ``t0`` and reaches ``p1`` at ``t1`` (default: at cruise speed). Turn
        limits involve two segments and are checked only on whole paths.
        """
        from pathzoo.rules import segment_problem

        return segment_problem(self, np.asarray(p0, float), np.asarray(p1, float), t0, t1) is None

    def with_endpoints(
        self,
        start: np.ndarray,
        goal: np.ndarray,
        *,
        id: str | None = None,
        reference_length: float | None = None,
        metadata: Mapping[str, Any] | None = None,
    ) -> "Scenario":
        """A copy with another start and goal (re-validated); map arrays, graph and clearance are shared.

        A known optimum belongs to its endpoints, so the copy's
        ``reference_length`` is the one given here (default: unknown), not the
        original's. ``metadata`` replaces the original's when given.
        """
        from dataclasses import replace

        new = replace(
            self,
            start=start,
            goal=goal,
            id=id or self.id,
            reference_length=reference_length,
            metadata=self.metadata if metadata is None else metadata,
        )
        for name in ("graph", "clearance", "blocked"):
            if name in self.__dict__:
                new.__dict__[name] = self.__dict__[name]
        return new
