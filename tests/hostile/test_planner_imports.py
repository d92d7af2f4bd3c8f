"""Commands that only read planner declarations import no planner module in the harness's process.

``sandbox.import_time`` is declared lazily; importing its module rewrites the
harness's store function (:mod:`sandbox_import_payload`). Tuning reads its
parameter declarations, and an experiment that nothing can run reads its
kinds, from the description a child process gives (:mod:`pathzoo.harness.planner_info`).
"""

from __future__ import annotations

import sys

import pytest

import sandbox_lazy_declaration
from pathzoo.core.errors import InvalidExperimentError
from pathzoo.harness import Experiment
from pathzoo.plugins.manager import get_registry
from pathzoo.tuning import load_tuning

SCENARIO = """
id = "imports.random{i}"
kind = "grid2d"
description = "8x8 random obstacles"
endpoint_seed = {i}

[map]
generator = "random"
seed = {i}
shape = [8, 8]
density = 0.1
"""

TUNING = """
train = ["r1.toml"]
test = ["r2.toml"]

[experiment]
name = "imports"
budget = { iterations = 2 }

[[planner]]
id = "sandbox.import_time"
"""


@pytest.fixture()
def lazy_planner():
    registry = get_registry()
    if registry.pm.get_plugin("sandbox-lazy-declaration") is None:
        registry.add_plugin(sandbox_lazy_declaration, "sandbox-lazy-declaration")
    assert "sandbox_import_payload" not in sys.modules
    yield
    assert "sandbox_import_payload" not in sys.modules


def test_tuning_reads_the_declared_ranges_without_importing_the_planner(lazy_planner, tmp_path):
    for i in (1, 2):
        (tmp_path / f"r{i}.toml").write_text(SCENARIO.format(i=i))
    (tmp_path / "tuning.toml").write_text(TUNING)
    setup = load_tuning(tmp_path / "tuning.toml")
    (space,) = setup.spaces
    assert (space["spin"].low, space["spin"].high, space["spin"].integer) == (1, 3, True)


def test_an_experiment_nothing_can_run_names_the_kinds_without_importing_the_planner(lazy_planner):
    with pytest.raises(InvalidExperimentError, match="the planners support grid2d"):
        Experiment.build(planners=["sandbox.import_time"], scenarios=["fgdaco.scenario1"], seeds=1)
