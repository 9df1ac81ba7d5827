"""The posture NLP under the Coulomb and frictionless laws: the fixed Coulomb mode agrees
with the impact map, its derivatives with finite differences, the optimum with its checks."""

import copy
import tomllib
from pathlib import Path

import numpy as np
import pytest
from helpers import assert_nlp_derivatives

from formopt import SceneError, solve
from formopt.io.scene import parse
from formopt.mechanics import contact
from formopt.mechanics.impact import Check

DEMO = tomllib.loads((Path(__file__).with_name("bounded.toml")).read_text())


def scene(law, **optimize):
    data = copy.deepcopy(DEMO)
    data["ground"]["contact"] = law
    data["optimize"].update(optimize)
    return parse(data, "edited.toml")


@pytest.fixture(scope="module")
def coulomb():
    s = scene("coulomb", max_slip_mps=2.0, starts=3)
    return s, s.posture_problem()


def test_fixed_mode_objective_is_the_impact_maps_where_the_mode_holds(coulomb):
    s, problem = coulomb
    mode, _ = problem.mode
    rng = np.random.default_rng(7)
    impact = s.impact()
    compared = 0
    for u in rng.uniform(0, 1, (200, len(problem.index))):
        x = problem.to_state(u)
        g = np.asarray(problem.constraint_function(u, problem.p0), float).ravel()
        region = [k for k, r in enumerate(problem.records) if r.name.startswith("coulomb_mode")]
        r = impact(x)
        approaching = Check.NO_APPROACH not in r.checks  # the NLP's approach constraint holds
        if np.all(g[region] > 1e-9) and approaching:  # inside the fixed mode: the same impact
            assert r.mode == contact.MODES[mode]
            assert float(problem.objective_function(u, problem.p0)) == pytest.approx(r.T_c, rel=1e-9)
            compared += 1
    assert compared > 20


def test_coulomb_nlp_derivatives_match_finite_differences(coulomb):
    _s, problem = coulomb
    rng = np.random.default_rng(8)
    assert_nlp_derivatives(problem, rng.uniform(0.1, 0.9, (5, len(problem.index))))


def test_coulomb_optimum_is_valid_in_its_mode_and_within_the_slip_bound(coulomb):
    _s, problem = coulomb
    opt = problem.solve()
    assert opt.success and opt.impact.valid and opt.impact.law == "coulomb"
    assert opt.impact.mode == contact.MODES[problem.mode[0]]
    assert abs(opt.impact.slip_velocity) <= 2.0 * (1 + 1e-6)
    assert opt.objective == pytest.approx(opt.impact.T_c, rel=1e-8)
    assert any("Coulomb mode fixed" in n for n in opt.notes)
    assert opt.impact.T_c <= opt.impact.contact_laws["no-slip"].T_c


def test_frictionless_optimum_never_uses_friction():
    opt = solve(scene("frictionless", starts=2))
    assert opt.success and opt.impact.law == "frictionless"
    assert opt.impact.impulse_total[0] == 0.0


@pytest.mark.parametrize("law, edit, key", [
    ("no-slip", {"max_slip_mps": 1.0}, "optimize.max_slip_mps"),
    ("coulomb", {"objective": "T_c_total"}, "ground.contact"),
])
def test_laws_the_nlp_cannot_take_are_refused(law, edit, key):
    with pytest.raises(SceneError, match=key):
        scene(law, **edit)
