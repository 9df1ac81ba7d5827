"""formopt compare --trial T --static S --mass M --height H: measured against optimal.

Every setting is an option and a key of the [compare] table of a --scene file (options given
on the command line win); a scene's [[trial]] entries (trial, static, forces, and any setting
that differs per runner) give one comparison each and one table across them (trials.csv).
"""

from __future__ import annotations

import argparse
import json
import sys
import tomllib
from pathlib import Path

from ..io import markerset, mocap
from ..io.export import write_mot, write_trc
from ..io.files import output_folder, save_figure, write_csv
from ..measure import Options
from ..mechanics.contact import LAWS
from ..mechanics.errors import InputError
from ..optim.variables import RANGE_OF_MOTION_DEG
from ..report.figures import comparison_figure
from ..report.tables import comparison_table, trials_table
from ..studies.compare import BOUNDS_DEG, JOINTS, SUPPORT, compare, report
from .common import add_format, emit, out_folder

# every setting: its default and what it is (the option's help)
SETTINGS = {
    "trial": (None, "running trial: C3D, or RBDS marker text (repeatable: one row each)"),
    "static": (None, "standing calibration trial (C3D or text)"),
    "forces": (None, "force text file for a text trial (RBDS layout)"),
    "mass": (None, "runner's mass (kg)"),
    "height": (None, "runner's stature (m)"),
    "sex": ("male", "male or female (de Leva's segment parameters)"),
    "markers": (None, "marker map: " + ", ".join(markerset.shipped()) +
                " or a TOML file (default: recognised from the labels)"),
    "cutoff": (Options.cutoff_hz, "low-pass cutoff of the markers (Hz)"),
    "force_threshold": (Options.force_threshold_n, "vertical force at touchdown (N)"),
    "foot_speed_fraction": (Options.foot_speed_fraction,
                            "without a force plate: touchdown when the foot's speed over the "
                            "ground falls below this fraction of the running speed"),
    "friction": (0.8, "the ground's friction"),
    "contact": ("no-slip", "contact law of the impacts and the optima: " + ", ".join(LAWS)),
    "bounds": ({}, "the optimum's bounds in deg, JOINT=LO:HI, repeatable (default the ranges of "
                   "motion: " + ", ".join(f"{k}={lo:g}:{hi:g}" for k, (lo, hi) in BOUNDS_DEG.items()) + ")"),
    "support": (SUPPORT, "weight of the stance's support in the optimum's objective (0: T_c alone)"),
    "starts": (4, "starts of the optimum"),
    "seed": (0, "seed of the random starts"),
    "per_step": (True, "an optimum for every step as well (--no-per-step: the mean step's only)"),
}


def add_parser(commands):
    cmd = commands.add_parser("compare", help="measured touchdowns of a motion-capture trial "
                                              "against the optimum")
    add_format(cmd)
    cmd.add_argument("--scene", help="TOML file: [compare] settings and [[trial]] entries")
    for key, (default, text) in SETTINGS.items():
        flag = "--" + key.replace("_", "-")
        shown = f" (default {default})" if default not in (None, {}, True) else ""
        if key == "per_step":
            cmd.add_argument("--no-per-step", dest="per_step", action="store_false", default=None, help=text)
        elif key in ("trial", "bounds"):
            cmd.add_argument(flag, action="append", default=None, help=text + shown)
        else:
            cmd.add_argument(flag, dest=key, default=None, help=text + shown,
                             type=float if isinstance(default, float) or key in ("mass", "height")
                             else int if isinstance(default, int) else str)
    cmd.add_argument("--json", action="store_true", help="one JSON object on stdout")
    cmd.add_argument("--out", help="folder for the figures, CSV, JSON and OpenSim files "
                                   "(default out/<trial>)")


def parse_bounds(items) -> dict:
    """{joint: (lo, hi)} from JOINT=LO:HI strings, or an InputError naming the bad one."""
    bounds = {}
    for item in items:
        joint, _, values = item.partition("=")
        try:
            lo, hi = map(float, values.split(":"))
        except ValueError:
            raise InputError(f"--bounds {item!r}: write JOINT=LO:HI in deg, e.g. knee=0:60") from None
        bounds[joint] = (lo, hi)
    return bounds


