"""Harnesses that open one new result database at the same moment all get a working database."""

from __future__ import annotations

import multiprocessing as mp

from pathzoo.harness.store import SCHEMA_VERSION, ResultStore


def _open(path: str, barrier, errors) -> None:
    try:
        barrier.wait(timeout=60)
        with ResultStore(path) as store:
            store.conn.execute("SELECT count(*) FROM runs").fetchone()
    except Exception as exc:  # noqa: BLE001 - reported to the test
        errors.put(f"{type(exc).__name__}: {exc}")


def test_processes_creating_one_database_together_do_not_clash(tmp_path):
    ctx = mp.get_context("fork")
    errors = ctx.Queue()
    n_procs, tries = 6, 12
    for i in range(tries):
        path = str(tmp_path / f"race{i}.sqlite")
        barrier = ctx.Barrier(n_procs)
        procs = [ctx.Process(target=_open, args=(path, barrier, errors)) for _ in range(n_procs)]
        for p in procs:
            p.start()
        for p in procs:
            p.join(120)
        assert all(p.exitcode == 0 for p in procs)
        with ResultStore(path) as store:
            assert store.conn.execute("SELECT version FROM pathzoo_schema").fetchall() == [(SCHEMA_VERSION,)]
    found = []
    while not errors.empty():
        found.append(errors.get())
    assert found == []
