"""Checks of a solved half stride against independent methods.

- `impact_check`: each impact's T_c by the joint-space projection at the solution's state
  against formopt's own impact map on the natural-coordinate model (mechanics.impact.projection
  with q = q(theta), q' = J theta'), and the Coulomb law's mode (mechanics.contact) there; a
  sliding touchdown's against contact.coulomb's T_c (its sliding mode).
- `forward`: the optimal joint moments (piecewise linear) integrated forward phase by phase
  (CVODES's Adams method through CasADi, rtol 1e-10: `integrator`) through the same contact
  sequence and phase durations, with the exact impact maps (a slide with its force on the
  cone's edge); the largest state difference at the nodes is the transcription's error (each
  phase from the NLP's state at its start), and what it grows to open loop; over a slide,
  whether the slip keeps its sign and when it stops. The muscle rung replays its excitations
  through the muscles instead (`forward`).
- `drift`: how far the held contact points moved (m) over each phase.
- `swing_clearance`: the swing foot's least height (m) over the stance phases' nodes, which
  the NLP holds at or above StrideSettings.clearance (contact.RigidContact.swing).
"""

from __future__ import annotations

import threading
import weakref

import casadi as ca
import numpy as np

from ...mechanics import contact
from ...mechanics.impact import projection
from ...mechanics.joint_space import POINTS, THETA, JointSpace
from .actuation import MuscleDriven
from .collocation import NU, NX, StrideNLP
from .contact import height, rows_kinematics
from .layout import held_rows
from .ocp import periodicity, step_length
from .problem import other_leg

# the replays' rtol and atol (`integrator`): their figures within 1e-8 rad of scipy's DOP853 at
# 1e-10 and LSODA at 1e-8 (tests/optim/stride/test_forward.py), far inside the check's 0.1 rad
TOLERANCE = 1e-10
SLIP_STEPS = 400  # a sliding phase's uniform steps on which its slip is read (`grid`, `_slip`)


def force_directions(js: JointSpace, rows, theta, slope, sliding: tuple | None = None):
    """(G, D): the held rows of J_c (rows x 9, `held_rows`; J_c of contact rows
    ((point, "t" | "n"), ...)) and the directions of their forces, as CasADi matrices of a
    numeric or symbolic theta. `sliding` = (point, s, mu): that point's "t" row is not held and
    its normal row's force acts along J_n - s mu J_t (on the cone's edge, against the slip s);
    without it G = D = J_c."""
    Jc = rows_kinematics(js, rows, theta, ca.DM.zeros(NX), slope)[0]
    point, slip, mu = sliding or ("", 0, 0.0)
    held = held_rows(rows, point)
    G = Jc[held, :]
    D = ca.vertcat(*[Jc[k, :] - (slip * mu * Jc[rows.index((point, "t")), :]
                                 if sliding and rows[k] == (point, "n") else 0) for k in held])
    return G, D


def joint_impact(js: JointSpace, rows, theta, thetad, slope, sliding: tuple | None = None):
    """(theta'+, impulse (N s, per held row), T_c (J)) in joint coordinates:
    p = -(G M^-1 D^T)^-1 G theta'-, theta'+ = theta'- + M^-1 D^T p (`force_directions`: the
    sticking projection, or Coulomb's sliding mode with `sliding` = (point, s, mu))."""
    M = np.asarray(js.mass(theta), float)
    G, D = (np.asarray(ca.DM(m), float) for m in force_directions(js, rows, theta, slope, sliding))
    Minv_DT = np.linalg.solve(M, D.T)
    p = -np.linalg.solve(G @ Minv_DT, G @ thetad)
    plus = thetad + Minv_DT @ p
    return plus, p, 0.5 * thetad @ M @ thetad - 0.5 * plus @ M @ plus


