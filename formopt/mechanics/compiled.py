"""CasADi Functions compiled to C: code generation, a content-keyed cache, a light call.

`library(f)` generates C for f, compiles it with the system's C compiler and caches the shared
library under a key of the generated source and the compiler flags, so a second run (or a
second process) does not compile again; `keyed_library(name, key, f)` caches it under a key
the caller gives instead (what determines f's source, cheaper to make than the source: a library
on disk is then found without generating C). `external(f)` loads it back as a CasADi Function (for
use inside other CasADi graphs, or mapped over batches); `Compiled(f)` calls that external
through CasADi's `Function.buffer()` on preallocated numpy arrays, which costs about a
microsecond per call instead of CasADi's Python dispatch (`f.call`, tens of microseconds).
`Compiled(f, compiled=False)` calls f itself the same way (no C compiler needed).

The cache folder is $FORMOPT_CACHE, or ~/.cache/formopt.
"""

from __future__ import annotations

import contextlib
import ctypes
import functools
import hashlib
import inspect
import os
import shutil
import subprocess
import tempfile
from collections.abc import Callable
from pathlib import Path

import casadi as ca
import numpy as np

FLAGS = ("-fPIC", "-shared", "-fno-math-errno")
# Small functions evaluated millions of times get -O3; an NLP's generated derivatives (tens of
# thousands of lines, called a few dozen times per solve) compile ten times faster at -O0 and
# solve almost as fast: IPOPT's own work dominates (benchmarks/solve_speed.py).
FUNCTION_OPT, NLP_OPT = "-O1", "-O0"
GENERATOR = {"with_header": False}  # CasADi's code generator's options


def cache_dir() -> Path:
    return Path(os.environ.get("FORMOPT_CACHE", Path.home() / ".cache" / "formopt"))


def compiler() -> str:
    for cc in (os.environ.get("CC"), "cc", "gcc", "clang"):
        if cc and shutil.which(cc):
            return cc
    raise RuntimeError("no C compiler found (set CC): compiled functions need one; "
                       "use the interpreted CasADi Function instead")


def library(function: ca.Function, jacobian: bool = False) -> Path:
    """Path of the compiled shared library of `function` (built once, then cached); with
    `jacobian`, its Jacobian too (`jac_<name>`, which CasADi differentiates a loaded external by)."""
    return _compile(_source(function, jacobian), function.name(), FUNCTION_OPT)


def keyed_library(name: str, key: str, function: Callable[[], ca.Function], jacobian: bool = False) -> Path:
    """As `library(function(), jacobian)`, cached under `key` instead of its C source: a text
    that determines the source (with CasADi's version and GENERATOR, which the key takes in), so
    a library on disk is found without generating C (the source of a stride node model's
    Hessian, hundreds of kB, costs about 0.1 s). `function()`, the Function named `name`, is
    called only when the library is compiled."""
    target = _target(_keyed(key, jacobian), name, FUNCTION_OPT)
    return _compile(lambda: _source(function(), jacobian), name, FUNCTION_OPT, target)


def keyed_cached(name: str, key: str, jacobian: bool = False) -> bool:
    """Whether `keyed_library(name, key, ..., jacobian)` is in the disk cache already."""
    return _target(_keyed(key, jacobian), name, FUNCTION_OPT).exists()


def keyed_uses(name: str, key: str, add: int = 0) -> int:
    """How much a `keyed_library(name, key, ...)` not compiled was used interpreted instead,
    in the caller's units (the stride's node models: IPOPT iterations), over every process and
    run sharing the disk cache (a file beside the libraries, one byte a unit, appended:
    processes may count at once); `add`: this many counted first. 0 where the cache cannot be
    written."""
    path = _target(_keyed(key, False), name, FUNCTION_OPT).with_suffix(".uses")
    try:
        if add:
            path.parent.mkdir(parents=True, exist_ok=True)
            with open(path, "ab") as uses:
                uses.write(b"." * add)
        return path.stat().st_size if path.exists() else 0
    except OSError:
        return 0


