"""The OMPL motion validator applies the harness's own segment rule, and the evaluation budget."""

import numpy as np
import pytest

from pathzoo import Budget
from pathzoo.rules import segment_problem
from pathzoo.testing import check_scenario
from pathzoo_ompl.engine import SegmentValidator, _Run, segment_clear


def _grid(rng, cell_size):
    from pathzoo import Scenario

    occ = rng.random((9, 11)) < 0.3
    occ[0, 0] = occ[-1, -1] = False
    return Scenario(id="v", kind="grid2d", occupancy=occ, cell_size=cell_size, start=[0.5 * cell_size] * 2,
                    goal=[10.5 * cell_size, 8.5 * cell_size])


@pytest.mark.parametrize("cell_size", [1.0, 0.3, 2.5])
def test_compiled_rule_agrees_with_segment_problem(cell_size):
    rng = np.random.default_rng(0)
    scenario = _grid(rng, cell_size)
    h, w = scenario.shape
    centres = (rng.integers(0, [w, h], (300, 2)) + 0.5) * cell_size
    corners = rng.integers(0, [w + 1, h + 1], (300, 2)) * cell_size
    # points within a hair of cell borders and centres: the validator snaps these, so must we
    hairs = np.concatenate([centres, corners]) + rng.choice([-3e-10, 0.0, 3e-10], (600, 2)) * cell_size
    anywhere = rng.uniform(0, 1, (300, 2)) * scenario.extent
    pts = np.clip(np.concatenate([centres, corners, hairs, anywhere]), 0, scenario.extent)
    pairs = rng.integers(0, len(pts), (6000, 2))
    for i, j in pairs:
        expected = segment_problem(scenario, pts[i], pts[j]) is None
        assert segment_clear(scenario.blocked, cell_size, *pts[i], *pts[j]) == expected, (pts[i], pts[j])


def _validator(scenario, evaluations):
    from ompl import base as ob

    space = ob.RealVectorStateSpace(2)
    space.setBounds(0.0, float(scenario.extent.max()))
    si = ob.SpaceInformation(space)
    budget = Budget(evaluations=evaluations)
    run = _Run(budget, budget.start(), 1, None)
    return SegmentValidator(si, scenario, run), run, si


def test_terrain_motions_respect_the_slope_limits():
    scenario = check_scenario("terrain")
    validator, run, si = _validator(scenario, None)
    rng = np.random.default_rng(1)
    pts = rng.uniform(0, 1, (2000, 2)) * scenario.extent
    verdicts = []
    for a, b in zip(pts[::2], pts[1::2]):
        got = validator.checkMotion(tuple(a), tuple(b))
        assert got == (segment_problem(scenario, a, b) is None)
        verdicts.append(got)
    assert any(verdicts) and not all(verdicts)
    assert run.motions == 1000


def test_motions_beyond_the_evaluation_limit_are_refused_unchecked():
    scenario = check_scenario("grid2d")
    validator, run, _ = _validator(scenario, 3)
    free = (tuple((1.5, 1.5)), tuple((2.5, 2.5)))
    assert [validator.checkMotion(*free) for _ in range(5)] == [True, True, True, False, False]
    assert run.motions == 3
