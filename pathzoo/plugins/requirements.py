"""Optional dependencies of planners: which are missing, and the command that installs them.

A planner class that needs an optional package declares it as
``requires: ClassVar[Mapping[str, str]] = {"pyswarms": "evo"}`` (import name
to the extra of its distribution that installs it). The registry keeps such
a planner listed, but :func:`missing_modules` finds what is not installed
(without importing anything), ``pathzoo list planners`` shows the install
command, and an experiment that names the planner stops before running
anything (:meth:`pathzoo.harness.specs.PlannerSpec.of`).
"""

from __future__ import annotations

import importlib.util
import sys
from typing import Any, Mapping

__all__ = ["missing_modules", "install_hint"]


def _installed(module: str) -> bool:
    top = module.split(".")[0]
    if top in sys.modules:
        return sys.modules[top] is not None
    try:
        return importlib.util.find_spec(top) is not None
    except (ImportError, ValueError):
        return False


def missing_modules(obj: Any) -> dict[str, str]:
    """``{module: extra}`` of the modules ``obj.requires`` names that are not installed."""
    requires = getattr(obj, "requires", None)
    if not isinstance(requires, Mapping):
        return {}
    return {module: str(extra) for module, extra in requires.items() if not _installed(str(module))}


def install_hint(missing: Mapping[str, str], distribution: str = "") -> str:
    """``pip install "pathzoo[evo]"`` for the extras that provide ``missing``."""
    extras = ",".join(sorted({extra for extra in missing.values() if extra}))
    dist = distribution or "pathzoo"
    return f'pip install "{dist}[{extras}]"' if extras else f"pip install {' '.join(sorted(missing))}"
