"""The installed pathzoo's version, read once from its distribution's metadata."""

from __future__ import annotations

import functools

__all__ = ["installed_version"]


@functools.cache
def installed_version() -> str:
    """pathzoo's version (``pathzoo.__version__``); ``0.0.0+unknown`` in a source tree that is not installed."""
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("pathzoo")
    except PackageNotFoundError:
        return "0.0.0+unknown"
