"""Scenario TOML files: every kind, every table, and one-line errors naming the file and the field."""

import re
import shutil
import textwrap

import numpy as np
import pytest
from scipy.sparse.csgraph import dijkstra

import pathzoo
from pathzoo import InvalidScenarioError
from pathzoo.generators import GENERATORS, gaussian_peaks, rooms
from pathzoo.io import load_scenario_file, load_scenario_files, read_map


def write(tmp_path, text, name="s.toml"):
    path = tmp_path / name
    path.write_text(textwrap.dedent(text))
    return path


def fails(path, pattern):
    with pytest.raises(InvalidScenarioError) as info:
        load_scenario_file(path)
    message = str(info.value)
    assert "\n" not in message
    assert message.startswith(str(path)), message
    assert re.search(pattern, message), message


@pytest.fixture()
def arena(tmp_path, shared_data):
    shutil.copy(shared_data / "movingai" / "grid" / "dao" / "arena.map", tmp_path / "arena.map")
    return read_map(tmp_path / "arena.map")


GRID = """
    id = "t.arena"
    kind = "grid2d"
    description = "arena"
    cell_size = 0.5
    start = [1.75, 1.75]
    goal_cell = [40, 30]
    reference_length = 30.0
    [map]
    file = "arena.map"
    [metadata]
    paper = "none"
"""


def test_grid2d_from_a_map_file(tmp_path, arena):
    s = load_scenario_file(write(tmp_path, GRID))
    assert s.id == "t.arena" and s.kind == "grid2d" and s.description == "arena"
    assert np.array_equal(s.occupancy, arena) and s.cell_size == 0.5
    assert s.start.tolist() == [1.75, 1.75]
    assert s.goal.tolist() == [(30 + 0.5) * 0.5, (40 + 0.5) * 0.5]
    assert s.reference_length == 30.0
    assert s.metadata["paper"] == "none" and s.metadata["map"]["file"].endswith("arena.map")
    assert len(s.metadata["map"]["sha256"]) == 64
    assert [x.id for x in load_scenario_files(tmp_path / "s.toml")] == ["t.arena"]
    assert pathzoo.load_scenario(tmp_path / "s.toml").id == "t.arena"


def test_occupancy_from_npz_with_key(tmp_path):
    occ = np.zeros((4, 5), dtype=np.int8)
    occ[1, 1:4] = 1
    np.savez(tmp_path / "m.npz", occ=occ, other=np.zeros(3))
    s = load_scenario_file(write(tmp_path, """
        id = "n"
        kind = "grid2d"
        start_cell = [0, 0]
        goal_cell = [3, 4]
        [map]
        file = "m.npz"
        key = "occ"
    """))
    assert np.array_equal(s.occupancy, occ.astype(bool)) and s.metadata["map"]["key"] == "occ"


ROOMS = """
    id = "t.rooms"
    kind = "grid2d"
    [map]
    generator = "rooms"
    seed = 11
    shape = [30, 40]
    room_size = 5
"""


def test_generated_map_with_drawn_endpoints_is_solvable_and_recorded(tmp_path):
    path = write(tmp_path, ROOMS)
    a, b = load_scenario_file(path), load_scenario_file(path)
    assert np.array_equal(a.occupancy, rooms((30, 40), 11, room_size=5))
    assert np.array_equal(a.start, b.start) and np.array_equal(a.goal, b.goal)
    assert a.metadata["map"] == {"generator": "rooms", "version": GENERATORS["rooms"].version, "seed": 11,
                                 "params": {"shape": [30, 40], "room_size": 5, "door_width": 1,
                                            "extra_door_probability": 0.5}}
    assert a.metadata["endpoints"]["seed"] == 11
    d = dijkstra(a.graph.to_sparse(), indices=[a.start_node])
    assert np.isfinite(d[0, a.goal_node]) and a.start_node != a.goal_node
    c = load_scenario_file(write(tmp_path, "endpoint_seed = 5\n" + textwrap.dedent(ROOMS), "c.toml"))
    assert c.metadata["endpoints"]["seed"] == 5


