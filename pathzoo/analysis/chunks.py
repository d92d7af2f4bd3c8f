"""A stored experiment's runs a chunk of whole scenarios at a time, each run named as in the whole experiment.

:func:`pathzoo.harness.store_scan.scenario_chunks` reads the runs of an
experiment in frames of whole scenarios. A configuration's name
(:func:`~pathzoo.analysis.frame.config_labels`) depends on every
configuration of the experiment, not only on those of one chunk, so
:func:`config_names` names them once from the experiment's distinct
configurations and :func:`named_chunks` writes that name into each chunk's
``label`` column: :func:`~pathzoo.analysis.frame.with_config` of a chunk
then gives every run the name it has in ``read_runs`` of the whole
experiment, and every statistic taken within a scenario equals the one of
the whole frame.
"""

from __future__ import annotations

from pathlib import Path
from typing import Iterator, Sequence

import pandas as pd

from pathzoo.analysis.frame import config_labels

__all__ = ["ConfigKey", "config_names", "named_chunks"]

ConfigKey = tuple[str, str, str]
"""``(planner, params_hash, stored label)`` of a configuration."""


def config_names(db: str | Path, experiment: str) -> dict[ConfigKey, str]:
    """Each configuration's name over the whole experiment, by :data:`ConfigKey`.

    Raises
    ------
    ResultsDatabaseError
        Missing or foreign file, or unknown experiment.
    """
    from pathzoo.harness.store_scan import configurations

    configs = configurations(db, experiment)
    names = config_labels(configs)
    return dict(zip(zip(configs["planner"], configs["params_hash"], configs["label"]), names))


def named_chunks(db: str | Path, experiment: str, metrics: Sequence[str], names: dict[ConfigKey, str], *,
                 chunk_runs: int = 20_000, columns: Sequence[str] = ()) -> Iterator[pd.DataFrame]:
    """:func:`~pathzoo.harness.store_scan.scenario_chunks` with ``label`` set to each run's name in ``names``.

    Parameters
    ----------
    db, experiment, metrics, chunk_runs, columns
        As for :func:`~pathzoo.harness.store_scan.scenario_chunks`.
    names : dict
        :func:`config_names` of the experiment.
    """
    from pathzoo.harness.store_scan import scenario_chunks

    for chunk in scenario_chunks(db, experiment, metrics, chunk_runs=chunk_runs, columns=columns):
        chunk["label"] = [names[k] for k in zip(chunk["planner"], chunk["params_hash"], chunk["label"])]
        yield chunk
