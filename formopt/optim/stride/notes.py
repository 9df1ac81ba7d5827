"""How sure a stride's optimum is of its mesh and its transcription, in words: figures measured
once on RBDS001 (docs/concepts/stride.md, "One answer"; docs/concepts/muscles.md, "The mesh: N
against 2N" and "On Hermite-Simpson"), said beside every stride whose own mesh is not checked
(`mesh_note`) and, where the other transcription was measured to find another stride for the
same cost, beside it too (`transcription_note`)."""

from __future__ import annotations

from .actuation import springs
from .problem import (
    APPROACH_SPEED,
    FORCE_RATE_WEIGHT,
    MOMENT_TIME,
    RUNNER_ANKLE,
    RUNNER_IMPACT_WEIGHT,
    RUNNER_NODES,
    RUNNER_TRANSCRIPTION,
    StrideSettings,
)

# How far a stride's optimum moved with its mesh, N to 2N intervals (docs/concepts/stride.md,
# "One answer"): every stride says it beside its numbers (`mesh_note`). Measured with Riener &
# Edrich's passive moments on RBDS001's body, heel, torque+springs, effort, free cadence, each
# mesh warm from the one before (python problems/stride_mesh.py --cadence 0 --speed 2.5 / 3.5 /
# 4.5 --meshes trapezoid:40 trapezoid:80 hermite-simpson:40 hermite-simpson:80, 2026-11-27):
# the trapezoid 156.0 -> 153.1, 169.5 -> 167.0 and 180.3 -> 178.3 steps/min, its cost 4.4, 16.2
# and 13.9 % lower; Hermite-Simpson (without its release's force row) 124.8 -> 124.8 (an invalid,
# grazing touchdown), 155.8 -> 155.4 and 163.3 -> 162.8, its cost 4.0, 0.01 and 0.17 % lower,
# and 20 -> 40 intervals at 3.5 m/s 158.1 -> 155.8 (cost -1.9 %). Hermite-Simpson converges but
# its torque sources end the stance pushing 1.3 body weights, and its global optimum at 3.5 m/s
# (problems/stride_search.py --transcription hermite-simpson) is 139.2 steps/min with the forefoot
# phase on its 0.25 s ceiling: a converged answer held by a bound, so the scenes stayed on the
# trapezoid until RUNNER_MESH's stride (2026-11-28).
MESH_SHIFT = {"trapezoid": "1-2 % in cadence but 4-16 % in cost from 40 to 80 nodes, and at 3.5 m/s "
                            "finer meshes find cheaper strides near 140-144 steps/min, which the rows at the "
                            "phase ends hold off only on coarse meshes",
              "hermite-simpson": "under 2 % in cadence and 1-6 % in cost from 20 to 40 intervals"}
MESH_FINE = {"hermite-simpson": (40, "under 0.3 % in cadence and 0.2 % in cost from 40 to 80 intervals on "
                                     "RBDS001's body at 3.5 and 4.5 m/s from the generic start, but 2.5 % in cost "
                                     "for the cheaper 139 steps/min stride held on the forefoot phase's duration "
                                     "bound, and its torque sources end the stance pushing 1.3 body weights: "
                                     "`--mesh-check` measures your stride")}

