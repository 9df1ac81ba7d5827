"""Every example runs as a user would run it, prints its result and writes its figure."""

import subprocess
import sys

import pytest
from helpers import ROOT

EXAMPLES = sorted((ROOT / "examples").glob("*.py"))


@pytest.mark.parametrize("example", EXAMPLES, ids=[e.stem for e in EXAMPLES])
def test_example_runs_and_writes_its_figure(example, tmp_path):
    """An example with a quick mode runs in it (`make docs` runs every example in full)."""
    quick = ["--quick"] if "--quick" in example.read_text() else []
    out = subprocess.run([sys.executable, str(example), str(tmp_path), *quick], capture_output=True,
                         text=True, timeout=600)
    assert out.returncode == 0, out.stderr[-2000:]
    assert list(tmp_path.rglob("*.png")), "the example's figure"


def test_strike_laws_script_reads_the_real_trial(tmp_path):
    """problems/strike_laws.py: the fair heel-against-forefoot comparison on RBDS001."""
    out = subprocess.run([sys.executable, str(ROOT / "problems" / "strike_laws.py"), "--out",
                          str(tmp_path)], capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr[-2000:]
    table = {line.split()[0]: line.split() for line in out.stdout.splitlines()
             if line.split() and line.split()[0] in ("no-slip", "coulomb", "frictionless")}
    assert float(table["no-slip"][3]) > 1 > float(table["coulomb"][3])  # forefoot / heel
    assert table["coulomb"][6] == "10/10" and table["no-slip"][7] == "0/10"
    assert (tmp_path / "strike_laws.png").exists() and (tmp_path / "strike_laws.csv").exists()


def test_muscle_redundancy_converges_from_a_poor_guess():
    """problems/muscle_redundancy.py: the muscle layer's per-node rows (mechanics.muscles'
    LegFunctions) in a collocation problem on RBDS001's measured cycle, 25 nodes: IPOPT
    converges from a = e = F = 0.1 and the muscles carry the measured moments (reserves small)."""
    out = subprocess.run([sys.executable, str(ROOT / "problems" / "muscle_redundancy.py"),
                          "--speed", "3.5", "--every", "4"], capture_output=True, text=True,
                         timeout=600)
    assert out.returncode == 0, out.stderr[-2000:]
    assert "Solve_Succeeded" in out.stdout
    reserve = next(line for line in out.stdout.splitlines() if line.startswith("largest reserve"))
    assert float(reserve.split()[-3]) < 5.0  # "largest reserve moment: 3.58 N m"
