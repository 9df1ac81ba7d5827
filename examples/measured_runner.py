"""A measured runner
=================

The touchdowns of RBDS subject 001 at 3.5 m/s (Fukuchi, Fukuchi &
Duarte 2017, PeerJ 5:e3298, CC BY 4.0) against the least-T_c posture at the same speed.

    python examples/measured_runner.py [OUT]     (reads data/rbds, shipped with the repository)
"""

import sys
from pathlib import Path

import formopt
from formopt.io import mocap
from formopt.io.files import save_figure
from formopt.report.figures import comparison_figure
from formopt.report.tables import comparison_table

DATA = Path(formopt.__file__).resolve().parents[1] / "data" / "rbds"  # the repository's data/ (a checkout)
out = Path(sys.argv[1] if len(sys.argv) > 1 else "out/examples")

trial = mocap.read(DATA / "RBDS001runT35.c3d")
static = mocap.read(DATA / "RBDS001static.c3d")
result = formopt.compare(trial, static, mass=62.0, height=1.81, friction=0.8)
report = result.to_dict()  # the JSON report, built once: the table and the figure read it
print(comparison_table(result, report))
print("wrote", save_figure(comparison_figure(result, report), out / "measured_runner.png"))
