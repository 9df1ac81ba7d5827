"""The muscle layer: published curve values, the gait2d sign mapping, the equilibrium at rest,
moment-angle curves, the metabolic rate and CasADi derivatives against central differences."""

import math

import casadi as ca
import numpy as np
import pytest
from helpers import central_difference

from formopt.io.muscle_table import gait2d_muscles
from formopt.mechanics import muscles as mu

RUNNER = (62.0, 1.81)  # RBDS001: kg, m (data/rbds/RBDSinfo.txt)


@pytest.fixture(scope="module")
def leg():
    return gait2d_muscles(*RUNNER)


@pytest.fixture(scope="module")
def functions(leg):
    return mu.leg_functions(leg)


def values(x):
    """A CasADi DM (or a float) as a flat float array."""
    return np.asarray(x, float).ravel()


def column(muscles, name):
    return muscles.names.index(name)


# -- the curves at named points (gait2d's fibres, De Groote et al. 2016's tendon and f_V) ---
def test_active_force_length_named_points(leg):
    for width in leg.width:
        assert float(mu.active_force_length(1.0, width)) == 1.0
        for side in (-1.0, 1.0):
            assert abs(float(mu.active_force_length(1.0 + side * width, width)) - math.exp(-1)) < 1e-15


def test_force_velocity_named_points():
    assert abs(float(mu.force_velocity(0.0)) - 1.0) < 3e-3  # isometric
    assert abs(float(mu.force_velocity(-1.0))) < 0.015  # v_max: no force
    assert abs(float(mu.force_velocity(1.0)) - 1.79) < 0.01  # eccentric plateau ~1.8 F_max


def test_passive_and_tendon_named_points():
    # gait2d's parallel element: slack at 1.2 l_opt, F_max at 1 l_opt beyond (k = 1); the
    # rounded corner adds (w / 2)^2 = 6e-4 at the slack length and 1e-3 at F_max
    assert abs(float(mu.passive_force_length(1.2, 1.2, 1.0)) - 6.25e-4) < 1e-15
    assert abs(float(mu.passive_force_length(2.2, 1.2, 1.0)) - 1.0) < 1.3e-3
    assert float(mu.passive_force_length(1.0, 1.2, 1.0)) < 2e-4
    # the tendon: slack at l_Ts (F = -0.012, i.e. 0), F_max at 4.7 % strain; exact inverse
    assert abs(float(mu.tendon_force(1.0))) < 0.012
    assert abs(float(mu.tendon_length(1.0)) - 1.0474) < 1e-4
    for force in (0.0, 0.3, 1.0, 1.5):
        assert abs(float(mu.tendon_force(mu.tendon_length(force))) - force) < 1e-12


# -- geometry: formopt's angles against gait2d's ---------------------------------------------
def test_lengths_are_gait2ds_with_the_sign_mapping():
    """gait2d: l_MT = L0 - d . theta_gait2d with theta_gait2d = (hip, -knee, ankle)."""
    reference = gait2d_muscles()
    d = np.array([[0.05, 0, 0], [-0.062, 0, 0], [-0.072, -0.034, 0], [0.034, 0.05, 0],
                  [0, 0.042, 0], [0, -0.02, -0.053], [0, 0, -0.053], [0, 0, 0.037]])
    theta = np.array([0.4, 0.7, -0.2])
    expected = reference.length_at_zero - d @ (theta * np.array([1, -1, 1]))
    np.testing.assert_allclose(values(mu.mtu_lengths(reference, theta)), expected, atol=1e-15)


