"""Planner classes built from declarations of external planners (:class:`pathzoo.plugins.external.ExternalPlanner`)."""

from __future__ import annotations

from typing import TYPE_CHECKING

from pathzoo_external.planner import CommandPlanner, ExternalPlannerBase, OctavePlanner
from pathzoo_external.program import Program

if TYPE_CHECKING:
    from pathzoo.plugins.external import ExternalPlanner

__all__ = ["planner_class"]


def planner_class(declaration: "ExternalPlanner") -> type[ExternalPlannerBase]:
    """A new planner class for ``declaration``, its version the digest of the program's files.

    The class is made at run time, so no worker can import it by name: the
    harness sends it to workers by value (:func:`pathzoo.harness.specs.planner_by_value`).
    """
    program = Program(tuple(declaration.command), declaration.octave)
    base: type[ExternalPlannerBase] = OctavePlanner if declaration.octave else CommandPlanner
    return type(base.__name__, (base,), {
        "__module__": __name__,
        "__qualname__": f"{base.__name__}[{declaration.id}]",
        "__doc__": f"{declaration.id}: {declaration.summary}",
        "id": declaration.id,
        "version": program.digest(),
        "summary": declaration.summary,
        "kinds": frozenset(declaration.kinds),
        "params": dict(declaration.params),
        "program": program,
        "declaration": declaration,
    })
