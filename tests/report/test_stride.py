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
