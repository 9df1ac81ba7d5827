"""Studies composed of the layers below: measured against optimal, sweeps, the bench."""
