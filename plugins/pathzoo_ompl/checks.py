"""Compiled state and motion checks for OMPL: the judge's segment and slope rules as one numba call each.

OMPL calls a Python state checker once per state and a Python motion
validator once per motion (the ompl 2.x bindings take only Python
callables); everything such a call does beyond crossing into Python happens
here, in one compiled call:

- :func:`point_free`: the state lies inside the map, in a free cell;
- :func:`motion_clear`: :func:`segment_clear`, the closed-cell collision rule
  of :func:`pathzoo.grid.segments.segment_blocked_2d` (with its margin), on
  cell units (``tests/ompl/test_ompl_validator.py`` checks that it agrees
  with :func:`~pathzoo.rules.segment_problem`); then, on terrain,
  :func:`slopes_within`: the slope limits over the exact gradient range of
  the segment, :func:`pathzoo.grid.terrain.segment_slope_range`, the function
  the judge uses. It is conservative: a segment is refused when its slope
  comes within :data:`SLOPE_MARGIN_DEG` of a limit, so rounding can only make
  OMPL stricter than the judge, never laxer.
- in air volumes, :func:`point_free_3d` and :func:`motion_clear_3d`: the
  state lies in a free voxel; the motion touches no blocked voxel
  (:func:`pathzoo.grid.segments.segment_blocked_3d`, the judge's voxel rule,
  margin included) and pitches at most the vehicle's limit minus
  :data:`SLOPE_MARGIN_DEG`.

Why addresses and entry points
------------------------------
Calling a numba function from Python normally goes through its dispatcher,
which works out the argument types on every call, and then unboxes each
array. Per motion that costs as much as the collision check itself. So the
two functions OMPL's callbacks call are compiled once, eagerly, for one
signature of plain numbers: the address of a small int64 block holding
everything a check needs (the map's address and shape, the address of the
cell size and slope limits, the motion counter and its limit; arrays are
rebuilt inside the compiled code by :func:`numba.carray`), then the
coordinates. The callbacks call the compiled entry point directly
(:func:`entry_point`: ``dispatcher.overloads[signature].entry_point``),
skipping type dispatch. :class:`CompiledChecks` owns the block and every
array it points to, so they outlive every call made with its address. ``docs/planners/ompl.md``
("Speed") gives the measured costs; ``benchmarks/baselines.py --section ompl``
measures the resulting rate.
"""

from __future__ import annotations

import math
from typing import Any, Callable

import numba
import numpy as np
from numba import types
from numba.extending import intrinsic

from pathzoo.grid.segments import segment_blocked_2d, segment_blocked_3d
from pathzoo.grid.terrain import segment_slope_range

__all__ = [
    "SLOPE_MARGIN_DEG",
    "CompiledChecks",
    "entry_point",
    "motion_clear",
    "motion_clear_3d",
    "point_free",
    "point_free_3d",
    "segment_clear",
    "slopes_within",
]

SLOPE_MARGIN_DEG = 1e-6
"""Degrees by which a motion's slope must stay inside the vehicle's climb and descent limits."""


def _pointer_from_address(element: types.Type) -> Callable[..., Any]:
    """A numba intrinsic turning an integer address into a typed pointer (``inttoptr``)."""

    @intrinsic
    def pointer(typingctx: Any, address: types.Integer) -> Any:
        signature = types.CPointer(element)(types.intp)

        def codegen(context: Any, builder: Any, sig: Any, args: Any) -> Any:
            return builder.inttoptr(args[0], context.get_value_type(sig.return_type))

        return signature, codegen

    return pointer


_bool_pointer = _pointer_from_address(types.boolean)
_float_pointer = _pointer_from_address(types.float64)
_int_pointer = _pointer_from_address(types.int64)

# The int64 parameter block a callback passes by address: slot indices.
_MOTIONS, _MOTION_LIMIT, _BLOCKED, _ELEVATION, _ROWS, _COLS, _REALS, _LAYERS = range(8)
# The float64 block at address ``block[_REALS]``: slot indices.
_CELL_SIZE, _MAX_CLIMB, _MAX_DESCENT, _VERTICAL_CELL_SIZE, _MAX_PITCH = range(5)

_POINT = "boolean(intp, float64, float64)"
_MOTION = "boolean(intp, float64, float64, float64, float64)"
_POINT_3D = "boolean(intp, float64, float64, float64)"
_MOTION_3D = "boolean(intp, float64, float64, float64, float64, float64, float64)"


@numba.njit(_POINT, cache=True)
def point_free(block_address: int, x: float, y: float) -> bool:
    """True when world point ``(x, y)`` lies in a free cell of the map described at ``block_address``."""
    block = _int_pointer(block_address)
    cell_size = _float_pointer(block[_REALS])[_CELL_SIZE]
    rows, cols = block[_ROWS], block[_COLS]
    col, row = math.floor(x / cell_size), math.floor(y / cell_size)
    if row < 0 or row >= rows or col < 0 or col >= cols:
        return False
    return not numba.carray(_bool_pointer(block[_BLOCKED]), (rows, cols))[row, col]


