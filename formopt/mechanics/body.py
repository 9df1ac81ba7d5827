"""Segment data of the runner: the paper's body and anthropometric scaling.

Every segment has its own frame, with the origin at its proximal joint, rotated by the
segment's absolute angle (counter-clockwise positive, x forward, z up):

- thigh, shank: the distal joint is at (0, -length), the centre of mass at (0, -com);
- foot: origin at the ankle, x along the sole toward the toes, z up; heel and forefoot
  are points of this frame;
- trunk (head, arms and trunk): origin at the hip, the trunk's axis along +z up to the
  shoulder at (0, length), the centre of mass at (0, com);
- swing_leg: the other leg, a point mass at the hip.

The paper's leg lumps trunk and swing leg into one point mass at the hip; the rigid-trunk
model ("leg-trunk") needs the trunk's length, centre of mass and inertia.

Units: kg, m, kg m^2.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .errors import InputError

SEGMENTS = ("trunk", "swing_leg", "thigh", "shank", "foot")


@dataclass(frozen=True)
class Segment:
    """Mass properties and landmarks of one rigid segment, in the segment's frame."""

    name: str
    mass: float  # kg
    com: tuple[float, float]  # m, centre of mass in the segment frame
    inertia_com: float  # kg m^2, about the centre of mass, sagittal axis
    landmarks: dict[str, tuple[float, float]] = field(default_factory=dict)  # m

    @property
    def length(self) -> float:
        """Distance from the proximal joint to the distal joint (0 for foot and trunk)."""
        distal = {"thigh": "knee", "shank": "ankle"}.get(self.name)
        return float(np.hypot(*self.landmarks[distal])) if distal else 0.0

    @property
    def inertia_proximal(self) -> float:
        """Moment of inertia about the segment frame's origin (the proximal joint), kg m^2."""
        return self.inertia_com + self.mass * float(np.dot(self.com, self.com))


@dataclass(frozen=True)
class Body:
    """The runner's segments (only those a model uses need be present) and where they came from."""

    segments: dict[str, Segment]
    source: str

    def __getitem__(self, name: str) -> Segment:
        if name == "effective_mass" and name not in self.segments:
            return effective_mass(self)
        return self.segments[name]

    @property
    def mass(self) -> float:
        return sum(s.mass for s in self.segments.values())


def bar(name: str, mass: float, length: float, com: float, inertia_com: float) -> Segment:
    """A thigh or shank: proximal joint at the origin, distal joint `length` below it."""
    proximal, distal = {"thigh": ("hip", "knee"), "shank": ("knee", "ankle")}[name]
    return Segment(name, mass, (0.0, -com), inertia_com,
                   {proximal: (0.0, 0.0), distal: (0.0, -length)})


def foot(mass: float, com, inertia_com: float, heel, forefoot) -> Segment:
    """The foot, in its frame (origin at the ankle, x along the sole toward the toes)."""
    return Segment("foot", mass, (float(com[0]), float(com[1])), inertia_com,
                   {"ankle": (0.0, 0.0), "heel": (float(heel[0]), float(heel[1])),
                    "forefoot": (float(forefoot[0]), float(forefoot[1]))})


def trunk(mass: float, com: float = 0.0, inertia_com: float = 0.0, length: float = 0.0) -> Segment:
    """Head, arms and trunk: centre of mass `com` above the hip, shoulder `length` above it.

    With no length it is only a mass (the paper's point mass at the hip).
    """
    landmarks = {"hip": (0.0, 0.0)}
    if length > 0:
        landmarks["shoulder"] = (0.0, length)
    return Segment("trunk", mass, (0.0, com), inertia_com, landmarks)


def effective_mass(body: Body) -> Segment:
    """The lower limb (shank and foot) as one mass at the strike point: the effective mass of
    the impact in Lieberman et al. (2010)'s one-degree-of-freedom picture."""
    return Segment("effective_mass", body["shank"].mass + body["foot"].mass, (0.0, 0.0), 0.0,
                   {"heel": (0.0, 0.0), "forefoot": (0.0, 0.0)})


