"""gait2d's muscle table read into mechanics.muscles' units, scaled to a body.

data/gait2d_muscles.csv holds the right leg's rows of BioMAC-Sim-Toolbox's gait2dc_par.xls (the
gait2d model of Ackermann & van den Bogert 2010), the columns formopt uses, unchanged; its
licence (Apache-2.0) is data/LICENSE-gait2dc.txt.
"""

from __future__ import annotations

import csv
from pathlib import Path

import numpy as np

from ..mechanics.body import Body, stature
from ..mechanics.errors import InputError
from ..mechanics.joint_space import JointSpace
from ..mechanics.muscles import MUSCLES, REFERENCE_HEIGHT, REFERENCE_MASS, Muscles, from_gait2d

DATA = Path(__file__).resolve().parent / "data" / "gait2d_muscles.csv"
COLUMNS = ("Fmax", "Lceopt", "Width", "PEEslack", "SEEslack", "L0", "dRhip", "dRknee", "dRankle",
           "kPEE", "%FT/100")


def read_gait2d_table(path=DATA) -> dict[str, np.ndarray]:
    """The table's `COLUMNS` (gait2d's names and units), one value per muscle of `MUSCLES`."""
    try:
        lines = [line for line in Path(path).read_text().splitlines() if not line.startswith("#")]
    except OSError as err:
        raise InputError(f"{path}: cannot read the muscle table ({err.strerror})") from None
    rows = list(csv.DictReader(lines))
    if len(rows) != len(MUSCLES):
        raise InputError(f"{path}: {len(rows)} muscle rows, gait2d has {len(MUSCLES)}")
    try:
        return {key: np.array([float(row[key]) for row in rows]) for key in COLUMNS}
    except (KeyError, TypeError, ValueError) as err:
        raise InputError(f"{path}: the muscle table needs numbers in the columns "
                         f"{', '.join(COLUMNS)} ({err!r})") from None


def gait2d_muscles(mass: float = REFERENCE_MASS, height: float = REFERENCE_HEIGHT,
                   path=DATA) -> Muscles:
    """One leg's gait2d muscles scaled to `mass` (kg) and `height` (m) (mechanics.muscles.from_gait2d)."""
    return from_gait2d(read_gait2d_table(path), mass, height)


def body_muscles(body: Body, path=DATA) -> Muscles:
    """One leg's gait2d muscles scaled to a body: its whole mass (both legs: the joint space's)
    and the stature its leg stands for (mechanics.body.stature)."""
    return gait2d_muscles(JointSpace(body).mass_total, stature(body), path)
