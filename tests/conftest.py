"""Shared test fixtures."""

from __future__ import annotations

from pathlib import Path

import pytest

REPO_ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="session")
def shared_data() -> Path:
    """``tests/data``: MovingAI maps and scenarios and real DEMs, with their licences (see its README.md).

    The files are part of the repository (about 0.7 MB), so a lone clone runs
    the tests. Fails (never skips) when the folder is incomplete.
    """
    path = REPO_ROOT / "tests" / "data"
    if not (path / "movingai").is_dir() or not (path / "dem").is_dir():
        pytest.fail(f"test data not found at {path}", pytrace=False)
    return path


def pytest_sessionfinish(session: pytest.Session) -> None:
    """Uninstall what the tests pip-installed, once every worker is done.

    Under pytest-xdist only the controller (which has no ``workerinput``)
    does it, after all workers have finished.
    """
    if not hasattr(session.config, "workerinput"):
        from installed_by_tests import uninstall_what_tests_installed

        uninstall_what_tests_installed()
