"""The stride NLP's derivatives, assembled node by node (what IPOPT calls: grad_f, jac_g,
hess_lag), instead of derived from the whole NLP's graph.

The NLP (collocation.StrideNLP) is g = [G(z_k) for every node k; R(x, ell(x))] and
f = F(x, ell(x)), where z_k (the node's state, accelerations, controls, forces, power split
and the touchdown state) is a selection E_k x of the decision vector, G the node model's rows
and ell_k = L(z_k) its integrands. With the node model's own derivatives (one small SX graph
per phase, `NodeDerivatives`) and R, F's (a small graph: defects, transitions, periodicity,
integrals):

    dg/dx = [dG/dz_k E_k ;  R_x + R_ell ell_x],      ell_x = [dL/dz_k E_k]_k
    df/dx = F_x + ell_x^T F_ell
    hess  = Phi_xx + Phi_x,ell ell_x + ell_x^T Phi_ell,x + ell_x^T Phi_ell,ell ell_x
            + sum_k E_k^T d2/dz2 (lam_k . G + Phi_ell,k . L)(z_k) E_k

with Phi = lam_f F + lam_R . R (the Lagrangian's part outside the nodes). Nothing is derived on
the whole graph, so a 40-node build takes a fraction of a second; the functions are SX, the
node models and their derivatives optionally compiled to C, phase by phase (mechanics.compiled,
cached on disk under the node Function serialised, `_key`: one phase model's libraries serve
every NLP that holds it; `problem` then calls the compiled node models for IPOPT's f and g
too): they are the evaluations' bulk (the paper's body, heel, 40 nodes, ms of CPU an IPOPT
iteration: f, g, grad_f, jac_g and hess_lag 0.7, 0.8, 3.4, 3.5 and 8.8 interpreted, 0.08, 0.2,
0.3, 0.3 and 0.9 compiled; benchmarks/stride_speed.py, docs/reference/performance.md).
"""

from __future__ import annotations

import functools
import threading
import weakref

import casadi as ca
import numpy as np

from ...mechanics.compiled import keyed_cached, keyed_library, keyed_uses, recipe
from .ocp import INTEGRANDS

PARTS = ("value", "jacobian", "hessian")  # a node model's functions (`_functions`' order and names)


class NodeDerivatives:
    """One phase's node Function (collocation.StrideNLP.node_functions) on the stacked node
    vector z: its outputs [rows; integrands], their Jacobian and the Hessian of w . outputs;
    `compiled`: the three as C (mechanics.compiled.keyed_library under `_key`; the outputs with
    their Jacobian, so that CasADi can differentiate a graph calling them; derived and generated
    only when not in the disk cache), else SX."""

    def __init__(self, node: ca.Function, compiled: bool = False):
        self.rows = node.size1_out(0)
        if not compiled:
            self.value, self.jacobian, self.hessian = derived(node)
            return
        key = _key(node)
        parts = functools.partial(derived, node)
        self.value, self.jacobian, self.hessian = (_library(node, k, key, parts) for k in range(len(PARTS)))


def _library(node: ca.Function, k: int, key: str, parts) -> ca.Function:
    """The node model's function PARTS[k] compiled, from the disk cache when there (`key`:
    `_key(node)`; `parts()`: `derived(node)`, called only to compile)."""
    name = f"{node.name()}_{PARTS[k]}"
    return ca.external(name, str(keyed_library(name, key, lambda: parts()[k], jacobian=k == 0)))


def _functions(node: ca.Function) -> tuple[ca.Function, ca.Function, ca.Function]:
    """The node Function's value [rows; integrands], its Jacobian and the Hessian of w . value,
    SX functions of the stacked node vector z (and p, w)."""
    sizes = [node.size1_in(k) for k in range(node.n_in() - 1)]  # all inputs but p
    z, p = ca.SX.sym("z", sum(sizes)), ca.SX.sym("p", node.size1_in(node.n_in() - 1))
    parts = ca.vertsplit(z, np.cumsum([0, *sizes]).tolist())
    out = ca.vertcat(*node(*parts, p))
    w = ca.SX.sym("w", out.shape[0])
    return (ca.Function(f"{node.name()}_value", [z, p], [out]),
            ca.Function(f"{node.name()}_jacobian", [z, p], [out, ca.jacobian(out, z)]),
            ca.Function(f"{node.name()}_hessian", [z, p, w], [ca.hessian(ca.dot(w, out), z)[0]]))


