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


def touchdown(foot_deg: float, order: str, omega_foot: float = 0.0, cop: float | None = None) -> Touchdown:
    """A touchdown with the foot at foot_deg relative to standing (shank vertical); `cop`:
    the plate's strike index, None without a plate."""
    foot = math.radians(foot_deg)
    segments = {"trunk": 0.1, "thigh": 0.3, "shank": 0.0, "foot": foot}
    angles = {"trunk": 0.1, "hip": 0.4, "knee": 0.3, "ankle": foot}
    return Touchdown(0.0, "R", 10, "midfoot", foot, segments, angles,
                     {"thigh": 0.0, "shank": 0.0, "foot": omega_foot}, (3.5, -0.6), 0.9,
                     {"heel": (0.0, 0.9), "forefoot": (0.0, 0.9)}, contact_order=order, cop_index=cop)


def test_the_model_sole_puts_its_lower_point_first():
    sole = sole_function(BODY)
    heel, fore = (np.array(BODY["foot"].landmarks[p]) for p in ("heel", "forefoot"))
    length = float(np.linalg.norm(fore - heel))  # the sole, heel to metatarsal heads
    for deg in (-8.0, 3.0, 12.0):
        z_heel, z_fore, _, _ = np.asarray(sole(touchdown(deg, "heel").state()), float).ravel()
        # by hand: the forefoot stands L sin(foot angle) above the heel (sole flat in the foot)
        assert z_fore - z_heel == pytest.approx(length * math.sin(math.radians(deg)), abs=1e-12)
        assert impact_point(sole, touchdown(deg, "heel"))[1] == ("heel" if deg > 0 else "forefoot")


def test_the_impact_point_is_the_plate_s_where_there_is_one_else_the_markers():
    sole = sole_function(BODY)
    # a foot 3 deg toe up that lands on its lateral metatarsal: the model's sole says heel
    assert impact_point(sole, touchdown(3.0, "forefoot"))[:2] == ("forefoot", "heel")
    assert impact_point(sole, touchdown(3.0, "flat"))[0] == "flat"
    # the plate's centre of pressure wins over the markers: thirds of the heel-forefoot line
    for cop, point in ((0.9, "forefoot"), (0.5, "flat"), (0.1, "heel")):
        assert impact_point(sole, touchdown(3.0, "heel", cop=cop))[0] == point


def test_a_step_is_modelled_with_its_impact_point_on_the_ground():
    """A flat step, or a forefoot step whose sagittal foot angle holds the forefoot above the
    heel, is modelled with its sole level; a step whose point is the model's lower one as
    measured."""
    sole = sole_function(BODY)
    for deg, point, level in ((0.3, "flat", True), (3.0, "forefoot", True), (3.0, "heel", False),
                              (-5.0, "forefoot", False), (-5.0, "heel", True)):
        z_heel, z_fore, _, _ = np.asarray(sole(modelled_state(touchdown(deg, point), point)), float).ravel()
        assert (abs(z_heel - z_fore) < 1e-12) == level


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
    """RBDS001 T35, left, read as a heel strike (its model sole's lower point; the plate says
    forefoot): the optimum in the reference's mode is held by that mode's region; solved again
    across it, the kept optimum is lower and its T_c is the true Coulomb law's (the checked
    impact, mode switches and all), not a mode's closed form extrapolated."""
    from formopt.mechanics.impact import Impact
    from formopt.optim.posture import PostureProblem
    o = t35.sides["L"]
    reference = np.mean([modelled_state(t35.steps.touchdowns[k], "heel") for k in o.steps], axis=0)
    pp = PostureProblem(_model(t35), "heel", reference, o.problem, 0.0, 0.8, law="coulomb")
    fixed, optimum = pp.solve_fixed(), pp.solve()
    assert any(c.name.startswith("coulomb_mode_") for c in fixed.held_by)
    assert optimum.objective < fixed.objective - 1e-3
    assert not any(c.name.startswith("coulomb_mode_") for c in optimum.held_by)
    assert optimum.impact.T_c == pytest.approx(optimum.objective, rel=1e-6)
    # the saving is measured against the reference's T_c under the law itself
    checked = Impact(_model(t35), "heel", 0.0, 0.8, law="coulomb")(reference)
    assert optimum.reference_objective == pytest.approx(checked.T_c, rel=1e-6)


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
    """RBDS001 T25's steps whose model sole puts both points down within FLAT_S: the landing from each step's state puts the first point down (its T_c the impact
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
    flats = [(td, first) for td in m.steps.valid for _, first, follows in [impact_point(sole, td)]
             if follows <= FLAT_S][:6]
    assert len(flats) == 6
    for td, first in flats:
        seq = flat_sequence(lm, first, td.state(), 0.8)
        rigid = Impact(model, "flat", 0.0, 0.8, law="coulomb")(modelled_state(td, "flat")).T_c
        assert seq.first_J == pytest.approx(Impact(model, first, 0.0, 0.8, law="coulomb")(td.state()).T_c, rel=1e-6)
        assert 0 < seq.second_ms < 5.0
        assert seq.first_J < seq.total_J <= rigid * 1.01


def test_the_effective_mass_gives_the_frictionless_impact(t35):
    """Each touchdown's m_eff = 1 / W_nn and approach v_n against the projection's own
    frictionless impact (a normal-only contact: p_n = m_eff |v_n|, T_c = m_eff v_n^2 / 2);
    the plate's two-mass fit beside every step of the trial with forces, its R^2 above the
    body's half sine alone."""
    assert len(t35.masses) == len(t35.results)
    for im, r in zip(t35.masses, t35.results):
        free = r.contact_laws["frictionless"]
        assert im.p_n == pytest.approx(sum(v[1] for v in free.impulse.values()), rel=1e-6)
        assert free.T_c == pytest.approx(0.5 * im.m_eff * im.v_n ** 2, rel=1e-6)
        assert im.fit is not None and im.fit.r2 >= im.fit.r2_half_sine
