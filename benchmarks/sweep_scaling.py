"""Scaling of a landing sweep from 1 to 2 workers: local process pool and Dask distributed.

    python benchmarks/sweep_scaling.py [--scene formopt/scenes/landing_spring.toml]

A 41 x 8 grid (ankle angle x running speed, 328 landings); each setting runs on an empty
output file. Prints wall time, landings per second and the speed-up over one worker. The
machine has 2 cores: 2 workers is the ceiling here.
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
from pathlib import Path

from formopt import load
from formopt.studies import sweep

ROOT = Path(__file__).resolve().parent.parent


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--scene", default=str(ROOT / "formopt" / "scenes" / "landing_spring.toml"))
    args = parser.parse_args()
    scene = load(args.scene)
    params = [sweep.parse_param("ankle_deg=-25:-5:41"), sweep.parse_param("hip_vx=3:5:8")]
    n = 41 * 8
    sweep.run(scene, [sweep.parse_param("ankle_deg=-10:-10:1")], Path(tempfile.mkdtemp()) / "warm.csv",
              progress=False)  # compile once, so every setting loads from the cache
    print(f"{scene.name}: {n} landings; {os.cpu_count()} cores\n")
    print(f"{'setting':32s} {'wall (s)':>9s} {'landings/s':>11s} {'speed-up':>9s}")
    base = {}
    for label, kwargs, family in (("process pool, 1 worker", {"workers": 1}, "pool"),
                                  ("process pool, 2 workers", {"workers": 2}, "pool"),
                                  ("Dask LocalCluster, 1 worker", {"dask": 1}, "dask"),
                                  ("Dask LocalCluster, 2 workers", {"dask": 2}, "dask")):
        out = Path(tempfile.mkdtemp()) / "sweep.csv"
        if "dask" in kwargs:
            from dask.distributed import LocalCluster

            with LocalCluster(n_workers=kwargs["dask"], threads_per_worker=1, processes=True,
                              dashboard_address=None) as cluster:
                t = time.perf_counter()
                sweep.run(scene, params, out, progress=False, scheduler=cluster.scheduler_address)
                wall = time.perf_counter() - t
        else:
            t = time.perf_counter()
            sweep.run(scene, params, out, progress=False, **kwargs)
            wall = time.perf_counter() - t
        base.setdefault(family, wall)
        print(f"{label:32s} {wall:9.2f} {n / wall:11.1f} {base[family] / wall:9.2f}")


if __name__ == "__main__":
    main()
