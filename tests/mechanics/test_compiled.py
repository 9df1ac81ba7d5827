"""mechanics.compiled's disk cache: a library keyed by the caller, compiled once when several
want it at once, and the interpreted uses counted beside it."""

import time
from concurrent.futures import ThreadPoolExecutor

import casadi as ca
import numpy as np

from formopt.mechanics import compiled


def _function() -> ca.Function:
    x = ca.SX.sym("x", 2)
    return ca.Function("cache_probe", [x], [ca.sin(x) * x[0]])


def test_a_keyed_library_is_found_without_its_source(tmp_path, monkeypatch):
    monkeypatch.setenv("FORMOPT_CACHE", str(tmp_path))
    f = _function()
    assert not compiled.keyed_cached("cache_probe", "key")
    path = compiled.keyed_library("cache_probe", "key", lambda: f)
    assert compiled.keyed_cached("cache_probe", "key") and not compiled.keyed_cached("cache_probe", "other")
    assert compiled.keyed_library("cache_probe", "key", lambda: 1 / 0) == path  # not made again
    loaded = ca.external("cache_probe", str(path))
    np.testing.assert_array_equal(np.asarray(loaded([0.3, 2.0])), np.asarray(f([0.3, 2.0])))


def test_a_library_wanted_at_once_compiles_once(tmp_path, monkeypatch):
    """Two callers (threads here, processes in compare's band) asking for one library: the
    second waits for the first's compile and uses it."""
    monkeypatch.setenv("FORMOPT_CACHE", str(tmp_path))
    builds, build = [], compiled._build

    def slow(*args):
        builds.append(args[-1])
        time.sleep(0.3)
        build(*args)
    monkeypatch.setattr(compiled, "_build", slow)
    with ThreadPoolExecutor(2) as pool:
        paths = list(pool.map(lambda _: compiled.library(_function()), range(2)))
    assert len(builds) == 1 and paths[0] == paths[1] and paths[0].exists()


def test_uses_are_counted_on_disk(tmp_path, monkeypatch):
    monkeypatch.setenv("FORMOPT_CACHE", str(tmp_path))
    assert compiled.keyed_uses("probe", "key") == 0
    assert compiled.keyed_uses("probe", "key", add=2) == 2
    assert compiled.keyed_uses("probe", "key", add=1) == 3 and compiled.keyed_uses("probe", "other") == 0