def impact_check(js: JointSpace, rows, theta, thetad, slope, mu, sliding: tuple | None = None) -> dict:
    """The joint-space impact against formopt's natural-coordinate impact map, and the
    Coulomb mode (contact.coulomb for one point, contact.velocity_level for a flat foot).
    Sticking: against the projection (mechanics.impact); `sliding` = (point, s, mu)
    (Coulomb's sliding mode): against contact.coulomb's T_c at the same state."""
    model = js.model
    plus, p_held, T_c = joint_impact(js, rows, theta, thetad, slope, sliding)
    p = np.zeros(len(rows))
    p[held_rows(rows, sliding[0] if sliding else "")] = p_held
    if sliding:
        point, slip, _ = sliding
        p[rows.index((point, "t"))] = -slip * mu * p[rows.index((point, "n"))]
    q = np.asarray(js.q(theta), float).ravel()
    qd = np.asarray(js.J(theta), float) @ thetad
    points = tuple(dict.fromkeys(POINTS[pt] for pt, _ in rows))
    C = model.contact_rows(points, slope, tangential=points[:1])
    W = contact.admissible_inverse_inertia(ca.DM(model.M_inv), model.constraint_jacobian(ca.DM(q)))
    W_c, v0 = ca.DM(C) @ W @ ca.DM(C).T, ca.DM(C) @ qd
    law = contact.coulomb if len(points) == 1 else contact.velocity_level
    p_coulomb, mode, slip_after = law(W_c, v0, mu)
    T_c_coulomb = float(contact.absorbed(W_c, v0, p_coulomb))
    reference = T_c_coulomb if sliding else float(projection(model, ca.DM(q), ca.DM(qd), C)["T_c"])
    normal = sum(p[k] for k, (_, a) in enumerate(rows) if a == "n")
    tangential = sum(p[k] for k, (_, a) in enumerate(rows) if a == "t")
    return {"T_c": T_c, "T_c_formopt": reference, "difference_J": abs(T_c - reference),
            "impulse_t": float(tangential), "impulse_n": float(normal),
            "mu_c": abs(tangential) / normal if normal > 0 else None,
            "coulomb_mode": contact.MODES[int(mode)], "T_c_coulomb": T_c_coulomb,
            "coulomb_slip_mps": float(slip_after), "theta_d_plus": plus}


def accelerations(nlp: StrideNLP, i: int) -> ca.Function:
    """theta'' (9) of the constrained equations of motion in `phase`, a Function of
    (theta (9), theta' (9), active moments (N m, 6), theta at touchdown (9, the tendons'
    rest), slope (rad), mu): [M -D^T; G 0] [theta''; f] = [g + passive - c - tau; -dJ/dt theta']
    (`force_directions`: a sliding point's force on the cone's edge, against the slip
    settings.slip) in phase i; tau adds the actuation's passive moments (the tendons)."""
    js = nlp.js
    th, thd, td = ca.SX.sym("theta", NX), ca.SX.sym("thetad", NX), ca.SX.sym("theta_td", NX)
    tau, slope, mu = ca.SX.sym("tau", NU), ca.SX.sym("slope"), ca.SX.sym("mu")
    phase = nlp.phases[i]
    moments = ca.vertcat(0, 0, 0, tau + nlp.ocp.models[i].actuation.passive(th, td, bool(phase.points)))
    rhs = js.gravity(th) + nlp.ocp.models[i].actuation.joint_passive(js, th) - js.bias(th, thd) - moments
    M, rows = js.mass(th), phase.rows
    if rows:
        sliding = (phase.sliding, nlp.settings.slip, mu) if phase.sliding else None
        G, D = force_directions(js, rows, th, slope, sliding)
        held = held_rows(rows, phase.sliding)
        drift = ca.vertcat(*[js.points[pt](th, thd, slope)[3][0 if a == "t" else 1] for pt, a in rows])[held]
        K = ca.blockcat([[M, -D.T], [G, ca.SX.zeros(len(held), len(held))]])
        thdd = ca.solve(K, ca.vertcat(rhs, -drift))[:NX]
    else:
        thdd = ca.solve(M, rhs)
    return ca.Function("accelerations", [th, thd, tau, td, slope, mu], [thdd],
                       ["theta", "thetad", "tau", "theta_td", "slope", "mu"], ["thetadd"])


