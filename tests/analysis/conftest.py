"""Fixtures for the analysis tests: a registry holding only test metrics."""

from __future__ import annotations

import types

import pluggy
import pytest

import pathzoo
from pathzoo.core.metric import Metric
from pathzoo.plugins import manager


def _metric(mid: str, unit: str, direction: str) -> type[Metric]:
    def compute(self, scenario, record):  # pragma: no cover - never called
        return float("nan")

    return type(f"M_{mid}", (Metric,), dict(id=mid, unit=unit, direction=direction, summary=mid, compute=compute))


TEST_METRICS = [
    _metric("length", "m", "min"),
    _metric("energy", "J", "min"),
    _metric("turns", "1", "min"),
    _metric("planning_time", "s", "min"),
    _metric("success", "1", "max"),
]


@pytest.fixture(autouse=True)
def metric_registry(monkeypatch: pytest.MonkeyPatch) -> manager.Registry:
    """Replace the process registry by one with the test metrics only (others' plugins are not needed)."""
    plugin = types.SimpleNamespace(pathzoo_register_metrics=pathzoo.hookimpl(lambda: TEST_METRICS))
    reg = manager.Registry(pluggy.PluginManager("pathzoo"))
    reg.add_plugin(plugin, "test-metrics")
    monkeypatch.setattr(manager, "_registry", reg)
    return reg
