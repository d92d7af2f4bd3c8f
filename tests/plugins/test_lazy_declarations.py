"""Planners and metrics declared lazily: listed from their declaration, imported on first use, checked against it."""

from __future__ import annotations

import sys
import types

import pytest

import pathzoo
from pathzoo.builtin import METRICS
from pathzoo.metrics import BUILTIN_METRICS
from pathzoo.plugins.entries import LazyClass, LazyPlanner, PluginDeclarationError, PluginEntry
from pathzoo.plugins.manager import get_registry

LAZY = [(kind, entry) for kind in ("planners", "metrics") for entry in pathzoo.list_plugins(kind)
        if isinstance(entry.provided, LazyClass)]


def test_the_builtin_planners_and_metrics_are_declared_lazily():
    lazy_ids = {entry.id for _, entry in LAZY}
    assert {"aco.as", "aco.fgdaco", "exact.astar", "swarm.pso", "search.movns", "success", "length"} <= lazy_ids
    assert len([1 for kind, _ in LAZY if kind == "metrics"]) == len(BUILTIN_METRICS)


@pytest.mark.parametrize(("kind", "entry"), LAZY, ids=[entry.id for _, entry in LAZY])
def test_every_declaration_agrees_with_its_class(kind, entry):
    cls = entry.obj  # imports the class and compares every declared field with it
    assert cls.id == entry.id and cls.summary == entry.summary
    assert issubclass(cls, pathzoo.Planner if kind == "planners" else pathzoo.Metric)


def test_builtin_metrics_keep_the_column_order():
    assert [m.load() for m in METRICS] == list(BUILTIN_METRICS)


@pytest.fixture
def fake_module(monkeypatch):
    module = types.ModuleType("pz_fake_lazy")

    class Slow(pathzoo.Planner):
        id = "fake.slow"
        summary = "a planner"
        kinds = frozenset({"grid2d"})
        requires = {"deap": "evo"}

        def plan(self, scenario, *, budget, rng, progress=None):
            raise NotImplementedError

    module.Slow = Slow
    monkeypatch.setitem(sys.modules, module.__name__, module)
    return module


def _declared(**changes):
    fields = dict(id="fake.slow", summary="a planner", target="pz_fake_lazy:Slow", kinds=frozenset({"grid2d"}),
                  requires={"deap": "evo"})
    return LazyPlanner(**{**fields, **changes})


def test_a_matching_declaration_loads_its_class(fake_module):
    assert _declared().load() is fake_module.Slow


@pytest.mark.parametrize(("field", "value"), [("summary", "another text"), ("kinds", frozenset({"terrain"})),
                                              ("requires", {}), ("id", "fake.other")])
def test_a_declaration_that_drifted_from_its_class_is_an_error(fake_module, field, value):
    with pytest.raises(PluginDeclarationError, match=f"declares {field}="):
        _declared(**{field: value}).load()


@pytest.mark.parametrize("target", ["pz_fake_lazy:Missing", "pz_no_such_module_xyz:Slow", "pz_fake_lazy",
                                    "pz_fake_lazy:Slow.plan"])
def test_a_target_that_is_not_an_importable_class_is_an_error(fake_module, target):
    with pytest.raises(PluginDeclarationError, match="fake.slow"):
        _declared(target=target).load()


def test_listing_reads_the_declaration_without_importing(fake_module, monkeypatch):
    monkeypatch.delitem(sys.modules, "pz_fake_lazy")  # importing it now would fail
    entry = PluginEntry("fake.slow", "a planner", _declared(), "fake", "", "")
    assert entry.declared("kinds") == frozenset({"grid2d"})
    with pytest.raises(PluginDeclarationError):
        entry.obj


def test_unavailable_planners_are_reported_from_the_declaration():
    entry = PluginEntry("fake.slow", "a planner", _declared(requires={"pz_not_installed_xyz": "evo"}), "fake",
                        "pathzoo", "0")
    assert entry.unavailable == 'needs pz_not_installed_xyz: pip install "pathzoo[evo]"'


def test_make_planner_imports_a_lazily_declared_class():
    planner = pathzoo.make_planner("exact.astar")
    assert type(planner) is get_registry().get("planners", "exact.astar").obj


def test_path_model_is_declared_and_checked():
    assert get_registry().planners["exact.sipp"].declared("path_model") == "timed"
    assert get_registry().planners["exact.astar"].declared("path_model") == "grid"
    with pytest.raises(PluginDeclarationError, match="path_model='curvy'"):
        LazyPlanner("x.y", "s", "mod:Cls", path_model="curvy")