def swing_leg(mass: float) -> Segment:
    """The swing leg as a point mass at the hip."""
    return Segment("swing_leg", mass, (0.0, 0.0), 0.0, {"hip": (0.0, 0.0)})


# Head, arms and trunk (HAT) from Winter D.A. (2009) Biomechanics and Motor Control of Human
# Movement, 4th ed., Table 4.1: greater trochanter to glenohumeral joint 0.288 of stature
# (Fig. 4.1: 0.818 - 0.530), centre of mass 0.626 of that length from the hip, radius of
# gyration about the centre of mass 0.496 of the length.
HAT_LENGTH_PER_STATURE = 0.288
HAT_COM = 0.626
HAT_GYRATION = 0.496


def hat(mass: float, height: float) -> Segment:
    """The rigid trunk (head, arms and trunk) of a given mass (kg) for a stature (m)."""
    length = HAT_LENGTH_PER_STATURE * height
    return trunk(mass, HAT_COM * length, mass * (HAT_GYRATION * length) ** 2, length)


def paper_body() -> Body:
    """The paper's body (Table 1): 73 kg, 1.731 m.

    Thigh: 10.3 kg, 0.402 m, centre of mass 0.164 m from the hip, 0.557 kg m^2 about the
    hip (Table 1's inertias are about the proximal joint and equal m L^2 / 3).
    Shank: Table 1's row is not reproduced in the brief we work from; we take the mass that
    completes 73 kg (3.2 kg, de Leva's 4.33 % of 73 kg is 3.16 kg), de Leva's length ratio
    (434.0 / 1741 of stature: 0.4315 m), his centre-of-mass ratio (44.59 %: 0.1924 m) and the
    paper's inertia convention m L^2 / 3 about the knee.
    Foot: Table 1's foot "length" 0.074 m is not heel-to-toe. We use the geometry of the
    formopt reference scene (issue 2): 1.0 kg (de Leva 1.37 % of 73 kg), ankle 0.07 m above the
    sole, heel 0.055 m behind and forefoot (metatarsal heads) 0.16 m ahead of the ankle,
    centre of mass (0.06, -0.045) m (de Leva: 44.15 % of the 0.257 m heel-to-toe length from
    the heel), inertia 0.0042 kg m^2 about the centre of mass (de Leva's radius of gyration
    25.7 % of foot length gives 0.0044).
    Trunk: 58.5 kg at the hip in the paper (head, arms, trunk and the swing leg). Split here
    into the swing leg (14.5 kg, the stance leg's segments) and head-arms-trunk (44.0 kg,
    Winter's HAT geometry at 1.731 m), so that the rigid-trunk model has a trunk; the paper's
    leg lumps both at the hip again (58.5 kg).
    """
    shank_length = 0.4340 / 1.741 * 1.731
    shank_mass = 73.0 - 58.5 - 10.3 - 1.0
    shank_com = 0.4459 * shank_length
    shank_inertia_proximal = shank_mass * shank_length**2 / 3.0
    leg_mass = 10.3 + shank_mass + 1.0
    return Body({
        "trunk": hat(58.5 - leg_mass, 1.731),
        "swing_leg": swing_leg(leg_mass),
        "thigh": bar("thigh", 10.3, 0.402, 0.164, 0.557 - 10.3 * 0.164**2),
        "shank": bar("shank", shank_mass, shank_length, shank_com,
                     shank_inertia_proximal - shank_mass * shank_com**2),
        "foot": foot(1.0, (0.06, -0.045), 0.0042, (-0.055, -0.07), (0.16, -0.07)),
    }, source="paper Table 1 (73 kg, 1.731 m)")


