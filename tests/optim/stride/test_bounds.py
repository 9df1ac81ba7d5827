"""optim.stride.bounds: a stride says which of its NLP's bounds hold it (the phase durations,
the solve's numerical bounds, the torque limit), and leaves out the bounds that are the
contact law itself."""

import numpy as np
import pytest

from formopt.io.muscle_table import body_muscles
from formopt.mechanics.joint_space import THETA, JointSpace
from formopt.optim.stride.bounds import BOXES_NOTE, ON_BOUND_S, held_by_bounds, held_text, on_bounds
from formopt.optim.stride.collocation import ACCELERATION, STATE_RATE, StrideNLP
from formopt.optim.stride.contact import FORCE_LIMIT, FRICTION_FORCE
from formopt.optim.stride.problem import StrideSettings
from formopt.optim.stride.result import Stride

NX = len(THETA)


def test_a_phase_on_its_duration_bound_is_named_in_the_remarks():
    bounds = StrideSettings().duration
    low, high = bounds["heel"][0], bounds["forefoot"][1]
    durations = [("heel", low + 0.2 * ON_BOUND_S), ("flat", 0.1), ("forefoot", high), ("flight", 0.12)]
    found = on_bounds(durations, bounds)
    assert [(b["phase"], b["side"]) for b in found] == [("heel", "low"), ("forefoot", "high")]
    s = Stride.__new__(Stride)
    s.on_bound, s.held, s.impacts, s.friction, s.budget = found, [], [], 0.8, {}
    assert s.remarks[0].startswith("heel phase 10.0 ms on its low bound (10 ms)")
    assert not on_bounds([("heel", low + 2 * ON_BOUND_S)], bounds)


@pytest.fixture(scope="module")
def nlp(body):
    return StrideNLP(JointSpace(body), StrideSettings(strike="heel", nodes=18))


def _inside(nlp) -> dict:
    """A decision vector strictly inside every bound (the midpoint, or 0 where a side is open)."""
    lo, hi = np.concatenate(nlp.blocks.lower), np.concatenate(nlp.blocks.upper)
    low, high = np.isfinite(lo), np.isfinite(hi)
    x = np.add(lo, hi, where=low & high, out=np.zeros_like(lo)) / 2
    x[low & ~high] = lo[low & ~high] + 1.0
    x[~low & high] = hi[~low & high] - 1.0
    return nlp.blocks.split(x)


def test_a_solution_inside_its_bounds_is_held_by_none(nlp):
    assert held_by_bounds(nlp, _inside(nlp)) == []


def test_the_solves_bounds_are_found_and_grouped_by_variable(nlp):
    b = _inside(nlp)
    knee = NX + 4  # knee_R's rate
    b["X_heel"][knee, 0] = STATE_RATE
    b["A_flight"][8, [1, 2]] = -ACCELERATION * (1 - 1e-8)  # ankle_L, within IPOPT's relaxation
    b["A_flat"][8, 0] = -ACCELERATION
    b["F_heel"][1, :] = 0.0  # the heel's normal force at zero: a point unloading, not a bound's work
    b["F_flat"][1, 3] = FORCE_LIMIT
    b["U_forefoot"][2, 0] = nlp.settings.torque_limit
    held = {(h["variable"], h["side"]): h for h in held_by_bounds(nlp, b)}
    assert set(held) == {("knee_R rate", "high"), ("ankle_L acceleration", "low"),
                         ("heel_R normal force", "high"), ("ankle_R torque", "high")}
    ankle = held[("ankle_L acceleration", "low")]
    assert ankle["phases"] == ["flat", "flight"] and ankle["nodes"] == 3 and ankle["unit"] == "rad/s^2"
    text = held_text(list(held.values()))
    assert text.startswith("held by the solve's bounds, not the mechanics: knee_R rate 15 rad/s (heel: 1 node)")
    assert "ankle_L acceleration -1000 rad/s^2 (flat, flight: 3 nodes)" in text
    assert text.endswith(f". {BOXES_NOTE}")  # a rate and an acceleration among them: the solver's boxes


def test_angles_are_said_in_degrees(nlp):
    b = _inside(nlp)
    b["X_flight"][4, 2] = nlp.blocks.split(np.concatenate(nlp.blocks.lower))["X_flight"][4, 2]  # knee_R at -5 deg
    assert held_text(held_by_bounds(nlp, b)) == \
        "held by the solve's bounds, not the mechanics: knee_R angle -5 deg (flight: 1 node)"


def test_a_tangential_force_and_the_touchdowns_rates_are_found(nlp):
    b = _inside(nlp)
    b["F_heel"][0, 2] = -FRICTION_FORCE  # heel_R tangential, its low bound (a bound's work, not the law's)
    b["V_touchdown"][NX - 1, 0] = -STATE_RATE  # ankle_L's rate after the touchdown
    held = {(h["variable"], h["side"]) for h in held_by_bounds(nlp, b)}
    assert held == {("heel_R tangential force", "low"), ("ankle_L rate after the touchdown", "low")}


def test_the_muscles_controls_and_states_are_left_out(body):
    """An excitation at zero is a muscle at rest, a reserve has its own check: the muscles'
    controls and states on their bounds are not listed; the body's states still are."""
    nlp = StrideNLP(JointSpace(body), StrideSettings(strike="flat", nodes=14, objective="metabolic",
                                                     muscles=body_muscles(body)))
    b = _inside(nlp)
    lower = nlp.blocks.split(np.concatenate(nlp.blocks.lower))
    for key in b:
        if key[0] in "UZ":
            b[key][:] = lower[key]
    assert held_by_bounds(nlp, b) == []
    b["X_flat"][NX + 4, 0] = STATE_RATE
    assert [h["variable"] for h in held_by_bounds(nlp, b)] == ["knee_R rate"]
