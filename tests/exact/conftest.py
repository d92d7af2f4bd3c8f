"""Fixtures of the exact planners' tests: the MovingAI problem lists, loaded once per session."""

from __future__ import annotations

from pathlib import Path
from typing import Callable

import pytest

from pathzoo.core import Scenario
from pathzoo.io import load_scenario_files


@pytest.fixture(scope="session")
def load_scen(shared_data: Path) -> Callable[[str], list[Scenario]]:
    """``load_scen("grid/dao/arena.map.scen")``: that file's problems as Scenarios (one shared graph per map)."""
    cache: dict[str, list[Scenario]] = {}

    def load(relative: str) -> list[Scenario]:
        if relative not in cache:
            cache[relative] = load_scenario_files(shared_data / "movingai" / relative)
        return cache[relative]

    return load
