"""formopt compare --trial T --static S --mass M --height H: measured against optimal.

Every setting is an option and a key of the [compare] table of a --scene file (options given
on the command line win); a scene's [[trial]] entries (trial, static, forces, and any setting
that differs per runner) give one comparison each and one table across them (trials.csv).
"""

from __future__ import annotations

import sys
from pathlib import Path
from typing import Any

from ..io import markerset, mocap
from ..io import validate as val
from ..io.export import write_mot, write_osim, write_trc
from ..io.files import output_folder, save_figure, write_csv
from ..io.progress import Stages
from ..measure import Options
from ..mechanics import limits
from ..mechanics.body import DE_LEVA
from ..mechanics.contact import LAWS
from ..mechanics.errors import InputError
from ..report.figures import comparison_figure, stride_cadence_figure
from ..report.tables import comparison_table, trials_table
from ..studies.compare import BOUNDS_DEG, JOINTS, SIDES, SUPPORT, compare
from ..studies.compare_band import stage_count, stage_shares
from ..studies.compare_stride import answer
from ..studies.stride_form import STRIDE_MODEL, STRIDE_MODELS
from .common import add_format, emit, out_folder

# every setting: its default and what it is (the option's help)
SETTINGS: dict[str, tuple[Any, str]] = {
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
    "contact": ("coulomb", "contact law of the impacts and the optima: " + ", ".join(LAWS)),
    "bounds": ({}, "the optimum's bounds in deg, JOINT=LO:HI, repeatable (default the ranges of "
                   "motion: " + ", ".join(f"{k}={lo:g}:{hi:g}" for k, (lo, hi) in BOUNDS_DEG.items()) + ")"),
    "support": (SUPPORT, "weight of the stance's support in the optimum's objective (0: T_c alone)"),
    "starts": (4, "starts of the optimum"),
    "seed": (0, "seed of the random starts"),
    "per_step": (True, "an optimum for every step as well (--no-per-step: the mean step's only)"),
    "stride": (True, "the stride optimum of the runner's body and what-if cadences -10 to +10 %% "
                     "(--no-stride: the touchdowns only)"),
    "stride_model": (STRIDE_MODEL, "the stride's model: scenes (formopt stride's: Hermite-Simpson at 40 "
                                   "intervals, mesh-converged: 80-165 s a trial) or quick (a preview: the "
                                   "trapezoid at 30 intervals, knee and ankle springs: 15-18 s a trial, not "
                                   "mesh-converged)"),
}


def add_parser(commands):
    cmd = commands.add_parser("compare", help="measured touchdowns of a motion-capture trial "
                                              "against the optimum")
    add_format(cmd)
    cmd.add_argument("--scene", help="TOML file: [compare] settings and [[trial]] entries")
    for key, (default, text) in SETTINGS.items():
        flag = "--" + key.replace("_", "-")
        shown = f" (default {default})" if default not in (None, {}, True) else ""
        if key in ("per_step", "stride"):
            cmd.add_argument("--no-" + key.replace("_", "-"), dest=key, action="store_false",
                             default=None, help=text)
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
    """{joint: [lo, hi]} from --bounds JOINT=LO:HI strings (checked with the scene's bounds)."""
    bounds = {}
    for item in items:
        joint, _, values = item.partition("=")
        try:
            bounds[joint] = list(map(float, values.split(":")))
        except ValueError:
            raise InputError(f"--bounds {item!r}: write JOINT=LO:HI in deg, e.g. knee=0:60") from None
    return bounds


# A setting's range where it is not a physical limit (mechanics.limits): the markers' low-pass
# cut-off (running kinematics are filtered at 6-20 Hz; the sampling theorem caps it at half
# the rate, checked by mocap), the force plate's touchdown threshold, the touchdown's fraction
# of the running speed, the support term's weight.
RANGES = {"mass": limits.BODY_MASS_KG, "height": limits.BODY_HEIGHT_M,
          "friction": limits.FRICTION, "cutoff": limits.Range(0.5, 1000.0, "Hz"),
          "force_threshold": limits.Range(1.0, 5000.0, "N"),
          "foot_speed_fraction": limits.Range(0.05, 0.95), "support": limits.Range(0.0, 1e6)}
