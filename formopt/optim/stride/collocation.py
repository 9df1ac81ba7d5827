"""Direct collocation of the half stride (ocp.StrideProblem), built once, solved for any
parameters p = [speed (m/s), slope (rad), mu]; an imposed cadence through the bounds of the
half-period's row.

Decision variables, per phase of N intervals, one column per collocation point (N + 1 for the
trapezoid, 2N + 1 for Hermite-Simpson): X = (theta, theta') (18 rows), A = theta'' (9), U the
actuation's controls, Z its states (the muscles': collocated with X, rates actuation.rates(U);
continuous across the transitions, periodic with the legs swapped), F the contact forces (one per contact row), S the power split (work
objectives); the phase's duration T; per impact the impulse P (one per contact row after it;
the touchdown's also its post-impact velocity V_touchdown).

Each phase's node model is one CasADi Function of SX (ocp.NodeModel), mapped over its columns
(an MX graph; IPOPT's derivatives assembled node by node, derivatives.py); the transcription
(transcription.py's `Trapezoid`, `HermiteSimpson`: settings.transcription) gives the defects of x' = (theta',
theta'') and the quadrature of the integrands. Neither sees accelerations that alternate column
to column (problem.SMOOTHING says how that is closed).

Both converge from the generic guess in about 50-150 iterations (a Hermite-Simpson tried before
the node derivatives, with CasADi's own, stalled at dual infeasibility 1e14). The forward
simulation (`Stride.checks`) measures the transcription's error, the drift of the held contact
points too.
"""

from __future__ import annotations

import hashlib
import math
import pickle
import time
import warnings
from dataclasses import replace

import casadi as ca
import numpy as np

from ...mechanics.compiled import compiler, one_blas_thread
from ...mechanics.joint_space import GRAVITY, JOINTS, LIMIT_MARGIN, RANGES, THETA, JointSpace
from . import derivatives
from .contact import height
from .ipopt_options import MUSCLE_WARM_START, WARM_START, rung_options
from .layout import Blocks, Rows, Solved
from .ocp import INTEGRANDS, Impact, StrideProblem, periodicity, step_length
from .problem import RELEASE_DRIFT, StrideSettings
from .transcription import TRANSCRIPTIONS, steps, times

NX = len(THETA)
NU = len(JOINTS)
PARAMETERS = ("speed", "slope", "mu")
ACCELERATION = 1000.0  # rad/s^2 (m/s^2 for the hip): bound on theta''
TRUNK = (math.radians(-20.0), math.radians(45.0))  # rad, the trunk's lean (forward positive)
STATE_RATE = 15.0  # m/s and rad/s: bound on theta'
# The node models and their derivatives in C (derivatives.py, mechanics.compiled's disk cache):
# True, False or "auto" (numerics.compiled's words): compiled from an NLP's COMPILE_FROM-th solve
# on, when a C compiler is found. Compiled, the functions cost 1.8 instead of 17 ms an IPOPT
# iteration, a cold solve 0.98 instead of 2.34 s of CPU, but the first build costs 28 s (-O1;
# once per body and phase models, then from the cache); the paper's body, heel, 40 nodes,
# benchmarks/stride_speed.py, 2026-11-26. "auto" rents before it buys: it compiles once the
# chain's interpreted solves have cost about what the build does (28 s / 1.4 s saved a solve),
# so a long chain (a search at a larger spend, a map) ends compiled and a short one (a stride, a
# cadence curve) does not pay a build; a build in the disk cache already (the same body and phase
# models solved before) is used from the first solve, phase by phase. The rent is counted on disk
# too, per phase model, in IPOPT iterations (derivatives.phase_rent): short chains that come back
# (compare's band variants, 6 solves a trial, interpreted: 21.6 of T25's 58.4 s of CPU; the same
# runner's other trials) compile once they have run RENT_ITERATIONS interpreted over every run,
# about a phase's build (5-7 s of cc at -O1) at the 3-4 ms an iteration it costs interpreted
# (24 against 10-12 ms an iteration for four phases; compare_speed.py --stride T25, 2026-11-27).
# The iterates are the same to round-off (compare's stride section on RBDS001 T25, 2688
# iterations, all compiled against "auto" from the 20th solve, or phase by phase: the same
# numbers bit for bit, 2026-11-27).
COMPILED: bool | str = "auto"
COMPILE_FROM = 20
RENT_ITERATIONS = 2000


