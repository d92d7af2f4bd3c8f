"""Fixtures of the harness tests: the forged test plugin, registered in this process (and shipped to workers)."""

from __future__ import annotations

from types import ModuleType

import pytest

from pathzoo.plugins.manager import get_registry

from . import forged as forged_module

PLUGIN_NAME = "forged-test"


@pytest.fixture(scope="session")
def forged() -> ModuleType:
    """The :mod:`forged` test plugin, registered once for the session."""
    registry = get_registry()
    if registry.pm.get_plugin(PLUGIN_NAME) is None:
        registry.add_plugin(forged_module, PLUGIN_NAME)
    return forged_module
