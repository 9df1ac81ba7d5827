"""The landing under each contact law: energy bookkeeping with sliding friction, the
friction cone through the contact phase, the stick event, the impacts' law."""

import copy
import tomllib

import numpy as np
import pytest
from helpers import SHIPPED

from formopt import simulate
from formopt.io.scene import parse

SPRING = tomllib.loads((SHIPPED / "landing_spring.toml").read_text())
# a forefoot strike whose foot is not swept back: it needs friction 1.96 to stick, so under
# Coulomb it slides (the shipped scene's swept foot sticks at friction 0.8)
SPRING["touchdown"].update(angles_deg={"trunk": 5.0, "hip": 25.0, "knee": 15.0, "ankle": -12.0},
                           angular_velocity_dps={"thigh": 40.0, "shank": -220.0, "foot": -140.0})


def landing(law, friction=None, **edits):
    data = copy.deepcopy(SPRING)
    data["ground"]["contact"] = law
    if friction is not None:
        data["ground"]["friction"] = friction
    data.update(edits)
    return parse(data, "edited.toml"), simulate(parse(data, "edited.toml"))


@pytest.fixture(scope="module", params=[0.3, 0.8])
def coulomb(request):
    return landing("coulomb", request.param)


def contact_phase(L):
    """Samples with one held foot point and finite force (between the impacts)."""
    return np.array([len(a) == 1 and np.all(np.isfinite(f)) for a, f in zip(L.active, L.force)])


def test_coulomb_landing_keeps_energy_and_the_friction_cone(coulomb):
    scene, L = coulomb
    assert L.ended == "heel and forefoot both down"
    assert L.energy_error < 1e-6  # T + V + springs + (dampers and sliding friction) + T_c
    assert L.drift < 1e-9
    held = contact_phase(L)
    f_t, f_n = L.force[held].T
    assert np.all(f_n > 0)
    assert np.all(np.abs(f_t) <= scene.friction * f_n * (1 + 1e-9))
    sliding = held & (L.slide != 0)
    # a sliding point feels the kinetic friction -mu s f_n exactly
    np.testing.assert_allclose(L.force[sliding, 0], -scene.friction * L.slide[sliding] * L.force[sliding, 1],
                               rtol=1e-12)


def test_a_sliding_point_sticks_when_its_tangential_velocity_reaches_zero(coulomb):
    scene, L = coulomb
    first = L.impacts[0]
    assert first.mode == "slide" and abs(first.slip) > 0.5  # the realistic forefoot slides
    model = scene.model()
    stuck = np.flatnonzero((L.slide[:-1] != 0) & (L.slide[1:] == 0))
    assert stuck.size, "the sliding forefoot never came to rest"
    k = stuck[0] + 1
    t_axis = np.array([1.0, 0.0])
    assert abs(L.qd[k][model.cols("forefoot")] @ t_axis) < 1e-9  # at rest along the ground
    # while it slid, it moved in its sliding direction; held, it moves no more
    v = np.array([qd[model.cols("forefoot")] @ t_axis for qd in L.qd])
    sliding = contact_phase(L) & (L.slide != 0)
    assert np.all(v[sliding] * L.slide[sliding] >= -1e-9)
    after = contact_phase(L) & (np.arange(len(L.t)) > k) & (L.slide == 0)
    assert np.all(np.abs(v[after]) < 1e-7)


def test_frictionless_landing_has_no_tangential_force():
    _, L = landing("frictionless")
    held = contact_phase(L)
    assert np.all(L.force[held, 0] == 0.0)
    assert all(e.impulse[0] == 0.0 for e in L.impacts)
    assert L.energy_error < 1e-6


def test_laws_order_the_first_impact_as_at_the_impact():
    """The landing's first impact is the impact map's, law by law."""
    from formopt import impact
    for law in ("no-slip", "coulomb", "frictionless"):
        scene, L = landing(law)
        r = impact(scene)
        assert L.impacts[0].T_c == pytest.approx(r.T_c, rel=1e-9)
        np.testing.assert_allclose(L.impacts[0].impulse, r.impulse_total, rtol=1e-8, atol=1e-10)
        assert L.impacts[0].mode == (r.mode or {"no-slip": "stick", "frictionless": "slide"}[law])


def test_coulomb_landing_with_ample_friction_holds_like_no_slip():
    """Where the first impact sticks and friction never runs short, Coulomb is no-slip."""
    _, strict = landing("no-slip", 50.0)
    _, loose = landing("coulomb", 50.0)
    assert loose.impacts[0].mode == "stick"
    assert not np.any(loose.slide)
    assert loose.T_c_total == pytest.approx(strict.T_c_total, rel=1e-9)