def muscle_dynamics(nlp: StrideNLP, i: int) -> ca.Function:
    """[theta', theta'', z'] of the muscle-driven body (actuation.MuscleDriven) in phase i, a
    Function of (x = [theta, theta'] (18), z (the muscles' states), u (the controls), theta at
    touchdown (9), slope (rad), mu): the tendon forces' moments and the reserves
    (MuscleDriven.active) through `accelerations`, and the states' rates of the excitations
    (MuscleDriven.forward_rates)."""
    act = nlp.ocp.models[i].actuation
    assert isinstance(act, MuscleDriven), "muscle_dynamics: the phase is not muscle-driven"
    x, z, u = ca.MX.sym("x", 2 * NX), ca.MX.sym("z", act.states), ca.MX.sym("u", act.controls)
    td, slope, mu = ca.MX.sym("theta_td", NX), ca.MX.sym("slope"), ca.MX.sym("mu")
    thdd = accelerations(nlp, i)(x[:NX], x[NX:], act.active(z, u), td, slope, mu)
    rates = ca.vertcat(x[NX:], thdd, act.forward_rates(x[:NX], x[NX:], z, u))
    return ca.Function("muscle_dynamics", [x, z, u, td, slope, mu], [rates],
                       ["x", "z", "u", "theta_td", "slope", "mu"], ["rates"])


def replay(nlp: StrideNLP, i: int, excitations: bool) -> ca.Function:
    """Phase i's forward simulation, a CasADi integrator built once per NLP and thread and kept
    with the NLP: `integrator` on the phase's `grid`. One per thread: two threads calling one
    CVODES integrator at once crash the process (CasADi 3.8.2; a Dask worker runs its tasks in
    threads, and collocation.build shares an NLP among them)."""
    replays = _REPLAYS.setdefault(nlp, {})
    key = (i, excitations, threading.get_ident())
    if key not in replays:
        replays[key] = integrator(nlp, i, excitations, grid(nlp, i)[0])
    return replays[key]


_REPLAYS: weakref.WeakKeyDictionary = weakref.WeakKeyDictionary()  # `replay`'s, per NLP (and thread)


def integrator(nlp: StrideNLP, i: int, excitations: bool, fractions: np.ndarray) -> ca.Function:
    """Phase i's forward simulation as a CasADi integrator: y = [theta, theta'] with the active
    moments replayed (`accelerations`), or (`excitations`) y = [theta, theta', z] with the
    muscles' excitations and reserves replayed (`muscle_dynamics`), over the phase's normalised
    time s = t / T, dy/ds = T f(y, u(s)), its states at the `fractions` of T (0 first, 1 last).
    The controls are linear between the columns, u = a_k + b_k s on interval k: the input
    [a_k; b_k] (`controls`), CVODES restarting where it changes (at the columns, where u' jumps).
    CVODES's Adams-Moulton (variable step and order, functional iteration; rtol = atol =
    TOLERANCE): a method independent of the collocation, in C but for the right-hand side
    (CasADi's virtual machine). Not BDF: its Newton iterations need the right-hand side's
    Jacobian, ten times its cost (a 24-node heel strike's check took 0.35 s of CPU against 0.085
    s, the muscle stride's 1.13 s against 0.84: benchmarks/forward_speed.py's cases). Its call:
    x0 = y(0), p = [T, theta at touchdown (9), slope, mu], u = `controls`."""
    act = nlp.ocp.models[i].actuation
    sym = ca.MX.sym if excitations else ca.SX.sym  # the muscles' right-hand side holds a rootfinder
    states, inputs = (2 * NX + act.states, act.controls) if excitations else (2 * NX, NU)
    y, ab, s, p = sym("y", states), sym("ab", 2 * inputs), sym("s"), sym("p", NX + 3)
    u = ab[:inputs] + s * ab[inputs:]
    args = (p[1:NX + 1], p[NX + 1], p[NX + 2])
    if excitations:
        rates = muscle_dynamics(nlp, i)(y[:2 * NX], y[2 * NX:], u, *args)
    else:
        rates = ca.vertcat(y[NX:], accelerations(nlp, i)(y[:NX], y[NX:], u, *args))
    dae = {"x": y, "u": ab, "p": p, "t": s, "ode": p[0] * rates}
    return ca.integrator(f"replay_{nlp.phases[i].name}", "cvodes", dae, 0.0, fractions[1:],
                         {"abstol": TOLERANCE, "reltol": TOLERANCE, "linear_multistep_method": "adams",
                          "nonlinear_solver_iteration": "functional", "disable_internal_warnings": True,
                          "show_eval_warnings": False})


