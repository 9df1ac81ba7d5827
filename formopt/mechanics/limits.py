"""Physical limits: what a runner, a ground or a joint can be, each once, with its source.

Every entry point (scene keys, compare settings, the numeric API's touchdown state) checks its
input against these ranges; beyond them a number is a typing error or an overflow, not a
runner. A `Range` is closed unless `low_open`; its unit is the one it is written in (SI inside;
the `*_DEG` ranges are the degrees that scene files and options use at the edge).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .errors import InputError


@dataclass(frozen=True)
class Range:
    """An admissible interval `low <= value <= high` (`low < value` when `low_open`)."""

    low: float
    high: float = math.inf
    unit: str = ""
    low_open: bool = False

    def __contains__(self, value: float) -> bool:
        return (self.low < value if self.low_open else self.low <= value) and value <= self.high

    def text(self) -> str:
        """The range in words, as errors print it: "> 0", ">= 1", "> 0 and <= 10",
        "between -60 and 60 deg"."""
        unit = f" {self.unit}" if self.unit else ""
        if self.high == math.inf:
            return f"{'>' if self.low_open else '>='} {self.low:g}{unit}"
        if self.low_open:
            return f"> {self.low:g} and <= {self.high:g}{unit}"
        return f"between {self.low:g} and {self.high:g}{unit}"

    def scaled(self, factor: float, unit: str) -> Range:
        """The same range in another unit (value * factor), e.g. rad/s -> deg/s."""
        return Range(self.low * factor, self.high * factor, unit, self.low_open)


# -- the touchdown state (model.STATE) ----------------------------------------------------
ANGLE_LIMIT = math.pi  # rad: joint and trunk angles within half a turn either way
# The hip at most 30 m/s: 2.4 times the fastest human sprint (about 12.4 m/s, the peak speed
# of the 100 m world record, Berlin 2009).
SPEED_LIMIT = 30.0  # m/s
# Segment rates at most 5000 deg/s: sprinting limbs reach about 2000 deg/s.
RATE_LIMIT = math.radians(5000.0)  # rad/s
RATE_DPS = Range(-RATE_LIMIT, RATE_LIMIT).scaled(math.degrees(1.0), "deg/s")  # at the edge
ANGLE_DEG = Range(-ANGLE_LIMIT, ANGLE_LIMIT).scaled(math.degrees(1.0), "deg")  # at the edge

# -- the joints ------------------------------------------------------------------------
# Active ranges of motion (deg): American Academy of Orthopaedic Surgeons (1965), Joint Motion:
# Method of Measuring and Recording, as tabulated in Norkin C.C. & White D.J. (2016) Measurement
# of Joint Motion, 5th ed.: hip extension 30 / flexion 120, knee flexion 135 (0 = straight),
# ankle plantarflexion 50 / dorsiflexion 20; trunk: thoracolumbar extension 25 / flexion 80.
RANGE_OF_MOTION_DEG = {"trunk": (-25.0, 80.0), "hip": (-30.0, 120.0), "knee": (0.0, 135.0),
                       "ankle": (-50.0, 20.0)}
# What a scene may set for a spring-damper joint, per kg of body mass: stiffness 1 N m/(kg deg),
# three times the knee of sprinters (17-24 N m/deg, Kuitunen, Komi & Kyrolainen 2002, Med Sci
# Sports Exerc 34:166); damping 0.02 N m s/(kg deg), the critical damping of the paper's shank
# and foot about the knee at that stiffness (beyond it the joint is locked over a landing: use
# model "locked"); preload 5 N m/kg, above the stance joint moments of running (a few N m/kg
# at the knee and ankle, e.g. Schache et al. 2011, Med Sci Sports Exerc 43:1260).
JOINT_LIMITS = {"stiffness": 1.0, "damping": 0.02, "preload": 5.0}
# A prescribed joint moment at most 5000 N m: ten times 5 N m/kg (JOINT_LIMITS' preload) for a
# 100 kg runner.
JOINT_MOMENT_NM = Range(-5000.0, 5000.0, "N m")

# -- the ground ------------------------------------------------------------------------
# Friction: Coulomb's coefficient between shoe and ground, > 0 (0 is no ground to push on) and
# at most 100. Shoe soles on dry ground stay below about 2 (the shipped scenes use 0.8); the
# range is left open to 100 for limit cases (Coulomb with ample friction against no-slip,
# sliding past W_nn / |W_tn|, about 6 for a heel strike: design.md section 1). Beyond 100, a
# typing error.
FRICTION = Range(0.0, 100.0, "", low_open=True)
# Slope: +-60 deg, beyond what can be run (the steepest vertical-kilometre courses average
# about 30 deg, and the steepest paved streets about 20 deg).
SLOPE_DEG = Range(-60.0, 60.0, "deg")

# -- the runner ------------------------------------------------------------------------
# Body mass and stature: wider than adult runners (de Leva 1996's segment parameters are
# adults'); the recorded extremes of adult stature are 0.55 m and 2.72 m.
BODY_MASS_KG = Range(1.0, 500.0, "kg")
BODY_HEIGHT_M = Range(0.5, 2.5, "m")
# Cadence 60-300 steps/min: slow jogging is about 140 (RBDS001: 156.5 at 2.5 m/s), elite
# sprinters reach about 5 steps/s.
CADENCE_SPM = Range(60.0, 300.0, "steps/min")

# -- the segments (a scene's [body] tables) ----------------------------------------------
# de Leva (1996)'s ratios (body.DE_LEVA) at the statures of BODY_HEIGHT_M and masses of
# BODY_MASS_KG give thigh, shank and trunk lengths of 0.11-0.72 m, segment masses of
# 0.013-250 kg and inertias about the centre of mass of 5e-6-32 kg m^2; the ranges below leave
# a factor of about two beyond those. Below them the impact map's G is ill conditioned and a
# solve does not end (a thigh of 0.1 mm ran > 300 s without output, issue 25).
SEGMENT_LENGTH_M = Range(0.05, 1.5, "m")
SEGMENT_MASS_KG = Range(0.005, 500.0, "kg")
SEGMENT_INERTIA_KGM2 = Range(1e-6, 100.0, "kg m^2")

# -- the solver (an [optimize] table, solve()'s overrides) ----------------------------------
# The multi-start: at least one start; more than 1000 is hours of IPOPT, not a study.
STARTS = Range(1, 1000)
SEED = Range(0, 2**32 - 1)  # numpy's default_rng seeds
# IPOPT's tol: below 1e-14 is beneath the round-off of an objective of order 1 J (double
# precision, 2.2e-16 relative, times the NLP's scale); above 1e-2 an optimum is not resolved.
TOLERANCE = Range(1e-14, 1e-2)
MAX_ITERATIONS = Range(1, 100000)  # IPOPT's max_iter: a solve stays finite
# An objective term's weight: the terms are of order 1 in SI (T_c in J, a velocity change in
# m/s, the support in J), so a weight beyond 1e6 either way makes one term all of the objective
# (weighting the others by 0 says that plainly) and leaves IPOPT's scaling meaningless; 1e308
# overflowed the objective to inf and its report to a traceback (issue 37).
OBJECTIVE_WEIGHT = Range(-1e6, 1e6)

# -- the landing (simulate_state, a scene's [landing] table) -----------------------------
# A landing lasts 1 ms to 2 s (a stance at the slowest jog is about 0.4 s); its step 0.1 us
# to 5 ms and at most the duration (the ladder's midpoint integrator diverges at 2 ms;
# below 0.1 us, 2 s is 2e7 steps of memory).
LANDING_DURATION_S = Range(1e-3, 2.0, "s")
LANDING_DT_S = Range(1e-7, 5e-3, "s")


def check(name: str, value, allowed: Range, whole: bool = False) -> float:
    """`value` as a float (an int when `whole`) when it is a finite number within `allowed`;
    else InputError "name: must be <range>, not <value>" (one line)."""
    if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise InputError(f"{name}: must be a {'whole ' if whole else ''}number, not {value!r}")
    if whole and not float(value).is_integer():
        raise InputError(f"{name}: must be a whole number {allowed.text()}, not {value!r}")
    if not (math.isfinite(value) and float(value) in allowed):
        raise InputError(f"{name}: must be a finite number {allowed.text()}, not {value!r}")
    return int(value) if whole else float(value)
