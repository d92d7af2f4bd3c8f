"""Registry entries: what ``pathzoo list`` shows for each planner, scenario and metric."""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Callable

from pathzoo.plugins.requirements import install_hint, missing_modules

if TYPE_CHECKING:
    from pathzoo.core.scenario import Scenario

__all__ = ["ScenarioEntry", "PluginEntry", "PluginFailure"]


@dataclass(frozen=True)
class ScenarioEntry:
    """A scenario that can be loaded by id without loading it up front.

    Parameters
    ----------
    id : str
        Scenario id, e.g. ``"gant.fig7"``.
    summary : str
        One line for ``pathzoo list scenarios``.
    load : callable
        Zero-argument function returning the :class:`~pathzoo.core.scenario.Scenario`.
        It must be picklable (a module-level function or a ``functools.partial``
        of one), because worker processes load scenarios themselves.
    kind : str
        Scenario kind, shown in listings.
    """

    id: str
    summary: str
    load: Callable[[], "Scenario"]
    kind: str = ""


@dataclass(frozen=True)
class PluginEntry:
    """One registered object with its provenance."""

    id: str
    summary: str
    obj: Any
    plugin: str
    distribution: str
    version: str

    @property
    def missing(self) -> dict[str, str]:
        """Optional modules the object needs that are not installed, with their extras."""
        return missing_modules(self.obj)

    @property
    def unavailable(self) -> str:
        """Why the object cannot be used here (``needs pyswarms: pip install "pathzoo[evo]"``), or ``""``."""
        missing = self.missing
        if not missing:
            return ""
        return f"needs {', '.join(sorted(missing))}: {install_hint(missing, self.distribution)}"


@dataclass(frozen=True)
class PluginFailure:
    """A plugin that could not be loaded, or an id that clashed."""

    plugin: str
    distribution: str
    error: str
