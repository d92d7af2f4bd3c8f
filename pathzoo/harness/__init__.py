"""The experiment harness: run planners x scenarios x seeds, validate, measure and store.

The public names are loaded lazily, so importing the package stays cheap:

- :class:`~pathzoo.harness.experiment.Experiment`,
  :class:`~pathzoo.harness.specs.PlannerSpec`;
- :func:`~pathzoo.harness.runner.run_experiment`;
- :func:`~pathzoo.harness.store.read_runs`, :func:`~pathzoo.harness.store.read_history`,
  :func:`~pathzoo.harness.store.read_path`, :func:`~pathzoo.harness.store.read_record`,
  :func:`~pathzoo.harness.store.read_experiments`,
  :class:`~pathzoo.harness.store_file.ResultsDatabaseError`;
- :func:`~pathzoo.rules.validate_path`.
"""

from __future__ import annotations

from pathzoo.lazy_names import lazy_getattr

__all__ = [
    "Experiment",
    "PlannerSpec",
    "ResultsDatabaseError",
    "read_experiments",
    "read_history",
    "read_path",
    "read_record",
    "read_runs",
    "run_experiment",
    "validate_path",
]

_WHERE = {
    "Experiment": "experiment",
    "PlannerSpec": "specs",
    "ResultsDatabaseError": "store_file",
    "read_experiments": "store",
    "read_history": "store",
    "read_path": "store",
    "read_record": "store",
    "read_runs": "store",
    "run_experiment": "runner",
    "validate_path": "pathzoo.rules",
}


__getattr__ = lazy_getattr(__name__, _WHERE)
