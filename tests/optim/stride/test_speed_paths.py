"""The stride NLP's node derivatives compiled to C (collocation.COMPILED) solve as the
interpreted ones do: the same iterations and optimum to round-off (no timing here: speed
lives in benchmarks/stride_speed.py)."""

import ctypes
import os
import shutil
from dataclasses import replace
from pathlib import Path

import casadi as ca
import numpy as np
import pytest

from formopt.mechanics import compiled as compiled_functions
from formopt.mechanics.body import paper_body
from formopt.mechanics.joint_space import JointSpace
from formopt.optim.stride import StrideNLP, StrideSettings, collocation, derivatives
from formopt.optim.stride.guess import ballistic

SETTINGS = StrideSettings(strike="flat", nodes=14)


@pytest.fixture(scope="module")
def solves():
    """(interpreted, compiled): each NLP's solve from the generic guess at 3.5 m/s."""
    out = []
    for compiled in (False, True):
        nlp = StrideNLP(JointSpace(paper_body()), SETTINGS, compiled=compiled)
        out.append((nlp, nlp.solve(ballistic(nlp, 3.5), 3.5)))
    return out


def test_compiled_solves_as_interpreted(solves):
    (plain, a), (fast, b) = solves
    assert not plain.compiled and fast.compiled
    assert a.success and b.success
    assert a.iterations == b.iterations
    np.testing.assert_allclose(b.x, a.x, rtol=0, atol=1e-9)
    for got, want in ((b.lam_g, a.lam_g), (b.lam_x, a.lam_x)):  # the warm start's multipliers
        np.testing.assert_allclose(got, want, rtol=0, atol=1e-9 * max(1.0, np.max(np.abs(want))))
    assert b.objective == pytest.approx(a.objective, rel=1e-12)


def test_a_built_solver_leaves_casadis_blas_on_one_thread(solves):
    """mechanics.compiled.one_blas_thread: MUMPS's dense kernels on one thread, not one per core."""
    path = Path(ca.__file__).parent / "libcasadi-tp-openblas.so.0"
    if not path.exists() or "OPENBLAS_NUM_THREADS" in os.environ:
        pytest.skip("not CasADi's own OpenBLAS, or its threads set by the user")
    assert ctypes.CDLL(str(path)).openblas_get_num_threads() == 1


