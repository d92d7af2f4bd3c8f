"""Module attributes imported on first use (PEP 562), for packages whose own import must stay light."""

from __future__ import annotations

import importlib
from typing import Any, Callable, Mapping

__all__ = ["lazy_getattr"]


def lazy_getattr(package: str, where: Mapping[str, str]) -> Callable[[str], Any]:
    """A module ``__getattr__`` that imports each name of ``where`` from its module when it is first asked for.

    Parameters
    ----------
    package : str
        The package the ``__getattr__`` is for, e.g. ``"pathzoo.io"``.
    where : mapping
        Attribute name to the module that defines it: a dotted name is
        absolute (``"pathzoo.rules"``), a plain one a module of ``package``
        (``"loader"`` for ``pathzoo.io.loader``).

    Examples
    --------
    In a package's ``__init__.py``::

        __getattr__ = lazy_getattr(__name__, {"read_map": "movingai"})
    """

    def __getattr__(name: str) -> Any:
        if name in where:
            module = where[name]
            return getattr(importlib.import_module(module if "." in module else f"{package}.{module}"), name)
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    return __getattr__
