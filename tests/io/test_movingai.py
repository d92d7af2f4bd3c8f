"""MovingAI .map and .scen files: real files from shared data, and malformed copies."""

import shutil

import numpy as np
import pytest

import pathzoo
from pathzoo import InvalidScenarioError
from pathzoo.io import load_scenario_files, read_map, read_scen


@pytest.fixture()
def arena(shared_data):
    return shared_data / "movingai" / "grid" / "dao"


def test_read_map_matches_the_characters(arena):
    occ = read_map(arena / "arena.map")
    rows = (arena / "arena.map").read_text().splitlines()[4:]
    assert occ.shape == (49, 49)
    assert occ.sum() == sum(ch in "@OTW" for row in rows for ch in row)
    r, c = np.argwhere(occ)[0]
    assert rows[r][c] in "@OTW"


@pytest.mark.parametrize(
    "body, field",
    [
        ("type octile\nheight 2\nwidth 3\nmap\n...\n..\n", "map row 1"),  # ragged rows
        ("type octile\nheight 2\nwidth 3\nmap\n...\n.x.\n", "map row 1"),  # unknown character
        ("type octile\nheight 3\nwidth 3\nmap\n...\n...\n", "height"),
        ("type octile\nwidth 3\nmap\n...\n", "height"),
    ],
)
def test_malformed_maps_name_file_and_field(tmp_path, body, field):
    path = tmp_path / "bad.map"
    path.write_text(body)
    with pytest.raises(InvalidScenarioError, match=rf"bad.map: field '{field}'"):
        read_map(path)


def test_scen_gives_one_scenario_per_line_sharing_one_map_graph_and_clearance(arena):
    scen = arena / "arena.map.scen"
    problems = read_scen(scen)
    scenarios = load_scenario_files(scen)
    assert len(scenarios) == len(problems) == len((scen).read_text().split("\n")[1:]) - 1
    first, last = scenarios[0], scenarios[-1]
    assert [s.id for s in scenarios[:2]] == ["arena.0", "arena.1"]
    p = problems[-1]
    assert last.id == f"arena.{len(problems) - 1}"
    assert last.start.tolist() == [p.start_col + 0.5, p.start_row + 0.5]
    assert last.goal.tolist() == [p.goal_col + 0.5, p.goal_row + 0.5]
    assert last.reference_length == p.optimal_length * last.cell_size
    assert last.metadata["problem_index"] == len(problems) - 1 and last.metadata["bucket"] == p.bucket
    assert all(s.occupancy is first.occupancy for s in scenarios)
    assert all(s.graph is first.graph for s in scenarios)
    assert all(s.__dict__["clearance"] is first.clearance for s in scenarios)  # computed once, with the graph
    assert pathzoo.load_scenarios(scen)[3].id == "arena.3"


def test_map_named_with_a_folder_is_found_next_to_the_scen(shared_data, tmp_path):
    rooms = shared_data / "movingai" / "grid" / "rooms"
    lines = (rooms / "8room_000.map.scen").read_text().splitlines()
    assert lines[1].split("\t")[1] == "maps/rooms/8room_000.map"
    # the first 20 problems only: the whole file takes the same path, 100 times over
    shutil.copy(rooms / "8room_000.map", tmp_path / "8room_000.map")
    (tmp_path / "short.scen").write_text("\n".join(lines[:21]) + "\n")
    scenarios = load_scenario_files(tmp_path / "short.scen")
    assert len(scenarios) == 20 and scenarios[0].shape == (512, 512) and scenarios[19].id == "8room_000.19"


def _copy(tmp_path, arena, scen_text):
    shutil.copy(arena / "arena.map", tmp_path / "arena.map")
    path = tmp_path / "x.scen"
    path.write_text(scen_text)
    return path


def test_scen_problem_in_an_obstacle_names_file_and_problem(tmp_path, arena):
    occ = read_map(arena / "arena.map")
    r, c = np.argwhere(occ)[0]
    path = _copy(tmp_path, arena, f"version 1\n0\tarena.map\t49\t49\t{c}\t{r}\t25\t25\t1\n")
    with pytest.raises(InvalidScenarioError, match=r"x.scen: field 'start': problem 0 \(arena.map\): .* obstacle"):
        load_scenario_files(path)


def test_scen_with_wrong_size_or_missing_map(tmp_path, arena):
    path = _copy(tmp_path, arena, "version 1\n0\tarena.map\t50\t49\t1\t1\t2\t2\t1\n")
    with pytest.raises(InvalidScenarioError, match=r"x.scen: field 'map': problem 0 .*50x49"):
        load_scenario_files(path)
    path.write_text("version 1\n0\tmaps/none.map\t49\t49\t1\t1\t2\t2\t1\n")
    with pytest.raises(InvalidScenarioError, match=r"x.scen: field 'map': .*map file not found"):
        load_scenario_files(path)
