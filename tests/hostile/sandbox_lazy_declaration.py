"""Declares ``sandbox.import_time`` lazily: the harness reads this declaration, never the planner's module."""

from __future__ import annotations

from typing import Sequence

from pathzoo import hookimpl
from pathzoo.plugins.entries import LazyPlanner


@hookimpl
def pathzoo_register_planners() -> Sequence[LazyPlanner]:
    return [LazyPlanner("sandbox.import_time", "import-time payload", "sandbox_import_payload:ImportTime",
                        kinds=frozenset({"grid2d"}))]
