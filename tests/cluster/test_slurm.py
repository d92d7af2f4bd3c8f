"""``pathzoo run --executor slurm`` on a real single-node SLURM: the same results as the local executor, no job left.

The cluster comes from ``shared/tools/slurm-single-node`` beside the
repository (CI lays ``shared/`` next to its clone; a developer's work tree
may sit deeper, so the repository's ancestors are searched). It needs root
and installs ``slurm-wlm`` and ``munge`` when missing; where it cannot start
the tests are skipped with its reason.
"""

from __future__ import annotations

import logging
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from pathzoo.analysis.repeatability import compare_results
from pathzoo.cli.main import main
from pathzoo.core.errors import PathzooError
from pathzoo.harness.executors import ClusterOptions, jobqueue_executor

pytest.importorskip("dask_jobqueue")

pytestmark = pytest.mark.slow

REPO = Path(__file__).resolve().parents[2]
TOOL = Path("shared") / "tools" / "slurm-single-node"

EXPERIMENT = """
[experiment]
name = "small"
seeds = 2
budget = { iterations = 20 }
timeout_s = 120
scenarios = ["gant.fig7", "movingai.random-32-32-20.b10.13"]

[[planner]]
id = "exact.astar"

[[planner]]
id = "aco.as"
params = { n_ants = 10 }

[cluster]
cores = 2
memory = "1GB"
walltime = "00:10:00"
"""


def _tool() -> Path | None:
    for folder in REPO.parents:
        if (folder / TOOL).is_file():
            return folder / TOOL
    return None


@pytest.fixture(scope="module")
def slurm(tmp_path_factory) -> str:
    """The ``SLURM_CONF`` of a running SLURM: the one of the environment (``.ci/run`` starts one), else started."""
    given = os.environ.get("SLURM_CONF")
    if given and shutil.which("sinfo") and not subprocess.run(["sinfo", "-h"], capture_output=True,
                                                              timeout=30).returncode:
        yield given
        return
    tool = _tool()
    if tool is None:
        pytest.skip(f"no {TOOL} beside the repository (CI lays shared/ next to its clone)")
    if os.geteuid() != 0:
        pytest.skip("the single-node SLURM needs root (it starts munged, slurmctld and slurmd)")
    if shutil.which("bash") is None:
        pytest.skip("no bash to run the SLURM tool")
    folder = tmp_path_factory.mktemp("slurm")
    done = subprocess.run(["bash", str(tool), "start", str(folder)], capture_output=True, text=True, timeout=900)
    if done.returncode != 0:
        pytest.skip(f"SLURM could not start: {(done.stderr or done.stdout).strip().splitlines()[-1:]}")
    conf = next(line.split("=", 1)[1] for line in done.stdout.splitlines() if line.startswith("export SLURM_CONF="))
    yield conf
    subprocess.run(["bash", str(tool), "stop", str(folder)], capture_output=True, timeout=60)


def _our_jobs(conf: str, folder: Path) -> list[str]:
    """The pathzoo jobs in ``squeue`` submitted from ``folder`` (each test's own: tests may run side by side)."""
    out = subprocess.run(["squeue", "-h", "-n", "pathzoo", "-o", "%i %T %Z"], capture_output=True, text=True,
                         env={**os.environ, "SLURM_CONF": conf}, timeout=30)
    if out.returncode != 0:
        return [f"squeue failed: {out.stderr}"]
    return [line for line in out.stdout.splitlines() if line.split(" ", 2)[-1] == str(folder)]


def _no_job_left(conf: str, folder: Path, within_s: float = 30.0) -> list[str]:
    """The jobs of :func:`_our_jobs` still in ``squeue`` after ``within_s`` (cancelled jobs leave within seconds)."""
    deadline = time.monotonic() + within_s
    while (jobs := _our_jobs(conf, folder)) and time.monotonic() < deadline:
        time.sleep(1.0)
    return jobs


