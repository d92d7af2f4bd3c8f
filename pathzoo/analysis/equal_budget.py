"""A paper's comparison at equal evaluations: every rival gets the proposed method's evaluation count per scenario.

``pathzoo reproduce PAPER --equal evaluations`` runs in two steps:

1. the paper's proposed method (its ``reference``) with the paper's budget,
   as in the plain rerun;
2. per scenario, every rival with ``Budget(evaluations=E)``, where ``E`` is
   the median of the evaluations the proposed method stored on that
   scenario (rounded down), and no iteration count, so the rival searches
   until it has spent exactly as many evaluations (never more: every family
   caps evaluations exactly) or ends by itself first.

One evaluation is what each planner's page says it is (an ant walk, a
particle or individual decoded and costed, a motion check of OMPL, a node
expansion of an exact search); the harness stores the count of every run.
The experiments are named ``<rerun name>.equal-evaluations`` (the proposed
method) and ``...equal-evaluations.<scenario key>`` (the rivals), apart from
the plain rerun's in one database.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING

import pandas as pd

from pathzoo.analysis.reproduction.paper_data import PaperData
from pathzoo.analysis.reproduction.runs import (
    RerunOptions,
    experiment_name,
    paper_budget,
    planner_groups,
    run_labelled,
    selected_scenarios,
)

if TYPE_CHECKING:
    from pathzoo.harness.experiment import Experiment

__all__ = ["EQUAL_CHOICES", "equal_sentence", "reference_evaluations", "run_paper_equal_evaluations"]

EQUAL_CHOICES = ("evaluations",)
"""What ``--equal`` can make equal."""

_SUFFIX = ".equal-evaluations"


def reference_evaluations(runs: pd.DataFrame, scenario_ids: list[str]) -> dict[str, int]:
    """Per scenario id, the median evaluations of ``runs`` there, rounded down (at least 1)."""
    out = {}
    for sid in scenario_ids:
        values = pd.to_numeric(runs.loc[runs["scenario"] == sid, "evaluations"], errors="coerce").dropna()
        out[sid] = max(1, int(math.floor(float(values.median())))) if len(values) else 1
    return out


def _reference_experiment(paper: PaperData, seeds: int, iterations: int | None, ids: list[str],
                          db: str | Path | None) -> "Experiment":
    from pathzoo.core.budget import Budget
    from pathzoo.harness.experiment import Experiment

    groups = planner_groups(paper, iterations, keys=lambda p: p.key == paper.reference)
    ((variant, specs),) = groups.items()
    return Experiment.build(planners=specs, scenarios=[sid + variant for sid in ids], seeds=seeds,
                            budget=Budget(**paper_budget(paper, iterations)),
                            name=experiment_name(paper, seeds, iterations) + _SUFFIX, db=db)


def _rival_experiments(paper: PaperData, seeds: int, iterations: int | None, evaluations: dict[str, int],
                       keys: dict[str, str], db: str | Path | None) -> list["Experiment"]:
    from pathzoo.core.budget import Budget
    from pathzoo.harness.experiment import Experiment

    clocks = {k: v for k, v in paper_budget(paper, iterations).items() if k in ("cpu_s", "time_s")}
    groups = planner_groups(paper, iterations, keys=lambda p: p.key != paper.reference)
    name = experiment_name(paper, seeds, iterations) + _SUFFIX
    return [
        Experiment.build(planners=specs, scenarios=[sid + variant], seeds=seeds,
                         budget=Budget(evaluations=evaluations[sid], **clocks),
                         name=f"{name}.{keys[sid]}" + variant.replace("_", "."), db=db)
        for sid in evaluations
        for variant, specs in sorted(groups.items())
    ]


def run_paper_equal_evaluations(paper: PaperData,
                                options: RerunOptions) -> tuple[pd.DataFrame, list[str], dict[str, int]]:
    """Run (or resume) the paper's comparison at equal evaluations (see the module docstring).

    Returns
    -------
    runs : DataFrame
        The labelled runs of every experiment, as :func:`~pathzoo.analysis.reproduction.runs.run_paper` returns them.
    names : list of str
        The experiments' names, the proposed method's first.
    evaluations : dict
        Scenario id -> the evaluation budget every rival got there.
    """
    n = options.seeds if options.seeds is not None else paper.runs
    chosen = selected_scenarios(paper, options.scenarios)
    ids = list(chosen.values())
    keys = {sid: key for key, sid in chosen.items()}
    reference = _reference_experiment(paper, n, options.iterations, ids, options.db)
    frames = [run_labelled(paper, reference, options)]
    evaluations = reference_evaluations(frames[0], ids)
    rivals = _rival_experiments(paper, n, options.iterations, evaluations, keys, options.db)
    frames.extend(run_labelled(paper, exp, options) for exp in rivals)
    return pd.concat(frames, ignore_index=True), [reference.name, *(exp.name for exp in rivals)], evaluations


def equal_sentence(paper: PaperData, evaluations: dict[str, int]) -> str:
    """One sentence: which evaluation count every rival got on each scenario."""
    ref = next(p.label for p in paper.planners if p.key == paper.reference)
    per = ", ".join(f"{sid} {e:,}" for sid, e in evaluations.items())
    return (f"Equal evaluations: every rival got {ref}'s median evaluation count per scenario as its only count "
            f"budget ({per}).")