# The torque scenes' stride (problem.RUNNER_ANKLE: Hermite-Simpson, the ankle's spring, the impacts
# charged, moment dynamics; docs/concepts/stride.md, "The torque scenes on Hermite-Simpson"), 40 -> 80
# intervals from the generic start (python problems/stride_mesh.py --cadence 0 --tendons knee=0
# --impact-weight 4 --approach-speed 0.05 --moment-time 0.012 --strike S --speed V; the solver's
# options of ipopt_options.TORQUE_HERMITE_IPOPT, 2026-11-28): RBDS001's body, heel 171.9 / 178.5 /
# 184.0 steps/min at 2.5 / 3.5 / 4.5 m/s, cadence -0.17 / -0.02 / +0.09 %, cost -0.29 / -0.08 /
# -0.14 %; forefoot 181.5 and 179.0 at 3.5 and 4.5 m/s, +0.04 / +0.08 % and -0.22 / -0.23 %;
# another lab's runner (79 kg, 1.77 m, 3.37 m/s) heel 177.1, +0.01 / -0.10 %, forefoot 178.8,
# +0.03 / -0.19 %. The 80-interval solves of the flat strike (2.5 and 4.5 m/s: 1000 iterations;
# 3.5 m/s: stopped after 720) and of the forefoot at 2.5 m/s (1000) did not converge, their cost
# 0.19-1.07 % below the 40-interval one's; the forefoot strides' flat phase sits on its 30 ms floor.
RUNNER_CADENCE_PCT, RUNNER_COST_PCT = 0.2, 0.3  # the largest moves, 40 -> 80 intervals (%, rounded up)
# the largest cost move of the strides whose 80-interval solve did not converge (the flat strike,
# the forefoot at 2.5 m/s): their 80-interval cost was up to 1.1 % below the 40-interval one
RUNNER_UNCONVERGED_PCT = 1.1
RUNNER_SHIFT = f"under {RUNNER_CADENCE_PCT} % in cadence and {RUNNER_COST_PCT} % in cost from 40 to 80 intervals"
RUNNER_MESH = (f"{RUNNER_SHIFT} on RBDS001's body (heel at "
               "2.5-4.5 m/s, forefoot at 3.5 and 4.5) and another lab's runner (heel and forefoot, 3.37 m/s); "
               "the 80-interval solves of the flat strike (2.5-4.5 m/s) and of the forefoot at 2.5 m/s did not "
               "converge, 0.2-1.1 % cheaper")
# The same under Coulomb (law "coulomb": the touchdown solved sliding where formopt's Coulomb map says
# it slides, local.touchdown_mode), the free optima of stride_rbds001.toml's settings with contact =
# "coulomb", 40 -> 80 intervals (formopt stride SCENE --strike S [--speed 2.54] --mesh-check, the
# search's 4 starts, 2026-11-28; compare's stride_model "scenes" solves this): RBDS001's body at 3.58
# m/s, heel 189.4 steps/min (sliding 2.3 cm) -0.04 % in cadence and -0.15 % in cost, forefoot 196.4
# (3.9 cm) +0.06 / -0.49 %; at 2.54 m/s the forefoot 185.6 (6.6 cm) +0.56 / -1.95 %.
RUNNER_COULOMB_COST_PCT, RUNNER_COULOMB_FOREFOOT_PCT = 0.5, 2.0  # cost, and the forefoot's below 3.5 m/s
RUNNER_COULOMB_MESH = ("under Coulomb, RBDS001's sliding free optima moved -0.04 / +0.06 % in cadence and "
                       "-0.15 / -0.49 % in cost (heel / forefoot, 3.58 m/s), the forefoot's at 2.54 m/s +0.56 % "
                       "and -1.95 %")


# The torque scenes' stride with the torque-velocity limit (StrideSettings.torque_velocity), 40 ->
# 80 intervals from the generic start (python problems/stride_mesh.py --cadence 0 --tendons knee=0
# --impact-weight 4 --approach-speed 0.05 --moment-time 0.012 --torque-velocity --strike heel
# --speed 3.5 --meshes hermite-simpson:20 hermite-simpson:40 hermite-simpson:80, 2026-11-28;
# docs/concepts/stride.md, "What holds the torque scenes' stride"): RBDS001's body, 178.7 steps/min,
# cadence -0.11 %, cost -0.24 %, the 80-interval solve stopped at 1000 iterations; still on the
# 15 rad/s box, and with the boxes lifted the strides move as without the limit.
VELOCITY_MESH = ("-0.11 % in cadence and -0.24 % in cost from 40 to 80 intervals on RBDS001's body (heel, "
                 "3.5 m/s; the 80-interval solve stopped at 1000 iterations), still held by the joints' rate box")


def mesh_cost_pct(settings: StrideSettings, speed: float) -> float | None:
    """How far (%) the mesh was measured to move the cost of a stride of these settings (its
    strike's) at `speed` (m/s) whose own mesh is not checked: for the torque scenes' stride on 40
    intervals or more RUNNER_COST_PCT, or RUNNER_UNCONVERGED_PCT for the flat strike and the
    forefoot below 3.5 m/s (RUNNER_MESH); under Coulomb RUNNER_COULOMB_COST_PCT, or
    RUNNER_COULOMB_FOREFOOT_PCT for the forefoot below 3.5 m/s (RUNNER_COULOMB_MESH); None where
    no figure holds as a bound."""
    if not _runner(settings):
        return None
    slow_forefoot = settings.strike == "forefoot" and speed < 3.5
    if settings.law == "coulomb" and settings.strike != "flat":  # a flat touchdown never slides
        return RUNNER_COULOMB_FOREFOOT_PCT if slow_forefoot else RUNNER_COULOMB_COST_PCT
    return RUNNER_UNCONVERGED_PCT if settings.strike == "flat" or slow_forefoot else RUNNER_COST_PCT


