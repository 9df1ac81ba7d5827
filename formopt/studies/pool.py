"""A local process pool whose workers end with their run (studies.sweep's chunks, compare's
band): the workers ignore Ctrl-C (the run stops them), die with a killed parent, and are
terminated when the run ends, by an error or an interrupt as well."""

from __future__ import annotations

import contextlib
import multiprocessing
import os
import signal
import threading
import time

POOL_END_S = 5.0  # s: the most a run waits for its pool to end (`end`)
WATCH = 0.1  # s: how often a pool worker looks for its parent where the kernel does not tell it


@contextlib.contextmanager
def local_pool(workers: int):
    """A multiprocessing Pool of `workers` processes (the platform's start method: fork on
    Linux, so each inherits what the run built), closed when the block ends, then terminated
    (`end`) whichever way it ends."""
    pool = multiprocessing.Pool(workers, _worker_start, (os.getpid(),))
    try:
        yield pool
        pool.close()
    finally:  # Ctrl-C or an error: the workers end with the run
        end(pool)


def independent(tasks: list[tuple], workers: int, say) -> list:
    """[fn(args) for fn, args, name in tasks] on a local pool of `workers` processes (fork:
    each inherits what the run built, e.g. compare's NLPs; 1: in this process), `say(name)` as
    each ends; the results in the tasks' order. fn must be picklable (a module's function)."""
    results: list = [None] * len(tasks)
    if workers <= 1 or len(tasks) <= 1:
        for k, task in enumerate(tasks):
            results[k] = _numbered((k, task))[1]
            say(task[2])
        return results
    with local_pool(min(workers, len(tasks))) as pool:
        for k, result in pool.imap_unordered(_numbered, list(enumerate(tasks))):
            results[k] = result
            say(tasks[k][2])
    return results


def _numbered(item: tuple) -> tuple:
    """(k, fn(args)) of a numbered task (k, (fn, args, name))."""
    k, (fn, args, _) = item
    return k, fn(args)


def end(pool) -> None:
    """Terminate a process pool, waiting at most POOL_END_S: CPython's Pool.terminate can wait
    forever on the result queue's lock when it kills a worker that held it (seen once on a full
    disk, the workers dead and the main thread in terminate's join). A terminate still waiting
    then is left in a daemon thread, and the workers are killed here."""
    ender = threading.Thread(target=lambda: (pool.terminate(), pool.join()), daemon=True)
    ender.start()
    ender.join(POOL_END_S)
    if ender.is_alive():
        for worker in pool._pool:
            worker.kill()


def _worker_start(parent: int):
    """A pool worker ignores Ctrl-C (its run stops it) and ends when its run is killed:
    at once on Linux (the kernel sends SIGKILL when the parent dies, prctl PR_SET_PDEATHSIG),
    elsewhere within WATCH seconds (it polls its parent)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    try:
        import ctypes
        ctypes.CDLL(None, use_errno=True).prctl(1, signal.SIGKILL)  # 1 = PR_SET_PDEATHSIG
    except (OSError, AttributeError):  # not Linux: the watch below
        pass

    def watch():
        while os.getppid() == parent:
            time.sleep(WATCH)
        os._exit(1)

    threading.Thread(target=watch, daemon=True).start()