WHOLE = {"starts": (1, 1000), "seed": (0, 2**31)}
CHOICES = {"contact": LAWS, "stride_model": tuple(STRIDE_MODELS), "sex": tuple(DE_LEVA)}
FILES = ("trial", "static", "forces", "markers")


def check(table: dict, where: str, folder: Path | None = None) -> dict:
    """The settings of one table ([compare], a [[trial]] entry or the options) checked with
    io.validate and converted (numbers to float, bounds to {joint: (lo, hi)} deg, files
    relative to `folder`); keys not in `table` stay out."""
    val.keys(table, where, set(SETTINGS))
    out: dict[str, Any] = {}
    for key in table:
        if key in RANGES:
            out[key] = val.number(table, key, where, limit=RANGES[key])
        elif key in WHOLE:
            out[key] = val.integer(table, key, where, None, *WHOLE[key])
        elif key in FILES:
            name = val.string(table, key, where)
            relative = key != "markers" or name.endswith(".toml")
            out[key] = str(folder / name) if folder is not None and relative else name
        elif key in ("per_step", "stride"):
            out[key] = val.flag(table, key, where, True)
        elif key == "bounds":
            full = f"{where}.bounds" if where else "bounds"
            if not isinstance(table[key], dict):
                raise val.ValidationError(full, f"must be a table of JOINT = [lo, hi] in deg ("
                                                f"{', '.join(BOUNDS_DEG)}), not {val.short(table[key])}")
            b = val.table(table, key, set(BOUNDS_DEG), (), where)
            out[key] = {j: val.joint_bounds(v, f"{full}.{j}", j) for j, v in b.items()}
        else:
            out[key] = val.choice(table[key], f"{where}.{key}" if where else key, CHOICES[key])
    return out


def read_scene(path) -> tuple[dict, list[dict]]:
    """([compare] settings, [[trial]] entries) of a scene file, checked; paths relative to it."""
    path = Path(path)
    data = val.read_toml(path, "a compare scene")
    try:
        val.keys(data, "", {"compare", "trial"})
        shared = check(val.table(data, "compare", set(SETTINGS)) if "compare" in data else {},
                       "compare", path.parent)
        trials = data.get("trial", [])
        if not isinstance(trials, list) or not all(isinstance(t, dict) for t in trials):
            raise val.ValidationError("trial", "must be [[trial]] entries (an array of tables), "
                                               f"not {val.short(trials)}")
        return shared, [check(t, f"trial[{k + 1}]", path.parent) for k, t in enumerate(trials)]
    except val.ValidationError as err:
        raise err.in_file(path) from None


def settings(args) -> list[dict]:
    """One dict of every setting per trial: defaults < scene [compare] < [[trial]] < options."""
    shared, trials = read_scene(args.scene) if args.scene else ({}, [])
    given = {k: getattr(args, k) for k in SETTINGS if getattr(args, k) is not None}
    if "bounds" in given:
        given["bounds"] = parse_bounds(given["bounds"])
    cli_trials = given.pop("trial", None)
    try:
        given = check(given, "")
    except val.ValidationError as err:
        raise InputError(f"--{err.key.replace('_', '-')}: {err.reason}") from None
    if cli_trials:
        trials = [check({"trial": t}, "") for t in cli_trials]
    base = {k: d for k, (d, _) in SETTINGS.items()}
    out = []
    for entry in trials or [{}]:
        s = {**base, **shared, **entry, **given}
        missing = [k for k in ("trial", "static", "mass", "height") if s.get(k) is None]
        if missing:
            raise InputError(f"compare needs {', '.join('--' + k for k in missing)} (or the keys "
                             f"in a --scene file)")
        out.append(s)
    return out


