"""The command line under signals and pipes: Ctrl-C at any moment is one line and exit 130; a
reader that goes away ends formopt quietly."""

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from helpers import DATA, ROOT

from formopt.cli import main

# a run of 8-20 s: reading the trial, touchdowns, per-step optima
COMMAND = [sys.executable, "-m", "formopt.cli", "compare", "--trial", str(DATA / "rbds/RBDS001runT35.c3d"),
           "--static", str(DATA / "rbds/RBDS001static.c3d"), "--mass", "62", "--height", "1.81",
           "--out"]


def loaded(pid: int, library: str) -> bool:
    """Whether the process has mapped a shared library whose path holds `library`."""
    try:
        return library in Path(f"/proc/{pid}/maps").read_text()
    except OSError:
        return False


@pytest.mark.parametrize("delay", [0.0, 1.0])  # s after CasADi loads: while importing, computing
def test_ctrl_c_is_one_line_and_exit_130(tmp_path, delay):
    p = subprocess.Popen(COMMAND + [str(tmp_path)], cwd=ROOT, stdout=subprocess.DEVNULL,
                         stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + 60
    while not loaded(p.pid, "casadi") and p.poll() is None and time.monotonic() < deadline:
        time.sleep(0.005)  # formopt's main is running (the interpreter's own start is not ours)
    time.sleep(delay)
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=60)
    if p.returncode == 0:  # finished before the signal came: nothing to check
        return
    assert p.returncode == 130 and "Traceback" not in err
    assert err.strip().splitlines()[-1].startswith("formopt: interrupted")


def test_a_closed_pipe_is_a_quiet_exit(monkeypatch, capsys):
    read, write = os.pipe()
    os.close(read)  # the reader is gone, as after `formopt ... | head -c 1`
    monkeypatch.setattr(sys, "stdout", os.fdopen(write, "w"))
    assert main(["impact", "demo", "--json"]) == 141
    assert capsys.readouterr().err == ""
