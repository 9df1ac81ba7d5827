"""The periodic half stride (formopt.optim.stride): one coarse solve per strike (module
fixtures, 24 nodes), checked against independent methods: formopt's impact map at each
impact's state, the optimal moments integrated forward, periodicity, the energy budget, the
NLP's derivatives against finite differences, and other initial guesses."""

import casadi as ca
import numpy as np
import pytest
from helpers import SEED, forward_check_again

from formopt.mechanics.body import paper_body
from formopt.mechanics.errors import InputError
from formopt.mechanics.joint_space import JointSpace
from formopt.optim.stride import StrideNLP, StrideSettings, forward_checked, optimum
from formopt.optim.stride.guess import ballistic, perturbed

NODES = 24
SPEED = 3.5


@pytest.fixture(scope="module")
def js():
    return JointSpace(paper_body())


@pytest.fixture(scope="module", params=["heel", "forefoot"])
def solved(js, request):
    nlp = StrideNLP(js, StrideSettings(strike=request.param, nodes=NODES))
    return nlp, optimum(nlp, SPEED)


def test_solves_from_the_generic_guess(solved):
    _nlp, stride = solved
    assert stride.success, stride.status
    assert stride.step_length_m == pytest.approx(SPEED * stride.half_period_s)
    assert stride.cadence_spm == pytest.approx(60 / stride.half_period_s)
    assert 0 < stride.duty_factor < 0.5  # running: a flight phase
    assert stride.flight_s > 0.01
    assert stride.peak_vertical_grf_bw > 1.0
    # the stance knee's deepest flexion, from the nodes of the contact phases
    stance = [th[4] for name, th in zip(stride.phase, stride.theta) if name != "flight"]
    assert stride.stance_knee_deg == pytest.approx(np.degrees(max(stance)), rel=1e-12)
    assert 0 < stride.stance_knee_deg < 90


def test_each_impact_equals_formopt_impact_map(solved):
    """T_c of the joint-space projection at each impact's state against
    mechanics.impact.projection on the natural-coordinate model: 1e-9 J; the NLP's own T_c
    (from its post-impact velocity variables) to IPOPT's tolerance."""
    _, stride = solved
    for impact in stride.impacts:
        assert impact["impact_map_difference_J"] < 1e-9
        assert impact["T_c"] == pytest.approx(impact["T_c_exact"], abs=1e-5)
        assert impact["impulse_Ns"][1] > 0  # the ground pushes
        assert impact["mu_c"] <= stride.friction * (1 + 1e-6)  # no-slip within the friction
        assert impact["coulomb_mode"] in ("stick", "slide", "reversed slide")


def test_periodic_and_contacts_held(solved):
    """The post-touchdown state, legs swapped and moved back a step, is the start; the held
    contact points drift by less than 5 mm (trapezoidal, 24 nodes)."""
    _, stride = solved
    assert stride.checks["periodicity"] < 1e-6
    assert stride.checks["drift_m"] < 5e-3


def test_energy_budget_closes(solved):
    """W+ - W- - impacts - friction - passive = 0 to the transcription's accuracy: under
    2 % of W+ at 24 nodes (measured: 0.2 % at 40 nodes, problems/stride_checks.py)."""
    _, stride = solved
    b = stride.budget
    assert b["positive_work_J"] > 0 and b["negative_work_J"] > 0
    assert abs(b["balance_J"]) < 0.02 * b["positive_work_J"]
    assert stride.cost_of_transport == pytest.approx(
        b["positive_work_J"] / (stride.mass_kg * 9.81 * stride.step_length_m))


def test_forward_simulation_reproduces_each_phase(solved):
    """The optimal moments (piecewise linear) integrated forward by CVODES from the NLP's state
    at each phase's start, through the same contacts and impacts, reproduce every phase to
    0.25 rad at 24 nodes (the trapezoidal rule's O(h^2) error at steps up to 15 ms: measured
    0.08 rad heel, 0.17 rad forefoot strike; it falls with the nodes, problems/stride_checks.py;
    open loop over the whole half stride the free swing leg amplifies it: reported in checks,
    not asserted)."""
    _, stride = solved
    assert stride.checks["forward_theta"] < 0.25
    assert np.isfinite(stride.checks["open_loop_theta"])


