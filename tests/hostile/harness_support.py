"""Fixtures of the hostile harness tests (imported by each ``test_harness_*`` module; no conftest needed)."""

from __future__ import annotations

import importlib
import time
from types import ModuleType
from typing import Iterator

import psutil
import pytest

import harness_hostile
import pathzoo
from pathzoo.core.scenario import Scenario
from pathzoo.harness import Experiment
from pathzoo.plugins.manager import get_registry, reset_registry

PLUGIN_NAME = "hostile-harness-test"

_PATCHABLE = [*((m, "validate_path") for m in harness_hostile.validator_modules()),
              (time, "perf_counter"), (time, "process_time"), (Scenario, "graph"), (psutil.Process, "cpu_times"),
              *((module, name) for module in map(importlib.import_module, harness_hostile.CLOCK_HOLDERS)
                for name in ("_clock", "_cpu", "process_cpu_time") if name in module.__dict__)]


@pytest.fixture()
def hostile() -> Iterator[ModuleType]:
    """The hostile plugin registered in this process (and shipped to workers); whatever it patched here is undone."""
    saved = [(obj, name, obj.__dict__[name]) for obj, name in _PATCHABLE]
    registry = get_registry()
    if registry.pm.get_plugin(PLUGIN_NAME) is None:
        registry.add_plugin(harness_hostile, PLUGIN_NAME)
    yield harness_hostile
    for obj, name, value in saved:
        setattr(obj, name, value)
    reset_registry()


def experiment(planners: list, scenarios: list[str], *, seeds: int = 1, timeout_s: float = 30.0,
               name: str = "hostile") -> Experiment:
    """A small experiment bound by iterations."""
    return Experiment.build(planners=planners, scenarios=scenarios, seeds=seeds, name=name,
                            budget=pathzoo.Budget(iterations=5, time_s=5.0), timeout_s=timeout_s)

