"""Each [numerics] option reaches every path that a scene builds (its factories)."""

from dataclasses import replace

import numpy as np
import pytest
from helpers import SHIPPED

import formopt
from formopt.studies import sweep

LANDING = SHIPPED / "landing_optimum.toml"  # an [optimize] table through the landing
DEMO = SHIPPED / "demo.toml"  # a gait-anchored [optimize] table: the same factory, a smaller NLP


def with_numerics(path=LANDING, **options):
    scene = formopt.load(path)
    return replace(scene, numerics=replace(scene.numerics, **options))


@pytest.mark.parametrize("graph", ["SX", "MX"])
def test_graph_reaches_the_impact_and_the_posture_problem(graph):
    scene = with_numerics(graph=graph)
    assert scene.impact().function.is_a(f"{graph}Function")
    assert scene.impact().graph == graph and scene.posture_problem().graph == graph


@pytest.mark.parametrize("compiled", [True, False, "auto"])
def test_compiled_reaches_impact_landing_and_posture_problem(compiled):
    """(The compiled posture problem is the demo's: compiling the landing NLP proves nothing more
    about the flag and costs most of this file's time.)"""
    scene = with_numerics(compiled=compiled)
    assert scene.impact().compiled is (compiled is True)
    assert scene.landing().compiled is (compiled is True)  # "auto": one landing runs interpreted
    assert scene.landing(many=True).compiled is (compiled is not False)  # a sweep's landings compiled
    assert with_numerics(DEMO, compiled=compiled).posture_problem().compiled is (compiled is True)


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
