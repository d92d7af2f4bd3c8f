"""Compare two result databases run by run: the same experiment must store the same results, times aside.

Two runs of an experiment whose runs are ended by iteration or evaluation
limits store bit-identical results on any machine, executor and load
(``docs/timing.md``). :func:`compare_results` checks that: for every run key
of the experiment it compares what the planner's seed decides (status,
validity and its reason, counts, ``stopped_by``, the path and its times,
the convergence history's counts and costs, and every metric) and leaves out
only what a clock measures (wall and CPU times, the history's times and the
metrics computed from them) and the planner's free-text message. Floats are
compared exactly (NaN equals NaN). ``pathzoo compare A B`` runs it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["Comparison", "RunDifference", "compare_results", "measured_time_metrics"]

_FIELDS = ("planner_version", "params_hash", "seed", "status", "valid", "invalid_reason", "iterations", "evaluations",
           "stopped_by")
_MEASURED = ("wall_time_s", "cpu_time_s")


@dataclass(frozen=True)
class RunDifference:
    """One stored value that differs between the two databases."""

    run_key: str
    field: str
    first: str
    second: str


@dataclass(frozen=True)
class Comparison:
    """The outcome of :func:`compare_results`."""

    experiment: str
    n_runs: int
    differences: tuple[RunDifference, ...]

    @property
    def identical(self) -> bool:
        """True when no compared value differs and both hold the same runs."""
        return not self.differences

    def summary(self, limit: int = 20) -> str:
        """A few lines for a terminal: the verdict, then up to ``limit`` differences."""
        if self.identical:
            return f"experiment '{self.experiment}': {self.n_runs} runs, identical paths and metrics (times aside)"
        runs = len({d.run_key for d in self.differences})
        lines = [(f"experiment '{self.experiment}': {runs} of {self.n_runs} runs differ "
                  f"({len(self.differences)} values):")]
        lines += [f"  {d.run_key}  {d.field}: {d.first} != {d.second}" for d in self.differences[:limit]]
        if len(self.differences) > limit:
            lines.append(f"  ... and {len(self.differences) - limit} more")
        return "\n".join(lines)


def measured_time_metrics() -> frozenset[str]:
    """Ids of the registered metrics whose value is a measured time (``wall_time_s``, ``cpu_time_s``)."""
    from pathzoo.plugins.manager import get_registry

    out = set()
    for mid, entry in get_registry().metrics.items():
        try:
            cls = entry.obj()
        except Exception:  # noqa: BLE001 - a metric that cannot load is compared like any other column
            continue
        if getattr(cls, "attribute", "") in _MEASURED:
            out.add(mid)
    return frozenset(out)


def _same(a: Any, b: Any) -> bool:
    if isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return True
    return bool(a == b)


def _text(value: Any) -> str:
    return repr(float(value)) if isinstance(value, (float, np.floating)) else str(value)


def _arrays_same(a: np.ndarray | None, b: np.ndarray | None) -> bool:
    if a is None or b is None:
        return a is None and b is None
    return a.shape == b.shape and a.tobytes() == b.tobytes()


def _history(db: Path, experiment: str) -> dict[str, list[tuple[int, int, float]]]:
    from pathzoo.harness.store import read_history

    out: dict[str, list[tuple[int, int, float]]] = {}
    frame = read_history(db, experiment)
    for key, it, ev, cost in zip(frame["run_key"], frame["iteration"], frame["evaluations"], frame["best_cost"]):
        out.setdefault(str(key), []).append((int(it), int(ev), float(cost)))
    return out


def compare_results(first: str | Path, second: str | Path, experiment: str | None = None) -> Comparison:
    """Compare the stored runs of one experiment in two result databases; see the module docstring.

    Parameters
    ----------
    first, second : path
        Result databases written by ``pathzoo run``.
    experiment : str, optional
        The experiment to compare; needed when ``first`` holds several.

    Returns
    -------
    Comparison
        Every differing value, and the runs stored in one database only
        (field ``run``).

    Raises
    ------
    ResultsDatabaseError
        A file is missing or not a results database, or lacks the experiment.
    """
    from pathzoo.harness.store import read_experiments, read_path, read_runs
    from pathzoo.harness.store_file import ResultsDatabaseError

    first, second = Path(first), Path(second)
    if experiment is None:
        names = sorted(str(n) for n in read_experiments(first)["name"])
        if len(names) != 1:
            raise ResultsDatabaseError(f"{first} holds {len(names)} experiments ({', '.join(names) or 'none'}); "
                                       "name the one to compare")
        experiment = names[0]
    runs = [read_runs(db, experiment).set_index("run_key") for db in (first, second)]
    skip = measured_time_metrics()
    metric_cols = sorted({c for r in runs for c in r.columns if c not in skip and c not in _FIELDS
                          and c not in _MEASURED and c not in ("experiment", "planner", "scenario", "seed_index",
                                                               "params", "message", "label", "isolated")})
    diffs: list[RunDifference] = []
    keys = list(dict.fromkeys([*runs[0].index, *runs[1].index]))
    histories = [_history(db, experiment) for db in (first, second)]
    for key in keys:
        present = [key in r.index for r in runs]
        if not all(present):
            diffs.append(RunDifference(key, "run", *("stored" if p else "missing" for p in present)))
            continue
        a, b = runs[0].loc[key], runs[1].loc[key]
        for col in (*_FIELDS, *metric_cols):
            va = a[col] if col in a.index else math.nan
            vb = b[col] if col in b.index else math.nan
            if not _same(va, vb):
                diffs.append(RunDifference(key, col, _text(va), _text(vb)))
        (pa, ta), (pb, tb) = (read_path(db, experiment, key) for db in (first, second))
        if not _arrays_same(pa, pb):
            diffs.append(RunDifference(key, "path", f"{None if pa is None else pa.shape}",
                                       f"{None if pb is None else pb.shape} (other values)"))
        if not _arrays_same(ta, tb):
            diffs.append(RunDifference(key, "times", "arrival times", "other arrival times"))
        ha, hb = histories[0].get(key, []), histories[1].get(key, [])
        if len(ha) != len(hb) or not all(x[:2] == y[:2] and _same(x[2], y[2]) for x, y in zip(ha, hb)):
            diffs.append(RunDifference(key, "history", f"{len(ha)} points", f"{len(hb)} points (other values)"))
    return Comparison(experiment, len(keys), tuple(diffs))
