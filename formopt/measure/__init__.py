"""Motion-capture processing: a run and its standing trial (io.mocap.read) to touchdown states.

One module per topic, in the order `measure` runs them (pipeline.py):

    clean        missing samples, spikes and frozen stretches marked; short gaps filled
    units        the markers' units checked against the stature, or inferred
    labels       the standing trial holds still; swapped labels swapped back
    axes         lab axes from physics (the force, the standing body, the stance foot)
    joints       joint centres and foot points in the standing trial (Harrington hip)
    filters      the zero-lag Butterworth low-pass
    kinematics   clusters fitted frame by frame (Kabsch), segment angles
    touchdowns   touchdowns from the force plate or the foot's speed; touchdown states

Conventions, said once: time is the first dimension of every array (a marker is (frames, 3),
a sagittal point (frames, 2) forward and up, an angle (frames,)); markers are in m in the
file's lab frame until `axes` names forward, left and up; angles in rad and rates in rad/s
(design.md section 2); labels are the marker map's (io.markerset), sides "R" and "L".
"""

from .pipeline import Measurement, Options, measure
from .touchdowns import Steps, Touchdown

__all__ = ["Measurement", "Options", "Steps", "Touchdown", "measure"]
