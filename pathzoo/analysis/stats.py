"""Pairwise tests within a scenario: Mann-Whitney U or Wilcoxon signed-rank, Holm correction, Vargha-Delaney A12.

Every comparison is two-sided and works on *losses* (see
:func:`pathzoo.analysis.frame.loss_values`): the metric itself for metrics to
minimise, its negative for metrics to maximise, and ``+inf`` for every run
that did not succeed. Failed runs are therefore worse than every successful
run and tied with each other, and a planner cannot look good by failing on
the hard seeds. Success rate is reported separately by
:func:`pathzoo.analysis.summary.summarize`. The statistical choices are
explained in ``docs/statistics.md``.
"""

from __future__ import annotations

import functools
import itertools
import math
import warnings
from typing import Sequence

import numpy as np
import pandas as pd
from scipy import stats

from pathzoo.analysis.frame import Direction, loss_values, metric_info, with_config
from pathzoo.analysis.significance import ALPHA
from pathzoo.core.errors import InvalidParameterError

__all__ = [
    "A12_THRESHOLDS",
    "a12",
    "a12_magnitude",
    "holm",
    "min_pvalue",
    "runs_needed",
    "compare_losses",
    "pair_by_seed",
    "pairwise_tests",
]

A12_THRESHOLDS: tuple[tuple[float, str], ...] = ((0.71, "large"), (0.64, "medium"), (0.56, "small"))
"""Vargha & Delaney (2000) thresholds on ``max(A, 1 - A)``; below 0.56 is negligible."""


def holm(pvalues: Sequence[float] | np.ndarray) -> np.ndarray:
    """Holm's step-down adjusted p-values (statsmodels' ``multipletests(method="holm")``).

    Rejecting where the adjusted value is below alpha controls the family-wise
    error rate at alpha (Holm 1979). NaN p-values (undefined tests) count as 1
    in the family and stay NaN in the output.
    """
    from statsmodels.stats.multitest import multipletests

    p = np.asarray(pvalues, dtype=np.float64).reshape(-1)
    if len(p) == 0:
        return p.copy()
    adj = multipletests(np.where(np.isnan(p), 1.0, p), method="holm")[1]
    adj[np.isnan(p)] = np.nan
    return adj


def min_pvalue(n_a: int, n_b: int, *, paired: bool) -> float:
    """The smallest two-sided p-value a rank test can reach with these sample sizes.

    Wilcoxon signed-rank on ``n`` pairs (``n = n_a = n_b``): ``2 / 2**n``, when
    every difference has the same sign. Mann-Whitney U: ``2 / C(n_a + n_b, n_a)``,
    when the two samples do not overlap (exact null distribution). Both are
    capped at 1. Below ``alpha`` after the multiple-comparison correction is
    a precondition for any ``better``/``worse`` verdict.
    """
    if n_a < 1 or n_b < 1:
        return 1.0
    if paired:
        return min(1.0, 2.0 * 0.5 ** min(n_a, n_b))
    return min(1.0, 2.0 / math.comb(n_a + n_b, n_a))


@functools.lru_cache(maxsize=256)
def runs_needed(family: int, alpha: float, *, paired: bool, limit: int = 1000) -> int:
    """Fewest runs per configuration for which one test in a Holm family of ``family`` can reach ``alpha``.

    With equal sample sizes ``n`` per side; the smallest Holm-adjusted p-value
    is ``family * min_pvalue(n, n)``. Returns ``limit`` when even that is not enough.
    """
    for n in range(1, limit):
        if family * min_pvalue(n, n, paired=paired) < alpha:
            return n
    return limit


def a12(loss_a: np.ndarray, loss_b: np.ndarray) -> float:
    """Vargha-Delaney A12: probability that a run of ``a`` beats a run of ``b``.

    ``A = P(L_a < L_b) + 0.5 P(L_a = L_b)`` over all pairs of runs, with
    losses (smaller is better; failed runs ``+inf`` tie with each other).
    Computed from mid-ranks as ``(R_b - n_b (n_b + 1) / 2) / (n_a n_b)``,
    where ``R_b`` is the rank sum of ``b`` in the pooled sample (ascending
    loss), i.e. the Mann-Whitney U of ``b`` divided by the number of pairs.
    NaN when a sample is empty.
    """
    a = np.asarray(loss_a, dtype=np.float64)
    b = np.asarray(loss_b, dtype=np.float64)
    na, nb = len(a), len(b)
    if na == 0 or nb == 0:
        return float("nan")
    ranks = stats.rankdata(np.concatenate([a, b]))
    rb = ranks[na:].sum()
    return float((rb - nb * (nb + 1) / 2) / (na * nb))


def a12_magnitude(a: float) -> str:
    """``negligible``, ``small``, ``medium`` or ``large`` (see :data:`A12_THRESHOLDS`)."""
    if not np.isfinite(a):
        return "–"
    d = max(a, 1.0 - a)
    for threshold, name in A12_THRESHOLDS:
        if d >= threshold:
            return name
    return "negligible"


