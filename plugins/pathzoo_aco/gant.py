"""aco.gant: G-Ant, the green ant of Jabbarpour et al. (IEEE Access, 2017), eqs. 4-16.

Mechanism, with the paper's equations:

- forward ants choose by the *additive* rule
  ``PF_ij ∝ (α τ_ij + β η_ij) · N_j / (N_j + 1)`` (eq. 13), with
  ``η_ij = 1 / ll_ij + v_ij / φ`` (eq. 14): :meth:`GreenAnt.walk_rules`;
- a forward ant that reaches the goal turns into a backward ant that lays
  ``Δτ = 1 / TT + 1 / Ê_c`` on every link of its route after evaporation
  ``τ <- (1 - ρ) τ`` (eqs. 15-16): :meth:`GreenAnt.update_trail`;
- ``Ê_c`` is predicted by the linear power model of eq. 7 whose ``b`` and
  ``C`` an RLS with forgetting factor ``λ_ff`` and an EWMA residual chart
  with weight ``λ_u`` estimate from power data generated with eq. 4 (eqs.
  7-12, :mod:`pathzoo_aco.gant_energy`): :meth:`GreenAnt.init_state`.

Table 3 gives α = 0.4, β = 0.6, ρ = 0.3, φ = 2 m/s, λ_ff = λ_u = 0.98,
Δt = 10 s (mass 30 kg and b = 0 W live in the scenario's vehicle). See
``docs/planners/aco.gant.md`` for every interpretation.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from pathzoo.core.planner import Param
from pathzoo_aco.engine import (
    AntColonyPlanner,
    ColonyProblem,
    ColonyState,
    Pheromone,
    WalkEngine,
    WalkRules,
    Walks,
    colony_params,
    deposit_walks,
)
from pathzoo_aco.gant_energy import RlsEwmaPredictor, synthetic_drive

__all__ = ["GreenAnt", "GantState", "green_heuristic", "PHI", "ENERGY_FLOOR"]

PHI = Param(2.0, "φ, the UGV's maximum speed normalising v in η (G-Ant eq. 14, GGACO eq. 16), m/s",
            low=0.0, low_open=True)
ENERGY_FLOOR = Param(1.0, "lower bound on an energy E in 1/E, J (zero on steep descents without regeneration)",
                     low=0.0, low_open=True)


def green_heuristic(distance: np.ndarray, speed: float, phi: float) -> np.ndarray:
    """``η = 1 / distance + v / φ``: G-Ant's eq. 14, reused by GGACO's eq. 16."""
    return 1.0 / distance + speed / phi


@dataclass
class GantState(ColonyState):
    """Colony state plus the fitted energy predictor and its per-link predictions."""

    predictor: RlsEwmaPredictor | None = None
    link_energy: np.ndarray | None = None
    link_energy_var: np.ndarray | None = None


class GreenAnt(AntColonyPlanner):
    """G-Ant (Jabbarpour et al. 2017) with the parameters of its Table 3."""

    id = "aco.gant"
    version = "1"
    summary = "G-Ant (Jabbarpour et al. 2017): additive rule, travel-time and predicted-energy deposits"
    kinds = frozenset({"grid2d", "terrain"})
    params = {
        **colony_params(n_ants=100, iterations=100, alpha=0.4, beta=0.6, rho=0.3),
        "phi": PHI,
        "tau0": Param(0.0, "initial trail on every link", low=0.0),
        "lambda_ff": Param(0.98, "RLS forgetting factor λ_ff", low=0.0, high=1.0, low_open=True),
        "lambda_u": Param(0.98, "EWMA weight λ_u of the residual chart (eq. 9)", low=0.0, high=1.0, low_open=True),
        "dt": Param(10.0, "sampling interval Δt of the power data, s", low=0.0, low_open=True),
        "samples": Param(100, "power samples of the calibration drive", low=3),
        "noise": Param(0.1, "noise SD of the generated power as a fraction of its mean (eq. 4's ε)", low=0.0),
        "energy_floor_j": ENERGY_FLOOR,
    }

    def heuristic(self, problem: ColonyProblem) -> np.ndarray:
        """Eq. 14: ``η_ij = 1 / ll_ij + v_ij / φ`` with ``ll`` the 3-D link length and ``v`` the cruise speed."""
        return green_heuristic(problem.graph.length, problem.scenario.vehicle.cruise_speed, self.phi)

    def walk_rules(self, problem: ColonyProblem) -> WalkRules:
        """Eq. 13: the additive rule ``(α τ + β η) · N_j / (N_j + 1)``."""
        return WalkRules.additive(self.alpha, self.heuristic(problem), self.beta,
                                  self.neighbour_factor(problem), **self.walk_options(problem))

    def initial_trail(self, problem: ColonyProblem) -> float:
        """``τ0`` (default 0: the additive rule needs no initial trail)."""
        return self.tau0

    def init_state(self, problem: ColonyProblem, rules: WalkRules, trail: Pheromone, engine: WalkEngine,
                   rng: np.random.Generator) -> GantState:
        """Fit ``b̂, Ĉ`` on a generated drive (flat ground) and predict every link's energy.

        A link of grade ``θ`` driven at cruise speed ``v`` for ``TT = ll / v``
        seconds is predicted to draw ``P̂ = W v (Ĉ + θ) + b̂`` (eq. 7 with the
        linearised grade of eq. 5, clipped at ``b̂`` as the vehicle model has no
        regeneration), i.e. ``Ê = P̂ TT``; its variance follows eq. 12.
        """
        vehicle = problem.scenario.vehicle
        drive = synthetic_drive(vehicle, rng, self.samples, self.dt, self.phi, self.noise)
        predictor = RlsEwmaPredictor(lambda_ff=self.lambda_ff, lambda_u=self.lambda_u)
        for x, y in zip(drive.x, drive.y):
            predictor.update(float(x), float(y))
        g = problem.graph
        speed = vehicle.cruise_speed
        x = vehicle.weight_n * speed
        power = np.maximum(x * (predictor.c + g.slope), 0.0) + predictor.b
        travel = g.length / speed
        return GantState(problem, rules, trail, rng, predictor=predictor, link_energy=power * travel,
                         link_energy_var=travel * self.dt * float(predictor.power_variance(x)))

    def update_trail(self, state: ColonyState, walks: Walks, costs: np.ndarray) -> None:
        """Eqs. 15-16: evaporate, then each backward ant lays ``1 / TT + 1 / Ê_c`` on its route's links."""
        assert isinstance(state, GantState) and state.link_energy is not None
        state.trail.evaporate(self.rho)
        ok = np.flatnonzero(walks.reached)
        if ok.size == 0:
            return
        g = state.problem.graph
        travel_time = costs[ok] / state.problem.scenario.vehicle.cruise_speed  # costs: the walks' lengths
        energy = np.maximum(walks.totals(state.link_energy)[ok], self.energy_floor_j)
        deposit_walks(state.trail, g.indices, walks.flat, walks.offsets, ok, 1.0 / travel_time + 1.0 / energy)

    def result_extras(self, state: ColonyState) -> dict[str, Any]:
        """The fitted power model and the predicted energy (mean, SD) of the returned route."""
        assert isinstance(state, GantState) and state.predictor is not None
        out: dict[str, Any] = {"b_hat_w": state.predictor.b, "c_hat": state.predictor.c,
                               "rls_resets": state.predictor.resets}
        if state.best_edges is not None and state.link_energy is not None and state.link_energy_var is not None:
            out["predicted_energy_j"] = float(state.link_energy[state.best_edges].sum())
            out["predicted_energy_sd_j"] = float(np.sqrt(state.link_energy_var[state.best_edges].sum()))
        return out
