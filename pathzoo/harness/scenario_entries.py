"""The scenario entries of an experiment resolved to scenarios: registered ids, glob patterns and files.

An entry is a registered id, a glob pattern of registered ids
(``"movingai.arena.*"``) or a file path (anything with a ``/`` or a scenario
file suffix; a relative path is relative to the experiment file). A
``.scen`` file gives all its problems; ``"maps/den312d.scen#12"`` the problem
at the 0-based index 12 only, and ``"maps/den312d.scen#den312d.1?"`` those
whose id (or index) matches the glob.
"""

from __future__ import annotations

import fnmatch
from pathlib import Path
from typing import Sequence

from pathzoo.core.errors import InvalidExperimentError
from pathzoo.core.scenario import Scenario
from pathzoo.harness.specs import ScenarioSpec
from pathzoo.io.paths import looks_like_path

__all__ = ["resolve_scenarios"]


def resolve_scenarios(
    items: Sequence["str | Path | Scenario | ScenarioSpec"], base: Path | None
) -> tuple[ScenarioSpec, ...]:
    """The distinct scenarios ``items`` name, in order; relative paths are relative to ``base``.

    Raises
    ------
    InvalidExperimentError
        No scenario at all, two different scenarios with one id, or a bad ``#`` selector.
    """
    from pathzoo.plugins.lookup import load_scenarios
    from pathzoo.plugins.manager import get_registry

    specs: dict[str, ScenarioSpec] = {}

    def add(spec: ScenarioSpec) -> None:
        prev = specs.get(spec.id)
        if prev is not None and prev.cache_key != spec.cache_key:
            raise InvalidExperimentError(f"two different scenarios share the id '{spec.id}'")
        specs.setdefault(spec.id, spec)

    if isinstance(items, (str, Path, Scenario, ScenarioSpec)):
        items = [items]
    for item in items:
        if isinstance(item, ScenarioSpec):
            add(item)
        elif isinstance(item, Scenario):
            add(ScenarioSpec.of_object(item))
        elif isinstance(item, Path) or (isinstance(item, str) and looks_like_path(item)):
            name, selector = _split_selector(item, base)
            path = Path(name).expanduser()
            if base is not None and not path.is_absolute():
                path = base / path
            location = str(path.resolve())
            if selector is not None and path.suffix.lower() != ".scen":
                raise InvalidExperimentError(f"{item}: '#' selects problems of a .scen file, and {path.name} is not one")
            found = load_scenarios(Path(location))
            for sc in found if selector is None else _select_problems(found, selector, str(item)):
                add(ScenarioSpec(sc.id, sc.kind, "file", location))
        elif isinstance(item, str):
            registry = get_registry()
            for sid in registry.match("scenarios", item):
                entry = registry.get("scenarios", sid)
                kind = getattr(entry.obj, "kind", "") or entry.obj.load().kind
                add(ScenarioSpec(sid, kind, "registry", sid))
        else:
            raise InvalidExperimentError(
                f"a scenario must be an id, a glob pattern, a path or a Scenario, got {item!r}"
            )
    if not specs:
        raise InvalidExperimentError("no scenarios given")
    return tuple(specs.values())


def _split_selector(item: "str | Path", base: Path | None) -> tuple["str | Path", str | None]:
    """``("maps/x.scen", "12")`` for ``"maps/x.scen#12"``; the item and None without a ``#`` selector.

    A ``#`` belongs to the file name when a file of the whole name exists.
    """
    if not isinstance(item, str) or "#" not in item:
        return item, None
    whole = Path(item).expanduser()
    if (whole if base is None or whole.is_absolute() else base / whole).exists():
        return item, None
    name, _, selector = item.rpartition("#")
    return name, selector


def _select_problems(scenarios: "list[Scenario]", selector: str, item: str) -> "list[Scenario]":
    """The problems of a ``.scen`` file that ``file.scen#<selector>`` names.

    ``selector`` is a 0-based problem index (``#12``: the 13th problem line
    after the ``version`` line) or a glob pattern matched against the
    scenario ids (``#den312d.1?``) and the indices (``#1?``).

    Raises
    ------
    InvalidExperimentError
        An index past the last problem, or a pattern that matches nothing.
    """
    if selector.isdigit():
        index = int(selector)
        if index >= len(scenarios):
            raise InvalidExperimentError(
                f"{item}: problem index {index} is past the last problem, {len(scenarios) - 1} (indices start at 0)"
            )
        return [scenarios[index]]
    chosen = [s for i, s in enumerate(scenarios)
              if fnmatch.fnmatchcase(s.id, selector) or fnmatch.fnmatchcase(str(i), selector)]
    if not chosen:
        raise InvalidExperimentError(
            f"{item}: no problem id or index matches '{selector}' (ids {scenarios[0].id} .. {scenarios[-1].id})"
        )
    return chosen