def test_terrain_from_hugo_asc_blocks_nodata(tmp_path, shared_data):
    shutil.copy(shared_data / "dem" / "hugo_site.asc", tmp_path / "hugo.asc")
    text = """
        id = "t.hugo"
        kind = "terrain"
        start_cell = [27, 38]
        goal_cell = [30, 40]
        [elevation]
        file = "hugo.asc"
        [vehicle]
        max_climb_deg = 25
    """
    s = load_scenario_file(write(tmp_path, text))
    assert s.cell_size == 10.0 and s.shape == (55, 76) and s.vehicle.max_climb_deg == 25
    assert s.blocked.sum() == 2028 and np.array_equal(s.blocked, np.isnan(s.elevation))
    assert s.metadata["elevation"]["nodata_cells"] == 2028
    fails(write(tmp_path, text.replace("[27, 38]", "[0, 0]"), "a.toml"), r"field 'start_cell': .*obstacle")
    fails(write(tmp_path, "cell_size = 5\n" + textwrap.dedent(text), "b.toml"), r"field 'cell_size': hugo.asc sets")


def test_terrain_nan_in_an_array_needs_a_policy(tmp_path):
    z = np.zeros((5, 5))
    z[2, 2] = np.nan
    np.save(tmp_path / "z.npy", z)
    text = """
        id = "z"
        kind = "terrain"
        cell_size = 2.0
        start = [1, 1]
        goal = [9, 9]
        [elevation]
        file = "z.npy"
    """
    fails(write(tmp_path, text), r"field 'elevation.file': .*z.npy.*1 cells are NaN.*nodata = \"obstacle\"")
    s = load_scenario_file(write(tmp_path, text + 'nodata = "obstacle"\n', "ok.toml"))
    assert s.blocked[2, 2] and s.blocked.sum() == 1 and s.cell_size == 2.0


DSACO = """
    id = "t.dsaco"
    kind = "air3d"
    cell_size = 1000.0
    vertical_cell_size = 200.0
    layers = 12
    max_step = [1, 2]
    start = [1500, 17500, 700]
    goal = [48500, 30500, 700]
    [elevation]
    generator = "gaussian_peaks"
    seed = 0
    shape = [50, 50]
    peaks = [[30000, 9000, 660, 4000, 3000], [16000, 17000, 1640, 7000, 8000], [35000, 32000, 1300, 5000, 8000]]
"""


def test_air3d_volume_from_gaussian_peaks(tmp_path):
    s = load_scenario_file(write(tmp_path, DSACO))
    ground = gaussian_peaks((50, 50), 0, cell_size=1000.0, peaks=[[30000, 9000, 660, 4000, 3000],
                            [16000, 17000, 1640, 7000, 8000], [35000, 32000, 1300, 5000, 8000]])
    assert s.shape == (12, 50, 50) and s.max_step == (1, 2) and s.vertical_cell_size == 200.0
    layer, row, col = 3, 17, 16  # bottom at 600 m, under the 1640 m peak
    assert s.occupancy[layer, row, col] == (layer * 200.0 < ground[row, col]) == True  # noqa: E712
    assert s.occupancy.sum() == sum((k * 200.0 < ground).sum() for k in range(12))
    assert np.array_equal(s.elevation, ground)
    fails(write(tmp_path, DSACO.replace("[1500, 17500, 700]", "[16500, 17500, 300]"), "in.toml"),
          r"field 'start': .*obstacle")
    fails(write(tmp_path, DSACO.replace("layers = 12", ""), "nolayers.toml"), r"field 'layers': missing")


def test_air3d_from_a_volume_file(tmp_path):
    vol = np.zeros((3, 4, 5), bool)
    vol[1, 2, :] = True
    np.save(tmp_path / "v.npy", vol)
    s = load_scenario_file(write(tmp_path, """
        id = "v"
        kind = "air3d"
        cell_size = 2.0
        vertical_cell_size = 1.0
        start_cell = [0, 0, 0]
        goal_cell = [2, 3, 4]
        [map]
        file = "v.npy"
    """))
    assert np.array_equal(s.occupancy, vol) and s.goal.tolist() == [9.0, 7.0, 2.5]


DYNAMIC = """
    id = "t.dyn"
    kind = "dynamic"
    start = [0.5, 0.5]
    goal = [9.5, 9.5]
    [map]
    generator = "random"
    seed = 1
    shape = [10, 10]
    density = 0.0
    [[moving_obstacles]]
    radius = 1.0
    waypoints = [[2, 5], [8, 5]]
    speed = 0.5
    mode = "loop"
    [[moving_obstacles]]
    radius = 0.5
    waypoints = [[5, 2]]
    speed = 0.0
"""