def _tame(x: np.ndarray) -> np.ndarray:
    """Replace ±inf by finite values beyond every finite one (order and ties kept)."""
    fin = np.abs(x[np.isfinite(x)])
    big = 2.0 * (fin.max() if len(fin) else 0.0) + 1.0
    return np.where(np.isposinf(x), big, np.where(np.isneginf(x), -big, x))


_WILCOXON_PERMUTATION_MAX_N = 13
"""scipy's ``wilcoxon`` runs a full sign-flip permutation test for tied or zero differences up to this size."""


def _wilcoxon_exact_tied(ranks: np.ndarray, positive: np.ndarray) -> tuple[float, float]:
    """Exact two-sided Wilcoxon p-value given tied mid-ranks, by counting sign assignments.

    The null distribution of ``R+`` over all ``2^n`` sign flips is built by
    dynamic programming on doubled ranks (mid-ranks are multiples of 1/2).
    It is the distribution scipy's permutation branch enumerates, computed
    in microseconds instead of seconds; the result is identical.
    """
    r2 = np.rint(2.0 * ranks).astype(np.int64)
    counts = np.zeros(int(r2.sum()) + 1)
    counts[0] = 1.0
    for v in r2:
        shifted = np.zeros_like(counts)
        shifted[v:] = counts[: len(counts) - v]
        counts = counts + shifted
    obs = int(r2[positive].sum())
    total = counts.sum()
    p = 2.0 * min(counts[: obs + 1].sum(), counts[obs:].sum()) / total
    r_plus = obs / 2.0
    return float(min(r_plus, ranks.sum() - r_plus)), float(min(p, 1.0))


def compare_losses(loss_a: np.ndarray, loss_b: np.ndarray, *, paired: bool) -> tuple[str, float, float, int]:
    """Two-sided test of two loss samples.

    Parameters
    ----------
    loss_a, loss_b : ndarray
        Losses (``+inf`` = failed run). When ``paired``, equal lengths and
        element ``i`` of both come from the same seed index.
    paired : bool
        Wilcoxon signed-rank on the differences (pairs where both runs failed
        are zero differences, dropped by Wilcoxon's rule; a pair where only
        one failed is a difference larger than any finite one) instead of
        Mann-Whitney U.

    Returns
    -------
    test : str
        ``"wilcoxon"`` or ``"mannwhitneyu"``.
    statistic : float
        scipy's statistic (Wilcoxon: the smaller signed-rank sum; U of ``a``).
    p : float
        Two-sided p-value; 1.0 when all values (differences) are equal.
    direction : int
        -1 when ``a`` tends to be better, +1 when ``b`` does, 0 otherwise
        (the sign of the rank evidence, not of a significance test).
    """
    a = np.asarray(loss_a, dtype=np.float64)
    b = np.asarray(loss_b, dtype=np.float64)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        warnings.simplefilter("ignore", UserWarning)
        if paired:
            both_failed = np.isposinf(a) & np.isposinf(b)
            d = _tame(np.where(both_failed, 0.0, a - b))
            nz = d[d != 0]
            if len(nz) == 0:
                return "wilcoxon", 0.0, 1.0, 0
            r = stats.rankdata(np.abs(nz))
            sign = int(np.sign(r[nz > 0].sum() - r[nz < 0].sum()))
            tied = len(nz) < len(d) or len(np.unique(r)) < len(r)
            if tied and len(d) <= _WILCOXON_PERMUTATION_MAX_N:
                stat, p = _wilcoxon_exact_tied(r, nz > 0)
                return "wilcoxon", stat, p, sign
            res = stats.wilcoxon(d)
            return "wilcoxon", float(res.statistic), float(res.pvalue), sign
        pooled = _tame(np.concatenate([a, b]))
        ta, tb = pooled[: len(a)], pooled[len(a) :]
        if len(ta) == 0 or len(tb) == 0:
            return "mannwhitneyu", float("nan"), float("nan"), 0
        if np.all(pooled == pooled[0]):
            return "mannwhitneyu", len(ta) * len(tb) / 2.0, 1.0, 0
        mwu = stats.mannwhitneyu(ta, tb, alternative="two-sided")
        sign = int(np.sign(0.5 - a12(a, b)))  # b beats a more often -> +1
        return "mannwhitneyu", float(mwu.statistic), float(mwu.pvalue), sign


