"""Initial guesses of the half stride: generic ("ballistic"), perturbed, or a previous solution.

Measured (problems/stride_checks.py, heel strike, 3.5 m/s, 40 nodes): the generic guess
reaches a local optimum (objective 0.774, 156 steps/min); three perturbed guesses and a
continuation from 3.0 m/s all reach a better one (0.739, 176 steps/min). A multi-start
(local.optimum's `starts`) keeps the best.

The generic guess knows nothing of the optimum: the hip moves forward at the speed at a
constant height; the stance foot lies flat under the hip's mid-stance position, the stance
leg following by inverse kinematics; the legs swap their poses over the half stride (the
swing leg with a knee flexion bump of 60 deg that keeps its foot off the ground); the ground
carries the body weight over the stance (a half-sine); joint moments are zero. The phases
last what a runner's do at about 165 steps/min (`DURATIONS`).
"""

from __future__ import annotations

import math

import numpy as np

from ...mechanics.joint_space import JointSpace, swap_legs
from .collocation import NU, NX, StrideNLP
from .transcription import Trapezoid, times

# guessed phase durations (s): RBDS001 at 3.5 m/s (contact 0.24 s, half period 0.35 s)
DURATIONS = {"slide": 0.01, "heel": 0.03, "landing": 0.03, "flat": 0.11, "forefoot": 0.09, "flight": 0.12}
TRAILING_POSE = (math.radians(-15.0), math.radians(70.0), math.radians(-10.0))  # hip, knee, ankle
SWING_KNEE_BUMP = math.radians(60.0)
TRUNK_LEAN = math.radians(5.0)


def _leg_ik(js: JointSpace, hip, ankle, trunk):
    """Hip flexion, knee flexion, ankle (rad) of a leg whose hip and ankle are at the given
    points (m, 2 x n) with the foot flat, the knee ahead of the hip-ankle line."""
    body = js.model.body
    L1, L2 = body["thigh"].length, body["shank"].length
    d = ankle - hip
    D = np.clip(np.hypot(*d), abs(L1 - L2) + 1e-3, L1 + L2 - 1e-4)
    knee = math.pi - np.arccos((L1 ** 2 + L2 ** 2 - D ** 2) / (2 * L1 * L2))
    thigh = np.arctan2(d[0], -d[1]) + np.arccos((L1 ** 2 + D ** 2 - L2 ** 2) / (2 * L1 * D))
    shank = thigh - knee
    return thigh + trunk, knee, -shank


def ballistic(nlp: StrideNLP, speed: float) -> dict:
    """The generic guess (module docstring) for the NLP's phases and nodes, by block name."""
    js, phases = nlp.js, nlp.phases
    lo_hi = nlp.settings.duration
    durations = [float(np.clip(DURATIONS[p.name], *lo_hi[p.name])) for p in phases]
    stance = sum(d for p, d in zip(phases, durations) if p.rows)
    period = sum(durations)
    t = np.concatenate([nlp.times(i, d) + sum(durations[:i]) for i, d in enumerate(durations)])
    body = js.model.body
    ankle_height = -body["foot"].landmarks["heel"][1]
    reach = 0.97 * (body["thigh"].length + body["shank"].length)
    x_ankle = speed * stance / 2
    z_hip = math.sqrt(max(reach ** 2 - x_ankle ** 2, 0.25 * reach ** 2)) + ankle_height
    theta = np.zeros((NX, t.size))
    theta[0], theta[1], theta[2] = speed * t, z_hip, TRUNK_LEAN
    s = t / period
    touchdown = np.array(_leg_ik(js, np.array([[0.0], [z_hip]]), np.array([[x_ankle], [ankle_height]]),
                                 TRUNK_LEAN)).ravel()
    trailing = np.array(TRAILING_POSE)
    in_stance = t <= stance
    hip = np.vstack([theta[0], theta[1]])
    ankle = np.vstack([np.full(t.size, x_ankle), np.full(t.size, ankle_height)])
    right = np.array(_leg_ik(js, hip, ankle, TRUNK_LEAN))
    toe_off = right[:, in_stance][:, -1]
    r = np.clip((t - stance) / (period - stance), 0, 1)
    swing_r = toe_off[:, None] + (trailing - toe_off)[:, None] * r
    theta[3:6] = np.where(in_stance, right, swing_r)
    theta[6:9] = trailing[:, None] + (touchdown - trailing)[:, None] * s
    theta[7] += SWING_KNEE_BUMP * np.sin(math.pi * s)
    thetad = _rates(theta, t)
    return _blocks(nlp, theta, thetad, durations, stance, period, speed)


def _rates(theta, t):
    """Finite-difference rates of node values (repeated times at phase boundaries allowed)."""
    out = np.zeros_like(theta)
    for k in range(t.size):
        a, b = max(k - 1, 0), min(k + 1, t.size - 1)
        while t[b] - t[a] <= 0 and b < t.size - 1:
            b += 1
        out[:, k] = (theta[:, b] - theta[:, a]) / max(t[b] - t[a], 1e-9)
    return out


