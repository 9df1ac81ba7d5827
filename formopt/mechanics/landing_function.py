"""The differentiable landing: the two-impact landing of a no-slip strike as a CasADi Function
of the touchdown state, for the posture NLP (optim.posture) and its gradient.

The event-driven simulation (any law, releases, stick-slip, adaptive steps) is landing.py; this
module follows only the one contact sequence an NLP can: the strike point held from the first
impact, fixed steps to the second impact, whose time is an NLP variable (`landing_function`)
or the root of the other point's height (`absorbed_function`, by Newton's method).
"""

from __future__ import annotations

import casadi as ca
import numpy as np

from .errors import InputError
from .landing import LandingModel
from .model import STATE


def landing_function(lm: LandingModel, strike: str, steps: int = 60) -> ca.Function:
    """The two-impact landing as a CasADi Function (differentiable).

    (x, t_e) -> T_c_total, T_c (both impacts), residual, force_t, force_n: x the touchdown state
    (model.STATE), t_e the time (s) of the second impact. The strike point is held from the
    first impact; `steps` fixed steps of t_e / steps (the model's fixed-step integrator; RK4
    in place of the adaptive one) integrate to t_e, where `residual` is the
    other point's height (zero at the event) and `approach` its normal velocity then (m/s,
    negative when it strikes); force_t, force_n are the contact force (N) and
    height the other point's height (m) after each step. `absorbed_function` solves
    residual = 0 for t_e. The strike point is held throughout: the no-slip law only.
    """
    if strike not in ("heel", "forefoot"):
        raise InputError("the two-impact landing starts with a heel or forefoot strike")
    if lm.law != "no-slip":
        raise InputError(f"the differentiable landing holds the strike point (no-slip), not "
                         f"{lm.law!r}: a sliding contact phase has events an NLP cannot follow")
    m = lm.model
    point, other = strike, "heel" if strike == "forefoot" else "forefoot"
    xs = ca.SX.sym("x", len(STATE))
    q0, qd0 = m.state(xs, point)
    touchdown = ca.Function("touchdown", [xs], [q0, qd0, ca.vertcat(lm.hinge_angles(q0),
                                                                    lm.spring_parameters()),
                                                ca.dot(q0[m.cols(point)], ca.DM(lm.t_axis))])
    n = 2 * m.n + 1
    xk, h, t = ca.SX.sym("xk", n), ca.SX.sym("h"), ca.SX.sym("t")
    s_anchor, joint = ca.SX.sym("s_anchor"), ca.SX.sym("joint", 4 * len(lm.hinges))
    x_next = lm.advance((point,), xk, h, s_anchor, joint, t=t,
                        scheme="rk4" if lm.integrator == "adaptive" else None)[0]
    forces = lm.motion((point,))(q=x_next[:m.n], qd=x_next[m.n:2 * m.n], s_anchor=s_anchor,
                                 joint=joint, friction=0, t=t + h,
                                 moments=ca.DM.zeros(len(lm.hinges)))["force"]
    height = ca.dot(x_next[m.cols(other)], ca.DM(lm.n_axis))
    step = ca.Function("step", [xk, ca.vertcat(h, t, s_anchor, joint)],
                       [x_next, ca.vertcat(forces, height)])
    run = step.mapaccum("run", steps, [0], [0])

    x = ca.MX.sym("x", len(STATE))
    t_e = ca.MX.sym("t_e")
    q, qd, joint_mx, s_mx = touchdown(x)
    qd1, T_c1 = lm.impact_map((point,))(q, qd, joint_mx, 0)[:2]
    params = ca.vertcat(ca.repmat(t_e / steps, 1, steps), ca.DM(np.arange(steps)).T * t_e / steps,
                        ca.repmat(ca.vertcat(s_mx, joint_mx), 1, steps))
    states, f = run(ca.vertcat(q, qd1, 0), params)
    end = states[:, -1]
    q_e, qd_e = end[:m.n], end[m.n:2 * m.n]
    residual = ca.dot(q_e[m.cols(other)], ca.DM(lm.n_axis))
    T_c2 = lm.impact_map((point, other))(q_e, qd_e, joint_mx, 0)[1]
    approach = ca.dot(qd_e[m.cols(other)], ca.DM(lm.n_axis))
    return ca.Function("landing", [x, t_e],
                       [T_c1 + T_c2, ca.vertcat(T_c1, T_c2), residual, approach, f[0, :].T,
                        f[1, :].T, f[2, :].T],
                       ["x", "t_e"], ["T_c_total", "T_c", "residual", "approach", "force_t",
                                      "force_n", "height"])


def absorbed_function(lm: LandingModel, strike: str, t_guess: float, steps: int = 60) -> ca.Function:
    """x -> (T_c_total, t_e): the summed absorbed energy of the two-impact landing, with the
    second impact's time found by Newton's method from `t_guess` (differentiable by the
    implicit function theorem)."""
    landing = landing_function(lm, strike, steps)
    t_e, x = ca.MX.sym("t_e"), ca.MX.sym("x", len(STATE))
    event = ca.rootfinder("event", "newton", ca.Function("g", [t_e, x], [landing(x, t_e)[2]]),
                          {"abstol": 1e-13, "max_iter": 50})
    t_star = event(t_guess, x)
    return ca.Function("absorbed", [x], [landing(x, t_star)[0], t_star], ["x"], ["T_c_total", "t_e"])
