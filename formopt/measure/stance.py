"""When a foot rests on the ground, and the direction the resting feet move (the belt's).

A foot rests where it is in the lowest LOW_QUANTILE of its heights and both its angular speed
and its vertical speed are under REST_FRACTION of their own 95th percentiles over the trial.
Both speeds scale with the cadence (a faster runner's foot turns and lifts faster in swing and
in stance alike), so the rule picks the same frames of a run played at any speed: it holds up
to 210 steps/min and beyond (tests/measure/test_stance.py plays real runs 1.3 times faster),
where the absolute rule it replaces (|omega| < 0.5 rad/s, |v_up| < 0.1 m/s, about 5 % of the
95th percentiles of RBDS001 and the RIC runner at 156-171 steps/min) found no rest at 184.
(The markers' fixed low-pass does change with the cadence: it smears the heel strike's turn
into the short flat phase of a fast heel striker; REST_FRACTION's margin covers it.)
A rate 10 times too high is refused, in one line naming the
rate (no rest: the markers' low-pass then cuts the stride; or a vertical far from the standing
body's; or a cadence the feet do not show).

Only measured frames rest (`measured`: none of the foot's markers missing, frozen or spiked,
measure.clean), and the speeds' percentiles are taken over them: a cluster frozen or lost for
seconds, filled by interpolation, glides slowly along a straight line and would otherwise be
one long "stance" whose path turns the vertical (40 deg on the RIC runner with its right foot
frozen for 10 s). A stance is a run of MIN_REST_FRAMES to MAX_STANCE_S of rest (stances). A
foot without any is named with what it failed (no_rest_reason); the other foot carries on.

On a treadmill the resting foot rides the belt, so its markers move along a level line: the
first principal direction of their paths over every stance (each marker's path centred on its
own mean, each side's, and the two sides' directions averaged) is horizontal (axes.find_axes
pitches the vertical to it). How well the paths fix it: a bootstrap over each side's stances
(BOOTSTRAP resamples, a fixed seed), and the difference between the sides.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .clean import runs

LOW_QUANTILE = 35.0  # percent: a resting foot is in the lowest third of its heights
REST_FRACTION = 0.07  # of the 95th percentile of the foot's angular and vertical speeds. The
#   margin, with the markers' default 10 Hz low-pass: the RIC runner (a heel striker, whose
#   foot is flat only briefly) played 1.5 times faster (246 steps/min) still rests 5+ frames
#   a stance; at 0.05 it did not beyond 1.3 times (214). The vertical without a plate moves
#   by up to 0.16 deg between 0.05 and 0.1 (0.26-0.28 deg from the plate's on RBDS001 T35,
#   0.14-0.30 on T25)
MIN_REST_FRAMES = 5  # frames in a row: a stance, for the paths
MAX_STANCE_S = 1.0  # s: a foot at rest longer is not running (stance 0.2-0.3 s at 2.5-4.5 m/s,
#                     walking's 0.6-0.7 s)
BOOTSTRAP = 200  # resamples of the stances for the direction's spread


def rest_tests(height, omega, v_up=None, measured=None) -> dict[str, np.ndarray]:
    """Each test of at_rest, (frames,) bool: "measured", "low", "turning slowly" and (with
    `v_up`) "moving up or down slowly"."""
    ok = np.ones(len(height), bool) if measured is None else np.asarray(measured, bool)
    if not ok.any():
        return {"measured": ok}
    tests = {"measured": ok, "low": height < np.percentile(height[ok], LOW_QUANTILE)}
    for name, speed in (("turning slowly", omega), ("moving up or down slowly", v_up)):
        if speed is not None:
            tests[name] = np.abs(speed) < REST_FRACTION * np.percentile(np.abs(speed[ok]), 95)
    return tests


def at_rest(height, omega, v_up=None, measured=None) -> np.ndarray:
    """(frames,) bool: the foot rests (module docstring); `height` (frames,; m), `omega` its
    pitch rate (frames,; rad/s), `v_up` its vertical velocity (frames,; m/s; None: not tested,
    where up is not yet known to better than the belt's speed times the tilt), `measured`
    (frames,) bool the frames its markers were measured (None: all)."""
    return np.logical_and.reduce(list(rest_tests(height, omega, v_up, measured).values()))


def stances(rest, rate: float) -> list[tuple[int, int]]:
    """(start, stop) frames of each run of `rest` from MIN_REST_FRAMES to MAX_STANCE_S long."""
    return [(a, b) for a, b in runs(rest) if MIN_REST_FRAMES <= b - a <= MAX_STANCE_S * rate]


def no_rest_reason(height, omega, v_up, measured, rate: float) -> str:
    """Why a foot has no stance: the share of frames that pass each test, all of them at once,
    and their longest run against MIN_REST_FRAMES and MAX_STANCE_S."""
    tests = rest_tests(height, omega, v_up, measured)
    both = np.logical_and.reduce(list(tests.values()))
    longest = max((b - a for a, b in runs(both)), default=0)
    return (", ".join(f"{name} {100 * t.mean():.0f} %" for name, t in tests.items())
            + f", all at once {100 * both.mean():.1f} % of the frames; the longest run {longest} frames "
            f"(a stance: {MIN_REST_FRAMES} to {MAX_STANCE_S * rate:.0f})")


@dataclass(frozen=True)
class StancePaths:
    """The resting feet's marker paths (module docstring), in the file's frame."""

    velocity: np.ndarray  # (3,) m/s: the resting feet's median velocity
    scatter: np.ndarray  # (stances, 3, 3) m^2: each stance's centred paths' scatter matrix
    sides: tuple[str, ...]  # (stances,) the side of each stance

    @property
    def direction(self) -> np.ndarray:
        """(3,) unit, along the feet's motion: the mean of each side's principal direction
        (the sides weigh alike, however many frames each rests)."""
        return _direction(self.scatter, np.array(self.sides), self.velocity)

    def spread(self, up) -> float:
        """Standard deviation (rad) of `direction`'s angle to the plane normal to `up` (3,)
        over BOOTSTRAP resamples of each side's stances (with replacement; seed 0)."""
        rng, sides = np.random.default_rng(0), np.array(self.sides)
        angles = []
        for _ in range(BOOTSTRAP):
            pick = np.concatenate([rng.choice(np.flatnonzero(sides == s), np.sum(sides == s))
                                   for s in dict.fromkeys(self.sides)])
            angles.append(_elevation(_direction(self.scatter[pick], sides[pick], self.velocity), up))
        return float(np.std(angles))

    def side_elevations(self, up) -> dict[str, float]:
        """Each side's path direction's angle (rad) to the plane normal to `up`, rising
        positive along the feet's motion."""
        sides = np.array(self.sides)
        return {s: _elevation(_direction(self.scatter[sides == s], sides[sides == s], self.velocity), up)
                for s in dict.fromkeys(self.sides)}


def stance_paths(markers: dict[str, np.ndarray], rest: dict[str, np.ndarray], rate: float) -> StancePaths | None:
    """The paths of each side's foot markers (`markers`: side -> (frames, k, 3); m, filtered)
    over its `rest` frames (side -> (frames,) bool), in stances (stances); None without any."""
    scatter, sides, velocities = [], [], []
    for side, M in markers.items():
        v = np.gradient(M, 1.0 / rate, axis=0)
        for a, b in stances(rest[side], rate):
            velocities.append(v[a:b].reshape(-1, 3))
            c = (M[a:b] - M[a:b].mean(axis=0)).reshape(-1, 3)
            scatter.append(c.T @ c)
            sides.append(side)
    if not scatter:
        return None
    return StancePaths(np.median(np.concatenate(velocities), axis=0), np.array(scatter), tuple(sides))


def _direction(scatter, sides, along) -> np.ndarray:
    """The unit mean (3,) over sides of the principal direction (largest eigenvalue) of each
    side's summed `scatter` (stances, 3, 3), each turned to point along `along` (3,)."""
    total = np.zeros(3)
    for s in dict.fromkeys(sides.tolist()):
        d = np.linalg.eigh(scatter[sides == s].sum(axis=0))[1][:, -1]
        total += d * np.sign(d @ along)
    return total / np.linalg.norm(total)


def _elevation(direction, up) -> float:
    """Angle (rad) of `direction` (3,) to the plane normal to `up` (3,): positive when it rises."""
    return float(np.arcsin(np.clip(direction @ up, -1.0, 1.0)))