def _blocks(nlp, theta, thetad, durations, stance, period, speed) -> dict:
    """Blocks by name from node histories (stacked over the phases)."""
    guess, k = {}, 0
    weight = period / stance
    for i, (phase, c) in enumerate(zip(nlp.phases, nlp.columns)):
        cols = slice(k, k + c)
        name = phase.name
        guess[f"X_{name}"] = np.vstack([theta[:, cols], thetad[:, cols]])
        guess[f"A_{name}"] = np.zeros((NX, c))
        act = nlp.ocp.models[i].actuation
        z, guess[f"U_{name}"] = act.initial(theta[:, cols], thetad[:, cols], np.zeros((NU, c)))
        if act.states:
            guess[f"Z_{name}"] = z
        normals = [a == "n" for _, a in phase.rows]
        force = np.zeros((len(phase.rows), c))
        if any(normals):
            force[normals] = weight / sum(normals)
        guess[f"F_{name}"] = force
        guess[f"T_{name}"] = durations[i]
        if nlp.split_power:  # the power split of zero moments
            guess[f"S_{name}"] = np.zeros((2 * NU, c))
        k += c
    for i, phase in enumerate(nlp.phases[1:], 1):
        if nlp.impact_before(i):
            guess[f"P_{phase.name}"] = np.zeros((len(phase.rows), 1))
    guess["P_touchdown"] = np.zeros((len(nlp.touchdown_rows), 1))
    guess["V_touchdown"] = swap_legs(thetad[:, 0])
    return guess


def perturbed(guess: dict, rng: np.random.Generator) -> dict:
    """A guess with its joint angles moved by up to 10 deg (one offset per joint and phase)
    and its joint rates by up to 1 rad/s at every node (a multi-start's other starts)."""
    out = {k: v.copy() if isinstance(v, np.ndarray) else v for k, v in guess.items()}
    for key in [k for k in out if k.startswith("X_")]:
        out[key][3:NX] += rng.uniform(-0.17, 0.17, (NX - 3, 1))
        out[key][NX + 3:] += rng.uniform(-1, 1, out[key][NX + 3:].shape)
    return out


def slide_guess(nlp: StrideNLP, stick: dict, mu: float) -> dict:
    """A sliding NLP's guess from a sticking solution's blocks: the slide phase held at the
    sticking start (state, moments and forces of its first node, the tangential force and the
    touchdown's tangential impulse on the cone's edge, -s mu times the normal), lasting
    DURATIONS["slide"]; every other block as solved (`fitted` onto this NLP's nodes)."""
    phase, c, slip = nlp.phases[0], nlp.columns[0], nlp.settings.slip
    first = nlp.phases[1].name
    guess = fitted(nlp, {k: v for k, v in stick.items() if not k.startswith("S_")})
    t, normal = phase.rows.index((phase.sliding, "t")), phase.rows.index((phase.sliding, "n"))
    force = np.repeat(guess[f"F_{first}"][:, :1], c, axis=1)
    force[t] = -slip * mu * force[normal]
    guess.update({f"X_{phase.name}": np.repeat(guess[f"X_{first}"][:, :1], c, axis=1),
                  f"A_{phase.name}": np.zeros((NX, c)),
                  **{f"{key}_{phase.name}": np.repeat(guess[f"{key}_{first}"][:, :1], c, axis=1)
                     for key in "UZ" if f"{key}_{first}" in guess},
                  f"F_{phase.name}": force,
                  f"T_{phase.name}": float(np.clip(DURATIONS["slide"], *nlp.settings.duration["slide"]))})
    guess["P_touchdown"][t] = -slip * mu * guess["P_touchdown"][normal]
    return guess


def fitted(nlp: StrideNLP, guess: dict, source: StrideNLP | None = None) -> dict:
    """A guess (blocks by name, e.g. another NLP's solution: a sliding one warm-starting a
    sticking one, or the reverse, or another mesh's) with each phase's node histories
    interpolated linearly in the phase's time onto this NLP's columns where they lie elsewhere;
    `source`: an NLP of the guess's transcription and grading (its columns' times; default
    this NLP's), its node counts the guess's own. Blocks it does not name are left out."""
    out: dict = {}
    for name in nlp.blocks.names:
        if name not in guess:
            continue
        value = np.array(guess[name], float)
        cols = nlp.blocks.shapes[name][1]
        if value.ndim == 2 and cols > 1:
            old, new = _fractions(source or nlp, value.shape[1]), _fractions(nlp, cols)
            if old.shape != new.shape or (old != new).any():
                value = np.array([np.interp(new, old, row) for row in value]).reshape(value.shape[0], cols)
        out[name] = value
    return out


def _fractions(nlp: StrideNLP, columns: int) -> np.ndarray:
    """The times of a phase's `columns` columns over its duration on `nlp`'s mesh (its
    transcription and grading: transcription.times); a count its transcription cannot have (an
    even one on Hermite-Simpson) the trapezoid's."""
    scheme = nlp.transcription
    if scheme.columns(scheme.intervals(columns)) != columns:
        scheme = Trapezoid
    return times(scheme, 1.0, scheme.intervals(columns), nlp.settings.grading)


def from_torques(nlp: StrideNLP, torques: StrideNLP, solved) -> dict:
    """A guess for `nlp` (another actuation, e.g. the muscles) from a solution of `torques` (a
    torque rung's NLP of the same phases; its nodes `fitted` to nlp's): its motion, forces and durations, and the
    actuation's states and controls that make the same net joint moments (active plus springs;
    the actuation's `initial`)."""
    blocks = solved.blocks
    out = {k: v for k, v in blocks.items() if not k.startswith(("S_", "U_"))}
    for i, phase in enumerate(nlp.phases):
        X = blocks[f"X_{phase.name}"]
        act = nlp.ocp.models[i].actuation
        z, out[f"U_{phase.name}"] = act.initial(X[:NX], X[NX:], np.add(*torques.moments(blocks, i)))
        if act.states:
            out[f"Z_{phase.name}"] = z
    return fitted(nlp, out, torques)
