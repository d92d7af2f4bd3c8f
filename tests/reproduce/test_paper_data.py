"""The papers' data files: they parse, name registered scenarios and planners, and bad files fail with one line."""

from __future__ import annotations

import pytest

from pathzoo.analysis.reproduction import (
    NOT_AVAILABLE,
    PAPERS,
    PaperDataError,
    load_paper,
    paper_file,
    planner_status,
)
from pathzoo.core.errors import InvalidParameterError
from pathzoo.plugins.manager import get_registry

# every rival each paper compares against, by the id pathzoo gives it (written or still missing)
EXPECTED_RIVALS = {
    "fgdaco": {"swarm.coa", "evo.fuzzy_rate_ga", "aco.flaco", "aco.acs"},
    "dsaco": {"aco.as", "aco.mmas", "aco.chen"},
    "ggaco": {"aco.aco_astar", "exact.zstar", "swarm.mopso", "evo.lro_ga", "swarm.mosfla", "search.movns"},
    "gant": {"evo.ga", "aco.as"},
    "iaca": {"exact.dijkstra"},
}


@pytest.mark.parametrize("name", PAPERS)
def test_paper_file_parses_and_names_registered_scenarios(name):
    paper = load_paper(name)
    registry = get_registry()
    for sid in paper.scenarios.values():
        assert sid in registry.scenarios, sid
    ref = paper.planner(paper.reference)
    assert planner_status(ref) == "", f"{name}: the proposed method {ref.id} must run"
    assert {p.id for p in paper.planners} - {ref.id} == EXPECTED_RIVALS[name]
    # the paper's number for every planner in every scenario and metric
    v = paper.values
    for key in paper.scenarios:
        for p in paper.planners:
            for m in paper.metrics:
                hit = v[(v.scenario == key) & (v.planner == p.key) & (v.metric == m.id)]
                assert len(hit) == (1 if p.in_table else 0), (name, key, p.key, m.id)
    assert paper.runs >= 1 and paper.table.startswith("Table")


def test_paper_numbers_are_the_papers():
    """Spot checks against the paper files (one cell per table)."""
    v = load_paper("fgdaco").values
    row = v[(v.scenario == "3") & (v.planner == "flaco") & (v.metric == "length")].iloc[0]
    assert (row.value, row.sd) == (201.43, 4.69)
    v = load_paper("dsaco").values
    assert v[(v.planner == "dsaco") & (v.metric == "length")].value.iloc[0] == 74.1204
    v = load_paper("ggaco").values
    row = v[(v.scenario == "5") & (v.planner == "mosfla") & (v.metric == "length")].iloc[0]
    assert (row.value, row.mark) == (642.7, "↓")
    v = load_paper("gant").values
    assert v[(v.scenario == "simple.1") & (v.planner == "gant")].value.iloc[0] == 562.58


def test_unknown_planner_is_reported_not_available():
    paper = load_paper("ggaco")
    missing = [p for p in paper.planners if p.id not in get_registry().planners]
    for p in missing:
        assert planner_status(p) == NOT_AVAILABLE


def test_unknown_paper_is_a_one_line_error():
    with pytest.raises(InvalidParameterError, match="unknown paper 'nope'") as info:
        paper_file("nope")
    assert "\n" not in str(info.value)


@pytest.mark.parametrize(
    ("edit", "field"),
    [
        (lambda t: t.replace('reference = "iaca"', 'reference = "zzz"'), "reference"),
        (lambda t: t.replace('statistic = "value"', 'statistic = "mode"'), "statistic"),
        (lambda t: t.replace('planner = "iaca"\nvalues', 'planner = "ghost"\nvalues'), "ghost"),
        (lambda t: t.replace("eq21_distance = [33.5], cpu_time = [21.0]", "bogus = [1.0]"), "bogus"),
        (lambda t: t.replace("[paper]", "[paper", 1), "toml"),
        (lambda t: t.replace("[paper]", "[paper]\nsandbox_memory_gib = 0", 1), "sandbox_memory_gib"),
        (lambda t: t.replace("[paper]", '[paper]\nsandbox_memory_gib = "8"', 1), "sandbox_memory_gib"),
    ],
)
def test_bad_paper_file_names_the_file_and_field(tmp_path, edit, field):
    text = paper_file("iaca").read_text(encoding="utf-8")
    bad = tmp_path / "iaca.toml"
    bad.write_text(edit(text), encoding="utf-8")
    with pytest.raises(PaperDataError) as info:
        load_paper("iaca", bad)
    msg = str(info.value)
    assert str(bad) in msg and "\n" not in msg
    if field != "toml":
        assert field in msg


def test_a_paper_sets_its_workers_memory_and_the_rerun_passes_it_to_the_harness(tmp_path, monkeypatch):
    from pathzoo.analysis.reproduction.runs import RerunOptions, run_labelled
    from pathzoo.harness import runner
    from pathzoo.harness.sandbox import SandboxLimits

    assert load_paper("ggaco").sandbox_memory_gib == 8.0
    assert load_paper("iaca").sandbox_memory_gib is None
    seen = []

    def fake_run_experiment(experiment, **kwargs):
        seen.append(kwargs["sandbox_limits"])
        raise KeyboardInterrupt

    monkeypatch.setattr(runner, "run_experiment", fake_run_experiment)
    for paper, given, expected in [("ggaco", None, 8 << 30), ("ggaco", SandboxLimits(memory_bytes=5 << 30), 5 << 30),
                                   ("iaca", None, None)]:
        with pytest.raises(KeyboardInterrupt):
            run_labelled(load_paper(paper), None, RerunOptions(db=tmp_path / "r.sqlite", sandbox_limits=given))
        assert (seen[-1] and seen[-1].memory_bytes) == expected


def test_the_papers_tables_come_through_the_plugin_hook(tmp_path):
    """The analysis reads no plugin's files by itself: a plugin hands each table over (``pathzoo_paper_tables``)."""
    import types

    from pathzoo.analysis.reproduction import paper_tables
    from pathzoo.plugins.hookspecs import hookimpl

    assert set(paper_tables()) == set(PAPERS)
    own = tmp_path / "mine.toml"
    own.write_text(paper_file("iaca").read_text(encoding="utf-8"), encoding="utf-8")
    plugin = types.ModuleType("paper_plugin_for_test")
    plugin.pathzoo_paper_tables = hookimpl(lambda: {"mine": own, "iaca": tmp_path / "shadowed.toml"})
    registry = get_registry()
    registry.pm.register(plugin, name="paper-plugin-for-test")
    try:
        assert paper_file("mine") == own
        assert paper_file("iaca").name == "iaca.toml" and paper_file("iaca").is_file()  # the first provider wins
        assert load_paper("mine").runs == load_paper("iaca").runs
    finally:
        registry.pm.unregister(plugin)
    with pytest.raises(InvalidParameterError, match="unknown paper 'mine'"):
        paper_file("mine")
