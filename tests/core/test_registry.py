"""Plugin discovery: built-ins and third parties go through the same entry points, one group per kind of plugin."""

import importlib.metadata as md
import sys
import types

import pytest

import pathzoo
from pathzoo import Param, Planner, PlanResult, ScenarioEntry, Status, UnknownPluginError
from pathzoo.plugins import manager
from pathzoo.plugins.manager import KIND_GROUPS, discover


class Dummy(Planner):
    id = "dummy.one"
    summary = "a dummy"
    kinds = frozenset({"grid2d"})
    params = {"k": Param(1, "k", low=1)}

    def plan(self, scenario, *, budget, rng, progress=None):
        return PlanResult(Status.FAILED)


@pytest.fixture
def fake_plugins(monkeypatch):
    good = types.ModuleType("pz_fake_good")

    @pathzoo.hookimpl
    def pathzoo_register_planners():
        return [Dummy]

    good.pathzoo_register_planners = pathzoo_register_planners
    clash = types.ModuleType("pz_fake_clash")
    clash.pathzoo_register_planners = pathzoo.hookimpl(lambda: [Dummy])
    bad_hook = types.ModuleType("pz_fake_badhook")

    def boom():
        raise RuntimeError("hook exploded")

    bad_hook.pathzoo_register_planners = pathzoo.hookimpl(boom)
    for mod in (good, clash, bad_hook):
        monkeypatch.setitem(sys.modules, mod.__name__, mod)
    return [
        md.EntryPoint("good", "pz_fake_good", "pathzoo"),
        md.EntryPoint("clash", "pz_fake_clash", "pathzoo"),
        md.EntryPoint("badhook", "pz_fake_badhook", "pathzoo"),
        md.EntryPoint("missing", "pz_fake_does_not_exist", "pathzoo"),
    ]


def test_discover_registers_and_reports_failures(fake_plugins):
    reg = discover(fake_plugins)
    assert list(reg.planners) == ["dummy.one"]
    failures = {f.plugin: f.error for f in reg.failures}
    assert "import failed: ModuleNotFoundError" in failures["missing"]
    assert "hook raised" in failures["badhook"]
    assert "already provided by" in failures["good"] or "already provided by" in failures["clash"]


def test_unknown_ids_and_globs(fake_plugins):
    reg = discover(fake_plugins)
    with pytest.raises(UnknownPluginError, match="unknown planner 'dummy.two'; did you mean 'dummy.one'?"):
        reg.get("planners", "dummy.two")
    assert reg.match("planners", "dummy.*") == ["dummy.one"]
    with pytest.raises(UnknownPluginError):
        reg.match("planners", "nothing.*")
    with pytest.raises(UnknownPluginError, match="unknown plugin kind"):
        reg.table("widgets")


def test_builtins_come_through_entry_points():
    names = {kind: {ep.name for ep in md.entry_points(group=group)} for kind, group in KIND_GROUPS.items()}
    assert {"exact", "aco", "baselines", "ompl", "rivals"} <= names["planners"]
    assert "scenarios" in names["scenarios"] and "core" in names["metrics"]
    with pytest.raises(UnknownPluginError):
        pathzoo.make_planner("no.such.planner")


def test_entry_point_plugins_are_remembered_even_after_uninstall(fake_plugins, monkeypatch):
    from pathzoo.harness.planner_info import extra_plugin_modules

    reg = discover(fake_plugins)
    assert reg.entry_point_plugins == {"good", "clash", "badhook"}
    # the distribution is uninstalled after discovery: its plugin is still not "hand-registered"
    monkeypatch.setattr(md, "entry_points", lambda **kw: [])
    assert extra_plugin_modules(reg) == ()
    by_hand = types.ModuleType("pz_fake_by_hand")
    monkeypatch.setitem(sys.modules, by_hand.__name__, by_hand)
    reg.add_plugin(by_hand, "by_hand")
    assert extra_plugin_modules(reg) == (("by_hand", "pz_fake_by_hand"),)


def _scenario():
    raise AssertionError("not loaded in these tests")


