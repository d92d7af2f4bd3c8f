"""Shards: a deterministic, disjoint split of an experiment's runs (``pathzoo run --shard K/N``).

Shard ``K`` of ``N`` holds the runs whose position in the experiment's run
list (:meth:`~pathzoo.harness.experiment.Experiment.tasks`: planners within
scenarios, then seeds) is ``K - 1`` modulo ``N``. The list depends only on
the experiment file and the installed planners and scenarios, and every
run's key and seed are derived from the experiment alone, so machines that
share no file system each run one shard into a database of their own, and
``pathzoo merge`` joins the databases into exactly the experiment: the
shards are disjoint and together hold every run. Dealing the runs out one
by one (rather than in blocks) gives every shard a similar mix of planners
and scenarios, hence a similar running time.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Sequence, TypeVar

from pathzoo.core.errors import InvalidExperimentError

__all__ = ["Shard", "parse_shard"]

T = TypeVar("T")

_SHARD = re.compile(r"^\s*(\d+)\s*/\s*(\d+)\s*$")


@dataclass(frozen=True)
class Shard:
    """Shard ``index`` (1-based) of ``count``."""

    index: int
    count: int

    def __post_init__(self) -> None:
        if not 1 <= self.index <= self.count:
            raise InvalidExperimentError(f"shard {self.index}/{self.count}: K must be between 1 and N in K/N")

    def select(self, runs: Sequence[T]) -> list[T]:
        """The runs of this shard, in their order: every ``count``-th from position ``index - 1``."""
        return list(runs[self.index - 1::self.count])

    def __str__(self) -> str:
        return f"{self.index}/{self.count}"


def parse_shard(text: str) -> Shard:
    """``"2/4"`` as ``Shard(2, 4)``.

    Raises
    ------
    InvalidExperimentError
        Not of the form K/N with 1 <= K <= N.
    """
    match = _SHARD.match(text)
    if match is None:
        raise InvalidExperimentError(f"shard {text!r}: must be K/N, e.g. 1/4 (the first of four shards)")
    return Shard(int(match.group(1)), int(match.group(2)))
