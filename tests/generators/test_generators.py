"""The map generators: determinism, versions, the structure each promises, and parameter errors."""

import numpy as np
import pytest
from scipy import ndimage

from pathzoo import InvalidScenarioError
from pathzoo.generators import (
    GENERATORS,
    fractal_terrain,
    gaussian_peaks,
    generate,
    maze,
    random_obstacles,
    rooms,
    terrain_volume,
)

SMALL = {
    "random": dict(shape=(20, 30)),
    "rooms": dict(shape=(40, 50)),
    "maze": dict(shape=(21, 31)),
    "fractal": dict(shape=(32, 48)),
    "gaussian_peaks": dict(shape=(30, 40)),
}


@pytest.mark.parametrize("name", sorted(GENERATORS))
def test_same_seed_same_array_other_seed_other_array(name):
    info = GENERATORS[name]
    a = info.function(seed=3, **SMALL[name])
    b = info.function(seed=3, **SMALL[name])
    c = info.function(seed=4, **SMALL[name])
    assert a.shape == SMALL[name]["shape"]
    assert a.dtype == (bool if info.produces == "occupancy" else np.float64)
    assert np.array_equal(a, b)
    assert not np.array_equal(a, c)
    assert isinstance(info.version, int) and info.version >= 1


def test_every_generator_is_registered_once_with_its_module_version():
    from pathzoo.generators import fractal, peak_terrain, perfect_maze, random_field, room_grid

    modules = {"random": random_field, "rooms": room_grid, "maze": perfect_maze, "fractal": fractal,
               "gaussian_peaks": peak_terrain}
    assert set(GENERATORS) == set(modules)
    for name, module in modules.items():
        assert GENERATORS[name].version == module.GENERATOR_VERSION


def test_random_density_and_3d_shape():
    occ = random_obstacles((200, 200), 0, density=0.3)
    assert abs(occ.mean() - 0.3) < 0.01
    assert random_obstacles((3, 10, 12), 1).shape == (3, 10, 12)
    assert not random_obstacles((10, 10), 1, density=0.0).any()


def _door_cells(occ, room_size):
    period = room_size + 1
    rows = np.arange(room_size, occ.shape[0] - 1, period)
    cols = np.arange(room_size, occ.shape[1] - 1, period)
    on_wall = np.zeros(occ.shape, bool)
    on_wall[rows, :] = True
    on_wall[:, cols] = True
    return int((on_wall & ~occ).sum()), len(rows) + 1, len(cols) + 1


def test_rooms_tree_has_one_door_per_tree_edge_and_everything_is_connected():
    occ = rooms((43, 52), 7, room_size=6, extra_door_probability=0.0)
    doors, nr, nc = _door_cells(occ, 6)
    assert doors == nr * nc - 1  # a spanning tree of the rooms
    _, n = ndimage.label(~occ)  # 4-connected free components
    assert n == 1


def test_rooms_with_every_extra_door_open_every_wall():
    occ = rooms((47, 52), 7, room_size=6, extra_door_probability=1.0, door_width=2)  # every band >= 2 wide
    doors, nr, nc = _door_cells(occ, 6)
    adjacencies = nr * (nc - 1) + (nr - 1) * nc
    assert doors == 2 * adjacencies


def test_maze_is_a_perfect_maze():
    occ = maze((41, 61), 5)
    free = ~occ
    _, n = ndimage.label(free)
    edges = (free[:, 1:] & free[:, :-1]).sum() + (free[1:, :] & free[:-1, :]).sum()
    assert n == 1 and edges == free.sum() - 1  # connected and acyclic: a tree


def test_wide_maze_corridors_and_leftover_rows_blocked():
    occ = maze((33, 33), 2, corridor_width=2, wall_width=2)
    assert occ[32, :].all() and occ[:, 32].all()  # 33 = 8 periods of 4 + 1 leftover
    assert not occ[:2, :2].any()
    _, n = ndimage.label(~occ)
    assert n == 1


def test_fractal_range_and_smoothness_follow_parameters():
    rough = fractal_terrain((64, 64), 1, hurst=0.2, relief=50.0, base=100.0)
    smooth = fractal_terrain((64, 64), 1, hurst=0.9, relief=50.0, base=100.0)
    assert rough.min() == pytest.approx(100.0) and rough.max() == pytest.approx(150.0)
    assert np.abs(np.diff(smooth, axis=1)).mean() < np.abs(np.diff(rough, axis=1)).mean()


