"""Across scenarios: Friedman test on per-scenario ranks and the Nemenyi critical difference.

Each scenario is one block. A configuration's value on a scenario is its
penalized median loss (:func:`pathzoo.analysis.summary.summarize`: median over
all runs with failed runs counted as worst), so a configuration that fails
on more than half the runs of a scenario gets the worst rank there, tied with
any other such configuration. Ranks are 1 = best, ties share the average rank
(Demšar 2006, "Statistical comparisons of classifiers over multiple data
sets", JMLR 7:1-30).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd
from scipy import stats

from pathzoo.analysis.frame import Direction
from pathzoo.analysis.summary import summarize
from pathzoo.core.errors import InvalidParameterError

__all__ = ["FriedmanResult", "friedman", "friedman_of_summary", "friedman_statistic", "nemenyi_q", "nemenyi_cd"]


@dataclass(frozen=True)
class FriedmanResult:
    """The Friedman test over scenarios and the Nemenyi critical difference.

    Attributes
    ----------
    ranks : DataFrame
        Rank of each configuration (columns) on each scenario (rows).
    mean_ranks : Series
        Average rank per configuration, best (lowest) first.
    statistic : float
        Friedman chi-square (tie-corrected).
    pvalue : float
        Its p-value (chi-square with ``k - 1`` degrees of freedom).
    iman_davenport : float
        Iman-Davenport F statistic, ``(N - 1) chi2 / (N (k - 1) - chi2)``.
    iman_davenport_pvalue : float
        Its p-value (F with ``k - 1`` and ``(k - 1)(N - 1)`` degrees of freedom).
    cd : float
        Nemenyi critical difference at ``alpha``: two configurations whose
        mean ranks differ by at least ``cd`` differ significantly.
    q_alpha : float
        The Nemenyi ``q`` used for ``cd``.
    alpha : float
        Significance level.
    dropped : tuple of str
        Scenarios left out because not every configuration ran on them.
    metric : str
        Metric id.
    """

    ranks: pd.DataFrame
    mean_ranks: pd.Series
    statistic: float
    pvalue: float
    iman_davenport: float
    iman_davenport_pvalue: float
    cd: float
    q_alpha: float
    alpha: float
    dropped: tuple[str, ...]
    metric: str

    @property
    def n_scenarios(self) -> int:
        """Number of blocks ``N``."""
        return len(self.ranks)

    @property
    def n_configs(self) -> int:
        """Number of configurations ``k``."""
        return self.ranks.shape[1]

    def nemenyi_pvalues(self) -> pd.DataFrame:
        """Pairwise Nemenyi p-values (scikit-posthocs' ``posthoc_nemenyi_friedman`` on the block ranks).

        A pair differs at ``alpha`` exactly when its mean ranks differ by more
        than :attr:`cd` (both come from the studentized range distribution).
        """
        import scikit_posthocs as sp

        return sp.posthoc_nemenyi_friedman(self.ranks)

    def cliques(self) -> list[tuple[str, ...]]:
        """Maximal groups of configurations whose mean ranks all lie within ``cd`` of each other.

        Ordered by mean rank; only groups of two or more, and none contained
        in another (the bars of a critical-difference diagram).
        """
        names = list(self.mean_ranks.index)
        r = self.mean_ranks.to_numpy()
        groups: list[tuple[int, int]] = []
        for i in range(len(r)):
            j = i
            while j + 1 < len(r) and r[j + 1] - r[i] < self.cd:
                j += 1
            if j > i and not (groups and groups[-1][1] >= j):
                groups.append((i, j))
        return [tuple(names[i : j + 1]) for i, j in groups]


def nemenyi_q(k: int, alpha: float = 0.05) -> float:
    """Nemenyi's ``q_alpha``: studentized range quantile for ``k`` groups and infinite df, over √2."""
    if k < 2:
        raise InvalidParameterError(f"the Nemenyi test needs at least 2 planners, got {k}")
    return float(stats.studentized_range.ppf(1.0 - alpha, k, np.inf) / math.sqrt(2.0))


def nemenyi_cd(k: int, n: int, alpha: float = 0.05) -> float:
    """Critical difference ``q_alpha * sqrt(k (k + 1) / (6 N))`` for ``k`` planners on ``n`` scenarios."""
    if n < 1:
        raise InvalidParameterError(f"the Nemenyi test needs at least 1 scenario, got {n}")
    return nemenyi_q(k, alpha) * math.sqrt(k * (k + 1) / (6.0 * n))


def friedman_statistic(ranks: np.ndarray) -> tuple[float, float]:
    """Tie-corrected Friedman chi-square and p-value of an ``(N, k)`` matrix of within-block ranks.

    ``chi2 = (12 / (N k (k + 1)) sum_j R_j^2 - 3 N (k + 1)) / C`` with
    ``R_j`` the rank sums and ``C = 1 - sum(t^3 - t) / (N k (k^2 - 1))`` over
    tie groups of size ``t``. Blocks where every configuration ties carry no
    information; when all do, the statistic is 0 and the p-value 1.
    """
    r = np.asarray(ranks, dtype=np.float64)
    n, k = r.shape
    ties = 0.0
    for row in r:
        _, counts = np.unique(row, return_counts=True)
        ties += float((counts**3 - counts).sum())
    c = 1.0 - ties / (n * k * (k * k - 1))
    if c <= 0:
        return 0.0, 1.0
    chi2 = (12.0 / (n * k * (k + 1)) * float((r.sum(axis=0) ** 2).sum()) - 3.0 * n * (k + 1)) / c
    chi2 = max(chi2, 0.0)
    return chi2, float(stats.chi2.sf(chi2, k - 1))


def friedman(
    runs: pd.DataFrame,
    metric: str = "length",
    *,
    direction: Direction | None = None,
    alpha: float = 0.05,
) -> FriedmanResult:
    """Friedman test across scenarios with the Nemenyi critical difference.

    Parameters
    ----------
    runs : DataFrame
        One row per run.
    metric : str
        Metric id.
    direction : {"min", "max"}, optional
        Override the registered direction.
    alpha : float
        Level of the critical difference.

    Raises
    ------
    InvalidParameterError
        Fewer than two configurations, or no scenario on which all ran.
    """
    if not 0.0 < alpha < 1.0:
        raise InvalidParameterError(f"alpha must be in (0, 1), got {alpha!r}")
    return friedman_of_summary(summarize(runs, metric, direction=direction), alpha=alpha)


def friedman_of_summary(summary: pd.DataFrame, *, alpha: float = 0.05) -> FriedmanResult:
    """:func:`friedman` of the runs whose :func:`~pathzoo.analysis.summary.summarize` table is ``summary``.

    Parameters
    ----------
    summary : DataFrame
        A :func:`~pathzoo.analysis.summary.summarize` table (its
        ``penalized_median`` column and ``attrs["metric"]`` are used).
    alpha : float
        Level of the critical difference.

    Raises
    ------
    InvalidParameterError
        ``alpha`` out of (0, 1), fewer than two configurations, or no scenario on which all ran.
    """
    if not 0.0 < alpha < 1.0:
        raise InvalidParameterError(f"alpha must be in (0, 1), got {alpha!r}")
    info = summary.attrs["metric"]
    metric = info.id
    sign = 1.0 if info.direction == "min" else -1.0
    table = summary.pivot(index="scenario", columns="config", values="penalized_median") * sign
    k = table.shape[1]
    if k < 2:
        raise InvalidParameterError(f"the Friedman test needs at least 2 planners, got {k}")
    complete = table.notna().all(axis=1)
    dropped = tuple(str(s) for s in table.index[~complete])
    table = table[complete]
    if table.empty:
        raise InvalidParameterError("no scenario has runs of every planner; the Friedman test needs complete blocks")
    ranks = pd.DataFrame(stats.rankdata(table.to_numpy(), axis=1), index=table.index, columns=table.columns)
    n = len(ranks)
    chi2, p = friedman_statistic(ranks.to_numpy())
    denom = n * (k - 1) - chi2
    if n > 1 and denom > 0:
        f = (n - 1) * chi2 / denom
        pf = float(stats.f.sf(f, k - 1, (k - 1) * (n - 1)))
    else:
        f, pf = (math.inf, 0.0) if n > 1 else (math.nan, math.nan)
    return FriedmanResult(
        ranks=ranks,
        mean_ranks=ranks.mean(axis=0).sort_values(kind="stable"),
        statistic=chi2,
        pvalue=p,
        iman_davenport=f,
        iman_davenport_pvalue=pf,
        cd=nemenyi_cd(k, n, alpha),
        q_alpha=nemenyi_q(k, alpha),
        alpha=alpha,
        dropped=dropped,
        metric=metric,
    )
