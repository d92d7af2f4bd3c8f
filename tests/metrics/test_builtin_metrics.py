"""Built-in metrics on paths whose values can be worked out by hand."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pathzoo import MovingObstacle, RunRecord, RunStatus, Scenario, VehicleModel
from pathzoo.core.vehicle import GRAVITY
from pathzoo.rules import validate_path
from pathzoo.metrics import BUILTIN_METRICS
from pathzoo.metrics.geometry import clearance_samples, turn_angles

METRICS = {cls.id: cls() for cls in BUILTIN_METRICS}


def record(path, status=RunStatus.SOLVED, times=None, **kw) -> RunRecord:
    fields = dict(
        run_key="k", experiment="e", planner_id="p", planner_version="1", params={}, params_hash="h",
        scenario_id="s", seed_index=0, seed=1, status=status, valid=status is RunStatus.SOLVED, invalid_reason="",
        message="", wall_time_s=0.25, cpu_time_s=0.2, iterations=7, evaluations=70,
        path=None if path is None else np.asarray(path, float),
        times=None if times is None else np.asarray(times, float),
        history=(), metrics={}, versions={}, started_at="",
    )
    fields.update(kw)
    return RunRecord(**fields)


def measure(scenario: Scenario, rec: RunRecord) -> dict[str, float]:
    if rec.success:
        assert validate_path(scenario, rec.path, rec.times), "test paths must be valid"
    return {mid: m.compute(scenario, rec) for mid, m in METRICS.items()}


def open_grid(h=10, w=10, **kw) -> Scenario:
    return Scenario(id="open", kind="grid2d", occupancy=np.zeros((h, w), bool), cell_size=1.0, **kw)


def test_three_four_five_segment():
    sc = open_grid(start=(0.5, 0.5), goal=(3.5, 4.5))
    m = measure(sc, record([(0.5, 0.5), (3.5, 4.5)]))
    v = sc.vehicle
    assert m["length"] == pytest.approx(5.0)
    assert m["turns"] == 0 and m["turning_angle"] == 0 and m["smoothness"] == 0
    assert m["travel_time"] == pytest.approx(5.0 / v.cruise_speed)
    # eq. 4 on flat ground, no acceleration, b = 0: E = f W L
    assert m["energy"] == pytest.approx(v.rolling_resistance * v.mass_kg * GRAVITY * 5.0)
    # graph optimum: 3 diagonals + 1 straight move; the straight segment is shorter (any-angle)
    assert m["length_ratio"] == pytest.approx(5.0 / (3 * math.sqrt(2) + 1))
    assert m["length_ratio"] < 1
    assert m["success"] == 1 and m["planning_time"] == 0.25 and m["cpu_time"] == 0.2
    assert m["iterations"] == 7 and m["evaluations"] == 70


def test_two_right_angles_and_a_u_turn():
    sc = open_grid(start=(0.5, 0.5), goal=(0.5, 1.5))
    v = VehicleModel()  # m = 30 kg, v = 2 m/s, a = 1 m/s^2, b = 0
    m = measure(sc, record([(0.5, 0.5), (4.5, 0.5), (4.5, 1.5), (0.5, 1.5)]))
    assert m["length"] == pytest.approx(9.0)
    assert m["turns"] == 2
    assert m["turning_angle"] == pytest.approx(math.pi)
    assert m["smoothness"] == pytest.approx(math.pi / 9.0)
    # a 90 degree turn slows to v/2 = 1 m/s: extra time (2 - 1)^2 / (1 * 2) = 0.5 s, energy 1/2 m (4 - 1) = 45 J
    assert m["travel_time"] == pytest.approx(9.0 / 2 + 2 * 0.5)
    assert m["energy"] == pytest.approx(v.rolling_resistance * 30 * GRAVITY * 9.0 + 2 * 45.0)

    sc2 = open_grid(start=(0.5, 0.5), goal=(2.5, 0.5))
    u = measure(sc2, record([(0.5, 0.5), (4.5, 0.5), (2.5, 0.5)]))
    assert u["turns"] == 1 and u["turning_angle"] == pytest.approx(math.pi)
    # a U-turn stops: extra time v / a = 2 s, energy 1/2 m v^2 = 60 J
    assert u["travel_time"] == pytest.approx(6.0 / 2 + 2.0)
    assert u["energy"] == pytest.approx(v.rolling_resistance * 30 * GRAVITY * 6.0 + 60.0)


def test_collinear_waypoints_are_not_turns():
    sc = open_grid(start=(0.5, 0.5), goal=(4.5, 4.5))
    m = measure(sc, record([(0.5, 0.5), (1.5, 1.5), (1.5, 1.5), (4.5, 4.5)]))
    assert m["turns"] == 0 and m["length"] == pytest.approx(4 * math.sqrt(2))


def slope_scenario(start, goal, **vehicle) -> Scenario:
    elev = np.tile(0.5 * np.arange(6, dtype=float), (3, 1))  # rises 0.5 m per 1 m cell along x
    return Scenario(id="ramp", kind="terrain", occupancy=np.zeros((3, 6), bool), cell_size=1.0, start=start,
                    goal=goal, elevation=elev, vehicle=VehicleModel(**vehicle))


def test_energy_on_a_known_slope_matches_eq4_by_hand():
    up = slope_scenario((0.5, 1.5), (4.5, 1.5), onboard_power_w=10.0)
    m = measure(up, record([(0.5, 1.5), (4.5, 1.5)]))
    theta = math.atan(0.5)
    length = math.hypot(4.0, 2.0)
    w = 30 * GRAVITY
    v = 2.0
    power = (w * math.sin(theta) + 0.05 * w * math.cos(theta)) * v + 10.0  # eq. 4 with a = 0, C_I = 0
    assert m["length"] == pytest.approx(length)
    assert m["energy"] == pytest.approx(power * length / v)
    assert m["travel_time"] == pytest.approx(length / v)

    down = slope_scenario((4.5, 1.5), (0.5, 1.5), onboard_power_w=10.0)
    d = measure(down, record([(4.5, 1.5), (0.5, 1.5)]))
    # downhill the traction force W sin(-θ) + f W cos θ is negative: no regeneration, only b is drawn
    assert d["energy"] == pytest.approx(10.0 * length / v)


def test_timed_path_uses_its_own_times_and_pays_the_onboard_load_while_waiting():
    sc = Scenario(id="dyn", kind="dynamic", occupancy=np.zeros((4, 6), bool), cell_size=1.0, start=(0.5, 0.5),
                  goal=(4.5, 0.5), vehicle=VehicleModel(onboard_power_w=5.0),
                  moving_obstacles=(MovingObstacle(0.3, [(5.5, 3.5)], 0.0),))
    path = [(0.5, 0.5), (2.5, 0.5), (2.5, 0.5), (4.5, 0.5)]
    times = [0.0, 1.0, 4.0, 5.0]  # drive 2 m, wait 3 s, drive 2 m
    m = measure(sc, record(path, times=times))
    assert m["travel_time"] == pytest.approx(5.0)
    assert m["energy"] == pytest.approx(0.05 * 30 * GRAVITY * 4.0 + 5.0 * 5.0)
    assert m["length_ratio"] != m["length_ratio"]  # NaN: no reference for dynamic scenarios


def test_clearance_by_hand():
    sc = Scenario(id="c", kind="grid2d", occupancy=np.zeros((5, 9), bool), cell_size=1.0, start=(0.5, 1.5),
                  goal=(8.5, 1.5))
    m = measure(sc, record([(0.5, 1.5), (8.5, 1.5)]))
    # samples every 0.5 m at x = 0.5, 1.0, ..., 8.5 fall in columns 0, 1, 1, 2, 2, ..., 8, 8; the border
    # ring counts as blocked, so cell (1, c) has clearance min(2, c + 1, 9 - c)
    cols = np.floor(np.arange(0.5, 8.51, 0.5)).astype(int)
    by_hand = np.minimum(np.minimum(2, cols + 1), 9 - cols).astype(float)
    assert np.array_equal(clearance_samples(sc, np.array([(0.5, 1.5), (8.5, 1.5)])), by_hand)
    assert m["clearance_min"] == 1.0
    assert m["clearance_mean"] == pytest.approx(31 / 17)


def test_air_path_is_3d():
    sc = Scenario(id="air", kind="air3d", occupancy=np.zeros((4, 4, 4), bool), cell_size=1.0, vertical_cell_size=2.0,
                  start=(0.5, 0.5, 1.0), goal=(3.5, 0.5, 5.0))
    m = measure(sc, record([(0.5, 0.5, 1.0), (3.5, 0.5, 5.0)]))
    assert m["length"] == pytest.approx(5.0)
    assert turn_angles(np.array([(0, 0, 0), (1, 0, 0), (1, 0, 1.0)])) == pytest.approx([math.pi / 2])


@pytest.mark.parametrize("status", [RunStatus.INVALID, RunStatus.FAILED, RunStatus.NO_PATH, RunStatus.CRASH,
                                    RunStatus.TIMEOUT])
def test_unsuccessful_runs_give_nan_except_success_and_counts(status):
    sc = open_grid(start=(0.5, 0.5), goal=(3.5, 4.5))
    m = {mid: metric.compute(sc, record([(0.5, 0.5), (3.5, 4.5)], status=status)) for mid, metric in METRICS.items()}
    assert m.pop("success") == 0.0
    counts = (m.pop("iterations"), m.pop("evaluations"))
    if status in (RunStatus.CRASH, RunStatus.TIMEOUT):
        assert all(math.isnan(c) for c in counts)
    else:
        assert counts == (7.0, 70.0)
    assert all(math.isnan(v) for v in m.values()), m


def test_metric_declarations():
    assert len(METRICS) == len(BUILTIN_METRICS)
    for metric in METRICS.values():
        assert metric.direction in ("min", "max") and metric.unit and metric.summary
    assert METRICS["clearance_min"].direction == "max" and METRICS["success"].direction == "max"
