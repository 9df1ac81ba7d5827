"""Coulomb's sliding touchdown in the stride (formopt.optim.stride, issue 23): the impact in
its sliding mode and the slide after it, checked against formopt's Coulomb impact map, the
forward simulation with the sliding contact set, the energy budget and the slip's sign.

One coarse solve (24 nodes, 1 start): a forefoot strike at 3.5 m/s, Coulomb friction 0.3. Its
sticking optimum needs a touchdown impulse on the friction cone's edge (the map says it
slides), so the mode decision solves the sliding variant. Reproducible: the generic guess is
deterministic. With Riener & Edrich's passive joint moments (2026-11-27) the slide is kept and
valid at friction 0.3 (objective 0.9264 against 0.9822 sticking, 182 steps/min); at 0.4-0.8
the sliding variant converges to an invalid stride (its slide on its 0.1 s ceiling, the
forward check 1.6 rad) and the sticking one is kept, as the mode decision should (before them:
the slide kept at 0.4 and 0.8). Setup about 9 CPU seconds: two builds, two solves, one forward
simulation."""

import casadi as ca
import numpy as np
import pytest
from helpers import forward_check_again

from formopt.mechanics import contact
from formopt.mechanics.body import paper_body
from formopt.mechanics.errors import InputError
from formopt.mechanics.joint_space import POINTS, JointSpace
from formopt.optim.stride import StrideNLP, StrideSettings, optimum
from formopt.optim.stride.checks import joint_impact
from formopt.optim.stride.guess import fitted
from formopt.optim.stride.problem import SLIDING_PHASES

NODES = 24
SPEED = 3.5
MU = 0.3


@pytest.fixture(scope="module")
def js():
    return JointSpace(paper_body())


@pytest.fixture(scope="module")
def slid(js):
    nlp = StrideNLP(js, StrideSettings(strike="forefoot", nodes=NODES, law="coulomb"))
    return nlp, optimum(nlp, SPEED, 0.0, MU)


def test_sliding_phase_lists():
    """A sliding touchdown adds a slide of the strike's first point before its sticking
    sequence; a flat touchdown (two points) has none; under Coulomb the nodes must suffice
    for the sliding variant."""
    for strike, phases in SLIDING_PHASES.items():
        assert phases[0].name == "slide" and phases[0].sliding == phases[1].rows[0][0]
        assert StrideSettings(strike=strike, law="coulomb", touchdown="slide").phases == phases
    assert "flat" not in SLIDING_PHASES
    for bad in ({"law": "no-slip"}, {"law": "coulomb", "strike": "flat"}):
        with pytest.raises(InputError, match="touchdown 'slide'"):
            StrideSettings(touchdown="slide", **bad)
    with pytest.raises(InputError, match="slip"):
        StrideSettings(law="coulomb", touchdown="slide", slip=0)
    StrideSettings(strike="forefoot", nodes=20)  # 4 phases: 18 nodes at least
    with pytest.raises(InputError, match="nodes = 20: expected at least 22"):  # the sliding variant's 5
        StrideSettings(strike="forefoot", nodes=20, law="coulomb")


def test_sliding_impact_against_the_coulomb_map(js):
    """The joint-space sliding impact (force along n - s mu t, the normal velocity zero after)
    equals contact.coulomb's closed form on the natural-coordinate model wherever that one
    slides through the impact: T_c and the final slip to round-off (no solve: a running
    posture with random velocities, those with the heel moving into the ground and sliding)."""
    theta = np.array([0.0, 0.95, 0.1, 0.4, 0.3, 0.05, -0.2, 1.0, -0.1])  # m, rad
    rows = (("heel_R", "t"), ("heel_R", "n"))
    rng = np.random.default_rng(1)
    checked = 0
    for _ in range(40):
        thetad = rng.uniform(-3, 3, 9)
        q = np.asarray(js.q(theta), float).ravel()
        qd = np.asarray(js.J(theta), float) @ thetad
        C = js.model.contact_rows((POINTS["heel_R"],), 0.0, tangential=(POINTS["heel_R"],))
        W = contact.admissible_inverse_inertia(ca.DM(js.model.M_inv),
                                               js.model.constraint_jacobian(ca.DM(q)))
        W_c, v0 = ca.DM(C) @ W @ ca.DM(C).T, ca.DM(C) @ qd
        p, mode, slip = contact.coulomb(W_c, v0, MU)
        if float(v0[1]) >= 0 or contact.MODES[int(mode)] != "slide":
            continue
        s = 1 if float(v0[0]) >= 0 else -1
        plus, _, T_c = joint_impact(js, rows, theta, thetad, 0.0, ("heel_R", s, MU))
        v_plus = np.asarray(js.points["heel_R"](theta, plus, 0.0)[1], float).ravel()
        assert T_c == pytest.approx(float(contact.absorbed(W_c, v0, p)), abs=1e-9)
        assert v_plus[0] == pytest.approx(float(slip), abs=1e-9)
        assert abs(v_plus[1]) < 1e-9
        checked += 1
    assert checked >= 5


