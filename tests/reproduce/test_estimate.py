"""``pathzoo reproduce PAPER --estimate``: the fit of a run's CPU time and the pilot end to end."""

from __future__ import annotations

import math

import pytest

from pathzoo.analysis.reproduction.estimate import fit_run, rerun_cpu, setup_cpu
from pathzoo.cli.main import main


def test_fit_run_reads_the_line_through_the_pilots_two_runs_at_the_full_count():
    # 2 s fixed + 0.5 s per iteration: 2.5 s at 1 iteration, 3.5 s at 3
    assert fit_run((1.0, 2.5), (3.0, 3.5), 1000) == pytest.approx(502.0)
    # a dearer low run (noise) gives no negative slope: the higher run's cost is the floor
    assert fit_run((1.0, 4.0), (3.0, 3.0), 1000) == pytest.approx(4.0)
    # a slope larger than the low run's cost gives no negative fixed part
    assert fit_run((1.0, 1.0), (3.0, 5.0), 10) == pytest.approx(20.0)


def test_fit_run_takes_the_pilot_run_as_the_full_run_when_the_planner_does_not_iterate():
    assert fit_run((1.0, 7.0), None, 1000) == 7.0          # ended by itself at the low cap
    assert fit_run((1.0, 7.0), (1.0, 7.2), 1000) == 7.0    # no more iterations at the high cap
    assert fit_run((1.0, 7.0), (3.0, 9.0), None) == 7.0    # nothing limits its iterations


def test_setup_cpu_is_what_the_first_run_took_beyond_the_cheaper_one():
    # a worker's first run on a scenario carries its load: 2.7 s beside 0.74 s
    assert setup_cpu([2.7, 0.74]) == pytest.approx(1.96)
    assert setup_cpu([0.74, 2.7]) == pytest.approx(1.96)  # whichever ran first
    assert setup_cpu([3.0]) == 0.0
    assert math.isnan(setup_cpu([1.0, math.nan])) and math.isnan(setup_cpu([math.nan, 1.0]))



def test_rerun_cpu_counts_the_load_once_and_the_rest_with_every_seed():
    # an exact search: 2.7 s in a worker's first run, 0.74 s in the next, 20 seeds
    assert rerun_cpu((1.0, 2.7), None, None, 1.96, 20) == pytest.approx(1.96 + 20 * 0.74)
    # an iterative planner: the fitted 502 s run (2 s fixed, 1 s of it the load) at 1000 iterations, 10 seeds
    assert rerun_cpu((1.0, 2.5), (3.0, 3.5), 1000, 1.0, 10) == pytest.approx(1.0 + 10 * 501.0)
    assert rerun_cpu((1.0, 2.5), (3.0, 3.5), 1000, 0.0, 10) == pytest.approx(10 * 502.0)  # no load measured


@pytest.mark.slow
def test_estimate_prints_each_planners_cpu_hours_and_stores_nothing(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["reproduce", "iaca", "--estimate", "--seeds", "4", "--executor", "inline", "--no-progress"]) == 0
    out = capsys.readouterr().out
    assert "Expected CPU time of the full rerun" in out
    lines = {line.split("  ")[0]: line.split() for line in out.splitlines()}
    dijkstra, iaca, total = lines["Dijkstra (exact.dijkstra)"], lines["IACA (aco.iaca)"], lines["total"]
    assert dijkstra[2:6] == ["4", "ends", "by", "itself"]  # an exact search: its pilot run is its full run
    assert iaca[2:4] == ["4", "100"]  # the paper's 100 iterations, 4 runs
    assert float(total[-1]) == pytest.approx(float(dijkstra[-1]) + float(iaca[-1]), rel=0.01)
    assert "4 run(s) per planner and scenario (the paper: 10)" in out
    assert list(tmp_path.iterdir()) == []  # the pilot's runs went to a temporary database


def test_estimate_refuses_options_that_store_results(capsys):
    assert main(["reproduce", "iaca", "--estimate", "--markdown", "page.md"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--estimate" in err[0] and "--markdown" in err[0]


def test_the_pilot_raises_a_cap_until_the_run_costs_twice_the_first():
    from pathzoo.analysis.reproduction.estimate import PILOT_GROWTH, _resolved

    assert PILOT_GROWTH == 2.0
    assert not _resolved((1.0, 5.0), (3.0, 5.1), 3)   # set-up dominates: try a higher cap
    assert _resolved((1.0, 5.0), (30.0, 10.0), 30)    # twice the first run: fit through these two
    assert _resolved((1.0, 5.0), (12.0, 5.5), 30)     # ended before its cap (converged): nothing more to learn
    assert _resolved((1.0, 5.0), (1.0, 5.0), 3)       # made no more iterations