def _runner(settings: StrideSettings, velocity: bool = False) -> bool:
    """The torque scenes' stride (the effort objective with problem.RUNNER_ANKLE,
    RUNNER_IMPACT_WEIGHT, MOMENT_TIME and APPROACH_SPEED on Hermite-Simpson at 40 intervals or more,
    uniform), with the torque-velocity limit or without: what RUNNER_MESH (without) and
    VELOCITY_MESH (with, the heel strike) were measured with."""
    return (settings.muscles is None and settings.objective == "effort" and settings.transcription == RUNNER_TRANSCRIPTION
            and springs(settings.tendons) == RUNNER_ANKLE and settings.impact_weight == RUNNER_IMPACT_WEIGHT
            and settings.moment_time == MOMENT_TIME and settings.approach_speed == APPROACH_SPEED
            and settings.torque_velocity == velocity and settings.nodes >= RUNNER_NODES and not settings.grading)


# The muscles' trapezoid from 40 to 80 nodes (RBDS001, heel and forefoot, 2.5 / 3.5 / 4.5 m/s,
# problems/muscle_mesh.py; docs/concepts/muscles.md, "The mesh: N against 2N", 2026-11-27): the
# uniform mesh's cadence 0.7-3.8 % and cost 8.6-11.4 %; graded (StrideSettings.grading 1, the
# search's strides, heel 2.5-4.5 and forefoot 3.5-4.5 m/s) 0.4-1.9 % and 2.3-6.6 % (from 80 to 160
# nodes 0.1-0.7 % and 1.2-2.2 %).
MUSCLE_MESH_SHIFT = ("0.7-3.8 % in cadence and 9-11 % in cost from 40 to 80 nodes on RBDS001's body "
                     "(a mesh graded toward the phases' ends, grading 1: 0.4-1.9 % and 2-7 %)")
# The same cost on Hermite-Simpson (RBDS001, heel, the default path's stride on 20 intervals
# continued on 40 and 80; problems/muscle_mesh.py --transcription hermite-simpson --start path
# --nodes 20 40 80; docs/concepts/muscles.md, "On Hermite-Simpson", 2026-11-27): at 3.5 m/s
# 142.0 / 136.7 / 135.7 steps/min, cost -1.66 / -1.10 %, the forefoot phase on its 0.25 s ceiling on
# every mesh (the global search at 40 intervals answers 136.7; on its grid 180 steps/min, next to
# the trapezoid's cadence, costs 11 % more); at 4.5 m/s 141.0 / 137.4 / 135.9, cost -7.7 / -3.0 %,
# the flat phase on its 30 ms floor; at 2.5 m/s 199.1 / 198.0 / 197.8, cost -3.2 / -0.8 %, the heel
# and flat phases on their floors; the forefoot strike at 3.5 m/s 135.1 / 134.3 / 134.0, -1.2 /
# -1.3 %. The force rates replayed forward along the excitations (no
# mesh's quadrature) put such a stride's (131.2 steps/min) force-rate term 24-34 % below the
# trapezoid's strides' (176.2 and 177.7 at 80 and 40 nodes) per metre, its muscles' energy 18 %
# above: consistent with the trapezoid's phase-end layers holding its cadence up, and
# FORCE_RATE_WEIGHT was calibrated on the trapezoid. Measured with that weight and power 2 only.
MUSCLE_HERMITE = ("a more accurate transcription (Hermite-Simpson) puts this cost's best stride near 131-137 "
                  "steps/min at 3.4-4.5 m/s and 198 at 2.5 m/s, a cadence falling with speed, each with a "
                  "stance phase held at a duration limit (at 3.5 m/s the forefoot phase, heel-off to toe-off, at "
                  "250 ms; RBDS001's body, heel and forefoot strikes; another lab's runner at 3.37 m/s), "
                  "and at 3.5 and 4.5 m/s a crouched stance (the stance knee to 85-90 deg; a runner's 37-44)")
