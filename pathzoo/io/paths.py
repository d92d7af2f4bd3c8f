"""Telling a scenario file path from a registered scenario id."""

from __future__ import annotations

from pathlib import Path

__all__ = ["SCENARIO_FILE_SUFFIXES", "looks_like_path"]

SCENARIO_FILE_SUFFIXES = frozenset({".toml", ".map", ".scen", ".npy", ".npz", ".asc"})
"""File endings pathzoo reads scenarios from."""


def looks_like_path(text: str) -> bool:
    """Whether ``text`` names a file rather than a registered id.

    True when it contains a path separator, ends in a scenario file suffix or
    names an existing file. Registered ids are dotted words such as
    ``gant.fig7`` or ``movingai.arena.b15.150``, which none of these match.
    """
    return any(sep in text for sep in ("/", "\\")) or Path(text).suffix in SCENARIO_FILE_SUFFIXES or Path(text).exists()
