"""The stride's joint angles against RBDS001's mean cycle, taken apart (issue 33 item 5).

    python problems/stride_angles.py [--speed 3.5] [--rungs torque+springs muscles]
                                     [--strikes heel] [--figure out/angles.png] [--markers]

Each rung is the shipped scene stride_rbds001.toml (torque+springs, effort, Hermite-Simpson at 40
intervals since 2026-11-28), the muscles with its torque rung's keys dropped (tendons, objective,
transcription, impact weight, approach floor, moment dynamics: the muscles' trapezoid at 40 nodes)
and actuation = "muscles" (metabolic).
Per joint the RMS of d = predicted - measured (studies.stride.compare_cycle) taken apart as a
biomechanist reads it: the mean offset (a definition or a posture), the best circular time shift
of the offset-removed curve (within +-SHIFT_MAX % of the cycle; positive: the prediction late)
and the RMS left after both (the shape); the range of motion and the percent of the cycle of
the largest and least angle, predicted / measured; the predicted trunk's mean lean (deg, the
hip's reference in formopt, the pelvis in the data set). At 2.5 and 3.5 m/s (the trials with
markers) a `thigh` row too: formopt's hip less the trunk's lean (the thigh from the downward
vertical) against the thigh formopt measures on the runner's markers, a hip free of the
reference segment's definition.

`--markers` checks the data set's conventions end to end first: formopt's own measurement of
RBDS001's trial at the speed (the thigh and shank from the downward vertical, the foot's
heel-to-forefoot line against standing, the pelvis's tilt against standing, over the right cycles
between force-plate touchdowns) against the processed mean cycle's hip, knee and ankle:
the offset (Visual3D - formopt), its sd, and the sd left after the best shift.
`--figure` draws the predicted angles of every stride solved beside the measured.
"""

from __future__ import annotations

import argparse
import sys
import time
import tomllib
from pathlib import Path

import numpy as np

from formopt import api
from formopt.io.mocap import read
from formopt.io.stride_scene import parse
from formopt.measure import mean_cycle, measure
from formopt.studies.stride import CYCLE_JOINTS, cycle_angles, measured_cycle

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "data" / "rbds"
SCENE = ROOT / "formopt" / "scenes" / "stride_rbds001.toml"
SHIFT_MAX = 25  # percent of the cycle
TRIALS = {3.5: ("RBDS001runT35.c3d",), 2.5: ("RBDS001runT25markers.txt", "RBDS001runT25forces.txt")}


def solve(rung: str, strike: str, speed: float):
    """The best stride of the shipped RBDS001 scene on `rung` ("torque+springs" or "muscles")."""
    data = tomllib.loads(SCENE.read_text())
    if rung == "muscles":
        for key in ("tendons", "objective", "transcription", "impact_weight", "approach_speed_mps", "moment_time_s"):
            data["stride"].pop(key, None)
        data["stride"]["actuation"] = "muscles"
    return api.stride(parse(data, str(SCENE)), speed, strike).best


def decompose(predicted, measured) -> dict:
    """One joint's curves over 0-99 % of the cycle (deg): rms, offset, shape (rms of d - mean d),
    shift (%, the circular shift of the prediction that least leaves, positive: it is late) and
    shifted (the rms left after the offset and the shift)."""
    d = predicted - measured
    left = {k: np.std(np.roll(predicted, -k) - measured) for k in range(-SHIFT_MAX, SHIFT_MAX + 1)}
    shift = min(left, key=left.get)
    return {"rms": np.sqrt(np.mean(d ** 2)), "offset": np.mean(d), "shape": np.std(d), "shift": shift,
            "shifted": left[shift], "rom": (np.ptp(predicted), np.ptp(measured)),
            "max_at": (np.argmax(predicted), np.argmax(measured)), "min_at": (np.argmin(predicted), np.argmin(measured))}


def table(name: str, stride, measured: dict, segments: dict | None) -> None:
    """The decomposition per joint, and the thigh's (formopt's hip less the trunk's lean, against
    the measured thigh from the downward vertical) when `segments` are measured."""
    percent = measured["percent"][:100]  # 0-99: the cycle once, for the circular shift
    curves = cycle_angles(stride, percent)
    against = {j: measured["angles"][j][:100] for j in CYCLE_JOINTS}
    if segments is not None:
        against["thigh"] = segments["thigh"][:100]
    print(f"\n{name}: {stride.cadence_spm:.1f} steps/min, duty {stride.duty_factor:.3f} (measured"
          f" {np.mean(measured['vertical'][:-1] > 0.5):.2f} by the force), trunk lean {np.degrees(stride.theta[:, 2].mean()):+.1f} deg, valid {stride.valid}")
    print(f"{'joint':6s} {'RMS':>5s} {'offset':>6s} {'shape':>5s} {'shift%':>6s} {'left':>5s}"
          f" {'ROM pred/meas':>13s} {'max at %':>9s} {'min at %':>9s}")
    for j in against:
        c = decompose(curves[j], against[j])
        print(f"{j:6s} {c['rms']:5.1f} {c['offset']:+6.1f} {c['shape']:5.1f} {c['shift']:+6d} {c['shifted']:5.1f}"
              f" {c['rom'][0]:6.1f}/{c['rom'][1]:<6.1f} {c['max_at'][0]:4d}/{c['max_at'][1]:<4d}"
              f" {c['min_at'][0]:4d}/{c['min_at'][1]:<4d}")


