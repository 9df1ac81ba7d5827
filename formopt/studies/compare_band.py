"""compare's stride band: the variants of the nominal stride, and the solves on worker processes.

The band says how much of a what-if's change (studies.compare_stride) the model cannot tell
from what it does not know about the runner. Its parts, each a few variants of the nominal
scene (`band_variants`), each variant solved at the nominal's cadences warm from the nominal's
strides there (`start_band`, `band_results`):

- friction: the coefficient at FRICTION_BAND's ends;
- objective: OBJECTIVE_BAND's objectives beside the nominal's effort;
- body: the legs' share of the body's mass scaled by LEG_MASS_BAND (the trunk carrying the rest).

A what-if's band [low_W, high_W] spans the change over the nominal and every variant that
converged; a part's own width is the span over the nominal and that part's variants, and its
share that width over the parts' summed widths (compare_stride.WhatIf.parts and .shares; the
JSON's `band_parts_W` and `band_shares`).

The solves that do not wait for each other run on WORKERS processes (studies.pool.Background,
one pool for the section, compare_stride.answer): the other strikes' free optima beside the
nominal curve (`strike_tasks`), the nominal's forward checks and the band's free optima beside
its family (`check_tasks`, `start_band`), the band's strides after it, the longest variants'
first (LONGEST_FIRST). `stage_count` and `stage_shares` are the progress stages the section tells.
"""

from __future__ import annotations

import os
from dataclasses import replace
from typing import NamedTuple

from ..io.stride_scene import StrideScene
from ..mechanics.body import scaled_body
from ..optim.stride import Stride, forward_checked, summarise
from ..optim.stride.problem import STRIKES
from .pool import Background
from .stride_form import STRIDE_MODEL, with_body
from .stride_map import free, warm

# the band: friction over the range of shod running on track and treadmill belts (0.6-1.0,
# the coefficient's usual span in the stride and compare scenes); the objective: what a runner
# minimises is not known: effort and metabolic (the `work` objective, W+ alone, converged at no
# imposed cadence within 500 iterations on RBDS001 at 3.58 m/s, 24 nodes, and cost 3 solves per
# failure: metabolic, which weighs W+ and W-, stands for the work objectives); the body: the
# stride's dynamics are nearly homogeneous in mass (segment masses and inertias, the joint
# moments' bound and springs per kg, the friction cone; only Riener & Edrich's passive joint
# moments are an adult's, not scaled), so a runner's total mass scales the power and barely
# moves the stride (RBDS001's body, 3.5 m/s, heel, 18 nodes: +5 % of mass gave +5.7 % of power
# and -0.16 % of cadence; test_compare_stride), and a runner's mass is known to 1-2 %; what
# moves the stride is how the mass is shared: de Leva's segment masses are a population's
# regression, an individual's differ from it by about 5 %: the legs' segments +-5 %, the trunk
# carrying the rest (mechanics.body.scaled_body's `legs`; there -2.4 / +2.3 % of power,
# +0.8 / -0.8 % of cadence). Until 2026-11-27 the band scaled the total mass, which measured
# the scale and the solves' local optima more than the body.
FRICTION_BAND = (0.6, 1.0)
OBJECTIVE_BAND = ("metabolic",)
LEG_MASS_BAND = (0.95, 1.05)
BAND_PARTS = ("friction", "objective", "body")  # the band's parts, in `Curve.part`
# the section's pool (compare_stride.answer): the other strikes' free optima, the nominal curve's
# first sweep and the band's solves, independent of each other, on this many processes
# (studies.pool.Background; the brief's budget for compare is 2 cores)
WORKERS = min(2, os.cpu_count() or 1)
# the band's parts, their variants started in this order: the longest first (RBDS001 T25, one
# process, CPU s: the metabolic objective 15.3, from the nominal's primal values alone, another
# objective's NLP; each legs' mass 3-4; each friction 1-1.5, the nominal's NLP; 2026-11-27)
LONGEST_FIRST = ("objective", "body", "friction")
# the section's wall time on 2 processes, shares (`stage_shares`) by stride model
# (stride_form.STRIDE_MODELS): the nominal curve, its family (the band's free optima beside it),
# the band until its first variant ends, the rest of the band (benchmarks/compare_speed.py
# --stride's timeline; quick 2026-11-27, load 2-3.2: RBDS001 T25 8.1, 1.7, 5.4 and 1.9 s of 17.1;
# T35 14.7, 2.9, 7.8, 2.3 of 27.7; RIC 12.2, 3.5, 9.3, 4.6 of 29.6; scenes 2026-11-28, --model
# scenes: T35 44.1, 17.3, 11.8, 12.2 of 86.1; T25 52.0, 23.9, 41.7, 40.9 of 159.2 and 63.3, 22.4,
# 19.4, 68.7 of 174.4)
STAGE_SHARES = {"quick": (0.47, 0.11, 0.30, 0.12), "scenes": (0.41, 0.16, 0.17, 0.26)}


class Variant(NamedTuple):
    """One variant of the nominal scene: its name, its part (BAND_PARTS) and its scene."""

    name: str
    part: str
    scene: StrideScene


def band_text() -> str:
    """What the what-if band spans, in words."""
    return (f"friction {FRICTION_BAND[0]:g}-{FRICTION_BAND[1]:g}, the objective (effort, "
            f"{', '.join(OBJECTIVE_BAND)}) and the legs' mass {LEG_MASS_BAND[0] * 100 - 100:+.0f}/"
            f"{LEG_MASS_BAND[1] * 100 - 100:+.0f} %")


