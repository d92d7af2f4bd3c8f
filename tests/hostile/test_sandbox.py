"""Attacks through the operating system (``sandbox_hostile``): the rival's stored result stays that of a clean run.

Each test runs ``exact.astar`` (the rival) beside a hostile planner and
compares the rival's stored rows with those of a run without it; the hostile
runs are stored as invalid, crashed or timed out. The experiments use the
process executor with the OS sandbox (bubblewrap and cgroups v1,
``docs/sandbox.md``), except where a test says otherwise.
"""

from __future__ import annotations

import socket
import sqlite3
import subprocess
import sys
import textwrap
from pathlib import Path

import psutil
import pytest

import sandbox_hostile
from harness_support import experiment, hostile  # noqa: F401 - fixture
from pathzoo.harness import read_runs, run_experiment
from pathzoo.harness.executors import ProcessExecutor
from pathzoo.harness.sandbox import SandboxLimits, SandboxUnavailableError, sandbox_problem
from pathzoo.harness.store import ResultStore
from pathzoo.plugins.manager import get_registry

pytestmark = pytest.mark.skipif(bool(sandbox_problem()), reason=f"no OS sandbox here: {sandbox_problem()}")

RIVAL = "exact.astar"
_COMPARED = ["status", "valid", "invalid_reason", "iterations", "evaluations", "length"]


@pytest.fixture()
def attackers(hostile):  # noqa: F811 - the fixture of harness_support, which also provides hostile.wall
    registry = get_registry()
    if registry.pm.get_plugin("sandbox-hostile") is None:
        registry.add_plugin(sandbox_hostile, "sandbox-hostile")
    yield sandbox_hostile


def _run(planners: list, tmp_path: Path, name: str, *, jobs: int = 1, seeds: int = 2, **kw: object):
    exp = experiment(planners, ["hostile.wall"], seeds=seeds, name=name)
    return run_experiment(exp, db=tmp_path / f"{name}.sqlite", executor=ProcessExecutor(jobs, **kw), progress=False)


def _rival(runs):
    rows = runs[runs.planner == RIVAL].sort_values("run_key")
    return rows[["run_key", *_COMPARED]].reset_index(drop=True)


def _assert_rival_clean(tmp_path: Path, attacked, seeds: int = 2) -> None:
    clean = _run([RIVAL], tmp_path, "clean", seeds=seeds)
    assert (clean.status == "solved").all()
    assert _rival(attacked).equals(_rival(clean))


def _grandchildren() -> list[int]:
    mark = sandbox_hostile.GRANDCHILD_ARG
    return [p.pid for p in psutil.process_iter(["cmdline"]) if mark in (p.info["cmdline"] or [])]


def _hostile_rows(runs):
    return runs[runs.planner != RIVAL]


def test_planner_module_is_imported_in_its_worker_only(hostile, tmp_path):  # noqa: F811
    import sandbox_lazy_declaration

    from pathzoo.harness import runner

    store = runner._store
    get_registry().add_plugin(sandbox_lazy_declaration, "sandbox-lazy-declaration")
    runs = _run(["sandbox.import_time", RIVAL], tmp_path, "attacked")
    assert "sandbox_import_payload" not in sys.modules and runner._store is store
    assert set(_hostile_rows(runs).status) == {"invalid"}
    _assert_rival_clean(tmp_path, runs)


def test_store_rewritten_through_open_files_or_its_path(attackers, tmp_path):
    db = tmp_path / "attacked.sqlite"
    runs = _run([("sandbox.store", {"db": str(db)}), RIVAL], tmp_path, "attacked", jobs=2)
    assert set(_hostile_rows(runs).status) == {"invalid"}  # its straight path crosses the wall
    assert set(_hostile_rows(runs).message) == {"wrote to 0 database(s)"}
    assert (runs.sandboxed).all()
    _assert_rival_clean(tmp_path, runs)


def test_replaced_scenario_cache_and_recursion_limit_stay_in_their_process(attackers, tmp_path):
    runs = _run(["sandbox.scenario_cache", "sandbox.recursion", RIVAL], tmp_path, "attacked", jobs=1)
    assert set(_hostile_rows(runs).status) == {"invalid"}
    _assert_rival_clean(tmp_path, runs)


