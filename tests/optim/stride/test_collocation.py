"""optim.stride.collocation (the trapezoidal transcription of ocp.StrideProblem): solved strides
checked against what the NLP must impose, each by a formula written here, apart from the code
that imposes it: the release (on the trapezoid a dropped point leaves with no force; on
Hermite-Simpson no row holds the controls at one instant), the periodicity's shift along a slope, the objective's scale and the impacts' sign, and the work and metabolic
objectives. Cheap: the paper's body, 18 nodes."""

import dataclasses

import casadi as ca
import numpy as np
import pytest

from formopt.io.muscle_table import body_muscles
from formopt.mechanics.body import paper_body, scaled_body
from formopt.mechanics.joint_space import JointSpace
from formopt.optim.stride import StrideNLP, StrideSettings, optimum
from formopt.optim.stride.collocation import NX
from formopt.optim.stride.contact import CLEARANCE, height
from formopt.optim.stride.ocp import Release, StrideProblem
from formopt.optim.stride.problem import MOMENT_TIME, RUNNER_ANKLE
from formopt.optim.stride.transcription import HermiteSimpson, Trapezoid

NODES, SPEED, G = 18, 3.5, 9.81
SLOPE = np.arctan(0.05)  # a 5 % slope


@pytest.fixture(scope="module")
def js():
    return JointSpace(paper_body())


@pytest.fixture(scope="module")
def uphill(js):
    """A heel strike on a 5 % slope, with an impact weight (the impacts in the objective)."""
    nlp = StrideNLP(js, StrideSettings(strike="heel", nodes=NODES, impact_weight=0.5))
    return nlp, optimum(nlp, SPEED, SLOPE, simulate=False)


def _objective(stride, nlp, weights):
    """The objective per distance written out: effort 100/(m g)^2 int sum tau^2 dt, W+ and W-
    per m g, the impacts' T_c times impact_weight per m g, and 1e-6 sum h |dA|^2 (problem's
    SMOOTHING), all over d = v T. `weights`: (effort, positive, negative)."""
    m, d, b = stride.mass_kg, stride.step_length_m, stride.budget
    effort = np.trapezoid(np.sum(stride.tau ** 2, axis=1), stride.t)
    smooth = 0.0
    for phase, n in zip(nlp.phases, nlp.split):
        A, h = stride.solved.blocks[f"A_{phase.name}"], stride.solved.blocks[f"T_{phase.name}"].item() / n
        smooth += h * np.sum(np.diff(A, axis=1) ** 2)
    total = (weights[0] * 100 * effort / (m * G) ** 2 + weights[1] * b["positive_work_J"] / (m * G)
             + weights[2] * b["negative_work_J"] / (m * G)
             + nlp.settings.impact_weight * b["impacts_J"] / (m * G))
    return total / d + 1e-6 * smooth / d


def test_uphill_stride_converges_and_is_valid(uphill):
    _, stride = uphill
    assert stride.success and stride.valid, stride.failed_checks


def test_the_swing_foot_clears_the_ground_while_the_other_holds_it(uphill):
    """Every node of the stance phases keeps the swing foot's heel and forefoot (leg L) at least
    StrideSettings.clearance above the slope, measured from the stride's own joint histories;
    the stride reports that least height."""
    nlp, stride = uphill
    stance = {p.name for p in nlp.phases if p.rows}
    normal = np.array([-np.sin(SLOPE), np.cos(SLOPE)])
    heights = [float(np.asarray(nlp.js.points[point](theta, np.zeros(9), SLOPE)[0], float).ravel() @ normal)
               for theta, phase in zip(stride.theta, stride.phase) if phase in stance
               for point in ("heel_L", "forefoot_L")]
    assert nlp.settings.clearance == CLEARANCE == 0.01
    assert min(heights) >= CLEARANCE - 1e-6
    assert stride.swing_clearance_m == pytest.approx(min(heights), abs=1e-12)


