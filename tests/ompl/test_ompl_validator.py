"""The OMPL motion validator applies the harness's own segment rule, and the evaluation budget."""

import numpy as np
import pytest

from pathzoo.rules import segment_problem
from pathzoo.testing import check_scenario
from pathzoo_ompl.checks import CompiledChecks
from pathzoo_ompl.engine import compiled_checks, segment_validator, state_checker


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
    checks = CompiledChecks(scenario.blocked, cell_size)
    for i, j in pairs:
        expected = segment_problem(scenario, pts[i], pts[j]) is None
        assert checks.motion(*pts[i], *pts[j]) == expected, (pts[i], pts[j])
    assert checks.motions == len(pairs)


@pytest.mark.parametrize("cell_size", [1.0, 0.3])
def test_compiled_state_check_is_inside_and_free(cell_size):
    rng = np.random.default_rng(5)
    scenario = _grid(rng, cell_size)
    h, w = scenario.shape
    checks = CompiledChecks(scenario.blocked, cell_size)
    pts = rng.uniform(-0.2, 1.2, (3000, 2)) * scenario.extent
    for x, y in pts:
        col, row = int(np.floor(x / cell_size)), int(np.floor(y / cell_size))
        expected = 0 <= row < h and 0 <= col < w and not scenario.blocked[row, col]
        assert checks.point(x, y) == expected, (x, y)


def _validator(scenario, evaluations):
    from ompl import base as ob

    space = ob.RealVectorStateSpace(2)
    space.setBounds(0.0, float(scenario.extent.max()))
    si = ob.SpaceInformation(space)
    checks = compiled_checks(scenario, evaluations)
    return segment_validator(si, checks), checks, si


def test_ompl_calls_reach_the_compiled_checks():
    """Through OMPL's own C++ calls (SpaceInformation.isValid, checkMotion), each check is the compiled one."""
    from ompl import base as ob

    scenario = check_scenario("grid2d")
    validator, checks, si = _validator(scenario, None)
    si.setStateValidityChecker(state_checker(checks))
    si.setMotionValidator(validator)
    si.setup()
    rng = np.random.default_rng(4)
    pts = rng.uniform(0, 1, (400, 2)) * scenario.extent
    states = []
    for x, y in pts:
        s = si.allocState()
        s[0], s[1] = float(x), float(y)
        states.append(s)
    for s, (x, y) in zip(states, pts):
        assert si.isValid(s) == checks.point(x, y)
    for k in range(len(pts) - 1):
        assert si.checkMotion(states[k], states[k + 1]) == (segment_problem(scenario, pts[k], pts[k + 1]) is None)
    assert isinstance(validator, ob.MotionValidator)
    assert checks.motions == len(pts) - 1  # motions are counted; state checks are not


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
    free = ((1.5, 1.5), (2.5, 2.5))
    assert [validator.checkMotion(*free) for _ in range(5)] == [True, True, True, False, False]
    assert run.motions == 3


def test_terrain_check_is_never_laxer_than_the_judge_near_the_limit():
    from pathzoo import Scenario, VehicleModel

    # a ramp rising along x: every piece of a segment along x has the same slope, so the limit can be hit exactly
    cols = np.arange(12, dtype=float)
    rng = np.random.default_rng(2)
    for limit_offset in (-1e-5, -1e-8, 0.0, 1e-8, 1e-5):
        slope_deg = 20.0
        elevation = np.tile(np.tan(np.radians(slope_deg)) * cols, (6, 1))
        scenario = Scenario(
            id="ramp", kind="terrain", occupancy=np.zeros((6, 12), dtype=bool), cell_size=1.0,
            start=[0.5, 0.5], goal=[11.5, 5.5], elevation=elevation,
            vehicle=VehicleModel(max_climb_deg=slope_deg + limit_offset, max_descent_deg=slope_deg + limit_offset),
        )
        validator, _, _ = _validator(scenario, None)
        for _ in range(200):
            a = rng.uniform([0.5, 0.5], [11.5, 5.5])
            b = rng.uniform([0.5, 0.5], [11.5, 5.5])
            if rng.random() < 0.5:
                b[1] = a[1]  # along the ramp: the steepest direction, slope exactly slope_deg
            if validator.checkMotion(tuple(a), tuple(b)):
                assert segment_problem(scenario, a, b) is None, (a, b, limit_offset)