def pair_by_seed(
    a: pd.DataFrame, b: pd.DataFrame, paired: bool | str
) -> tuple[bool, pd.DataFrame, pd.DataFrame]:
    """Decide pairing and align two configurations' runs on one scenario by ``seed_index``.

    ``paired="auto"`` pairs when both have the same set of seed indices, each
    used once. ``paired=True`` pairs on the seed indices both have (runs
    without a partner are left out) and raises when a seed index repeats.
    ``paired=False`` never pairs.

    Returns
    -------
    paired : bool
        Whether the runs are paired.
    a, b : DataFrame
        Sorted by seed index and restricted to the common ones when paired,
        unchanged otherwise.
    """
    if paired not in (True, False, "auto"):
        raise InvalidParameterError(f"paired must be True, False or 'auto', got {paired!r}")
    if paired is False:
        return False, a, b
    sa, sb = a["seed_index"], b["seed_index"]
    unique = sa.is_unique and sb.is_unique
    if paired == "auto":
        if not (unique and len(sa) > 0 and set(sa) == set(sb)):
            return False, a, b
    elif not unique:
        raise InvalidParameterError("paired=True needs each seed_index at most once per planner and scenario")
    common = sorted(set(sa) & set(sb))
    return True, a.set_index("seed_index").loc[common].reset_index(), b.set_index("seed_index").loc[common].reset_index()


def pairwise_tests(
    runs: pd.DataFrame,
    metric: str = "length",
    *,
    direction: Direction | None = None,
    reference: str | None = None,
    alpha: float = ALPHA,
    paired: bool | str = "auto",
) -> pd.DataFrame:
    """Test every pair of configurations on every scenario, Holm-corrected per scenario.

    Parameters
    ----------
    runs : DataFrame
        One row per run.
    metric : str
        Metric id.
    direction : {"min", "max"}, optional
        Override the registered direction.
    reference : str, optional
        Only compare this configuration (as ``a``) with each other one (as
        ``b``); the Holm family is then those ``k - 1`` tests per scenario.
        Without it, all ``k (k - 1) / 2`` pairs form the family.
    alpha : float
        Level for the ``winner`` column.
    paired : bool or "auto"
        See :func:`pair_by_seed`.

    Returns
    -------
    DataFrame
        One row per (scenario, a, b): ``n_a, n_b, test, paired, statistic,
        p, p_holm, a12`` (probability that a run of ``a`` beats a run of
        ``b``), ``magnitude``, ``testable`` (whether the sample sizes can reach
        ``alpha`` at all after Holm's correction over the scenario's family, see
        :func:`min_pvalue`), ``runs_needed`` (runs per side for which they
        could) and ``winner`` (``"a"``, ``"b"`` or ``"tie"``: the better side
        when ``p_holm < alpha``). ``attrs["metric"]`` holds
        the metric's :class:`~pathzoo.analysis.frame.MetricInfo`.

    Raises
    ------
    InvalidParameterError
        ``reference`` is not a configuration in ``runs``, or ``alpha`` is not in (0, 1).
    """
    if not 0.0 < alpha < 1.0:
        raise InvalidParameterError(f"alpha must be in (0, 1), got {alpha!r}")
    info = metric_info(metric, direction)
    df = with_config(runs, metric)
    df["loss"] = loss_values(df[metric], df["success"], info.direction)
    configs = sorted(df["config"].unique())
    if reference is not None and reference not in configs:
        raise InvalidParameterError(f"reference '{reference}' is not among the planners: {', '.join(configs)}")
    rows = []
    for scenario, sdf in df.groupby("scenario", sort=True):
        groups = {c: g for c, g in sdf.groupby("config")}
        if reference is not None:
            pairs = [(reference, c) for c in configs if c != reference]
        else:
            pairs = list(itertools.combinations(configs, 2))
        block = []
        for ca, cb in pairs:
            if ca not in groups or cb not in groups:
                continue
            is_paired, ga, gb = pair_by_seed(groups[ca], groups[cb], paired)
            la, lb = ga["loss"].to_numpy(), gb["loss"].to_numpy()
            if is_paired:
                keep = ~(np.isnan(la) | np.isnan(lb))
                la, lb = la[keep], lb[keep]
            else:
                la, lb = la[~np.isnan(la)], lb[~np.isnan(lb)]
            test, stat, p, sign = compare_losses(la, lb, paired=is_paired)
            eff = a12(la, lb)
            block.append(
                dict(scenario=scenario, a=ca, b=cb, n_a=len(la), n_b=len(lb), test=test, paired=is_paired,
                     statistic=stat, p=p, a12=eff, magnitude=a12_magnitude(eff), _sign=sign)
            )
        adj = holm([r["p"] for r in block])
        for r, q in zip(block, adj):
            sign = r.pop("_sign")
            r["p_holm"] = q
            r["testable"] = len(block) * min_pvalue(r["n_a"], r["n_b"], paired=r["paired"]) < alpha
            r["runs_needed"] = runs_needed(len(block), alpha, paired=r["paired"])
            r["winner"] = ("a" if sign < 0 else "b" if sign > 0 else "tie") if q < alpha else "tie"
        rows += block
    cols = ["scenario", "a", "b", "n_a", "n_b", "test", "paired", "statistic", "p", "p_holm", "a12", "magnitude",
            "testable", "runs_needed", "winner"]
    out = pd.DataFrame(rows, columns=cols)
    out.attrs["metric"] = info
    out.attrs["alpha"] = alpha
    return out
