"""Checks of a solved half stride against independent methods.

- `impact_check`: each impact's T_c by the joint-space projection at the solution's state
  against formopt's own impact map on the natural-coordinate model (mechanics.impact.projection
  with q = q(theta), q' = J theta'), and the Coulomb law's mode (mechanics.contact) there; a
  sliding touchdown's against contact.coulomb's T_c (its sliding mode).
- `forward`: the optimal joint moments (piecewise linear) integrated forward phase by phase
  (scipy's DOP853, rtol 1e-10) through the same contact sequence and phase durations, with the
  exact impact maps (a slide with its force on the cone's edge); the largest state difference
  at the nodes is the transcription's error (each phase from the NLP's state at its start),
  and what it grows to open loop; over a slide, whether the slip keeps its sign and when it
  stops.
- `drift`: how far the held contact points moved (m) over each phase.
- `swing_clearance`: the swing foot's least height (m) over the stance phases' nodes, which
  the NLP holds at or above StrideSettings.clearance (contact.RigidContact.swing).
"""

from __future__ import annotations

import casadi as ca
import numpy as np

from ...mechanics import contact
from ...mechanics.compiled import Compiled
from ...mechanics.impact import projection
from ...mechanics.joint_space import POINTS, JointSpace
from .collocation import NU, NX, StrideNLP
from .contact import height, rows_kinematics
from .layout import held_rows
from .ocp import periodicity, step_length
from .problem import other_leg


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


def accelerations(nlp: StrideNLP, i: int) -> Compiled:
    """theta'' (9) of the constrained equations of motion in `phase`, as a numpy call of
    (theta (9), theta' (9), active moments (N m, 6), theta at touchdown (9, the tendons'
    rest), slope (rad), mu): [M -D^T; G 0] [theta''; f] = [g + passive - c - tau; -dJ/dt theta']
    (`force_directions`: a sliding point's force on the cone's edge, against the slip
    settings.slip) in phase i; tau adds the actuation's passive moments (the tendons)."""
    js = nlp.js
    th, thd, td = ca.SX.sym("theta", NX), ca.SX.sym("thetad", NX), ca.SX.sym("theta_td", NX)
    tau, slope, mu = ca.SX.sym("tau", NU), ca.SX.sym("slope"), ca.SX.sym("mu")
    phase = nlp.phases[i]
    moments = ca.vertcat(0, 0, 0, tau + nlp.ocp.models[i].actuation.passive(th, td, bool(phase.points)))
    rhs = js.gravity(th) + js.passive(th) - js.bias(th, thd) - moments
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
    return Compiled(ca.Function("accelerations", [th, thd, tau, td, slope, mu], [thdd],
                                ["theta", "thetad", "tau", "theta_td", "slope", "mu"], ["thetadd"]),
                    compiled=False)


def forward(nlp: StrideNLP, blocks: dict, parameters: dict) -> dict:
    """Integrate the optimal moments forward (module docstring), twice: open loop over the
    whole half stride (`theta`, `thetad`, `per_phase_theta`: the largest node differences, m
    or rad and m/s or rad/s), and phase by phase from the NLP's state at each phase's start
    (`reset_theta`, `reset_per_phase`); `periodicity`: the open-loop post-touchdown state
    against the start; `slip_mps`: over a sliding phase (from its NLP start), the least and
    the largest s v_t of the sliding point on a fine grid (the slip held if the least is not
    below zero beyond the integration's error), and its v_t at the phase's end.
    `parameters`: speed, slope, mu (Solved.parameters)."""
    from scipy.integrate import solve_ivp  # here: scipy.integrate costs 0.2 s at every CLI start

    js = nlp.js
    slope, mu, slip = parameters["slope"], parameters["mu"], nlp.settings.slip
    X0 = blocks[f"X_{nlp.phases[0].name}"]
    state = X0[:, 0].copy()
    errors: list[np.ndarray] = []
    reset: list[np.ndarray] = []
    slips: dict = {}
    for i, phase in enumerate(nlp.phases):
        X, U, T = blocks[f"X_{phase.name}"], nlp.moments(blocks, i)[0], blocks[f"T_{phase.name}"].item()
        if nlp.impact_before(i):  # an impact starts the phase
            state[NX:] = joint_impact(js, phase.rows, state[:NX], state[NX:], slope)[0]
        times = np.linspace(0.0, T, X.shape[1])
        acc = accelerations(nlp, i)

        def rhs(t, x, U=U, times=times, acc=acc):
            k = min(max(int(np.searchsorted(times, t)) - 1, 0), len(times) - 2)  # piecewise linear moments
            w = min(max((t - times[k]) / (times[k + 1] - times[k]), 0.0), 1.0)
            tau = (1 - w) * U[:, k] + w * U[:, k + 1]
            return np.r_[x[NX:], acc(x[:NX], x[NX:], tau, X0[:NX, 0], slope, mu)["thetadd"]]

        for start, record in ((state, errors), (X[:, 0], reset)):
            out = solve_ivp(rhs, (0.0, T), start, method="DOP853", t_eval=times, rtol=1e-10,
                            atol=1e-10, dense_output=True)
            record.append(np.abs(out.y - X).max(axis=1))
            if record is errors:
                state = out.y[:, -1]
            elif phase.sliding:
                slips = _slip(js, phase.sliding, out.sol, T, slope, slip)
    touchdown = (other_leg(nlp.phases[0].sliding), slip, mu) if nlp.phases[0].sliding else None
    plus = joint_impact(js, nlp.touchdown_rows, state[:NX], state[NX:], slope, touchdown)[0]
    step = step_length(parameters["speed"], half_period(nlp, blocks))
    period_error = np.abs(np.asarray(periodicity(state[:NX], plus, X0[:, 0], step, slope), float)).max()
    err, res = np.array(errors), np.array(reset)
    return {"theta": float(err[:, :NX].max()), "thetad": float(err[:, NX:].max()),
            "per_phase_theta": [float(e) for e in err[:, :NX].max(axis=1)],
            "reset_theta": float(res[:, :NX].max()),
            "reset_per_phase": [float(e) for e in res[:, :NX].max(axis=1)],
            "periodicity": float(period_error), **slips}


def _slip(js: JointSpace, point: str, path, T: float, slope: float, slip: int) -> dict:
    """s v_t (m/s) of a sliding point along a simulated phase (`path`: the dense solution) on
    400 steps: its least and largest before it first stops, v_t at the phase's end, and when
    it first stops (`slip_stop_s`, s; T if it slides through; the NLP's slide stops at T)."""
    times = np.linspace(0.0, T, 401)
    v = slip * np.array([float(js.points[point](x[:NX], x[NX:], slope)[1][0]) for x in path(times).T])
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
