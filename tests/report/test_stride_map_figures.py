"""A stride map's figures (report/stride_sweep.py) drawn from the rows a map writes."""

import matplotlib.pyplot as plt
import numpy as np

from formopt.report.stride_sweep import PANELS, map_figure


def test_a_map_of_one_speed_draws_every_stride():
    """One speed and three cadences: too few points for contours; the fallback drew nothing
    (a pcolormesh of one column), now a square per stride coloured by its value."""
    rows = [{"speed_mps": "3.5", "cadence_spm": str(c), "error": "", "success": "True", "valid": "True",
             "objective_value": str(v), "mechanical_power_W": str(400 + v), "impact_loss_W": str(8 - v)}
            for c, v in ((160.0, 0.49), (170.0, 0.50), (180.0, 0.51))]
    fig = map_figure(rows, "speed_mps", "cadence_spm")
    for ax, key in zip(fig.axes, PANELS):  # the panels (their colour bars follow)
        [squares] = ax.collections
        assert np.allclose(squares.get_offsets(), [[3.5, 160], [3.5, 170], [3.5, 180]])
        assert np.allclose(squares.get_array(), [float(r[key]) for r in rows])
    plt.close(fig)
