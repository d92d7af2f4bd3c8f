"""Hand-made or random runs frames in the store's schema, for examples, tests and trying the analysis.

The frames have exactly the columns of ``pathzoo.harness.store.read_runs``,
so every analysis function accepts them; nothing here runs a planner.
"""

from __future__ import annotations

import hashlib
import json
from typing import TYPE_CHECKING, Any, Iterator, Mapping, Sequence

import numpy as np
import pandas as pd

if TYPE_CHECKING:
    from pathzoo.core.results import RunRecord

__all__ = ["RUN_FRAME_COLUMNS", "make_runs", "random_runs", "random_history", "random_records"]

RUN_FRAME_COLUMNS: tuple[str, ...] = (
    "run_key", "experiment", "planner", "planner_version", "params_hash", "params", "scenario",
    "seed_index", "seed", "status", "valid", "invalid_reason", "message", "wall_time_s",
    "cpu_time_s", "iterations", "evaluations",
)  # fmt: skip
"""Non-metric columns of a runs frame, in store order."""


def _hash(params: Mapping[str, object]) -> str:
    return hashlib.sha256(json.dumps(params, sort_keys=True).encode()).hexdigest()[:16]


def make_runs(
    results: Mapping[str, Mapping[str, Sequence[float]]],
    *,
    metric: str = "length",
    experiment: str = "synthetic",
    statuses: Mapping[tuple[str, str], Sequence[str]] | None = None,
) -> pd.DataFrame:
    """A runs frame with given metric values.

    Parameters
    ----------
    results : mapping
        ``results[scenario][planner]`` is the list of metric values of that
        planner's runs on that scenario, seed index = position. NaN marks a
        run that did not succeed (status ``failed`` unless ``statuses`` says
        otherwise).
    metric : str
        Name of the metric column.
    experiment : str
        Experiment name.
    statuses : mapping, optional
        ``statuses[(scenario, planner)]`` lists each run's status explicitly.

    Returns
    -------
    DataFrame
        One row per run; ``success`` (0/1) is filled in, other metric
        columns are absent.
    """
    rows = []
    for scenario, per_planner in results.items():
        for planner, values in per_planner.items():
            given = (statuses or {}).get((scenario, planner))
            for i, v in enumerate(values):
                v = float(v)
                status = given[i] if given is not None else ("failed" if np.isnan(v) else "solved")
                ok = status == "solved" and not np.isnan(v)
                rows.append(
                    dict(
                        run_key=f"{planner}|{_hash({})}|{scenario}|{i}", experiment=experiment, planner=planner,
                        planner_version="1", params_hash=_hash({}), params="{}", scenario=scenario, seed_index=i,
                        seed=1000 + i, status=status, valid=ok, invalid_reason="", message="",
                        wall_time_s=0.01, cpu_time_s=0.01, iterations=10, evaluations=100,
                        **{metric: v if ok else np.nan, "success": int(ok)},
                    )
                )
    return pd.DataFrame(rows, columns=[*RUN_FRAME_COLUMNS, metric, "success"])


def random_runs(
    planners: Sequence[str] = ("aco.a", "aco.b", "exact.dijkstra"),
    scenarios: Sequence[str] = ("s1", "s2", "s3"),
    n_seeds: int = 10,
    *,
    seed: int = 0,
    failure_rate: float = 0.1,
) -> pd.DataFrame:
    """A random but plausible runs frame: each planner has its own quality and failure rate.

    Columns ``length``, ``energy``, ``turns``, ``planning_time`` and
    ``success`` are filled (NaN for unsuccessful runs). The last planner is
    exact: it always succeeds with the scenario's optimal length.
    """
    rng = np.random.default_rng(seed)
    rows = []
    for si, scenario in enumerate(scenarios):
        optimum = 50.0 + 25.0 * si
        for pi, planner in enumerate(planners):
            exact = pi == len(planners) - 1
            for i in range(n_seeds):
                ok = exact or rng.random() >= failure_rate * (1 + pi)
                excess = 0.0 if exact else rng.gamma(2.0, 0.02 * (1 + pi))
                length = optimum * (1 + excess)
                t = float(rng.lognormal(-3 + pi, 0.4))
                rows.append(
                    dict(
                        run_key=f"{planner}|{_hash({})}|{scenario}|{i}", experiment="synthetic", planner=planner,
                        planner_version="1", params_hash=_hash({}), params="{}", scenario=scenario, seed_index=i,
                        seed=int(rng.integers(2**31)), status="solved" if ok else "failed", valid=ok,
                        invalid_reason="", message="", wall_time_s=t * 1.1, cpu_time_s=t, iterations=100,
                        evaluations=1000,
                        length=length if ok else np.nan,
                        energy=length * (30 + 5 * pi) if ok else np.nan,
                        turns=float(rng.integers(2, 10 + 3 * pi)) if ok else np.nan,
                        planning_time=t if ok else np.nan,
                        success=int(ok),
                    )
                )
    return pd.DataFrame(rows, columns=[*RUN_FRAME_COLUMNS, "length", "energy", "turns", "planning_time", "success"])


