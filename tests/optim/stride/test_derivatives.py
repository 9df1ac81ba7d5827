"""optim.stride.derivatives: IPOPT's gradient, constraint Jacobian and Hessian of the
Lagrangian, assembled node by node, against CasADi's own derivatives of the whole NLP and
against central finite differences, at a perturbed generic guess with random multipliers."""

import casadi as ca
import numpy as np
import pytest
from helpers import SEED
from scipy import sparse

from formopt.io.muscle_table import body_muscles
from formopt.mechanics.body import paper_body
from formopt.mechanics.joint_space import JointSpace
from formopt.optim.stride import StrideNLP, StrideSettings, derivatives
from formopt.optim.stride.derivatives import derived, functions
from formopt.optim.stride.guess import ballistic, perturbed
from formopt.optim.stride.problem import RUNNER_TENDONS

FORCE_RATE = {"strike": "flat", "nodes": 14, "objective": "metabolic", "muscles": "gait2d",
              "force_rate_weight": 1e4}  # the force-rate term dominant
FORCE_RATE_ABS = {**FORCE_RATE, "force_rate_power": 1, "force_rate_weight": 1e3}  # |F'|, smoothed
CASES = [{"strike": "heel", "tendons": RUNNER_TENDONS},
         {"strike": "heel", "tendons": RUNNER_TENDONS, "consistency_rows": "trapezoid"},  # its one-sided rows
         {"strike": "forefoot", "objective": "metabolic", "impact_weight": 1.0},
         {"strike": "flat", "transcription": "hermite-simpson", "nodes": 14, "tendons": RUNNER_TENDONS,
          "objective": "work"},
         {"strike": "heel", "objective": "metabolic", "muscles": "gait2d", "nodes": 18},  # an impact mid-stance
         FORCE_RATE,
         {"strike": "flat", "objective": "joint-metabolic", "nodes": 14},
         {"strike": "heel", "transcription": "hermite-simpson", "tendons": RUNNER_TENDONS, "moment_time": 0.012,
          "torque_velocity": True}]  # with the torque-velocity rows


@pytest.fixture(scope="module", params=CASES)
def case(request):
    settings = dict(request.param)
    if settings.get("muscles"):  # the muscle rung: its states, rows, reserves and costs
        settings["muscles"] = body_muscles(paper_body())
    nlp = StrideNLP(JointSpace(paper_body()), StrideSettings(**{"nodes": 18, **settings}))
    rng = np.random.default_rng(SEED)
    guess = nlp._with_power_split(perturbed(ballistic(nlp, 3.5), rng))
    if nlp.settings.objective == "joint-metabolic" or nlp.settings.moment_time or nlp.settings.force_rate_power == 1:
        # moments (or with moment dynamics their rates, with |F'| the tendon-force rates F'/10) of order
        # one: beyond the joint-metabolic smoothing (0.2 N m/kg), |F'|'s (0.5 /s)
        for phase in nlp.phases:
            guess[f"U_{phase.name}"] = rng.uniform(-2.0, 2.0, np.shape(guess[f"U_{phase.name}"]))
    x = nlp.blocks.join(guess)
    x += rng.uniform(-0.01, 0.01, x.size)
    return nlp, functions(nlp), x, np.array([3.5, 0.05, 0.8]), rng