def test_a_dropped_point_leaves_the_ground_with_no_force_on_the_trapezoid(uphill):
    """Heel-off and toe-off on the trapezoid: the dropped point's normal force at its phase's
    last node is zero (without the release rows, the forefoot left pushing 2.3 body weights)."""
    nlp, stride = uphill
    for i, transition in enumerate(nlp.ocp.transitions):
        if isinstance(transition, Release):
            F = stride.solved.blocks[f"F_{nlp.phases[i].name}"]
            assert np.abs(F[list(transition.dropped), -1]).max() < 1e-6
    assert stride.force[len(stride.t) - 1].sum() == pytest.approx(0.0, abs=1e-6)  # flight's end


@pytest.fixture(scope="module")
def hermite(js):
    """A heel strike with Hermite-Simpson, from the generic guess."""
    nlp = StrideNLP(js, StrideSettings(strike="heel", nodes=NODES, transcription="hermite-simpson"))
    return nlp, optimum(nlp, SPEED, simulate=False)


def test_no_row_holds_hermite_simpsons_controls_at_one_instant(hermite):
    """Apart from the node model's rows (at every column) and the integrals, no row of a torque
    rung on Hermite-Simpson ties the contact forces or the controls at one column: such a row
    (the release's f_n = 0 at toe-off until 2026-11-26) holds the controls at one instant, which
    the continuous problem meets by a jump of the moments and the transcription by a layer one
    interval wide costing O(h), so the optimum converged only as O(h) with the mesh."""
    nlp, _ = hermite
    x = nlp.blocks.vector()
    rows = ca.Function("rows", [x, nlp.ell, nlp.p], [nlp.rest(x, nlp.ell, nlp.p)[1]])
    jac = np.array(ca.DM(rows.sparsity_jac(0, 0), 1)) != 0  # ell (the integrals) apart
    for name in nlp.blocks.names:
        if name.startswith(("F_", "U_")):
            start = nlp.blocks.offsets[name]
            size = nlp.blocks.shapes[name][0] * nlp.blocks.shapes[name][1]
            assert not jac[:, start:start + size].any(), name


def test_a_dropped_point_leaves_the_ground_as_the_next_phase_begins(hermite):
    """Hermite-Simpson's heel-off and toe-off: the dropped point's normal force is >= 0 to its
    phase's end, and in the next phase the point is at or above the ground at every column."""
    nlp, stride = hermite
    for i, transition in enumerate(nlp.ocp.transitions):
        if isinstance(transition, Release):
            before, after = nlp.phases[i], nlp.phases[i + 1]
            assert stride.solved.blocks[f"F_{before.name}"][[a == "n" for _, a in before.rows], :].min() > -1e-8
            X = stride.solved.blocks[f"X_{after.name}"]
            for point in (p for p in before.points if p not in after.points):
                h = [float(height(nlp.js, point, ca.DM(X[:NX, k]), 0.0)) for k in range(X.shape[1])]
                assert min(h) > -1e-8, (after.name, point, h[:3])


def test_a_released_point_accelerates_off_the_ground(hermite):
    """Without the release's f_n = 0 row, nothing but the next phase's heights >= 0 at its columns
    makes the moments' jump lift the point: at the next phase's first column the dropped point,
    at rest on the ground, must accelerate away from it (a rigid contact lets go only so; 45 and
    125 m/s^2 at heel-off and toe-off here), or the ground would have to pull."""
    nlp, stride = hermite
    for i, transition in enumerate(nlp.ocp.transitions):
        if isinstance(transition, Release):
            before, after = nlp.phases[i], nlp.phases[i + 1]
            X, A = (stride.solved.blocks[f"{key}_{after.name}"] for key in "XA")
            for point in (p for p in before.points if p not in after.points):
                _, _, J, drift = nlp.js.points[point](ca.DM(X[:NX, 0]), ca.DM(X[NX:, 0]), 0.0)
                assert float((J @ ca.DM(A[:, 0]) + drift)[1]) > 0.0, (after.name, point)