def recipe(function) -> str:
    """What a keyed library's C is made by, for its key: `function`'s source (a Python function
    or class), or formopt's version where the sources are not installed."""
    try:
        return inspect.getsource(function)
    except (OSError, TypeError):
        from .. import __version__
        return f"formopt {__version__}"


def _keyed(key: str, jacobian: bool) -> str:
    """`keyed_library`'s key with what else makes its C: CasADi, its options, `_source`."""
    return "\0".join([key, ca.__version__, repr(GENERATOR), _SOURCE_RECIPE, str(jacobian)])


def _source(function: ca.Function, jacobian: bool) -> str:
    """The C source of `function` (and of its Jacobian, `jacobian`)."""
    generator = ca.CodeGenerator(f"{function.name()}.c", GENERATOR)
    generator.add(function)
    if jacobian:
        generator.add(function.jacobian())
    return generator.dump()


_SOURCE_RECIPE = recipe(_source)


def cached_nlpsol(name: str, nlp: dict, opts: dict, compiled: bool = False) -> ca.Function:
    """An IPOPT solver of `nlp`; with `compiled`, its functions and derivatives run as C.

    The objective, constraints, gradient, Jacobian and Hessian of the Lagrangian are generated
    once (CasADi's generate_dependencies), compiled and cached like `library`.
    """
    one_blas_thread()
    solver = ca.nlpsol(name, "ipopt", nlp, opts)
    if not compiled:
        return solver
    with tempfile.TemporaryDirectory() as tmp, contextlib.chdir(tmp):
        solver.generate_dependencies(f"{name}_nlp.c", {"with_header": False})
        source = Path(f"{name}_nlp.c").read_text()
    return ca.nlpsol(name, "ipopt", str(_compile(source, f"{name}_nlp", NLP_OPT)), opts)


def _target(key: str, name: str, level: str) -> Path:
    """The cached library's path: keyed by its source (or `keyed_library`'s key), the compiler
    and its flags."""
    digest = hashlib.sha256("\0".join([key, compiler(), level, *FLAGS]).encode()).hexdigest()[:20]
    return cache_dir() / f"{name}_{digest}.so"


def _compile(source: str | Callable[[], str], name: str, level: str, target: Path | None = None) -> Path:
    """The library of `source` at `target` (default: keyed by the source, then a str), compiled
    unless there; a callable `source` is generated only when this process compiles it (not
    while another compiles it, not when it is there)."""
    cc, flags = compiler(), (level, *FLAGS)
    if target is None:
        assert isinstance(source, str), "_compile: a source generated on demand needs its target"
        target = _target(source, name, level)
    if target.exists():
        return target
    target.parent.mkdir(parents=True, exist_ok=True)
    with _locked(target):
        if target.exists():  # another process compiled it while this one waited
            return target
        _build(cc, flags, source() if callable(source) else source, name, target)
    return target


@contextlib.contextmanager
def _locked(target: Path):
    """One process at a time compiles `target` (a lock file beside it; POSIX): processes that
    want one library at once (compare's band workers, `auto` compiling one variant's phases)
    compile it once, the others wait for it."""
    try:
        import fcntl
    except ImportError:  # not POSIX: each compiles, the atomic rename keeps one
        yield
        return
    lock = None
    try:
        lock = open(target.with_suffix(".lock"), "w")
        fcntl.flock(lock, fcntl.LOCK_EX)
    except OSError:  # a folder without locks (NFS without lockd): compile unlocked, as above
        pass
    try:
        yield
    finally:
        if lock is not None:
            lock.close()


def _build(cc: str, flags: tuple, source: str, name: str, target: Path) -> None:
    with tempfile.TemporaryDirectory(dir=target.parent) as tmp:
        c_file, so_file = Path(tmp) / f"{name}.c", Path(tmp) / target.name
        c_file.write_text(source)
        done = subprocess.run([cc, *flags, str(c_file), "-o", str(so_file), "-lm"],
                              capture_output=True, text=True, check=False)
        if done.returncode != 0:
            raise RuntimeError(f"compiling {name} failed:\n{done.stderr[-2000:]}")
        os.replace(so_file, target)  # atomic: a half-written library is never seen as built


