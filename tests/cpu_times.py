"""`pytest --cpu-times` (with or without -n): the CPU seconds of each test file, printed slowest
first at the end, beside its wall seconds and the worker that ran it.

A test's CPU is its process's own and its waited-for children's (subprocesses, pools, kernels)
over its setup, call and teardown; a child reaped late (a pool ended by the garbage collector)
counts in the test that reaps it. A loaded machine stretches the wall time far more than the CPU
time: compare CPU between runs. (The suite on two workers is bounded by each worker's wall sum.)
"""

from __future__ import annotations

import collections
import os
import resource
import time

import pytest

KEY = "cpu_times"  # the records' key in xdist's workeroutput
_RECORDS = pytest.StashKey[list]()  # (file, CPU s, wall s, worker) per test


def pytest_addoption(parser):
    parser.addoption("--cpu-times", action="store_true", help="print each test file's CPU seconds at the end")


def _cpu() -> float:
    """CPU seconds of this process and its waited-for children, user and system."""
    own, children = (resource.getrusage(who) for who in (resource.RUSAGE_SELF, resource.RUSAGE_CHILDREN))
    return own.ru_utime + own.ru_stime + children.ru_utime + children.ru_stime


def pytest_configure(config):
    if config.getoption("--cpu-times"):
        config.stash[_RECORDS] = []



@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_protocol(item, nextitem):
    records = item.config.stash.get(_RECORDS, None)
    cpu, wall = _cpu(), time.perf_counter()
    yield
    if records is not None:
        records.append((item.nodeid.split("::", 1)[0], _cpu() - cpu, time.perf_counter() - wall,
                        os.environ.get("PYTEST_XDIST_WORKER", "-")))


def hand_over(session, stash: pytest.StashKey, key: str) -> None:
    """An xdist worker hands its records (config.stash[stash]) to the main process under `key`
    (xdist's workeroutput); the records' plugins share it (stride_solves.py)."""
    records = session.config.stash.get(stash, None)
    if records is not None and hasattr(session.config, "workeroutput"):
        session.config.workeroutput[key] = records


def take_over(node, stash: pytest.StashKey, key: str) -> None:
    """The main process's records (config.stash[stash]) extended by a finished worker's."""
    records = node.config.stash.get(stash, None)
    if records is not None:
        records.extend(tuple(r) for r in getattr(node, "workeroutput", {}).get(key, []))


def pytest_sessionfinish(session):
    hand_over(session, _RECORDS, KEY)


@pytest.hookimpl(optionalhook=True)
def pytest_testnodedown(node, error):
    take_over(node, _RECORDS, KEY)


def pytest_terminal_summary(terminalreporter, config):
    records = config.stash.get(_RECORDS, None)
    if not records:
        return
    cpu, wall, count, worker = (collections.defaultdict(float), collections.defaultdict(float),
                                collections.Counter(), {})
    for path, c, w, node in records:
        cpu[path] += c
        wall[path] += w
        count[path] += 1
        worker[path] = node
    write = terminalreporter.write_line
    write(f"{'CPU s':>7} {'wall s':>7} {'tests':>5} {'worker':>6}  file")
    for path in sorted(cpu, key=cpu.get, reverse=True):
        write(f"{cpu[path]:7.1f} {wall[path]:7.1f} {count[path]:5d} {worker[path]:>6}  {path}")
    for node in sorted(set(worker.values())) if len(set(worker.values())) > 1 else ():
        write(f"{sum(cpu[p] for p in cpu if worker[p] == node):7.1f} "
              f"{sum(wall[p] for p in cpu if worker[p] == node):7.1f} {'':5} {node:>6}  (the worker's files)")
    write(f"{sum(cpu.values()):7.1f} {sum(wall.values()):7.1f} {sum(count.values()):5d} {'':6}  all files")
