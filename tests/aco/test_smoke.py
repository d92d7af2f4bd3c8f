"""Every ant-colony planner on its paper's scenario packs (and the classics on the same maps), tiny budgets."""

from __future__ import annotations

import numpy as np
import pytest

import pathzoo
from pathzoo import Budget
from pathzoo.rules import validate_path

CASES = [
    # G-Ant: its 10 x 10 space (Fig. 7) and terrain
    ("aco.gant", "gant.fig7", {}),
    ("aco.gant", "ggaco.hugo", {"n_ants": 10}),
    # GGACO: real-DEM traversable maps, and a grid
    ("aco.ggaco", "ggaco.hugo", {}),
    ("aco.ggaco", "ggaco.jacksboro", {"n_ants": 5}),
    ("aco.ggaco", "gant.fig7", {}),
    # the classics on both kinds
    ("aco.as", "gant.fig7", {}),
    ("aco.mmas", "gant.fig7", {}),
    ("aco.acs", "gant.fig7", {}),
    ("aco.as", "ggaco.hugo", {}),
    ("aco.mmas", "ggaco.hugo", {}),
    ("aco.acs", "ggaco.hugo", {}),
]


@pytest.mark.parametrize(("planner_id", "scenario_id", "params"), CASES, ids=[f"{p}-{s}" for p, s, _ in CASES])
def test_solves_its_scenario_with_a_tiny_budget(planner_id, scenario_id, params):
    scenario = pathzoo.load_scenario(scenario_id)
    result = pathzoo.make_planner(planner_id, **params).plan(scenario, budget=Budget(iterations=2),
                                                             rng=np.random.default_rng(0))
    assert result.solved, result.message
    verdict = validate_path(scenario, result.path)
    assert verdict, verdict.reason
    assert result.iterations == 2
