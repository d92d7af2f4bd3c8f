"""Fair tuning: every planner gets the same Optuna budget on training scenarios, then default and tuned are compared on test scenarios.

Read a tuning experiment file with :func:`load_tuning` and run it with
:func:`tune` (``pathzoo tune`` on the command line); docs/tuning.md explains
the protocol.
"""

from pathzoo.tuning.objective import WORST_RATIO, trial_score
from pathzoo.tuning.setup import DEFAULT_TRIALS, TuningSetup, load_tuning
from pathzoo.tuning.space import SearchRange, default_space, parse_space
from pathzoo.analysis.tuning_report import optuna_storage_path, study_name
from pathzoo.tuning.tuner import PlannerTuning, TuningResult, tune

__all__ = [
    "DEFAULT_TRIALS",
    "PlannerTuning",
    "SearchRange",
    "TuningResult",
    "TuningSetup",
    "WORST_RATIO",
    "default_space",
    "load_tuning",
    "optuna_storage_path",
    "parse_space",
    "study_name",
    "trial_score",
    "tune",
]
