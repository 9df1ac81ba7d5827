"""Each [numerics] option reaches every path that a scene builds (its factories)."""

from dataclasses import replace

import numpy as np
import pytest
from helpers import SHIPPED

import formopt
from formopt.studies import sweep

LANDING = SHIPPED / "landing_optimum.toml"  # an [optimize] table through the landing


def with_numerics(**options):
    scene = formopt.load(LANDING)
    return replace(scene, numerics=replace(scene.numerics, **options))


@pytest.mark.parametrize("graph", ["SX", "MX"])
def test_graph_reaches_the_impact_and_the_posture_problem(graph):
    scene = with_numerics(graph=graph)
    assert scene.impact().function.is_a(f"{graph}Function")
    assert scene.impact().graph == graph and scene.posture_problem().graph == graph


@pytest.mark.parametrize("compiled", [True, False, "auto"])
def test_compiled_reaches_impact_landing_and_posture_problem(compiled):
    scene = with_numerics(compiled=compiled)
    assert scene.impact().compiled is (compiled is True)
    assert scene.landing().compiled is (compiled is not False)  # "auto": the landing pays
    assert scene.posture_problem().compiled is (compiled is True)


@pytest.mark.parametrize("hessian, expected", [("exact", "exact"),
                                               ("limited-memory", "limited-memory"),
                                               ("auto", "limited-memory")])
def test_hessian_reaches_the_posture_problem(hessian, expected):
    assert with_numerics(hessian=hessian).posture_problem().hessian == expected


def test_integrator_reaches_simulate_sweep_and_the_posture_problem(tmp_path):
    totals = {}
    for integrator in ("rk4", "midpoint"):
        scene = with_numerics(integrator=integrator)
        assert scene.landing().integrator == integrator
        assert scene.posture_problem().landing.integrator == integrator
        simulated = formopt.simulate(scene).T_c_total
        rows = sweep.run(scene, [("friction", np.array([scene.friction]))],
                         tmp_path / f"{integrator}.csv", progress=False, landings=True)
        assert float(rows[0]["T_c_total"]) == pytest.approx(simulated, rel=1e-12)
        totals[integrator] = simulated
    assert totals["rk4"] != totals["midpoint"]