# de Leva P. (1996) Adjustments to Zatsiorsky-Seluyanov's segment inertia parameters.
# J Biomech 29(9):1223-1230, Table 4. Per sex: reference stature (m), and per segment:
# length (m at the reference stature), mass fraction, centre of mass from the proximal end
# (fraction of length), sagittal radius of gyration (fraction of length). Foot: heel to toe tip.
DE_LEVA: dict[str, dict[str, Any]] = {  # sex -> stature (m), segment -> the four fractions
    "male": {"stature": 1.741,
             "thigh": (0.4222, 0.1416, 0.4095, 0.329),
             "shank": (0.4340, 0.0433, 0.4459, 0.255),
             "foot": (0.2581, 0.0137, 0.4415, 0.257)},
    "female": {"stature": 1.735,
               "thigh": (0.3685, 0.1478, 0.3612, 0.369),
               "shank": (0.4323, 0.0481, 0.4416, 0.271),
               "foot": (0.2283, 0.0129, 0.4014, 0.299)},
}
# Foot landmarks not in de Leva's table, as fractions: the ankle joint 0.039 of stature above
# the sole (Drillis & Contini, in Winter 2009, Biomechanics and Motor Control of Human
# Movement, Fig. 4.1); heel 0.214 and metatarsal heads 0.623 of the heel-to-toe length behind
# and ahead of the ankle, and the centre of mass 0.643 of the ankle height below the ankle
# (the paper body's foot: 0.055 and 0.16 of 0.257 m; 0.045 of 0.07 m).
ANKLE_HEIGHT_PER_STATURE = 0.039
FOOT_COM_BELOW_ANKLE = 0.643
HEEL_BEHIND_ANKLE = 0.214
FOREFOOT_AHEAD_OF_ANKLE = 0.623


def stature(body: Body) -> float:
    """The stature (m) a body's leg stands for: (thigh + shank length) over de Leva's male
    share of stature (0.4917; the paper body: 1.69 m against its 1.731 m)."""
    table = DE_LEVA["male"]
    return (body["thigh"].length + body["shank"].length) / ((table["thigh"][0] + table["shank"][0]) / table["stature"])


def scaled_body(mass: float, height: float, sex: str = "male", legs: float = 1.0) -> Body:
    """A body scaled from total mass (kg) and stature (m) with de Leva (1996), Table 4.

    The swing leg mirrors the stance leg; head, arms and trunk carry the rest (Winter's HAT
    geometry). `legs`: the legs' segment masses and inertias times this (an individual's
    against de Leva's regression), the trunk carrying the rest of the same total mass.
    """
    if sex not in DE_LEVA:
        raise InputError(f"sex must be one of {sorted(DE_LEVA)}, not {sex!r}")
    if not 0.5 <= legs <= 1.5:
        raise InputError(f"legs = {legs:g}: the legs' mass factor is between 0.5 and 1.5")
    table = DE_LEVA[sex]
    scale = height / table["stature"]

    def props(name):
        length, mass_fraction, com_fraction, gyration = table[name]
        length *= scale
        m = mass_fraction * mass * legs
        return length, m, com_fraction * length, m * (gyration * length) ** 2

    thigh_l, thigh_m, thigh_c, thigh_i = props("thigh")
    shank_l, shank_m, shank_c, shank_i = props("shank")
    foot_l, foot_m, foot_c, foot_i = props("foot")
    ankle_height = ANKLE_HEIGHT_PER_STATURE * height
    heel_x = -HEEL_BEHIND_ANKLE * foot_l
    leg_mass = thigh_m + shank_m + foot_m
    return Body({
        "trunk": hat(mass - 2 * leg_mass, height),
        "swing_leg": swing_leg(leg_mass),
        "thigh": bar("thigh", thigh_m, thigh_l, thigh_c, thigh_i),
        "shank": bar("shank", shank_m, shank_l, shank_c, shank_i),
        "foot": foot(foot_m, (heel_x + foot_c, -FOOT_COM_BELOW_ANKLE * ankle_height), foot_i,
                     (heel_x, -ankle_height), (FOREFOOT_AHEAD_OF_ANKLE * foot_l, -ankle_height)),
    }, source=f"de Leva 1996 Table 4 ({sex}), scaled to {mass:g} kg, {height:g} m"
              + ("" if legs == 1.0 else f", legs' mass x {legs:g}"))