def test_dynamic_with_moving_obstacles(tmp_path):
    s = load_scenario_file(write(tmp_path, DYNAMIC))
    assert len(s.moving_obstacles) == 2 and s.moving_obstacles[0].mode == "loop"
    assert s.moving_obstacles[0].position(4.0).tolist() == [4.0, 5.0]
    fails(write(tmp_path, DYNAMIC.replace("radius = 0.5", "radius = -1"), "r.toml"),
          r"field 'moving_obstacles\[1\].radius': must be > 0")
    fails(write(tmp_path, DYNAMIC.replace("speed = 0.0", "speed = 0.0\ncolour = 'red'"), "c.toml"),
          r"field 'moving_obstacles\[1\].colour': unknown key")
    fails(write(tmp_path, DYNAMIC.replace("radius = 0.5", "radius = 'big'"), "t.toml"),
          r"field 'moving_obstacles\[1\].radius': must be a number, got 'big'")
    fails(write(tmp_path, DYNAMIC.replace("speed = 0.0", ""), "m.toml"), r"field 'moving_obstacles\[1\].speed': missing")
    fails(write(tmp_path, DYNAMIC.replace("[[5, 2]]", "[[5, 'a']]"), "w.toml"),
          r"field 'moving_obstacles\[1\].waypoints': must be a number")


def test_rules_with_soil_from_files_and_inline(tmp_path):
    rci = np.full((6, 6), 50.0)
    rci[2:4, 2:4] = 10.0
    np.save(tmp_path / "rci.npy", rci)
    np.savez(tmp_path / "soil.npz", types=np.arange(36).reshape(6, 6) % 3)
    text = """
        id = "soil"
        kind = "terrain"
        start_cell = [0, 0]
        goal_cell = [5, 5]
        [elevation]
        generator = "fractal"
        seed = 3
        shape = [6, 6]
        relief = 2.0
        [rules]
        soil_strength = "rci.npy"
        min_soil_strength = 20.0
        soil_types = { file = "soil.npz", key = "types" }
        soil_names = ["sand", "clay", "rock"]
        slope_weights = [[-10, 1.5], [10, 1.0], [90, 2.0]]
    """
    s = load_scenario_file(write(tmp_path, text))
    assert s.blocked.sum() == 4 and s.blocked[2:4, 2:4].all()
    assert s.rules.soil_names == ("sand", "clay", "rock") and s.rules.soil_types[1, 0] == 0
    assert s.rules.slope_weight(0.0) == 1.0
    fails(write(tmp_path, text.replace("[90, 2.0]", "[90, 'x']"), "sw.toml"), r"field 'rules.slope_weights': must be")
    fails(write(tmp_path, text.replace("= 20.0", "= 'x'"), "min.toml"), r"field 'rules.min_soil_strength': must be")
    fails(write(tmp_path, text.replace('"rock"]', '3]'), "names.toml"), r"field 'rules.soil_names': must be a list")
    np.save(tmp_path / "rci.npy", rci[:5])
    fails(write(tmp_path, text, "shape.toml"), r"field 'rules.soil_strength': shape \(5, 6\) differs")
    fails(write(tmp_path, text.replace('"rci.npy"', "[[1, 2], [3]]"), "ragged.toml"),
          r"field 'rules.soil_strength': ragged")