def test_the_muscles_release_with_no_force():
    """With muscles, whose moments are states, the dropped points' normal forces reach zero at
    their phase's end (a row on the state), as a runner's ground force falls at toe-off."""
    settings = StrideSettings(strike="heel", nodes=NODES, muscles=body_muscles(scaled_body(62.0, 1.81)),
                              objective="metabolic", transcription="hermite-simpson")
    problem = StrideProblem(JointSpace(paper_body()), settings)
    releases = [t for t in problem.transitions if isinstance(t, Release)]
    assert len(releases) == 2 and all(t.dropped for t in releases)


def test_moment_dynamics_release_with_no_force_on_hermite_simpson():
    """With moment dynamics (the torque scenes' stride, problem.MOMENT_TIME) the moments are
    states, so the dropped points' normal forces reach zero at their phase's end on
    Hermite-Simpson too: the stance does not end pushing (0.4-2.1 body weights with moments that
    jump, which hold no such row)."""
    def releases(moment_time):
        settings = StrideSettings(strike="forefoot", nodes=NODES, transcription="hermite-simpson",
                                  moment_time=moment_time, tendons=dict(RUNNER_ANKLE))
        problem = StrideProblem(JointSpace(paper_body()), settings)
        return [t for t in problem.transitions if isinstance(t, Release)]
    assert len(releases(MOMENT_TIME)) == 2 and all(t.dropped for t in releases(MOMENT_TIME))
    assert not any(t.dropped for t in releases(0.0))


def test_hermite_simpsons_torque_rungs_perturb_the_constraints_at_every_iteration(hermite, uphill):
    """ipopt_options.TORQUE_HERMITE_IPOPT on Hermite-Simpson's torque rungs only (the trapezoid's
    and the muscles' options unchanged)."""
    assert hermite[0].options["perturb_always_cd"] == "yes"
    assert "perturb_always_cd" not in uphill[0].options
    muscles = StrideSettings(strike="heel", nodes=NODES, muscles=body_muscles(scaled_body(62.0, 1.81)),
                             objective="metabolic", transcription="hermite-simpson")
    assert "perturb_always_cd" not in StrideNLP(JointSpace(paper_body()), muscles).options


def test_the_period_moves_the_hip_one_step_along_the_slope(uphill):
    """The touchdown's hip is one step d = v T along the ground from the start's: up the slope by
    d sin(slope); the budget's climb is m g d sin(slope) and the budget closes."""
    _, stride = uphill
    d = SPEED * stride.half_period_s
    hip = stride.theta[-1, :2] - stride.theta[0, :2]
    assert hip == pytest.approx([d * np.cos(SLOPE), d * np.sin(SLOPE)], abs=1e-7)
    assert stride.budget["climb_J"] == pytest.approx(stride.mass_kg * G * d * np.sin(SLOPE))
    assert abs(stride.budget["balance_J"]) < 0.05 * stride.budget["positive_work_J"]


def test_the_objective_is_the_written_formula(uphill):
    """The objective IPOPT minimised equals the formula with the impacts counted as a cost (their
    sign) and each scale as written."""
    nlp, stride = uphill
    assert stride.budget["impacts_J"] > 0
    assert stride.objective_value == pytest.approx(_objective(stride, nlp, (1, 0, 0)), rel=1e-6)


@pytest.mark.parametrize("objective, weights", [("work", (1e-2, 1, 0)),
                                                ("metabolic", (1e-2, 4, 1 / 1.2))])
