"""The worked examples of docs/coordinates.md, computed through the scenario reader."""

import shutil

import numpy as np

from pathzoo.io import load_scenario_file


def test_2d_example(tmp_path):
    np.save(tmp_path / "m.npy", np.zeros((3, 4), bool))
    (tmp_path / "s.toml").write_text(
        'id = "c"\nkind = "grid2d"\ncell_size = 2.0\nstart = [5.0, 3.0]\ngoal_cell = [2, 3]\n[map]\nfile = "m.npy"\n'
    )
    s = load_scenario_file(tmp_path / "s.toml")
    assert s.extent.tolist() == [8.0, 6.0]
    assert s.cell_of(s.start).tolist() == [[1, 2]] and s.start_node == 6
    assert s.cell_of(np.array([6.0, 2.0])).tolist() == [[1, 3]]
    assert s.goal.tolist() == [7.0, 5.0]


def test_hugo_example(tmp_path, shared_data):
    shutil.copy(shared_data / "dem" / "hugo_site.asc", tmp_path)
    (tmp_path / "s.toml").write_text(
        'id = "h"\nkind = "terrain"\nstart_cell = [27, 38]\ngoal_cell = [27, 39]\n[elevation]\nfile = "hugo_site.asc"\n'
    )
    s = load_scenario_file(tmp_path / "s.toml")
    assert s.start.tolist() == [385.0, 275.0]
    header = s.metadata["elevation"]["header"]
    northing = header["yllcorner"] + header["nrows"] * s.cell_size - s.start[1]
    assert northing == 275.0
    data_rows = (tmp_path / "hugo_site.asc").read_text().splitlines()[6:]
    assert s.elevation[27, 38] == float(data_rows[27].split()[38])


def test_air3d_example(tmp_path):
    np.save(tmp_path / "v.npy", np.zeros((4, 3, 5), bool))
    (tmp_path / "s.toml").write_text(
        'id = "a"\nkind = "air3d"\ncell_size = 10.0\nvertical_cell_size = 2.5\nstart_cell = [0, 0, 0]\n'
        'goal_cell = [3, 2, 4]\n[map]\nfile = "v.npy"\n'
    )
    s = load_scenario_file(tmp_path / "s.toml")
    assert s.extent.tolist() == [50.0, 30.0, 10.0]
    assert s.goal.tolist() == [45.0, 25.0, 8.75] and s.goal_node == 59