@numba.njit(cache=True)
def segment_clear(blocked: np.ndarray, cell_size: float, x0: float, y0: float, x1: float, y1: float) -> bool:
    """The validator's closed-cell collision rule for a world-coordinate segment."""
    return not segment_blocked_2d(blocked, x0 / cell_size, y0 / cell_size, x1 / cell_size, y1 / cell_size)


@numba.njit(cache=True)
def slopes_within(
    elevation: np.ndarray,
    cell_size: float,
    max_climb_deg: float,
    max_descent_deg: float,
    x0: float,
    y0: float,
    x1: float,
    y1: float,
) -> bool:
    """The segment's exact gradient range lies within the limits minus :data:`SLOPE_MARGIN_DEG`."""
    g_lo, g_hi = segment_slope_range(elevation, x0 / cell_size, y0 / cell_size, x1 / cell_size, y1 / cell_size)
    if not (math.isfinite(g_lo) and math.isfinite(g_hi)):
        return False
    climb = math.degrees(math.atan2(g_hi, cell_size))
    descent = math.degrees(math.atan2(-g_lo, cell_size))
    return climb <= max_climb_deg - SLOPE_MARGIN_DEG and descent <= max_descent_deg - SLOPE_MARGIN_DEG


@numba.njit(_MOTION, cache=True)
def motion_clear(block_address: int, x0: float, y0: float, x1: float, y1: float) -> bool:
    """Count one motion and check it: :func:`segment_clear`, then on terrain :func:`slopes_within`.

    Once the block's motion count has reached its limit, the motion is
    refused unchecked and not counted.
    """
    block = _int_pointer(block_address)
    if block[_MOTIONS] >= block[_MOTION_LIMIT]:
        return False
    block[_MOTIONS] += 1
    reals = _float_pointer(block[_REALS])
    rows, cols, cell_size = block[_ROWS], block[_COLS], reals[_CELL_SIZE]
    if not segment_clear(numba.carray(_bool_pointer(block[_BLOCKED]), (rows, cols)), cell_size, x0, y0, x1, y1):
        return False
    if block[_ELEVATION] == 0:
        return True
    elevation = numba.carray(_float_pointer(block[_ELEVATION]), (rows, cols))
    return slopes_within(elevation, cell_size, reals[_MAX_CLIMB], reals[_MAX_DESCENT], x0, y0, x1, y1)


@numba.njit(_POINT_3D, cache=True)
def point_free_3d(block_address: int, x: float, y: float, z: float) -> bool:
    """True when world point ``(x, y, z)`` lies in a free voxel of the volume described at ``block_address``."""
    block = _int_pointer(block_address)
    reals = _float_pointer(block[_REALS])
    layers, rows, cols = block[_LAYERS], block[_ROWS], block[_COLS]
    col, row = math.floor(x / reals[_CELL_SIZE]), math.floor(y / reals[_CELL_SIZE])
    layer = math.floor(z / reals[_VERTICAL_CELL_SIZE])
    if row < 0 or row >= rows or col < 0 or col >= cols or layer < 0 or layer >= layers:
        return False
    return not numba.carray(_bool_pointer(block[_BLOCKED]), (layers, rows, cols))[layer, row, col]


@numba.njit(_MOTION_3D, cache=True)
def motion_clear_3d(block_address: int, x0: float, y0: float, z0: float, x1: float, y1: float, z1: float) -> bool:
    """Count one motion in an air volume and check it: the voxel rule, then the pitch limit (conservatively).

    Once the block's motion count has reached its limit, the motion is
    refused unchecked and not counted.
    """
    block = _int_pointer(block_address)
    if block[_MOTIONS] >= block[_MOTION_LIMIT]:
        return False
    block[_MOTIONS] += 1
    reals = _float_pointer(block[_REALS])
    horizontal = math.hypot(x1 - x0, y1 - y0)
    if math.degrees(math.atan2(abs(z1 - z0), horizontal)) > reals[_MAX_PITCH] - SLOPE_MARGIN_DEG:
        return False
    cs, vcs = reals[_CELL_SIZE], reals[_VERTICAL_CELL_SIZE]
    p0 = np.array([x0 / cs, y0 / cs, z0 / vcs])
    p1 = np.array([x1 / cs, y1 / cs, z1 / vcs])
    blocked = numba.carray(_bool_pointer(block[_BLOCKED]), (block[_LAYERS], block[_ROWS], block[_COLS]))
    return not segment_blocked_3d(blocked, p0, p1)


