"""formopt compare --trial T --static S --mass M --height H: measured against optimal."""

from __future__ import annotations

from ..io import mocap
from ..io.files import save_figure, write_csv
from ..mechanics.contact import LAWS
from ..mechanics.errors import InputError
from ..report.figures import comparison_figure
from ..report.tables import comparison_table
from ..optim.variables import RANGE_OF_MOTION_DEG
from ..studies.compare import BOUNDS_DEG, SUPPORT, compare, report
from .common import add_format, emit, out_folder


def add_parser(commands):
    cmd = commands.add_parser("compare", help="measured touchdowns of a motion-capture trial "
                                              "against the optimum")
    add_format(cmd)
    cmd.add_argument("--trial", required=True, help="running trial: C3D, or RBDS marker text")
    cmd.add_argument("--static", required=True, help="standing calibration trial (C3D or text)")
    cmd.add_argument("--forces", help="force text file for a text trial (RBDS layout)")
    cmd.add_argument("--mass", type=float, required=True, help="runner's mass (kg)")
    cmd.add_argument("--height", type=float, required=True, help="runner's stature (m)")
    cmd.add_argument("--sex", default="male", choices=["male", "female"])
    cmd.add_argument("--friction", type=float, default=0.8, help="the ground's friction (default 0.8)")
    cmd.add_argument("--contact", default="no-slip", choices=LAWS,
                     help="contact law of the impacts and the optimum (default no-slip, the "
                          "paper's); every law's T_c and validity are shown either way")
    cmd.add_argument("--bounds", action="append", default=[], metavar="JOINT=LO:HI",
                     help="the optimum's bounds in deg, repeatable (default the ranges of motion: "
                          + ", ".join(f"{k}={lo:g}:{hi:g}" for k, (lo, hi) in BOUNDS_DEG.items()) + ")")
    cmd.add_argument("--support", type=float, default=SUPPORT,
                     help=f"weight of the stance's support in the optimum's objective (default "
                          f"{SUPPORT:g}; 0: T_c alone)")
    cmd.add_argument("--starts", type=int, default=4, help="starts of the optimum (default 4)")
    cmd.add_argument("--seed", type=int, default=0, help="seed of the random starts (default 0)")
    cmd.add_argument("--json", action="store_true", help="one JSON object on stdout")
    cmd.add_argument("--out", help="folder for the figure, CSV and JSON (default out/<trial>)")


def parse_bounds(items) -> dict:
    """{joint: (lo, hi)} from JOINT=LO:HI strings, or an InputError naming the bad one."""
    bounds = {}
    for item in items:
        joint, _, values = item.partition("=")
        try:
            lo, hi = map(float, values.split(":"))
        except ValueError:
            raise InputError(f"--bounds {item!r}: write JOINT=LO:HI in deg, e.g. knee=0:60") from None
        if joint not in BOUNDS_DEG:
            raise InputError(f"--bounds {item!r}: the joint is one of {', '.join(BOUNDS_DEG)}")
        rom = RANGE_OF_MOTION_DEG[joint]
        if not rom[0] <= lo < hi <= rom[1]:
            raise InputError(f"--bounds {item!r}: need {rom[0]:g} <= LO < HI <= {rom[1]:g} "
                             f"(the {joint}'s range of motion)")
        bounds[joint] = (lo, hi)
    return bounds


TOUCHDOWN_COLUMNS = ["time_s", "side", "strike", "trunk_deg", "hip_deg", "knee_deg", "ankle_deg",
                     "foot_angle_deg", "hip_vx", "hip_vz", "T_c_J", "valid",
                     *[f"{column}_{law}" for law in LAWS for column in ("T_c_J", "valid")]]


def run(args) -> int:
    if not 1.0 <= args.mass <= 500.0 or not 0.5 <= args.height <= 2.5:
        raise InputError("--mass must be 1 to 500 kg and --height 0.5 to 2.5 m")
    if not args.friction > 0:
        raise InputError("--friction must be > 0")
    if not args.support >= 0 or not 1 <= args.starts <= 1000:
        raise InputError("--support must be >= 0 and --starts 1 to 1000")
    bounds = parse_bounds(args.bounds)
    trial = mocap.read(args.trial, args.forces)
    static = mocap.read(args.static)
    out = out_folder(args, args.trial)
    result = compare(trial, static, args.mass, args.height, args.sex, args.friction,
                     starts=args.starts, seed=args.seed, law=args.contact, bounds_deg=bounds,
                     support=args.support)
    rep = report(result)
    rep["figure"] = str(save_figure(comparison_figure(result), out / f"comparison.{args.format}"))
    rows = [TOUCHDOWN_COLUMNS]
    for t in rep["touchdowns"]:
        a = t["angles_deg"]
        rows.append([t["time"], t["side"], t["strike"], a["trunk"], a["hip"], a["knee"], a["ankle"],
                     t["foot_angle_deg"], *t["hip_velocity"], t["T_c"], t["valid"],
                     *[t["contact_laws"][law][k] for law in LAWS for k in ("T_c", "valid")]])
    csv_path = write_csv(out / "touchdowns.csv", rows)
    emit(args, rep, out / "comparison.json", comparison_table(result), [rep["figure"], csv_path])
    return 0 if result.optimum.success else 1