MUSCLE_HERMITE_SHIFT = ("0.1-1.7 % in cadence and 0.8-3.0 % in cost from 40 to 80 intervals on RBDS001's body "
                        "(heel 2.5-4.5 m/s, forefoot 3.5 m/s), at 198 steps/min at 2.5 m/s and 129-137 above, "
                        "each with a phase on its duration bound; the cost's weight was calibrated on the "
                        "24-node trapezoid")


def _calibrated(settings: StrideSettings) -> bool:
    """The muscles' cost as calibrated (power 2 at FORCE_RATE_WEIGHT): what MUSCLE_HERMITE and
    MUSCLE_HERMITE_SHIFT were measured with."""
    return settings.force_rate_power == 2 and settings.force_rate_weight in (None, FORCE_RATE_WEIGHT)


def transcription_note(settings: StrideSettings) -> str:
    """What the other transcription finds for this stride's cost, where it was measured to differ
    (MUSCLE_HERMITE: the muscles' calibrated cost on the trapezoid), else ""; said whether or not
    the stride's own mesh is checked."""
    if settings.muscles is None or settings.transcription != "trapezoid" or not _calibrated(settings):
        return ""
    return (f"{MUSCLE_HERMITE}: this cadence may come from the mesh more than from the cost "
            "(docs/concepts/muscles.md, 'On Hermite-Simpson')")


def mesh_note(settings: StrideSettings) -> str:
    """How sure a stride's optimum is of its mesh, in words (MESH_SHIFT, MESH_FINE: measured on
    the torque+springs rung on uniform meshes; MUSCLE_MESH_SHIFT on the muscles' trapezoid, uniform
    and graded; MUSCLE_HERMITE_SHIFT on Hermite-Simpson: what it finds, `transcription_note`;
    RUNNER_MESH and VELOCITY_MESH on the torque scenes' stride, without and with the torque-velocity limit)."""
    if settings.muscles is not None:
        if settings.transcription != "trapezoid":
            if _calibrated(settings) and settings.nodes >= 40:
                return (f"{settings.transcription} at {settings.nodes} intervals: the muscles' optimum moved "
                        f"{MUSCLE_HERMITE_SHIFT} (docs/concepts/muscles.md, 'On Hermite-Simpson')")
            return (f"{settings.transcription} at {settings.nodes} intervals: the muscles' optimum is measured on "
                    "it from 40 intervals with the calibrated cost only (docs/concepts/muscles.md, "
                    "'On Hermite-Simpson')")
        return (f"trapezoid at {settings.nodes} nodes is not mesh-converged: the muscles' optimum moved "
                f"{MUSCLE_MESH_SHIFT} (docs/concepts/muscles.md, 'The mesh: N against 2N')")
    if settings.grading:
        return (f"{settings.transcription} at {settings.nodes} intervals graded {settings.grading:g}: on the "
                "torque rungs a graded mesh was measured costlier, converging elsewhere (docs/concepts/"
                "stride.md, 'A mesh graded toward the phases' ends')")
    if settings.torque_velocity:
        measured = (f"the heel stride of the torque scenes' settings moved {VELOCITY_MESH}, other strikes not "
                    "measured" if _runner(settings, velocity=True) else "not measured on these settings")
        return (f"{settings.transcription} at {settings.nodes} intervals with the torque-velocity limit: "
                f"{measured} (docs/concepts/stride.md, 'What holds the torque scenes' stride')")
    if _runner(settings):
        coulomb = f"; {RUNNER_COULOMB_MESH}" if settings.law == "coulomb" else ""
        return (f"hermite-simpson at {settings.nodes} intervals: the torque scenes' effort optimum moved "
                f"{RUNNER_MESH}{coulomb} (docs/concepts/stride.md, 'The torque scenes on Hermite-Simpson')")
    least, shift = MESH_FINE.get(settings.transcription, (None, ""))
    if least is not None and settings.nodes >= least:
        return (f"{settings.transcription} at {settings.nodes} intervals: the effort optimum moved {shift} "
                "(docs/concepts/stride.md, 'One answer')")
    return (f"{settings.transcription} at {settings.nodes} intervals is not mesh-converged: on RBDS001's body "
            f"the effort optimum moved {MESH_SHIFT[settings.transcription]} (the torque scenes' stride, on "
            f"hermite-simpson with moment dynamics, moved {RUNNER_SHIFT}: docs/concepts/stride.md, "
            "'The torque scenes on Hermite-Simpson')")