def test_the_forward_check_added_afterwards_is_the_same(solved):
    """forward_checked adds the forward check to a stride summarised without it (compare's free
    optima): the entries summarise's own check gives, under the NLP the stride was solved with
    (the sliding variant where its touchdown slides), and the same validity."""
    nlp, stride = solved
    checked, forward = forward_check_again(nlp, stride)
    assert sorted(k for k in checked.checks if k in forward) == sorted(forward)
    assert checked.checks["forward_theta"] == pytest.approx(stride.checks["forward_theta"], rel=1e-9)
    assert checked.valid == stride.valid
    assert forward_checked(nlp, checked) is checked  # checked once


def test_warm_start_from_a_neighbouring_speed_returns(solved):
    """Continuation in speed: solved at 3.3 m/s from the 3.5 m/s optimum, then back at 3.5
    m/s from that, an optimum at least as good (objective to 1e-4), in fewer iterations. Not
    always the same one: with Riener & Edrich's passive moments the forefoot strike at 24 nodes
    comes back 1.8 % cheaper (0.9288 against the generic guess's 0.9462, 2026-11-27): the
    landscape has several optima, which the global search (optim.stride.search) is for."""
    nlp, stride = solved
    near = nlp.solve(stride.solved.blocks, SPEED - 0.2)
    back = nlp.solve(near.blocks, SPEED)
    assert near.success and back.success
    assert back.objective <= stride.objective_value * (1 + 1e-4)
    assert back.iterations < stride.iterations


def test_random_guesses_reach_an_optimum(solved):
    """The generic guess perturbed at random (joint angles +-10 deg, rates +-1 rad/s): each
    solve succeeds and is periodic. The NLP is not convex: they reach local optima whose
    objective differs by up to about 15 % (heel strike, 24 nodes: 0.87 from the generic
    guess, 0.74 from a random one); problems/stride_checks.py reports them."""
    nlp, stride = solved
    rng = np.random.default_rng(SEED)
    base = ballistic(nlp, SPEED)
    for _ in range(2):
        out = nlp.solve(perturbed(base, rng), SPEED)
        assert out.success, out.status
        assert 0.5 * stride.objective_value < out.objective < 2 * stride.objective_value


def test_nlp_derivatives_match_finite_differences(js):
    """The constraint Jacobian CasADi gives IPOPT against central differences, at the generic
    guess, for 30 random variables (18 nodes)."""
    nlp = StrideNLP(js, StrideSettings(strike="heel", nodes=18))
    x0 = nlp.blocks.join(ballistic(nlp, SPEED))
    g = ca.Function("g", [nlp.blocks.vector(), nlp.p], [ca.vertcat(*nlp.rows.expr)])
    jacobian = ca.Function("dg", [nlp.blocks.vector(), nlp.p],
                           [ca.jacobian(g(nlp.blocks.vector(), nlp.p), nlp.blocks.vector())])
    p = np.array([SPEED, 0.05, 0.8])
    J = np.asarray(ca.densify(jacobian(x0, p)), float)
    rng = np.random.default_rng(SEED)
    for k in rng.choice(x0.size, 30, replace=False):
        e = np.zeros(x0.size)
        e[k] = 1e-6
        numeric = (np.asarray(g(x0 + e, p)) - np.asarray(g(x0 - e, p))).ravel() / 2e-6
        assert np.allclose(J[:, k], numeric, rtol=1e-5, atol=1e-5)


@pytest.mark.parametrize("settings, key", [({"strike": "toe"}, "strike"),
                                           ({"objective": "speed"}, "objective"),
                                           ({"nodes": 5}, "nodes"),
                                           ({"law": "frictionless"}, "law"),
                                           ({"torque_limit": 100.0}, "torque_limit"),
                                           ({"clearance": -0.01}, "clearance_m"),
                                           ({"clearance": float("nan")}, "clearance_m"),
                                           ({"approach_speed": -0.01}, "approach_speed_mps"),
                                           ({"approach_speed": 2.0}, "approach_speed_mps")])
def test_bad_settings_name_their_key(settings, key):
    with pytest.raises(InputError, match=key):
        StrideSettings(**settings)
