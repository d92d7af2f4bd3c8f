"""Scenarios and planners by registered id: what the installed plugins provide, built or loaded.

These are the package's public :func:`pathzoo.load_scenario`,
:func:`pathzoo.load_scenarios`, :func:`pathzoo.make_planner` and
:func:`pathzoo.list_plugins`; they live here, on the plugin layer, so that
the harness, the conformance kit and the analysis can use them without
importing the package's top-level interface (``docs/layers.md``).
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    from pathzoo.core.planner import Planner
    from pathzoo.core.scenario import Scenario
    from pathzoo.plugins.entries import PluginEntry

__all__ = ["list_plugins", "load_scenario", "load_scenarios", "make_planner"]


def load_scenario(id_or_path: str | Path) -> Scenario:
    """Load one scenario by registered id or from a file.

    Parameters
    ----------
    id_or_path : str or path
        A registered id such as ``"gant.fig7"`` (see ``pathzoo list
        scenarios``), or a scenario TOML file.

    Raises
    ------
    UnknownPluginError
        No scenario is registered under that id.
    InvalidScenarioError
        The file is malformed; the message names the file and field.
    """
    from pathzoo.core.errors import UnknownPluginError
    from pathzoo.io.paths import looks_like_path

    text = str(id_or_path)
    if isinstance(id_or_path, Path) or looks_like_path(text):
        from pathzoo.io import load_scenario_file

        return load_scenario_file(Path(text))
    from pathzoo.plugins.manager import get_registry

    try:
        entry = get_registry().get("scenarios", text)
    except UnknownPluginError as exc:
        raise UnknownPluginError(f"{exc} (and no file named '{text}' exists)") from None
    return entry.obj.load()


def load_scenarios(path: str | Path) -> list[Scenario]:
    """Load every scenario a file describes.

    A ``.scen`` file gives one scenario per problem line (with its optimal
    length as ``reference_length``); a scenario TOML gives one; a glob pattern
    of registered ids (``"movingai.arena.*"``) gives every match.
    """
    from pathzoo.io.paths import looks_like_path

    text = str(path)
    if isinstance(path, Path) or looks_like_path(text):
        from pathzoo.io import load_scenario_files

        return load_scenario_files(Path(text))
    from pathzoo.plugins.manager import get_registry

    reg = get_registry()
    return [reg.get("scenarios", sid).obj.load() for sid in reg.match("scenarios", text)]


def make_planner(planner_id: str, **params: Any) -> Planner:
    """Build a registered planner; parameters are validated now.

    Raises
    ------
    UnknownPluginError
        No planner is registered under ``planner_id``.
    InvalidParameterError
        A parameter is unknown or out of range.
    """
    from pathzoo.plugins.manager import get_registry

    cls = get_registry().get("planners", planner_id).obj
    return cls(**params)


def list_plugins(kind: str = "planners") -> list[PluginEntry]:
    """Entries of one kind (``planners``, ``scenarios`` or ``metrics``), sorted by id."""
    from pathzoo.plugins.manager import get_registry

    table = get_registry().table(kind)  # type: ignore[arg-type]
    return [table[k] for k in sorted(table)]
