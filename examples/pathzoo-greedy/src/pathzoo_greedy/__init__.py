"""pathzoo-greedy: an example third-party pathzoo plugin providing ``greedy.best_first``.

The planner class is imported on first access (``pathzoo_greedy.GreedyBestFirst``),
so importing the plugin module, as ``pathzoo list`` does, stays cheap.
"""

from __future__ import annotations

import importlib
from typing import Any

__all__ = ["GreedyBestFirst"]


def __getattr__(name: str) -> Any:
    if name == "GreedyBestFirst":
        return importlib.import_module("pathzoo_greedy.planner").GreedyBestFirst
    raise AttributeError(f"module 'pathzoo_greedy' has no attribute {name!r}")
