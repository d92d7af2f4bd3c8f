"""Pairwise tests, Holm, A12, Friedman and Nemenyi, cross-checked against scipy and by hand."""

from __future__ import annotations

import itertools

import numpy as np
import pandas as pd
import pytest
from scipy import stats

from pathzoo.analysis.ranks import friedman, friedman_statistic, nemenyi_cd, nemenyi_q
from pathzoo.analysis.stats import a12, a12_magnitude, compare_losses, holm, min_pvalue, pairwise_tests, runs_needed
from pathzoo.analysis.summary import summarize_metrics
from pathzoo.analysis.synthetic import make_runs, random_runs
from pathzoo.core.errors import InvalidParameterError

nan, inf = np.nan, np.inf


@pytest.mark.slow
def test_holm_hand_computed():
    # sorted: .005*4=.02, .01*3=.03, .03*2=.06, .04*1=.04 -> running max .02 .03 .06 .06
    assert holm([0.01, 0.04, 0.03, 0.005]) == pytest.approx([0.03, 0.06, 0.06, 0.02])
    assert holm([0.5, 0.6]) == pytest.approx([1.0, 1.0])
    out = holm([0.01, nan, 0.02])  # NaN counts as 1 in a family of 3
    assert out[0] == pytest.approx(0.03) and out[2] == pytest.approx(0.04) and np.isnan(out[1])
    assert len(holm([])) == 0


def previous_holm(pvalues):
    """The hand-written Holm step-down that statsmodels replaced, kept here as the oracle."""
    p = np.asarray(pvalues, dtype=np.float64).reshape(-1)
    m = len(p)
    filled = np.where(np.isnan(p), 1.0, p)
    order = np.argsort(filled, kind="stable")
    adj = np.empty(m)
    adj[order] = np.maximum.accumulate(np.minimum(1.0, (m - np.arange(m)) * filled[order]))
    adj[np.isnan(p)] = np.nan
    return adj


@pytest.mark.slow
def test_holm_from_statsmodels_gives_the_previous_numbers():
    rng = np.random.default_rng(3)
    for m in (1, 2, 5, 17):
        for _ in range(50):
            p = rng.uniform(0, 0.2, m) ** rng.uniform(0.5, 3)
            p[rng.uniform(size=m) < 0.1] = nan
            assert holm(p) == pytest.approx(previous_holm(p), nan_ok=True, abs=1e-15)


def test_min_pvalue_matches_scipy_at_the_extremes():
    for n in range(2, 9):
        a, b = np.arange(n, dtype=float), np.arange(n, dtype=float) + 100
        assert min_pvalue(n, n, paired=False) == pytest.approx(stats.mannwhitneyu(a, b, method="exact").pvalue)
        assert min_pvalue(n, n, paired=True) == pytest.approx(stats.wilcoxon(a - b).pvalue)
    assert min_pvalue(0, 5, paired=False) == 1.0
    # the case: 6 seeds, 7 comparisons -> smallest Holm-adjusted p is 7 * 2/64 = 0.22
    assert 7 * min_pvalue(6, 6, paired=True) == pytest.approx(0.21875)
    assert runs_needed(7, 0.05, paired=True) == 9 and 7 * min_pvalue(9, 9, paired=True) < 0.05
    assert 7 * min_pvalue(8, 8, paired=True) >= 0.05


def brute_a12(a, b):
    wins = sum(1.0 if x < y else 0.5 if x == y else 0.0 for x in a for y in b)
    return wins / (len(a) * len(b))


def test_a12_matches_definition():
    rng = np.random.default_rng(1)
    for _ in range(20):
        a = rng.integers(0, 5, rng.integers(1, 9)).astype(float)
        b = rng.integers(0, 5, rng.integers(1, 9)).astype(float)
        a[rng.random(len(a)) < 0.2] = inf
        b[rng.random(len(b)) < 0.2] = inf
        assert a12(a, b) == pytest.approx(brute_a12(a, b))
        assert a12(a, b) + a12(b, a) == pytest.approx(1.0)
    assert np.isnan(a12(np.array([]), np.array([1.0])))