@pytest.mark.parametrize(
    "change, pattern",
    [
        (("kind = \"grid2d\"", "kind = \"grid2d\"\ncolour = 1"), r"field 'colour': unknown key; allowed here: "),
        (("file = \"arena.map\"", "file = \"arena.map\"\nscale = 2"), r"field 'map.scale': unknown key"),
        (("[metadata]", "[vehicle]\nwheels = 4\n[metadata]"), r"field 'vehicle': unknown key\(s\) \['wheels'\]"),
        (("[metadata]", "[vehicle]\nmass_kg = -3\n[metadata]"), r"field 'vehicle.mass_kg': must be > 0"),
        (("cell_size = 0.5", "cell_size = 0"), r"field 'cell_size': must be in \(0, inf\), got 0"),
        (("cell_size = 0.5", "cell_size = -1.0"), r"field 'cell_size': must be in"),
        (("start = [1.75, 1.75]", "start = [100.0, 1.75]"), r"field 'start': .*outside the map"),
        (("start = [1.75, 1.75]", "start = [1.75]"), r"field 'start': must be a list of 2 numbers"),
        (("goal_cell = [40, 30]", "goal_cell = [49, 30]"), r"field 'goal_cell': \[49, 30\] lies outside"),
        (("goal_cell = [40, 30]", "goal_cell = [0, 0]"), r"field 'goal_cell': .*obstacle"),
        (("goal_cell = [40, 30]", ""), r"field 'goal': missing \(the other endpoint is given\)"),
        (("goal_cell = [40, 30]", "goal_cell = [40, 30]\ngoal = [1.0, 1.0]"), r"field 'goal_cell': give goal or"),
        (("goal_cell = [40, 30]", "goal_cell = [40, 30]\nendpoint_seed = 1"), r"field 'endpoint_seed': only used"),
        (("file = \"arena.map\"", "file = \"gone.map\""), r"field 'map.file': file not found: .*gone.map"),
        (("file = \"arena.map\"", "file = \"arena.txt\""), r"field 'map.file': 'arena.txt' must end in .map"),
        (("file = \"arena.map\"", "file = \"arena.map\"\ngenerator = \"maze\""), r"field 'map.file': give exactly one"),
        (("kind = \"grid2d\"", "kind = \"ocean\""), r"field 'kind': must be one of 'grid2d'"),
        (("kind = \"grid2d\"", "kind = \"grid2d\"\nlayers = 3"), r"field 'layers': applies to kind 'air3d' only"),
        (("paper = \"none\"", "source = \"me\""), r"field 'metadata.source': is set by the reader"),
        (("id = \"t.arena\"", ""), r"field 'id': missing"),
        (("reference_length = 30.0", "reference_length = -1"), r"field 'reference_length': must be in \[0, inf\)"),
    ],
)
def test_errors_name_file_and_field(tmp_path, arena, change, pattern):
    old, new = change
    assert old in GRID
    fails(write(tmp_path, GRID.replace(old, new)), pattern)


def test_malformed_toml_is_one_line(tmp_path):
    fails(write(tmp_path, 'id = "x"\nkind = \n'), r": malformed TOML: .*line 2")


def test_map_file_problems_are_reported_at_map_file(tmp_path):
    (tmp_path / "ragged.map").write_text("type octile\nheight 2\nwidth 3\nmap\n...\n..\n")
    np.save(tmp_path / "f.npy", np.zeros((3, 3)))
    np.save(tmp_path / "obj.npy", np.array([None], dtype=object), allow_pickle=True)
    base = 'id = "x"\nkind = "grid2d"\nstart = [0.5, 0.5]\ngoal = [1.5, 0.5]\n[map]\n'
    fails(write(tmp_path, base + 'file = "ragged.map"\n', "a.toml"),
          r"field 'map.file': .*ragged.map: field 'map row 1'")
    fails(write(tmp_path, base + 'file = "f.npy"\n', "b.toml"), r"field 'map.file': .*f.npy: .*dtype float64")
    fails(write(tmp_path, base + 'file = "obj.npy"\n', "c.toml"), r"field 'map.file': .*obj.npy: .*pickled")
    fails(write(tmp_path, base + 'file = "f.npy"\nkey = "a"\n', "d.toml"), r"field 'map.file': .*'key'")


def test_generator_problems(tmp_path):
    fails(write(tmp_path, ROOMS.replace("room_size = 5", "room_size = 0")), r"field 'map.room_size': must be in")
    fails(write(tmp_path, ROOMS.replace('"rooms"', '"fractal"'), "f.toml"),
          r"field 'map.generator': generator 'fractal' makes elevation; put it under \[elevation\]")
    fails(write(tmp_path, ROOMS.replace("seed = 11", ""), "s.toml"), r"field 'map.seed': generator 'rooms' needs it")
    fails(write(tmp_path, ROOMS.replace('kind = "grid2d"', 'kind = "air3d"\nvertical_cell_size = 1.0'), "a.toml"),
          r"field 'map.generator': must be a non-empty 3-D array")


def test_no_endpoints_and_no_seed(tmp_path, arena):
    text = 'id = "x"\nkind = "grid2d"\n[map]\nfile = "arena.map"\n'
    fails(write(tmp_path, text), r"field 'start': missing; give start and goal .* or endpoint_seed")
    s = load_scenario_file(write(tmp_path, 'endpoint_seed = 4\n' + text, "seeded.toml"))
    assert s.metadata["endpoints"]["seed"] == 4 and not s.blocked[tuple(s.cell_of(s.goal)[0])]


def test_missing_map_table(tmp_path):
    fails(write(tmp_path, 'id = "x"\nkind = "grid2d"\nstart = [0.5, 0.5]\ngoal = [0.5, 0.5]\n'),
          r"field 'map': missing")
    fails(write(tmp_path, 'id = "x"\nkind = "terrain"\n[map]\nfile = "a.map"\n', "t.toml"), r"field 'elevation'")
