"""report.stride: the budget chart draws every term the budget balances."""

from types import SimpleNamespace

import pytest

from formopt.report.stride import budget_figure


def test_the_budget_chart_draws_every_term_it_balances():
    budget = {"positive_work_J": 138.4, "negative_work_J": 106.0, "impacts_J": 3.1, "friction_J": 0.0,
              "passive_J": 0.0, "spring_J": 29.3, "climb_J": 0.0, "balance_J": 0.0, "metabolic_J": 642.0}
    fig = budget_figure(SimpleNamespace(budget=budget, cost_of_transport=0.15, mechanical_power_W=376.0))
    ax = fig.axes[0]
    out = sum(p.get_height() for p in ax.patches if p.get_x() > 0.5)
    assert out == pytest.approx(138.4)  # the tendons' 29.3 J included
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert any("tendons" in s and "29.3" in s for s in labels) and len(labels) == 7
    assert "in - out +0.00 J" in ax.get_title()


def synthetic(mass_kg=62.0, speed_mps=3.5, n=11):
    import numpy as np

    t = np.linspace(0.0, 0.18, n)
    force = np.zeros((n, 2, 2))
    force[:6, 0] = [[-100.0, 1200.0]] * 6  # heel: braking, pushing
    return SimpleNamespace(t=t, half_period_s=0.18, mass_kg=mass_kg, speed_mps=speed_mps,
                           theta=np.zeros((n, 9)), thetad=np.zeros((n, 9)), tau=np.zeros((n, 6)),
                           tau_spring=np.zeros((n, 6)), force=force, muscles=None)


def test_the_force_figure_draws_both_components():
    from formopt.report.stride import cycle_figure

    fig = cycle_figure(synthetic(), None, "vertical")
    titles = [ax.get_title() for ax in fig.axes]
    assert titles == ["vertical (N/kg)", "fore-aft (forward +) (N/kg)"]
    fore_aft = fig.axes[1].lines[0].get_ydata()
    assert min(fore_aft) == pytest.approx(-100.0 / 62.0)


@pytest.mark.parametrize("mass, speed, drawn", [(62.0, 3.5, True), (73.0, 3.5, False), (62.0, 3.0, False)])
def test_the_measured_runner_is_drawn_only_beside_its_own_body_and_speed(mass, speed, drawn):
    from formopt.report.stride import measured_applies

    assert measured_applies(synthetic(mass, speed)) is drawn


def test_the_power_figure_is_the_net_moment_times_the_rate():
    """P = -tau theta' per kg (generation positive): an extensor moment while the knee extends."""
    import numpy as np

    from formopt.report.stride import cycle_figure

    stride = synthetic()
    stride.tau[:, 1] = 62.0  # 1 N m/kg at the right knee, extensor
    stride.thetad[:, 4] = -2.0  # the knee extending at 2 rad/s
    fig = cycle_figure(stride, None, "powers")
    assert [ax.get_title() for ax in fig.axes] == ["hip (W/kg)", "knee (W/kg)", "ankle (W/kg)"]
    assert np.max(fig.axes[1].lines[0].get_ydata()) == pytest.approx(2.0)
    assert "power of the net moment" in fig.axes[0].lines[0].get_label()


def test_the_search_line_names_its_spend_and_each_optimum():
    from formopt.report.stride import search_text

    record = {"procedure": "free cadence", "spend": 2, "solves": 30, "iterations": 1200, "seconds": 95.0,
              "optima": [{"cadence_spm": 160.2, "objective": 0.4, "valid": True, "answer": True, "reached": 3},
                         {"cadence_spm": 131.0, "objective": 0.38, "valid": False, "answer": False, "reached": 1}],
              "spread_pct": 5.3}
    line = search_text(SimpleNamespace(strike="heel", search=record, objective_value=0.4))
    assert line.startswith("search heel: global, spend 2: 30 solves, 1200 IPOPT iterations, 95 s")
    assert "160 steps/min 0.4 (the answer)," in line and "131 steps/min 0.38 (-5.0 %) invalid" in line
    assert line.endswith("(spread 5.3 %)")


def test_the_search_line_and_json_when_no_free_solve_converged(tmp_path):
    """No optimum met: the line says none and gives no spread; the record is valid JSON (the
    writer refuses NaN, so the spread is None)."""
    from formopt.io.files import write_json
    from formopt.report.stride import search_text

    record = {"procedure": "free cadence", "spend": 1, "solves": 16, "iterations": 9000, "seconds": 300.0,
              "optima": [], "spread_pct": None}
    line = search_text(SimpleNamespace(strike="heel", search=record, objective_value=float("inf")))
    assert line.endswith("0 distinct optima with the cadence free: none")
    write_json(tmp_path / "search.json", record)
