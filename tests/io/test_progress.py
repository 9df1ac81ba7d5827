"""io.progress: one bar for every long run, on stderr, with the elapsed and remaining time,
only to a terminal."""

import io
import sys

import pytest

from formopt.io import progress


class Terminal(io.StringIO):
    def isatty(self):
        return True


def test_a_terminal_sees_elapsed_and_remaining_time_and_the_stage(monkeypatch):
    monkeypatch.setattr(progress, "DELAY_S", 0.0)
    monkeypatch.setattr(sys, "stderr", Terminal())
    with progress.Stages(3, "compare") as say:
        say("measuring")
        say("side R: the optimum")
    text = sys.stderr.getvalue()
    assert "compare" in text and "side R: the optimum" in text and "1/3" in text
    assert "00:00<" in text  # [elapsed<remaining, ...]


def test_stages_with_shares_count_percent_of_the_run(monkeypatch):
    """compare's stride: stages of unequal length, the remaining time from their shares."""
    monkeypatch.setattr(progress, "DELAY_S", 0.0)
    monkeypatch.setattr(sys, "stderr", Terminal())
    with progress.Stages(3, "compare: stride", [2, 1, 5]) as say:
        say("the nominal")
        say("the family")
        assert say.bar.n == 25.0
        say("the band")
        assert say.bar.n == 37.5
    with pytest.raises(ValueError, match="2 shares for 3 stages"):
        progress.Stages(3, "compare: stride", [1, 1])


def test_a_pipe_or_a_log_sees_nothing(monkeypatch):
    monkeypatch.setattr(progress, "DELAY_S", 0.0)
    monkeypatch.setattr(sys, "stderr", io.StringIO())
    with progress.bar(10, "sweep", "landing") as b:
        b.update(10)
    assert sys.stderr.getvalue() == ""