def entry_point(dispatcher: Any) -> Callable[..., bool]:
    """The compiled function behind an eagerly compiled ``dispatcher``'s only signature, called without type dispatch.

    Only for :func:`point_free` and :func:`motion_clear`, whose arguments are
    plain numbers: the entry point does not check its argument types.
    """
    (signature,) = dispatcher.signatures
    return dispatcher.overloads[signature].entry_point


_POINT_FREE = entry_point(point_free)
_MOTION_CLEAR = entry_point(motion_clear)
_POINT_FREE_3D = entry_point(point_free_3d)
_MOTION_CLEAR_3D = entry_point(motion_clear_3d)

_NO_LIMIT = np.iinfo(np.int64).max


class CompiledChecks:
    """One map prepared for :func:`point_free` and :func:`motion_clear`, and its motion counter.

    Everything the two compiled checks need sits in a small int64 block
    (motion count and limit, the addresses of the blocked and elevation
    arrays, the shape, the address of a float64 block with the cell size and
    slope limits), whose address :attr:`address` is the first argument of
    every check. This object keeps all those arrays alive, so the addresses
    stay valid as long as it lives; OMPL's callbacks
    (:mod:`pathzoo_ompl.engine`) hold a reference to it.

    Parameters
    ----------
    blocked : numpy.ndarray
        Blocked cells, shape ``(rows, cols)``, or voxels, shape ``(layers,
        rows, cols)``; stored as a contiguous bool array.
    cell_size : float
        Side of a cell, metres.
    elevation : numpy.ndarray, optional
        Elevation per cell, metres (terrain maps); stored as contiguous float64. Without it
        motions are not slope-checked.
    max_climb_deg, max_descent_deg : float
        Slope limits (used only with ``elevation``).
    motion_limit : int, optional
        Motions checked at most; every later motion is refused unchecked. None: no limit.
    vertical_cell_size, max_pitch_deg : float
        Voxel height and pitch limit (air volumes only).
    """

    def __init__(
        self,
        blocked: np.ndarray,
        cell_size: float,
        elevation: np.ndarray | None = None,
        max_climb_deg: float = 90.0,
        max_descent_deg: float = 90.0,
        motion_limit: int | None = None,
        vertical_cell_size: float = 1.0,
        max_pitch_deg: float = 90.0,
    ) -> None:
        self.blocked = np.ascontiguousarray(blocked, dtype=np.bool_)
        self.dim = self.blocked.ndim
        self.elevation = None if elevation is None else np.ascontiguousarray(elevation, dtype=np.float64)
        if self.elevation is not None and self.elevation.shape != self.blocked.shape:
            raise ValueError(f"elevation shape {self.elevation.shape} differs from the map's {self.blocked.shape}")
        self.reals = np.array([cell_size, max_climb_deg, max_descent_deg, vertical_cell_size, max_pitch_deg],
                              dtype=np.float64)
        self.block = np.zeros(8, dtype=np.int64)
        self.block[_MOTION_LIMIT] = _NO_LIMIT if motion_limit is None else motion_limit
        self.block[_BLOCKED] = self.blocked.ctypes.data
        self.block[_ELEVATION] = 0 if self.elevation is None else self.elevation.ctypes.data
        self.block[_ROWS], self.block[_COLS] = self.blocked.shape[-2:]
        self.block[_LAYERS] = self.blocked.shape[0] if self.dim == 3 else 1
        self.block[_REALS] = self.reals.ctypes.data
        self.address: int = int(self.block.ctypes.data)

    def __reduce__(self) -> Any:
        """Refuse to be pickled or copied: a copy would carry addresses of arrays it does not own."""
        raise TypeError("CompiledChecks holds memory addresses; build a new one instead of copying or pickling it")

    @property
    def motions(self) -> int:
        """Motions counted (checked) so far."""
        return int(self.block[_MOTIONS])

    def point(self, x: float, y: float) -> bool:
        """:func:`point_free` at world point ``(x, y)``."""
        return _POINT_FREE(self.address, x, y)

    def motion(self, x0: float, y0: float, x1: float, y1: float) -> bool:
        """:func:`motion_clear` for the world segment ``(x0, y0) -> (x1, y1)`` (counted)."""
        return _MOTION_CLEAR(self.address, x0, y0, x1, y1)

    def point_3d(self, x: float, y: float, z: float) -> bool:
        """:func:`point_free_3d` at world point ``(x, y, z)`` (air volumes)."""
        return _POINT_FREE_3D(self.address, x, y, z)

    def motion_3d(self, x0: float, y0: float, z0: float, x1: float, y1: float, z1: float) -> bool:
        """:func:`motion_clear_3d` for the world segment ``p0 -> p1`` (counted; air volumes)."""
        return _MOTION_CLEAR_3D(self.address, x0, y0, z0, x1, y1, z1)
