"""A JSON leaderboard carries what its numbers depend on: budget, seeds and versions."""

from __future__ import annotations

import json
import textwrap

from pathzoo.cli.main import main


def test_json_leaderboard_names_budget_seeds_and_versions(tmp_path, capsys):
    exp = tmp_path / "e.toml"
    exp.write_text(textwrap.dedent("""\
        [experiment]
        name = "tiny"
        seed = 7
        seeds = [0, 3]
        budget = { iterations = 3, time_s = 5.0 }
        scenarios = ["gant.fig7"]
        [[planner]]
        id = "exact.astar"
        [[planner]]
        id = "aco.as"
        params = { n_ants = 4 }
        label = "as-4"
        """))
    db = tmp_path / "r.sqlite"
    assert main(["run", str(exp), "--db", str(db), "--executor", "inline", "--no-progress"]) == 0
    capsys.readouterr()
    assert main(["leaderboard", str(db), "--format", "json"]) == 0
    document = json.loads(capsys.readouterr().out)
    facts = document["experiment"]
    assert facts["name"] == "tiny" and facts["seed"] == 7 and facts["seeds"] == [0, 3]
    assert facts["budget"] == {"iterations": 3, "evaluations": None, "time_s": 5.0}
    versions = facts["versions"]
    assert versions["planners"] == {"as-4": "1", "exact.astar": "1"}
    assert versions["pathzoo"] and versions["numpy"] and versions["python"]
    assert "cpu" not in versions and "peak_rss_mb" not in versions
    assert len(document["rows"]) == 2
