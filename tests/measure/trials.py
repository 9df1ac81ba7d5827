"""Where the real trials are (beside the repository) and the runners' statures."""

from helpers import DATA

RBDS, RIC = DATA / "rbds", DATA / "ric"
RUN35, STATIC = RBDS / "RBDS001runT35.c3d", RBDS / "RBDS001static.c3d"
RUN25, FORCES25 = RBDS / "RBDS001runT25markers.txt", RBDS / "RBDS001runT25forces.txt"
RIC_RUN, RIC_STATIC = RIC / "20160226T120637_run.c3d", RIC / "20160226T120637_static.c3d"
HEIGHT = 1.81  # m, RBDS001 (RBDSinfo.txt)
RIC_HEIGHT = 1.77  # m, the Running Injury Clinic runner
