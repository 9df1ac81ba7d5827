"""Progress of long runs on stderr, one helper for every command: a tqdm bar with the elapsed
and the remaining time, shown only to a person (stderr a terminal, as tqdm's own convention)
and only once a run has taken DELAY_S (a quick run prints nothing). Callers that know their
work in stages of unequal length (compare: measuring, the band, each side) tell `Stages` each
stage; its remaining time is then an estimate from the stages done."""

from __future__ import annotations

import sys

DELAY_S = 2.0  # s: a run shorter than this shows no bar


def bar(total: int | None, desc: str, unit: str = "step", initial: int = 0):
    """A tqdm bar on stderr: `total` units of work (`initial` done already), its elapsed and
    remaining time; silent when stderr is not a terminal or the run ends within DELAY_S."""
    from tqdm import tqdm

    return tqdm(total=total, initial=initial, desc=desc, unit=unit, delay=DELAY_S, file=sys.stderr,
                disable=not sys.stderr.isatty(), dynamic_ncols=True, leave=False)


class Stages:
    """`say(text)` for a run of `total` stages: each call completes the stage before it and names
    the next on the bar (`total` None: stages not counted, the elapsed time only). `shares`:
    each stage's expected share of the run, in the order they are told (any unit): the bar then
    counts percent, and the remaining time is estimated from the shares done, not the count.
    Use as a context manager (the bar closes on leaving)."""

    def __init__(self, total: int | None, desc: str, shares: list[float] | None = None):
        if shares is not None and len(shares) != total:
            raise ValueError(f"Stages: {len(shares)} shares for {total} stages")
        self.shares = None if shares is None else [100.0 * w / sum(shares) for w in shares]
        self.bar = bar(100 if shares else total, desc, unit="%" if shares else "stage")
        self.done, self.started = 0, False

    def __call__(self, text: str) -> None:
        if self.started:
            self.bar.update(self.shares[self.done] if self.shares else 1)
            self.done += 1
        self.started = True
        self.bar.set_postfix_str(text, refresh=True)

    def __enter__(self) -> Stages:
        return self

    def __exit__(self, *exc) -> None:
        self.bar.close()
