"""The leaderboard read from the database a chunk of scenarios at a time equals the in-memory one."""

from __future__ import annotations

import math

import pandas as pd
import pytest

from pathzoo.analysis.leaderboard import leaderboard, leaderboard_from_db
from pathzoo.analysis.summary import relative_medians
from pathzoo.analysis.synthetic import make_runs, random_records
from pathzoo.core.errors import InvalidParameterError
from pathzoo.harness.experiment import Experiment
from pathzoo.harness.store import ResultStore, read_runs
from pathzoo.harness.store_scan import library_versions, scenario_chunks


@pytest.fixture(scope="module")
def synthetic_db(tmp_path_factory: pytest.TempPathFactory):
    db = tmp_path_factory.mktemp("lb") / "r.sqlite"
    exp = Experiment.build(planners=["exact.astar"], scenarios=["dsaco.simple"], seeds=1, name="synthetic")
    with ResultStore(db) as store:
        store.add_experiment(exp)
        assert store.insert_batch(list(random_records(9, 7, ("p.a", "p.b", "p.c")))) == 9 * 3 * 7
    return db


@pytest.mark.parametrize("metric, reference", [("length", "p.c"), ("length", None), ("model_ratio", None),
                                               ("planning_time", "p.a")])
def test_chunked_leaderboard_equals_the_in_memory_one(synthetic_db, metric, reference):
    whole = leaderboard(read_runs(synthetic_db, "synthetic"), metric, reference=reference)
    chunked = leaderboard_from_db(synthetic_db, "synthetic", metric, reference=reference, chunk_runs=40)
    pd.testing.assert_frame_equal(whole, chunked)
    assert whole.attrs == chunked.attrs  # metric, reference, alpha, sections and the CPU warning


def test_chunks_hold_whole_scenarios_in_order(synthetic_db):
    chunks = list(scenario_chunks(synthetic_db, "synthetic", ["length"], chunk_runs=40))
    assert len(chunks) == 5 and [len(c) for c in chunks] == [42, 42, 42, 42, 21]  # 21 runs per scenario
    scenarios = [list(dict.fromkeys(c["scenario"])) for c in chunks]
    assert sum(scenarios, []) == [f"s{i:05d}" for i in range(9)]
    stored = read_runs(synthetic_db, "synthetic").set_index("run_key")
    both = pd.concat(chunks).set_index("run_key")
    pd.testing.assert_series_equal(both["length"].sort_index(), stored["length"].sort_index())


def test_an_unknown_reference_is_named(synthetic_db):
    with pytest.raises(InvalidParameterError, match="reference 'p.z' is not among the planners: p.a, p.b, p.c"):
        leaderboard_from_db(synthetic_db, "synthetic", reference="p.z")


def test_library_versions_are_aggregated_in_sql(synthetic_db):
    assert library_versions(synthetic_db, "synthetic", skip=["peak_rss_mb"]) == {
        "python": ["3"], "pathzoo": ["synthetic"]}


def test_relative_medians_divide_by_the_best_of_each_scenario():
    runs = make_runs({"s1": {"a": [10.0, 10.0, 11.0], "b": [20.0, 19.0, 21.0]},
                      "s2": {"a": [6.0, 6.0, math.nan], "b": [3.0, 3.0, 3.0]}})
    table = relative_medians(runs, "length").set_index(["scenario", "config"])["ratio"]
    assert table.to_dict() == {("s1", "a"): 1.0, ("s1", "b"): 2.0, ("s2", "a"): 2.0, ("s2", "b"): 1.0}