def test_killing_other_workers_and_the_judge_reaches_nothing(attackers, tmp_path):
    runs = _run(["sandbox.kill_workers", RIVAL], tmp_path, "attacked", jobs=2, seeds=3)
    assert set(_hostile_rows(runs).message) == {"killed 0"}
    assert set(_hostile_rows(runs).status) == {"invalid"}
    _assert_rival_clean(tmp_path, runs, seeds=3)


def test_a_grandchild_does_not_outlive_its_run(attackers, tmp_path):
    runs = _run(["sandbox.grandchild", RIVAL], tmp_path, "attacked", jobs=1)
    assert _grandchildren() == []
    assert set(_hostile_rows(runs).status) == {"invalid"}
    _assert_rival_clean(tmp_path, runs)


def test_numba_cache_of_the_package_is_not_writable(attackers, tmp_path):
    for path in sandbox_hostile.numba_index_files():
        path.unlink(missing_ok=True)
    runs = _run(["sandbox.poison_cache"], tmp_path, "attacked", seeds=1)
    assert list(runs.message) == ["wrote 0"]
    assert not any(path.exists() for path in sandbox_hostile.numba_index_files())


def test_no_network(attackers, tmp_path):
    server = socket.create_server(("127.0.0.1", 0))
    server.settimeout(0.0)
    port = server.getsockname()[1]
    try:
        runs = _run([("sandbox.network", {"port": port})], tmp_path, "attacked", seeds=1)
        with pytest.raises(BlockingIOError):
            server.accept()
    finally:
        server.close()
    assert list(runs.message) == ["no connection (ConnectionRefusedError)"]


def test_cpu_time_of_children_is_counted(attackers, tmp_path):
    runs = _run([("sandbox.spin", {"seconds": 0.5})], tmp_path, "attacked", seeds=1)
    assert runs.cpu_time_s.iloc[0] >= 0.45  # the child's CPU time: the planner itself only waited


def test_memory_and_process_limits(attackers, tmp_path):
    # each limit on its own: 64 forked interpreters touch enough copy-on-write pages to come near 200 MiB
    memory = _run([("sandbox.hog", {"mib": 400})], tmp_path, "memory", seeds=1,
                  limits=SandboxLimits(memory_bytes=200 << 20, max_tasks=64)).iloc[0]
    forks = _run([("sandbox.hog", {"children": 200}, "forks")], tmp_path, "forks", seeds=1,
                 limits=SandboxLimits(memory_bytes=2 << 30, max_tasks=64)).iloc[0]
    assert memory.status == "crash" and "out of memory" in memory.message
    started = int(forks.message.split(", ")[1].split()[0])
    assert forks.status == "invalid" and started < 64
    assert not [p for p in psutil.process_iter(["cmdline"]) if "sandbox.hog" in " ".join(p.info["cmdline"] or [])]


def test_the_scratch_directory_is_bounded(attackers, tmp_path):
    run = _run([("sandbox.hog", {"disk_mib": 80})], tmp_path, "disk", seeds=1,
               limits=SandboxLimits(scratch_bytes=32 << 20)).iloc[0]
    assert run.status == "invalid" and run.message.startswith("wrote 3") and "No space left" in run.message


def test_killing_the_harness_and_its_parent_reaches_nothing(tmp_path):
    db = tmp_path / "attacked.sqlite"
    script = textwrap.dedent(f"""
        import sys
        sys.path.insert(0, {str(Path(__file__).parent)!r})
        import harness_hostile, sandbox_hostile
        from harness_support import experiment
        from pathzoo.harness import run_experiment
        from pathzoo.plugins.manager import get_registry
        registry = get_registry()
        registry.add_plugin(harness_hostile, "hostile-harness-test")
        registry.add_plugin(sandbox_hostile, "sandbox-hostile")
        exp = experiment(["sandbox.kill_harness", "exact.astar"], ["hostile.wall"], seeds=2, name="attacked")
        run_experiment(exp, db={str(db)!r}, jobs=2, progress=False)
    """)
    done = subprocess.run([sys.executable, "-c", script, sandbox_hostile.HARNESS_MARKER], capture_output=True,
                          text=True, timeout=600)
    assert done.returncode == 0, done.stderr[-2000:]
    runs = read_runs(db, "attacked")
    assert len(runs) == 4
    assert set(_hostile_rows(runs).status) <= {"invalid", "crash"}  # a run's parent is its own worker: killing it
    assert set(_rival(runs).status) == {"solved"}  # crashes that run only


