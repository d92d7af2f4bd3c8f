"""All packs: registered by id, lazily loadable, picklable, versioned, and drawable as PNG."""

from __future__ import annotations

import pickle
from functools import partial

import pytest

import pathzoo
from pathzoo.plotting.scenario import save_scenario_png
from pathzoo.plugins.manager import get_registry
from pathzoo_scenarios import dsaco, fgdaco, gant, ggaco, movingai, plugin

EXPECTED_NON_MOVINGAI = {
    "gant.fig7", "gant.acopso", *(f"gant.{s}.{p}" for s in ("simple", "moderate", "complex") for p in (1, 2, 3)),
    "dsaco.simple", "dsaco.medium", "dsaco.complex",
    "iaca.offroad",
    *(f"fgdaco.scenario{k}{v}" for k in (1, 2, 3) for v in ("", "_static")),
    "ggaco.jacksboro", "ggaco.frontrange", "ggaco.hugo", *(f"ggaco.case{k}" for k in range(1, 6)),
}
# one cheap scenario per pack, loaded, checked and drawn
ONE_PER_PACK = ["gant.simple.2", "dsaco.medium", "iaca.offroad", "fgdaco.scenario2", "ggaco.hugo",
                "movingai.maze-32-32-2.b4.1"]


def test_every_pack_is_registered():
    reg = get_registry()
    ids = set(reg.scenarios)
    assert EXPECTED_NON_MOVINGAI <= ids
    assert {i.split(".")[0] for i in ids if reg.scenarios[i].plugin == "scenarios"} == set(plugin.PACKS)
    assert not [f for f in reg.failures if f.plugin == "scenarios"]


def test_entries_are_picklable_and_declare_their_kind():
    reg = get_registry()
    for sid in EXPECTED_NON_MOVINGAI:
        entry = reg.scenarios[sid].obj
        assert entry.kind in pathzoo.core.SCENARIO_KINDS
        assert pickle.loads(pickle.dumps(entry.load)) is not None
        assert entry.summary


@pytest.mark.parametrize("sid", ONE_PER_PACK)
def test_load_kind_version_and_png(sid, tmp_path):
    entry = get_registry().scenarios[sid].obj
    s = pathzoo.load_scenario(sid)
    assert s.id == sid and s.kind == entry.kind
    pack = sid.split(".")[0]
    module = __import__(f"pathzoo_scenarios.{pack}", fromlist=["PACK_VERSION"])
    assert s.metadata["pack"] == pack and s.metadata["pack_version"] == module.PACK_VERSION
    assert s.metadata["source"]
    out = save_scenario_png(s, tmp_path / f"{sid}.png")
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert pickle.loads(pickle.dumps(s)).id == sid


@pytest.mark.parametrize(
    "call",
    [
        partial(gant.load_large, "hard", 1),
        partial(gant.load_large, "simple", 4),
        partial(dsaco.load, "alpine"),
        partial(fgdaco.load, 4),
        partial(ggaco.load, "moon"),
        partial(ggaco.load, "hugo", 30.0, 10.0),
        partial(movingai.load, "arena", 999),
    ],
)
def test_bad_arguments_raise_one_line_parameter_errors(call):
    with pytest.raises(pathzoo.InvalidParameterError) as info:
        call()
    assert "\n" not in str(info.value)


def test_impossible_slope_bounds_are_a_scenario_error():
    with pytest.raises(pathzoo.InvalidScenarioError, match="slope"):
        ggaco.load("hugo", slope_min_deg=89.0, slope_max_deg=90.0)
