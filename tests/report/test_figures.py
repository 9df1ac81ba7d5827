"""Figures drawn from the rows a command writes (report/figures.py); compare's cadence figure
promises only the stars it draws."""

import matplotlib.pyplot as plt

from formopt.report.figures import stride_cadence_figure, sweep_figure


def landing_row(ankle, knee, error="", valid=True):
    """A row of a landing sweep's CSV (the strings the CSV holds)."""
    values = {"T_c_first": "", "T_c_total": "", "f_n_max_N": ""} if error else \
        {"T_c_first": f"{1 + ankle / 100:.3f}", "T_c_total": f"{2 + knee / 100:.3f}", "f_n_max_N": "900"}
    return {"ankle_deg": str(ankle), "knee_deg": str(knee), "error": error, "valid": str(valid), **values}


def test_a_two_parameter_landing_sweep_draws_its_maps():
    """Valid, invalid and failed points on a 3 x 2 grid (issue 37: the two-parameter branch read
    a name only the one-parameter branch set)."""
    rows = [landing_row(a, k, valid=(a, k) != (-10, 20)) for a in (-12, -10, -8) for k in (10, 20)]
    rows[0] = landing_row(-12, 10, error="Diverged: the landing did not end")
    fig = sweep_figure(rows, ["ankle_deg", "knee_deg"])
    assert len(fig.axes) == 4  # two maps and their colour bars
    assert "4 valid, 1 invalid, 1 failed of 6" in fig._suptitle.get_text()
    plt.close(fig)

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


def test_the_nominal_cadence_curve_passes_through_its_free_optimum():
    """The envelope: the free optimum (161 steps/min, 379 W) is a point of the nominal's line."""
    s = {"curves": [curve("nominal", (161.0, 379.0)), curve("8 Hz", (165.0, 300.0))],
         "measured_cadence_spm": 171.4, "speed_mps": 3.5, "measured_strike": "heel"}
    power = stride_cadence_figure(s).axes[0]
    nominal, other = [ln for ln in power.lines if ln.get_marker() == "o"]
    assert list(nominal.get_xdata()) == [150.0, 160.0, 161.0, 170.0]
    assert list(nominal.get_ydata()) == [400.0, 380.0, 379.0, 390.0]
    assert len(other.get_xdata()) == 3  # a variant's star stays off its line
    plt.close("all")
