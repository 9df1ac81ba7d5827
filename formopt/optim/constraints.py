"""The posture NLP's constraints as records: name, bounds, physical meaning, expression.

`lbg <= g <= ubg` and the active set at an optimum both follow from the records, so a
constraint is written once. Every expression is smooth in the decision vector:

- no-slip law: t - mu n <= 0 and -t - mu n <= 0 (t, n: the ground's impulse, the total over
  heel and forefoot for a flat strike); every law: n >= 0 at every strike point; Coulomb and
  frictionless: optionally slip^2 <= max_slip^2;
- Coulomb: the inequalities of the impact's fixed mode (contact.coulomb_in_mode);
- the strike point approaches the ground; the other foot point is not below it;
- the gait, when held: the hip's place over the strike point, (x, z) along and normal to the
  ground (equalities, m), and optionally the strike point's tangential velocity (m/s);
- local mode: sum_k ((x_k - x_ref,k) / radius)^2 <= 1 over the angle variables;
- optionally the overstride and the hip height (m);
- landing problems: the second impact's event, the other point above the ground before it,
  the held point pushed (and not slipping) through the contact phase.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import casadi as ca
import numpy as np

from ..mechanics.model import STRIKES, ground_axes, landmarks
from .variables import FRICTION, SLOPE

# The second point must strike at least this fast (m/s, normal): a grazing touch (zero normal
# velocity, which absorbs nothing) dips below the ground by less than the integration error,
# so a slower strike is not an event the simulation would see.
SECOND_APPROACH = -0.01
APPROACH = -1e-3  # m/s: the strike point meets the ground at least this fast (normal)


@dataclass(frozen=True)
class Record:
    """One scalar constraint lower <= expression <= upper (equal when lower == upper)."""

    name: str
    lower: float
    upper: float
    unit: str  # of the expression
    meaning: str  # what it means physically when it holds the optimum
    expression: object = field(default=None, compare=False, repr=False)  # SX or MX scalar

    @property
    def equality(self) -> bool:
        return self.lower == self.upper

    @property
    def bound(self) -> float:
        """The finite bound (the lower one of an equality)."""
        return self.lower if np.isfinite(self.lower) else self.upper


def stack(records) -> tuple[object, np.ndarray, np.ndarray]:
    """g, lbg, ubg of a list of records."""
    return (ca.vertcat(*[r.expression for r in records]),
            np.array([r.lower for r in records]), np.array([r.upper for r in records]))


def _rows(name, expression, lower, upper, unit, meaning) -> list[Record]:
    """One record per entry of a vector expression, named name_1 .. name_n."""
    return [Record(f"{name}_{k + 1}", lower, upper, unit, meaning, expression[k])
            for k in range(expression.shape[0])]


def posture_constraints(posture, problem, law, u, x, out, p, reference_hip,
                        landing=None) -> list[Record]:
    """The records of the posture problem, in a fixed order: the impact's, the gait's, the
    local mode's radius, the overstride and hip height, the landing's.

    posture: variables.Posture; problem: posture.Problem; law: contact.LAWS; u, x: the scaled
    variables and the touchdown state (SX/MX); out: the impact's indicators under the law;
    p: the NLP's parameters (variables.PARAMETERS); reference_hip: (x, z) of
    the reference's hip over the strike point (m), used when the gait's placement is not
    given; landing: landing_function's outputs when the problem needs the landing.
    """
    points = STRIKES[posture.strike]
    t_axis, n_axis = ground_axes(p[SLOPE])
    hip = landmarks(x, posture.model.body, points[0])["hip"][0]
    records = _impact_records(posture, problem, law, out, p[FRICTION])
    if problem.gait is not None:
        records += _gait_records(posture, problem.gait, out, p, reference_hip, hip, t_axis, n_axis)
    if problem.radius is not None:
        angles = [k for k, v in enumerate(posture.variables) if not v.startswith("omega_")]
        spread = sum(((posture.lower[k] + (posture.upper[k] - posture.lower[k]) * u[k]
                       - posture.reference_of(p)[posture.index[k]]) / problem.radius) ** 2
                     for k in angles)
        records.append(Record("radius", -np.inf, 1.0, "",
                              "the best posture lies on the edge of the search radius: the "
                              "reference is not a local optimum", spread))
    if problem.max_overstride is not None:
        records.append(Record("overstride", -np.inf, problem.max_overstride, "m",
                              "the foot lands as far ahead of the hip as allowed", ca.dot(-hip, t_axis)))
    if problem.hip_height is not None:
        lo, hi = problem.hip_height
        height = ca.dot(hip, n_axis)
        meaning = "the hip height limit holds the optimum"
        records += [Record("hip_height_min", lo, np.inf, "m", meaning, height),
                    Record("hip_height_max", -np.inf, hi, "m", meaning, height)]
    if landing is not None:
        records += _landing_records(problem, landing, _other(points), p[FRICTION])
    return records


def _other(points) -> str | None:
    """The foot point that is not the strike point (None for a flat strike)."""
    if len(points) > 1:
        return None
    return "heel" if points == ("forefoot",) else "forefoot"


def _impact_records(posture, problem, law, out, mu) -> list[Record]:
    """Friction (no-slip), the Coulomb mode's region, the slip bound, each strike point
    pushed and approaching, the other point not below the ground."""
    inf = np.inf
    records = []
    total_t, total_n = out["impulse_total"][0], out["impulse_total"][1]
    if law == "no-slip":
        slips = "friction holds the optimum: the foot would slip past it (more friction lets the " \
                "posture go further)"
        records += [Record("no_slip_forward", -inf, 0.0, "N s", slips, total_t - mu * total_n),
                    Record("no_slip_backward", -inf, 0.0, "N s", slips, -total_t - mu * total_n)]
    if "region" in out:
        records += _rows("coulomb_mode", out["region"], 0.0, inf, "",
                         "the impact's Coulomb mode changes past here (slide, stick or reversed "
                         "slide, or the sliding direction): solve again from a posture in the next mode")
    if problem.max_slip is not None:
        records.append(Record("max_slip", -inf, problem.max_slip ** 2, "m^2/s^2",
                              "the strike point leaves the impact sliding as fast as allowed "
                              "([optimize] max_slip_mps)", out["slip"] ** 2))
    points = STRIKES[posture.strike]
    for k, point in enumerate(points):
        records.append(Record(f"push_{point}", 0.0, inf, "N s",
                              "the ground would have to pull the foot past here: the contact "
                              "would not hold", out["impulse"][2 * k + 1]))
        records.append(Record(f"approach_{point}", -inf, APPROACH, "m/s",
                              "the point would strike the ground no faster than allowed: no "
                              "impact past here", out["approach"][k]))
    other = _other(points)
    if other is not None:
        records.append(Record(f"clearance_{other}", 0.0, inf, "m",
                              "the other foot point touches the ground: past here the strike "
                              "pattern changes", out["clearance"]))
    return records


def _gait_records(posture, gait, out, p, reference_hip, hip, t_axis, n_axis) -> list[Record]:
    """The gait's hip placement over the strike point (and its foot speed), held."""
    held = hip
    if gait.hip_from_strike is not None:
        along, normal = gait.hip_from_strike
    else:  # the reference's placement: the reference in p (one optimum per measured step),
        #    written as an offset from the problem's own so that the bounds read in metres
        along, normal = reference_hip
        x_ref = posture.reference_of(p)
        held = hip - landmarks(x_ref, posture.model.body, STRIKES[posture.strike][0])["hip"][0] \
            + along * t_axis + normal * n_axis
    records = [
        Record("hip_from_strike_x", along, along, "m",
               "the gait's hip placement along the ground: the multiplier is the objective's "
               "change per m of the hip further ahead of the strike point", ca.dot(held, t_axis)),
        Record("hip_from_strike_z", normal, normal, "m",
               "the gait's hip height over the strike point: the multiplier is the "
               "objective's change per m of hip height", ca.dot(held, n_axis))]
    if gait.foot_velocity is not None:
        records.append(Record("foot_velocity", gait.foot_velocity, gait.foot_velocity, "m/s",
                              "the gait's foot speed along the ground before the strike",
                              out["v_contact"][0]))
    return records


def _landing_records(problem, landing, other, mu) -> list[Record]:
    """The second impact's event, the other point above the ground before it, the held point
    pushed (and not slipping) through the contact phase."""
    inf = np.inf
    records = [Record(f"{other}_down_at_second_impact", 0.0, 0.0, "m",
                      "the event itself: the other point reaches the ground at the second "
                      "impact", landing["residual"]),
               Record(f"approach_{other}", -inf, SECOND_APPROACH, "m/s",
                      "the other point would come down no faster than an impact the "
                      "simulation sees", landing["approach"])]
    records += _rows(f"{other}_above_ground", landing["height"][:-1], 0.0, inf, "m",
                     "the other point would touch the ground earlier in the contact phase")
    f_t, f_n = landing["force_t"], landing["force_n"]
    records += _rows("contact_push", f_n, 0.0, inf, "N",
                     "the ground would have to pull the held point: the contact would not hold")
    if problem.contact_friction:
        meaning = "friction during the contact phase holds the optimum: the held point would slide"
        records += _rows("contact_no_slip_forward", f_t - mu * f_n, -inf, 0.0, "N", meaning)
        records += _rows("contact_no_slip_backward", -f_t - mu * f_n, -inf, 0.0, "N", meaning)
    return records