def check_bounds(bounds: dict) -> dict:
    for joint, (lo, hi) in bounds.items():
        if joint not in BOUNDS_DEG:
            raise InputError(f"bounds {joint!r}: the joint is one of {', '.join(BOUNDS_DEG)}")
        rom = RANGE_OF_MOTION_DEG[joint]
        if not rom[0] <= lo < hi <= rom[1]:
            raise InputError(f"bounds {joint}={lo:g}:{hi:g}: need {rom[0]:g} <= LO < HI <= "
                             f"{rom[1]:g} (the {joint}'s range of motion)")
    return {k: (float(lo), float(hi)) for k, (lo, hi) in bounds.items()}


def read_scene(path) -> tuple[dict, list[dict]]:
    """([compare] settings, [[trial]] entries) of a scene file; paths relative to it."""
    path = Path(path)
    try:
        data = tomllib.loads(path.read_text())
    except (OSError, tomllib.TOMLDecodeError) as err:
        raise InputError(f"{path}: not a readable scene ({err})") from None
    unknown = set(data) - {"compare", "trial"}
    if unknown:
        raise InputError(f"{path}: unknown table {sorted(unknown)[0]!r} (a compare scene has "
                         f"[compare] and [[trial]])")
    shared, trials = data.get("compare", {}), data.get("trial", [])
    for where, table in [("[compare]", shared)] + [(f"[[trial]] {k + 1}", t) for k, t in enumerate(trials)]:
        bad = set(table) - set(SETTINGS)
        if bad:
            raise InputError(f"{path}: {where}: unknown key {sorted(bad)[0]!r} "
                             f"(keys: {', '.join(SETTINGS)})")
        for key in ("trial", "static", "forces", "markers"):
            if isinstance(table.get(key), str) and (key != "markers" or table[key].endswith(".toml")):
                table[key] = str(path.parent / table[key])
        if isinstance(table.get("bounds"), dict):
            table["bounds"] = {k: tuple(v) for k, v in table["bounds"].items()}
    return shared, trials


def settings(args) -> list[dict]:
    """One dict of every setting per trial: defaults < scene [compare] < [[trial]] < options."""
    shared, trials = read_scene(args.scene) if args.scene else ({}, [])
    given = {k: getattr(args, k) for k in SETTINGS if getattr(args, k) is not None}
    if "bounds" in given:
        given["bounds"] = parse_bounds(given["bounds"])
    cli_trials = given.pop("trial", None)
    if cli_trials:
        trials = [{"trial": t} for t in cli_trials]
    base = {k: d for k, (d, _) in SETTINGS.items()}
    out = []
    for entry in trials or [{}]:
        s = {**base, **shared, **entry, **given}
        if isinstance(s["trial"], list):
            raise InputError("trial: one file per [[trial]] entry")
        missing = [k for k in ("trial", "static", "mass", "height") if s.get(k) is None]
        if missing:
            raise InputError(f"compare needs {', '.join('--' + k for k in missing)} (or the keys "
                             f"in a --scene file)")
        out.append(_checked(s))
    return out


def _checked(s: dict) -> dict:
    def number(key, lo, hi, unit=""):
        try:
            value = float(s[key])
        except (TypeError, ValueError):
            raise InputError(f"{key} must be a number, not {s[key]!r}") from None
        if not lo <= value <= hi:
            raise InputError(f"{key} = {value:g}{unit} is outside {lo:g} to {hi:g}{unit}")
        return value
    s["mass"], s["height"] = number("mass", 1, 500, " kg"), number("height", 0.5, 2.5, " m")
    s["friction"] = number("friction", 1e-6, 1e6)
    s["support"] = number("support", 0, 1e6)
    s["cutoff"] = number("cutoff", 0.5, 1000, " Hz")
    s["force_threshold"] = number("force_threshold", 1, 5000, " N")
    s["foot_speed_fraction"] = number("foot_speed_fraction", 0.05, 0.95)
    s["starts"], s["seed"] = int(number("starts", 1, 1000)), int(number("seed", 0, 2 ** 31))
    if s["sex"] not in ("male", "female"):
        raise InputError(f"sex must be male or female, not {s['sex']!r}")
    if s["contact"] not in LAWS:
        raise InputError(f"contact {s['contact']!r}: one of {', '.join(LAWS)}")
    s["bounds"] = check_bounds(s["bounds"])
    return s


