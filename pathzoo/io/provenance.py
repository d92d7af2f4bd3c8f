"""Provenance records of the data files a scenario was read from."""

from __future__ import annotations

import hashlib
from pathlib import Path

__all__ = ["file_record"]


def file_record(path: Path) -> dict[str, str]:
    """The file's path and the SHA-256 of its bytes, for ``Scenario.metadata``."""
    return {"file": str(path), "sha256": hashlib.sha256(path.read_bytes()).hexdigest()}
