"""What holds a solved stride: the bounds of its own NLP that it sits on.

An optimum on a bound is set by the bound, not by the mechanics (design.md section 7: "no phase
duration held by a numerical bound"), so a stride says which it sits on (`Stride.on_bound`,
`Stride.held`, both in its remarks):

- the phase durations (problem.StrideSettings.duration: a runner's, with sources), `on_bounds`;
- the solve's numerical bounds on the states, accelerations and forces (collocation's
  STATE_RATE 15 rad/s and m/s, ACCELERATION 1000 rad/s^2, the joints' ranges of running plus
  joint_space.LIMIT_MARGIN, the trunk's lean, the hip's height, contact.FORCE_LIMIT and
  FRICTION_FORCE) and the torque rungs' torque limit, `held_by_bounds`.

Left out on purpose: a normal force or impulse at zero (a point unloading: the contact law
itself), the work objectives' power-split slacks, the muscles' controls and states (an
excitation at zero is a muscle at rest; their reserves have their own check).

A variable is on a bound when it lies within ON_BOUND (relative to max(1, |bound|)) of it:
IPOPT leaves a variable its bound holds within about 1e-8 of it (bound_relax_factor), a free
one farther off.
"""

from __future__ import annotations

import math

import numpy as np

from ...mechanics.joint_space import JOINTS, THETA

# A phase duration this close to one of its bounds (s): IPOPT leaves a variable it holds at a
# bound within about 1e-8 s of it; a free phase lies farther off (the closest seen on the
# shipped scenes, 2026-11-25: 6.7 ms). 0.1 ms is 1 % of the shortest bound (the heel's 0.01 s).
ON_BOUND_S = 1e-4
# Any other variable (relative to max(1, |bound|)); see the module docstring.
ON_BOUND = 1e-6
# the units of THETA's rows (`_rows`)
_STATE_UNITS = ["m", "m", "rad", *["rad"] * len(JOINTS)]


def on_bounds(durations: list, bounds: dict) -> list[dict]:
    """The phases (name, duration s) within ON_BOUND_S of their (low, high) bounds (s)."""
    return [{"phase": name, "duration_s": d, "side": side, "bound_s": bound}
            for name, d in durations for side, bound in zip(("low", "high"), bounds[name])
            if abs(d - bound) <= ON_BOUND_S]


def held_by_bounds(nlp, blocks: dict) -> list[dict]:
    """The variables of a solution (blocks by name) on one of the solve's bounds (module
    docstring), grouped by variable and side: {"variable", "side": "low" | "high", "bound"
    (m, rad, rad/s, rad/s^2, N m/kg or body weights), "unit", "phases" (in order), "nodes"
    (how many columns)}."""
    lower = nlp.blocks.split(np.concatenate(nlp.blocks.lower))
    upper = nlp.blocks.split(np.concatenate(nlp.blocks.upper))
    found: dict[tuple, dict] = {}
    for key, value in blocks.items():
        names = _rows(nlp, key)
        if names is None:
            continue
        value = np.asarray(value, float)
        for side, bound in (("low", lower[key]), ("high", upper[key])):
            on = np.isfinite(bound) & (np.abs(value - bound) <= ON_BOUND * np.maximum(1.0, np.abs(bound)))
            for row, column in zip(*np.nonzero(on)):
                name, unit = names[row]
                if key.startswith("F_") and side == "low" and bound[row, column] == 0.0:
                    continue
                entry = found.setdefault((name, side), {"variable": name, "side": side, "bound": float(bound[row, column]),
                                                        "unit": unit, "phases": [], "nodes": 0})
                entry["nodes"] += 1
                phase = key.split("_", 1)[1]
                if phase not in entry["phases"]:
                    entry["phases"].append(phase)
    return list(found.values())


def _rows(nlp, key: str) -> list[tuple[str, str]] | None:
    """(name, unit) of each row of block `key` (None: a block whose bounds do not count, the
    module docstring)."""
    kind, _, phase = key.partition("_")
    states = [(f"{n} angle" if u == "rad" else n, u) for n, u in zip(THETA, _STATE_UNITS)]
    rates = [(f"{n} rate", u + "/s") for n, u in zip(THETA, _STATE_UNITS)]
    if kind == "X":
        return states + rates
    if key == "V_touchdown":
        return [(f"{n} after the touchdown", u) for n, u in rates]
    if kind == "A":
        return [(f"{n} acceleration", u + "/s^2") for n, u in zip(THETA, _STATE_UNITS)]
    dynamic = nlp.settings.moment_time > 0
    if kind == ("Z" if dynamic else "U") and nlp.settings.muscles is None:  # the torque rungs' limit
        return [(f"{j} torque", "N m/kg") for j in JOINTS]
    if kind == "U" and dynamic:
        return [(f"{j} torque rate", "x100 N m/kg/s") for j in JOINTS]
    if kind == "F":
        rows = nlp.ocp.models[[p.name for p in nlp.phases].index(phase)].contact.rows
        return [(f"{p} {'tangential' if a == 't' else 'normal'} force", "BW") for p, a in rows]
    return None


# Said after the bounds when a rate or an acceleration is among them: those boxes are the solver's
# (collocation.STATE_RATE, ACCELERATION), and lifted they moved the torque scenes' optima.
BOXES_NOTE = ("The rates' and accelerations' bounds are boxes for the solver, not a runner's limits: a stride "
              "on them is set by the box (lifted, the torque scenes' strides moved 7-50 % in cost: "
              "docs/concepts/stride.md, 'What holds the torque scenes' stride')")


def held_text(held: list[dict]) -> str:
    """The bounds a stride sits on, in words ("" when none): "held by the solve's bounds, not
    the mechanics: knee_R rate 15 rad/s (heel: 1 node); ..." (angles in deg), and BOXES_NOTE
    where a rate or an acceleration is held."""
    if not held:
        return ""
    parts = []
    for h in held:
        value, unit = h["bound"], h["unit"]
        if unit == "rad":
            value, unit = math.degrees(value), "deg"
        nodes = f"{h['nodes']} node{'s' if h['nodes'] > 1 else ''}"
        parts.append(f"{h['variable']} {value:.4g} {unit} ({', '.join(h['phases'])}: {nodes})")
    boxes = any(h["unit"] in ("rad/s", "m/s", "rad/s^2", "m/s^2") for h in held)
    return "held by the solve's bounds, not the mechanics: " + "; ".join(parts) + (f". {BOXES_NOTE}" if boxes else "")
