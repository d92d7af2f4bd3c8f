"""The module named in the ``pathzoo`` entry-point group: it tells pathzoo what this package provides."""

from __future__ import annotations

from typing import Sequence

import pathzoo

from pathzoo_greedy.planner import GreedyBestFirst

__all__ = ["pathzoo_register_planners"]


@pathzoo.hookimpl
def pathzoo_register_planners() -> Sequence[type[pathzoo.Planner]]:
    """The planners of this plugin."""
    return [GreedyBestFirst]