def test_muscles_lengthen_and_pull_as_anatomy_says(leg):
    def length(name, hip=0.0, knee=0.0, ankle=0.0):
        return float(mu.mtu_lengths(leg, ca.DM([hip, knee, ankle]))[column(leg, name)])

    assert length("soleus", ankle=-0.3) < length("soleus")  # plantarflexion shortens soleus
    assert length("tibialis_anterior", ankle=-0.3) > length("tibialis_anterior")
    assert length("vasti", knee=0.5) > length("vasti")  # knee flexion lengthens vasti
    assert length("hamstrings", hip=0.5) > length("hamstrings")  # hip flexion stretches them
    assert length("hamstrings", knee=0.5) < length("hamstrings")
    assert length("iliopsoas", hip=0.5) < length("iliopsoas")

    def moments(name):  # N m per unit tendon force: extensor / plantarflexor positive
        force = np.zeros(len(leg.names))
        force[column(leg, name)] = 1.0
        return values(mu.joint_moments(leg, ca.DM(force)))

    hip, knee, ankle = moments("hamstrings")
    assert hip > 0 and knee < 0 and ankle == 0  # extend the hip, flex the knee
    assert moments("gastrocnemius")[2] > 0 and moments("gastrocnemius")[1] < 0
    assert moments("soleus")[2] > 0 and moments("tibialis_anterior")[2] < 0
    assert moments("iliopsoas")[0] < 0 and moments("glutei")[0] > 0
    assert moments("rectus_femoris")[0] < 0 and moments("rectus_femoris")[1] > 0
    assert moments("vasti")[1] > 0


def test_scaling_with_mass_and_height():
    light, heavy, tall = (gait2d_muscles(62.0, 1.8), gait2d_muscles(75.0, 1.8),
                          gait2d_muscles(75.0, 1.98))
    np.testing.assert_allclose(light.max_force / heavy.max_force, (62 / 75) ** (2 / 3))
    np.testing.assert_allclose(tall.optimal_fibre_length / heavy.optimal_fibre_length, 1.1)
    np.testing.assert_allclose(tall.moment_arms / 1.1, heavy.moment_arms, atol=1e-15)
    # a heavier runner of the same height is weaker per kg: the stride sees the body
    assert light.max_force.sum() / 62 > heavy.max_force.sum() / 75
    # fibre mass of one leg's eight units, F_max l_opt rho / sigma: 10.2 kg for the 75 kg body,
    # the order of a whole lower limb's muscle (Handsfield et al. 2014, J Biomech 47:631, by
    # MRI): gait2d's forces with sigma = 0.25 MPa err on the heavy side
    assert 8.0 < heavy.mass.sum() < 12.0


# -- the equilibrium at rest and the moment-angle curves --------------------------------------
@pytest.mark.parametrize("activation", [0.0, 0.3, 1.0])
def test_isometric_equilibrium_solves(leg, activation):
    theta = np.array([0.3, 0.4, 0.1])
    force = mu.isometric_force(leg, np.full(8, activation), theta)
    residual = mu.hill_residual(leg, activation, ca.DM(theta), ca.DM.zeros(3), ca.DM(force), 0.0)
    assert np.abs(values(residual)).max() < 1e-10
    assert np.all(force > -0.02) and np.all(force < 1.8)
    length, _ = mu.fibre_state(leg, ca.DM(theta), ca.DM.zeros(3), ca.DM(force), 0.0)
    # consistent: the tendon carries what the fibres make at that length
    fibre = (activation * mu.active_force_length(length, leg.width) * mu.force_velocity(0.0)
             + mu.passive_force_length(length, leg.passive_slack, leg.passive_stiffness))
    np.testing.assert_allclose(values(fibre), force, atol=1e-10)


def test_isometric_force_rises_with_activation(leg):
    theta = np.array([0.3, 0.4, 0.1])
    forces = [mu.isometric_force(leg, np.full(8, a), theta) for a in (0.1, 0.5, 1.0)]
    assert np.all(np.diff(forces, axis=0) > 0)


def plantarflexor_moment(leg, knee, ankle):
    active = np.isin(leg.names, ["gastrocnemius", "soleus"]).astype(float)
    theta = np.array([0.0, knee, ankle])
    force = mu.isometric_force(leg, active, theta) * active
    return float(mu.joint_moments(leg, ca.DM(force))[2])


