"""Shared test fixtures."""

from __future__ import annotations

from pathlib import Path

import pytest

REPO_ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="session")
def shared_data() -> Path:
    """``<repo>/../shared/data``: MovingAI maps and scenarios and real DEMs (see its README.md).

    Fails (never skips) when the folder is missing, so a checkout without the
    shared data cannot pass silently.
    """
    path = (REPO_ROOT / ".." / "shared" / "data").resolve()
    if not (path / "movingai").is_dir() or not (path / "dem").is_dir():
        pytest.fail(f"shared test data not found at {path}: put shared/ beside the repository", pytrace=False)
    return path


def pytest_sessionfinish(session: pytest.Session) -> None:
    """Uninstall what the tests pip-installed, once every worker is done.

    Under pytest-xdist only the controller (which has no ``workerinput``)
    does it, after all workers have finished.
    """
    if not hasattr(session.config, "workerinput"):
        from installed_by_tests import uninstall_what_tests_installed

        uninstall_what_tests_installed()
