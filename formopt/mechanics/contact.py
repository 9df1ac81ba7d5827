"""Contact laws at the impact of one foot point: no-slip, frictionless, Coulomb.

In impulse space the contact point's velocity v = (v_t, v_n) (tangential along the ground,
normal out of it) changes with the ground's impulse p = (p_t, p_n) as

    v = v0 + W_c p,    W_c = C W C^T = [[a, b], [b, c]],
    W = M^-1 - M^-1 Phi_b^T (Phi_b M^-1 Phi_b^T)^-1 Phi_b M^-1

(C the contact rows, W the inverse inertia on the body's admissible motion), and the
generalised velocity by q'+ = q'- + W C^T p. The energy absorbed by any impulse is

    T_c(p) = -p . v0 - 1/2 p^T W_c p,

and the laws choose p:

- no-slip (the paper's): v_t and v_n both end at zero, p = -W_c^-1 v0;
- frictionless (normal only): p_t = 0, v_n ends at zero, p_n = -v_n0 / c;
- Coulomb, rigid and perfectly plastic (e = 0), Darboux-Keller equations with the normal
  impulse p_n as the clock (Routh's method; Stronge, Impact Mechanics, 2000): while the point
  slides in direction s = sign(v_t), dp_t = -mu s dp_n, so dv/dp_n = (k_t, k_n) =
  (b - mu s a, c - mu s b); the impact ends when v_n reaches 0. If v_t reaches 0 first, the
  point sticks when |b / a| <= mu (then dv_n/dp_n = det W_c / a) and otherwise slides on in
  the direction sign(b), reversed. Modes: SLIDE (0), STICK (1, slide then stick, or stick
  from the start), REVERSE (2, slide then reversed slide). Each is a closed form; when
  mu > c / |b| with s b > 0, v_n falls while sliding (Painleve's inequality), and the impact
  still ends, because sticking is then possible (|b| / a < c / |b| < mu).

The Coulomb impulse is selected by `if_else` between the closed forms: exact values and
exact derivatives inside each mode, a kink at the switches. An NLP that uses it must hold the
mode fixed and check it after the solve (the mode is an output).

`posture_friction` is the paper's eq. 7: b / a, the friction a touchdown with no tangential
velocity at the contact point would need (signed; its magnitude is the critical value).
"""

from __future__ import annotations

import casadi as ca

LAWS = ("no-slip", "coulomb", "frictionless")
SLIDE, STICK, REVERSE = 0, 1, 2
MODES = {SLIDE: "slide", STICK: "stick", REVERSE: "reversed slide"}


def admissible_inverse_inertia(M_inv, Phi_b):
    """W = M^-1 - M^-1 Phi_b^T (Phi_b M^-1 Phi_b^T)^-1 Phi_b M^-1 (n x n, symbolic)."""
    A = M_inv @ Phi_b.T
    return M_inv - A @ ca.solve(Phi_b @ A, A.T)


def no_slip(W_c, v0):
    """Impulse (N s) that brings both velocity components of the point to zero."""
    return -ca.solve(W_c, v0)


def frictionless(W_c, v0):
    """Impulse (N s) along the normals only that brings every normal velocity to zero
    (rows [t, n_1, ..., n_k]; the tangential impulse is zero)."""
    return ca.vertcat(0, -ca.solve(W_c[1:, 1:], v0[1:]))


def _closed_forms(W_c, v0, mu, s):
    """Each mode's impulse, for sliding direction s (+1 or -1), and the switches: `k_n`
    (> 0: sliding brings v_n toward zero), `before_end` (> 0: v_t reaches zero before v_n
    does) and `holds` (>= 0: sticking holds)."""
    a, b, c = W_c[0, 0], W_c[0, 1], W_c[1, 1]
    vt, vn = v0[0], v0[1]
    k_t, k_n = b - mu * s * a, c - mu * s * b
    p_slide = -vn / k_n  # slide to the end: the normal velocity reaches zero first
    p_stick = -vt / k_t  # normal impulse when v_t reaches zero
    vn_1 = vn + k_n * p_stick
    p_rest_stick = -vn_1 * a / (a * c - b * b)
    p_rest_reverse = -vn_1 / (c + mu * s * b)
    return {
        SLIDE: ca.vertcat(-mu * s * p_slide, p_slide),
        STICK: ca.vertcat(-mu * s * p_stick - b / a * p_rest_stick, p_stick + p_rest_stick),
        REVERSE: ca.vertcat(mu * s * (p_rest_reverse - p_stick), p_stick + p_rest_reverse),
        # |v_t| / |k_t| < -v_n / k_n, multiplied out so that no branch divides by zero
        "k_n": k_n,
        "before_end": -s * (vt * k_n - vn * k_t),
        "holds": mu * mu * a * a - b * b,
    }


