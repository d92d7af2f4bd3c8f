"""The report read from a database a chunk of scenarios at a time holds the numbers of the frame-based computation."""

from __future__ import annotations

import dataclasses
import math
import re

import numpy as np
import pandas as pd
import pytest

from pathzoo.analysis.anytime import time_to_target
from pathzoo.analysis.comparison_table import paper_table
from pathzoo.analysis.database import experiment_info
from pathzoo.analysis.frame import with_config
from pathzoo.analysis.leaderboard import leaderboard
from pathzoo.analysis.path_models import MODEL_RATIO, with_model_ratio
from pathzoo.analysis.ranks import friedman, friedman_of_summary
from pathzoo.analysis.report import render_report, write_report
from pathzoo.analysis.report_data import gather_from_db
from pathzoo.analysis.summary import median_runs, summarize
from pathzoo.analysis.synthetic import random_records
from pathzoo.core.errors import InvalidParameterError
from pathzoo.core.results import HistoryPoint
from pathzoo.core.status import RunStatus
from pathzoo.harness.experiment import Experiment
from pathzoo.harness.store import ResultStore, read_history, read_path, read_runs

SHOWN = ["s00002", "s00009"]


def _with_history(record, k: int):
    """Every other run gets a best-cost curve ending at its length (every fifth above it); a few crash."""
    if k % 31 == 0:
        return dataclasses.replace(record, status=RunStatus.CRASH, valid=False, message="boom")
    if k % 2 or not record.valid:
        return record
    final = record.metrics["length"] * (1.0 if k % 5 else 1.3)
    points = tuple(HistoryPoint(i, 10 * i, final * (1 + 0.05 * (5 - i)), 0.01 * i) for i in range(1, 6))
    return dataclasses.replace(record, history=points)


@pytest.fixture(scope="module")
def db(tmp_path_factory: pytest.TempPathFactory):
    path = tmp_path_factory.mktemp("report") / "r.sqlite"
    exp = Experiment.build(planners=["exact.astar"], scenarios=["dsaco.simple"], seeds=1, name="synthetic")
    drawn = random_records(15, 8, ("p.a", "p.b", "p.c"), seed=4, failure_rate=0.25)
    records = [_with_history(r, k) for k, r in enumerate(drawn)]
    with ResultStore(path) as store:
        store.add_experiment(exp)
        store.insert_batch(records, labels=["clever" if r.planner_id == "p.b" else "" for r in records])
    return path


@pytest.fixture(scope="module")
def whole(db):
    return read_runs(db, "synthetic"), read_history(db, "synthetic")


@pytest.fixture(scope="module")
def gathered(db):
    return gather_from_db(db, "synthetic", "length", reference="p.c", detail=SHOWN, chunk_runs=40)


def test_the_chunks_were_several(gathered, whole):
    runs, _ = whole
    assert gathered.data.n_runs == len(runs) == 15 * 3 * 8
    assert gathered.data.scenario_ids == sorted(runs["scenario"].unique())
    assert gathered.has_history and gathered.shown_ids == SHOWN
    assert len(list(gathered.chunks(["length"]))) == 8  # 24 runs per scenario: 2 scenarios make a chunk of 40 or more


def test_tables_equal_the_frame_based_ones(gathered, whole):
    runs, history = whole
    data = gathered.data
    board = leaderboard(runs, "length", reference="p.c")
    pd.testing.assert_frame_equal(data.leaderboard, board)
    assert data.leaderboard.attrs == board.attrs
    assert data.own_leaderboard is not None
    pd.testing.assert_frame_equal(data.own_leaderboard, leaderboard(with_model_ratio(runs), MODEL_RATIO))
    paper = paper_table(runs, "p.c", ["length", "planning_time"])
    assert data.paper is not None and [i.id for i in data.paper.metrics] == ["length", "planning_time"]
    pd.testing.assert_frame_equal(data.paper.table, paper.table)
    pd.testing.assert_frame_equal(data.paper.wtl, paper.wtl)
    assert data.paper.wtl["wins"].sum() + data.paper.wtl["losses"].sum() > 0  # the marks decide something
    assert set(data.summaries) == {"length", "length_ratio", "planning_time"}
    for m, table in data.summaries.items():
        pd.testing.assert_frame_equal(table, summarize(runs, m))
    assert data.valued == {"length", "length_ratio", "planning_time"}
    ranks, chunked = friedman(runs, "length"), friedman_of_summary(data.summaries["length"])
    pd.testing.assert_frame_equal(chunked.ranks, ranks.ranks)
    assert (chunked.statistic, chunked.pvalue, chunked.cd) == (ranks.statistic, ranks.pvalue, ranks.cd)


