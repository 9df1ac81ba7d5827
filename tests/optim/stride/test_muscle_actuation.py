"""optim.stride.actuation.MuscleDriven: the muscle rung's guess makes the moments it is given
and holds the Hill equilibrium, its settings refuse what the muscles cannot take, and its
states are periodic with the legs swapped."""

import casadi as ca
import numpy as np
import pytest

from formopt.io.muscle_table import body_muscles
from formopt.mechanics import muscles as hill
from formopt.mechanics.body import paper_body, scaled_body
from formopt.mechanics.errors import InputError
from formopt.optim.stride.actuation import ACTIVATION_RATE_SMOOTHING, MuscleDriven, Torques, actuation
from formopt.optim.stride.costs import terms
from formopt.optim.stride.layout import Rows
from formopt.optim.stride.notes import (
    MUSCLE_HERMITE,
    MUSCLE_HERMITE_SHIFT,
    MUSCLE_MESH_SHIFT,
    mesh_note,
    transcription_note,
)
from formopt.optim.stride.problem import (
    FORCE_RATE_WEIGHT,
    FORCE_RATE_WEIGHTS,
    StrideSettings,
)

BODY = scaled_body(62.0, 1.81)


@pytest.fixture(scope="module")
def rung():
    return MuscleDriven(62.0, body_muscles(BODY))


def test_guess_makes_the_moments_and_holds_the_equilibrium(rung):
    """At a mid-stance posture at rest, moments within the muscles' reach (N m): the guess's
    muscle moments are the ones asked for (the least-squares split's small penalty aside) and
    its Hill rows vanish where the activation is not clipped."""
    theta = np.r_[0.0, 0.9, 0.1, 0.3, 0.6, 0.2, -0.2, 1.2, 0.0][:, None]
    tau = np.array([[40.0], [90.0], [110.0], [-20.0], [-15.0], [-5.0]])
    z, u = rung.initial(theta, np.zeros((9, 1)), tau)
    moments = np.asarray(rung.active(ca.DM(z[:, 0]), ca.DM(u[:, 0])), float)
    np.testing.assert_allclose(moments, tau, atol=3.0)
    rows = Rows()
    rung.rows(rows, ca.DM(theta[:, 0]), ca.DM.zeros(9), ca.DM(z[:, 0]), ca.DM(u[:, 0]))
    hill_rows = np.r_[np.asarray(rows.expr[1], float).ravel(), np.asarray(rows.expr[3], float).ravel()]
    a = np.r_[z[:8, 0], z[16:24, 0]]
    free = (a > 0.011) & (a < 0.999)
    assert free.sum() >= 4
    np.testing.assert_allclose(hill_rows[free], 0.0, atol=1e-9)


def test_states_swap_legs(rung):
    z = np.arange(32.0)
    swapped = np.asarray(rung.swap(ca.DM(z)), float).ravel()
    np.testing.assert_array_equal(swapped, np.r_[z[16:], z[:16]])


@pytest.mark.parametrize("scale", [ACTIVATION_RATE_SMOOTHING, 0.0, 3.0])
def test_the_smoothing_sees_the_activation_rates(rung, scale):
    """The rates the transcription's smoothing adds to the accelerations: the activations' a'
    (1/s, controls b = a'/100) of both legs times the settings' scale
    (StrideSettings.activation_rate_smoothing, through `actuation`), none of the tendon forces'
    rates, the excitations or the reserves; the torque rung's none."""
    n = rung.n
    U = np.random.default_rng(0).uniform(-1.0, 1.0, (rung.controls, 5))
    scaled = actuation(62.0, 0.0, {}, rung.muscles, rate_smoothing=scale)
    smoothed = np.asarray(scaled.smoothed(ca.DM(U)), float)
    rows = np.r_[n:2 * n, 4 * n:5 * n]  # b_R, b_L (MuscleDriven's u)
    np.testing.assert_allclose(smoothed, scale * rung.ACTIVATION_SCALE * U[rows])
    assert Torques(62.0, 4.0).smoothed(ca.DM(U[:6])).shape == (0, 5)


@pytest.mark.parametrize("value", [-1.0, float("nan"), float("inf")])
def test_the_activation_rate_smoothing_is_a_finite_number_at_least_zero(value):
    with pytest.raises(InputError, match="activation_rate_smoothing = "):
        StrideSettings(muscles=body_muscles(BODY), objective="metabolic", activation_rate_smoothing=value)


def test_the_activation_rate_smoothing_is_the_muscles_own():
    """Its default (ACTIVATION_RATE_SMOOTHING) on every rung; another value only with muscles."""
    assert StrideSettings().activation_rate_smoothing == ACTIVATION_RATE_SMOOTHING
    with pytest.raises(InputError, match=r"activation_rate_smoothing: .*actuation 'muscles'"):
        StrideSettings(activation_rate_smoothing=0.0)


