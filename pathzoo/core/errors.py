"""The small error hierarchy that every pathzoo component raises from."""

from __future__ import annotations

__all__ = [
    "PathzooError",
    "InvalidScenarioError",
    "InvalidParameterError",
    "UnknownPluginError",
    "UnsupportedScenarioError",
    "InvalidExperimentError",
    "ExternalPlannerError",
]


class PathzooError(Exception):
    """Base class of every error pathzoo raises on bad input.

    The CLI prints ``str(error)`` as one line and exits with code 2, so messages
    must name the offending file, field or parameter and fit on one line.
    """


class InvalidScenarioError(PathzooError, ValueError):
    """A scenario file or scenario object is malformed.

    Parameters
    ----------
    message : str
        What is wrong.
    source : str, optional
        The file (or scenario id) the problem was found in.
    field : str, optional
        The field of that file that is wrong.
    """

    def __init__(self, message: str, *, source: str | None = None, field: str | None = None):
        self.source = source
        self.field = field
        where = ""
        if source is not None and field is not None:
            where = f"{source}: field '{field}': "
        elif source is not None:
            where = f"{source}: "
        elif field is not None:
            where = f"field '{field}': "
        super().__init__(f"{where}{message}")


class InvalidParameterError(PathzooError, ValueError):
    """A planner (or metric) hyperparameter has a bad name, type or value."""


class UnknownPluginError(PathzooError, LookupError):
    """No planner, scenario or metric is registered under the requested id."""


class UnsupportedScenarioError(PathzooError, TypeError):
    """A planner was asked to plan on a scenario kind it does not declare."""


class InvalidExperimentError(PathzooError, ValueError):
    """An experiment description (TOML file or Python arguments) is malformed."""


class ExternalPlannerError(PathzooError, RuntimeError):
    """An external planner (a command or an Octave function file) broke pathzoo's planner protocol.

    The message's first line names the planner and the cause (Octave missing,
    the function raised, the answer has the wrong shape, no answer in time,
    too much output); the lines after it hold the tail of what the program
    wrote on standard error. A run that raises it is stored as a crash with
    this message, without a traceback of the bridge (``docs/external-planners.md``).
    """
