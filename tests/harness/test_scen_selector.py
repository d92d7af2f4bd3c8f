"""One problem of a ``.scen`` file in an experiment: ``"file.scen#12"`` (0-based index) or ``"file.scen#<glob>"``."""

from __future__ import annotations

import re
import shutil
import textwrap
from pathlib import Path

import pytest

from pathzoo.core.errors import InvalidExperimentError
from pathzoo.harness.experiment import Experiment

DAO = Path(__file__).parents[1] / "data" / "movingai" / "grid" / "dao"


@pytest.fixture()
def maps(tmp_path):
    folder = tmp_path / "maps"
    folder.mkdir()
    for name in ("arena.map", "arena.map.scen"):
        shutil.copy(DAO / name, folder / name)
    return tmp_path


def experiment(root: Path, *entries: str) -> Experiment:
    listed = ", ".join(f'"{e}"' for e in entries)
    (root / "e.toml").write_text(textwrap.dedent(f"""\
        [experiment]
        seeds = 1
        scenarios = [{listed}]
        [[planner]]
        id = "exact.astar"
        """))
    return Experiment.from_toml(root / "e.toml")


def test_one_problem_by_its_zero_based_index(maps):
    exp = experiment(maps, "maps/arena.map.scen#12")
    assert [s.id for s in exp.scenarios] == ["arena.12"]
    scenario = exp.scenarios[0].load()
    assert scenario.metadata["problem_index"] == 12
    line = (maps / "maps" / "arena.map.scen").read_text().splitlines()[1 + 12].split()
    assert scenario.start.tolist() == [int(line[4]) + 0.5, int(line[5]) + 0.5]


def test_several_problems_and_globs(maps):
    exp = experiment(maps, "maps/arena.map.scen#0", "maps/arena.map.scen#arena.1?")
    assert [s.id for s in exp.scenarios] == ["arena.0"] + [f"arena.1{i}" for i in range(10)]
    assert [s.id for s in experiment(maps, "maps/arena.map.scen#2?").scenarios] == [f"arena.2{i}" for i in range(10)]


@pytest.mark.parametrize(("entry", "message"), [
    ("maps/arena.map.scen#999", "problem index 999 is past the last problem"),
    ("maps/arena.map.scen#nothing*", "no problem id or index matches 'nothing*'"),
    ("maps/arena.map#3", "'#' selects problems of a .scen file, and arena.map is not one"),
])
def test_bad_selectors_name_the_entry(maps, entry, message):
    with pytest.raises(InvalidExperimentError, match=re.escape(message)) as info:
        experiment(maps, entry)
    assert "field 'experiment.scenarios[0]'" in str(info.value) and entry in str(info.value)
