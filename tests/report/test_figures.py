"""report.figures: compare's cadence figure promises only the stars it draws."""

from formopt.report.figures import stride_cadence_figure


def curve(name, free):
    return {"name": name, "converged": True, "cadence_spm": [150.0, 160.0, 170.0],
            "mechanical_power_W": [400.0, 380.0, 390.0], "impact_loss_W": [9.0, 8.0, 7.5],
            "free_cadence_spm": free[0], "free_mechanical_power_W": free[1]}


def test_the_cadence_figure_names_stars_only_where_it_draws_them():
    s = {"curves": [curve("nominal", (161.0, 379.0)), curve("8 Hz", (None, None))],
         "measured_cadence_spm": 171.4, "speed_mps": 3.5, "measured_strike": "heel"}
    power, loss = stride_cadence_figure(s).axes[:2]
    stars = [ln for ln in power.lines if ln.get_marker() == "*"]
    assert len(stars) == 1 and "star" in power.get_title()
    assert not [ln for ln in loss.lines if ln.get_marker() == "*"] and "star" not in loss.get_title()
    s["curves"] = [curve("nominal", (None, None))]
    assert "star" not in stride_cadence_figure(s).axes[0].get_title()