TOUCHDOWN_COLUMNS = ["time_s", "side", "valid_data", "strike", "foot_strike_angle_deg",
                     "impact_point", "contact_order", "cop_index", "cop_point",
                     *[f"{k}_deg" for k in JOINTS], "thigh_deg", "shank_deg", "foot_deg",
                     "hip_vx", "hip_vz", "T_c_J", "T_c_low_J", "T_c_high_J", "valid",
                     *[f"{column}_{law}" for law in LAWS for column in ("T_c_J", "valid")],
                     "optimum_hip_deg", "optimum_knee_deg", "optimum_ankle_deg", "saving_J",
                     "m_eff_kg", "v_n_mps", "p_n_Ns", "plate_J1_Ns", "plate_t1_ms", "plate_r2",
                     "data_problems"]

TRIAL_COLUMNS = ["trial", "markers", "method", "touchdowns", "valid_data", "cadence_spm",
                 "speed_mps", "side", "steps", "strike", "foot_strike_angle_deg",
                 *[f"{k}_deg" for k in JOINTS], "T_c_J", "impact_point", "reference_valid",
                 "optimum_headline", *[f"optimum_{k}_deg" for k in ("hip", "knee", "ankle")],
                 "saving_J_per_step", "saving_low_J", "saving_high_J", "resolvable"]


def _blank(value):
    """A CSV cell: empty for None."""
    return "" if value is None else value


def run_one(s: dict, args, out: Path, show: bool = True):
    """One trial: compare, then its figure, CSV, OpenSim files and JSON (each written whole;
    the report built once, Comparison.to_dict); `show` False prints nothing."""
    trial = mocap.read(s["trial"], s["forces"])
    static = mocap.read(s["static"])
    options = Options(s["markers"], s["cutoff"], s["force_threshold"], s["foot_speed_fraction"])
    quiet = args.json or not show  # the bars themselves show only on a terminal (io.progress)
    with Stages(2 + len(SIDES), "compare") as say:  # measuring, the band, each side
        result = compare(trial, static, s["mass"], s["height"], s["sex"], friction=s["friction"],
                         starts=s["starts"], seed=s["seed"], law=s["contact"], bounds_deg=s["bounds"],
                         support=s["support"], options=options, per_step=s["per_step"],
                         progress=None if quiet else say)
    if s["stride"]:
        with Stages(stage_count(), "compare: stride", stage_shares(model=s["stride_model"])) as say:
            result.stride = answer(result, progress=None if quiet else say, model=s["stride_model"])
    rep = result.to_dict()
    rep["figure"] = str(save_figure(comparison_figure(result, rep), out / f"comparison.{args.format}"))
    rows = [TOUCHDOWN_COLUMNS]
    for t in rep["touchdowns"]:
        a, g, o = t["angles_deg"], t["segment_angles_deg"], t.get("optimum", {})
        ri, fit = t.get("rigid_impact", {}), t.get("plate_two_mass", {})
        rows.append([t["time"], t["side"], t["valid_data"], t["strike"], t["foot_strike_angle_deg"],
                     t["impact_point"], t["contact_order"], _blank(t["cop_index"]), _blank(t["cop_point"]),
                     *[a[k] for k in JOINTS], g["thigh"], g["shank"], g["foot"],
                     *t["hip_velocity_mps"], t["T_c"], *t["T_c_band_J"], t["valid"],
                     *[t["contact_laws"][law][k] for law in LAWS for k in ("T_c", "valid")],
                     *[o["angles_deg"][k] if o.get("success") else "" for k in ("hip", "knee", "ankle")],
                     o.get("saving_J", "") if o.get("success") else "",
                     *[ri.get(k, "") for k in ("m_eff_kg", "v_n_mps", "p_n_Ns")],
                     *[fit.get(k, "") for k in ("J1_Ns", "t1_ms", "r2")], "; ".join(t["data_problems"])])
    m = result.measurement
    if "stride" in rep:
        rep["stride"]["figure"] = str(save_figure(stride_cadence_figure(rep["stride"]),
                                                  out / f"stride_cadence.{args.format}"))
    files = [rep["figure"], *([rep["stride"]["figure"]] if "stride" in rep else []),
             write_csv(out / "touchdowns.csv", rows),
             write_trc(out / "markers.trc", m.kinematics, m.calibration),
             write_mot(out / "angles.mot", m.kinematics), write_osim(out / "model.osim", result.body)]
    emit(args, rep, comparison_table(result, rep), out / "comparison.json", files, show)
    return rep, result


