"""The report's tuning section: best score against trial, parameter importance, and default against tuned.

``pathzoo tune`` keeps its Optuna trials in :func:`optuna_storage_path` beside
the results database, one study per planner named :func:`study_name`, and
its runs in the experiments ``<name>.tune`` (training) and ``<name>.test``.
:func:`add_tuning_section` adds the section to a report of either experiment
when those studies exist, and does nothing otherwise.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any, Iterable

import numpy as np
import pandas as pd

from pathzoo.analysis.formatting import render_table
from pathzoo.analysis.frame import with_config

if TYPE_CHECKING:
    import optuna

    from pathzoo.analysis.report_page import ReportPage

__all__ = [
    "TUNING_STAGES",
    "optuna_storage_path",
    "study_name",
    "load_studies",
    "best_so_far",
    "importance_table",
    "default_vs_tuned",
    "add_tuning_section",
]

TUNING_STAGES = ("tune", "test")
"""Suffixes of the two experiments of a tuning run: ``<name>.tune`` and ``<name>.test``."""


def optuna_storage_path(db: str | Path) -> Path:
    """The Optuna storage beside a results database: ``results.sqlite`` -> ``results.optuna.sqlite``."""
    db = Path(db)
    return db.with_name(f"{db.stem}.optuna.sqlite")


def study_name(experiment: str, planner: str) -> str:
    """The study of one planner of a tuning experiment: ``"<experiment>:<planner name>"``."""
    return f"{experiment}:{planner}"


def _base_name(experiment: str) -> str:
    for stage in TUNING_STAGES:
        if experiment.endswith("." + stage):
            return experiment[: -len(stage) - 1]
    return experiment


def load_studies(db: str | Path, experiment: str) -> dict[str, "optuna.Study"]:
    """The planner name -> Optuna study of the tuning run behind ``experiment`` (empty when there is none)."""
    path = optuna_storage_path(db)
    if not path.is_file():
        return {}
    import optuna

    optuna.logging.set_verbosity(optuna.logging.WARNING)
    storage = f"sqlite:///{path.resolve()}"
    prefix = study_name(_base_name(experiment), "")
    return {
        s.study_name[len(prefix):]: optuna.load_study(study_name=s.study_name, storage=storage)
        for s in optuna.get_all_study_summaries(storage)
        if s.study_name.startswith(prefix)
    }


def best_so_far(study: "optuna.Study") -> pd.DataFrame:
    """Completed trials in order: ``trial`` (1-based), ``score`` and ``best`` (running minimum)."""
    from optuna.trial import TrialState

    done = sorted(study.get_trials(deepcopy=False, states=(TrialState.COMPLETE,)), key=lambda t: t.number)
    scores = np.array([t.value for t in done], dtype=np.float64)
    return pd.DataFrame({"trial": np.arange(1, len(done) + 1), "score": scores,
                         "best": np.minimum.accumulate(scores) if len(scores) else scores})


def importance_table(studies: dict[str, "optuna.Study"]) -> tuple[pd.DataFrame, list[str]]:
    """Optuna's parameter importance (PED-ANOVA, which needs no scikit-learn) per planner, and notes for planners where it is undefined."""
    import optuna

    rows, notes = [], []
    for name, study in sorted(studies.items()):
        try:
            imp = optuna.importance.get_param_importances(study, evaluator=optuna.importance.PedAnovaImportanceEvaluator())
        except (RuntimeError, ValueError, ImportError) as exc:
            notes.append(f"{name}: no importance ({' '.join(str(exc).split())[:120]})")
            continue
        if not imp:
            notes.append(f"{name}: no importance (nothing varied between trials)")
        rows += [{"planner": name, "parameter": p, "importance": f"{v:.3f}"} for p, v in imp.items()]
    return pd.DataFrame(rows, columns=["planner", "parameter", "importance"]), notes


def default_vs_tuned(runs: pd.DataFrame | Iterable[pd.DataFrame], metric: str, alpha: float) -> pd.DataFrame:
    """Per planner and test scenario: ``<name> default`` against ``<name> tuned`` (pairwise_tests, Holm per scenario).

    ``runs`` is one runs frame, or frames of disjoint sets of whole scenarios
    whose runs are named as in the whole experiment
    (:func:`pathzoo.analysis.chunks.named_chunks`); rows are ordered by the
    default configuration, then by scenario.
    """
    from pathzoo.analysis.stats import pairwise_tests

    parts = []
    for chunk in [runs] if isinstance(runs, pd.DataFrame) else runs:
        config = with_config(chunk)["config"]
        configs = set(config)
        for default in sorted(c for c in configs if c.endswith(" default")):
            tuned = default[: -len(" default")] + " tuned"
            if tuned not in configs:
                continue
            sub = chunk[config.isin([default, tuned]).to_numpy()]
            parts.append(pairwise_tests(sub, metric, reference=default, alpha=alpha))
    cols = ["scenario", "a", "b", "n_a", "n_b", "test", "p_holm", "a12", "magnitude", "winner"]
    if not parts:
        return pd.DataFrame(columns=cols)
    out = pd.concat(parts, ignore_index=True)[cols]
    return out.sort_values(["a", "scenario"], kind="stable").reset_index(drop=True)


def _plot_best(studies: dict[str, "optuna.Study"]) -> Any:
    from matplotlib.ticker import MaxNLocator

    from pathzoo.plotting.figure import legend_below, new_figure, planner_colors

    fig = new_figure((6.0, 4.2))
    ax = fig.subplots()
    colors = planner_colors(studies)
    for name, study in sorted(studies.items()):
        curve = best_so_far(study)
        ax.step(curve["trial"], curve["best"], where="post", color=colors[name], label=name)
        ax.plot(curve["trial"], curve["score"], "o", ms=3, alpha=0.5, color=colors[name])
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))
    ax.set_xlabel("trial")
    ax.set_ylabel("training score (lower is better)")
    legend_below(ax)
    return fig


def add_tuning_section(page: "ReportPage", db: str | Path, experiment: str,
                       runs: pd.DataFrame | Iterable[pd.DataFrame], *, metric: str, alpha: float) -> None:
    """Append the tuning section to ``page`` when ``experiment`` comes from ``pathzoo tune``.

    ``runs`` is the experiment's runs frame, or its frames of whole scenarios
    (as for :func:`default_vs_tuned`; an iterator is read only for a test experiment).
    """
    studies = load_studies(db, experiment)
    if not studies:
        return
    page.heading(2, "Tuning", "tuning")
    page.note("Every planner got the same number of seeded TPE trials on the training scenarios; a trial's score "
              "is the mean over training scenarios of the median length ratio, failed runs counting as worst "
              "(docs/tuning.md).")
    page.figure(_plot_best(studies), "tuning-best",
                "Best training score so far against trial, per planner (dots: each trial's score).")
    table, notes = importance_table(studies)
    if len(table):
        page.table(render_table(table, "html", title="Parameter importance (Optuna, PED-ANOVA)"))
    for text in notes:
        page.note(text)
    if experiment.endswith(".test"):
        tests = default_vs_tuned(runs, metric, alpha)
        if len(tests):
            shown = tests.astype(str)
            shown["p_holm"] = [f"{p:.3g}" for p in tests["p_holm"]]
            shown["a12"] = [f"{a:.2f}" for a in tests["a12"]]
            page.table(render_table(shown, "html", title=f"Default (a) against tuned (b) on the test scenarios, "
                                    f"{metric}; A12 = P(a beats b), winner at α = {alpha:g}"))
