"""The settings of the pairwise tests that callers pass on unchanged: the significance level and the pairing."""

from __future__ import annotations

from typing import TypedDict

__all__ = ["ALPHA", "PairwiseOptions"]

ALPHA = 0.05
"""The significance level of the pairwise tests unless a caller sets another."""


class PairwiseOptions(TypedDict, total=False):
    """The keywords of :func:`~pathzoo.analysis.stats.pairwise_tests` that set the tests themselves.

    A function that tests on its caller's behalf
    (:func:`~pathzoo.analysis.leaderboard.leaderboard`,
    :func:`~pathzoo.analysis.leaderboard.leaderboard_from_db`) takes them as
    ``**tests`` and passes them on, so they are declared, and defaulted, once.

    Attributes
    ----------
    alpha : float
        Significance level (:data:`ALPHA` unless given).
    paired : bool or "auto"
        Whether runs are paired by seed (see :func:`~pathzoo.analysis.stats.pair_by_seed`; ``"auto"`` unless
        given).
    """

    alpha: float
    paired: bool | str
