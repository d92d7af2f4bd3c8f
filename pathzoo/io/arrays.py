"""Safe loading of NumPy ``.npy``/``.npz`` arrays (never unpickling) and their checks as maps."""

from __future__ import annotations

import zipfile
from pathlib import Path
from typing import Literal

import numpy as np

from pathzoo.core.errors import InvalidScenarioError

__all__ = ["NodataPolicy", "load_array", "read_npz", "select_array", "as_occupancy", "as_elevation"]

NodataPolicy = Literal["error", "obstacle"]
"""What NaN or infinite elevation cells that no NODATA declaration explains mean."""


_NPY_MAGIC = b"\x93NUMPY"


def _open(path: Path) -> np.ndarray | np.lib.npyio.NpzFile:
    src = str(path)
    try:
        with path.open("rb") as fh:
            head = fh.read(len(_NPY_MAGIC))
    except OSError as exc:
        raise InvalidScenarioError(f"cannot read: {exc.strerror or exc}", source=src) from None
    if head[:1] == b"\x80":  # the opcode every pickle of protocol 2 or later starts with
        raise InvalidScenarioError(
            "holds pickled Python objects, which pathzoo never loads; save a plain numeric array", source=src
        )
    if head != _NPY_MAGIC and not zipfile.is_zipfile(path):
        raise InvalidScenarioError("not a NumPy file (neither an .npy array nor an .npz zip archive)", source=src)
    try:
        return np.load(path, allow_pickle=False)
    except (OSError, zipfile.BadZipFile) as exc:
        raise InvalidScenarioError(f"cannot read: {getattr(exc, 'strerror', None) or exc}", source=src) from None
    except ValueError as exc:
        if "pickle" in str(exc):
            raise InvalidScenarioError(
                "holds pickled Python objects, which pathzoo never loads; save a plain numeric array", source=src
            ) from None
        raise InvalidScenarioError(f"not a NumPy array file: {exc}", source=src) from None


def read_npz(path: str | Path) -> dict[str, np.ndarray]:
    """Every array of an ``.npz`` archive, loaded with ``allow_pickle=False``.

    Raises
    ------
    InvalidScenarioError
        Missing or unreadable file, not an archive, or pickled content (refused).
    """
    path = Path(path)
    src = str(path)
    loaded = _open(path)
    if not isinstance(loaded, np.lib.npyio.NpzFile):
        raise InvalidScenarioError("not an .npz archive", source=src)
    arrays: dict[str, np.ndarray] = {}
    with loaded:
        for name in loaded.files:
            try:
                arrays[name] = loaded[name]
            except ValueError as exc:  # object arrays inside the archive
                pickled = "pickle" in str(exc)
                what = "holds pickled Python objects, which pathzoo never loads" if pickled else f"is unreadable: {exc}"
                raise InvalidScenarioError(f"array {name!r} {what}", source=src, field=name) from None
            except zipfile.BadZipFile as exc:
                raise InvalidScenarioError(f"array {name!r} is unreadable: {exc}", source=src, field=name) from None
    return arrays


def select_array(arrays: dict[str, np.ndarray], key: str | None, *, source: str) -> tuple[str, np.ndarray]:
    """The array named ``key``, or the only array when ``key`` is ``None``."""
    names = sorted(arrays)
    if key is None:
        if len(names) != 1:
            raise InvalidScenarioError(f"holds arrays {names}; say which with 'key'", source=source, field="key")
        key = names[0]
    if key not in arrays:
        raise InvalidScenarioError(f"no array {key!r}; the archive holds {names}", source=source, field="key")
    return key, arrays[key]


def load_array(path: str | Path, *, key: str | None = None) -> np.ndarray:
    """Load one array from ``.npy`` or ``.npz``, with ``allow_pickle=False`` always.

    Parameters
    ----------
    path : path
        The file.
    key : str, optional
        Array name inside an ``.npz``; may be left out when the archive holds
        exactly one array. Not allowed for ``.npy``.

    Raises
    ------
    InvalidScenarioError
        Missing or unreadable file, pickled content (refused), unknown key.
    """
    path = Path(path)
    src = str(path)
    if path.suffix.lower() == ".npz":
        return select_array(read_npz(path), key, source=src)[1]
    if key is not None:
        raise InvalidScenarioError(f"'key' ({key!r}) applies to .npz files only", source=src, field="key")
    loaded = _open(path)
    if not isinstance(loaded, np.ndarray):
        loaded.close()
        raise InvalidScenarioError("is an .npz archive; name it .npz", source=src)
    return loaded


def as_occupancy(array: np.ndarray, *, ndim: int, source: str, field: str) -> np.ndarray:
    """Check an array as an obstacle grid: ``bool``, or integers that are all 0 or 1 (1 = blocked).

    Returns a read-only ``bool`` array. Floats are refused (a float grid is
    more likely an elevation put in the wrong place than an occupancy map).
    """
    if array.ndim != ndim or array.size == 0:
        raise InvalidScenarioError(
            f"must be a non-empty {ndim}-D array, got shape {array.shape}", source=source, field=field
        )
    if array.dtype == bool:
        occ = array.astype(bool, copy=True)
    elif array.dtype.kind in "iu":
        if not np.isin(array, (0, 1)).all():
            raise InvalidScenarioError(
                "integer occupancy must hold only 0 (free) and 1 (blocked)", source=source, field=field
            )
        occ = array.astype(bool)
    else:
        raise InvalidScenarioError(
            f"dtype {array.dtype} is not an occupancy grid; use bool or 0/1 integers", source=source, field=field
        )
    occ.setflags(write=False)
    return occ


def as_elevation(array: np.ndarray, *, nodata: NodataPolicy, source: str, field: str) -> np.ndarray:
    """Check an array as an elevation grid in metres: 2-D, integer or float.

    NaN or infinite cells are an error unless ``nodata == "obstacle"``, in
    which case they stay NaN and :attr:`Scenario.blocked` treats them as
    obstacles. Returns a read-only ``float64`` array.
    """
    if array.ndim != 2 or array.size == 0:
        raise InvalidScenarioError(
            f"must be a non-empty 2-D array, got shape {array.shape}", source=source, field=field
        )
    if array.dtype.kind not in "iuf":
        raise InvalidScenarioError(
            f"dtype {array.dtype} is not an elevation grid; use numbers", source=source, field=field
        )
    elev = array.astype(np.float64, copy=True)
    missing = ~np.isfinite(elev)
    if missing.any():
        if nodata != "obstacle":
            raise InvalidScenarioError(
                f"{int(missing.sum())} cells are NaN or infinite and no NODATA value declares them; "
                'set nodata = "obstacle" under [elevation] to treat them as obstacles',
                source=source,
                field=field,
            )
        elev[missing] = np.nan
    elev.setflags(write=False)
    return elev