def band_variants(nominal: StrideScene, body: dict) -> list[Variant]:
    """The band's variants of the nominal scene: friction, objective and the legs' mass (`body`:
    compare's body settings, mass_kg, height_m, sex)."""
    out = [Variant(f"friction {mu:g}", "friction", _with(nominal, friction=mu)) for mu in FRICTION_BAND]
    out += [Variant(o, "objective", _with(nominal, objective=o)) for o in OBJECTIVE_BAND]
    return out + [Variant(f"legs' mass {f * 100 - 100:+.0f} %", "body", with_body(nominal, scaled_body(
        body["mass_kg"], body["height_m"], body["sex"], legs=f))) for f in LEG_MASS_BAND]


def start_band(variants: list[Variant], points: list[tuple], pool: Background) -> list[list[list]]:
    """Each variant's strides at `points` (its (starts, cadence): the nominal's free optima with
    cadence None, or its stride at a cadence), each solved warm from one of its starts
    (`stride_at`), started on `pool` (independent of each other), the longest variants first
    (LONGEST_FIRST): the started tasks, variant by variant in that order (`band_results`)."""
    return [pool.start([(stride_at, (v.scene, starts, cadence), "") for starts, cadence in points])
            for v in _longest_first(variants)]


def band_results(variants: list[Variant], started: list[list[list[list]]], pool: Background,
                 say) -> dict[str, list[Stride]]:
    """Each variant's strides by name, from the tasks of each `start_band` call in `started`
    (its points' order), got in LONGEST_FIRST's order, `say("variant NAME done")` as each
    variant's last is got."""
    out = {}
    for k, v in enumerate(_longest_first(variants)):
        out[v.name] = pool.results([task for part in started for task in part[k]], say)
        say(f"variant {v.name} done")
    return out


def _longest_first(variants: list[Variant]) -> list[Variant]:
    """The variants in the order their solves start and their results are got (LONGEST_FIRST:
    by part, each part's in `variants`' order): `start_band`'s tasks and `band_results`' index."""
    return sorted(variants, key=lambda v: LONGEST_FIRST.index(v.part))


def stride_at(task: tuple) -> Stride:
    """The scene's stride at `cadence` (None: free), warm-started from the first of `starts`
    (strides) that is a converged solution of the scene's NLP, so with its multipliers
    (stride_map.warm), else from the first's primal values, from (scene, starts, cadence)."""
    scene, starts, cadence = task
    nlp = scene.nlp()
    start = next((s for s in starts if s.success and s.solved is not None and s.solved.layout == nlp.layout),
                 starts[0])
    return summarise(nlp, warm(nlp, start, scene.speed, scene.slope, scene.friction, cadence), False)


def strike_tasks(nominal: StrideScene, speed: float, strikes: list[str]) -> list[tuple]:
    """Background tasks: each strike's free optimum of the nominal scene (speed m/s),
    forward-checked (None where it does not converge), told "strike S done"."""
    return [(_strike, (_with(nominal, strike=s), speed), f"strike {s} done") for s in strikes]


def check_tasks(scene: StrideScene, strides: list[Stride]) -> list[tuple]:
    """Background tasks: each of the scene's `strides` forward-checked
    (optim.stride.forward_checked), not told."""
    return [(_checked, (scene, s), "") for s in strides]


def stage_count(band: bool = True) -> int:
    """The stages compare_stride.answer tells its progress of: the nominal, the family, the
    band's start and, with the band, each other strike and each variant as it ends."""
    return 3 + (len(FRICTION_BAND) + len(OBJECTIVE_BAND) + len(LEG_MASS_BAND) + len(STRIKES) - 1 if band else 0)


def stage_shares(band: bool = True, model: str = STRIDE_MODEL) -> list[float]:
    """Each of `stage_count`'s stages' expected share of the section's time, in the order
    compare_stride.answer tells them (io.progress.Stages' `shares`): the nominal curve, its
    family, each other strike (solved beside the nominal: done when told), the band until its
    first variant ends (the longest, LONGEST_FIRST) and the rest of the band (STAGE_SHARES of
    the stride `model`)."""
    nominal, family, first, rest = STAGE_SHARES[model]
    if not band:
        return [nominal, family, 0.0]
    strikes, variants = len(STRIKES) - 1, stage_count() - 3 - len(STRIKES) + 1
    return [nominal, family, *[0.0] * strikes, first, *[rest / (variants - 1)] * (variants - 1), 0.0]


def _strike(task: tuple) -> Stride | None:
    """One other strike's free optimum (`_free_or_none`), forward-checked, from (scene, speed)."""
    stride = _free_or_none(*task)
    return None if stride is None else forward_checked(task[0].nlp(), stride)


def _checked(task: tuple) -> Stride:
    """A stride of the scene forward-checked (optim.stride.forward_checked), from (scene, stride)."""
    scene, stride = task
    return forward_checked(scene.nlp(), stride)


def _with(scene: StrideScene, **changes) -> StrideScene:
    """The scene with its friction, or its settings' objective or strike, changed."""
    if "friction" in changes:
        return replace(scene, friction=changes["friction"])
    settings = replace(scene.settings, **changes)
    return replace(scene, settings=settings, strike=settings.strike)


def _free_or_none(scene: StrideScene, speed: float) -> Stride | None:
    """The scene's free optimum at `speed` (m/s), None where it does not converge."""
    stride = free(scene, speed, scene.slope, scene.friction)
    return stride if stride.success else None