def test_a12_magnitudes():
    assert [a12_magnitude(x) for x in (0.5, 0.55, 0.57, 0.3, 0.65, 0.8, 0.2)] == [
        "negligible", "negligible", "small", "medium", "medium", "large", "large"]


def test_mann_whitney_matches_scipy_and_failures_are_worst():
    rng = np.random.default_rng(2)
    a, b = rng.normal(0, 1, 12), rng.normal(0.8, 1, 9)
    test, stat, p, sign = compare_losses(a, b, paired=False)
    ref = stats.mannwhitneyu(a, b, alternative="two-sided")
    assert test == "mannwhitneyu" and stat == ref.statistic and p == pytest.approx(ref.pvalue)
    assert sign == -1  # a has smaller losses
    # failures (+inf) behave exactly like a tied value beyond all others
    fa, fb = a.copy(), b.copy()
    fa[:3], fb[:1] = inf, inf
    big = 1e6
    ref = stats.mannwhitneyu(np.where(np.isinf(fa), big, fa), np.where(np.isinf(fb), big, fb))
    _, stat, p, _ = compare_losses(fa, fb, paired=False)
    assert stat == ref.statistic and p == pytest.approx(ref.pvalue)
    assert compare_losses(np.full(3, inf), np.full(4, inf), paired=False)[2] == 1.0


def test_wilcoxon_matches_scipy_with_failure_rules():
    rng = np.random.default_rng(3)
    a, b = rng.normal(0, 1, 15), rng.normal(0.5, 1, 15)
    test, stat, p, sign = compare_losses(a, b, paired=True)
    ref = stats.wilcoxon(a - b)
    assert test == "wilcoxon" and stat == ref.statistic and p == pytest.approx(ref.pvalue) and sign == -1
    # both failed -> zero difference (dropped); one failed -> larger than any finite difference
    fa, fb = a.copy(), b.copy()
    fa[[0, 1]], fb[[1, 2]] = inf, inf
    d = a - b
    d[1] = 0.0
    d[0], d[2] = 1e6, -1e6
    ref = stats.wilcoxon(d)
    _, stat, p, _ = compare_losses(fa, fb, paired=True)
    assert stat == ref.statistic and p == pytest.approx(ref.pvalue)
    assert compare_losses(np.ones(4), np.ones(4), paired=True)[2] == 1.0


def frame_two_scenarios():
    rng = np.random.default_rng(4)
    res = {}
    for s in ("s1", "s2"):
        res[s] = {
            "a": list(rng.normal(10, 1, 8)),
            "b": list(rng.normal(12, 1, 8)),
            "c": list(rng.normal(10.2, 1, 8)),
        }
    res["s2"]["c"][0] = nan  # one failed run
    return make_runs(res)


@pytest.mark.slow
def test_pairwise_tests_end_to_end_paired_by_seed():
    runs = frame_two_scenarios()
    out = pairwise_tests(runs)
    assert len(out) == 6 and (out["test"] == "wilcoxon").all() and out["paired"].all()
    for s, sdf in out.groupby("scenario"):
        assert sdf["p_holm"].to_numpy() == pytest.approx(holm(sdf["p"].to_numpy()))
        for row in sdf.itertuples():
            la = runs[(runs.scenario == s) & (runs.planner == row.a)].sort_values("seed_index")["length"]
            lb = runs[(runs.scenario == s) & (runs.planner == row.b)].sort_values("seed_index")["length"]
            la, lb = la.fillna(1e9).to_numpy(), lb.fillna(1e9).to_numpy()
            assert row.p == pytest.approx(stats.wilcoxon(la - lb).pvalue)
            assert row.a12 == pytest.approx(brute_a12(la, lb))
    ab = out[(out.scenario == "s1") & (out.a == "a") & (out.b == "b")].iloc[0]
    assert ab.winner == "a" and ab.p_holm < 0.05 and ab.magnitude == "large"


