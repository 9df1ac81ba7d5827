"""measure.plate against forces of known shape: the impact window and ratios, and where the
centre of pressure puts the first push along a foot that rides the belt."""

import numpy as np
import pytest

from formopt.measure.plate import COP_WINDOW_S, cop_point, plate_impact, strike_index

X, Z = np.array([1.0, 0, 0]), np.array([0, 0, 1.0])


def test_plate_impact_on_a_force_of_known_shape():
    """A vertical force rising linearly to 1.5 BW in 25 ms (60 BW/s), falling to 1 BW and
    rising to the active peak; the horizontal force -0.2 times the vertical: the window ends
    at the impact peak, the impulse ratio is -0.2, the loading rate 60 BW/s (within what the
    force's 50 Hz low-pass rounds off)."""
    rate, weight, t0 = 1000.0, 600.0, 0.1
    t = np.arange(0, 0.5, 1 / rate)
    s = t - t0
    bw = np.interp(s, [0.0, 0.025, 0.045, 0.12, 0.25], [0.0, 1.5, 1.0, 2.5, 0.0], left=0.0, right=0.0)
    force = np.stack([-0.2 * bw * weight, np.zeros_like(t), bw * weight], axis=1)
    found = plate_impact(force, rate, X, Z, t0, weight)
    assert found.peak and found.window_s == pytest.approx(0.025, abs=0.004)
    assert found.impulse_ratio == pytest.approx(-0.2, abs=1e-6)
    assert found.impact_peak_bw == pytest.approx(1.5, rel=0.1)
    assert found.loading_rate_bw_per_s == pytest.approx(60.0, rel=0.1)



def test_the_strike_index_follows_the_foot_along_the_belt_and_weighs_out_the_first_samples():
    """A foot 0.2 m long riding the belt backward at 3.5 m/s; the push at 0.85 of it from the
    heel throughout, but the first two samples (at 50-60 N) put the centre of pressure 1 m off
    either way: the force-weighted index is 0.85 within what those two samples weigh."""
    rate, t0 = 1000.0, 0.1
    t = np.arange(0, 0.3, 1 / rate)
    heel = 1.0 - 3.5 * t
    force_z = np.interp(t - t0, [0.0, 0.03], [50.0, 1200.0], left=0.0)
    cop_x = heel + 0.85 * 0.2
    k0 = round(t0 * rate)
    cop_x[k0], cop_x[k0 + 1] = cop_x[k0] + 1.0, cop_x[k0 + 1] - 1.0
    force = np.stack([np.zeros_like(t), np.zeros_like(t), force_z], axis=1)
    cop = np.stack([cop_x, np.zeros_like(t), np.zeros_like(t)], axis=1)
    frames = np.arange(0, 0.3, 1 / 150)  # the markers at 150 Hz
    index = strike_index(force, cop, rate, Z, X, t0, frames, 1.0 - 3.5 * frames, 1.2 - 3.5 * frames)
    window = force_z[k0:k0 + round(COP_WINDOW_S * rate) + 1]
    assert index == pytest.approx(0.85 + (force_z[k0] - force_z[k0 + 1]) * 5.0 / window.sum(), abs=1e-6)
    assert cop_point(index) == "forefoot" and cop_point(0.2) == "heel" and cop_point(0.5) == "flat"


def test_the_two_mass_fit_finds_the_pulses_it_was_built_from():
    """A contact of 0.25 s at 1000 Hz: a stopped mass's half sine peaking at 20 ms (J1 8 N s)
    on the body's half sine (J2 200 N s), with 20 N of noise: J1 within 5 %, t1 within 2 ms,
    R^2 above 0.99; the body's half sine alone leaves no pulse (J1 near 0, R^2 no better than
    the half sine's alone)."""
    from formopt.measure.plate import two_mass_fit
    rate, t0, tc, t1 = 1000.0, 0.1, 0.25, 0.020
    t = np.arange(0, 0.6, 1 / rate) - t0
    inside = (t >= 0) & (t < tc)
    body = np.where(inside, 200.0 * np.pi / (2 * tc) * np.sin(np.pi * np.clip(t, 0, tc) / tc), 0.0)
    pulse = np.where((t >= 0) & (t < 2 * t1), 8.0 * np.pi / (4 * t1) * np.sin(np.pi * np.clip(t, 0, None) / (2 * t1)), 0.0)
    noise = np.random.default_rng(0).normal(0.0, 20.0, len(t))
    for vertical, J1 in ((body + pulse + noise, 8.0), (body, 0.0)):
        force = np.stack([np.zeros_like(t), np.zeros_like(t), np.where(inside, vertical, 0.0)], axis=1)
        fit = two_mass_fit(force, rate, Z, t0 + 0.001)
        assert fit.impulse_1 == pytest.approx(J1, abs=0.05 * 8.0)
        assert fit.r2 > 0.99 and fit.contact == pytest.approx(tc, abs=0.01)
        if J1:
            assert fit.t1 == pytest.approx(t1, abs=0.002) and not fit.bounded
            assert fit.r2 > fit.r2_half_sine + 0.01
        else:
            assert fit.r2 < fit.r2_half_sine + 1e-3