def grid(nlp: StrideNLP, i: int) -> tuple[np.ndarray, np.ndarray]:
    """(fractions, where the columns are in them): the fractions of phase i's duration its
    `replay` reports states at, its columns' (nlp.times), and for a sliding phase SLIP_STEPS + 1
    uniform ones too (`_slip`)."""
    columns = nlp.times(i, 1.0)
    if not nlp.phases[i].sliding:
        return columns, np.arange(len(columns))
    fine = np.linspace(0.0, 1.0, SLIP_STEPS + 1)
    fractions = np.union1d(columns, fine[np.abs(fine[:, None] - columns).min(axis=1) > 1e-9])  # none beside a column
    return fractions, np.searchsorted(fractions, columns)


def controls(nlp: StrideNLP, i: int, U: np.ndarray, fractions: np.ndarray) -> np.ndarray:
    """The `integrator`'s input of node values U (columns at nlp.times): for each step of
    `fractions`, [a_k; b_k] of the interval k holding it, U linear there, a_k + b_k s."""
    columns = nlp.times(i, 1.0)
    b = np.diff(U, axis=1) / np.diff(columns)
    a = U[:, :-1] - b * columns[:-1]
    k = np.clip(np.searchsorted(columns, fractions[1:], side="left") - 1, 0, len(columns) - 2)
    return np.vstack([a[:, k], b[:, k]])


def replayed(nlp: StrideNLP, i: int, blocks: dict, parameters: dict, excitations: bool,
             start: np.ndarray, fractions: np.ndarray | None = None) -> np.ndarray | None:
    """Phase i's states along its replay from `start` (y at its start), a column per point of
    its `grid` (the NLP's kept `replay`), or of `fractions` of its duration (0 first, 1 last: an
    `integrator` built for them); None where the start is not finite or the integration fails
    (CVODES, or the tendon rates' Newton in the right-hand side, not converging)."""
    if not np.isfinite(start).all():
        return None
    name = nlp.phases[i].name
    U = blocks[f"U_{name}"] if excitations else nlp.moments(blocks, i)[0]
    p = np.r_[blocks[f"T_{name}"].item(), blocks[f"X_{nlp.phases[0].name}"][:NX, 0],
              parameters["slope"], parameters["mu"]]
    if fractions is None:
        run, fractions = replay(nlp, i, excitations), grid(nlp, i)[0]
    else:
        run = integrator(nlp, i, excitations, fractions)
    try:
        path = run(x0=start, p=p, u=controls(nlp, i, U, fractions))["xf"]
    except RuntimeError:
        return None
    return np.column_stack([start, np.asarray(path, float)])


def forward(nlp: StrideNLP, blocks: dict, parameters: dict) -> dict:
    """Integrate the optimal controls forward (module docstring), twice: open loop over the
    whole half stride (`theta`, `thetad`, `per_phase_theta`: the largest node differences, m
    or rad and m/s or rad/s), and phase by phase from the NLP's state at each phase's start
    (`reset_theta`, `reset_per_phase`); `periodicity`: the open-loop post-touchdown state
    against the start; `slip_mps`: over a sliding phase (from its NLP start), the least and
    the largest s v_t of the sliding point on a fine grid (the slip held if the least is not
    below zero beyond the integration's error), and its v_t at the phase's end.
    The muscle rung (actuation.MuscleDriven) replays its controls, the excitations (and the
    reserves), through the activation dynamics and the Hill equilibrium, its activations and
    tendon forces states of the simulation: a muscle resists a departure from its path
    (force-length-velocity) where a moment replayed as a function of time does not (van Soest &
    Bobbert 1993, Biol Cybern 69:195: a simulated jump far less sensitive to perturbations
    under open-loop stimulation than under open-loop joint moments), so its strides are judged
    on that; their net moments replayed phase by phase stay a figure (`moments_reset_theta`,
    `moments_reset_per_phase`). `parameters`: speed, slope, mu (Solved.parameters)."""
    muscles = isinstance(nlp.ocp.models[0].actuation, MuscleDriven)
    out = _simulate(nlp, blocks, parameters, excitations=muscles)
    if muscles:
        moments = _simulate(nlp, blocks, parameters, excitations=False, open_loop=False)
        out.update(moments_reset_theta=moments["reset_theta"], moments_reset_per_phase=moments["reset_per_phase"])
    return out


