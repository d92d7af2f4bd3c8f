"""Leaderboard ranking, statistics and formatting on hand-made runs."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pathzoo.analysis.leaderboard import format_leaderboard, leaderboard
from pathzoo.analysis.synthetic import make_runs, random_runs
from pathzoo.core.errors import InvalidParameterError, UnknownPluginError

nan = np.nan


def test_statistics_use_successful_runs_only():
    runs = make_runs({"s": {"p": [1.0, 2.0, 3.0, 10.0, nan]}})
    row = leaderboard(runs).iloc[0]
    good = np.array([1.0, 2.0, 3.0, 10.0])
    assert row["n_runs"] == 5
    assert row["success_rate"] == pytest.approx(0.8)
    assert row["median"] == pytest.approx(np.median(good))
    assert row["iqr"] == pytest.approx(np.percentile(good, 75) - np.percentile(good, 25))
    assert row["sd"] == pytest.approx(np.std(good, ddof=1))


def test_failures_rank_worst_before_a_better_median():
    # "fails" has the best successful median but fails 3 of 5 runs: penalized median is inf
    runs = make_runs(
        {
            "s": {
                "fails": [1.0, 1.0, nan, nan, nan],
                "steady": [5.0, 5.0, 5.0, 5.0, 5.0],
                "worse": [6.0, 6.0, 6.0, 6.0, nan],
            }
        }
    )
    lb = leaderboard(runs)
    assert list(lb["config"]) == ["steady", "worse", "fails"]
    assert list(lb["rank"]) == [1, 2, 3]


def test_infinite_penalized_medians_are_separated_by_success_rate():
    runs = make_runs({"s": {"a": [1.0, nan, nan, nan], "b": [9.0, 9.0, nan, nan], "c": [nan] * 4}})
    lb = leaderboard(runs)
    assert list(lb["config"]) == ["b", "a", "c"]
    assert np.isnan(lb.set_index("config").loc["c", "median"])


def test_ties_share_a_rank_and_max_metrics_rank_high_first():
    runs = make_runs({"s": {"a": [3.0, 3.0], "b": [3.0, 3.0], "c": [5.0, 5.0]}}, metric="score")
    lb = leaderboard(runs, "score", direction="min")
    assert list(lb["rank"]) == [1, 1, 3]
    lb = leaderboard(runs, "score", direction="max")
    assert lb.iloc[0]["config"] == "c" and list(lb["rank"]) == [1, 2, 2]


def test_ranked_per_scenario_and_direction_from_registry():
    runs = make_runs({"s1": {"a": [1.0], "b": [2.0]}, "s2": {"a": [2.0], "b": [1.0]}})
    lb = leaderboard(runs, "length")
    assert lb.attrs["metric"].direction == "min" and lb.attrs["metric"].unit == "m"
    best = lb[lb["rank"] == 1].set_index("scenario")["config"]
    assert best.to_dict() == {"s1": "a", "s2": "b"}


def test_success_metric_is_maximised():
    runs = random_runs(n_seeds=6)
    lb = leaderboard(runs, "success")
    assert ((lb["rank"] == 1) == (lb["success_rate"] == lb.groupby("scenario")["success_rate"].transform("max"))).all()
    assert (lb.loc[lb["config"] == "exact.dijkstra", "rank"] == 1).all()


def test_several_parameter_sets_get_distinct_labels():
    a = make_runs({"s": {"p": [1.0, 1.0]}})
    b = make_runs({"s": {"p": [2.0, 2.0]}}).assign(params_hash="ffffffffffff")
    lb = leaderboard(pd.concat([a, b], ignore_index=True))
    assert sorted(lb["config"]) == sorted([f"p@{a.params_hash[0][:7]}", "p@fffffff"])


def test_reference_columns():
    runs = make_runs({"s": {"ref": [1.0 + 0.01 * i for i in range(10)], "bad": [2.0 + 0.01 * i for i in range(10)],
                            "same": [1.0 + 0.01 * i for i in range(10)][::-1]}})
    lb = leaderboard(runs, reference="ref").set_index("config")
    assert lb.loc["ref", "vs_reference"] == "reference"
    assert lb.loc["bad", "vs_reference"] == "worse"
    assert lb.loc["bad", "a12"] == 0.0
    assert lb.loc["same", "vs_reference"] == "tie"
    assert lb.loc["same", "a12"] == pytest.approx(0.5)
    with pytest.raises(InvalidParameterError, match="reference 'nope'"):
        leaderboard(runs, reference="nope")


def test_too_few_runs_are_marked_not_testable():
    # 6 seeds, 7 planners against the reference: Holm over 7 tests cannot reach 0.05 (issue 13)
    worse = {f"p{i}": [10.0 + i + 0.1 * j for j in range(6)] for i in range(7)}
    runs = make_runs({"s": {"ref": [1.0 + 0.1 * j for j in range(6)], **worse}})
    lb = leaderboard(runs, reference="ref").set_index("config")
    assert (lb.drop(index="ref")["vs_reference"] == "n/s").all()
    assert (lb.drop(index="ref")["a12"] == 0.0).all() and (lb.drop(index="ref")["runs_needed"] == 9).all()
    text = format_leaderboard(leaderboard(runs, reference="ref"))
    assert "7 comparison(s) marked n/s" in text and "run at least 9 seeds" in text
    # with 9 seeds the same data is testable and every one is worse
    worse9 = {f"p{i}": [10.0 + i + 0.1 * j for j in range(9)] for i in range(7)}
    runs9 = make_runs({"s": {"ref": [1.0 + 0.1 * j for j in range(9)], **worse9}})
    lb9 = leaderboard(runs9, reference="ref").set_index("config")
    assert (lb9.drop(index="ref")["vs_reference"] == "worse").all()


def test_json_and_latex_formats():
    runs = make_runs({"s_1": {"a": [1.0, 2.0], "b%": [3.0, 4.0]}})
    lb = leaderboard(runs, reference="a")
    doc = json.loads(format_leaderboard(lb, "json"))
    assert doc["title"].startswith("Leaderboard") and doc["notes"]
    assert {r["config"] for r in doc["rows"]} == {"a", "b%"} and doc["rows"][0]["median"] == 1.5
    tex = format_leaderboard(lb, "latex")
    assert "\\begin{table}" in tex and "\\toprule" in tex and "s\\_1" in tex and "b\\%" in tex


def test_bad_inputs():
    runs = make_runs({"s": {"a": [1.0]}})
    with pytest.raises(UnknownPluginError, match="unknown metric 'foo'"):
        leaderboard(runs.assign(foo=1.0), "foo")
    with pytest.raises(InvalidParameterError, match="missing column 'bar'"):
        leaderboard(runs, "bar", direction="min")
    with pytest.raises(InvalidParameterError, match="missing column 'status'"):
        leaderboard(runs.drop(columns="status"))
    with pytest.raises(InvalidParameterError, match="fmt must be one of"):
        format_leaderboard(leaderboard(runs), "pdf")


def test_harness_columns_rank_without_registry():
    runs = make_runs({"s": {"a": [1.0], "b": [1.0]}})
    runs.loc[runs.planner == "a", "wall_time_s"] = 5.0
    lb = leaderboard(runs, "wall_time_s")
    assert lb.iloc[0]["config"] == "b" and lb.attrs["metric"].unit == "s"


def test_formats():
    runs = make_runs({"s1": {"a": [1.0, 2.0, nan], "b|x": [3.0, 3.0, 3.0]}})
    lb = leaderboard(runs, reference="a")
    text = format_leaderboard(lb, "text")
    assert text.splitlines()[0] == "Leaderboard: length [m], lower is better"
    assert "67%" in text and "penalized median" in text
    md = format_leaderboard(lb, "markdown")
    assert "| s1 | 1 | a |" in md and "b\\|x" in md
    csv = format_leaderboard(lb, "csv")
    back = pd.read_csv(__import__("io").StringIO(csv))
    assert back["median"].tolist() == pytest.approx(lb["median"].tolist())
    html = format_leaderboard(lb, "html")
    assert html.startswith('<table class="pz-table">') and "<caption>Leaderboard: length [m]" in html
    assert "<td>b|x</td>" in html and "<script" not in html


def test_status_enum_members_are_understood():
    from pathzoo.core import RunStatus

    runs = make_runs({"s": {"a": [1.0, 2.0], "b": [1.0, 2.0]}})
    runs["status"] = [RunStatus(v) for v in runs["status"]]
    assert (leaderboard(runs)["success_rate"] == 1.0).all()


def test_lazy_package_attributes():
    import pathzoo.analysis as analysis
    from pathzoo.analysis.report import write_report

    assert analysis.write_report is write_report and "friedman" in analysis.__all__
    with pytest.raises(AttributeError, match="no attribute 'nope'"):
        analysis.nope  # noqa: B018


def test_html_right_aligns_numbers_only():
    lb = leaderboard(make_runs({"s1": {"a": [1.0, 2.0, nan]}}))
    html = format_leaderboard(lb, "html")
    assert "<td>s1</td>" in html and "<td>a</td>" in html
    assert '<td class="num">67%</td>' in html and '<td class="num">1.5000</td>' in html


def test_floating_point_noise_does_not_split_ranks():
    import pandas as pd

    from pathzoo.analysis.leaderboard import leaderboard

    rows = []
    for planner, length in (("exact.dijkstra", 13.899494936611665), ("exact.astar", 13.899494936611667)):
        for seed in range(3):
            rows.append(dict(run_key=f"{planner}|h|s|{seed}", experiment="e", planner=planner, planner_version="1",
                             params_hash="h" + planner, params={}, scenario="s", seed_index=seed, seed=seed,
                             status="solved", valid=True, invalid_reason="", message="", wall_time_s=0.1,
                             cpu_time_s=0.1, iterations=1, evaluations=1, length=length, success=1.0))
    table = leaderboard(pd.DataFrame(rows), metric="length", direction="min")
    assert sorted(table["rank"]) == [1, 1]


def test_identical_values_have_exactly_zero_sd():
    import pandas as pd

    from pathzoo.analysis.summary import summarize

    x = 60.56854249492379  # the mean of three copies is not exactly x in floating point
    rows = [dict(run_key=f"p|h|s|{i}", experiment="e", planner="p", planner_version="1", params_hash="h", params={},
                 scenario="s", seed_index=i, seed=i, status="solved", valid=True, invalid_reason="", message="",
                 wall_time_s=0.1, cpu_time_s=0.1, iterations=1, evaluations=1, length=x, success=1.0)
            for i in range(3)]
    assert summarize(pd.DataFrame(rows), "length")["sd"].iloc[0] == 0.0


def test_numbers_just_below_a_power_of_ten_keep_the_same_width():
    from pathzoo.analysis.formatting import format_number

    assert format_number(0.99999999) == format_number(1.0) == "1.0000"
    assert format_number(9.9999999) == "10.000"
    assert format_number(0.999994) == "0.99999"


def test_rows_carry_path_model_cpu_and_evaluations_in_every_format():
    runs = make_runs({"s": {"exact.astar": [2.0, 2.0], "exact.thetastar": [1.9, 1.9]}})
    runs.loc[runs["planner"] == "exact.thetastar", "cpu_time_s"] = [0.5, 0.7]
    runs.loc[runs["planner"] == "exact.thetastar", "evaluations"] = [30, 50]
    lb = leaderboard(runs)
    rows = {r["config"]: r for r in json.loads(format_leaderboard(lb, "json"))["rows"]}
    assert rows["exact.thetastar"]["path_model"] == "anyangle" and rows["exact.astar"]["path_model"] == "grid"
    assert rows["exact.thetastar"]["median_cpu_s"] == pytest.approx(0.6)
    assert rows["exact.thetastar"]["median_evaluations"] == 40 and rows["exact.astar"]["median_evaluations"] == 100
    csv = format_leaderboard(lb, "csv").splitlines()[0].split(",")
    assert {"path_model", "median_cpu_s", "median_evaluations"} <= set(csv)
    text = format_leaderboard(lb, "text")
    assert "anyangle" in text and "CPU s" in text and "evals" in text


def test_planners_of_different_path_models_are_ranked_within_their_model():
    runs = make_runs({"s": {"exact.astar": [2.0, 2.0], "exact.dijkstra": [2.5, 2.5], "exact.thetastar": [1.9, 1.9]}})
    lb = leaderboard(runs).set_index("config")
    assert lb.loc["exact.thetastar", "rank"] == 1 and lb.loc["exact.astar", "rank"] == 1
    assert lb.loc["exact.dijkstra", "rank"] == 2
    assert "Ranked within each path model" in format_leaderboard(leaderboard(runs), "text")
    one_model = make_runs({"s": {"exact.astar": [2.0, 2.0], "exact.dijkstra": [2.5, 2.5]}})
    assert "Ranked within each path model" not in format_leaderboard(leaderboard(one_model), "text")


def test_a_cpu_spread_over_ten_times_is_one_warning_line():
    runs = make_runs({"s": {"a": [1.0, 1.0], "b": [2.0, 2.0]}})
    runs.loc[runs["planner"] == "b", "cpu_time_s"] = 0.099  # 9.9x the 0.01 s of "a"
    assert not leaderboard(runs).attrs["cpu_warning"]
    runs.loc[runs["planner"] == "b", "cpu_time_s"] = 0.2  # 20x
    lb = leaderboard(runs)
    warnings = [line for line in format_leaderboard(lb, "text").splitlines() if line.startswith("Warning:")]
    assert len(warnings) == 1 and "20x" in warnings[0] and "unequal work" in warnings[0]
