"""Suggestions for a mistyped name: the known names closest to it, closest first."""

from __future__ import annotations

import difflib
from typing import Iterable

__all__ = ["closest", "did_you_mean"]


def closest(word: str, known: Iterable[str], n: int = 3) -> list[str]:
    """Up to ``n`` names of ``known`` similar to ``word``, the most similar first (:func:`difflib.get_close_matches`).

    Examples
    --------
    >>> closest("lenght", ["length", "energy", "turns"])
    ['length']
    """
    return difflib.get_close_matches(word, list(known), n=n, cutoff=0.6)


def did_you_mean(word: str, known: Iterable[str]) -> str:
    """``"; did you mean 'length'?"`` (or ``"... one of 'a', 'b'?"``) for the closest names, else ``""``."""
    close = closest(word, known)
    if not close:
        return ""
    if len(close) == 1:
        return f"; did you mean '{close[0]}'?"
    return "; did you mean one of " + ", ".join(f"'{c}'" for c in close) + "?"
