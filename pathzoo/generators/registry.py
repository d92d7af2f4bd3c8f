"""The generator registry: name -> seeded, versioned function, and how a scenario file calls one."""

from __future__ import annotations

import inspect
from importlib import import_module
from dataclasses import dataclass
from typing import Any, Callable, Literal, Mapping

import numpy as np

from pathzoo.core.errors import InvalidScenarioError
from pathzoo.generators.checks import check_seed, relocated

__all__ = ["GeneratorInfo", "GENERATORS", "generate"]


@dataclass(frozen=True)
class GeneratorInfo:
    """One registered generator.

    Attributes
    ----------
    name : str
        What a scenario file writes as ``generator = "<name>"``.
    function : callable
        ``function(shape, seed, **params) -> ndarray``; deterministic in its arguments.
    version : int
        The module's ``GENERATOR_VERSION``.
    produces : {"occupancy", "elevation"}
        A boolean obstacle grid or an elevation grid in metres.
    """

    name: str
    function: Callable[..., np.ndarray]
    version: int
    produces: Literal["occupancy", "elevation"]

    @property
    def parameters(self) -> tuple[str, ...]:
        """Names a scenario file may set (``seed`` included; ``cell_size`` comes from the scenario)."""
        return tuple(p for p in inspect.signature(self.function).parameters if p != "cell_size")


def _info(name: str, module: str, function: str, produces: Literal["occupancy", "elevation"]) -> GeneratorInfo:
    mod = import_module(f"pathzoo.generators.{module}")
    return GeneratorInfo(name, getattr(mod, function), mod.GENERATOR_VERSION, produces)


GENERATORS: dict[str, GeneratorInfo] = {
    info.name: info
    for info in (
        _info("random", "random_field", "random_obstacles", "occupancy"),
        _info("rooms", "room_grid", "rooms", "occupancy"),
        _info("maze", "perfect_maze", "maze", "occupancy"),
        _info("fractal", "fractal", "fractal_terrain", "elevation"),
        _info("gaussian_peaks", "peak_terrain", "gaussian_peaks", "elevation"),
    )
}
"""Every generator by name."""


def generate(
    name: str,
    params: Mapping[str, Any],
    *,
    cell_size: float = 1.0,
    source: str | None = None,
    table: str = "map",
) -> tuple[np.ndarray, dict[str, Any]]:
    """Run a registered generator with parameters read from a scenario file.

    Parameters
    ----------
    name : str
        Registered generator name.
    params : mapping
        ``seed``, ``shape`` and the generator's own keywords.
    cell_size : float
        Passed to generators that take one (hills are placed in metres).
    source : str, optional
        The scenario file, for error messages.
    table : str
        The file's table holding the parameters, for error messages (``map.density``).

    Returns
    -------
    array : ndarray
        What the generator made.
    provenance : dict
        ``generator``, ``version``, ``seed`` and every parameter (defaults
        filled in), for ``Scenario.metadata``.

    Raises
    ------
    InvalidScenarioError
        Unknown generator or parameter, missing ``seed``/``shape``, or a bad
        value; the message names the file and ``table.parameter``.
    """
    info = GENERATORS.get(name)
    if info is None:
        raise InvalidScenarioError(
            f"unknown generator {name!r}; known: {', '.join(sorted(GENERATORS))}",
            source=source,
            field=f"{table}.generator",
        )
    unknown = sorted(set(params) - set(info.parameters))
    if unknown:
        raise InvalidScenarioError(
            f"unknown parameter for generator {name!r}; allowed: {', '.join(info.parameters)}",
            source=source,
            field=f"{table}.{unknown[0]}",
        )
    for required in ("seed", "shape"):
        if required not in params:
            raise InvalidScenarioError(f"generator {name!r} needs it", source=source, field=f"{table}.{required}")
    seed = check_seed(params["seed"], f"{table}.seed", source=source)
    kwargs = dict(params)
    if "cell_size" in inspect.signature(info.function).parameters:
        kwargs["cell_size"] = cell_size
    try:
        array = info.function(**kwargs)
    except InvalidScenarioError as exc:
        raise relocated(exc, source=source, field=f"{table}.{exc.field}") from None
    bound = inspect.signature(info.function).bind(**kwargs)
    bound.apply_defaults()
    settings = {k: v for k, v in bound.arguments.items() if k not in ("seed", "cell_size")}
    return array, {"generator": name, "version": info.version, "seed": seed, "params": settings}