@pytest.mark.slow
def test_pairing_rules():
    runs = frame_two_scenarios()
    unpaired = pairwise_tests(runs, paired=False)
    assert (unpaired["test"] == "mannwhitneyu").all()
    # drop one seed of "b": sets differ, auto falls back to Mann-Whitney; paired=True uses the common seeds
    cut = runs.drop(runs.index[(runs.planner == "b") & (runs.seed_index == 3)])
    auto = pairwise_tests(cut, reference="a")
    s1 = auto.set_index(["scenario", "b"])
    assert s1.loc[("s1", "b"), "test"] == "mannwhitneyu" and s1.loc[("s1", "c"), "test"] == "wilcoxon"
    forced = pairwise_tests(cut, reference="a", paired=True).set_index(["scenario", "b"])
    assert forced.loc[("s1", "b"), "test"] == "wilcoxon" and forced.loc[("s1", "b"), "n_a"] == 7
    with pytest.raises(InvalidParameterError, match="paired must be"):
        pairwise_tests(runs, paired="yes")
    with pytest.raises(InvalidParameterError, match="alpha"):
        pairwise_tests(runs, alpha=2)


@pytest.mark.slow
def test_reference_family_and_max_direction():
    runs = frame_two_scenarios()
    out = pairwise_tests(runs, reference="b")
    assert set(zip(out.a, out.b)) == {("b", "a"), ("b", "c")}
    assert len(out) == 4
    # maximising flips who wins (on s1, which has no failed run)
    flipped = pairwise_tests(runs, reference="b", direction="max")
    win_min = out.set_index(["scenario", "b"])["winner"].loc["s1"]
    win_max = flipped.set_index(["scenario", "b"])["winner"].loc["s1"]
    assert (win_min == "b").all() and (win_max == "a").all()


def test_friedman_statistic_matches_scipy():
    rng = np.random.default_rng(5)
    for k in (3, 4, 6):
        data = rng.integers(0, 4, (9, k)).astype(float)  # many ties
        ranks = stats.rankdata(data, axis=1)
        chi2, p = friedman_statistic(ranks)
        ref = stats.friedmanchisquare(*data.T)
        assert chi2 == pytest.approx(ref.statistic) and p == pytest.approx(ref.pvalue)
    assert friedman_statistic(np.full((3, 3), 2.0)) == (0.0, 1.0)


def test_nemenyi_against_demsar_table():
    # Demšar (2006), Table 5(a): q_0.05 for k = 2..10
    table = [1.960, 2.343, 2.569, 2.728, 2.850, 2.949, 3.031, 3.102, 3.164]
    # (the printed table is rounded; two entries differ from the exact quantile in the last digit)
    assert [nemenyi_q(k) for k in range(2, 11)] == pytest.approx(table, abs=1.5e-3)
    assert nemenyi_q(4, 0.10) == pytest.approx(2.291, abs=1.5e-3)  # Table 5(a), alpha = 0.10
    assert nemenyi_cd(4, 14) == pytest.approx(2.569 * np.sqrt(4 * 5 / (6 * 14)), rel=1e-3)


def test_friedman_on_runs():
    runs = random_runs(("p1", "p2", "p3", "p4"), [f"s{i}" for i in range(6)], n_seeds=5, seed=7)
    res = friedman(runs, "length")
    assert res.n_scenarios == 6 and res.n_configs == 4 and res.dropped == ()
    med = runs.assign(loss=runs["length"].fillna(inf)).groupby(["scenario", "planner"])["loss"].median().unstack()
    expect = stats.rankdata(med.to_numpy(), axis=1).mean(axis=0)
    assert res.mean_ranks[med.columns].to_numpy() == pytest.approx(expect)
    ref = stats.friedmanchisquare(*med.to_numpy().T)
    assert res.statistic == pytest.approx(ref.statistic) and res.pvalue == pytest.approx(ref.pvalue)
    assert res.cd == pytest.approx(nemenyi_cd(4, 6))
    n, k, chi2 = 6, 4, res.statistic
    assert res.iman_davenport == pytest.approx((n - 1) * chi2 / (n * (k - 1) - chi2))
    # a scenario missing a planner is dropped and named
    res2 = friedman(runs[~((runs.scenario == "s0") & (runs.planner == "p2"))], "length")
    assert res2.dropped == ("s0",) and res2.n_scenarios == 5
    with pytest.raises(InvalidParameterError, match="at least 2 planners"):
        friedman(runs[runs.planner == "p1"], "length")


