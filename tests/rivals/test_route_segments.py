"""Per-segment measures of routes and the compiled leap geometry: the same bits as the whole-path NumPy computation."""

from __future__ import annotations

import numpy as np
import pytest

import pathzoo
from pathzoo.grid.terrain import path_profile, segments_profile
from pathzoo.metrics.geometry import drive_time_energy, driven_pieces, travel_time_energy, turn_angles
from pathzoo_rivals.route_kernels import blend_cells, clearance_samples, resample
from pathzoo_rivals.route_segments import SegmentCache
from pathzoo_rivals.routes import RouteProblem


@pytest.fixture(scope="module")
def hugo() -> pathzoo.Scenario:
    return pathzoo.load_scenario("ggaco.hugo")


def routes(problem: RouteProblem, n: int, seed: int = 0) -> list[np.ndarray]:
    rng = np.random.default_rng(seed)
    return [r for r in (problem.random_route(rng) for _ in range(n)) if r is not None]


def whole_path_clearances(problem: RouteProblem, pts: np.ndarray) -> np.ndarray:
    cs = problem.scenario.cell_size
    seg = np.diff(pts, axis=0)
    steps = np.maximum(1, np.ceil(np.hypot(seg[:, 0], seg[:, 1]) / (0.5 * cs)).astype(np.int64))
    return clearance_samples(problem.scenario.clearance, np.ascontiguousarray(pts), steps, float(cs))


def test_segments_profile_joins_to_path_profile(hugo):
    rng = np.random.default_rng(4)
    h, w = hugo.shape
    for _ in range(30):
        pts = np.stack([rng.uniform(0, w * hugo.cell_size, 12), rng.uniform(0, h * hugo.cell_size, 12)], axis=1)
        whole = path_profile(hugo.elevation, pts, hugo.cell_size)
        parts = [segments_profile(hugo.elevation, pts[i:i + 1], pts[i + 1:i + 2], hugo.cell_size) for i in range(11)]
        for k in range(2):
            assert np.concatenate([p[k] for p in parts]).tobytes() == whole[k].tobytes()


def test_segment_cache_gives_the_whole_path_bits(hugo):
    problem = RouteProblem(hugo)
    cache = SegmentCache(hugo)
    shared = 0
    for route in routes(problem, 40) * 2:  # the second pass is answered from what was kept
        pts = problem.world_path(route)
        lengths, slopes = cache.pieces(pts)
        expected = driven_pieces(hugo, pts)
        assert lengths.tobytes() == expected[0].tobytes() and slopes.tobytes() == expected[1].tobytes()
        assert cache.clearances(pts).tobytes() == whole_path_clearances(problem, pts).tobytes()
        energy = drive_time_energy(hugo.vehicle, lengths, slopes, turn_angles(pts))[1]
        assert energy == travel_time_energy(hugo, pts)[1]
        shared += len(pts) - 1
    assert shared > 0


def test_blend_cells_is_numpys_resampling(hugo):
    problem = RouteProblem(hugo)
    found = routes(problem, 12, seed=3)
    rng = np.random.default_rng(5)
    cs, (h, w) = hugo.cell_size, hugo.shape

    def numpy_resample(points: np.ndarray, n: int) -> np.ndarray:
        s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(points, axis=0).T))])
        t = np.linspace(0.0, s[-1], n)
        return np.stack([np.interp(t, s, points[:, 0]), np.interp(t, s, points[:, 1])], axis=1)

    for a, b in zip(found[:-1], found[1:]):
        pa, pb = problem.polyline(a), problem.polyline(b)
        n = max(len(a), len(b), int(np.ceil(max(np.hypot(*np.diff(p, axis=0).T).sum() for p in (pa, pb)) / cs)) + 1)
        r = rng.uniform()
        assert resample(pa, n).tobytes() == numpy_resample(pa, n).tobytes()
        blend = numpy_resample(pa, n) + r * (numpy_resample(pb, n) - numpy_resample(pa, n))
        cells = (np.clip((blend[:, 1] / cs).astype(np.int64), 0, h - 1) * w
                 + np.clip((blend[:, 0] / cs).astype(np.int64), 0, w - 1))
        cells[0], cells[-1] = problem.start, problem.goal
        expected = cells[np.concatenate([[True], cells[1:] != cells[:-1]])]
        assert np.array_equal(blend_cells(pa, pb, n, r, cs, h, w, problem.start, problem.goal), expected)