def test_reserves_are_moments_per_kg(rung):
    u = np.zeros(rung.controls)
    u[-6:] = [0.1, 0, 0, 0, 0, -0.2]
    moments = np.asarray(rung.active(ca.DM.zeros(rung.states), ca.DM(u)), float).ravel()
    np.testing.assert_allclose(moments, [6.2, 0, 0, 0, 0, -12.4])


@pytest.mark.parametrize("changes", [{"objective": "effort"}, {"tendons": {"ankle": 4.0}}])
def test_muscle_settings_refuse_torque_costs_and_parallel_springs(changes):
    with pytest.raises(InputError, match="actuation 'muscles'"):
        StrideSettings(muscles=body_muscles(paper_body()), **{"objective": "metabolic", **changes})


def test_tendon_energy_is_the_integral_of_its_force():
    leg = body_muscles(BODY)
    force = np.linspace(0.0, 1.2, 4001)
    length = np.asarray(hill.tendon_length(ca.DM(force)), float).ravel() * leg.tendon_slack_length[6]
    numeric = leg.max_force[6] * np.trapezoid(force, length)
    start = hill.tendon_energy(leg, np.zeros(8))[6]
    assert hill.tendon_energy(leg, np.full(8, 1.2))[6] - start == pytest.approx(numeric, rel=1e-6)


def test_bhargava_terms_by_hand():
    """A fully active soleus at its optimal length: A + M = m_M ((1 - f)(40 + 74) + f (133 + 111))
    W isometric; shortening at 0.2 v_max adds S = (0.16 F_iso + 0.18 F_M) v and W = F_M v
    (Bhargava et al. 2004's constants; the smoothing moves them by under 1 %)."""
    soleus = hill.subset(body_muscles(BODY), ("soleus",))
    mass, fast, force, speed = soleus.mass[0], soleus.fast_twitch[0], soleus.max_force[0], 0.2 * soleus.max_velocity[0]
    held = mass * ((1 - fast) * (40 + 74) + fast * (133 + 111))
    terms = {k: float(v) for k, v in hill.metabolic_terms(soleus, 1.0, 1.0, -0.2).items()}
    fibre = force * float(hill.force_velocity(-0.2))
    assert terms["activation"] + terms["maintenance"] == pytest.approx(held, rel=1e-2)
    assert terms["shortening"] == pytest.approx((0.16 * force + 0.18 * fibre) * speed, rel=1e-2)
    assert terms["work"] == pytest.approx(fibre * speed, rel=1e-9)
    assert float(hill.metabolic_rate(soleus, 1.0, 1.0, -0.2)) == pytest.approx(sum(terms.values()), rel=1e-6)
    assert float(hill.metabolic_rate(soleus, 1.0, 1.0, 0.0)) == pytest.approx(held, rel=1e-2)


def test_force_rate_integrand_is_volume_weighted(rung):
    """The force-rate integrand: sum over legs of sum_i V_i F'_i^2 / sum_i V_i (1/s^2)."""
    u = np.zeros(rung.controls)
    u[16:24] = 0.3  # g = F'/10 of the right leg's muscles: F' = 3 /s
    u[40] = -0.5  # the left iliopsoas, F' = -5 /s
    got = rung.integrands(ca.DM.zeros(9), ca.DM.zeros(9), ca.DM.ones(rung.states) * 0.2, ca.DM(u))["force_rate"]
    share = rung.muscles.volume / rung.muscles.volume.sum()
    assert float(got) == pytest.approx(9.0 + 25.0 * share[0], rel=1e-12)


def test_force_rate_abs_integrand_is_volume_weighted_and_smooth(rung):
    """Power 1's integrand: sum over legs of sum_i V_i (sqrt(F'_i^2 + eps^2) - eps) / sum_i V_i
    (1/s), within eps of |F'|, zero at F' = 0."""
    eps = hill.FORCE_RATE_SMOOTHING
    u = np.zeros(rung.controls)
    u[16:24] = 0.3  # F' = 3 /s, the right leg's muscles
    u[40] = -0.5  # the left iliopsoas, F' = -5 /s
    got = rung.integrands(ca.DM.zeros(9), ca.DM.zeros(9), ca.DM.ones(rung.states) * 0.2, ca.DM(u))["force_rate_abs"]
    share = rung.muscles.volume / rung.muscles.volume.sum()
    smooth = [np.sqrt(x ** 2 + eps ** 2) - eps for x in (3.0, 5.0)]
    assert float(got) == pytest.approx(smooth[0] + smooth[1] * share[0], rel=1e-12)
    assert 3.0 - eps < smooth[0] < 3.0
    zero = rung.integrands(ca.DM.zeros(9), ca.DM.zeros(9), ca.DM.ones(rung.states) * 0.2, ca.DM.zeros(rung.controls))
    assert float(zero["force_rate_abs"]) == 0.0


