"""Fixtures of the external-planner tests: the test programs, a compiled A*, Octave's presence."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
PROGRAMS = Path(__file__).resolve().parent / "programs"
ASTAR_C = REPO / "examples" / "external" / "astar.c"

needs_octave = pytest.mark.skipif(shutil.which("octave-cli") is None,
                                  reason="GNU Octave is not installed (CI installs it: .ci/run)")


@pytest.fixture(scope="session")
def astar_program(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """``examples/external/astar.c`` compiled with ``cc`` (CI installs a compiler where it lacks one)."""
    compiler = shutil.which("cc") or shutil.which("gcc")
    if compiler is None:
        pytest.fail("no C compiler (cc) to build examples/external/astar.c", pytrace=False)
    out = tmp_path_factory.mktemp("astar") / "astar"
    subprocess.run([compiler, "-O2", "-o", str(out), str(ASTAR_C), "-lm"], check=True)
    return out
