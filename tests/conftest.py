"""Fixtures: the paper's body and its models, one compile cache and one Dask cluster per
session (helpers.py holds the shared functions)."""

import pytest

from formopt.mechanics.body import paper_body
from formopt.mechanics.model import build_model


@pytest.fixture(scope="session")
def body():
    return paper_body()


@pytest.fixture(scope="session")
def leg(body):
    return build_model(body, "leg")


@pytest.fixture(scope="session")
def shank_foot(body):
    return build_model(body, "shank-foot")


@pytest.fixture(scope="session", autouse=True)
def compile_cache(tmp_path_factory):
    """One cache of compiled functions for the whole session (FORMOPT_CACHE): every test that
    compiles the same graph reuses the library, and no test reads the user's own cache."""
    mp = pytest.MonkeyPatch()
    path = tmp_path_factory.mktemp("formopt-cache")
    mp.setenv("FORMOPT_CACHE", str(path))
    yield path
    mp.undo()


@pytest.fixture(scope="session")
def dask_scheduler():
    """The address of a local Dask cluster (two worker processes), started once per session."""
    from dask.distributed import LocalCluster

    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster:
        yield cluster.scheduler_address
