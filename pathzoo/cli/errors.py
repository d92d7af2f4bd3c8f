"""The error the CLI raises for problems found by a command itself (not by the library)."""

from __future__ import annotations

from pathzoo.core.errors import PathzooError

__all__ = ["CommandError"]


class CommandError(PathzooError):
    """A command cannot go on: a results file that is not a database, an experiment not in it, ..."""