def coulomb(W_c, v0, mu):
    """(impulse (N s), mode, final tangential velocity (m/s)) of the rigid, perfectly plastic
    impact with Coulomb friction mu, by the closed form of each mode (module docstring). A
    point that does not approach the ground (v_n >= 0) has no impact: zero impulse, T_c = 0
    (the closed forms assume v_n < 0 and would give a negative T_c there)."""
    s = ca.if_else(v0[0] >= 0, 1, -1)
    forms = _closed_forms(W_c, v0, mu, s)
    slide_only = ca.logic_and(forms["k_n"] > 0, forms["before_end"] <= 0)
    holds = forms["holds"] >= 0
    impulse = ca.if_else(slide_only, forms[SLIDE], ca.if_else(holds, forms[STICK], forms[REVERSE]))
    impulse = ca.if_else(v0[1] < 0, impulse, ca.DM.zeros(2))
    mode = ca.if_else(slide_only, SLIDE, ca.if_else(holds, STICK, REVERSE))
    slip = (v0 + W_c @ impulse)[0]
    return impulse, mode, ca.if_else(mode == STICK, 0, slip)


def coulomb_in_mode(W_c, v0, mu, mode: int, s: int):
    """(impulse, region) of one Coulomb mode and sliding direction s, both smooth: the closed
    form of `mode`, and the expressions that are all >= 0 exactly where the impact is in that
    mode (s v_t >= 0; SLIDE: k_n > 0 and v_n reaches zero first; STICK and REVERSE: v_t
    reaches zero first, and sticking holds or not). An NLP fixes the mode and keeps these."""
    forms = _closed_forms(W_c, v0, mu, s)
    region = [s * v0[0]]
    if mode == SLIDE:
        region += [forms["k_n"], -forms["before_end"]]
    else:
        region += [forms["before_end"], forms["holds"] if mode == STICK else -forms["holds"]]
    return forms[mode], ca.vertcat(*region)


def velocity_level(W_c, v0, mu):
    """(impulse, mode, final tangential velocity) of a plastic Coulomb impact at one or more
    points of one rigid foot, by the velocity-level law (Moreau 1988; the impact step of
    Stewart & Trinkle 1996). Rows: [t, n_1, ..., n_k], the points sharing their tangential
    motion (a flat foot). Every normal velocity ends at zero; the foot sticks when the impulse
    that stops it lies in the friction cone, |p_t| <= mu sum p_n, and otherwise slides with
    p_t = mu s_f sum p_n, s_f the sign of the sticking impulse. For one point it gives the
    Darboux-Keller impulse wherever that one slides or sticks, and differs after a reversed
    slide (tests/mechanics/test_contact.py); two frictional contacts have no single
    normal-impulse clock, so this is the law formopt applies to them."""
    k = v0.shape[0] - 1
    p_stick = no_slip(W_c, v0)
    total = ca.sum1(p_stick[1:])
    holds = ca.fabs(p_stick[0]) <= mu * total
    s_f = ca.if_else(p_stick[0] >= 0, 1, -1)
    W_nn, W_nt = W_c[1:, 1:], W_c[1:, 0]
    p_n = -ca.solve(W_nn + mu * s_f * W_nt @ ca.DM.ones(1, k), v0[1:])
    p_slide = ca.vertcat(mu * s_f * ca.sum1(p_n), p_n)
    impulse = ca.if_else(holds, p_stick, p_slide)
    slip = (v0 + W_c @ impulse)[0]
    return impulse, ca.if_else(holds, STICK, SLIDE), ca.if_else(holds, 0, slip)


def absorbed(W_c, v0, p):
    """T_c(p) = -p . v0 - 1/2 p^T W_c p (J): the energy an impulse p takes out."""
    return -ca.dot(p, v0) - 0.5 * ca.dot(p, W_c @ p)