def test_nemenyi_pvalues_from_scikit_posthocs_agree_with_the_critical_difference():
    for seed in range(8):
        runs = random_runs(("p1", "p2", "p3", "p4", "p5"), [f"s{i}" for i in range(12)], n_seeds=3, seed=seed)
        res = friedman(runs, "length")
        p = res.nemenyi_pvalues()
        r = res.mean_ranks
        for a_, b_ in itertools.combinations(r.index, 2):
            if abs(abs(r[a_] - r[b_]) - res.cd) > 1e-9:
                assert (p.loc[a_, b_] < res.alpha) == (abs(r[a_] - r[b_]) > res.cd)


def test_cliques():
    rows = {f"s{i}": {"a": [1.0], "b": [2.0], "c": [3.0], "d": [4.0]} for i in range(3)}
    rows["s3"] = {"a": [2.0], "b": [1.0], "c": [4.0], "d": [3.0]}
    res = friedman(make_runs(rows), "length")
    assert list(res.mean_ranks.index) == ["a", "b", "c", "d"]
    r = res.mean_ranks.to_numpy()
    expected = []
    for i, j in itertools.combinations(range(4), 2):
        members = tuple(res.mean_ranks.index[i : j + 1])
        if r[j] - r[i] < res.cd and not any(set(members) <= set(e) for e in expected):
            expected = [e for e in expected if not set(e) <= set(members)] + [members]
    assert res.cliques() == expected


def test_summarize_metrics_covers_registered_columns():
    runs = random_runs(n_seeds=4)
    out = summarize_metrics(runs)
    assert set(out["metric"]) == {"length", "energy", "turns", "planning_time", "success", "iterations", "evaluations"}
    one = out[(out.metric == "energy") & (out.scenario == "s1") & (out.config == "aco.a")].iloc[0]
    vals = runs[(runs.scenario == "s1") & (runs.planner == "aco.a") & (runs.success == 1)]["energy"]
    assert one["median"] == pytest.approx(vals.median()) and one["sd"] == pytest.approx(vals.std())
    assert isinstance(out, pd.DataFrame)


def test_wilcoxon_with_ties_matches_scipy_permutation_branch():
    rng = np.random.default_rng(6)
    for n in (5, 7, 9):
        for _ in range(3):
            d = rng.integers(-3, 4, n).astype(float)  # ties and zeros
            if not d.any():
                continue
            ref = stats.wilcoxon(d)  # scipy enumerates all 2^n sign flips here
            _, stat, p, _ = compare_losses(d, np.zeros(n), paired=True)
            assert stat == ref.statistic and p == pytest.approx(ref.pvalue, rel=1e-9)
    # above 13 pairs scipy's normal approximation is used, as in scipy
    d = rng.integers(-3, 4, 20).astype(float)
    assert compare_losses(d, np.zeros(20), paired=True)[2] == pytest.approx(stats.wilcoxon(d).pvalue)


def test_lengths_equal_up_to_summation_noise_are_ties():
    import pandas as pd

    from pathzoo.analysis.stats import pairwise_tests

    rows = []
    for planner, length in (("a", 13.899494936611665), ("b", 13.899494936611667)):
        for seed in range(6):
            rows.append(dict(run_key=f"{planner}|h|s|{seed}", experiment="e", planner=planner, planner_version="1",
                             params_hash="h" + planner, params={}, scenario="s", seed_index=seed, seed=seed,
                             status="solved", valid=True, invalid_reason="", message="", wall_time_s=0.1,
                             cpu_time_s=0.1, iterations=1, evaluations=1, length=length, success=1.0))
    res = pairwise_tests(pd.DataFrame(rows), "length", direction="min", paired=False)
    assert res["a12"].iloc[0] == 0.5
    assert res["winner"].iloc[0] not in ("a", "b")
