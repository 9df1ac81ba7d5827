"""A local process pool whose workers end with their run (studies.sweep's chunks; `Background`:
compare's stride section, its other strikes, first sweep, forward checks and band on one pool):
the workers ignore Ctrl-C (the run stops them), die with a killed parent, and are terminated
when the run ends, by an error or an interrupt as well; a worker that dies while the run waits
for it (killed, out of memory) is an error (`WorkerLost`), not a run that waits forever."""

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
    pool.formopt_workers = _pids(pool)  # type: ignore[attr-defined]  # `watched`: the workers it began with
    try:
        yield pool
        pool.close()
    finally:  # Ctrl-C or an error: the workers end with the run
        end(pool)


class WorkerLost(RuntimeError):
    """A pool worker ended while the run waited for a result (killed, or out of memory)."""


def watched(pool, get):
    """get(timeout)'s result, a pool's (AsyncResult.get, IMapIterator.next), waited for in
    WATCH-second steps; WorkerLost where one of the workers local_pool began with has ended:
    multiprocessing's Pool starts another in its place, but the task the dead one held never
    returns, and a plain get() would wait for it forever."""
    while True:
        try:
            return get(WATCH)
        except multiprocessing.TimeoutError:
            if not _pids(pool) <= pool.formopt_workers or any(w.exitcode is not None for w in pool._pool):
                raise WorkerLost("a worker process ended while it worked (killed, or out of memory: "
                                 "the system's log says which); its task is lost, so the run stops") from None


def _pids(pool) -> frozenset[int]:
    """The process ids of a Pool's workers now."""
    return frozenset(w.pid for w in pool._pool)


class Background:
    """Independent tasks (fn, args, name) started on a local pool of `workers` processes as soon
    as they are `start`ed (or held `later`), while this process works on (fork: each worker
    inherits what the run built when the pool started; 1 worker: each task runs here when its
    result is asked); `results` waits for them, in their order, `say(name)` as each is got. fn
    must be picklable (a module's function). Use as a context manager: the pool ends with the
    block (local_pool)."""

    def __init__(self, workers: int):
        self.workers, self.pool, self._stack = workers, None, contextlib.ExitStack()
        self._held: list[list] = []  # started `later`, not yet on the pool

    def __enter__(self) -> Background:
        if self.workers > 1:
            self.pool = self._stack.enter_context(local_pool(self.workers))
        return self

    def __exit__(self, *exc) -> None:
        self._stack.__exit__(*exc)

    def start(self, tasks: list[tuple], later: bool = False) -> list[list]:
        """The tasks started (on the pool; here, their handles only), longest first where the
        caller orders them so; `later`: held, and started behind the next call's tasks (or when
        a result is asked), to fill the pool once what the caller waits for is started."""
        started = [[None, task] for task in tasks]
        if later:
            self._held += started
        else:
            self._submit(started + self._held)
            self._held = []
        return started

    def _submit(self, started: list[list]) -> None:
        """Each started task put on the pool (none: it runs here when its result is asked)."""
        if self.pool is not None:
            for handle in started:
                handle[0] = self.pool.apply_async(handle[1][0], (handle[1][1],))

    def results(self, started: list[list], say) -> list:
        """[fn(args) for each started task], in their order, `say(name)` as each is got (a task
        named "" is not told: a part of a stage); tasks still held are started first."""
        self.start([])
        out = []
        for handle, (fn, args, name) in started:
            out.append(fn(args) if handle is None else watched(self.pool, handle.get))
            if name:
                say(name)
        return out


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