def test_compiled_problem_is_the_same_nlp(solves):
    """The solvers' own problems (the compiled one calls the C node models) give the same
    objective and constraints at any x and p, a slope and another friction included."""
    (plain, a), (fast, _) = solves
    x = a.x + 1e-3 * np.random.default_rng(0).standard_normal(a.x.size)
    p = [3.2, 0.05, 0.6]
    (f0, g0), (f1, g1) = ([np.asarray(v, float) for v in ca.Function(
        "fg", [n._nlp["x"], n._nlp["p"]], [n._nlp["f"], n._nlp["g"]])(x, p)] for n in (plain, fast))
    assert fast._nlp is not fast.problem and plain._nlp is plain.problem
    np.testing.assert_allclose(g1, g0, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(f1, f0, rtol=1e-12)


def test_auto_compiles_from_a_chains_nth_solve(solves, monkeypatch):
    (_, first), _ = solves
    monkeypatch.setattr(collocation, "COMPILE_FROM", 3)  # a short chain stands for a long one
    monkeypatch.setattr(derivatives, "cached_phases", lambda nlp: [False] * len(nlp.phases))  # not compiled before
    monkeypatch.setattr(derivatives, "phase_rent", lambda nlp, *args: [0] * len(nlp.phases))  # nor solved
    nlp = StrideNLP(JointSpace(paper_body()), SETTINGS)  # compiled="auto"
    seen = []
    for speed in (3.5, 3.6, 3.7):
        seen.append(nlp.compiled)
        previous = nlp.solve(first.blocks, speed)
    assert seen == [False, False, True]
    assert previous.success and nlp._nlp is not nlp.problem  # the solver was built again, compiled
    warm = nlp.resolve(previous, 3.8)  # the warm solver shares the compiled derivatives
    assert warm.success and nlp.compiled


def test_auto_uses_a_cached_build_from_the_first_solve(solves, tmp_path, monkeypatch):
    """A node model compiled before (the fixture's, in the disk cache) costs nothing to use:
    "auto" solves compiled from the first solve, as True does; another cache holds none."""
    _, (_, fast_first) = solves
    nlp = StrideNLP(JointSpace(paper_body()), SETTINGS)  # compiled="auto"
    assert nlp.compiled
    again = nlp.solve(ballistic(nlp, 3.5), 3.5)
    assert nlp._nlp is not nlp.problem and again.iterations == fast_first.iterations
    monkeypatch.setenv("FORMOPT_CACHE", str(tmp_path))
    assert not StrideNLP(JointSpace(paper_body()), SETTINGS).compiled


def test_a_cached_build_is_used_without_generating_c(solves, monkeypatch):
    """A node model in the disk cache is found by its key (the node Function serialised) and
    loaded as it is: no C source generated, nothing derived, the same solve."""
    _, (_, fast_first) = solves

    def no_source(function, jacobian):
        raise AssertionError(f"C source of {function.name()} generated")
    monkeypatch.setattr(compiled_functions, "_source", no_source)
    monkeypatch.setattr(derivatives, "_functions", no_source)
    monkeypatch.setattr(derivatives, "_DERIVED", {})  # derivatives.derived's models of this process
    nlp = StrideNLP(JointSpace(paper_body()), SETTINGS, compiled=True)
    assert all(derivatives.cached_phases(nlp))
    assert nlp.solve(ballistic(nlp, 3.5), 3.5).iterations == fast_first.iterations


def test_auto_uses_the_phases_in_the_cache(solves, tmp_path, monkeypatch):
    """A forefoot strike's NLP shares its flat, forefoot and flight phase models with the flat
    strike's (the fixture's, compiled): "auto" runs those three as C from the first solve and
    the landing interpreted, and solves as the interpreted NLP does."""
    shared = [f for f in Path(os.environ["FORMOPT_CACHE"]).glob("node_*.so")
              if f.name.split("_")[1] in ("flat", "forefoot", "flight")]
    for library in shared:
        shutil.copy(library, tmp_path)
    monkeypatch.setenv("FORMOPT_CACHE", str(tmp_path))
    settings = replace(SETTINGS, strike="forefoot", nodes=18)
    mixed = StrideNLP(JointSpace(paper_body()), settings)
    assert [p.name for p in mixed.phases] == ["landing", "flat", "forefoot", "flight"]
    assert mixed.compiled_phases == (False, True, True, True) and not mixed.compiled
    plain = StrideNLP(JointSpace(paper_body()), settings, compiled=False)
    a, b = (nlp.solve(ballistic(nlp, 3.5), 3.5) for nlp in (plain, mixed))
    assert mixed._nlp is not mixed.problem and not list(tmp_path.glob("node_landing_*.so"))  # nothing compiled
    assert a.success and b.success and a.iterations == b.iterations
    np.testing.assert_array_equal(b.x, a.x)  # C computes what CasADi's virtual machine does


def test_auto_counts_interpreted_iterations_over_runs(tmp_path, monkeypatch):
    """"auto"'s rent is kept on disk, per phase model, in IPOPT iterations: once RENT_ITERATIONS
    ran interpreted, by any NLP object or process sharing the cache, another NLP of the same
    phase models compiles from its first solve; a cache of its own has counted none."""
    monkeypatch.setenv("FORMOPT_CACHE", str(tmp_path))
    nlp = StrideNLP(JointSpace(paper_body()), SETTINGS)  # compiled="auto"
    first = nlp.solve(ballistic(nlp, 3.5), 3.5)
    assert derivatives.phase_rent(nlp) == [first.iterations] * 3 and not any(nlp.compiled_phases)
    again = nlp.resolve(first, 3.6)
    monkeypatch.setattr(collocation, "RENT_ITERATIONS", first.iterations + again.iterations)
    later = StrideNLP(JointSpace(paper_body()), SETTINGS)  # another run's NLP
    assert later.solves == 0 and later.compiled
    monkeypatch.setenv("FORMOPT_CACHE", str(tmp_path / "other"))
    assert not StrideNLP(JointSpace(paper_body()), SETTINGS).compiled


def test_auto_counts_no_rent_without_a_compiler(solves, tmp_path, monkeypatch):
    """Without a C compiler "auto" never compiles: its interpreted iterations are not counted
    (the rent's file would grow by a byte an iteration for nothing)."""
    (_, first), _ = solves
    monkeypatch.setenv("FORMOPT_CACHE", str(tmp_path))
    monkeypatch.setattr(collocation, "_has_compiler", lambda: False)
    nlp = StrideNLP(JointSpace(paper_body()), SETTINGS)  # compiled="auto"
    assert nlp.solve(first.blocks, 3.5).success and not nlp.compiled
    assert not list(tmp_path.glob("*.uses"))


def test_auto_goes_on_interpreted_when_compiling_fails(solves, tmp_path, monkeypatch):
    """A C compiler that is found but fails: "auto" warns and solves interpreted (a long chain
    goes on), True raises."""
    (_, first), _ = solves
    monkeypatch.setenv("FORMOPT_CACHE", str(tmp_path))  # an empty cache: each library compiles

    def broken(source, name, level, target=None):
        raise RuntimeError(f"compiling {name} failed")
    monkeypatch.setattr(compiled_functions, "_compile", broken)
    monkeypatch.setattr(collocation, "COMPILE_FROM", 2)
    monkeypatch.setattr(derivatives, "cached_phases", lambda nlp: [False] * len(nlp.phases))  # not compiled before
    monkeypatch.setattr(derivatives, "phase_rent", lambda nlp, *args: [0] * len(nlp.phases))  # nor solved
    nlp = StrideNLP(JointSpace(paper_body()), SETTINGS, compiled="auto")
    assert nlp.solve(first.blocks, 3.5).success and nlp.compiled  # the next solve would compile
    with pytest.warns(RuntimeWarning, match="did not compile"):
        again = nlp.solve(first.blocks, 3.6)
    assert again.success and not nlp.compiled and nlp.resolve(again, 3.7).success
    with pytest.raises(RuntimeError, match="failed"):
        StrideNLP(JointSpace(paper_body()), SETTINGS, compiled=True).solve(first.blocks, 3.5)


def test_the_modules_setting_is_the_default(monkeypatch):
    """collocation.COMPILED is read when an NLP is built, not when the module is imported, and
    build() keeps one NLP per setting."""
    monkeypatch.setattr(collocation, "_BUILT", {})
    monkeypatch.setattr(collocation, "COMPILED", True)
    assert StrideNLP(JointSpace(paper_body()), SETTINGS).compiled
    assert collocation.build(paper_body(), SETTINGS).compiled
    monkeypatch.setattr(collocation, "COMPILED", False)
    assert not collocation.build(paper_body(), SETTINGS).compiled


def test_bad_compiled_value_is_refused():
    with pytest.raises(ValueError, match="compiled"):
        StrideNLP(JointSpace(paper_body()), SETTINGS, compiled="yes")
