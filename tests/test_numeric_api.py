"""One acceptance rule for the numeric API (issue 25): a non-finite, out-of-range or absurd
argument raises InputError naming the argument and its range (mechanics.limits); a scene
segment outside its physical range is refused by the loader; the impact energy is never
negative where the impact is valid."""

import math
import re

import numpy as np
import pytest
from helpers import SHIPPED
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from formopt import Impact, InputError, load, solve
from formopt.mechanics import limits
from formopt.mechanics.landing import LandingModel, simulate_state
from formopt.mechanics.model import STATE_LIMITS

NAN, INF = float("nan"), float("inf")


@pytest.mark.parametrize("override, name", [
    ({"starts": 0}, "starts"), ({"starts": 2.5}, "starts"), ({"starts": 10**6}, "starts"),
    ({"tolerance": NAN}, "tolerance"), ({"tolerance": 0.0}, "tolerance"),
    ({"tolerance": INF}, "tolerance"), ({"max_iterations": 0}, "max_iterations"),
    ({"seed": -1}, "seed"), ({"seed": "0"}, "seed")])
def test_solve_refuses_absurd_settings_before_any_work(override, name):
    with pytest.raises(InputError, match=f"^{name}: must be"):
        solve(load(SHIPPED / "demo.toml"), **override)


@pytest.fixture(scope="module")
def landing():
    scene = load(SHIPPED / "landing_spring.toml")
    return scene, LandingModel(scene.model(), scene.joints, scene.slope, False, "adaptive", "no-slip")


@pytest.mark.parametrize("friction, dt, duration, name", [
    (0.8, 1e-3, 0.0, "duration"), (0.8, 1e-3, -0.1, "duration"), (0.8, 1e-3, INF, "duration"),
    (0.8, 1e-3, NAN, "duration"), (0.8, 0.0, 0.2, "dt"), (0.8, NAN, 0.2, "dt"),
    (0.8, -1e-3, 0.2, "dt"), (0.8, 0.004, 0.002, "dt"), (0.0, 1e-3, 0.2, "friction"),
    (-1.0, 1e-3, 0.2, "friction"), (NAN, 1e-3, 0.2, "friction")])
def test_simulate_state_refuses_a_landing_that_cannot_end_or_a_ground_that_cannot_be(
        landing, friction, dt, duration, name):
    scene, lm = landing
    with pytest.raises(InputError, match=f"^{name}"):
        simulate_state(lm, scene.strike, scene.state, friction, dt, duration)


@pytest.mark.parametrize("table, key, value, limit", [
    ("thigh", "length", 1e-4, limits.SEGMENT_LENGTH_M), ("shank", "length", 5.0, limits.SEGMENT_LENGTH_M),
    ("thigh", "mass", 1e-6, limits.SEGMENT_MASS_KG), ("shank", "inertia_com", 1e-12,
                                                         limits.SEGMENT_INERTIA_KGM2)])
def test_a_segment_outside_its_physical_range_is_refused_by_the_loader(tmp_path, table, key, value,
                                                                         limit):
    text = (SHIPPED / "demo.toml").read_text().replace(
        'preset = "paper"', f'preset = "paper"\n{table} = {{ {key} = {value!r}'
        + (", com = 0.00005" if key == "length" and value < 0.01 else "") + " }")
    path = tmp_path / "scene.toml"
    path.write_text(text)
    with pytest.raises(InputError, match=re.escape(f"body.{table}.{key}: must be {limit.text()}")):
        load(path)


def test_every_limit_check_names_its_argument_and_range():
    with pytest.raises(InputError, match=r"^x: must be a finite number between 1 and 2 m, not nan$"):
        limits.check("x", NAN, limits.Range(1.0, 2.0, "m"))
    assert limits.check("n", 3.0, limits.STARTS, whole=True) == 3


LAWS = ("no-slip", "coulomb", "frictionless")


@pytest.fixture(scope="module")
def impacts(leg):
    return {(law, strike): Impact(leg, strike, 0.0, 0.8, law=law)
            for law in LAWS for strike in ("heel", "forefoot")}


@settings(max_examples=300, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(u=st.lists(st.floats(-1.0, 1.0), min_size=10, max_size=10),
       law=st.sampled_from(LAWS), strike=st.sampled_from(["heel", "forefoot"]))
def test_no_impact_absorbs_a_negative_energy(impacts, u, law, strike):
    """Anywhere in the touchdown state's limits: T_c finite and >= 0 to round-off (scaled by
    G's condition number), under every law (projections: T_c = 1/2 b^T G^-1 b >= 0; Coulomb:
    no impulse where the point does not approach the ground, contact.coulomb)."""
    x = np.array(u) * np.array(STATE_LIMITS)
    try:
        r = impacts[law, strike](x)
    except InputError as err:
        assert "singular" in str(err)
        return
    assert math.isfinite(r.T_c) and math.isfinite(r.T)
    assert r.T_c >= -1e3 * np.finfo(float).eps * r.condition * max(r.T, 1e-300)
