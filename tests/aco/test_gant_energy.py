"""G-Ant's energy predictor (eqs. 7-12): RLS with forgetting plus the EWMA residual chart."""

from __future__ import annotations

import math

import numpy as np

from pathzoo import VehicleModel
from pathzoo_aco.gant_energy import RlsEwmaPredictor, synthetic_drive

VEHICLE = VehicleModel(mass_kg=30.0, rolling_resistance=0.05, internal_resistance_n=6.0, onboard_power_w=12.0)
TRUE_C = VEHICLE.rolling_resistance + VEHICLE.internal_resistance_n / VEHICLE.weight_n  # eq. 6 on flat ground
TRUE_B = VEHICLE.onboard_power_w


def _fit(drive, predictor=None):
    predictor = predictor or RlsEwmaPredictor()
    for x, y in zip(drive.x, drive.y):
        predictor.update(float(x), float(y))
    return predictor


def test_synthetic_drive_follows_eq4():
    drive = synthetic_drive(VEHICLE, np.random.default_rng(0), 200, 10.0, 2.0, noise=0.0, grade_rad=0.05)
    w = VEHICLE.weight_n
    force = w * math.sin(0.05) + 0.05 * w * math.cos(0.05) + 30.0 * drive.a + 6.0
    np.testing.assert_allclose(drive.power, force * drive.v + 12.0)
    np.testing.assert_allclose(drive.y, drive.power - 30.0 * drive.a * drive.v)
    assert drive.v.min() >= 0.0 and drive.v.max() <= 2.0


def test_rls_converges_to_true_c_and_b():
    drive = synthetic_drive(VEHICLE, np.random.default_rng(1), 500, 10.0, 2.0, noise=0.1)
    p = _fit(drive)
    assert abs(p.c - TRUE_C) < 0.03 * TRUE_C
    assert abs(p.b - TRUE_B) < 2.0
    # the residual scale matches the 10 % noise of the generator
    noise_sd = 0.1 * abs(float(np.mean(drive.power)))
    assert 0.5 * noise_sd < math.sqrt(p.resid_var) < 1.5 * noise_sd


def test_rls_without_noise_is_exact():
    drive = synthetic_drive(VEHICLE, np.random.default_rng(2), 50, 10.0, 2.0, noise=0.0)
    p = _fit(drive)
    assert math.isclose(p.c, TRUE_C, rel_tol=1e-6) and math.isclose(p.b, TRUE_B, rel_tol=1e-4)


def test_ewma_chart_resets_on_a_grade_change_and_rls_readapts():
    rng = np.random.default_rng(3)
    p = _fit(synthetic_drive(VEHICLE, rng, 200, 10.0, 2.0, noise=0.05))
    before = p.resets
    assert before <= 2  # a stationary drive stays in control (3-sigma band: rare false alarms)
    grade = 0.12
    new_c = math.sin(grade) + 0.05 * math.cos(grade) + 6.0 / VEHICLE.weight_n
    p = _fit(synthetic_drive(VEHICLE, rng, 20, 10.0, 2.0, noise=0.05, grade_rad=grade), p)
    assert p.resets > before
    assert abs(p.c - new_c) < 0.15 * new_c
    # without the chart (limit = inf) the forgetting RLS is still far off after the same samples
    slow = _fit(synthetic_drive(VEHICLE, np.random.default_rng(3), 200, 10.0, 2.0, noise=0.05),
                RlsEwmaPredictor(limit=math.inf))
    slow = _fit(synthetic_drive(VEHICLE, np.random.default_rng(9), 20, 10.0, 2.0, noise=0.05, grade_rad=grade), slow)
    assert abs(slow.c - new_c) > 0.25 * new_c


def test_mission_energy_eq11_and_variance_eq12():
    p = _fit(synthetic_drive(VEHICLE, np.random.default_rng(4), 300, 10.0, 2.0, noise=0.1))
    x = VEHICLE.weight_n * 2.0
    mean, var = p.mission_energy(consumed_j=500.0, steps_left=6, x_next=x, dt=10.0)
    assert math.isclose(mean, 500.0 + 6 * (p.b + p.c * x) * 10.0)
    assert math.isclose(var, 6 * float(p.power_variance(x)) * 100.0)
    assert var > 6 * p.resid_var * 100.0  # parameter uncertainty adds to the noise
