"""studies.compare's rules, each against an independent reading: the impact point from the
model's sole (geometry by hand), the saving's band and its words, the Coulomb mode's
neighbours (issue 24)."""

import math
from types import SimpleNamespace

import numpy as np
import pytest

from formopt.measure.touchdowns import FLAT_S, Touchdown
from formopt.mechanics import contact
from formopt.mechanics.body import scaled_body
from formopt.optim.posture import neighbours
from formopt.studies.compare import (
    SideOptimum,
    impact_point,
    modelled_state,
    sole_function,
)

BODY = scaled_body(62.0, 1.81)


def touchdown(foot_deg: float, order: str, omega_foot: float = 0.0) -> Touchdown:
    """A touchdown with the foot at foot_deg relative to standing (shank vertical)."""
    foot = math.radians(foot_deg)
    segments = {"trunk": 0.1, "thigh": 0.3, "shank": 0.0, "foot": foot}
    angles = {"trunk": 0.1, "hip": 0.4, "knee": 0.3, "ankle": foot}
    return Touchdown(0.0, "R", 10, "midfoot", foot, segments, angles,
                     {"thigh": 0.0, "shank": 0.0, "foot": omega_foot}, (3.5, -0.6), 0.9,
                     {"heel": (0.0, 0.9), "forefoot": (0.0, 0.9)}, contact_order=order)


def test_the_lower_point_of_the_model_sole_is_the_impact_point():
    sole = sole_function(BODY)
    heel, fore = (np.array(BODY["foot"].landmarks[p]) for p in ("heel", "forefoot"))
    length = float(np.linalg.norm(fore - heel))  # the sole, heel to metatarsal heads
    for deg in (-8.0, 3.0, 12.0):
        z_heel, z_fore, _, _ = np.asarray(sole(touchdown(deg, "heel").state()), float).ravel()
        # by hand: the forefoot stands L sin(foot angle) above the heel (sole flat in the foot)
        assert z_fore - z_heel == pytest.approx(length * math.sin(math.radians(deg)), abs=1e-12)
        point, first, _ = impact_point(sole, touchdown(deg, "heel"))
        assert point == first == ("heel" if deg > 0 else "forefoot")


def test_flat_only_when_the_model_and_the_markers_agree():
    sole = sole_function(BODY)
    # 0.3 deg: the forefoot 1 mm above the heel, approaching at 0.6 m/s: down in under 2 ms
    point, first, follows = impact_point(sole, touchdown(0.3, "flat"))
    assert first == "heel" and follows < FLAT_S and point == "flat"
    assert impact_point(sole, touchdown(0.3, "heel"))[0] == "heel"  # the markers disagree
    assert impact_point(sole, touchdown(12.0, "flat"))[0] == "heel"  # the model disagrees
    # a flat step is modelled with its sole on the ground
    x = modelled_state(touchdown(0.3, "flat"), "flat")
    z_heel, z_fore, _, _ = np.asarray(sole(x), float).ravel()
    assert z_heel == pytest.approx(z_fore, abs=1e-12)


def side(saving: float, uncertainty: float, valid: bool = True) -> SideOptimum:
    optimum = SimpleNamespace(success=True, saving=saving, verdict="interior optimum")
    checked = SimpleNamespace(valid=valid, law="coulomb", warnings=() if valid else ("the heel is 7.6 mm below the ground",))
    return SideOptimum("R", "heel", [0], np.zeros(10), checked, None, optimum, uncertainty=uncertainty)


def test_a_saving_inside_its_band_is_said_in_words():
    small = side(0.02, 0.30)
    assert small.band == pytest.approx((-0.28, 0.32)) and small.resolvable is False
    assert small.headline.startswith("no change that the measurement can resolve")
    large = side(0.5, 0.30)
    assert large.resolvable is True and large.headline == "interior optimum"


def test_an_invalid_reference_measures_no_saving():
    o = side(0.5, 0.1, valid=False)
    assert o.saving is None and o.band is None and o.resolvable is None
    assert o.headline.startswith("REFERENCE INVALID under coulomb (the heel is 7.6 mm below the ground)")


