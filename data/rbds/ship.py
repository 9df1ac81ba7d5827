"""The trial shipped in the wheel (formopt/data/rbds001, `formopt data copy DIR`): the first
SECONDS of RBDS001's 3.5 m/s run (markers at 150 Hz, treadmill force plate at 300 Hz) and its
static trial, unchanged otherwise (CC BY 4.0: the credit and licence travel beside them).

    python data/rbds/ship.py        # rewrites formopt/data/rbds001/RBDS001runT35_8s.c3d
"""

import shutil
from pathlib import Path

import ezc3d
import numpy as np

SECONDS = 8.0  # about 22 steps: enough for compare's per-side means, small enough for a wheel
HERE = Path(__file__).resolve().parent
OUT = HERE.parent.parent / "formopt" / "data" / "rbds001"


def trimmed(source: Path, seconds: float) -> ezc3d.c3d:
    c = ezc3d.c3d(str(source))
    rate = float(c["parameters"]["POINT"]["RATE"]["value"][0])
    frames = round(seconds * rate)
    ratio = c["data"]["analogs"].shape[2] // c["data"]["points"].shape[2]  # analog samples per frame
    points = np.array(c["data"]["points"][:, :, :frames])
    analogs = np.array(c["data"]["analogs"][:, :, :frames * ratio])
    c["data"]["points"] = points
    c["data"]["analogs"] = analogs
    c["data"]["meta_points"]["residuals"] = np.array(c["data"]["meta_points"]["residuals"][:, :, :frames])
    c["data"]["meta_points"]["camera_masks"] = np.array(
        c["data"]["meta_points"]["camera_masks"][:, :, :frames])
    return c


if __name__ == "__main__":
    OUT.mkdir(parents=True, exist_ok=True)
    trimmed(HERE / "RBDS001runT35.c3d", SECONDS).write(str(OUT / "RBDS001runT35_8s.c3d"))
    shutil.copyfile(HERE / "RBDS001static.c3d", OUT / "RBDS001static.c3d")
    print(f"wrote {OUT}: " + ", ".join(f"{p.name} {p.stat().st_size // 1024} kB" for p in sorted(OUT.glob("*.c3d"))))
