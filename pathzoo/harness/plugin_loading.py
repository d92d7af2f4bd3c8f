"""Plugin modules registered by hand in the parent, registered again in a worker or judge process."""

from __future__ import annotations

import contextlib
import importlib
import io
import threading
from typing import Any

__all__ = ["ensure_plugins", "quiet_registry"]

_plugin_lock = threading.Lock()


def ensure_plugins(modules: tuple[tuple[str, str], ...], *, missing_ok: bool = False) -> None:
    """Import and register plugin modules the parent had registered by hand (idempotent).

    With ``missing_ok`` a module that cannot be imported here (e.g. one made
    at run time in the parent's ``__main__``) is skipped: the judge needs only
    the scenario and metric plugins, and fails later, naming what is missing,
    if one of those was in it.
    """
    registry = quiet_registry()
    with _plugin_lock:
        for name, module in modules:
            if registry.pm.get_plugin(name) is None:
                try:
                    registry.add_plugin(importlib.import_module(module), name)
                except ImportError:
                    if not missing_ok:
                        raise


def quiet_registry() -> Any:
    """The registry, discovered without repeating the parent's plugin warnings on stderr."""
    from pathzoo.plugins.manager import get_registry

    with contextlib.redirect_stderr(io.StringIO()):
        return get_registry()