def test_counts_and_lists_equal_the_frame_based_ones(gathered, whole):
    runs, history = whole
    data = gathered.data
    df = with_config(runs, "length")
    counts = df.pivot_table(index="config", columns="status", values="run_key", aggfunc="count", fill_value=0)
    assert data.configs == ["clever", "p.a", "p.c"]
    for config, row in counts.iterrows():
        shown = data.outcomes.set_index("planner").loc[config]
        assert all(int(shown[s]) == int(row[s]) for s in counts.columns)
        assert shown["success"] == f"{100 * df.loc[df['config'] == config, 'success'].mean():.0f}%"
    assert "crash" in data.outcomes.columns
    assert data.clocked == int(df["stopped_by"].isin(["wall_time", "cpu_time"]).sum()) > 0
    assert data.not_isolated == 0 and data.not_sandboxed == len(runs)
    bad = df[~df["success"]].sort_values(["scenario", "config", "seed_index"])
    assert data.n_failures == len(bad) > 60
    assert list(data.failures["scenario"]) == list(bad["scenario"][:60])
    assert list(data.failures["planner"]) == list(bad["config"][:60])
    assert "boom" in set(data.failures["reason"])
    typical = median_runs(runs, "length")
    typical = typical[typical["scenario"].isin(SHOWN)].reset_index(drop=True)
    pd.testing.assert_frame_equal(data.typical, typical)
    keys = set(runs.loc[runs["scenario"].isin(SHOWN), "run_key"])
    expected = history[history["run_key"].isin(keys)].reset_index(drop=True)
    pd.testing.assert_frame_equal(data.shown_history.reset_index(drop=True), expected)
    hits = time_to_target(history, runs, eps=0.05)
    order = ["config", "comparable", "hit"]
    mine = data.hits.sort_values(order).reset_index(drop=True)
    pd.testing.assert_frame_equal(mine, hits[order].sort_values(order).reset_index(drop=True))
    assert np.isfinite(mine["hit"]).sum() > 0 and (~mine["comparable"]).sum() > 0


def _text(doc: str) -> str:
    doc = re.sub(r"\d{4}-\d\d-\d\d \d\d:\d\d \w+", "DATE", doc)
    return re.sub(r'src="data:image/png;base64,[^"]*"', 'src="PNG"', doc)


@pytest.mark.slow
def test_the_written_report_equals_the_one_of_the_whole_frame(db, whole, tmp_path):
    runs, history = whole
    index = write_report(db, tmp_path / "rep", reference="p.c", detail=SHOWN)
    info = experiment_info(db, "synthetic")
    meta = {"database": str(db.resolve()), "experiment": "synthetic", "budget per run": info.budget_text,
            "seeds": str(len(info.config["seeds"])), "created": info.created}
    page = render_report(runs, history, reference="p.c", detail=SHOWN, scenarios={},
                         path_of=lambda key: read_path(db, "synthetic", key)[0], title="pathzoo report: synthetic",
                         meta=meta)
    mine, theirs = _text(index.read_text(encoding="utf-8")), _text(page.html("pathzoo report: synthetic"))
    assert mine == theirs
    assert mine.count("<figure>") == 1 + 3 * 2 + 2 * 1 + 1  # cd, boxes (summary and named), convergence, ECDF


def test_errors_name_what_is_wrong(db):
    with pytest.raises(InvalidParameterError, match="reference 'p.z' is not among the planners: clever, p.a, p.c"):
        gather_from_db(db, "synthetic", reference="p.z")
    with pytest.raises(InvalidParameterError, match="runs: missing column 'nope'"):
        gather_from_db(db, "synthetic", "nope")
    with pytest.raises(InvalidParameterError, match="scenario 's99999' has no runs"):
        gather_from_db(db, "synthetic", detail=["s99999"])
    assert math.isfinite(gather_from_db(db, "synthetic", "planning_time").data.leaderboard["median"].max())
