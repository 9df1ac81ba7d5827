"""studies.pool: tasks started on a local process pool while the caller works on (compare's
strikes beside its nominal, then its band)."""

import os
import signal

import pytest

from formopt.studies import pool as pool_module
from formopt.studies.pool import Background, WorkerLost, local_pool, watched


def test_background_tasks_keep_their_order():
    """Tasks on two processes and in this one: results in the tasks' order, each told."""
    tasks = [(abs, -2, "a"), (abs, 3, "b"), (float, "4", "c")]
    for workers in (1, 2):
        told: list[str] = []
        with Background(workers) as pool:
            started = pool.start(tasks)
            assert pool.results(started, told.append) == [2, 3, 4.0]
        assert told == ["a", "b", "c"]


def test_held_tasks_start_behind_the_next():
    """Tasks started `later` go on the pool behind the next start's tasks, or when a result is
    asked: every result got, in each call's order."""
    for workers in (1, 2):
        with Background(workers) as pool:
            held = pool.start([(abs, -1, "")], later=True)
            assert held[0][0] is None  # not on the pool yet
            first = pool.start([(abs, -2, "")])
            assert pool.results(first, print) == [2] and pool.results(held, print) == [1]
            again = pool.start([(abs, -5, "")], later=True)
            assert pool.results(again, print) == [5]


def _die(code: int) -> int:
    """A task whose worker is killed while it runs (as the kernel's out-of-memory killer would)."""
    os.kill(os.getpid(), signal.SIGKILL)
    return code


def test_a_worker_killed_mid_task_is_an_error_not_a_hang(monkeypatch):
    """A worker that dies holding a task: WorkerLost within a second or so, where a plain
    Pool.get would wait forever (multiprocessing starts another worker and the task is lost);
    the sweep's chunks (imap_unordered) the same. (The pool's end then waits POOL_END_S for
    terminate, which the dead worker's lock can hold, before it kills the workers: shortened.)"""
    monkeypatch.setattr(pool_module, "POOL_END_S", 0.5)
    with Background(2) as pool:
        started = pool.start([(abs, -1, ""), (_die, 1, "")])
        with pytest.raises(WorkerLost, match="worker process ended"):
            pool.results(started, lambda text: None)
    with local_pool(2) as pool:
        got = pool.imap_unordered(_die, [1, 2])
        with pytest.raises(WorkerLost):
            watched(pool, got.next)