def test_default_range_caps_ompls_choice_at_eight_cells():
    from pathzoo import Scenario
    from pathzoo_ompl.planners import default_range

    def grid(side, cell_size):
        return Scenario(id="g", kind="grid2d", occupancy=np.zeros((side, side), dtype=bool), cell_size=cell_size,
                        start=[0.5 * cell_size] * 2, goal=[(side - 0.5) * cell_size] * 2)

    assert default_range(grid(32, 1.0)) == pytest.approx(6.4)  # OMPL's own 20% on small maps
    assert default_range(grid(512, 1.0)) == pytest.approx(8.0)
    assert default_range(grid(512, 0.5)) == pytest.approx(4.0)


def test_compiled_checks_own_their_arrays():
    """The checks read the map through addresses: the arrays must live as long as the checks, whatever the input."""
    import gc

    rng = np.random.default_rng(6)
    blocked = rng.random((12, 9)) < 0.4
    checks = CompiledChecks(blocked.T.copy().T[:, ::-1][:, ::-1], 1.0)  # a non-contiguous view of a temporary
    gc.collect()
    for _ in range(3):
        np.ones((12, 9), dtype=bool)  # reuse freed memory, if any was freed
    for r, c in np.ndindex(blocked.shape):
        assert checks.point(c + 0.5, r + 0.5) == (not blocked[r, c])


def test_elevation_must_match_the_map():
    with pytest.raises(ValueError, match="elevation shape"):
        CompiledChecks(np.zeros((3, 4), dtype=bool), 1.0, np.zeros((4, 3)))


def test_compiled_checks_cannot_be_copied_or_pickled():
    import copy
    import pickle

    checks = CompiledChecks(np.zeros((2, 2), dtype=bool), 1.0)
    for clone in (copy.copy, copy.deepcopy, pickle.dumps):
        with pytest.raises(TypeError, match="memory addresses"):
            clone(checks)


@pytest.mark.parametrize("sid", ["testing.air3d", "dsaco.simple"])
def test_compiled_voxel_rule_agrees_with_the_judge(sid):
    """In air volumes the compiled state and motion checks say what the judge says (voxels, pitch)."""
    import pathzoo

    sc = check_scenario("air3d") if sid == "testing.air3d" else pathzoo.load_scenario(sid)
    checks = compiled_checks(sc)
    rng = np.random.default_rng(3)
    a = rng.uniform(0, 1, (400, 3)) * sc.extent
    b = np.clip(a + rng.normal(0, 4, (400, 3)) * sc.cell_sizes, 0, np.nextafter(sc.extent, 0))
    agree = accepted = 0
    for p, q in zip(a, b):
        free = not sc.blocked[tuple(sc.cell_of(p[None])[0])]
        assert checks.point_3d(*p) == free
        ok = checks.motion_3d(*p, *q)
        judge = segment_problem(sc, p, q) is None
        assert not ok or judge  # never laxer than the judge
        agree += ok == judge
        accepted += ok
    assert agree >= 0.99 * len(a) and accepted > 20


@pytest.mark.parametrize("pid", ["ompl.rrtconnect", "ompl.rrtstar", "ompl.prmstar"])
def test_ompl_plans_in_air_volumes(pid):
    """A 3-D solution on the kit's volume; on dsaco.simple (turn limit 60 deg, not modelled) valid or stated."""
    import pathzoo
    from pathzoo.rules import validate_path

    planner = pathzoo.make_planner(pid)
    sc = check_scenario("air3d")
    result = planner.plan(sc, budget=pathzoo.Budget(iterations=50), rng=np.random.default_rng(0))
    assert result.solved and result.path.shape[1] == 3 and validate_path(sc, result.path)
    sc = pathzoo.load_scenario("dsaco.simple")
    result = planner.plan(sc, budget=pathzoo.Budget(iterations=50), rng=np.random.default_rng(0))
    assert (result.solved and validate_path(sc, result.path)) or (not result.solved and result.message)
