"""Fixtures: the paper's body and its models, one compile cache kept between runs, one Dask
cluster per session (helpers.py holds the shared functions)."""

import os
import time
from pathlib import Path

import pytest

from formopt.mechanics.body import paper_body
from formopt.mechanics.compiled import compiler
from formopt.mechanics.model import build_model
from formopt.optim.stride import collocation

# pytest --cpu-times: each file's CPU seconds (cpu_times.py); pytest --stride-solves: each file's
# stride solves, their CPU and the solves it repeats (stride_solves.py)
pytest_plugins = ("cpu_times", "stride_solves")


@pytest.fixture(scope="session")
def body():
    return paper_body()


@pytest.fixture(scope="session")
def leg(body):
    return build_model(body, "leg")


@pytest.fixture(scope="session")
def shank_foot(body):
    return build_model(body, "shank-foot")


# The compiler the tests compile with: the system's cc at -O0 (its flags come last, so they win
# over compiled.FUNCTION_OPT). The tests check numbers, not speed; without -ffast-math both levels
# give the same IEEE results (the full-body landing: the same T_c_total to the last bit), and -O0
# compiles the large step functions about six times faster (full-body landing: 17 s -> 2.7 s CPU).
FAST_CC = '#!/bin/sh\nexec "${FORMOPT_TEST_CC:-cc}" "$@" -O0\n'


KEEP_DAYS = 30  # a kept library built longer ago than this is built again (the cache's growth bounded)


def kept_cache(config) -> Path | None:
    """The compile cache's folder in pytest's cache (.pytest_cache/d/formopt-cache), or None
    without the cache plugin or where it cannot be written (a read-only checkout)."""
    cache = getattr(config, "cache", None)
    try:
        return cache.mkdir("formopt-cache") if cache is not None else None
    except OSError:
        return None


def pytest_configure(config):
    """The kept compile cache's libraries older than KEEP_DAYS removed, once a run, by the main
    process before any test (an xdist worker might be loading one), and "auto"'s rent
    (collocation.RENT_ITERATIONS, the .uses files): each run counts from none, so that
    processes no_compile_by_chance does not reach (the notebooks' kernel) do not start compiling
    after enough runs."""
    root = kept_cache(config)
    if root is None or hasattr(config, "workerinput"):
        return
    for library in (root / "libraries").glob("*.so"):
        if time.time() - library.stat().st_mtime > KEEP_DAYS * 86400:
            library.unlink(missing_ok=True)
    for rent in (root / "libraries").glob("*.uses"):
        rent.unlink(missing_ok=True)


@pytest.fixture(scope="session", autouse=True)
def compile_cache(request, tmp_path_factory):
    """One cache of compiled functions for the tests (FORMOPT_CACHE), kept between runs in
    pytest's cache folder (.pytest_cache/d/formopt-cache; `pytest --cache-clear` empties it;
    without it, the session's temp folder: kept_cache) and shared by the pytest-xdist workers:
    a library is keyed by its C source, flags and the compiler's path and written by an atomic
    rename (compiled._compile), so a graph compiles once, not once per run (test_speed_paths: 5 s
    of cc), and no test reads the user's own cache. CC compiles at -O0 (FAST_CC) through a
    wrapper at a fixed path in that folder: the key does not see a compiler upgrade (then
    `pytest --cache-clear`). Subprocesses (the CLI's, the notebooks' kernels) inherit both."""
    mp = pytest.MonkeyPatch()
    root = kept_cache(request.config)
    if root is None:
        root = tmp_path_factory.getbasetemp()
        if os.environ.get("PYTEST_XDIST_WORKER"):  # the workers' temp folders share one parent
            root = root.parent
    path = root / "libraries"
    path.mkdir(exist_ok=True)
    cc = root / "cc-O0"
    if not cc.exists() or cc.read_text() != FAST_CC:
        tmp = root / f"cc-O0.{os.getpid()}"
        tmp.write_text(FAST_CC)
        tmp.chmod(0o755)
        os.replace(tmp, cc)
    mp.setenv("FORMOPT_CACHE", str(path))
    mp.setenv("FORMOPT_TEST_CC", compiler())
    mp.setenv("CC", str(cc))
    yield path
    mp.undo()


@pytest.fixture(scope="session", autouse=True)
def no_compile_by_chance():
    """The stride NLP's "auto" compilation (collocation.COMPILE_FROM) never starts by chance in
    the tests: collocation.build keeps NLPs per process, so one NLP's solves add up across the
    tests of a worker in whatever order they run (test_search's imposed-cadence test made the
    20th solve and compiled the node models: 5 s of cc), nor from the rent kept in the disk cache,
    which the tests' cache keeps between runs (RENT_ITERATIONS). test_speed_paths tests the paths
    with its own; the compiled solves are checked there against the interpreted ones."""
    mp = pytest.MonkeyPatch()
    mp.setattr(collocation, "COMPILE_FROM", 10**9)
    mp.setattr(collocation, "RENT_ITERATIONS", 10**9)
    yield
    mp.undo()