def test_gaussian_peaks_match_dsaco_eq1_evaluated_directly():
    peaks = [[30e3, 9e3, 660.0, 4e3, 3e3], [16e3, 17e3, 1640.0, 7e3, 8e3], [35e3, 32e3, 1300.0, 5e3, 8e3]]
    z = gaussian_peaks((50, 50), 0, cell_size=1000.0, peaks=peaks)
    r, c = 17, 16
    x, y = (c + 0.5) * 1000.0, (r + 0.5) * 1000.0
    direct = sum(h * np.exp(-(((x - x0) / xs) ** 2) - ((y - y0) / ys) ** 2) for x0, y0, h, xs, ys in peaks)
    assert z[r, c] == pytest.approx(direct)
    assert z.max() < 1640.0 + 660.0 + 1300.0


def test_random_peaks_and_no_peaks():
    z = gaussian_peaks((40, 40), 2, n_peaks=3, max_height=50.0)
    assert 0 < z.max() <= 3 * 50.0
    assert not gaussian_peaks((5, 5), 0, n_peaks=0).any()


def test_terrain_volume_blocks_voxels_below_ground_and_no_data_columns():
    ground = np.array([[0.0, 150.0], [np.nan, 250.0]])
    vol = terrain_volume(ground, 3, 100.0)
    assert vol[:, 0, 0].tolist() == [False, False, False]
    assert vol[:, 0, 1].tolist() == [True, True, False]  # bottoms 0, 100 < 150
    assert vol[:, 1, 0].all()
    assert vol[:, 1, 1].tolist() == [True, True, True]


@pytest.mark.parametrize(
    "call, field",
    [
        (lambda: random_obstacles((10, 10), 0, density=1.0), "density"),
        (lambda: random_obstacles((10,), 0), "shape"),
        (lambda: random_obstacles((10, 10), -1), "seed"),
        (lambda: random_obstacles((10, 10), 1.5), "seed"),
        (lambda: rooms((10, 10), 0, room_size=0), "room_size"),
        (lambda: maze((10, 10), 0, wall_width=True), "wall_width"),
        (lambda: fractal_terrain((10, 10), 0, hurst=1.0), "hurst"),
        (lambda: gaussian_peaks((10, 10), 0, peaks=[[1, 2, 3, 0, 1]]), "peaks[0].x_spread"),
        (lambda: gaussian_peaks((10, 10), 0, peaks=[[1, 2, 3]]), "peaks"),
        (lambda: gaussian_peaks((10, 10), 0, peaks=[], n_peaks=2), "n_peaks"),
    ],
)
def test_bad_parameters_name_the_field(call, field):
    with pytest.raises(InvalidScenarioError, match=rf"field '{field.replace('[', '.').replace(']', '.')}'"):
        call()


def test_generate_records_provenance_and_locates_errors():
    arr, record = generate("rooms", {"seed": 2, "shape": [20, 20], "room_size": 4}, source="x.toml")
    assert np.array_equal(arr, rooms((20, 20), 2, room_size=4))
    assert record == {
        "generator": "rooms",
        "version": GENERATORS["rooms"].version,
        "seed": 2,
        "params": {"shape": [20, 20], "room_size": 4, "door_width": 1, "extra_door_probability": 0.5},
    }
    with pytest.raises(InvalidScenarioError, match=r"^x.toml: field 'map.density': must be in"):
        generate("random", {"seed": 1, "shape": [5, 5], "density": 2.0}, source="x.toml")
    with pytest.raises(InvalidScenarioError, match=r"^x.toml: field 'map.colour': unknown parameter"):
        generate("random", {"seed": 1, "shape": [5, 5], "colour": 2}, source="x.toml")
    with pytest.raises(InvalidScenarioError, match=r"field 'elevation.seed': generator 'fractal' needs it"):
        generate("fractal", {"shape": [5, 5]}, source="x.toml", table="elevation")
    with pytest.raises(InvalidScenarioError, match=r"field 'map.generator': unknown generator 'dungeon'"):
        generate("dungeon", {}, source="x.toml")
