"""Step-curve resampling, convergence bands and time-to-target on hand-made histories."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pathzoo.analysis.anytime import best_known, convergence_curves, resample_history, time_to_target
from pathzoo.analysis.synthetic import make_runs
from pathzoo.core.errors import InvalidParameterError

inf = np.inf


def test_resample_is_a_right_continuous_step_function():
    out = resample_history([2, 5, 9], [10.0, 8.0, 7.0], [0, 2, 3, 5, 8.9, 9, 100])
    assert out.tolist() == [inf, 10.0, 10.0, 8.0, 8.0, 7.0, 7.0]


def hist(key, xs, costs, t_scale=0.1):
    xs = np.asarray(xs)
    return pd.DataFrame(dict(run_key=key, iteration=xs, evaluations=xs * 10, best_cost=costs, time_s=xs * t_scale))


def three_runs():
    runs = make_runs({"s": {"p": [7.0, 9.0, np.nan]}})  # third run failed
    k = runs["run_key"].tolist()
    history = pd.concat([hist(k[0], [1, 4], [10.0, 7.0]), hist(k[1], [2, 3], [12.0, 9.0]),
                         hist(k[2], [1], [5.0])])  # the failed run's report is ignored
    return runs, history


def test_convergence_band_counts_unsolved_runs_as_infinite():
    runs, history = three_runs()
    c = convergence_curves(history, runs, x="iteration", n_points=4)  # grid 1, 2, 3, 4
    assert c["x"].tolist() == [1.0, 2.0, 3.0, 4.0]
    # per grid point the three runs hold: (10, inf, inf) (10, 12, inf) (10, 9, inf) (7, 9, inf)
    assert np.isnan(c["median"].iloc[0])
    assert c["median"].tolist()[1:] == [12.0, 10.0, 9.0]
    assert c["q25"].tolist() == [10.0, 10.0, 9.0, 7.0]
    assert c["q75"].isna().all() and (c["n_runs"] == 3).all()
    c = convergence_curves(history, runs, x="evaluations", n_points=4)
    assert c["x"].tolist() == [10.0, 20.0, 30.0, 40.0]
    with pytest.raises(InvalidParameterError, match="x must be one of"):
        convergence_curves(history, runs, x="seconds")
    with pytest.raises(InvalidParameterError, match="history: missing column 'time_s'"):
        convergence_curves(history.drop(columns="time_s"), runs)


def test_time_to_target_uses_comparable_runs_only():
    runs, history = three_runs()
    runs = pd.concat([runs, make_runs({"s": {"q": [8.0]}}).assign(run_key="other")], ignore_index=True)
    history = pd.concat([history, hist("other", [1, 2], [100.0, 80.0])])  # objective is not length
    assert best_known(runs).to_dict() == {"s": 7.0}
    t = time_to_target(history, runs, eps=0.3).set_index("run_key")  # target 9.1
    k = runs["run_key"].tolist()
    assert t.loc[k[0], "hit"] == pytest.approx(0.4) and t.loc[k[1], "hit"] == pytest.approx(0.3)
    assert t.loc[k[2], "hit"] == inf and t.loc[k[2], "comparable"]  # failed: never
    assert not t.loc["other", "comparable"] and np.isnan(t.loc["other", "hit"])
    t = time_to_target(history, runs, eps=0.0, optimum={"s": 7.0}, x="iteration").set_index("run_key")
    assert t.loc[k[0], "hit"] == 4 and t.loc[k[1], "hit"] == inf
    with pytest.raises(InvalidParameterError, match="eps must be"):
        time_to_target(history, runs, eps=-1)
