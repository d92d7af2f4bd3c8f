"""The quick start's first run: no warning about the bundled experiment's own unsupported pairs."""

from __future__ import annotations

import logging
import textwrap
from importlib import resources

from pathzoo.cli.main import main
from pathzoo.harness.experiment import Experiment
from pathzoo.harness.runner import never_run


def test_the_bundled_default_uses_every_planner_and_scenario():
    with resources.as_file(resources.files("pathzoo.experiments") / "default.toml") as path:
        exp = Experiment.from_toml(path)
    assert exp.skipped()  # a partial cross product: planners x scenarios of every kind
    assert never_run(exp) == ""


def test_a_partial_cross_product_is_no_warning(tmp_path, capsys, caplog):
    exp = tmp_path / "mixed.toml"
    exp.write_text(textwrap.dedent("""\
        [experiment]
        seeds = 1
        budget = { iterations = 2 }
        scenarios = ["gant.fig7", "iaca.offroad"]
        [[planner]]
        id = "exact.astar"
        [[planner]]
        id = "exact.thetastar"
        """))
    caplog.set_level(logging.INFO, logger="pathzoo.harness")
    assert main(["run", str(exp), "--db", str(tmp_path / "r.sqlite"), "--executor", "inline", "--no-progress"]) == 0
    warnings = [r.getMessage() for r in caplog.records if r.levelno >= logging.WARNING]
    assert not [w for w in warnings if "sandbox" not in w]  # inline runs are unsandboxed: that notice is expected
    assert any("skipping 1 unsupported planner x scenario pair(s)" in r.getMessage() for r in caplog.records)
    err = capsys.readouterr().err
    assert "3 runs stored" in err and "1 planner x scenario pair(s) not run" in err and "-v lists them" in err