@pytest.fixture(scope="session")
def dask_scheduler():
    """The address of a local Dask cluster, started once per session; the tests that take it
    say "dask" in their names, so that ByFile runs them on one worker
    (pytest_collection_modifyitems checks). One worker process: the tests compare Dask's rows
    with the serial and pool's, whose chains do not depend on the workers (test_stride_sweep);
    a second worker cost 1.6 s of CPU (its spawn and imports, 2026-11-27)."""
    from dask.distributed import LocalCluster

    with LocalCluster(n_workers=1, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster:
        yield cluster.scheduler_address


def pytest_collection_modifyitems(items):
    """A test that takes the Dask cluster says "dask" in its name (ByFile groups by the name)."""
    for item in items:
        if "dask_scheduler" in getattr(item, "fixturenames", ()) and "dask" not in item.name:
            raise pytest.UsageError(f"{item.nodeid}: a test that takes dask_scheduler says 'dask' in its name")


try:
    from xdist.scheduler import LoadFileScheduling
except ImportError:  # pytest-xdist comes with the test extra; without it the suite runs in one process
    LoadFileScheduling = None

if LoadFileScheduling is not None:

    class ByFile(LoadFileScheduling):
        """`pytest -n 2 --dist loadfile` (the Makefile): each file's tests on one worker, so its
        module fixtures are built once, the Dask tests (named "...dask...") together on one
        worker, so one cluster starts, and tests/measure/'s files together, so its conftest's
        session fixtures (the trials read and measured: 1.3 s of CPU) are built once. (xdist's
        loadgroup marks do not reach its scheduler under pytest 9, which no longer reads the node
        id xdist rewrites.)"""

        def _split_scope(self, nodeid: str) -> str:
            if "dask" in nodeid.rsplit("::", 1)[-1]:
                return "dask"
            return MEASURE if nodeid.startswith(MEASURE) else super()._split_scope(nodeid)

        def _assign_work_unit(self, node) -> None:
            """Hand out the files of SLOW first, in its order, then the others in xdist's order: the
            two workers then finish close together (in xdist's order, by number of tests, the
            last files handed out were among the slowest and one worker idled for 7 s)."""
            first = min(self.workqueue, key=_rank)
            self.workqueue.move_to_end(first, last=False)
            super()._assign_work_unit(node)

    MEASURE = "tests/measure/"  # one unit of work (ByFile)

    def _rank(nodeid: str) -> int:
        path = nodeid.split("::", 1)[0].removeprefix("tests/")
        return SLOW.index(path) if path in SLOW else len(SLOW)

    def pytest_xdist_make_scheduler(config, log):
        return ByFile(config, log) if config.getvalue("dist") == "loadfile" else None


# The files (and the units of the Dask tests, "dask", and of tests/measure/) by CPU seconds of their
# tests, slowest first: the mean of two runs of the suite on 2 workers (pytest -p no:cacheprovider
# -n 2 --dist loadfile --cpu-times: the compile cache cold, as on a clean clone), 2026-11-27 evening,
# another helper's solves beside them (load about 3: every figure stretched, by up to a half for the
# solves, against a quiet machine's); test_stride_sweep.py alone after its cuts; "dask" and the two
# files whose Dask test it holds from the list before (quiet, warm). They are handed out in this
# order, then the others (under 1 s each) in xdist's: the longest first, so the two workers end close
# together (these figures, greedy: 124.1 and 123.2 s). A stale list costs only balance, never a test.
SLOW = ("studies/test_stride_sweep.py",  # 22.5
        "optim/stride/test_derivatives.py",  # 20.1
        "optim/stride/test_speed_paths.py",  # 13.7 (6.6 with a warm compile cache)
        "test_examples.py",  # 13.3
        "optim/test_stride.py",  # 13.2
        "test_bad_input.py",  # 11.1 (more wall: its subprocesses)
        "test_notebooks.py",  # 10.8 (its kernel's)
        "cli/test_compare_command.py",  # 10.0
        "measure/",  # 9.8: tests/measure/'s files, one unit (ByFile)
        "optim/stride/test_collocation.py",  # 9.4
        "optim/test_posture.py",  # 8.7
        "optim/stride/test_search.py",  # 8.3
        "optim/stride/test_muscle_stride.py",  # 7.8
        "studies/test_compare_stride.py",  # 6.4
        "optim/stride/test_forward.py",  # 6.2
        "mechanics/test_contact.py",  # 5.8
        "test_docs.py",  # 5.6
        "optim/stride/test_consistency_rows.py",  # 5.5
        "studies/test_bench.py",  # 5.2
        "optim/stride/test_mesh_check.py",  # 5.0
        "mechanics/test_joint_moments.py",  # 4.2
        "io/test_numerics.py",  # 3.8
        "studies/test_compare.py",  # 3.4
        "optim/test_gait.py",  # 3.2
        "studies/test_stride_scene.py",  # 3.1
        "mechanics/test_extremes.py",  # 3.1
        "dask",  # 2.7: the cluster, its worker and the two Dask tests
        "mechanics/test_landing.py",  # 2.6 without its Dask test
        "studies/test_optimum_map.py",  # 2.6 without its Dask test
        "optim/test_stride_slide.py",  # 2.5
        "mechanics/test_impact.py",  # 2.5
        "optim/stride/test_grading.py",  # 2.4
        "optim/test_stride_tendons.py",  # 2.0
        "cli/test_reports.py",  # 1.9
        "io/test_mocap.py",  # 1.6
        "optim/stride/test_moment_dynamics.py",  # 1.5
        "test_signals.py",  # 1.4 (its subprocesses)
        "mechanics/test_joint_space.py",  # 1.2
        "test_layers.py",  # 1.1 (its subprocess)
        "io/test_scene.py",  # 1.1
        "report/test_figures.py")  # 1.0
