"""Input and output at the boundary: scene files, motion capture, atomic output files."""
