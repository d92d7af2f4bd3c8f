"""Base class of the metaheuristic baselines: scenario kinds, the hybrid flag, heavy imports done when a planner is built."""

from __future__ import annotations

import importlib
import time
from typing import Any, ClassVar

from pathzoo.core import Budget, Planner, ProgressCallback, Scenario
from pathzoo_baselines.encodings import Encoding, make_encoding
from pathzoo_baselines.params import ALL_KINDS
from pathzoo_baselines.search import Search

__all__ = ["BaselinePlanner"]


class BaselinePlanner(Planner):
    """A metaheuristic baseline over the shared encodings.

    The pure configurations (``hybrid = False``, every kind) search over
    straight-segment encodings and run no graph search; the hybrids
    (:mod:`pathzoo_baselines.hybrids`, ``hybrid = True``) decode with A*
    routes and support ``grid2d`` and ``terrain`` only.

    Building a planner imports the libraries its ``plan()`` needs (listed in
    ``preload``) and the compiled kernels of the encodings, so that the
    harness, which builds the planner before it starts timing ``plan()``, does
    not charge the first run of each process with them. Listing plugins never
    builds planners and stays fast. A missing library is not an error here;
    ``plan()`` raises the ImportError.
    """

    kinds: ClassVar[frozenset[str]] = ALL_KINDS
    hybrid: ClassVar[bool] = False
    preload: ClassVar[tuple[str, ...]] = ()

    def __init__(self, **params: Any) -> None:
        super().__init__(**params)
        shared = (
            "pathzoo_baselines.waypoints", "pathzoo_baselines.gridpath", "pathzoo_baselines.routed",
            "pathzoo_baselines.cellpath", "pathzoo.rules",
        )
        for module in (*shared, *self.preload):
            try:
                importlib.import_module(module)
            except ImportError:
                pass

    def _start(self, scenario: Scenario, budget: Budget, progress: ProgressCallback | None) -> tuple[Encoding, Search]:
        """Check the scenario kind, build the encoding this planner's parameters ask for and start the search."""
        started = time.perf_counter()
        self.check_supports(scenario)
        encoding = make_encoding(scenario, self._values)  # counts against a time limit: it may search the graph
        return encoding, Search(scenario, encoding, budget, progress, started=started)
