"""Planner parameter validation, budgets and the vehicle power model."""

import math
import pickle

import numpy as np
import pytest

from pathzoo import Budget, InvalidParameterError, InvalidScenarioError, Param, Planner, PlanResult, Status, VehicleModel
from pathzoo.core.vehicle import GRAVITY


class Toy(Planner):
    id = "toy.planner"
    summary = "test"
    kinds = frozenset({"grid2d"})
    params = {
        "ants": Param(10, "colony size", low=1),
        "rho": Param(0.5, "evaporation", low=0.0, high=1.0, low_open=True),
        "mode": Param("a", "mode", choices=("a", "b")),
        "flag": Param(True, "a flag"),
        "limit": Param(None, "optional", nullable=True),
    }

    def plan(self, scenario, *, budget, rng, progress=None):
        return PlanResult(Status.FAILED)


def test_defaults_and_access():
    p = Toy()
    assert p.ants == 10 and p.rho == 0.5 and p.get_params()["mode"] == "a"
    assert Toy(rho=1).rho == 1.0 and isinstance(Toy(rho=1).rho, float)


@pytest.mark.parametrize(
    "kwargs, fragment",
    [
        ({"ants": 0}, "'ants' must be int in [1, inf), got 0"),
        ({"ants": 2.5}, "'ants'"),
        ({"ants": True}, "'ants'"),
        ({"rho": 0.0}, "'rho' must be float in (0.0, 1.0], got 0.0"),
        ({"rho": float("nan")}, "'rho'"),
        ({"mode": "c"}, "one of 'a', 'b'"),
        ({"flag": 1}, "'flag'"),
        ({"bogus": 1}, "unknown parameter(s) ['bogus']"),
    ],
)
def test_bad_parameters_name_parameter_range_and_value(kwargs, fragment):
    with pytest.raises(InvalidParameterError) as err:
        Toy(**kwargs)
    assert fragment in str(err.value) and "toy.planner" in str(err.value)


def test_planner_pickles_with_params():
    p = pickle.loads(pickle.dumps(Toy(ants=3)))
    assert p.ants == 3 and p.params_hash == Toy(ants=3).params_hash != Toy(ants=4).params_hash


def test_budget_validation_and_clock():
    with pytest.raises(InvalidParameterError):
        Budget(iterations=0)
    with pytest.raises(InvalidParameterError):
        Budget(time_s=float("inf"))
    with pytest.raises(InvalidParameterError, match="unknown key"):
        Budget.from_mapping({"iters": 3})
    clock = Budget(iterations=3, evaluations=10).start()
    assert not clock.exhausted(iterations=2, evaluations=9)
    assert clock.exhausted(iterations=3) and clock.exhausted(evaluations=10)
    assert math.isinf(clock.remaining_time)


def test_power_model_matches_eq4_by_hand():
    v = VehicleModel(mass_kg=30, cruise_speed=2, rolling_resistance=0.05, internal_resistance_n=1.5, onboard_power_w=3)
    theta = math.radians(10)
    w = 30 * GRAVITY
    expected = (w * math.sin(theta) + 0.05 * w * math.cos(theta) + 1.5) * 2 + 3
    assert math.isclose(float(v.traction_power(theta)), expected)
    assert math.isclose(float(v.segment_energy(10.0, theta)), expected * 5.0)
    # steep descent: traction clipped at zero, onboard load remains
    assert math.isclose(float(v.traction_power(math.radians(-60))), 3.0)


def test_turn_penalty():
    v = VehicleModel(mass_kg=30, cruise_speed=2, max_acceleration=1.0)
    t, e = v.turn_penalty(np.array([0.0, math.pi]))
    assert t[0] == 0 and e[0] == 0
    assert math.isclose(t[1], 2.0) and math.isclose(e[1], 0.5 * 30 * 4)


def test_vehicle_rejects_bad_values():
    with pytest.raises(InvalidScenarioError, match="vehicle.mass_kg"):
        VehicleModel(mass_kg=-1)
    with pytest.raises(InvalidScenarioError, match="unknown key"):
        VehicleModel.from_mapping({"mass": 3}, source="x.toml")


# ------------------------------------------------------------------ budget clock limits (docs/timing.md)
def test_cpu_budget_is_validated_and_kept_out_of_old_budget_dicts():
    assert Budget.from_mapping({"cpu_s": 2.0}).cpu_s == 2.0
    assert "cpu_s" not in Budget(iterations=3).to_dict()  # budgets stored before cpu_s compare equal
    assert Budget(cpu_s=1.5).to_dict()["cpu_s"] == 1.5
    for bad in (0, -1.0, float("nan"), True, "2"):
        with pytest.raises(InvalidParameterError, match="budget.cpu_s"):
            Budget(cpu_s=bad)
    assert Budget(cpu_s=1.0).timed and not Budget(cpu_s=1.0).counted and not Budget(cpu_s=1.0).unlimited


def test_budget_clock_reports_the_first_limit_reached():
    clock = Budget(iterations=3, evaluations=10).start()
    assert not clock.exhausted(iterations=2, evaluations=5) and clock.stopped_by is None
    assert clock.limit_reached(iterations=2, evaluations=10) == "evaluations"
    assert clock.exhausted(iterations=3) and clock.stopped_by == "evaluations"  # the first one is kept


def test_an_attached_clock_stop_replaces_the_budget_clocks():
    class Stop:
        said = None

        def reason(self):
            return self.said

    stop = Stop()
    clock = Budget(time_s=1e-9, cpu_s=1e-9, stop=stop).start()
    assert not clock.exhausted()  # the harness's stop decides, not this process's clocks
    stop.said = "cpu_time"
    assert clock.exhausted() and clock.stopped_by == "cpu_time"
    assert Budget(time_s=1.0, stop=stop) == Budget(time_s=1.0)  # not part of the budget's value


def test_param_declarations_survive_json_and_wrong_ones_are_refused():
    import json

    from pathzoo.plugins.manager import get_registry

    registry = get_registry()
    for pid in registry.planners:  # every declaration the harness may be told by a planner's description
        if registry.get("planners", pid).unavailable:
            continue
        for name, param in registry.get("planners", pid).obj.params.items():
            assert Param.from_json(json.loads(json.dumps(param.to_json()))) == param, (pid, name)
    good = Param(0.5, "x", low=0.0, high=1.0, choices=None, tune=(0.1, 0.9)).to_json()
    for bad in ({**good, "extra": 1}, {k: v for k, v in good.items() if k != "doc"}, {**good, "low": "0"},
                {**good, "tune": [0.1]}, {**good, "nullable": 1}, {**good, "choices": [[1]]}, {**good, "default": {}},
                [good]):
        with pytest.raises(ValueError):
            Param.from_json(bad)
