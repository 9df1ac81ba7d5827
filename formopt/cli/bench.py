"""formopt bench [--quick]: time and accuracy of each model level and numerical option."""

from __future__ import annotations

import dataclasses
import sys
from pathlib import Path

from ..io.files import save_figure, write_csv
from ..report.figures import pareto_figure
from ..report.tables import bench_table
from ..studies import bench
from .common import add_format, emit


def add_parser(commands):
    cmd = commands.add_parser("bench", help="time and accuracy of each model level and numerical "
                                            "option (the bench states shipped with formopt)")
    add_format(cmd)
    cmd.add_argument("--quick", action="store_true", help="a reduced set, under a minute")
    cmd.add_argument("--json", action="store_true", help="one JSON object on stdout")
    cmd.add_argument("--out", default="out/bench", help="folder for bench.csv and pareto.png")


def run(args) -> int:
    result = bench.run(args.quick, progress=lambda text: print(f"  {text}", file=sys.stderr))
    out = Path(args.out)
    table = [dataclasses.asdict(r) for r in result.rows]
    files = [write_csv(out / "bench.csv", [list(table[0])] + [list(r.values()) for r in table]),
             save_figure(pareto_figure(result.rows), out / f"pareto.{args.format}")]
    report = {**result.to_dict(), "files": [str(f) for f in files]}
    emit(args, report, bench_table(result), out / "bench.json", files)
    return 0