def trial_rows(rep: dict) -> list[list]:
    """The rows of trials.csv of one trial: one per side, with that side's optimum."""
    rows = []
    for side, s in rep["summary"].items():
        opt = rep["optimum"].get(side, {})
        angles = opt.get("touchdown", {}).get("angles_deg", {})
        band = opt.get("saving_band_J") or ["", ""]
        saving = opt.get("saving_J_per_step")
        rows.append([rep["source"], rep["settings"]["markers"], rep["touchdown_method"],
                     rep["touchdowns_total"], rep["touchdowns_valid_data"], rep["cadence_spm"],
                     rep["speed"], side, s["steps"], s["strike"], s["foot_strike_angle_deg_mean"],
                     *[s["angles_deg_mean"][k] for k in JOINTS], s["T_c_mean"], opt.get("point", ""),
                     opt.get("reference", {}).get("valid", ""), opt.get("headline", ""),
                     *[angles.get(k, "") for k in ("hip", "knee", "ankle")],
                     "" if saving is None else saving, *band,
                     "" if opt.get("resolvable") is None else opt["resolvable"]])
    return rows


def trial_folders(trials: list[dict]) -> list[str]:
    """One output folder name per trial, unique for any set of trial paths (compared without
    case, as a case-insensitive file system does): the trial file's stem, and where two trials
    share it (run.c3d of two runners) the stem and the trial's number, lengthened while another
    trial's name holds it (x/a.c3d, y/a.c3d, x/a-1.c3d: a-1-1, a-2, a-1)."""
    stems = [Path(s["trial"]).stem for s in trials]
    keys = [stem.casefold() for stem in stems]
    taken = {key for key in keys if keys.count(key) == 1}
    names = []
    for k, (stem, key) in enumerate(zip(stems, keys), 1):
        name = stem
        if keys.count(key) > 1:
            name = f"{stem}-{k}"
            while name.casefold() in taken:
                name += f"-{k}"
            taken.add(name.casefold())
        names.append(name)
    return names


def readable(trials: list[dict]) -> None:
    """Every trial's files read once before the first comparison, so that a file that cannot be
    read (missing, damaged, of another format) is refused before any trial's work and output,
    in one line naming the trial and the file (0.01-0.6 s a file: RBDS001's 3.5 m/s C3D)."""
    for k, s in enumerate(trials, 1):
        try:
            mocap.read(s["trial"], s["forces"])
            mocap.read(s["static"])
        except InputError as err:
            raise InputError(f"{_trial_name(k, trials)}: {err}") from None


def _trial_name(k: int, trials: list[dict]) -> str:
    return f"trial {k} of {len(trials)} ({trials[k - 1]['trial']})" if len(trials) > 1 else str(trials[0]["trial"])


def run(args) -> int:
    trials = settings(args)
    many = len(trials) > 1
    if many:
        readable(trials)
    root = out_folder(args, args.scene or trials[0]["trial"])
    table, code = [TRIAL_COLUMNS], 0
    for k, (s, folder) in enumerate(zip(trials, trial_folders(trials)), 1):
        if many:
            if not args.json:
                print(f"[{k}/{len(trials)}] {s['trial']}", file=sys.stderr, flush=True)
            try:
                rep, result = run_one(s, args, output_folder(root / folder),
                                      show=not args.json)  # --json: only the JSON below on stdout
            except InputError as err:  # named by its trial; those before it stay in trials.csv
                before = "" if k == 1 else "the trial before it is" if k == 2 else f"the {k - 1} trials before it are"
                done = f"; {before} in {root / 'trials.csv'}" if before else ""
                raise InputError(f"{_trial_name(k, trials)}: {err}{done}") from None
        else:
            rep, result = run_one(s, args, root)
        code = max(code, 0 if all(o.optimum is None or o.optimum.success
                                  for o in result.sides.values()) else 1)
        table += trial_rows(rep)
        if many:
            write_csv(root / "trials.csv", table)  # after every trial: an interruption loses nothing
    if many:
        emit(args, {"trials": [dict(zip(table[0], row)) for row in table[1:]]},
             "\n" + trials_table(table), files=[root / "trials.csv"])
    return code