TOUCHDOWN_COLUMNS = ["time_s", "side", "valid_data", "strike", "foot_strike_angle_deg",
                     *[f"{k}_deg" for k in JOINTS], "thigh_deg", "shank_deg", "foot_deg",
                     "hip_vx", "hip_vz", "T_c_J", "valid",
                     *[f"{column}_{law}" for law in LAWS for column in ("T_c_J", "valid")],
                     "optimum_hip_deg", "optimum_knee_deg", "optimum_ankle_deg", "saving_J",
                     "data_problems"]

TRIAL_COLUMNS = ["trial", "markers", "method", "touchdowns", "valid_data", "cadence_spm",
                 "speed_mps", "side", "steps", "strike", "foot_strike_angle_deg",
                 *[f"{k}_deg" for k in JOINTS], "T_c_J", "optimum_verdict",
                 *[f"optimum_{k}_deg" for k in ("hip", "knee", "ankle")], "saving_J_per_step"]


def run_one(s: dict, args, out: Path):
    """One trial: compare, then its figure, CSV, OpenSim files and JSON (each written whole)."""
    trial = mocap.read(s["trial"], s["forces"])
    static = mocap.read(s["static"])
    options = Options(s["markers"], s["cutoff"], s["force_threshold"], s["foot_speed_fraction"])
    result = compare(trial, static, s["mass"], s["height"], s["sex"], s["friction"],
                     starts=s["starts"], seed=s["seed"], law=s["contact"], bounds_deg=s["bounds"],
                     support=s["support"], options=options, per_step=s["per_step"])
    rep = report(result)
    rep["figure"] = str(save_figure(comparison_figure(result), out / f"comparison.{args.format}"))
    rows = [TOUCHDOWN_COLUMNS]
    for t in rep["touchdowns"]:
        a, g, o = t["angles_deg"], t["segment_angles_deg"], t.get("optimum", {})
        rows.append([t["time"], t["side"], t["valid_data"], t["strike"], t["foot_strike_angle_deg"],
                     *[a[k] for k in JOINTS], g["thigh"], g["shank"], g["foot"],
                     *t["hip_velocity_mps"], t["T_c"], t["valid"],
                     *[t["contact_laws"][law][k] for law in LAWS for k in ("T_c", "valid")],
                     *[o["angles_deg"][k] if o.get("success") else "" for k in ("hip", "knee", "ankle")],
                     o.get("saving_J", "") if o.get("success") else "", "; ".join(t["data_problems"])])
    m = result.measurement
    files = [rep["figure"], write_csv(out / "touchdowns.csv", rows),
             write_trc(out / "markers.trc", m.kinematics, m.calibration),
             write_mot(out / "angles.mot", m.kinematics)]
    emit(args, rep, out / "comparison.json", comparison_table(result), files)
    return rep, result


def trial_rows(rep: dict) -> list[list]:
    """The rows of trials.csv of one trial: one per side."""
    rows = []
    opt = rep["optimum"]
    for side, s in rep["summary"].items():
        rows.append([rep["source"], rep["settings"]["markers"], rep["touchdown_method"],
                     rep["touchdowns_total"], rep["touchdowns_valid_data"], rep["cadence_spm"],
                     rep["speed"], side, s["steps"], s["strike"], s["foot_strike_angle_deg_mean"],
                     *[s["angles_deg_mean"][k] for k in JOINTS], s["T_c_mean"], opt["verdict"],
                     *[opt["touchdown"]["angles_deg"][k] for k in ("hip", "knee", "ankle")],
                     opt["saving_J_per_step"]])
    return rows


def run(args) -> int:
    trials = settings(args)
    many = len(trials) > 1
    root = out_folder(args, args.scene or trials[0]["trial"])
    table, code = [TRIAL_COLUMNS], 0
    quiet = argparse.Namespace(**{**vars(args), "json": False})
    for k, s in enumerate(trials, 1):
        if many:
            print(f"[{k}/{len(trials)}] {s['trial']}", file=sys.stderr, flush=True)
            rep, result = run_one(s, quiet, output_folder(root / Path(s["trial"]).stem))
        else:
            rep, result = run_one(s, args, root)
        code = max(code, 0 if result.optimum.success else 1)
        table += trial_rows(rep)
        if many:
            write_csv(root / "trials.csv", table)  # after every trial: an interruption loses nothing
    if many and args.json:
        print(json.dumps({"trials": [dict(zip(table[0], row)) for row in table[1:]]}, indent=2))
    elif many:
        print("\n" + trials_table(table) + f"\n\nwrote {root / 'trials.csv'}")
    return code
