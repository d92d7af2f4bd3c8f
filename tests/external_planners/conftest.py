"""Fixtures of the external-planner tests: the test programs, a compiled A*, Octave's presence."""

from __future__ import annotations

import shutil
import subprocess
from pathlib import Path
from typing import Iterator

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


@pytest.fixture(autouse=True)
def forget_declared_planners() -> Iterator[None]:
    """After each test, forget the planners its experiment files declared (later tests see the installed ones)."""
    yield
    from pathzoo.plugins.external import EXPERIMENT_FILES
    from pathzoo.plugins.manager import get_registry, reset_registry

    if any(e.plugin == EXPERIMENT_FILES for e in get_registry().planners.values()):
        reset_registry()
