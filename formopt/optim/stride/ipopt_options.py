"""IPOPT's options for the stride NLP (collocation.StrideNLP): the defaults, each rung's own, the
muscles' continuation's and the warm start's, each beside what it was measured to do."""

from __future__ import annotations

from .problem import StrideSettings

# MUMPS with 100 % room over its estimated workspace (IPOPT's default, 1000 %, mapped a 77 MB
# block afresh at each factorisation of the muscles' KKT matrix: 256,000 page faults and 1.3-4.4 s
# of system time in 40 iterations of the muscles' solve below, against 6,500 and 0.06 s; 100 %
# stays on the heap). The iterates are the same (the torque rung's bit for bit:
# benchmarks/stride_speed.py --same).
IPOPT_DEFAULTS = {"print_level": 0, "sb": "yes", "mu_strategy": "adaptive",
                  "nlp_scaling_method": "gradient-based", "linear_solver": "mumps", "mumps_mem_percent": 100}
# The muscles' NLP with IPOPT's adaptive barrier: the barrier rose to 1e5 and the dual
# infeasibility to 1e13 in 100 iterations (RBDS001, heel, 40 nodes, from the torque rung's
# optimum); with a monotone barrier from 0.01 it converges (24 nodes: 270 iterations).
# MUMPS's ordering METIS instead of its own choice (PORD here) factorises the muscles' KKT matrix
# (5,064 variables, 4,299 rows) faster: 40 iterations of the solve at reserve weight 10000 from
# the one at 100 (RBDS001, heel, 40 nodes, 3.5 m/s, one BLAS thread) 2.53 instead of 3.71 s of
# user CPU, the same optima to round-off (5.161650, 177.81 steps/min, 2026-11-26: before the
# activations' rates joined the smoothing, 177.67 since). Not for the torque rungs:
# no faster on their 3,027 rows (docs/reference/performance.md), and its round-off moved RBDS001's
# torque optimum at 3.5 m/s to another local one (217.2 -> 188.7 steps/min).
MUSCLE_IPOPT = {"mu_strategy": "monotone", "mu_init": 1e-2, "mumps_pivot_order": 5}
# The torque rungs on Hermite-Simpson with the constraints' block of IPOPT's KKT matrix perturbed
# at every iteration (perturb_always_cd; by default only where IPOPT finds the matrix singular,
# which MUMPS's pivoting may not report: IPOPT then raised the Hessian's perturbation up to 1e11-
# 1e14 at most iterations, a factorisation for each try). RBDS001 (62 kg, 1.81 m, 3.5 m/s, the
# torque scenes' stride without moment dynamics: problem.RUNNER_ANKLE), 40 intervals, the
# multi-start's 4 starts per strike: without it one flat-strike start took 367 iterations and 430 s
# of CPU (the others 2-22 s), with it every start 2.4-18 s and the same optima within 1e-5; with
# moment dynamics (12 ms) the
# heel strike from the generic start in 97 iterations and 4.9 s instead of 342 and 19.7 s, and on
# 40 intervals from that stride 41 iterations and 2.5 s instead of 619 and 63 s, to a 0.09 %
# lower optimum (2026-11-28; docs/concepts/stride.md, "The torque scenes on Hermite-Simpson").
TORQUE_HERMITE_IPOPT = {"perturb_always_cd": "yes"}
# The muscles' start's solves at a lower reserve weight (local.muscle_start) from a barrier of 1e-3:
# from the torque+springs optimum at weight 100, RBDS001 (heel, 40 nodes) at 2.5 / 3.5 / 4.5 m/s,
# 325 / 191 / 370 iterations instead of 369 / 299 / 448, the same optima (2.24417, 3.99212,
# 6.40699), and the solve at 10000 from them the same (3.01449, 5.16165, 9.99639). The solve at
# 10000 stays at 1e-2: from 1e-3 it ended elsewhere at 2.5 m/s (184.9 instead of 172.0 steps/min).
CONTINUATION_IPOPT = {"mu_init": 1e-3}
# IPOPT's warm start from a neighbouring solution's primal and dual values (StrideNLP.resolve):
# the barrier starts small and decreases monotonically. Along a cadence chain (paper body, 30
# nodes, tendons, 165-180 steps/min at 3.5 m/s) 12-20 iterations instead of 43-52, the same
# optima to IPOPT's tolerance (benchmarks/stride_sweep_speed.py measures the map). The
# complementarity to 1e-8 (IPOPT's compl_inf_tol, 1e-4 by default): with it at 1e-4 the monotone
# barrier stopped about 2e-5 (relative) above the optimum, even resolved at the optimum's own
# parameters (RBDS001 T25, 40 nodes, forefoot, 2.54 m/s: compare's "other starts' optima"
# 1.7-2.1e-5 costlier were this), with it within 3e-7 of a cold solve's; compare's 34 warm solves
# a section took T25 555 -> 575, T35 458 -> 533, RIC 513 -> 692 iterations. IPOPT's adaptive
# barrier instead also ended there, but left the branch it started on (RBDS001 RIC's family at
# 164 steps/min, 0.24 % costlier; 2026-11-27).
WARM_START = {"warm_start_init_point": "yes", "mu_strategy": "monotone", "mu_init": 1e-5,
              "warm_start_bound_push": 1e-6, "warm_start_mult_bound_push": 1e-6,
              "warm_start_slack_bound_push": 1e-6, "compl_inf_tol": 1e-8}
# The muscles' warm start from a barrier of 3e-4: RBDS001 (heel, 40 nodes) 0.1 m/s faster from
# the optimum at 2.5 / 3.5 / 4.5 m/s in 32 / 28 / 31 iterations instead of 23 / 56 / 173 from
# 1e-5 (1e-4: 23 / 27 / 113; 1e-3: 38 / 33 / 31), the same optima (3.17067, 5.47877, 10.75843).
MUSCLE_WARM_START = {"mu_init": 3e-4, "compl_inf_tol": 1e-4}  # IPOPT's default (WARM_START's 1e-8 not tried here)


def rung_options(settings: StrideSettings) -> dict:
    """IPOPT's options for a stride NLP of `settings`: IPOPT_DEFAULTS, with MUSCLE_IPOPT over them
    for the muscles and TORQUE_HERMITE_IPOPT for the torque rungs on Hermite-Simpson."""
    own = MUSCLE_IPOPT if settings.muscles is not None else \
        TORQUE_HERMITE_IPOPT if settings.transcription == "hermite-simpson" else {}
    return {**IPOPT_DEFAULTS, **own}
