"""Paper-style table: medians, SDs, marks from Holm-corrected tests and w/t/l counts."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pathzoo.analysis import frame
from pathzoo.analysis.comparison_table import format_paper_table, paper_table
from pathzoo.analysis.frame import MetricInfo
from pathzoo.analysis.stats import pairwise_tests
from pathzoo.analysis.synthetic import make_runs
from pathzoo.core.errors import InvalidParameterError, UnknownPluginError


def runs_three_scenarios() -> pd.DataFrame:
    base = np.linspace(0.0, 0.9, 10)
    length = make_runs(
        {
            "s1": {"ref": list(10 + base), "slow": list(12 + base), "twin": list(10 + base[::-1])},
            "s2": {"ref": list(10 + base), "slow": list(12 + base), "twin": list(10.05 + base)},
            "s3": {"ref": list(12 + base), "slow": list(10 + base), "twin": list(10 + base[::-1])},
        }
    )
    energy = make_runs(
        {
            "s1": {"ref": list(5 + base), "slow": list(5 + base), "twin": list(9 + base)},
            "s2": {"ref": list(5 + base), "slow": list(5 + base), "twin": list(9 + base)},
            "s3": {"ref": list(5 + base), "slow": list(5 + base), "twin": list(9 + base)},
        },
        metric="energy",
    )
    return length.assign(energy=energy["energy"].to_numpy())


@pytest.mark.slow
def test_marks_and_counts_follow_the_tests():
    runs = runs_three_scenarios()
    pt = paper_table(runs, "ref", ["length", "energy"])
    t = pt.table.set_index(["scenario", "config"])
    assert list(pt.table["config"][:3]) == ["ref", "slow", "twin"]  # reference first
    assert t.loc[("s1", "ref"), "length_mark"] == ""
    assert t.loc[("s1", "slow"), "length_mark"] == "↑"  # reference better
    assert t.loc[("s3", "slow"), "length_mark"] == "↓"  # reference worse
    assert t.loc[("s1", "twin"), "length_mark"] == "≈"
    assert t.loc[("s2", "slow"), "energy_mark"] == "≈"
    assert t.loc[("s2", "twin"), "energy_mark"] == "↑"
    assert t.loc[("s2", "slow"), "length_median"] == pytest.approx(12.45)
    assert t.loc[("s2", "slow"), "length_sd"] == pytest.approx(np.std(np.linspace(0, 0.9, 10), ddof=1))
    # marks agree with pairwise_tests row by row
    tests = pairwise_tests(runs, "length", reference="ref").set_index(["scenario", "b"])
    for (s, c), w in tests["winner"].items():
        assert t.loc[(s, c), "length_mark"] == {"a": "↑", "b": "↓", "tie": "≈"}[w]
    wtl = pt.wtl.set_index(["metric", "config"])
    assert tuple(wtl.loc[("length", "slow")]) == (2, 0, 1, 0)
    assert tuple(wtl.loc[("energy", "twin")]) == (3, 0, 0, 0)
    assert tuple(wtl.loc[("energy", "slow")]) == (0, 3, 0, 0)


@pytest.mark.slow
def test_unregistered_column_given_with_its_direction():
    """A column that is not a registered metric is compared by the MetricInfo it comes with, nothing global changes."""
    runs = runs_three_scenarios()
    runs = runs.assign(score=runs["length"])
    before = dict(frame.RUN_COLUMNS)
    with pytest.raises(UnknownPluginError):
        paper_table(runs, "ref", ["score"])
    lower = paper_table(runs, "ref", [MetricInfo("score", "1", "min")]).table.set_index(["scenario", "config"])
    higher = paper_table(runs, "ref", [MetricInfo("score", "1", "max")]).table.set_index(["scenario", "config"])
    assert lower.loc[("s1", "slow"), "score_mark"] == "↑"
    assert higher.loc[("s1", "slow"), "score_mark"] == "↓"
    assert frame.RUN_COLUMNS == before


@pytest.mark.slow
def test_formats():
    pt = paper_table(runs_three_scenarios(), "ref", ["length", "energy"])
    text = format_paper_table(pt)
    assert "length [m] median" in text and "12.450 ↑" in text and "2/0/1" in text and "↓: ref significantly worse" in text
    md = format_paper_table(pt, "markdown")
    assert "| s1 | slow | 100% | 12.450 ↑ |" in md
    html = format_paper_table(pt, "html")
    assert html.count('<table class="pz-table">') == 2 and "12.450 ↑" in html
    csv = format_paper_table(pt, "csv")
    assert "length_median" in csv and "wins,ties,losses" in csv


def test_bad_inputs():
    runs = runs_three_scenarios()
    with pytest.raises(InvalidParameterError, match="reference 'x'"):
        paper_table(runs, "x", ["length"])
    with pytest.raises(InvalidParameterError, match="at least one metric"):
        paper_table(runs, "ref", [])
