"""The ``[cluster]`` table and ``--cluster-*`` options: checked with one-line errors; the job script they make."""

from __future__ import annotations

import signal

import pytest

from pathzoo.cli.main import main
from pathzoo.core.errors import InvalidExperimentError
from pathzoo.harness.executors import ClusterOptions
from pathzoo.harness.executors.jobqueue import job_prologue

EXPERIMENT = """
[experiment]
seeds = 1
budget = { iterations = 5 }
scenarios = ["gant.fig7"]

[[planner]]
id = "exact.astar"
"""


def test_a_table_is_read_and_options_override_it():
    options = ClusterOptions.from_mapping({"queue": "short", "cores": 4, "memory": "8GB", "walltime": "02:00:00",
                                           "jobs": 3, "prologue": ["module load python"]}, "e.toml")
    assert (options.queue, options.cores, options.jobs, options.prologue) == ("short", 4, 3, ("module load python",))
    options = options.updated({"cores": 2, "queue": None})
    assert (options.queue, options.cores) == ("short", 2)
    assert ClusterOptions().value("cores") == 1 and ClusterOptions().value("memory", "16GB") == "16GB"


@pytest.mark.parametrize("table, message", [
    ({"cores": 0}, "field 'cluster.cores': must be a positive integer, got 0"),
    ({"cores": True}, "field 'cluster.cores': must be a positive integer"),
    ({"memory": "lots"}, "field 'cluster.memory': must be an amount"),
    ({"walltime": "2 hours"}, "field 'cluster.walltime': must be a time"),
    ({"prologue": [1]}, "field 'cluster.prologue': must be a list of shell lines"),
    ({"nodes": 2}, "unknown key(s) ['nodes']"),
    ([], "field 'cluster': must be a table"),
])
def test_bad_values_are_named(table, message):
    with pytest.raises(InvalidExperimentError) as info:
        ClusterOptions.from_mapping(table, "e.toml")
    assert str(info.value).startswith("e.toml: ") and message in str(info.value)


def test_the_job_exports_what_the_harness_needs_before_the_users_lines(monkeypatch):
    monkeypatch.setenv("NUMBA_CACHE_DIR", "/scratch/it's numba")
    monkeypatch.delenv("SLURM_CONF", raising=False)
    lines = job_prologue(ClusterOptions(prologue=("module load python",)))
    assert lines == ["export DASK_DISTRIBUTED__WORKER__DAEMON=False",
                     "export NUMBA_CACHE_DIR='/scratch/it'\"'\"'s numba'", "module load python"]


def test_importing_dask_jobqueue_keeps_ctrl_c(monkeypatch):
    """dask_jobqueue.runner sets a SIGINT handler that calls sys.exit() when imported: the executor undoes it."""
    pytest.importorskip("dask_jobqueue")
    import sys

    from pathzoo.harness.executors.jobqueue import _import_jobqueue

    for name in [m for m in sys.modules if m.startswith("dask_jobqueue")]:
        monkeypatch.delitem(sys.modules, name)
    before = signal.getsignal(signal.SIGINT)
    _import_jobqueue()
    assert signal.getsignal(signal.SIGINT) is before
    assert "dask_jobqueue.runner" in sys.modules  # the import that changes the handler did happen


def test_command_line_errors_are_one_line(tmp_path, capsys):
    path = tmp_path / "e.toml"
    path.write_text(EXPERIMENT + '\n[cluster]\nmemory = "lots"\n')
    assert main(["run", str(path), "--executor", "slurm", "--db", str(tmp_path / "r.sqlite")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and f"{path}: field 'cluster.memory': must be an amount" in err, err
    assert main(["run", str(path), "--cluster-cores", "2", "--db", str(tmp_path / "r.sqlite")]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--cluster-cores need(s) --executor slurm, pbs or sge" in err, err
    assert not (tmp_path / "r.sqlite").exists()


def test_the_table_is_no_part_of_the_experiment(tmp_path, capsys):
    """Other executors run a file with a [cluster] table as they run it without (its runs keep their keys)."""
    path = tmp_path / "e.toml"
    path.write_text(EXPERIMENT + '\n[cluster]\ncores = 2\n')
    assert main(["run", str(path), "--executor", "inline", "--no-progress", "--db", str(tmp_path / "r.sqlite")]) == 0
    assert "1 runs stored" in capsys.readouterr().err