# IPOPT's derivatives are assembled node by node (derivatives.py), each phase's node model's own
# derivatives mapped over its nodes. Measured (paper body, heel, 40 nodes, tendons, 2-core
# machine with other work on it, 2026-11-25), build CPU and ms a call of grad_f / jac_g /
# hess_lag: assembled 0.35 s, 3.4 / 3.9 / 9.5; CasADi's own derivatives of the whole NLP
# expanded to SX 7.3 s, about 0.2 / 4 / 10.7; in MX 0.9 s, but 35 ms (jac_g) and 89 ms
# (hess_lag); the node derivatives inlined into one SX graph 1.7 s, 0.16 / 3.4 / 4.5.

class StrideNLP:
    """The half stride NLP of one body and settings: build once, solve for any parameters.
    `ipopt`: IPOPT options over the defaults; `compiled`: True, False or "auto", the node models
    and their derivatives in C (COMPILED, read at each build, when not given)."""

    def __init__(self, js: JointSpace, settings: StrideSettings, ipopt: dict | None = None,
                 compiled: bool | str | None = None):
        compiled = COMPILED if compiled is None else compiled  # the module's, read at each build
        if not isinstance(compiled, bool) and compiled != "auto":
            raise ValueError(f"compiled must be true, false or \"auto\", not {compiled!r}")
        start = time.perf_counter()
        self.js, self.settings, self.ipopt, self.compile = js, settings, ipopt, compiled
        self.ocp = StrideProblem(js, settings)
        self.mass, self.phases = self.ocp.mass, self.ocp.phases
        self.split = settings.node_split()
        self.transcription = TRANSCRIPTIONS[settings.transcription]
        self.columns = [self.transcription.columns(n) for n in self.split]  # per phase
        self.steps = [steps(n, settings.grading) for n in self.split]  # per phase, transcription.steps
        self.split_power = self.ocp.models[0].split
        self.touchdown_rows = self.ocp.touchdown.contact.rows
        self.blocks, self.rows = Blocks(), Rows()
        self.p = ca.MX.sym("p", len(PARAMETERS))
        self._declare()
        self.v = self.blocks.finish()
        self.period = ca.sum1(ca.vertcat(*[self.v[f"T_{ph.name}"] for ph in self.phases]))
        self.node_bounds: list = []  # per phase, its node rows' (lower, upper) (_node_function)
        self.node_functions = [self._node_function(i) for i in range(len(self.phases))]
        self._moment_functions = [self._moment_function(i) for i in range(len(self.phases))]
        self.terms: dict = dict.fromkeys((*INTEGRANDS, "impacts", "smoothing"), 0)
        # the node integrands' values, one column per node (ell: their stack, node by node)
        self.ell_sizes = [len(INTEGRANDS) * c for c in self.columns]
        self.ell = ca.MX.sym("ell", sum(self.ell_sizes))
        self.node_rows = Rows()
        self.node_integrands: list = []  # per phase, its nodes' integrands (MX, stacked)
        for i in range(len(self.phases)):
            self._phase(i)
        for i in range(1, len(self.phases)):
            self._transition(i)
        self._touchdown()
        self.period_row = self.rows.add(self.period, 0.0, np.inf)
        self._energy_rows()
        self.terms["impacts"] += self.terms["slide"]
        objective = self.ocp.objective(self.terms, self.p[0], self.period)
        x = self.blocks.vector()
        # the objective and every row but the nodes', as functions of (x, ell, p); ell = the
        # node integrands of x in the NLP (derivatives.py assembles its derivatives so)
        self.rest = ca.Function("rest", [x, self.ell, self.p], [objective, ca.vertcat(*self.rows.expr)],
                                ["x", "ell", "p"], ["f", "g"])
        f, g = self.rest(x, ca.vertcat(*self.node_integrands), self.p)
        self.problem = {"x": x, "p": self.p, "f": f,
                        "g": ca.vertcat(*self.node_rows.expr, g)}  # the NLP's expressions
        self.settings_key = hashlib.sha256(pickle.dumps(settings)).hexdigest()  # `layout`'s
        self.options = {**rung_options(settings), "max_iter": settings.max_iter, "tol": settings.tolerance,
                        **(ipopt or {})}
        self._solver: ca.Function | None = None
        self._warm_solver: ca.Function | None = None
        self._solver_compiled: tuple = ()  # per phase, whether _solver's node model and derivatives are C
        self._in_cache: list[bool] | None = None  # per phase, whether they are in the disk cache
        self._nlp = self.problem  # the solvers' problem (derivatives.problem when compiled)
        self.solves = 0  # IPOPT runs of this NLP
        self.lbg = np.concatenate(self.node_rows.lower + self.rows.lower)
        self.ubg = np.concatenate(self.node_rows.upper + self.rows.upper)
        self.build_s = time.perf_counter() - start

    def _energy_rows(self) -> None:
        """With springs, the held contacts' work W_c = int f . v_c dt and the energy budget B (the
        balance's integral less the impacts' and the climb's work), per body weight (m): the
        springs let the optimum draw energy from the transcription. StrideSettings.consistency_rows
        "exact": W_c = B = 0; "trapezoid": W_c <= 0 <= B (the transcription may absorb energy, not
        give it); "off": no row."""
        form = self.settings.consistency_rows
        if any(self.settings.tendons.values()) and form != "off":
            weight = self.mass * GRAVITY
            climb = weight * step_length(self.p[0], self.period) * ca.sin(self.p[1])
            ground, budget = self.terms["ground"] / weight, (self.terms["balance"] - climb) / weight
            if form == "exact":
                self.rows.add(ca.vertcat(ground, budget))
            else:
                self.rows.add(ground, -np.inf, 0.0)
                self.rows.add(budget, 0.0, np.inf)

    @property
    def compiled(self) -> bool:
        """Whether the next solve's node models and derivatives all run as C (`compiled_phases`)."""
        return all(self.compiled_phases)

    @property
    def compiled_phases(self) -> tuple[bool, ...]:
        """Per phase, whether the next solve's node model and derivatives run as C (`compile`:
        True; or "auto" when a C compiler is found: every phase from the NLP's COMPILE_FROM-th
        solve, before it those in the disk cache already, a phase model being shared by NLPs of
        one body (a strike's, a sliding touchdown's variant: all but one phase), and those
        whose model ran interpreted for RENT_ITERATIONS IPOPT iterations over every run sharing
        the disk cache (derivatives.phase_rent); "auto" becomes False, with a RuntimeWarning,
        when compiling fails)."""
        n = len(self.phases)
        if self.compile != "auto" or not _has_compiler():
            return (self.compile is True,) * n
        if self._in_cache is None:  # looked up once: a library in the cache costs nothing to use
            self._in_cache = derivatives.cached_phases(self)
        if self.solves >= COMPILE_FROM - 1:
            return (True,) * n
        rent = derivatives.phase_rent(self)  # this process's iterations and every other run's
        return tuple(c or r >= RENT_ITERATIONS for c, r in zip(self._in_cache, rent))

    @property
    def solver(self) -> ca.Function:
        """IPOPT on the NLP with its derivatives (derivatives.functions), built on first use and
        again when more phases become compiled; build_s counts it."""
        if self._solver is None or self._solver_compiled != self.compiled_phases:
            start = time.perf_counter()
            compiled = self.compiled_phases
            try:
                nodes = derivatives.node_derivatives(self, compiled)
            except RuntimeError as error:  # the C compiler failed: "auto" goes on interpreted
                if self.compile != "auto":
                    raise
                warnings.warn(f"the stride NLP's node models did not compile, solved interpreted: {error}",
                              RuntimeWarning, stacklevel=2)
                self.compile, compiled = False, (False,) * len(self.phases)
                nodes = derivatives.node_derivatives(self, compiled)
            self._solver_compiled = compiled
            self._nlp = derivatives.problem(self, nodes) if any(compiled) else self.problem
            one_blas_thread()
            self._solver = ca.nlpsol("stride", "ipopt", self._nlp, {
                "ipopt": self.options, "print_time": False, **derivatives.functions(self, nodes)})
            self._warm_solver = None  # it shares the cold solver's derivatives
            self.build_s += time.perf_counter() - start
        return self._solver

    # -- variables -------------------------------------------------------------------
    def _declare(self):
        """The decision variables' blocks (module docstring) with their bounds."""
        b, s = self.blocks, self.settings
        joints = [RANGES[j[:-2]] for j in JOINTS]
        lo_th = np.r_[-np.inf, 0.4, TRUNK[0], [lo - LIMIT_MARGIN for lo, _ in joints]]  # m, rad
        hi_th = np.r_[np.inf, 1.4, TRUNK[1], [hi + LIMIT_MARGIN for _, hi in joints]]
        x_lo, x_hi = np.r_[lo_th, [-STATE_RATE] * NX][:, None], np.r_[hi_th, [STATE_RATE] * NX][:, None]
        for model, c in zip(self.ocp.models, self.columns):
            k, act = model.phase.name, model.actuation
            b.add(f"X_{k}", (2 * NX, c), x_lo, x_hi)
            b.add(f"A_{k}", (NX, c), -ACCELERATION, ACCELERATION)
            b.add(f"U_{k}", (act.controls, c), *_column(act.bounds()))  # torques: N m / kg
            if act.states:
                b.add(f"Z_{k}", (act.states, c), *_column(act.state_bounds()))
            b.add(f"F_{k}", (len(model.contact.rows), c), *model.contact.force_bounds())  # BW
            b.add(f"T_{k}", (1, 1), *s.duration[k])
            if model.split:  # joint power split: [positive; negative] parts, W/kg
                b.add(f"S_{k}", (2 * NU, c), 0.0, np.inf)
        for i, transition in enumerate(self.ocp.transitions, 1):
            if isinstance(transition, Impact):
                b.add(f"P_{self.phases[i].name}", (len(transition.contact.rows), 1),
                      *transition.contact.impulse_bounds())
        b.add("P_touchdown", (len(self.touchdown_rows), 1), *self.ocp.touchdown.contact.impulse_bounds())
        b.add("V_touchdown", (NX, 1), -STATE_RATE, STATE_RATE)

    def impact_before(self, i: int) -> bool:
        """Whether phase i starts with an impact (a point added), not a release."""
        return i > 0 and isinstance(self.ocp.transitions[i - 1], Impact)

    # -- the node model and its transcription -------------------------------------------
    def _node_function(self, i: int) -> ca.Function:
        """Phase i's node model (ocp.NodeModel) as one SX Function: (x, a, u, f, s, theta_td,
        p) -> (its rows, its integrands (INTEGRANDS)); `node_bounds[i]` its rows' bounds."""
        model = self.ocp.models[i]
        x, a = ca.SX.sym("x", 2 * NX), ca.SX.sym("a", NX)
        u, f = ca.SX.sym("u", model.actuation.controls), ca.SX.sym("f", len(model.contact.rows))
        s = ca.SX.sym("s", 2 * NU if model.split else 0)
        z = ca.SX.sym("z", model.actuation.states)
        td, p = ca.SX.sym("theta_td", NX), ca.SX.sym("p", len(PARAMETERS))
        rows, integrands = model(self.js, x, a, u, f, s, z, td, p)
        self.node_bounds.append((np.concatenate(rows.lower), np.concatenate(rows.upper)))
        return ca.Function(f"node_{model.phase.name}", [x, a, u, f, s, z, td, p],
                           [ca.vertcat(*rows.expr), ca.vertcat(*[integrands[k] for k in INTEGRANDS])],
                           ["x", "a", "u", "f", "s", "z", "theta_td", "p"], ["rows", "integrands"])

    def _phase(self, i):
        """Phase i: its node model at every node (mapped), the interval defects, the
        integrals of its integrands and the smoothing term (the transcription's)."""
        name, n, c = self.phases[i].name, self.split[i], self.columns[i]
        X, A, U, F, T = (self.v[f"{key}_{name}"] for key in "XAUFT")
        S = self.v.get(f"S_{name}", ca.MX(0, c))
        Z = self.v.get(f"Z_{name}", ca.MX(0, c))
        td = self.v[f"X_{self.phases[0].name}"][:NX, 0]
        G, L = self.node_functions[i].map(c)(X, A, U, F, S, Z, ca.repmat(td, 1, c), ca.repmat(self.p, 1, c))
        lower, upper = self.node_bounds[i]
        lower = np.tile(lower[:, None], c)
        if i > 0 and not self.impact_before(i):
            self._release_heights(i, lower)
        self.node_rows.add(G, lower.ravel(order="F"), np.tile(upper, c))
        self.node_integrands.append(ca.vec(L))
        h, s = T / n, self.steps[i]  # the uniform interval and each one's over it (transcription.steps)
        rates = ca.vertcat(X[NX:, :], A, self.ocp.models[i].actuation.rates(U))
        self.rows.add(self.transcription.defects(ca.vertcat(X, Z), rates, h, s))
        start = sum(self.ell_sizes[:i])
        ell = ca.reshape(self.ell[start:start + self.ell_sizes[i]], len(INTEGRANDS), c)
        integrals = ell @ self.transcription.weights(h, s).T
        for k, key in enumerate(INTEGRANDS):
            self.terms[key] += integrals[k]
        smoothed = ca.vertcat(A, self.ocp.models[i].actuation.smoothed(U))
        self.terms["smoothing"] += self.transcription.smoothing(smoothed, h, s)

    def _release_heights(self, i: int, lower: np.ndarray) -> None:
        """Phase i's released points' heights at its first column, the phase before's held drift
        (O(h^2), a transcription error, not a motion): >= 0 in `lower` (its node rows' lower
        bounds, a column per column) with StrideSettings.consistency_rows "exact" and no moment
        dynamics; else free there, and with "trapezoid" and no moment dynamics a row >=
        -RELEASE_DRIFT h^2 instead, h the phase before's last interval (s), whatever the actuation
        (RELEASE_DRIFT was measured on torque+springs). With moment dynamics the drift's sign was a
        row with multipliers of 850 (trapezoid) to 1.85e4 (Hermite-Simpson) and Hermite-Simpson 40
        did not converge in 1000 iterations (RBDS001, 3.5 m/s, moment_time 0.04 s)."""
        form = self.settings.consistency_rows
        if form == "exact" and not self.settings.moment_time:
            return
        free = self.ocp.models[i].contact.free
        released = [k for k, point in enumerate(free) if point in self.phases[i - 1].points]
        lower[released, 0] = -np.inf
        if form == "trapezoid" and not self.settings.moment_time:
            h = self.v[f"T_{self.phases[i - 1].name}"] / self.split[i - 1] * self.steps[i - 1][-1]
            theta = self.v[f"X_{self.phases[i].name}"][:NX, 0]
            for k in released:
                self.rows.add(height(self.js, free[k], theta, self.p[1]) + RELEASE_DRIFT * h ** 2, 0.0, np.inf)

    def _transition(self, i):
        """Phase i-1 -> i: the same configuration, then an impact or a release (ocp)."""
        before, after = self.phases[i - 1].name, self.phases[i].name
        X0, X1 = self.v[f"X_{before}"][:, -1], self.v[f"X_{after}"][:, 0]
        self.rows.add(X1[:NX] - X0[:NX])
        if f"Z_{after}" in self.v:  # the actuation's states are continuous
            self.rows.add(self.v[f"Z_{after}"][:, 0] - self.v[f"Z_{before}"][:, -1])
        transition = self.ocp.transitions[i - 1]
        if isinstance(transition, Impact):
            T_c = transition.rows(self.rows, self.js, X0[:NX], X0[NX:], X1[NX:], self.v[f"P_{after}"],
                                  self.p, self.mass)
            self.terms["impacts"] += T_c
            self.terms["balance"] -= T_c
        else:
            transition.rows(self.rows, self.js, X0[:NX], X0[NX:], X1[NX:], self.v[f"F_{before}"][:, -1], self.p)

    def _touchdown(self):
        """L's touchdown at the flight's end, its impact and periodicity with the start."""
        end, start = self.v[f"X_{self.phases[-1].name}"][:, -1], self.v[f"X_{self.phases[0].name}"][:, 0]
        V = self.v["V_touchdown"]
        T_c = self.ocp.touchdown.rows(self.rows, self.js, end[:NX], end[NX:], V, self.v["P_touchdown"],
                                      self.p, self.mass)
        self.terms["impacts"] += T_c
        self.terms["balance"] -= T_c
        self.rows.add(periodicity(end[:NX], V, start, step_length(self.p[0], self.period), self.p[1]))
        first, last = self.phases[0].name, self.phases[-1].name
        if f"Z_{first}" in self.v:  # the actuation's states, legs swapped
            self.rows.add(self.ocp.models[0].actuation.swap(self.v[f"Z_{last}"][:, -1]) - self.v[f"Z_{first}"][:, 0])
        self.rows.add(start[0])

    def integral(self, key: str) -> ca.MX:
        """The NLP's integral `key` (INTEGRANDS, "impacts", "smoothing") as an expression of
        the decision vector and the parameters (the node integrands put in for ell)."""
        x = self.blocks.vector()
        term = ca.Function("term", [x, self.ell, self.p], [self.terms[key]])
        return term(x, ca.vertcat(*self.node_integrands), self.p)

    def times(self, i: int, T: float) -> np.ndarray:
        """Phase i's columns' times (s from its start) for a duration T (s): transcription.times
        on its mesh (the settings' grading)."""
        return times(self.transcription, T, self.split[i], self.settings.grading)

    def integrands(self, blocks: dict, parameters) -> list[tuple[np.ndarray, np.ndarray]]:
        """Per phase, the node integrands of a numeric solution (len(INTEGRANDS) x columns) and
        the transcription's quadrature weights (columns): what the NLP integrates, evaluated at its
        nodes."""
        out = []
        td = blocks[f"X_{self.phases[0].name}"][:NX, 0]
        p = np.array([parameters["speed"], parameters["slope"], parameters["mu"]])
        for i, (phase, n, c) in enumerate(zip(self.phases, self.split, self.columns)):
            name = phase.name
            S = blocks.get(f"S_{name}", np.zeros((0, c)))
            Z = blocks.get(f"Z_{name}", np.zeros((0, c)))
            _, L = self.node_functions[i].map(c)(blocks[f"X_{name}"], blocks[f"A_{name}"], blocks[f"U_{name}"],
                                                blocks[f"F_{name}"], S, Z, np.repeat(td[:, None], c, 1),
                                                np.repeat(p[:, None], c, 1))
            w = np.asarray(self.transcription.weights(blocks[f"T_{name}"].item() / n, self.steps[i]), float).ravel()
            out.append((np.asarray(L, float), w))
        return out

    def moments(self, blocks: dict, i: int) -> tuple[np.ndarray, np.ndarray]:
        """(active, passive) joint moments (N m, each 6 x columns, JOINTS) of phase i in a
        numeric solution: the actuation's, and its springs' (the tendons in parallel) with the
        touchdown as their rest."""
        name, c = self.phases[i].name, self.columns[i]
        td = blocks[f"X_{self.phases[0].name}"][:NX, :1]
        active, passive = self._moment_functions[i](blocks.get(f"Z_{name}", np.zeros((0, c))), blocks[f"U_{name}"],
                                                   blocks[f"X_{name}"][:NX], np.repeat(td, c, 1))
        return np.asarray(active, float), np.asarray(passive, float)

    def _moment_function(self, i: int) -> ca.Function:
        """Phase i's (z, u, theta, theta_td) -> (active, passive) moments, mapped over its columns."""
        model = self.ocp.models[i]
        act = model.actuation
        z, u = ca.SX.sym("z", act.states), ca.SX.sym("u", act.controls)
        theta, td = ca.SX.sym("theta", NX), ca.SX.sym("theta_td", NX)
        return ca.Function("moments", [z, u, theta, td], [act.active(z, u),
                                                          act.passive(theta, td, bool(model.phase.points))]
                           ).map(self.columns[i])

    def variant(self, ipopt: dict | None = None, **changes) -> StrideNLP:
        """The NLP of the same body, IPOPT options (`ipopt` over them) and compilation with
        settings changed (e.g. touchdown="slide"), built once and kept."""
        key = tuple(sorted((k, repr(v)) for k, v in {**changes, " ipopt": ipopt}.items()))  # values may be dicts
        if not hasattr(self, "_variants"):
            self._variants: dict = {}
        if key not in self._variants:
            self._variants[key] = StrideNLP(self.js, replace(self.settings, **changes),
                                            {**(self.ipopt or {}), **(ipopt or {})}, self.compile)
        return self._variants[key]

    # -- solve -----------------------------------------------------------------------
    def _with_power_split(self, guess: dict) -> dict:
        """The guess with the power split (S_*) of its own moments and rates where it has none
        (a solution of an objective without the split, as a warm start)."""
        missing = [i for i, p in enumerate(self.phases) if self.split_power and f"S_{p.name}" not in guess]
        if not missing:
            return guess
        guess = dict(guess)
        for i in missing:
            name = self.phases[i].name
            power = -np.asarray(guess[f"U_{name}"]) * np.asarray(guess[f"X_{name}"])[NX + 3:]
            guess[f"S_{name}"] = np.vstack([np.maximum(power, 0), np.maximum(-power, 0)])
        return guess

    @property
    def layout(self) -> tuple:
        """What a warm start with multipliers needs to match: the settings, the block names and
        the number of rows. Another body of the same settings matches: its solution is a
        neighbouring problem's (a compare band's mass +-5 %, RBDS001 at 3.58 m/s, 30 nodes:
        9-19 iterations and 0.19-0.41 s of CPU from it against 12-52 and 0.29-1.47 s from its
        primal values alone, the same optima to 5e-6; 2026-11-27)."""
        return self.settings_key, tuple(self.blocks.names), len(self.lbg)

    def solve(self, guess: dict, speed: float, slope: float = 0.0, mu: float = 0.8,
              cadence: float | None = None) -> Solved:
        """Solve from a guess (blocks by name, or a previous Solved's blocks); `cadence`
        (steps/min) imposes the half-period 60 / cadence."""
        return self._run(self.solver, {"x0": self.blocks.join(self._with_power_split(guess))},
                         speed, slope, mu, cadence)

    def resolve(self, previous: Solved, speed: float, slope: float = 0.0, mu: float = 0.8,
                cadence: float | None = None) -> Solved:
        """Solve from a solution of this NLP (its layout; or another body's) at neighbouring
        parameters, with its multipliers (IPOPT's warm start, WARM_START, the muscles' barrier from
        MUSCLE_WARM_START; the solver built on first use, with the
        cold solver's derivative functions: 0.2 s instead of 2.7 s at 22 nodes); from
        its primal values alone (`solve`) when that fails."""
        if previous.layout != self.layout or previous.lam_x is None:
            raise ValueError("resolve: the previous solution is not one of this NLP's (solve from its blocks)")
        solver = self.solver  # built or compiled first: the warm solver shares its derivatives
        if self._warm_solver is None:  # the cold solver's derivatives, not derived again
            start = time.perf_counter()
            shared = {k: solver.get_function(f"nlp_{f}")
                      for k, f in (("grad_f", "grad_f"), ("jac_g", "jac_g"), ("hess_lag", "hess_l"))}
            self._warm_solver = ca.nlpsol("stride_warm", "ipopt", self._nlp, {
                "ipopt": {**self.options, **WARM_START,
                          **(MUSCLE_WARM_START if self.settings.muscles is not None else {})},
                "print_time": False, **shared})
            self.build_s += time.perf_counter() - start
        got = self._run(self._warm_solver, {"x0": previous.x, "lam_x0": previous.lam_x,
                                            "lam_g0": previous.lam_g}, speed, slope, mu, cadence)
        return got if got.success else self.solve(previous.blocks, speed, slope, mu, cadence)

    def _run(self, solver, start: dict, speed, slope, mu, cadence) -> Solved:
        """One IPOPT run of `solver` from `start` (x0 and maybe multipliers)."""
        lbg, ubg = self.lbg.copy(), self.ubg.copy()
        k = sum(len(e) for e in self.node_rows.lower + self.rows.lower[:self.period_row])
        if cadence is not None:
            lbg[k] = ubg[k] = 60.0 / cadence
        b = self.blocks
        clock = time.perf_counter()
        self.solves += 1
        out = solver(**start, p=np.array([speed, slope, mu]), lbx=np.concatenate(b.lower),
                     ubx=np.concatenate(b.upper), lbg=lbg, ubg=ubg)
        seconds = time.perf_counter() - clock
        stats = solver.stats()
        if self.compile == "auto" and not all(self._solver_compiled) and _has_compiler():  # "auto"'s rent, on disk
            derivatives.phase_rent(self, int(stats["iter_count"]), tuple(not c for c in self._solver_compiled))
        x = np.asarray(out["x"], float).ravel()
        return Solved(blocks=b.split(x), success=bool(stats["success"]),
                      status=str(stats["return_status"]), iterations=int(stats["iter_count"]),
                      solve_s=seconds, objective=float(out["f"]), x=x,
                      lam_g=np.asarray(out["lam_g"], float).ravel(),
                      parameters={"speed": speed, "slope": slope, "mu": mu, "cadence": cadence},
                      lam_x=np.asarray(out["lam_x"], float).ravel(), layout=self.layout)