def test_work_objectives_are_built_and_solved(js, uphill, objective, weights):
    """W+ and Margaria's W+/0.25 + W-/1.2 (with 1e-2 of effort), from the effort optimum: the
    power split's slacks end as the exact positive and negative parts (the objective equals
    the formula on the budget's max(P, 0) integrals)."""
    nlp = StrideNLP(js, StrideSettings(strike="heel", nodes=NODES, objective=objective))
    stride = optimum(nlp, SPEED, SLOPE, guess=uphill[1].solved.blocks, simulate=False)
    assert stride.success, stride.status
    assert stride.objective_value == pytest.approx(_objective(stride, nlp, weights), rel=1e-4)


def test_impact_weight_lowers_the_impacts(js, uphill):
    """A cost on the impacts lowers them (the same stride without it absorbs more)."""
    nlp, stride = uphill
    plain = StrideNLP(js, dataclasses.replace(nlp.settings, impact_weight=0.0))
    free = optimum(plain, SPEED, SLOPE, guess=stride.solved.blocks, simulate=False)
    assert free.success and free.budget["impacts_J"] > stride.budget["impacts_J"]


def test_hermite_simpson_solves_and_integrates_by_simpsons_rule(hermite):
    """The second transcription (2N + 1 columns: mesh points and midpoints) converges from the
    generic guess to a valid stride, and its objective is Simpson's rule on its columns, h/6
    (1, 4, 2, ..., 4, 1), with the smoothing on the accelerations' curvature in each interval,
    h |A_k - 2 A_m + A_k+1|^2."""
    nlp, stride = hermite
    assert stride.success and stride.valid, stride.failed_checks
    m, b = stride.mass_kg, stride.solved.blocks
    effort = smooth = 0.0
    for phase, n in zip(nlp.phases, nlp.split):
        h = b[f"T_{phase.name}"].item() / n
        w = np.full(2 * n + 1, 2.0)
        w[1::2], w[[0, -1]] = 4.0, 1.0
        effort += h / 6 * w @ np.sum((m * b[f"U_{phase.name}"]) ** 2, axis=0)
        A = b[f"A_{phase.name}"]
        smooth += h * np.sum((A[:, :-2:2] - 2 * A[:, 1::2] + A[:, 2::2]) ** 2)
    d = stride.step_length_m
    assert stride.objective_value == pytest.approx(100 * effort / (m * G) ** 2 / d + 1e-6 * smooth / d, rel=1e-6)


def test_the_smoothing_sees_each_transcriptions_null_mode():
    """Accelerations +c at the mesh points and -c/2 at the midpoints leave Hermite-Simpson's
    defects unchanged (the velocities see h/6 (c - 2c + c) = 0), +c and -c node to node the
    trapezoid's: their smoothing costs them 9 h c^2 an interval (the curvature in each, blind to
    accelerations linear in time: a share that falls as h^4) and 4 h c^2 a step (the change
    between nodes)."""
    h, n, c = 0.01, 3, 2.0
    rng = np.random.default_rng(0)
    for transcription, pattern, cost in ((HermiteSimpson, (c, -c / 2), 9 * n), (Trapezoid, (c, -c), 4 * 2 * n)):
        X, D = ca.DM(rng.random((4, 2 * n + 1))), ca.DM(rng.random((4, 2 * n + 1)))
        mode = ca.DM([[pattern[k % 2] for k in range(2 * n + 1)]] * 2)
        D_moved = ca.vertcat(D[:2, :], D[2:, :] + mode)  # the rates' lower half: the accelerations
        s = np.ones(transcription.intervals(2 * n + 1))  # a uniform mesh
        moved = np.array(transcription.defects(X, D_moved, h, s), float)
        assert np.allclose(moved, np.array(transcription.defects(X, D, h, s), float)), transcription
        assert float(transcription.smoothing(mode, h, s)) == pytest.approx(2 * cost * h * c ** 2)
    linear = ca.DM(np.outer([1.0, -3.0], np.linspace(0.0, 1.0, 2 * n + 1)))
    assert float(HermiteSimpson.smoothing(linear, h, np.ones(n))) == pytest.approx(0.0, abs=1e-20)
