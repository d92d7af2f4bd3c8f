"""Mamdani fuzzy controller of a GA's crossover and mutation rates, from population diversity and progress.

Inputs, each on ``[0, 1]`` with triangular sets *low* ``(0, 0, .5)``,
*medium* ``(0, .5, 1)`` and *high* ``(.5, 1, 1)``:

- **diversity** ``D``: for real genes, the mean over genes of the
  population's standard deviation divided by that of a uniform spread over
  the gene's bounds (``width / sqrt(12)``), so a random population reads
  about 1 and a converged one 0; for move genes (8 categories), the mean
  over genes of ``(1 - share of the commonest move) / (7/8)``. Clipped to 1.
  Encodings with their own ``diversity(population)`` (the variable-length
  cell chains: mean Jaccard distance of consecutive individuals' cell sets)
  use that instead.
- **progress** ``P``: relative improvement of the best cost over the last
  ``window`` generations, divided by ``progress_scale`` and clipped to 1
  (the first finite best after only infinite ones counts as full progress).

Outputs, on ``[cxpb_min, cxpb_max]`` and ``[mutpb_min, mutpb_max]``, with
the same three triangular sets stretched over each range.

Rules (rows: diversity low / medium / high; columns: progress low / medium / high)::

    mutation   high    high    medium        crossover  low     medium  medium
               medium  medium  low                      medium  high    high
               low     low     low                      high    high    high

A converged, stalled population is shaken by mutation and rests crossover;
a diverse population leans on crossover to mix good building blocks. Rules
fire with ``min``, outputs are clipped to the firing strength, aggregated
with ``max`` and defuzzified by centroid, with scikit-fuzzy's low-level API
(``trimf``, ``interp_membership``, ``defuzz``; the ``skfuzzy.control``
layer needs networkx and is slower).
"""

from __future__ import annotations

import math
from typing import Any, Callable

import numpy as np

__all__ = ["FuzzyRateController", "encoding_diversity", "population_diversity"]

_SETS = ((0.0, 0.0, 0.5), (0.0, 0.5, 1.0), (0.5, 1.0, 1.0))  # low, medium, high on [0, 1]
_MUTATION_RULES = np.array([[2, 2, 1], [1, 1, 0], [0, 0, 0]])  # [diversity, progress] -> set index
_CROSSOVER_RULES = np.array([[0, 1, 1], [1, 2, 2], [2, 2, 2]])
_RESOLUTION = 201


def population_diversity(genes: np.ndarray, low: np.ndarray, high: np.ndarray, integer: bool) -> float:
    """Diversity ``D`` in ``[0, 1]`` of a population of shape (n, n_genes); see the module docstring."""
    genes = np.asarray(genes, dtype=np.float64)
    if len(genes) < 2:
        return 0.0
    if integer:
        counts = np.stack([(genes == v).sum(axis=0) for v in range(8)])
        spread = (1.0 - counts.max(axis=0) / len(genes)) / (7.0 / 8.0)
    else:
        width = np.maximum(high - low, 1e-300)
        spread = genes.std(axis=0) / (width / math.sqrt(12.0))
    return float(min(1.0, spread.mean()))


class FuzzyRateController:
    """Sets ``(cxpb, mutpb)`` each generation; see the module docstring.

    One controller lives for one ``plan()`` call (it remembers the best costs).

    Parameters
    ----------
    diversity : callable
        ``diversity(population) -> D`` in ``[0, 1]`` (see :func:`encoding_diversity`).
    cxpb_range, mutpb_range : tuple of float
        Output universes.
    window : int
        Generations over which progress is measured.
    progress_scale : float
        Relative improvement that counts as full progress.
    """

    def __init__(
        self,
        diversity: Callable[[list], float],
        *,
        cxpb_range: tuple[float, float],
        mutpb_range: tuple[float, float],
        window: int,
        progress_scale: float,
    ) -> None:
        import skfuzzy as fuzz

        self._fuzz = fuzz
        self._diversity = diversity
        self._window = window
        self._scale = progress_scale
        self._history: list[float] = []
        self._unit = np.linspace(0.0, 1.0, _RESOLUTION)
        self._in_sets = [fuzz.trimf(self._unit, list(s)) for s in _SETS]
        self._outputs = []
        for lo, hi in (cxpb_range, mutpb_range):
            universe = lo + (hi - lo) * self._unit
            self._outputs.append((universe, [fuzz.trimf(self._unit, list(s)) for s in _SETS]))

    def progress(self, best_cost: float) -> float:
        """Record this generation's best cost and return ``P`` in ``[0, 1]``."""
        self._history.append(best_cost)
        old = self._history[max(0, len(self._history) - 1 - self._window)]
        if not math.isfinite(old):
            return 1.0 if math.isfinite(best_cost) else 0.0
        if old <= 0:
            return 0.0
        return float(min(1.0, max(0.0, (old - best_cost) / old / self._scale)))

    def infer(self, diversity: float, progress: float) -> tuple[float, float]:
        """Mamdani inference: crisp ``(cxpb, mutpb)`` for crisp inputs in ``[0, 1]``."""
        fuzz = self._fuzz
        mu_d = [float(fuzz.interp_membership(self._unit, s, diversity)) for s in self._in_sets]
        mu_p = [float(fuzz.interp_membership(self._unit, s, progress)) for s in self._in_sets]
        strength = np.minimum.outer(mu_d, mu_p)
        crisp = []
        for (universe, sets), rules in zip(self._outputs, (_CROSSOVER_RULES, _MUTATION_RULES)):
            aggregate = np.zeros(_RESOLUTION)
            for i in range(3):
                for j in range(3):
                    aggregate = np.fmax(aggregate, np.fmin(strength[i, j], sets[rules[i, j]]))
            crisp.append(float(fuzz.defuzz(universe, aggregate, "centroid")))
        return crisp[0], crisp[1]

    def __call__(self, population: list, best_cost: float) -> tuple[float, float]:
        """The rates for the next generation of ``population``."""
        return self.infer(self._diversity(population), self.progress(best_cost))


def encoding_diversity(encoding: Any) -> Callable[[list], float]:
    """The diversity measure of an encoding: its own ``diversity`` method, else :func:`population_diversity`."""
    own = getattr(encoding, "diversity", None)
    if own is not None:
        return own
    return lambda population: population_diversity(np.array(population), encoding.low, encoding.high, encoding.integer)
