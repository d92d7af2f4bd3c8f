"""The planner classes behind external planners: a command started per run, or a function run by Octave.

Each run writes the problem (:mod:`pathzoo_external.problem`) to the
program, whose working directory is an empty scratch folder
(:mod:`pathzoo_external.scratch`), waits for one answer under the deadline
of :func:`answer_limit`, and checks it (:mod:`pathzoo_external.answer`). Whatever goes wrong raises
:class:`~pathzoo.core.errors.ExternalPlannerError`, which the harness stores
as a crash with its one-line reason.
"""

from __future__ import annotations

import json
import time
from dataclasses import replace
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from pathzoo.core.budget import Budget
from pathzoo.core.errors import ExternalPlannerError
from pathzoo.core.planner import Planner, ProgressCallback
from pathzoo.core.results import PlanResult
from pathzoo.core.scenario import Scenario
from pathzoo_external.answer import Answer, decode_answer, read_answer
from pathzoo_external.child import run_once, with_stderr
from pathzoo_external.octave import octave_server
from pathzoo_external.problem import SEED_LIMIT, problem_json
from pathzoo_external.program import Program
from pathzoo_external.scratch import scratch_folder

if TYPE_CHECKING:
    from pathzoo.plugins.external import ExternalPlanner

__all__ = ["ExternalPlannerBase", "CommandPlanner", "OctavePlanner", "answer_limit", "rebuild", "GRACE_S", "GRACE_SHARE",
           "MAX_GRACE_S"]

GRACE_S = 1.0
"""Fixed part of the time an external planner is given beyond its time budget (start-up, reading, writing)."""

GRACE_SHARE = 0.5
"""Part of the time budget added to :data:`GRACE_S`."""

MAX_GRACE_S = 10.0
"""Largest grace beyond the time budget."""


def answer_limit(budget: Budget) -> float | None:
    """Seconds an external planner has to answer: the time budget plus a grace; ``None`` without a time budget.

    Without a time budget the harness's hard limit (``timeout_s``) is the
    only one, and a program that never answers is stored as a timeout.
    """
    if budget.time_s is None:
        return None
    return budget.time_s + min(MAX_GRACE_S, GRACE_S + GRACE_SHARE * budget.time_s)


def _attach(message: str, label: str, text: str) -> str:
    """``message`` with ``text`` (the tail of a program's other output) below it, if any."""
    return with_stderr(message, text).replace("\nstandard error:\n", f"\n{label}:\n", 1).lstrip("\n")


def rebuild(declaration: "ExternalPlanner", params: dict[str, Any]) -> "ExternalPlannerBase":
    """An external planner from its declaration and parameters (how its instances are unpickled)."""
    planner: ExternalPlannerBase = declaration.load()(**params)
    return planner


class ExternalPlannerBase(Planner):
    """A planner that is a program (built per declaration by :func:`pathzoo_external.declared.planner_class`).

    Its class is made at run time, so an instance pickles as its
    declaration and parameters (:func:`rebuild`).
    """

    program: ClassVar[Program] = Program(command=("true",))
    declaration: ClassVar["ExternalPlanner | None"] = None

    def __reduce__(self) -> tuple[Any, ...]:
        return (rebuild, (self.declaration, self.get_params()))

    def plan(self, scenario: Scenario, *, budget: Budget, rng: np.random.Generator,
             progress: ProgressCallback | None = None) -> PlanResult:
        """Send the problem to the program and return its checked answer (protocol in ``docs/external-planners.md``)."""
        self.check_supports(scenario)
        self.program.check_unchanged(self.id, self.version)
        seed = int(rng.integers(SEED_LIMIT))
        with scratch_folder() as scratch:
            problem = problem_json(scenario, budget=budget, seed=seed, params=self.get_params(), scratch=Path(scratch))
            answer = self.ask(problem, scratch, limit_s=answer_limit(budget), dim=scenario.dim)
        if progress is not None:
            for iteration, evaluations, best_cost in answer.history:
                progress(iteration, evaluations, best_cost)
        return answer.result

    def ask(self, problem: str, scratch: str, *, limit_s: float | None, dim: int) -> Answer:
        """Run the program on one problem (JSON text) and return its checked answer."""
        raise NotImplementedError


class CommandPlanner(ExternalPlannerBase):
    """A command started once per run: the problem on standard input, one JSON answer on standard output."""

    def ask(self, problem: str, scratch: str, *, limit_s: float | None, dim: int) -> Answer:
        """Start the command in ``scratch`` and read its answer; standard error goes below the message."""
        deadline = None if limit_s is None else time.perf_counter() + limit_s
        output = run_once(self.program.command, problem.encode() + b"\n", cwd=scratch, deadline=deadline,
                          limit_s=limit_s, who=self.id)
        answer = read_answer(decode_answer(output.stdout, self.id), dim=dim, who=self.id)
        message = _attach(answer.result.message, "standard error", output.stderr)
        return Answer(replace(answer.result, message=message), answer.history)


class OctavePlanner(ExternalPlannerBase):
    """A function file ``[path, info] = name(problem, params)`` called by this worker's Octave process."""

    def ask(self, problem: str, scratch: str, *, limit_s: float | None, dim: int) -> Answer:
        """Send the call to Octave and read its answer; printed output goes below the message."""
        name = Path(self.program.octave).name
        request = (f'{{"file":{json.dumps(self.program.octave)},"scratch":{json.dumps(scratch)},'
                   f'"problem":{problem}}}')
        line, printed = octave_server().ask(request.encode(), limit_s=limit_s, who=self.id)
        reply = decode_answer(line, self.id)
        if not isinstance(reply, dict) or not {"answer", "output", "error"} <= set(reply):
            raise ExternalPlannerError(f"{self.id}: the Octave shim's reply is malformed")
        output = "\n".join(str(t) for t in (reply["output"], printed) if isinstance(t, str) and t.strip())
        if reply["error"]:
            raise ExternalPlannerError(with_stderr(f"{self.id}: {name} {reply['error']}", output))
        answer = read_answer(reply["answer"], dim=dim, who=f"{self.id}: {name}")
        return Answer(replace(answer.result, message=_attach(answer.result.message, "output", output)), answer.history)