# what the compiled node models' sources are made by, besides the node Function (`_key`)
_RECIPE = recipe(_functions)
# `derived`'s node models kept per process (the most recently used): a compare's runner and
# its band's variants hold about ten
DERIVED_KEPT = 16
_DERIVED: dict[str, tuple[ca.Function, ca.Function, ca.Function]] = {}
_DERIVED_LOCK = threading.Lock()


def derived(node: ca.Function) -> tuple[ca.Function, ca.Function, ca.Function]:
    """`_functions(node)`, derived once per process for each node model (`_key`: the node count
    does not change a phase's node model, so a mesh check's or a finer mesh's NLP, and every NLP
    of one body, strike and settings, share them; CasADi Functions are immutable, so sharing
    them changes no number; tests/optim/stride/test_derivatives.py counts none derived for a
    second NLP). Under a lock: a Dask worker runs its tasks in threads."""
    key = _key(node)
    with _DERIVED_LOCK:
        if key in _DERIVED:
            _DERIVED[key] = _DERIVED.pop(key)  # the most recently used last
        else:
            if len(_DERIVED) >= DERIVED_KEPT:
                _DERIVED.pop(next(iter(_DERIVED)))
            _DERIVED[key] = _functions(node)
        return _DERIVED[key]


_KEYS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # `_key`'s, per node Function


def _key(node: ca.Function) -> str:
    """What determines the C sources of a node model's functions (`_functions`): the node
    Function serialised (its graph and constants: one body's, 2 ms) and how they are derived
    from it (the keyed library adds CasADi's version)."""
    if node not in _KEYS:
        _KEYS[node] = "\0".join([node.serialize(), _RECIPE])
    return _KEYS[node]


def phase_rent(nlp, iterations: int = 0, phases: tuple[bool, ...] | None = None) -> list[int]:
    """Per phase, the IPOPT iterations that ran its node model interpreted, over every process
    and run sharing the disk cache (mechanics.compiled.keyed_uses); `iterations` counted first
    for the `phases` flagged."""
    phases = phases or (False,) * len(nlp.node_functions)
    return [keyed_uses(node.name(), _key(node), iterations if ran else 0)
            for node, ran in zip(nlp.node_functions, phases)]


def cached_phases(nlp) -> list[bool]:
    """Per phase, whether its node model, compiled, is in the disk cache already (no C source
    generated: mechanics.compiled.keyed_cached; compiled as NodeDerivatives compiles it)."""
    return [all(keyed_cached(f"{node.name()}_{part}", _key(node), jacobian=k == 0) for k, part in enumerate(PARTS))
            for node in nlp.node_functions]


def node_indices(nlp, i: int, k: int) -> np.ndarray:
    """The decision vector's indices of node k of phase i's z (x, a, u, f, s, z, theta_td)."""
    b, name = nlp.blocks, nlp.phases[i].name
    out = []
    for key in ("X", "A", "U", "F", "S", "Z"):
        block = f"{key}_{name}"
        if block in b.offsets:
            rows = b.shapes[block][0]
            out.append(b.offsets[block] + k * rows + np.arange(rows))
    out.append(b.offsets[f"X_{nlp.phases[0].name}"] + np.arange(9))  # the touchdown state
    return np.concatenate(out)


def node_inputs(nlp, i: int, m: int, x: ca.MX) -> tuple[np.ndarray, ca.MX]:
    """Phase i's node indices (one column per node: node_indices) and its nodes' z (MX, a
    column each) in the decision vector x."""
    idx = np.column_stack([node_indices(nlp, i, k) for k in range(m)])
    return idx, ca.reshape(x[ca.DM(idx.ravel(order="F").tolist())], idx.shape[0], m)


