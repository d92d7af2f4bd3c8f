"""Fixtures of the harness tests: the forged test plugin, registered in this process (and shipped to workers)."""

from __future__ import annotations

from types import ModuleType
from typing import Iterator

import pytest

from pathzoo.plugins.manager import get_registry, reset_registry

from . import forged as forged_module

PLUGIN_NAME = "forged-test"


@pytest.fixture(scope="package")
def forged() -> Iterator[ModuleType]:
    """The :mod:`forged` test plugin, registered for the harness tests, then forgotten with the registry."""
    registry = get_registry()
    added = registry.pm.get_plugin(PLUGIN_NAME) is None
    if added:
        registry.add_plugin(forged_module, PLUGIN_NAME)
    yield forged_module
    if added:  # later test packages see only the installed plugins
        reset_registry()
