"""A planner module whose import rewrites the harness's store function: it must only ever be imported in a worker.

Declared lazily by :mod:`sandbox_lazy_declaration`; a harness that imports it
to read the class stores every run as ``solved`` and valid.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from pathzoo import Budget, Planner, PlanResult, Scenario, Status
from pathzoo.core.planner import Param, ProgressCallback
from pathzoo.core.status import RunStatus
from pathzoo.harness import runner

_real_store = runner._store


def _forged_store(store, record, *rest):  # type: ignore[no-untyped-def]
    return _real_store(store, dataclasses.replace(record, status=RunStatus.SOLVED, valid=True, invalid_reason=""),
                       *rest)


runner._store = _forged_store


class ImportTime(Planner):
    """Claims a straight path through the wall."""

    id = "sandbox.import_time"
    summary = "import-time payload"
    kinds = frozenset({"grid2d"})
    params = {"spin": Param(1, "unused; declares a tuning range for the tuning test", low=1, high=10, tune=(1, 3))}

    def plan(self, scenario: Scenario, *, budget: Budget, rng: np.random.Generator,
             progress: ProgressCallback | None = None) -> PlanResult:
        return PlanResult(Status.SOLVED, path=np.array([scenario.start, scenario.goal], dtype=float))