def random_history(runs: pd.DataFrame, *, n_points: int = 30, seed: int = 0) -> pd.DataFrame:
    """Random convergence histories (best cost falling to each run's ``length``) for a runs frame.

    Returns a frame with the columns of ``pathzoo.harness.store.read_history``:
    ``run_key, iteration, evaluations, best_cost, time_s``. Unsuccessful runs
    get no history.
    """
    rng = np.random.default_rng(seed)
    parts = []
    row: Any  # a DataFrame row: its fields are whatever the columns hold
    for row in runs.itertuples(index=False):
        if not row.success:
            continue
        final = float(row.length)
        iters = np.arange(1, n_points + 1)
        drops = np.sort(rng.random(n_points))[::-1] * final * rng.uniform(0.2, 0.8)
        best = np.minimum.accumulate(final + drops * (rng.random(n_points) < 0.4).cumsum()[::-1] / n_points)
        best[-1] = final
        best = np.minimum.accumulate(best)
        parts.append(
            pd.DataFrame(
                dict(run_key=row.run_key, iteration=iters, evaluations=iters * 10, best_cost=best,
                     time_s=iters * float(row.cpu_time_s) / n_points)
            )
        )
    cols = ["run_key", "iteration", "evaluations", "best_cost", "time_s"]
    return pd.concat(parts, ignore_index=True)[cols] if parts else pd.DataFrame(columns=cols)


def random_records(
    n_scenarios: int,
    n_seeds: int,
    planners: Sequence[str] = ("aco.a", "aco.b", "exact.dijkstra"),
    *,
    experiment: str = "synthetic",
    seed: int = 0,
    failure_rate: float = 0.1,
) -> "Iterator[RunRecord]":
    """Random but plausible stored runs (as :func:`random_runs` draws them), for building a database.

    Yields ``n_scenarios x len(planners) x n_seeds`` :class:`~pathzoo.core.results.RunRecord`
    objects, scenario by scenario, for :meth:`ResultStore.insert_batch
    <pathzoo.harness.store_writer.ResultStore.insert_batch>`: scenarios
    ``s00000, s00001, ...`` with metrics ``length``, ``length_ratio`` and
    ``planning_time``, no path and no history. A few runs per hundred end
    by the clock (``stopped_by="wall_time"``).
    """
    from pathzoo.core.results import RunRecord
    from pathzoo.core.status import RunStatus

    rng = np.random.default_rng(seed)
    phash = _hash({})
    versions = {"pathzoo": "synthetic", "python": "3", "peak_rss_mb": "1"}
    nan = float("nan")
    for si in range(n_scenarios):
        scenario = f"s{si:05d}"
        optimum = 50.0 + (si % 97)
        for pi, planner in enumerate(planners):
            exact = pi == len(planners) - 1
            ok = exact | (rng.random(n_seeds) >= failure_rate * (1 + pi))
            excess = np.zeros(n_seeds) if exact else rng.gamma(2.0, 0.02 * (1 + pi), n_seeds)
            times = rng.lognormal(-3 + pi, 0.4, n_seeds)
            clock = rng.random(n_seeds) < 0.02
            for i in range(n_seeds):
                good = bool(ok[i])
                length = optimum * (1 + float(excess[i]))
                yield RunRecord(
                    run_key=f"{planner}|{phash}|{scenario}|{i}", experiment=experiment, planner_id=planner,
                    planner_version="1", params={}, params_hash=phash, scenario_id=scenario, seed_index=i,
                    seed=1000 + i, status=RunStatus.SOLVED if good else RunStatus.FAILED, valid=good,
                    invalid_reason="", message="", wall_time_s=float(times[i]) * 1.1, cpu_time_s=float(times[i]),
                    iterations=100, evaluations=1000, path=None, times=None, history=(),
                    metrics={"length": length if good else nan, "length_ratio": length / optimum if good else nan,
                             "planning_time": float(times[i]) if good else nan},
                    versions=versions, started_at="2026-01-01T00:00:00Z",
                    stopped_by="wall_time" if clock[i] else "none",
                )