def test_against_casadis_own_derivatives(case):
    nlp, ours, x, p, rng = case
    X, P = nlp.problem["x"], nlp.problem["p"]
    Xs, Ps = ca.SX.sym("x", X.shape[0]), ca.SX.sym("p", P.shape[0])
    fg = ca.Function("fg", [X, P], [nlp.problem["f"], nlp.problem["g"]]).expand()
    fs, gs = fg(Xs, Ps)
    lam_f, lam_g = 0.7, rng.normal(size=gs.shape[0])
    lag = lam_f * fs + ca.dot(ca.DM(lam_g), gs)
    reference = ca.Function("ref", [Xs, Ps], [ca.gradient(fs, Xs), jacobian(gs, Xs), ca.hessian(lag, Xs)[0]])
    grad, jac, hess = (m.sparse() for m in reference(x, p))
    f1, grad1 = ours["grad_f"](x, p)
    g1, jac1 = ours["jac_g"](x, p)
    H1 = ours["hess_lag"](x, p, lam_f, lam_g).sparse()
    assert float(f1) == pytest.approx(float(fg(x, p)[0]), rel=1e-12)
    np.testing.assert_allclose(np.asarray(g1).ravel(), np.asarray(fg(x, p)[1]).ravel(), atol=1e-10)
    assert_close(grad1.sparse(), grad, rtol=1e-9, atol=1e-9)
    assert_close(jac1.sparse(), jac, rtol=1e-9, atol=1e-9)
    assert_close(sparse.triu(H1), sparse.triu(hess), rtol=1e-8, atol=1e-8)


def jacobian(g: ca.SX, x: ca.SX) -> ca.SX:
    """CasADi's Jacobian dg/dx, its few rows with many entries (the stride's cadence and
    speed rows) differentiated apart from the others: in one call their coloring took 2.8 s of
    CPU for the Hermite-Simpson case instead of 0.4 s."""
    entries = np.diff(np.asarray(ca.jacobian_sparsity(g, x).T.colind()))
    dense = [int(k) for k in np.flatnonzero(entries > 60)]
    rest = [int(k) for k in np.flatnonzero(entries <= 60)]
    stacked = ca.vertcat(ca.jacobian(g[dense], x), ca.jacobian(g[rest], x))
    return stacked[np.argsort(dense + rest).tolist(), :]


def assert_close(actual: sparse.sparray, desired: sparse.sparray, rtol: float, atol: float):
    """np.testing.assert_allclose on sparse matrices, entry by entry: |a - d| <= atol + rtol |d|
    (without densifying matrices of up to 2000 x 2000)."""
    assert actual.shape == desired.shape
    assert np.isfinite(actual.data).all() and np.isfinite(desired.data).all()
    excess = abs(actual - desired) - rtol * abs(desired)
    assert excess.max() <= atol, f"largest excess {excess.max():.3g} over atol {atol}"


def test_jacobian_against_finite_differences(case):
    nlp, ours, x, p, rng = case
    J = ours["jac_g"](x, p)[1].sparse().tocsc()  # its columns read sparse (densified: 0.9 s of CPU at 2542 columns)
    g = ca.Function("g", [nlp.problem["x"], nlp.problem["p"]], [nlp.problem["g"]])
    for k in rng.choice(x.size, 20, replace=False):
        e = np.zeros(x.size)
        e[k] = 1e-6
        numeric = (np.asarray(g(x + e, p)) - np.asarray(g(x - e, p))).ravel() / 2e-6
        np.testing.assert_allclose(J[:, [k]].toarray().ravel(), numeric, rtol=1e-5, atol=1e-5)


def test_gradient_against_finite_differences(case):
    """The objective's gradient (with the joint-level metabolic cost's smooth |tau| and
    Minetti & Alexander's rational phi) against central differences."""
    nlp, ours, x, p, rng = case
    grad = np.asarray(ours["grad_f"](x, p)[1], float).ravel()
    f = ca.Function("f", [nlp.problem["x"], nlp.problem["p"]], [nlp.problem["f"]])
    for k in rng.choice(x.size, 20, replace=False):
        e = np.zeros(x.size)
        e[k] = 1e-6
        numeric = (float(f(x + e, p)) - float(f(x - e, p))) / 2e-6
        assert grad[k] == pytest.approx(numeric, rel=1e-5, abs=1e-6)


@pytest.mark.parametrize("case", [FORCE_RATE_ABS], indirect=True, ids=["force-rate-abs"])
def test_force_rate_abs_against_casadis_own_derivatives(case):
    """The smoothed |F'| term's gradient, Jacobian and Hessian, node by node, as CasADi's."""
    test_against_casadis_own_derivatives(case)


