"""`pytest --stride-solves` (with or without -n): each test file's stride NLP solves (IPOPT runs,
optim.stride.collocation.StrideNLP._run), their CPU seconds, and how many repeat a solve made
earlier in the same file (the same body, settings, IPOPT options, start and parameters: a solve
a test could take from a fixture or the code under test instead of making it again, unless the
repeat is the point, as a determinism check's), printed slowest first at the end.

A solve in a pool's worker or a subprocess is not seen (its process has no records)."""

from __future__ import annotations

import collections
import hashlib
import pickle
import time

import numpy as np
import pytest
from cpu_times import hand_over, take_over

KEY = "stride_solves"  # the records' key in xdist's workeroutput
_RECORDS = pytest.StashKey[list]()  # (file, solve key, CPU s) per solve
_CURRENT = pytest.StashKey[dict]()  # {"file": the running test's file}
_RUN = pytest.StashKey[object]()  # StrideNLP._run unwrapped, put back at the end


def pytest_addoption(parser):
    parser.addoption("--stride-solves", action="store_true",
                     help="print each test file's stride solves, their CPU and repeats at the end")


def solve_key(nlp, start: dict, point: tuple) -> str:
    """What makes a solve: the NLP's body, settings and IPOPT options, the start (x0 and any
    multipliers) and (speed, slope, mu, cadence)."""
    digest = hashlib.sha256(pickle.dumps((nlp.js.body, nlp.settings, nlp.ipopt, point)))
    for name in sorted(start):
        digest.update(name.encode() + np.ascontiguousarray(start[name], float).tobytes())
    return digest.hexdigest()


def pytest_configure(config):
    if not config.getoption("--stride-solves"):
        return
    from formopt.optim.stride.collocation import StrideNLP

    records, run, current = [], StrideNLP._run, {"file": "-"}
    config.stash[_RECORDS], config.stash[_CURRENT], config.stash[_RUN] = records, current, run

    def counted(nlp, solver, start, *point):
        cpu = time.process_time()
        out = run(nlp, solver, start, *point)
        records.append((current["file"], solve_key(nlp, start, point), time.process_time() - cpu))
        return out

    StrideNLP._run = counted  # this process's, until pytest_unconfigure


def pytest_unconfigure(config):
    run = config.stash.get(_RUN, None)
    if run is not None:
        from formopt.optim.stride.collocation import StrideNLP

        StrideNLP._run = run


@pytest.hookimpl(hookwrapper=True)
def pytest_runtest_protocol(item, nextitem):
    current = item.config.stash.get(_CURRENT, None)
    if current is not None:
        current["file"] = item.nodeid.split("::", 1)[0]
    yield


def pytest_sessionfinish(session):
    hand_over(session, _RECORDS, KEY)


@pytest.hookimpl(optionalhook=True)
def pytest_testnodedown(node, error):
    take_over(node, _RECORDS, KEY)


def pytest_terminal_summary(terminalreporter, config):
    records = config.stash.get(_RECORDS, None)
    if not records:
        return
    cpu, count, repeats, repeat_cpu, seen = (collections.defaultdict(float), collections.Counter(),
                                             collections.Counter(), collections.defaultdict(float), set())
    for path, key, c in records:
        cpu[path] += c
        count[path] += 1
        if (path, key) in seen:
            repeats[path] += 1
            repeat_cpu[path] += c
        seen.add((path, key))
    write = terminalreporter.write_line
    write(f"{'CPU s':>7} {'solves':>6} {'repeats':>7} {'their CPU s':>11}  file")
    for path in sorted(cpu, key=cpu.get, reverse=True):
        write(f"{cpu[path]:7.1f} {count[path]:6d} {repeats[path]:7d} {repeat_cpu[path]:11.1f}  {path}")
    write(f"{sum(cpu.values()):7.1f} {sum(count.values()):6d} {sum(repeats.values()):7d} "
          f"{sum(repeat_cpu.values()):11.1f}  all files")