def external(function: ca.Function, jacobian: bool = False) -> ca.Function:
    """The compiled `function` as a CasADi Function (same inputs and outputs); `jacobian`: with
    its compiled Jacobian, so graphs that call it can be differentiated."""
    return ca.external(function.name(), str(library(function, jacobian)))


class Compiled:
    """Call a CasADi Function from Python with preallocated buffers.

    `Compiled(f)(x, ...)` returns a dict of dense numpy arrays, one per output, like
    `f.call`; the arrays are fresh copies. The Function evaluated is `external(f)` (compiled to
    C), or f itself with `compiled=False` (CasADi's virtual machine), through
    `Function.buffer()` on numpy arrays bound once (column-major nonzeros of each input and
    output): about a microsecond of overhead per call instead of tens for `f.call`.
    """

    def __init__(self, function: ca.Function, compiled: bool = True):
        self.function = function
        self._evaluated = external(function) if compiled else function
        self._buffer, self._eval = self._evaluated.buffer()
        # The generated code of an SX Function is arithmetic only and always returns 0; others
        # (an MX graph's linear solvers) have their status read, which costs about 1 us a call.
        self._checked = not function.is_a("SXFunction")
        self._ins = [np.zeros(function.nnz_in(i)) for i in range(function.n_in())]
        self._outs = [np.zeros(function.nnz_out(i)) for i in range(function.n_out())]
        for i, a in enumerate(self._ins):
            self._buffer.set_arg(i, a.data)
        for i, r in enumerate(self._outs):
            self._buffer.set_res(i, r.data)
        self._layout = []  # (name, shape of a matrix output or None for a vector, sparsity)
        for i in range(function.n_out()):
            sp = function.sparsity_out(i)
            pattern = None if sp.is_dense() else (np.array(sp.row()), np.array(sp.get_col()))
            shape = None if sp.is_dense() and sp.size2() == 1 else sp.shape
            self._layout.append((function.name_out(i), shape, pattern))

    def __call__(self, *args) -> dict[str, np.ndarray]:
        for buffer, value in zip(self._ins, args):
            if isinstance(value, np.ndarray) and value.ndim > 1:
                buffer[:] = np.ravel(value, order="F")
            else:  # a number or a vector
                buffer[:] = value
        self._eval()
        if self._checked and self._buffer.ret() != 0:
            raise RuntimeError(f"{self.function.name()}: evaluation failed")
        out = {}
        for (name, shape, pattern), values in zip(self._layout, self._outs):
            if shape is None:  # a dense column: a 1-D array
                out[name] = values.copy()
            elif pattern is None:
                out[name] = values.reshape(shape, order="F").copy()
            else:
                out[name] = np.zeros(shape)
                out[name][pattern] = values
        return out


@functools.cache
def one_blas_thread() -> None:
    """CasADi's OpenBLAS (MUMPS's dense kernels) on one thread, once per process. Its own
    default, a thread per core, spins its waiting thread on kernels too small to share: on the
    muscles' solve (40 iterations, as IPOPT_DEFAULTS') 23,000-47,000 involuntary context switches
    and 0.1-1.9 s of system time against 460-1,900 and 0.02-0.03 s on one thread, user time no
    higher. Nothing is done where the library is not CasADi's own (another build of CasADi) or
    where the user set OPENBLAS_NUM_THREADS. Called where a solver is built (cached_nlpsol,
    optim.stride's StrideNLP), so a run's speed does not depend on which solver came first."""
    if "OPENBLAS_NUM_THREADS" in os.environ:
        return
    path = Path(ca.__file__).parent / "libcasadi-tp-openblas.so.0"
    if path.exists():
        ctypes.CDLL(str(path)).openblas_set_num_threads(1)