def test_require_sandbox_refuses_an_unsandboxed_executor(hostile, tmp_path):  # noqa: F811
    exp = experiment([RIVAL], ["hostile.wall"], seeds=1)
    with pytest.raises(SandboxUnavailableError, match="inline"):
        run_experiment(exp, db=tmp_path / "r.sqlite", executor="inline", progress=False, require_sandbox=True)
    with ProcessExecutor(1, sandbox=False) as pool, pytest.raises(SandboxUnavailableError, match="switched off"):
        run_experiment(exp, db=tmp_path / "r.sqlite", executor=pool, progress=False, require_sandbox=True)
    assert not read_runs(tmp_path / "r.sqlite").shape[0]


def test_unsandboxed_runs_are_stored_as_such_and_old_files_gain_the_column(hostile, tmp_path):  # noqa: F811
    db = tmp_path / "r.sqlite"
    run_experiment(experiment([RIVAL], ["hostile.wall"], seeds=1), db=db, executor="inline", progress=False)
    with sqlite3.connect(db) as conn:  # a file written before the column existed
        conn.execute("ALTER TABLE runs DROP COLUMN sandboxed")
    assert list(read_runs(db).sandboxed) == [False]  # readable as it is
    with ResultStore(db):
        pass
    with sqlite3.connect(db) as conn:
        assert conn.execute("SELECT sandboxed FROM runs").fetchall() == [(0,)]


def test_workers_run_one_configuration_each(attackers, tmp_path):
    with ProcessExecutor(1) as pool:
        tasks = experiment(["sandbox.recursion", RIVAL], ["hostile.wall"], seeds=1).tasks()
        outcomes = [pool.submit(task).result() for task in tasks]
        assert [o.sandboxed for o in outcomes] == [True, True]
        configs = [w.config for w in pool._workers]  # the first one's worker is kept idle, never reused
        assert len(configs) == len(set(configs)) == 2 and None not in configs


def test_dask_runs_planners_in_the_sandbox_too(attackers, tmp_path):
    pytest.importorskip("distributed")
    from pathzoo.harness.executors import dask_executor

    exp = experiment(["sandbox.grandchild", RIVAL], ["hostile.wall"], seeds=2, name="attacked")
    runs = run_experiment(exp, db=tmp_path / "attacked.sqlite", executor=dask_executor(jobs=1, processes=False),
                          progress=False)
    assert runs.sandboxed.all()
    assert _grandchildren() == []
    assert set(_hostile_rows(runs).status) == {"invalid"}
    _assert_rival_clean(tmp_path, runs)


def test_a_harness_in_a_venv_under_a_hidden_directory_describes_its_planners(tmp_path):
    """CI's venv lives under /tmp, which the sandbox hides: its Python must still start with its site-packages."""
    venv = tmp_path / "venv"  # pytest's tmp_path is under the temporary directory, hidden in the sandbox
    subprocess.run([sys.executable, "-m", "venv", "--without-pip", str(venv)], check=True)
    site = next((venv / "lib").glob("python*/site-packages"))
    import site as this_site  # the new venv sees this environment's packages (editable installs included)

    dirs = [p for p in this_site.getsitepackages() if Path(p).is_dir()]
    (site / "here.pth").write_text(f"import site; list(map(site.addsitedir, {dirs!r}))\n")
    script = ("from pathzoo.harness.planner_info import describe\n"
              "print(describe([('exact.astar', {})])[0].version)\n")
    done = subprocess.run([str(venv / "bin" / "python"), "-c", script], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    assert done.stdout.strip() == get_registry().get("planners", "exact.astar").obj.version