def node_derivatives(nlp, compiled: bool | tuple[bool, ...] = False) -> list[NodeDerivatives]:
    """Each phase's NodeDerivatives (`compiled`: in C; per phase, or all)."""
    flags = compiled if isinstance(compiled, tuple) else (compiled,) * len(nlp.node_functions)
    return [NodeDerivatives(node, c) for node, c in zip(nlp.node_functions, flags)]


def problem(nlp, nodes: list[NodeDerivatives]) -> dict:
    """The NLP {"x", "p", "f", "g"} (nlpsol's problem) as StrideNLP.problem, each phase's node
    model called as its `nodes`' value on its nodes' z."""
    x, p = ca.MX.sym("x", nlp.blocks.size), ca.MX.sym("p", nlp.p.shape[0])
    G, ells = [], []
    for i, (d, m) in enumerate(zip(nodes, nlp.columns)):
        out = d.value.map(m)(node_inputs(nlp, i, m, x)[1], ca.repmat(p, 1, m))
        G.append(ca.vec(out[:d.rows, :]))
        ells.append(ca.vec(out[d.rows:, :]))
    f, g = nlp.rest(x, ca.vertcat(*ells), p)
    return {"x": x, "p": p, "f": f, "g": ca.vertcat(*G, g)}


def _scatter(values, rows, cols, shape) -> ca.MX:
    """The sparse matrix (MX) with values[t] at (rows[t], cols[t]), duplicates summed:
    one constant sparse product, A values, then cast to the pattern."""
    pattern, mapping = ca.Sparsity.triplet(shape[0], shape[1], list(rows), list(cols), True)
    A = ca.DM(ca.Sparsity.triplet(pattern.nnz(), len(mapping), list(mapping), list(range(len(mapping)))), 1.0)
    return ca.sparsity_cast(A @ values, pattern)


def _nonzeros(M: ca.MX) -> tuple[ca.MX, np.ndarray, np.ndarray]:
    """(the nonzeros of M as a column, their rows, their columns)."""
    r, c = M.sparsity().get_triplet()
    return M.nz[list(range(M.nnz()))], np.asarray(r), np.asarray(c)


