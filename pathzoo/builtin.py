"""The ``core`` plugin: pathzoo's own metrics, registered like any third-party plugin."""

from __future__ import annotations

from typing import Sequence

from pathzoo.core.metric import Metric
from pathzoo.plugins.hookspecs import hookimpl

__all__ = ["pathzoo_register_metrics"]


@hookimpl
def pathzoo_register_metrics() -> Sequence[type[Metric]]:
    """Every built-in metric (see ``docs/metrics.md``)."""
    from pathzoo.metrics import BUILTIN_METRICS

    return BUILTIN_METRICS