def _has_compiler() -> bool:
    """Whether a C compiler is found (mechanics.compiled.compiler)."""
    try:
        compiler()
    except RuntimeError:
        return False
    return True


def _column(bounds) -> tuple[np.ndarray, np.ndarray]:
    """(lower, upper), each a scalar or one value per row, as columns (broadcast over nodes)."""
    return tuple(np.asarray(b, float).reshape(-1, 1) for b in bounds)  # type: ignore[return-value]


_BUILT: dict[str, StrideNLP] = {}  # the last NLPS_KEPT NLPs built, by what they hold
NLPS_KEPT = 4  # a compare band alternates a few bodies and objectives; each NLP holds its solver


def build(body, settings: StrideSettings) -> StrideNLP:
    """The stride NLP of a body (mechanics.body.Body) and settings, built once per process and
    kept while it is among the last NLPS_KEPT asked for (keyed by everything it holds: the body,
    the settings and COMPILED)."""
    key = hashlib.sha256(pickle.dumps((body, settings, COMPILED))).hexdigest()
    nlp = _BUILT.pop(key, None) or StrideNLP(JointSpace(body), settings)
    _BUILT[key] = nlp  # the most recent last
    while len(_BUILT) > NLPS_KEPT:
        _BUILT.pop(next(iter(_BUILT)))
    return nlp