def test_slurm_stores_what_the_local_executor_stores_and_leaves_no_job(slurm, tmp_path, monkeypatch, capsys, caplog):
    monkeypatch.setenv("SLURM_CONF", slurm)
    monkeypatch.chdir(tmp_path)
    (tmp_path / "small.toml").write_text(EXPERIMENT)
    with caplog.at_level(logging.WARNING, logger="pathzoo.harness"):
        assert main(["run", "small.toml", "--db", "slurm.sqlite", "--executor", "slurm", "--no-progress"]) == 0
    said = [r.getMessage() for r in caplog.records if r.name == "pathzoo.harness"]
    assert "pathzoo: 1 slurm job(s) of 2 core(s) requested; their output goes to pathzoo-jobs/" in said, said
    assert "8 runs stored in slurm.sqlite" in capsys.readouterr().err
    assert main(["run", "small.toml", "--db", "local.sqlite", "--jobs", "2", "--no-progress"]) == 0
    comparison = compare_results(tmp_path / "local.sqlite", tmp_path / "slurm.sqlite")
    assert comparison.identical and comparison.n_runs == 8, comparison.summary()
    assert _no_job_left(slurm, tmp_path) == []
    assert list((tmp_path / "pathzoo-jobs").glob("*.err"))  # the job's output is where the docs say


def test_jobs_are_cancelled_when_no_worker_comes(slurm, tmp_path, monkeypatch):
    """A job whose worker never starts (its prologue sleeps): the wait ends in an error, and the job is cancelled."""
    monkeypatch.setenv("SLURM_CONF", slurm)
    monkeypatch.chdir(tmp_path)
    executor = jobqueue_executor("slurm", ClusterOptions(memory="500MB", prologue=("sleep 600",), wait_s=15.0))
    try:
        deadline = time.monotonic() + 60
        while not _our_jobs(slurm, tmp_path) and time.monotonic() < deadline:
            time.sleep(0.5)
        assert _our_jobs(slurm, tmp_path), "the job was never submitted"
        with pytest.raises(PathzooError, match="no slurm job started a Dask worker within 15 s"):
            executor.prepare([])
    finally:
        executor.shutdown()
    assert _no_job_left(slurm, tmp_path) == []


def test_ctrl_c_cancels_the_jobs(slurm, tmp_path):
    """Ctrl-C while waiting for the workers: the usual one-line 'interrupted' (dask-jobqueue's handler undone)."""
    (tmp_path / "small.toml").write_text(EXPERIMENT)
    proc = subprocess.Popen(
        [sys.executable, "-m", "pathzoo.cli.main", "run", "small.toml", "--executor", "slurm", "--no-progress",
         "--cluster-prologue", "sleep 600"],
        cwd=tmp_path, env={**os.environ, "SLURM_CONF": slurm}, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 120
        while not _our_jobs(slurm, tmp_path) and time.monotonic() < deadline and proc.poll() is None:
            time.sleep(0.5)
        assert _our_jobs(slurm, tmp_path), "the job was never submitted"
        time.sleep(2.0)
        proc.send_signal(signal.SIGINT)
        _, err = proc.communicate(timeout=60)
    finally:
        if proc.poll() is None:
            proc.kill()
    assert proc.returncode == 2 and "interrupted" in err.splitlines()[-1], err
    assert _no_job_left(slurm, tmp_path) == []


def test_a_refused_job_is_one_line(slurm, tmp_path, monkeypatch, capsys):
    """sbatch refuses the partition: its own error, in one line, at once (not a traceback and an endless wait)."""
    monkeypatch.setenv("SLURM_CONF", slurm)
    monkeypatch.chdir(tmp_path)
    (tmp_path / "small.toml").write_text(EXPERIMENT)
    started = time.monotonic()
    assert main(["run", "small.toml", "--executor", "slurm", "--cluster-queue", "no-such-partition"]) == 2
    err = capsys.readouterr().err
    assert err.splitlines()[-1] == ("pathzoo: error: the slurm job was refused: "
                                    "sbatch: error: invalid partition specified: no-such-partition"), err
    assert time.monotonic() - started < 60 and _no_job_left(slurm, tmp_path) == []
