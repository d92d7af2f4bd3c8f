"""Notice a planner that rebinds module attributes (monkeypatching) in its worker process.

:func:`module_fingerprint` records the identity of the code-like attributes
(modules, classes, functions, builtins, methods and descriptors) and float
constants of every loaded module, and of the classes those modules define.
:func:`changed_names` compares a later state with it: an attribute that was
there before and now is another object (``time.perf_counter = fake``,
``GridGraph.neighbours = fake``), or a module replaced in ``sys.modules``,
means the process can no longer be trusted to run another planner. New
attributes and new modules (lazy imports, numba caches), and attributes that
held ``None`` or plain data objects (lazily set globals, lazy-import proxies,
counters) are not tracked, since libraries rebind those themselves.

The executors act on it: the process executor retires such a worker and
starts a fresh one, the Dask executor restarts it, so no planner's patch can
reach a later run. A false alarm (a library that rebinds one of its own
globals) costs a worker restart, never a result.
"""

from __future__ import annotations

import functools
import sys
import types
from typing import Any

__all__ = ["module_fingerprint", "changed_names"]

Fingerprint = dict[tuple[str, str], int]


def _attributes(obj: Any) -> dict[str, Any]:
    try:
        return dict(vars(obj))
    except TypeError:
        return {}


_TRACKED = (types.ModuleType, type, types.FunctionType, types.BuiltinFunctionType, types.MethodType,
            types.MethodDescriptorType, types.WrapperDescriptorType, staticmethod, classmethod, property,
            functools.partial, functools.cached_property, float)


def module_fingerprint() -> Fingerprint:
    """``{(module, attribute): id(value)}`` over every loaded module and the classes it defines."""
    out: Fingerprint = {}
    for name, module in list(sys.modules.items()):
        if module is None:
            continue
        out[("sys.modules", name)] = id(module)
        for attr, value in _attributes(module).items():
            if not issubclass(type(value), _TRACKED):  # type(), not isinstance: proxies fake __class__
                continue
            out[(name, attr)] = id(value)
            if isinstance(value, type) and getattr(value, "__module__", None) == name:
                prefix = f"{name}.{attr}"
                for cattr, cvalue in _attributes(value).items():
                    if issubclass(type(cvalue), _TRACKED):
                        out[(prefix, cattr)] = id(cvalue)
    return out


def changed_names(before: Fingerprint, limit: int = 5) -> list[str]:
    """Up to ``limit`` ``"module.attribute"`` names whose object changed since ``before``."""
    after = module_fingerprint()
    changed = []
    for key, ident in before.items():
        if key in after and after[key] != ident:
            changed.append(f"{key[0]}.{key[1]}" if key[0] != "sys.modules" else f"sys.modules[{key[1]!r}]")
            if len(changed) >= limit:
                break
    return changed