def test_mode_decision_keeps_the_valid_slide(slid):
    """The sticking optimum's touchdown needs an impulse on the cone's edge (valid: there the
    sticking impulse is Coulomb's sliding one, result.CONE_EDGE); the sliding variant,
    warm-started from it, converges, is valid and cheaper, and is kept."""
    _nlp, stride = slid
    tried = {t["mode"]: t for t in stride.checks["touchdown_modes"]}
    assert tried["slide"]["valid"] and tried["slide"]["success"]
    assert tried["slide"]["objective"] < tried["stick"]["objective"]
    assert stride.success and stride.phases[0][0] == "slide"
    touchdown = stride.impacts[-1]
    assert touchdown["mode"] == touchdown["coulomb_mode"] == "slide"
    assert touchdown["slide_s"] > 0 and touchdown["slip"] * touchdown["slide_m"] > 0


def test_sliding_impact_equals_formopt_coulomb_map(slid):
    """At the solved touchdown state: the joint-space sliding impact against contact.coulomb on
    the natural-coordinate model, 1e-9 J; the NLP's own T_c (its post-impact velocity
    variables) to IPOPT's tolerance; the impulse on the cone's edge."""
    _, stride = slid
    touchdown = stride.impacts[-1]
    assert touchdown["impact_map_difference_J"] < 1e-9
    assert touchdown["T_c"] == pytest.approx(touchdown["T_c_coulomb"], abs=1e-5)
    assert touchdown["mu_c"] == pytest.approx(MU, rel=1e-6)
    assert touchdown["impulse_Ns"][1] > 0 and touchdown["approach_mps"] < 0
    for impact in stride.impacts[:-1]:  # the heel drop sticks, inside the cone
        assert impact["mode"] == impact["coulomb_mode"] == "stick" and impact["valid"]
        assert impact["impact_map_difference_J"] < 1e-9


def test_forward_simulation_through_the_slide(slid):
    """The optimal moments integrated forward (CVODES) with the sliding contact set (force on
    the cone's edge, only the normal row held) from the slide's NLP start reproduce the slide
    to 0.05 rad (measured 0.006 rad at 24 nodes), and every phase to 0.25 rad as the sticking
    strides do (tests/optim/test_stride.py)."""
    _, stride = slid
    c = stride.checks
    assert c["forward_per_phase"][0] < 0.05
    assert c["forward_theta"] < 0.25
    assert c["drift_m"] < 5e-3  # the slide's normal drift included


def test_slip_direction_held(slid):
    """s v_t >= 0 at every node of the slide (constraint) and in the forward simulation until
    the slip stops, which it does within 15 % of the slide's duration of the NLP's end (the
    trapezoidal rule's timing error; measured 0 % at friction 0.4, 14 % at 0.8); the sticking
    phases after it keep |f_t| <= mu f_n."""
    _, stride = slid
    touchdown, c = stride.impacts[-1], stride.checks
    assert touchdown["slip_min_mps"] >= -1e-8
    assert c["forward_slip_min_mps"] >= 0
    assert abs(c["forward_slip_stop_s"] - touchdown["slide_s"]) <= 0.15 * touchdown["slide_s"]
    assert touchdown["stick_friction_ratio"] <= 1 + 1e-5


def test_energy_budget_closes_with_the_slide(slid):
    """W+ - W- - impacts - friction - passive = 0 to the transcription's accuracy (under 2 %
    of W+ at 24 nodes, as for sticking strides); the slide's friction work is in the budget
    (positive: kinetic friction only takes energy), and leaving it out would open the balance."""
    _, stride = slid
    b, slide = stride.budget, stride.impacts[-1]["slide_friction_J"]
    assert slide > 0
    assert abs(b["balance_J"]) < 0.02 * b["positive_work_J"]
    assert abs(b["balance_J"] + slide) > 3 * abs(b["balance_J"])


def test_a_sliding_solution_warm_starts_the_sticking_nlp(slid):
    """A sliding solution fitted to the sticking NLP (one phase fewer, more nodes per phase):
    every block the sticking NLP has, in its shape, with the end states of each phase kept."""
    nlp, stride = slid
    guess = fitted(nlp, stride.solved.blocks)
    assert set(guess) == set(nlp.blocks.names) - {n for n in nlp.blocks.names if n.startswith("S_")}
    for name, value in guess.items():
        assert value.shape == nlp.blocks.shapes[name]
    for phase in nlp.phases:
        X, solved = guess[f"X_{phase.name}"], stride.solved.blocks[f"X_{phase.name}"]
        assert np.allclose(X[:, [0, -1]], solved[:, [0, -1]])
    nlp.blocks.join(guess)  # the solver's initial point


def test_the_forward_check_added_afterwards_takes_the_sliding_variant(slid):
    """forward_checked on a sliding touchdown's stride replays it under the NLP's sliding variant
    (its impact's slip sign): the entries summarise's own check gave."""
    nlp, stride = slid
    assert stride.impacts[-1]["mode"] == "slide"
    checked, forward = forward_check_again(nlp, stride)
    assert all(np.all(checked.checks[k] == stride.checks[k]) for k in forward)
    assert checked.valid == stride.valid
