"""The ``scenarios`` plugin: every bundled scenario pack (see ``docs/scenarios.md``) and the papers' tables."""

from __future__ import annotations

from pathlib import Path
from typing import Mapping, Sequence

from pathzoo.plugins.entries import ScenarioEntry
from pathzoo.plugins.hookspecs import hookimpl

__all__ = ["pathzoo_register_scenarios", "pathzoo_paper_tables", "PACKS"]

PACKS: tuple[str, ...] = ("gant", "dsaco", "iaca", "fgdaco", "ggaco", "movingai")
"""The pack modules of :mod:`pathzoo_scenarios`, in listing order."""


@hookimpl
def pathzoo_register_scenarios() -> Sequence[ScenarioEntry]:
    """Every scenario of every pack, as lazily loaded entries."""
    from importlib import import_module

    entries: list[ScenarioEntry] = []
    for pack in PACKS:
        entries.extend(import_module(f"pathzoo_scenarios.{pack}").entries())
    return entries


@hookimpl
def pathzoo_paper_tables() -> Mapping[str, Path]:
    """The data file of each paper's comparison table: ``papers/<name>.toml`` beside this module."""
    return {file.stem: file for file in sorted((Path(__file__).resolve().parent / "papers").glob("*.toml"))}
