"""Motion-capture processing: a run and its standing trial (io.mocap.read) to touchdown states.

One module per topic, in the order `measure` runs them (pipeline.py):

    clean        missing samples, spikes and frozen stretches marked; short gaps filled
    units        the markers' units checked against the stature, or inferred
    rigid        Kabsch fits of a cluster, their residual and angular velocity
    labels       the standing trial holds still; swapped labels swapped back
    filters      the zero-lag Butterworth low-pass
    stance       when a foot rests; the resting feet's level paths (the belt's direction)
    axes         lab axes from physics (the force, the standing body, the resting feet)
    joints       joint centres and foot points in the standing trial (Harrington hip)
    kinematics   clusters fitted frame by frame (Kabsch), segment angles
    touchdowns   touchdowns from the force plate or the foot's speed; touchdown states

Conventions, said once: time is the first dimension of every array (a marker is (frames, 3),
a sagittal point (frames, 2) forward and up, an angle (frames,)); markers are in m in the
file's lab frame until `axes` names forward, left and up; angles in rad and rates in rad/s
(design.md section 2); labels are the marker map's (io.markerset), sides "R" and "L".
"""

from .pipeline import Measurement, Options, mean_cycle, measure, stance_knee_deg
from .touchdowns import Steps, Touchdown

__all__ = ["Measurement", "Options", "Steps", "Touchdown", "mean_cycle", "measure", "stance_knee_deg"]