def _simulate(nlp: StrideNLP, blocks: dict, parameters: dict, excitations: bool, open_loop: bool = True) -> dict:
    """`forward`'s figures of one replay (`replayed`: the moments' or the excitations'), phase
    by phase and (`open_loop`) over the half stride; an integration that fails counts as an
    infinite error (open loop, so does what follows it)."""
    js, slope, mu, slip = nlp.js, parameters["slope"], parameters["mu"], nlp.settings.slip
    nodes = [np.vstack([blocks[f"X_{p.name}"]] + ([blocks[f"Z_{p.name}"]] if excitations else [])) for p in nlp.phases]
    state = nodes[0][:, 0].copy()
    errors: list[np.ndarray] = []
    reset: list[np.ndarray] = []
    slips: dict = {}
    for i, phase in enumerate(nlp.phases):
        Y, (fractions, columns) = nodes[i], grid(nlp, i)
        if nlp.impact_before(i) and np.isfinite(state).all():  # an impact starts the phase
            state[NX:2 * NX] = joint_impact(js, phase.rows, state[:NX], state[NX:2 * NX], slope)[0]
        for start, record in ([(state, errors)] if open_loop else []) + [(Y[:, 0], reset)]:
            path = replayed(nlp, i, blocks, parameters, excitations, start)
            record.append(np.full(2 * NX, np.inf) if path is None else np.abs(path[:2 * NX, columns] - Y[:2 * NX]).max(axis=1))
            if record is errors:
                state = np.full_like(state, np.nan) if path is None else path[:, -1]
            elif phase.sliding and path is not None:
                slips = _slip(js, phase.sliding, path, fractions * blocks[f"T_{phase.name}"].item(), slope, slip)
    res = np.array(reset)
    out = {"reset_theta": float(res[:, :NX].max()), "reset_per_phase": [float(e) for e in res[:, :NX].max(axis=1)], **slips}
    if open_loop:
        touchdown = (other_leg(nlp.phases[0].sliding), slip, mu) if nlp.phases[0].sliding else None
        period_error = np.inf
        if np.isfinite(state).all():
            plus = joint_impact(js, nlp.touchdown_rows, state[:NX], state[NX:2 * NX], slope, touchdown)[0]
            step = step_length(parameters["speed"], half_period(nlp, blocks))
            period_error = np.abs(np.asarray(periodicity(state[:NX], plus, nodes[0][:2 * NX, 0], step, slope), float)).max()
        err = np.array(errors)
        out.update(theta=float(err[:, :NX].max()), thetad=float(err[:, NX:].max()),
                   per_phase_theta=[float(e) for e in err[:, :NX].max(axis=1)], periodicity=float(period_error))
    return out


def _slip(js: JointSpace, point: str, path: np.ndarray, times: np.ndarray, slope: float, slip: int) -> dict:
    """s v_t (m/s) of a sliding point along a simulated phase (`path`: its states at `times`, s,
    the first 2 NX rows theta and theta'; `grid`'s: SLIP_STEPS + 1 uniform steps and the columns):
    its least and largest before it first stops, v_t at the phase's end, and when it first stops
    (`slip_stop_s`, s; the phase's duration if it slides through; the NLP's slide stops at its end)."""
    T = float(times[-1])
    v = slip * np.array([float(js.points[point](x[:NX], x[NX:2 * NX], slope)[1][0]) for x in path.T])
    stopped = np.flatnonzero(v <= 0.0)
    k = stopped[0] if stopped.size else len(v)
    stop = T if k == len(v) else float(np.interp(0.0, [v[k], v[k - 1]], [times[k], times[k - 1]])) if k else 0.0
    return {"slip_min_mps": float(v[:k].min()) if k else 0.0, "slip_max_mps": float(v.max()),
            "slip_end_mps": float(slip * v[-1]), "slip_stop_s": stop, "slip_duration_s": T}


def half_period(nlp: StrideNLP, blocks: dict) -> float:
    """The half-period (s): the phases' summed durations."""
    return sum(blocks[f"T_{p.name}"].item() for p in nlp.phases)


