"""Plugin discovery: built-ins and third parties go through the same entry points."""

import importlib.metadata as md
import sys
import types

import pytest

import pathzoo
from pathzoo import Param, Planner, PlanResult, Status, UnknownPluginError
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
    with pytest.raises(UnknownPluginError, match="unknown planner 'dummy.two'.*did you mean one of: dummy.one"):
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
    from pathzoo.harness.runner import extra_plugin_modules

    reg = discover(fake_plugins)
    assert reg.entry_point_plugins == {"good", "clash", "badhook"}
    # the distribution is uninstalled after discovery: its plugin is still not "hand-registered"
    monkeypatch.setattr(md, "entry_points", lambda **kw: [])
    assert extra_plugin_modules(reg) == ()
    by_hand = types.ModuleType("pz_fake_by_hand")
    monkeypatch.setitem(sys.modules, by_hand.__name__, by_hand)
    reg.add_plugin(by_hand, "by_hand")
    assert extra_plugin_modules(reg) == (("by_hand", "pz_fake_by_hand"),)
