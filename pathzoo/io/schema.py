"""Typed, located access to the tables of a scenario TOML file: every error names the file and the field."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Iterable, Mapping, Sequence

from pathzoo.core.errors import InvalidScenarioError
from pathzoo.generators.checks import check_number

__all__ = ["Table", "MISSING"]

MISSING: Any = object()
"""Default meaning "the key is required"."""


@dataclass(frozen=True)
class Table:
    """One TOML table of a scenario file.

    Parameters
    ----------
    data : mapping
        The parsed table.
    source : str
        The file, for error messages.
    name : str
        Dotted name of the table (``""`` for the top level), prefixed to keys
        in error messages: ``map.file``.
    """

    data: Mapping[str, Any]
    source: str
    name: str = ""

    def field(self, key: str) -> str:
        """Dotted field name of ``key``."""
        return f"{self.name}.{key}" if self.name else key

    def error(self, key: str, message: str) -> InvalidScenarioError:
        """An error located at ``key`` of this table."""
        return InvalidScenarioError(message, source=self.source, field=self.field(key))

    def __contains__(self, key: str) -> bool:
        return key in self.data

    def reject_unknown(self, allowed: Iterable[str]) -> None:
        """Raise on the first key not in ``allowed``."""
        allowed = sorted(allowed)
        for key in self.data:
            if key not in allowed:
                raise self.error(key, f"unknown key; allowed here: {', '.join(allowed)}")

    def _get(self, key: str, default: Any) -> Any:
        if key in self.data:
            return self.data[key]
        if default is MISSING:
            raise self.error(key, "missing")
        return default

    def string(self, key: str, *, default: Any = MISSING, choices: Sequence[str] | None = None) -> Any:
        """A string value (or ``default`` when absent), optionally one of ``choices``."""
        value = self._get(key, default)
        if key not in self.data:
            return value
        if not isinstance(value, str):
            raise self.error(key, f"must be a string, got {value!r}")
        if choices is not None and value not in choices:
            raise self.error(key, f"must be one of {', '.join(map(repr, choices))}, got {value!r}")
        return value

    def number(self, key: str, *, default: Any = MISSING, **bounds: Any) -> Any:
        """A finite number within ``bounds`` (see :func:`~pathzoo.generators.checks.check_number`)."""
        value = self._get(key, default)
        if key not in self.data:
            return value
        return check_number(value, self.field(key), source=self.source, **bounds)

    def vector(self, key: str, lengths: Sequence[int], *, integer: bool = False, default: Any = MISSING) -> Any:
        """A list of numbers (ints when ``integer``) whose length is one of ``lengths``, as a tuple."""
        value = self._get(key, default)
        if key not in self.data:
            return value
        if not isinstance(value, list) or len(value) not in lengths:
            n = " or ".join(map(str, lengths))
            raise self.error(key, f"must be a list of {n} {'integers' if integer else 'numbers'}, got {value!r}")
        return tuple(check_number(v, self.field(key), source=self.source, integer=integer) for v in value)

    def table(self, key: str) -> "Table | None":
        """The sub-table ``key`` (``None`` when absent)."""
        if key not in self.data:
            return None
        value = self.data[key]
        if not isinstance(value, Mapping):
            raise self.error(key, f"must be a table, got {value!r}")
        return Table(value, self.source, self.field(key))