def measured_segments(speed: float) -> dict:
    """formopt's measurement of RBDS001's trial at `speed` (2.5 or 3.5 m/s): the mean right cycle
    between force-plate touchdowns (101 rows, deg) of the thigh, shank, foot and pelvis (`trunk`)."""
    m = measure(read(*(DATA / f for f in TRIALS[speed])), read(DATA / "RBDS001static.c3d"), 1.81)
    angles, cycles = mean_cycle(m)
    return {**{k: np.degrees(v) for k, v in angles.items()}, "cycles": cycles}


def markers(segments: dict, measured: dict) -> None:
    """The conventions' check (module docstring)."""
    ours = {"hip (thigh)": segments["thigh"], "hip (thigh + pelvis tilt)": segments["thigh"] + segments["trunk"],
            "knee": segments["thigh"] - segments["shank"], "ankle": segments["foot"] - segments["shank"]}
    print(f"Visual3D's processed mean cycle against formopt's measurement of the markers ({segments['cycles']}"
          " right cycles), deg:")
    print(f"{'':28s} {'offset':>6s} {'sd':>5s} {'shift%':>6s} {'sd left':>7s}")
    for name, curve in ours.items():
        c = decompose(measured["angles"][name.split()[0]][:100], curve[:100])
        print(f"{name:28s} {c['offset']:+6.1f} {c['shape']:5.1f} {c['shift']:+6d} {c['shifted']:7.1f}")
    print(f"the pelvis's tilt against standing while running: {segments['trunk'].mean():+.1f} deg (mean)")


def figure(strides: dict, measured: dict, segments: dict | None, path: str) -> None:
    """hip, knee and ankle (and the thigh, with `segments`) of each stride beside the measured."""
    from matplotlib.figure import Figure
    panels = [*CYCLE_JOINTS, *(["thigh"] if segments is not None else [])]
    fig = Figure(figsize=(4 * len(panels), 4), layout="constrained")
    percent = measured["percent"]
    for ax, j in zip(fig.subplots(1, len(panels)), panels):
        ax.plot(percent, measured["angles"][j] if j != "thigh" else segments["thigh"], "k", lw=2.5,
                label="RBDS001 (Visual3D; the thigh: formopt's markers)")
        for name, stride in strides.items():
            line, = ax.plot(percent, cycle_angles(stride, percent)[j], label=name)
            ax.axvline(100 * stride.duty_factor, color=line.get_color(), ls=":", lw=1)
        ax.axvline(100 * np.mean(measured["vertical"][:-1] > 0.5), color="k", ls=":", lw=1)
        what = {"ankle": "dorsiflexion +", "thigh": "from the vertical, knee ahead +"}.get(j, "flexion +")
        ax.set(title=f"{j} ({what})", xlabel="% of the cycle from right touchdown (dotted: toe-off)", ylabel="deg")
    fig.axes[0].legend(fontsize=7)
    fig.savefig(path, dpi=110)
    print(f"\nfigure: {path}")


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--speed", type=float, default=3.5, choices=[2.5, 3.5, 4.5])
    parser.add_argument("--rungs", nargs="*", default=["torque+springs", "muscles"], choices=["torque+springs", "muscles"])
    parser.add_argument("--strikes", nargs="+", default=["heel"], choices=["heel", "forefoot"])
    parser.add_argument("--figure", default=None)
    parser.add_argument("--markers", action="store_true")
    args = parser.parse_args(argv)
    processed = DATA / "RBDS001processed.txt"
    measured = measured_cycle(processed, args.speed)
    segments = measured_segments(args.speed) if args.speed in TRIALS else None
    if args.markers and segments is not None:
        markers(segments, measured)
    strides = {}
    for rung in args.rungs:
        for strike in args.strikes:
            clock = time.process_time()
            strides[f"{rung} {strike}"] = stride = solve(rung, strike, args.speed)
            table(f"{rung}, {strike} strike, {args.speed} m/s ({time.process_time() - clock:.0f} s CPU)", stride, measured, segments)
    if args.figure:
        figure(strides, measured, segments, args.figure)
    return 0


if __name__ == "__main__":
    sys.exit(main())