def _module(monkeypatch, name: str, planners: bool, scenarios: bool) -> types.ModuleType:
    module = types.ModuleType(name)
    if planners:
        module.pathzoo_register_planners = pathzoo.hookimpl(lambda: [Dummy])
    if scenarios:
        module.pathzoo_register_scenarios = pathzoo.hookimpl(
            lambda: [ScenarioEntry(f"{name}.s", "a scenario", _scenario, "grid2d")])
    monkeypatch.setitem(sys.modules, name, module)
    return module


def test_each_group_provides_its_own_kind_only(monkeypatch):
    _module(monkeypatch, "pz_both", planners=True, scenarios=True)
    reg = discover([md.EntryPoint("both", "pz_both", KIND_GROUPS["scenarios"])])
    assert list(reg.scenarios) == ["pz_both.s"] and not reg.planners
    (note,) = reg.failures
    assert note.plugin == "both" and "its planners hook is ignored" in note.error and "pathzoo.planners" in note.error


def test_a_module_declared_in_two_groups_provides_both_and_is_registered_once(monkeypatch):
    module = _module(monkeypatch, "pz_both", planners=True, scenarios=True)
    reg = discover([md.EntryPoint("both", "pz_both", KIND_GROUPS["planners"]),
                    md.EntryPoint("both", "pz_both", KIND_GROUPS["scenarios"])])
    assert list(reg.planners) == ["dummy.one"] and list(reg.scenarios) == ["pz_both.s"]
    assert reg.failures == [] and reg.pm.get_plugins() == {module} and reg.entry_point_plugins == {"both"}


def test_the_old_single_group_still_provides_planners_and_says_what_it_ignores(monkeypatch):
    _module(monkeypatch, "pz_old", planners=True, scenarios=True)
    reg = discover([md.EntryPoint("old", "pz_old", manager.ENTRY_POINT_GROUP)])
    assert list(reg.planners) == ["dummy.one"] and not reg.scenarios
    assert "its scenarios hook is ignored" in reg.failures[0].error


def test_a_registry_limited_to_scenarios_and_metrics_never_imports_planner_plugins(monkeypatch):
    _module(monkeypatch, "pz_scen", planners=False, scenarios=True)
    eps = [md.EntryPoint("planner", "pz_planner_never_imported_xyz", KIND_GROUPS["planners"]),
           md.EntryPoint("old", "pz_old_never_imported_xyz", manager.ENTRY_POINT_GROUP),
           md.EntryPoint("scen", "pz_scen", KIND_GROUPS["scenarios"])]
    reg = discover(eps, kinds=("scenarios", "metrics"))
    assert list(reg.scenarios) == ["pz_scen.s"]
    assert reg.failures == []  # the planner entry points were not even tried (they would fail to import)
    with pytest.raises(UnknownPluginError, match="this process loads no planners plugins"):
        reg.get("planners", "dummy.one")


def test_hand_registered_modules_reach_the_judge_only_if_they_provide_scenarios_or_metrics(monkeypatch):
    reg = discover([])
    for name, planners, scenarios in [("p_only", True, False), ("s_only", False, True), ("both", True, True)]:
        reg.add_plugin(_module(monkeypatch, f"pz_{name}", planners, scenarios), name)
    pairs = (("p_only", "pz_p_only"), ("s_only", "pz_s_only"), ("both", "pz_both"))
    assert reg.judge_modules(pairs) == (("s_only", "pz_s_only"), ("both", "pz_both"))


def test_limit_kinds_refuses_once_other_plugins_are_loaded(monkeypatch):
    monkeypatch.setattr(manager, "_registry", discover([]))
    with pytest.raises(RuntimeError, match="already loaded"):
        manager.limit_kinds(("scenarios", "metrics"))
    monkeypatch.setattr(manager, "_registry", None)
    monkeypatch.setattr(manager, "_kinds", manager.KINDS)
    monkeypatch.setattr(manager, "discover", lambda kinds: discover([], kinds=kinds))
    manager.limit_kinds(("scenarios", "metrics"))
    assert manager.get_registry().kinds == ("scenarios", "metrics")