def test_plantarflexor_moment_angle_curve_is_plausible(leg):
    """Full activation of soleus and gastrocnemius, knee straight, for RBDS001's body (62 kg,
    1.81 m): the moment rises from plantarflexion to a peak of 318 N m at 20 deg dorsiflexion
    (290 N m at a neutral ankle), twice the 155 N m (2.5 N m/kg) RBDS001's ankle peaks at in
    stance at 3.5 m/s (docs/howto/landing-and-sweep.md) and above the issue's 150-250 N m: a
    model's maximum, every fibre fully active and no antagonist."""
    angles = np.radians([-30, -20, -10, 0, 10, 20])
    moments = np.array([plantarflexor_moment(leg, 0.0, a) for a in angles])
    assert np.all(np.diff(moments) > 0)
    assert 250.0 < moments.max() < 350.0


def test_passive_forces_stay_moderate_in_a_deep_swing(leg):
    """Hip 0 deg, knee 120 deg, inactive: only rectus femoris is stretched, to 0.46 F_max
    (De Groote's single curve: 4.3 F_max, the reason for gait2d's fibre curves)."""
    force = mu.isometric_force(leg, np.zeros(8), np.radians([0.0, 120.0, 0.0]))
    assert 0.3 < force[column(leg, "rectus_femoris")] < 0.6
    assert np.all(np.delete(force, column(leg, "rectus_femoris")) < 0.05)


# -- activation dynamics and costs -----------------------------------------------------------
def test_activation_is_fast_and_deactivation_slow():
    rise = float(mu.activation_rate(1.0, 0.0))
    fall = float(mu.activation_rate(0.0, 1.0))
    assert abs(rise - 1.0 / (0.5 * mu.ACTIVATION_TIME)) < 1e-3  # 1 / (tau_a (1/2 + 0)) at a = 0
    assert abs(fall + 2.0 / mu.DEACTIVATION_TIME) < 1e-3  # -(1/2 + 3/2) / tau_d at a = 1
    assert float(mu.activation_rate(0.4, 0.4)) == 0.0


def test_activation_cost_is_the_volume_weighted_mean_cube(leg):
    n = len(leg.names)
    assert float(mu.activation_cost(leg, ca.DM.zeros(n))) == 0.0
    assert abs(float(mu.activation_cost(leg, ca.DM.ones(n))) - 1.0) < 1e-14
    one = np.zeros(n)
    one[column(leg, "vasti")] = 0.5
    share = leg.volume[column(leg, "vasti")] / leg.volume.sum()
    assert abs(float(mu.activation_cost(leg, ca.DM(one))) - share * 0.125) < 1e-14


def soleus_rate(leg, activation, velocity, length=1.0):
    soleus = mu.subset(leg, ("soleus",))
    return float(mu.metabolic_rate(soleus, activation, length, velocity))


def test_metabolic_rate_is_positive_and_larger_concentric(leg):
    velocities = np.linspace(-0.5, 0.5, 11)  # v_max, lengthening positive
    for activation in (0.0, 0.05, 0.5, 1.0):
        rates = np.array([soleus_rate(leg, activation, v) for v in velocities])
        assert np.all(rates > 0)
    concentric, isometric, eccentric = (soleus_rate(leg, 0.5, v) for v in (-0.2, 0.0, 0.2))
    assert concentric > isometric > eccentric
    # the soleus (0.83 kg) at rest pays the 1 W/kg floor; isometric at full activation and
    # l_opt 40 * 0.8 + 133 * 0.2 + 74 * 0.8 + 111 * 0.2 = 140 W/kg (Bhargava et al. 2004), less
    # 0.8 W/kg where the smoothed length factor rounds its corner at l_opt
    mass = leg.mass[column(leg, "soleus")]
    assert abs(soleus_rate(leg, 0.0, 0.0) / mass - 1.0) < 0.01
    assert abs(soleus_rate(leg, 1.0, 0.0) / mass - 140.0) < 1.0


