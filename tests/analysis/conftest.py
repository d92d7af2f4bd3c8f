"""Fixtures for the analysis tests."""

from __future__ import annotations

from pathlib import Path

import pytest

import pathzoo
from pathzoo.core import Budget, Scenario
from pathzoo.testing import check_scenario


@pytest.fixture(scope="module")
def small_db(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, Scenario]:
    """A real results database: two exact planners x one tiny grid x three seeds (experiment "tiny")."""
    db = tmp_path_factory.mktemp("db") / "r.sqlite"
    sc = check_scenario("grid2d")
    pathzoo.run(["exact.dijkstra", "exact.astar"], [sc], seeds=3, db=db, budget=Budget(time_s=2.0),
                executor="inline", progress=False, experiment="tiny")
    return db, sc