def drift(nlp: StrideNLP, blocks: dict, slope: float) -> float:
    """Largest displacement (m) of a held contact point over a phase (zero if exact; a
    sliding point's normal displacement)."""
    worst = 0.0
    for phase in nlp.phases:
        X = blocks[f"X_{phase.name}"]
        for point in phase.points:
            r0, r1 = (np.asarray(nlp.js.points[point](X[:NX, k], np.zeros(NX), slope)[0], float).ravel()
                      for k in (0, -1))
            if point == phase.sliding:  # it slides along the ground: its normal drift only
                worst = max(worst, abs((r1 - r0) @ np.array([-np.sin(slope), np.cos(slope)])))
            else:
                worst = max(worst, float(np.hypot(*(r1 - r0))))
    return worst


def swing_clearance(nlp: StrideNLP, blocks: dict, slope: float) -> float:
    """The least height (m) above the ground of the swing leg's points (heel and forefoot of the
    leg with no point held) over the nodes of the phases with contact rows."""
    return min(float(height(nlp.js, point, X[:NX, k], slope))
               for model in nlp.ocp.models for X in [blocks[f"X_{model.phase.name}"]]
               for point in model.contact.swing for k in range(X.shape[1]))


# A runner's stance knee flexes to about 40 deg at its deepest: RBDS001 42.2 / 42.2 / 43.6 deg at
# 2.5 / 3.5 / 4.5 m/s (the data set's own processing, data/rbds/RBDS001processed.txt), 39.0 deg
# at 3.5 m/s and RIC's runner 36.5 deg (formopt's measure, the mean cycles of RBDS001runT35.c3d and
# 20160226T120637_run.c3d; problems/stance_knee.py prints them). A stride whose stance knee
# flexes beyond CROUCH_DEG (half again a runner's) is a crouched run, far from a runner's,
# whatever its cost says (`unlike_a_runner`): the torque+springs rung's knee spring on Hermite-Simpson
# crouches to 103 deg at 3.5 m/s (docs/concepts/stride.md, "The crouch").
CROUCH_DEG = 60.0
# A runner's touchdown absorbs 0.5-1.0 J (RBDS001 at 2.5 and 3.5 m/s, forefoot steps) to 2.3-2.7 J
# (RIC's runner, heel steps) under Coulomb's law, which holds them all, and 2.3-5.1 J held by
# no-slip (one impact each: formopt compare's measured T_c on problems/compare/runners.toml, three
# trials of two runners); the torque scenes' heel and forefoot strides take 1.2-5.4 J a step over
# both their impacts (the landing and the rest of the foot set down). A stride whose impacts take
# more than STIFF_LANDING_J a step lands stiff, far from a runner's (`unlike_a_runner`): the flat
# strike whose second point arrives with the first and stops the whole foot at once, 15-28 J at
# 3.5-4.5 m/s on the torque scenes, 8 J at 2.5 m/s (docs/concepts/stride.md, "The torque scenes").
STIFF_LANDING_J = 10.0


def unlike_a_runner(stance_knee_deg: float, impacts_J: float) -> list[str]:
    """A stride's remarks where it is far from a runner's: its stance knee beyond CROUCH_DEG (deg),
    its impacts' summed T_c beyond STIFF_LANDING_J (J a step)."""
    out = [f"a crouched stance: the stance knee flexes to {stance_knee_deg:.0f} deg, far beyond a runner's "
           "37-44 deg at 2.5-4.5 m/s (RBDS001 and RIC's runner)"] if stance_knee_deg > CROUCH_DEG else []
    return out + ([f"a stiff landing: the impacts take {impacts_J:.0f} J a step, where a runner's touchdown "
                   "absorbs 0.5-5 J (formopt compare on RBDS001 and RIC's runner, Coulomb or no-slip)"]
                  if impacts_J > STIFF_LANDING_J else [])


def deepest_stance_knee(nlp: StrideNLP, names: list, theta: np.ndarray) -> float:
    """The stance knee's deepest flexion (deg) over the nodes of the phases with a contact
    (`names`: the phase of each node; theta (n, 9), a column per THETA); NaN without such nodes."""
    held = {p.name for p in nlp.phases if p.rows}
    knee = np.array([th[THETA.index("knee_R")] for name, th in zip(names, theta) if name in held])
    return float(np.degrees(knee.max())) if knee.size else float("nan")
