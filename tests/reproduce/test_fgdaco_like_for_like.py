"""FGDACO's Table 7 reruns like for like (issue 21): every rival runs the dynamic scenarios itself, under an honest label."""

import pathzoo
from pathzoo.analysis.reproduction import load_paper
from pathzoo.plugins.manager import get_registry


def test_every_fgdaco_rival_runs_the_dynamic_scenarios_and_none_is_a_hybrid():
    paper = load_paper("fgdaco")
    planners = get_registry().table("planners")
    for sid in paper.scenarios.values():
        assert pathzoo.load_scenario(sid).kind == "dynamic", sid
    for p in paper.planners:
        assert p.variant == "", f"{p.key} runs a variant ({p.variant}), not the paper's scenario"
        assert "dynamic" in planners[p.id].declared("kinds"), p.id
        assert not planners[p.id].declared("hybrid", False), p.id


def test_fgdaco_names_its_coa_and_labels_its_fuzzy_ga_stand_in():
    paper = load_paper("fgdaco")
    assert paper.planner("coa").id == "swarm.coa"  # Rajabioun's COA, not Yang & Deb's cuckoo search
    fuzzy = paper.planner("fuzzy_ga")
    assert fuzzy.id == "evo.fuzzy_rate_ga" and "stand-in" in fuzzy.label and "not Singh" in fuzzy.label