def functions(nlp, nodes: list[NodeDerivatives] | None = None) -> dict:
    """{"grad_f", "jac_g", "hess_lag"}: nlpsol's derivative functions of `nlp` (module
    docstring), with its signatures: (x, p) -> (f, grad), (x, p) -> (g, jac), (x, p, lam_f,
    lam_g) -> triu(hess). MX graphs calling each phase's node derivatives (`nodes`, default
    SX) mapped over its nodes and the rest's (SX), their nonzeros scattered into the NLP's by
    constant sparse maps."""
    size, n_ell = nlp.blocks.size, nlp.ell.shape[0]
    x, p = ca.MX.sym("x", size), ca.MX.sym("p", nlp.p.shape[0])
    lam_f, lam_g = ca.MX.sym("lam_f"), ca.MX.sym("lam_g", len(nlp.lbg))
    value, grad_parts, rest_jac, rest_hess = _rest_derivatives(nlp)
    n_node = sum(e.shape[0] for e in nlp.node_rows.expr)
    G, ells, jac_nz, hess_nz, phases = [], [], [], [], []
    row, col = 0, 0  # the node rows and integrands before this phase
    for i, (d, m) in enumerate(zip(nodes or node_derivatives(nlp), nlp.columns)):
        idx, Z = node_inputs(nlp, i, m, x)
        out, J = d.jacobian.map(m)(Z, ca.repmat(p, 1, m))
        G.append(ca.vec(out[:d.rows, :]))
        ells.append(ca.vec(out[d.rows:, :]))
        nz, r, c = _nonzeros(J)
        k, j = c // idx.shape[0], c % idx.shape[0]
        out_rows = np.where(r < d.rows, row + k * d.rows + r, n_node + col + k * len(INTEGRANDS) + r - d.rows)
        jac_nz.append((nz, out_rows, idx[j, k]))
        phases.append((d, idx, Z, m, row, col))
        row, col = row + d.rows * m, col + len(INTEGRANDS) * m
    ell = ca.vertcat(*ells)
    both = _scatter(ca.vertcat(*[t[0] for t in jac_nz]), np.concatenate([t[1] for t in jac_nz]),
                    np.concatenate([t[2] for t in jac_nz]), (n_node + n_ell, size))
    J_G, L = both[:n_node, :], both[n_node:, :]
    f, g = value(x, ell, p)
    F_x, F_ell = grad_parts(x, ell, p)
    R_x, R_ell = rest_jac(x, ell, p)
    H_xx, H_xe, H_ee, dphi_dell = rest_hess(x, ell, p, lam_f, lam_g[n_node:])
    for d, idx, Z, m, row, col in phases:
        W = ca.vertcat(ca.reshape(lam_g[row:row + d.rows * m], d.rows, m),
                       ca.reshape(dphi_dell[col:col + len(INTEGRANDS) * m], len(INTEGRANDS), m))
        nz, r, c = _nonzeros(d.hessian.map(m)(Z, ca.repmat(p, 1, m), W))
        k = c // idx.shape[0]
        hess_nz.append((nz, idx[r, k], idx[c % idx.shape[0], k]))
    H_nodes = _scatter(ca.vertcat(*[t[0] for t in hess_nz]), np.concatenate([t[1] for t in hess_nz]),
                       np.concatenate([t[2] for t in hess_nz]), (size, size))
    cross = H_xe @ L
    H = H_xx + cross + cross.T + L.T @ H_ee @ L + H_nodes
    return {"grad_f": ca.Function("nlp_grad_f", [x, p], [f, F_x + L.T @ F_ell], ["x", "p"], ["f", "grad_f_x"]),
            "jac_g": ca.Function("nlp_jac_g", [x, p], [ca.vertcat(*G, g), ca.vertcat(J_G, R_x + R_ell @ L)],
                                 ["x", "p"], ["g", "jac_g_x"]),
            "hess_lag": ca.Function("nlp_hess_l", [x, p, lam_f, lam_g], [ca.triu(H)],
                                    ["x", "p", "lam_f", "lam_g"], ["triu_hess_gamma_x_x"])}


def _rest_derivatives(nlp) -> tuple[ca.Function, ...]:
    """The objective and the rows outside the nodes (StrideNLP.rest, expanded to SX), and their
    derivatives, as functions of (x, ell, p): (f, g), (F_x, F_ell), (R_x, R_ell), and of (x,
    ell, p, lam_f, lam_rest): (Phi_xx, Phi_x,ell, Phi_ell,ell, Phi_ell), Phi = lam_f f +
    lam_rest . g."""
    size = nlp.blocks.size
    x, ell, p = ca.SX.sym("x", size), ca.SX.sym("ell", nlp.ell.shape[0]), ca.SX.sym("p", nlp.p.shape[0])
    f, g = nlp.rest.expand()(x, ell, p)
    lam_f, lam = ca.SX.sym("lam_f"), ca.SX.sym("lam", g.shape[0])
    phi = lam_f * f + ca.dot(lam, g)
    H = ca.hessian(phi, ca.vertcat(x, ell))[0]
    args = [x, ell, p]
    return (ca.Function("rest_value", args, [f, g]),
            ca.Function("rest_gradient", args, [ca.gradient(f, x), ca.gradient(f, ell)]),
            ca.Function("rest_jacobian", args, [ca.jacobian(g, x), ca.jacobian(g, ell)]),
            ca.Function("rest_hessian", [*args, lam_f, lam],
                        [H[:size, :size], H[:size, size:], H[size:, size:], ca.gradient(phi, ell)]))