@pytest.mark.parametrize("power, integral, weight", [(2, "force_rate", FORCE_RATE_WEIGHT),
                                                     (1, "force_rate_abs", FORCE_RATE_WEIGHTS[1])])
def test_the_force_rate_power_picks_its_term_and_its_calibrated_weight(power, integral, weight):
    settings = StrideSettings(muscles=body_muscles(paper_body()), objective="metabolic", force_rate_power=power)
    rate = [t for t in terms(settings, 70.0) if t.integral.startswith("force_rate")]
    assert [(t.integral, t.weight) for t in rate] == [(integral, weight)]
    given = StrideSettings(muscles=body_muscles(paper_body()), objective="metabolic", force_rate_power=power,
                           force_rate_weight=3.0)
    assert [t.weight for t in terms(given, 70.0) if t.integral == integral] == [3.0]


@pytest.mark.parametrize("power", [0, 3, 1.5])
def test_force_rate_power_must_be_1_or_2(power):
    with pytest.raises(InputError, match="force_rate_power"):
        StrideSettings(muscles=body_muscles(paper_body()), objective="metabolic", force_rate_power=power)


@pytest.mark.parametrize("change", [{"force_rate_power": 1}, {"force_rate_weight": 3.0}])
def test_the_force_rate_term_is_the_muscles_alone(change):
    """A torque rung has no force-rate term: its power or weight set there is refused, and the
    muscles' torque+springs start (local.torque_start) drops them."""
    with pytest.raises(InputError, match="force_rate_power / force_rate_weight"):
        StrideSettings(objective="effort", **change)


@pytest.mark.parametrize("weight", [-1.0, float("nan"), float("inf")])
def test_force_rate_weight_must_be_finite_and_not_negative(weight):
    """An infinite weight was taken: the objective inf, or nan where the force rates are zero."""
    with pytest.raises(InputError, match="force_rate_weight"):
        StrideSettings(muscles=body_muscles(paper_body()), objective="metabolic", force_rate_weight=weight)


@pytest.mark.parametrize("weight", [0.0, -1.0, float("nan"), float("inf")])
def test_reserve_weight_must_be_finite_and_positive(weight):
    """The reserves' weight is a setting (a what-if), not a module global to overwrite."""
    with pytest.raises(InputError, match="reserve_weight"):
        StrideSettings(muscles=body_muscles(paper_body()), objective="metabolic", reserve_weight=weight)


def test_the_mesh_note_gives_the_muscles_their_own_figures():
    """notes.MESH_FINE was measured on the torque+springs rung: the muscles' note never claims
    its figure; on the trapezoid it gives the muscles' own (MUSCLE_MESH_SHIFT), on Hermite-Simpson
    from 40 intervals its own (MUSCLE_HERMITE_SHIFT), measured with the calibrated cost and claimed
    for it only. What Hermite-Simpson finds for a trapezoid stride (MUSCLE_HERMITE) is the
    transcription note's, for the calibrated cost only."""
    torque = StrideSettings(nodes=40, transcription="hermite-simpson")
    muscles = body_muscles(paper_body())
    hermite = StrideSettings(nodes=40, transcription="hermite-simpson", objective="metabolic", muscles=muscles)
    trapezoid = StrideSettings(nodes=40, objective="metabolic", muscles=muscles)
    assert "0.2 % in cost" in mesh_note(torque) and "not measured" not in mesh_note(torque)
    assert MUSCLE_HERMITE_SHIFT in mesh_note(hermite) and "0.2 % in cost" not in mesh_note(hermite)
    assert MUSCLE_MESH_SHIFT in mesh_note(trapezoid) and "effort" not in mesh_note(trapezoid)
    assert MUSCLE_HERMITE in transcription_note(trapezoid) and MUSCLE_HERMITE not in mesh_note(trapezoid)
    coarse = StrideSettings(nodes=20, transcription="hermite-simpson", objective="metabolic", muscles=muscles)
    reweighted = StrideSettings(nodes=40, transcription="hermite-simpson", objective="metabolic", muscles=muscles,
                                force_rate_weight=12.0)
    for other in (coarse, reweighted):
        assert MUSCLE_HERMITE_SHIFT not in mesh_note(other) and "calibrated cost only" in mesh_note(other)
    absolute = StrideSettings(nodes=40, objective="metabolic", muscles=muscles, force_rate_power=1)
    assert MUSCLE_MESH_SHIFT in mesh_note(absolute)
    assert not any(transcription_note(s) for s in (absolute, hermite, reweighted, torque))
    assert "graded mesh was measured costlier" in mesh_note(StrideSettings(grading=1.0))