@pytest.mark.parametrize("case", [FORCE_RATE, FORCE_RATE_ABS], indirect=True, ids=["force-rate", "force-rate-abs"])
def test_force_rate_gradient_against_finite_differences(case):
    """The muscles' force-rate term (the metabolic objective's weighted sum V_i F'_i^2 / sum V_i
    per distance, or with power 1 its smoothed |F'_i|), where it dominates: the objective's
    gradient in the tendon-force rates' controls F'/10 of both legs, at every phase's first,
    middle and last column, against central differences (the random columns of the test above
    may miss them)."""
    n = len(case[0].settings.muscles.names)
    _gradient_in_controls(case, [*range(2 * n, 3 * n), *range(5 * n, 6 * n)])  # the legs' F'/10


@pytest.mark.parametrize("case", [FORCE_RATE], indirect=True, ids=["force-rate"])
def test_activation_rate_smoothing_gradient_against_finite_differences(case):
    """The transcription's smoothing of the activations' rates (actuation.MuscleDriven.smoothed):
    the objective's gradient in the controls a'/100 of both legs, which only it reads, at every
    phase's first, middle and last column, against central differences; those controls of order
    one, so that the term is felt (at the guess they are near zero)."""
    nlp, ours, x, p, rng = case
    n = len(nlp.settings.muscles.names)
    rows = [*range(n, 2 * n), *range(4 * n, 5 * n)]  # the legs' a'/100
    x = x.copy()
    for phase in nlp.phases:
        start, (height, width) = nlp.blocks.offsets[f"U_{phase.name}"], nlp.blocks.shapes[f"U_{phase.name}"]
        for row in rows:
            x[start + row:start + height * width:height] = rng.uniform(-1.0, 1.0, width)
    _gradient_in_controls((nlp, ours, x, p, rng), rows)


def _gradient_in_controls(case, rows: list[int]) -> None:
    """The objective's gradient in the controls' `rows` (actuation.MuscleDriven's u) at every
    phase's first, middle and last column against central differences, felt there (not zeros)."""
    nlp, ours, x, p, _ = case
    grad = np.asarray(ours["grad_f"](x, p)[1], float).ravel()
    f = ca.Function("f", [nlp.problem["x"], nlp.problem["p"]], [nlp.problem["f"]])
    checked = 0
    for phase in nlp.phases:
        name = f"U_{phase.name}"
        start, (height, width) = nlp.blocks.offsets[name], nlp.blocks.shapes[name]
        for column in (0, width // 2, width - 1):
            for row in rows:
                k = start + column * height + row  # column-major, as the blocks are joined
                e = np.zeros(x.size)
                e[k] = 1e-6
                numeric = (float(f(x + e, p)) - float(f(x - e, p))) / 2e-6
                assert grad[k] == pytest.approx(numeric, rel=1e-5, abs=1e-6), (name, column, row)
                checked += abs(numeric) > 1e-3
    assert checked > len(rows)  # the term is felt there, not a gradient of zeros


def test_node_models_are_derived_once_per_process(monkeypatch):
    """derivatives.derived: two NLPs of one body and settings on other node counts hold the same
    node models (the node count does not change them), derived once and shared: the second
    NLP's node derivatives derive nothing."""
    coarse, fine = (StrideNLP(JointSpace(paper_body()), StrideSettings(strike="flat", nodes=n)) for n in (14, 28))
    first = derivatives.node_derivatives(coarse)
    derive, calls = derivatives._functions, []
    monkeypatch.setattr(derivatives, "_functions", lambda node: calls.append(node) or derive(node))
    again = derivatives.node_derivatives(fine)
    assert not calls
    for a, b, da, db in zip(coarse.node_functions, fine.node_functions, first, again):
        assert a is not b and derived(a) is derived(b)
        assert (da.value, da.jacobian, da.hessian) == derived(a) and db.hessian is da.hessian
