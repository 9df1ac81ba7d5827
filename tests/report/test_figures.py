"""Figures drawn from the rows a command writes (report/figures.py); compare's cadence figure
promises only the stars it draws; compare's comparison figure says why a side has no optimum."""

from types import SimpleNamespace as NS

import matplotlib.pyplot as plt
import numpy as np

import formopt
from formopt.report.figures import TITLE_CHARS, comparison_figure, stride_cadence_figure, sweep_figure


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


def comparison(left_optimum=None):
    """A synthetic two-sided comparison (compare's Comparison and its JSON, as far as the figure
    reads them): the right side with an optimum held by limits against an invalid reference,
    the left with `left_optimum` (None: none solved, a flat Coulomb side)."""
    demo = formopt.load("demo")
    x, moved = demo.state, demo.state + np.r_[0, 0, 0.1, -0.05, np.zeros(6)]
    why = ("3 of 3 steps are flat (both points down within 10 ms, the model and the markers agreeing): "
           "a flat strike's Coulomb impact has no smooth optimum (optim.posture.admissible)")
    right = NS(point="forefoot", steps=[0, 2, 4], reference=x, optimum=NS(success=True, state=moved, impact=NS(T_c=1.1)))
    left = NS(point="flat", steps=[1, 3, 5], reference=x, optimum=left_optimum, why_not=why if left_optimum is None else "")
    c = NS(sides={"R": right, "L": left}, body=demo.body, law="coulomb", T_c_band=[(1.2, 1.5)] * 6,
           steps=NS(cadence_spm=171.4, touchdowns=[NS(time=0.3 * k) for k in range(6)]),
           step_T_c=lambda k: 1.3 + 0.02 * k)
    joints = ("trunk", "hip", "knee", "ankle")
    headline = ("REFERENCE INVALID under coulomb (slip beyond the cone: mu_c 1.31 > 0.8): no saving measured "
                "against it; HELD BY ankle_deg lower, knee_deg upper")
    rep = {"optimum": {"R": {"headline": headline, "difference_deg": dict(zip(joints, (1.0, -3.0, 5.0, -2.0)))},
                       "L": {"headline": f"NO OPTIMUM: {why}", "law": "coulomb",
                             "reference": {"valid": False, "warnings": ["normal impulse pulls at heel"]}}},
           "summary": {s: {"angles_deg_sd": dict(zip(joints, (1.0, 2.0, 2.5, 3.0)))} for s in "RL"}}
    return c, rep, headline, why


def test_a_side_without_an_optimum_says_why_and_no_title_is_cut():
    """Issue 36: the side without an optimum had an empty joint panel, and the titles were cut
    at 70 characters."""
    c, rep, headline, why = comparison()
    fig = comparison_figure(c, rep)
    (stick_r, joints_r, _), (stick_l, joints_l, tc_l) = np.reshape(fig.axes, (2, 3))
    words = "".join(stick_r.get_title().split())
    assert words == "".join(f"right: {headline}".split())  # wrapped, not cut
    assert all(len(line) <= TITLE_CHARS for ax in fig.axes for line in ax.get_title().splitlines())
    assert joints_r.patches and not joints_l.axison
    note = " ".join(t.get_text() for t in joints_l.texts)
    assert " ".join(note.split()) == f"no valid optimum: {why}"
    assert "INVALID under coulomb (normal impulse pulls at heel)" in " ".join(stick_l.get_title().split())
    assert [ln.get_label() for ln in stick_l.lines if not ln.get_label().startswith("_")] == ["measured (mean flat touchdown)"]
    assert not [ln for ln in tc_l.lines if ln.get_linestyle() == "--"]  # no optimum's T_c drawn
    plt.close(fig)


def test_an_optimum_that_failed_is_not_drawn():
    failed = NS(success=False, verdict="NO OPTIMUM (Maximum_Iterations_Exceeded)", state=None, impact=None)
    c, rep, _, _ = comparison(failed)
    fig = comparison_figure(c, rep)
    note = " ".join(t.get_text() for t in fig.axes[4].texts)
    assert note == "no valid optimum: Maximum_Iterations_Exceeded"
    plt.close(fig)

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
