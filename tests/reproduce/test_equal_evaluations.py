"""``pathzoo reproduce PAPER --equal evaluations``: every rival gets the proposed method's evaluation count."""

from __future__ import annotations

import pandas as pd
import pytest

from pathzoo.analysis.equal_budget import reference_evaluations, run_paper_equal_evaluations
from pathzoo.analysis.reproduction import RerunOptions, compare_paper, load_paper
from pathzoo.cli.main import main


def test_the_reference_count_is_the_median_rounded_down():
    runs = pd.DataFrame({"scenario": ["a", "a", "a", "b", "b"], "evaluations": [10, 30, 20, 7, 8]})
    assert reference_evaluations(runs, ["a", "b", "c"]) == {"a": 20, "b": 7, "c": 1}


@pytest.mark.slow
def test_no_rival_stores_more_evaluations_than_fgdaco(tmp_path):
    paper = load_paper("fgdaco")
    runs, names, evaluations = run_paper_equal_evaluations(
        paper, RerunOptions(db=tmp_path / "r.sqlite", seeds=2, iterations=3, scenarios="fgdaco.scenario1",
                            executor="inline", progress=False))
    assert names[0] == "reproduce.fgdaco.s2.i3.equal-evaluations"
    assert evaluations == {"fgdaco.scenario1": 60}  # 3 iterations of 20 ants
    per = runs.groupby("planner")["evaluations"].max()
    assert per["fgdaco"] == 60 and set(per.index) >= {"coa", "fuzzy_ga", "flaco"}
    assert (per <= 60).all() and per["coa"] == 60  # a pure metaheuristic spends its whole count
    rep = compare_paper(paper, runs)
    assert len(rep.table[rep.table["planner"] == "coa"]) == 2


@pytest.mark.slow
def test_the_command_says_what_every_rival_got(tmp_path, capsys):
    args = ["reproduce", "fgdaco", "--equal", "evaluations", "--seeds", "1", "--iterations", "2",
            "--scenarios", "fgdaco.scenario1", "--executor", "inline", "--no-progress", "--db", str(tmp_path / "r.sqlite")]
    assert main(args) == 0
    out = capsys.readouterr().out
    assert "Equal evaluations: every rival got Proposed FGDACO's median evaluation count" in out
    assert "fgdaco.scenario1 40" in out