def test_coulomb_neighbours_cross_each_boundary_of_the_region():
    slide, stick, reverse = contact.SLIDE, contact.STICK, contact.REVERSE
    assert neighbours((slide, 1), 0) == [(slide, -1)]  # the sliding direction
    assert neighbours((slide, 1), 1) == []  # k_n > 0: no mode beyond
    assert neighbours((slide, 1), 2) == [(stick, 1), (reverse, 1)]
    assert neighbours((stick, -1), 1) == [(slide, -1)]
    assert neighbours((stick, 1), 2) == [(reverse, 1)]
    assert neighbours((reverse, 1), 2) == [(stick, 1)]


@pytest.fixture(scope="module")
def t35():
    from helpers import DATA

    from formopt.io import mocap
    from formopt.studies.compare import compare
    rbds = DATA / "rbds"
    return compare(mocap.read(rbds / "RBDS001runT35.c3d"), mocap.read(rbds / "RBDS001static.c3d"),
                   62.0, 1.81, friction=0.8, starts=2, per_step=False)


def test_the_coulomb_mode_is_followed_past_its_boundary(t35):
    """RBDS001 T35, left: the optimum in the reference's mode is held by that mode's region;
    solved again across it, the kept optimum is lower and its T_c is the true Coulomb law's
    (the checked impact, mode switches and all), not a mode's closed form extrapolated."""
    from formopt.optim.posture import PostureProblem
    o = t35.sides["L"]
    law = t35.results[o.steps[0]].law
    pp = PostureProblem(_model(t35), o.point, o.reference,
                        o.problem, 0.0, 0.8, law=law)
    fixed = pp.solve_fixed()
    assert any(c.name.startswith("coulomb_mode_") for c in fixed.held_by)
    assert o.optimum.objective < fixed.objective - 1e-3
    assert not any(c.name.startswith("coulomb_mode_") for c in o.optimum.held_by)
    assert o.optimum.impact.T_c == pytest.approx(o.optimum.objective, rel=1e-6)
    # the saving is measured against the reference's T_c under the law itself
    assert o.optimum.reference_objective == pytest.approx(o.checked.T_c, rel=1e-6)


def _model(c):
    from formopt.mechanics.model import build_model
    return build_model(c.body, "leg")


def test_each_side_is_its_own_and_every_step_has_its_impact_point(t35):
    for side, o in t35.sides.items():
        assert all(t35.steps.touchdowns[k].side == side for k in o.steps)
        assert all(t35.points[k] == o.point for k in o.steps)
        assert o.checked.valid  # the mean touchdown is a valid one (no point below the ground)
    for k, (lo, hi) in enumerate(t35.T_c_band):
        assert lo <= t35.step_T_c(k) <= hi


def test_a_flat_step_is_its_sequence_below_the_rigid_flat_impact():
    """RBDS001 T25's flat steps (the model and the markers agree both points are down within
    FLAT_S): the landing from each step's state puts the first point down (its T_c the impact
    map's at that point), the second within a few ms, and absorbs in all no more than the
    rigid flat impact (both points pinned at once) and no less than the first impact."""
    from helpers import DATA

    from formopt.io import mocap
    from formopt.measure import measure
    from formopt.mechanics.body import scaled_body
    from formopt.mechanics.impact import Impact
    from formopt.mechanics.landing import LandingModel
    from formopt.mechanics.model import build_model
    from formopt.studies.compare import flat_sequence, sole_function
    rbds = DATA / "rbds"
    m = measure(mocap.read(rbds / "RBDS001runT25markers.txt", rbds / "RBDS001runT25forces.txt"),
                mocap.read(rbds / "RBDS001static.c3d"), 1.81)
    body = scaled_body(62.0, 1.81)
    model, sole = build_model(body, "leg"), sole_function(body)
    lm = LandingModel(model, law="coulomb", compiled=False)
    flats = [(td, first) for td in m.steps.valid for p, first, _ in [impact_point(sole, td)] if p == "flat"][:6]
    assert len(flats) == 6
    for td, first in flats:
        seq = flat_sequence(lm, first, td.state(), 0.8)
        rigid = Impact(model, "flat", 0.0, 0.8, law="coulomb")(modelled_state(td, "flat")).T_c
        assert seq.first_J == pytest.approx(Impact(model, first, 0.0, 0.8, law="coulomb")(td.state()).T_c, rel=1e-6)
        assert 0 < seq.second_ms < 5.0
        assert seq.first_J < seq.total_J <= rigid * 1.01
