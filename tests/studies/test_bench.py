"""formopt bench --quick: every level and option measured, the report readable by tools."""

import json
import time

import pytest

from formopt.cli import main
from formopt.studies import bench
from formopt.studies.bench import LEVELS


def timed_once(f, args, repeats=1):
    """bench._median_time with one call, on the first argument (s): the tests check that each
    row is timed, not its median (every state's impact and landing, each posture solve 3 times,
    the batch 7 times: 0.8 of `bench.run(quick=True)`'s 3.5 s of CPU, 2026-11-27)."""
    start = time.perf_counter()
    f(next(iter(args)))
    return time.perf_counter() - start


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    out = tmp_path_factory.mktemp("bench")
    mp = pytest.MonkeyPatch()
    mp.setattr(bench, "_median_time", timed_once)
    try:
        assert main(["bench", "--quick", "--json", "--out", str(out)]) == 0
    finally:
        mp.undo()
    return json.loads((out / "bench.json").read_text()), out


def test_rows_cover_the_ladder_and_the_options(report):
    data, out = report
    rows = data["rows"]
    assert {"level", "option", "time_s", "error"} <= set(rows[0])
    for work in ("impact", "landing", "optimisation"):
        levels = {r["level"] for r in rows if r["work"] == work}
        assert levels >= set(LEVELS[1:])
    options = {r["option"] for r in rows if r["level"] == "leg"}
    assert {"SX compiled", "MX interpreted", "midpoint dt 1 ms", "limited-memory Hessian"} <= options
    assert all(r["time_s"] > 0 for r in rows)
    assert data["batch_states_per_s"] > 0  # measured, not judged: speed belongs to benchmarks/
    assert (data["friction"], data["slope_deg"]) == (0.8, 0.0)  # the bench scene's ground, shown
    assert (out / "pareto.png").stat().st_size > 0 and (out / "bench.csv").exists()


def test_errors_are_measured_not_assumed(report):
    data, _ = report
    impact = {r["level"]: r for r in data["rows"] if r["work"] == "impact" and r["option"].startswith("ladder")}
    assert impact["full-body"]["error"] == 0.0
    # the effective mass misses the full body's T_c by far more than the paper's leg does
    assert impact["effective-mass"]["error"] > 10 * impact["leg"]["error"] > 0
    compiled = next(r for r in data["rows"] if r["option"] == "SX compiled")
    assert compiled["error"] < 1e-12  # compiling changes the speed, not the numbers
