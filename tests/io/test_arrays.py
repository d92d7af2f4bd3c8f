"""NumPy array files: never unpickled, and checked as occupancy or elevation."""

import pickle

import numpy as np
import pytest

from pathzoo import InvalidScenarioError
from pathzoo.io import as_elevation, as_occupancy, load_array


def test_pickled_npy_is_refused(tmp_path):
    np.save(tmp_path / "obj.npy", np.array([{"a": 1}, None], dtype=object), allow_pickle=True)
    with pytest.raises(InvalidScenarioError, match="obj.npy: .*pickled"):
        load_array(tmp_path / "obj.npy")


def test_a_pickle_named_npy_is_refused_and_never_run(tmp_path):
    marker = tmp_path / "ran"

    class Boom:
        def __reduce__(self):
            return (open, (str(marker), "w"))

    (tmp_path / "evil.npy").write_bytes(pickle.dumps(Boom()))
    with pytest.raises(InvalidScenarioError, match="evil.npy: .*pickled"):
        load_array(tmp_path / "evil.npy")
    assert not marker.exists()


def test_object_array_inside_npz_is_refused(tmp_path):
    np.savez(tmp_path / "mix.npz", grid=np.zeros((2, 2), bool), junk=np.array([object()], dtype=object))
    with pytest.raises(InvalidScenarioError, match="mix.npz: field 'junk': .*pickled"):
        load_array(tmp_path / "mix.npz", key="grid")


def test_npz_keys(tmp_path):
    np.savez(tmp_path / "two.npz", a=np.zeros((2, 2)), b=np.ones((2, 2)))
    assert load_array(tmp_path / "two.npz", key="b").sum() == 4
    with pytest.raises(InvalidScenarioError, match="field 'key': holds arrays \\['a', 'b'\\]"):
        load_array(tmp_path / "two.npz")
    with pytest.raises(InvalidScenarioError, match="field 'key': no array 'c'"):
        load_array(tmp_path / "two.npz", key="c")
    np.save(tmp_path / "one.npy", np.zeros(3))
    with pytest.raises(InvalidScenarioError, match="field 'key'"):
        load_array(tmp_path / "one.npy", key="a")


def test_missing_or_garbage_file(tmp_path):
    with pytest.raises(InvalidScenarioError, match="none.npy: cannot read"):
        load_array(tmp_path / "none.npy")
    (tmp_path / "text.npy").write_text("hello")
    with pytest.raises(InvalidScenarioError, match="text.npy: "):
        load_array(tmp_path / "text.npy")


@pytest.mark.parametrize(
    "array, message",
    [
        (np.zeros((3, 3)), "dtype float64"),
        (np.array([[0, 2], [1, 0]]), "only 0"),
        (np.zeros((2, 2, 2), bool), "2-D"),
        (np.zeros((0, 3), bool), "non-empty"),
        (np.array([["a"]]), "dtype <U1"),
    ],
)
def test_bad_occupancy_arrays(array, message):
    with pytest.raises(InvalidScenarioError, match=f"f.npy: field 'map': .*{message}"):
        as_occupancy(array, ndim=2, source="f.npy", field="map")


def test_integer_occupancy_is_accepted_read_only():
    occ = as_occupancy(np.array([[0, 1], [1, 0]], dtype=np.uint8), ndim=2, source="f", field="map")
    assert occ.dtype == bool and occ.tolist() == [[False, True], [True, False]] and not occ.flags.writeable


def test_bad_elevation_arrays():
    with pytest.raises(InvalidScenarioError, match="dtype bool"):
        as_elevation(np.zeros((2, 2), bool), nodata="error", source="f", field="z")
    with pytest.raises(InvalidScenarioError, match="1 cells are NaN or infinite"):
        as_elevation(np.array([[0.0, np.inf]]), nodata="error", source="f", field="z")
    assert np.isnan(as_elevation(np.array([[0.0, np.inf]]), nodata="obstacle", source="f", field="z")[0, 1])
