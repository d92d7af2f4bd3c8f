"""MovingAI pack: every bundled problem registered, optimal lengths attached and reproduced, bucket globs."""

from __future__ import annotations

import hashlib

import numpy as np
import pytest

import pathzoo
from pathzoo.io.movingai import read_scen
from pathzoo.plugins.manager import get_registry
from pathzoo_scenarios import movingai
from pathzoo_scenarios.common import DATA_DIR


def _shared_scen_files(shared_data):
    return sorted((shared_data / "movingai").rglob("*.scen"))


def test_bundled_files_are_the_shared_ones_with_attribution(shared_data):
    shared = sorted(p for p in (shared_data / "movingai").rglob("*") if p.is_file())
    assert len(shared) == 12
    for p in shared:
        copy = DATA_DIR / "movingai" / p.name
        assert hashlib.sha256(copy.read_bytes()).digest() == hashlib.sha256(p.read_bytes()).digest(), p.name
    assert "Sturtevant" in (DATA_DIR / "movingai" / "HOG2_LICENSE.txt").read_text()


def test_every_problem_is_registered(shared_data):
    reg = get_registry()
    expected = set()
    for path in _shared_scen_files(shared_data):
        stem = next(k for k, v in movingai.SCEN_FILES.items() if v == path.name)
        expected |= {movingai.scenario_id(stem, p.bucket, p.index) for p in read_scen(path)}
    assert len(expected) == 3183
    registered = {k for k in reg.scenarios if k.startswith("movingai.")}
    assert registered == expected


def test_glob_selects_families_without_duplicates():
    reg = get_registry()
    arena = reg.match("scenarios", "movingai.arena.*")
    assert len(arena) == 160 == len(set(arena))
    bucket = reg.match("scenarios", "movingai.8room_000.b50.*")
    assert len(bucket) == 10 and all(".b50." in i for i in bucket)
    assert reg.match("scenarios", "movingai.arena.*.17") == ["movingai.arena.b1.17"]


def test_problems_of_a_map_share_one_graph():
    a = pathzoo.load_scenario("movingai.arena.b0.3")
    b = pathzoo.load_scenario("movingai.arena.b15.159")
    assert a.graph is b.graph and a.occupancy is b.occupancy
    assert a.metadata["pack"] == "movingai" and a.metadata["bucket"] == 0


@pytest.mark.parametrize("stem", list(movingai.SCEN_FILES))
def test_reference_lengths_are_attached_and_exact(stem, shortest):
    problems = read_scen(movingai.scen_path(stem))
    picks = np.linspace(0, len(problems) - 1, 8).round().astype(int)
    for k in picks:
        p = problems[k]
        s = pathzoo.load_scenario(movingai.scenario_id(stem, p.bucket, p.index))
        assert s.reference_length == p.optimal_length
        np.testing.assert_array_equal(s.start, [p.start_col + 0.5, p.start_row + 0.5])
        cost, _ = shortest(s)
        assert cost == pytest.approx(p.optimal_length, rel=1e-5, abs=1e-4)
