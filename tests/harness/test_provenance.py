"""Provenance of a run: loaded library versions, CPU, core count and peak RSS, measured in the worker."""

from __future__ import annotations

import math
import os
import sys
from importlib import metadata

import numpy as np
import pytest

import pathzoo
from pathzoo import Budget
from pathzoo.harness import provenance
from pathzoo.harness.store import read_runs, read_versions
from pathzoo.testing import check_scenario


def test_loaded_distributions_lists_only_imported_libraries(monkeypatch):
    monkeypatch.delitem(sys.modules, "deap", raising=False)
    monkeypatch.setitem(sys.modules, "pyswarms", sys.modules["numpy"])  # pretend it is loaded
    loaded = provenance.loaded_distributions()
    assert loaded["numpy"] == metadata.version("numpy")
    assert loaded["pyswarms"] == metadata.version("pyswarms")
    assert "deap" not in loaded


def test_host_names_the_cpu_and_core_count():
    info = provenance.host()
    assert info[provenance.CORES_KEY] == str(os.cpu_count())
    assert info[provenance.CPU_KEY] and info[provenance.CPU_KEY] != "unknown"


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="VmHWM reset is Linux only")
def test_peak_rss_sees_an_allocation_and_resets():
    assert provenance.reset_peak_rss()
    before = provenance.peak_rss_mb()
    block = np.ones(20_000_000)  # 160 MB, touched
    assert provenance.peak_rss_mb() > before + 100
    del block
    assert provenance.reset_peak_rss()
    assert provenance.peak_rss_mb() < before + 100


def test_a_process_run_records_its_libraries_host_and_memory(tmp_path):
    db = tmp_path / "p.sqlite"
    pathzoo.run(["ompl.rrtconnect"], [check_scenario("grid2d")], seeds=1, db=db, budget=Budget(time_s=0.5),
                executor="process", jobs=1, progress=False, experiment="prov")
    key = read_runs(db, "prov")["run_key"].iloc[0]
    versions = read_versions(db, "prov")[key]
    assert versions["ompl"] == metadata.version("ompl") and versions["numpy"] == np.__version__
    assert versions[provenance.CORES_KEY] == str(os.cpu_count())
    peak = float(versions[provenance.PEAK_RSS_KEY])
    assert math.isfinite(peak) and 10 < peak < 4096