def test_metabolic_rate_rises_with_activation(leg):
    for velocity in (-0.3, 0.0, 0.05):
        rates = [soleus_rate(leg, a, velocity) for a in np.linspace(0.0, 1.0, 11)]
        assert np.all(np.diff(rates) > 0)
    # fast lengthening: the negative lengthening heat outweighs activation and maintenance
    # heat at every activation, and the rate stays on the 1 W/kg floor
    mass = leg.mass[column(leg, "soleus")]
    for activation in (0.1, 0.5, 1.0):
        assert abs(soleus_rate(leg, activation, 0.3) / mass - 1.0) < 0.01


# -- derivatives: CasADi against central differences ----------------------------------------
def random_points(n_muscles, count, seed=3):
    """theta, theta', a, F, F' stacked: angles within running's range, F within (0, 1.5)."""
    rng = np.random.default_rng(seed)
    low = np.r_[-0.3, 0.0, -0.4, -8, -12, -10, np.zeros(n_muscles), np.full(n_muscles, 0.02),
                np.full(n_muscles, -8.0)]
    high = np.r_[1.0, 1.6, 0.35, 8, 12, 10, np.ones(n_muscles), np.full(n_muscles, 1.5),
                 np.full(n_muscles, 8.0)]
    points = [rng.uniform(low, high) for _ in range(count)]
    points.append(np.r_[0.0, 0.0, 0.0, np.zeros(3), np.zeros(n_muscles), np.full(n_muscles, 0.02),
                        np.zeros(n_muscles)])  # rest, inactive, slack: the extreme corner
    return points


@pytest.mark.parametrize("output", ["residual", "metabolic_rate"])
def test_jacobians_match_finite_differences(leg, functions, output):
    f = getattr(functions, output)
    n = len(leg.names)
    x = ca.SX.sym("x", 6 + 3 * n)
    parts = ca.vertsplit(x, [0, 3, 6, 6 + n, 6 + 2 * n, 6 + 3 * n])
    out = f(*parts)
    value = ca.Function("value", [x], [out])
    jac = ca.Function("jacobian", [x], [ca.jacobian(out, x)])
    for point in random_points(n, 4):
        exact = np.asarray(jac(point), float)
        approx = central_difference(lambda z: np.asarray(value(z), float).ravel(), point, h=1e-5)
        scale = max(1.0, np.abs(exact).max())
        np.testing.assert_allclose(approx, exact, atol=1e-6 * scale)


def test_activation_rate_derivative_matches_finite_differences(functions):
    x = ca.SX.sym("x", 16)
    out = functions.activation_rate(x[:8], x[8:])
    value, jac = ca.Function("v", [x], [out]), ca.Function("j", [x], [ca.jacobian(out, x)])
    point = np.random.default_rng(4).uniform(0.0, 1.0, 16)
    approx = central_difference(lambda z: np.asarray(value(z), float).ravel(), point, h=1e-5)
    np.testing.assert_allclose(approx, np.asarray(jac(point), float), atol=1e-5)
    assert math.isfinite(float(ca.norm_inf(jac(point))))


def test_tendon_force_rate_holds_the_hill_equilibrium(leg):
    """F' = tendon_force_rate(theta, theta', a, F) zeroes hill_residual, shortening and
    lengthening, from slack (a = 0.01) to full activation."""
    rng = np.random.default_rng(3)
    rate = mu.tendon_force_rate(leg)
    for activation in (0.01, 0.5, 1.0):
        theta, thetad = np.radians([20.0, 40.0, 5.0]), rng.uniform(-6.0, 6.0, 3)
        force = rng.uniform(0.05, 0.8, 8)
        force_rate = rate(theta, thetad, np.full(8, activation), force)
        residual = mu.hill_residual(leg, ca.DM(np.full(8, activation)), ca.DM(theta), ca.DM(thetad),
                                    ca.DM(force), force_rate)
        assert np.abs(np.asarray(residual)).max() < 1e-9
