"""Every example runs as a user would run it, prints its result and writes its figure. The
examples and scripts run in this process (`run_script`: as __main__, with their sys.argv), not
as subprocesses: a new interpreter's start, imports and first models cost about 1.2 s of CPU an
example; the CLI's own entry point is tested as a subprocess elsewhere (tests/io/test_scene.py).
Given up with the subprocess: a crash or hang at the interpreter's exit, and a fresh process (an
example may reuse a stride NLP an earlier test built: collocation's cache); `make docs` still
runs every example as a new interpreter."""

import runpy
import sys
from pathlib import Path

import matplotlib.pyplot as plt
import pytest
from helpers import ROOT

EXAMPLES = sorted((ROOT / "examples").glob("*.py"))


def run_script(path, args, monkeypatch, capfd) -> str:
    """What `python path *args` prints (its standard output, the C libraries' included), run
    in this process: the file as __main__ with sys.argv set and its folder first on sys.path (as
    python puts it: problems/ scripts import each other); an exit other than 0 fails, and the
    figures it left open are closed."""
    monkeypatch.setattr(sys, "argv", [str(path), *map(str, args)])
    monkeypatch.syspath_prepend(str(Path(path).parent))
    capfd.readouterr()
    try:
        runpy.run_path(str(path), run_name="__main__")
    except SystemExit as end:
        assert end.code in (None, 0), f"{path.name} exited with {end.code}"
    finally:
        plt.close("all")
    return capfd.readouterr().out


@pytest.mark.parametrize("example", EXAMPLES, ids=[e.stem for e in EXAMPLES])
def test_example_runs_and_writes_its_figure(example, tmp_path, monkeypatch, capfd):
    """An example with a quick mode runs in it (`make docs` runs every example in full)."""
    quick = ["--quick"] if "--quick" in example.read_text() else []
    assert run_script(example, [tmp_path, *quick], monkeypatch, capfd), "the example's result"
    assert list(tmp_path.rglob("*.png")), "the example's figure"


def test_strike_laws_script_reads_the_real_trial(tmp_path, monkeypatch, capfd):
    """problems/strike_laws.py: the fair heel-against-forefoot comparison on RBDS001."""
    out = run_script(ROOT / "problems" / "strike_laws.py", ["--out", tmp_path], monkeypatch, capfd)
    table = {line.split()[0]: line.split() for line in out.splitlines()
             if line.split() and line.split()[0] in ("no-slip", "coulomb", "frictionless")}
    assert float(table["no-slip"][3]) > 1 > float(table["coulomb"][3])  # forefoot / heel
    assert table["coulomb"][6] == "10/10" and table["no-slip"][7] == "0/10"
    assert (tmp_path / "strike_laws.png").exists() and (tmp_path / "strike_laws.csv").exists()


def test_muscle_redundancy_converges_from_a_poor_guess(monkeypatch, capfd):
    """problems/muscle_redundancy.py: the muscle layer's per-node rows (mechanics.muscles'
    LegFunctions) in a collocation problem on RBDS001's measured cycle, 25 nodes: IPOPT
    converges from a = e = F = 0.1 and the muscles carry the measured moments (reserves small)."""
    out = run_script(ROOT / "problems" / "muscle_redundancy.py", ["--speed", "3.5", "--every", "4"],
                     monkeypatch, capfd)
    assert "Solve_Succeeded" in out
    reserve = next(line for line in out.splitlines() if line.startswith("largest reserve"))
    assert float(reserve.split()[-3]) < 5.0  # "largest reserve moment: 3.58 N m"


def test_ankle_bound_script_reads_the_runner_without_a_solve(monkeypatch, capfd):
    """problems/ankle_bound.py --no-solve (docs/concepts/muscles.md, "Why the ankle goes to its
    bound"): the plantarflexors over RBDS001's stance and the relaxed ankle against Riener &
    Edrich, the figures the page quotes; --brief and --no-solve exclude each other."""
    script = ROOT / "problems" / "ankle_bound.py"
    out = run_script(script, ["--no-solve"], monkeypatch, capfd)
    assert "knee 40, ankle 22 deg: soleus l~ 1.073 / 0.868, gastrocnemius 1.324 / 0.973" in out
    relaxed = {int(line.split()[1]): line.split() for line in out.splitlines() if line.strip().startswith("knee ")}
    assert relaxed[0][-2:] == ["100.8", "154.6"] and relaxed[0][8] == "25.3"  # 30 deg: muscles, measured
    assert relaxed[50][8] == "6.9" and relaxed[50][-2] == "40.8"
    with pytest.raises(AssertionError, match="exited with 2"):
        run_script(script, ["--brief", "--no-solve"], monkeypatch, capfd)
