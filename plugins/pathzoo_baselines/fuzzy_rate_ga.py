"""``evo.fuzzy_rate_ga``: ``evo.ga`` with crossover and mutation rates set each generation by a fuzzy controller."""

from __future__ import annotations

from typing import Any, ClassVar, Mapping

from pathzoo.core import InvalidParameterError, Param
from pathzoo_baselines.encodings import Encoding
from pathzoo_baselines.ga import GA_PARAMS, GaPlanner, RateControl

__all__ = ["FuzzyRateGaPlanner"]


class FuzzyRateGaPlanner(GaPlanner):
    """Fuzzy-rate GA: ``evo.ga`` whose ``cxpb`` and ``mutpb`` follow a Mamdani controller.

    Before every generation the controller of :mod:`pathzoo_baselines.fuzzy`
    reads the population's diversity and the recent progress of the best
    cost and returns the crossover and mutation probabilities of that
    generation. This is the family of fuzzy-adaptive GAs (Herrera & Lozano's
    fuzzy logic controllers of GA parameters); the inputs, sets and rules are
    ours, so it claims no published name. It is *not* Singh et al. 2018's
    fuzzy-GA, FGDACO's Fuzzy-GA rival, which could not be reconstructed (see
    ``docs/planners/evo.fuzzy_rate_ga.md``).
    Everything else (encodings, operators, elitism, budgets, seeding) is
    ``evo.ga``'s.
    """

    id: ClassVar[str] = "evo.fuzzy_rate_ga"
    version: ClassVar[str] = "4"
    summary: ClassVar[str] = "GA whose crossover/mutation rates a fuzzy controller sets (our design; DEAP + scikit-fuzzy)"
    preload: ClassVar[tuple[str, ...]] = (*GaPlanner.preload, "skfuzzy", "pathzoo_baselines.fuzzy")
    params: ClassVar[Mapping[str, Param]] = {
        **GA_PARAMS,
        "cxpb_min": Param(0.5, "lowest crossover probability the controller may set", low=0.0, high=1.0),
        "cxpb_max": Param(1.0, "highest crossover probability the controller may set", low=0.0, high=1.0),
        "mutpb_min": Param(0.05, "lowest mutation probability the controller may set", low=0.0, high=1.0),
        "mutpb_max": Param(0.5, "highest mutation probability the controller may set", low=0.0, high=1.0),
        "window": Param(5, "generations over which progress is measured", low=1, high=10_000),
        "progress_scale": Param(
            0.05, "relative improvement of the best cost over the window that counts as full progress",
            low=0.0, low_open=True, high=1.0,
        ),
    }

    def _check_params(self, values: Mapping[str, Any]) -> None:
        super()._check_params(values)
        for name in ("cxpb", "mutpb"):
            lo, hi = values[f"{name}_min"], values[f"{name}_max"]
            if lo >= hi:
                raise InvalidParameterError(
                    f"{self.id}: parameter '{name}_min' must be below {name}_max={hi}, got {lo}"
                )

    def _rate_control(self, encoding: Encoding) -> RateControl:
        """A fresh :class:`~pathzoo_baselines.fuzzy.FuzzyRateController` for one run."""
        from pathzoo_baselines.fuzzy import FuzzyRateController, encoding_diversity

        return FuzzyRateController(
            encoding_diversity(encoding),
            cxpb_range=(self.cxpb_min, self.cxpb_max),
            mutpb_range=(self.mutpb_min, self.mutpb_max),
            window=self.window,
            progress_scale=self.progress_scale,
        )
