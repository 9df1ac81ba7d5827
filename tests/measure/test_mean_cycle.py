"""measure.mean_cycle against the data set's own processing (Visual3D's mean cycle,
RBDS001processed.txt): the conventions studies.stride.compare_cycle relies on. Visual3D's hip is
the thigh against the pelvis's ASIS-PSIS frame (11.5 deg anterior tilt standing,
problems/rbds_angles.py), formopt's stride hip the thigh against the trunk; its knee and ankle
are formopt's within about 2 deg; both cycles start at the right touchdown."""

import numpy as np
import pytest
from trials import RBDS

from formopt.measure import mean_cycle, stance_knee_deg
from formopt.studies.stride import measured_cycle


@pytest.mark.parametrize("speed", [3.5, 2.5])
def test_the_processed_cycle_is_formopts_angles_with_the_pelvis_tilted(measured, speed):
    segments, cycles = mean_cycle(measured[speed])
    assert cycles > 30
    a = {k: np.degrees(v) for k, v in segments.items()}
    v3d = measured_cycle(RBDS / "RBDS001processed.txt", speed)["angles"]
    hip = v3d["hip"] - (a["thigh"] + a["trunk"])  # the trunk: the pelvis's tilt from standing
    knee = v3d["knee"] - (a["thigh"] - a["shank"])
    ankle = v3d["ankle"] - (a["foot"] - a["shank"])
    assert 10.0 < np.mean(hip) < 14.0 and np.std(hip) < 2.5
    assert abs(np.mean(knee)) < 3.0 and abs(np.mean(ankle)) < 3.0 and np.std(ankle) < 3.5
    assert abs(np.argmax(v3d["knee"]) - np.argmax(a["thigh"] - a["shank"])) <= 2  # the swing's peak, %


@pytest.mark.parametrize("speed", [3.5, 2.5])
def test_the_stance_knee_is_the_processed_ones(measured, speed):
    """The stance's deepest knee flexion (compare's runner line) within 4 deg of Visual3D's
    (42.2 deg at both speeds; formopt's 39.0 at 3.5 m/s, problems/stance_knee.py), in stance."""
    knee, peak = stance_knee_deg(measured[speed])
    v3d = measured_cycle(RBDS / "RBDS001processed.txt", speed)["angles"]["knee"]
    assert abs(knee - v3d[:35].max()) < 4.0 and 8 <= peak <= 25
