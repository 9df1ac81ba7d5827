"""A stride solved again on a finer mesh from itself (issue 34 item 2: N against 2N nodes), and
the record of what that moved (`MeshCheck`).

`refined`: the stride's node histories interpolated onto the other mesh at both meshes' node
times (guess.fitted), solved there from them (local.optimum, its touchdown mode decided again
under Coulomb) at the stride's own speed, slope, friction and imposed cadence. The muscles from
IPOPT's barrier at ipopt_options.MUSCLE_WARM_START (3e-4), which keeps the iterate near the stride
it starts from: from their cold solves' 1e-2 the heel stride at 2.5 m/s went from 152.9
steps/min at 40 nodes to another optimum at 80 (170.2, 6 % costlier; from 3e-4: 148.0,
problems/muscle_mesh.py). The torque rungs with the NLP's own options, as problems/stride_mesh.py
always solved its finer meshes. A muscle stride directly, IPOPT stopped at its first restoration
phase, and where that fails by continuation in its activation rates' smoothing (`continued`: at
scale 0 first, then at the settings' from there), which reaches the stride where the direct solve
stalls. `mesh_check`: the stride on 2N nodes, everything else the same
(grading and transcription kept), and its `MeshCheck`; its own figures stay the N-node stride's.
"""

from __future__ import annotations

import time
from dataclasses import asdict, dataclass

from ...mechanics.errors import InputError
from .collocation import StrideNLP
from .guess import fitted
from .ipopt_options import MUSCLE_WARM_START
from .layout import Solved
from .local import best_of, optimum
from .ranges import RANGES
from .result import Stride

# Issue 34 item 2: a reported stride's cost and cadence change by less than 1 % from N to 2N nodes
MESH_TOLERANCE_PCT = 1.0
# IPOPT stops at its first restoration phase: a muscle stride's direct try (`refined`). The
# option is read only in a restoration phase, so a solve that meets none is the same bit for bit;
# a stopped one returns IPOPT's "Maximum_Iterations_Exceeded" (success False) before max_iter
DIRECT_TRY = {"max_resto_iter": 0}


@dataclass(frozen=True)
class MeshCheck:
    """What solving a stride again on twice its nodes from itself moved (`mesh_check`): each pair
    (N-node stride, 2N-node stride); the rest the 2N-node solve's."""

    nodes: tuple[int, int]  # collocation intervals over the half stride
    cadence_spm: tuple[float, float]
    objective_value: tuple[float, float]  # the scene's objective (per distance)
    # the touchdown's mode ("stick" or "slide", Stride.impacts): under Coulomb each mesh decides
    # its own (local.touchdown_mode), and a sliding stride's 2N solve starts from its sticking phases
    touchdown: tuple[str, str]
    valid: bool  # the 2N-node stride's (Stride.valid)
    failed_checks: tuple[str, ...]  # the 2N-node stride's (Stride.failed_checks)
    success: bool  # IPOPT converged on 2N nodes
    status: str  # IPOPT's return status
    iterations: int  # the 2N-node solves' (a `continued` muscle stride's tries too)
    cpu_s: float  # s of CPU (time.process_time): the 2N-node NLP's build, solve and checks
    coarse_valid: bool = True  # the N-node stride's own (Stride.valid): invalid, it is no answer to converge
    continued: bool = False  # a muscle stride's direct try stopped at a restoration: solved by `continued`
    mesh: str = "nodes"  # what `nodes` counts, in words: "nodes" (trapezoid) or "intervals" (Hermite-Simpson)

    @property
    def cadence_change_pct(self) -> float:
        """100 (c_2N - c_N) / c_N."""
        return _change(self.cadence_spm)

    @property
    def objective_change_pct(self) -> float:
        """100 (J_2N - J_N) / |J_N|."""
        return _change(self.objective_value)

    @property
    def measured(self) -> bool:
        """Both strides valid and the 2N-node one converged by IPOPT: the changes measure the mesh."""
        return self.success and self.valid and self.coarse_valid

    @property
    def converged(self) -> bool:
        """`measured`, and both changes under MESH_TOLERANCE_PCT."""
        return (self.measured and abs(self.cadence_change_pct) < MESH_TOLERANCE_PCT
                and abs(self.objective_change_pct) < MESH_TOLERANCE_PCT)

    def to_dict(self) -> dict:
        """JSON-ready: the fields, the changes (%), `converged` and the tolerance (%)."""
        return {**asdict(self), "cadence_change_pct": self.cadence_change_pct,
                "objective_change_pct": self.objective_change_pct, "converged": self.converged,
                "tolerance_pct": MESH_TOLERANCE_PCT}

    def text(self) -> str:
        """What was measured, in one sentence (the stride table's mesh note)."""
        n, fine = self.nodes
        unit = self.mesh.removesuffix("s")  # "40-node stride", "40-interval stride"
        solved = f"{fine} {self.mesh}, solved from this {n}-{unit} stride,"
        if not self.success:
            return f"{solved} did not converge (IPOPT: {self.status}): nothing measured"
        moved = (f"{solved} move the cadence {self.cadence_change_pct:+.2f} % "
                 f"and the cost {self.objective_change_pct:+.2f} %")
        verdict = (f"converged within {MESH_TOLERANCE_PCT:g} %" if self.converged else
                   f"the {n}-{unit} stride itself is invalid" if not self.coarse_valid else
                   f"the {fine}-{unit} stride is invalid ({'; '.join(self.failed_checks)})" if not self.valid else
                   f"not converged at {MESH_TOLERANCE_PCT:g} %")
        a, b = ({"stick": "sticking", "slide": "sliding"}[mode] for mode in self.touchdown)
        modes = "" if a == b else f"; the touchdown {a} on {n} {self.mesh}, {b} on {fine}"
        path = "; solved by continuation (unsmoothed first: the direct solve met a restoration)" if self.continued else ""
        return f"{moved}: {verdict}{modes}{path}"


def _tries(stride: Stride) -> int:
    """The iterations of a `continued` stride's tries before its own solve (0 for another)."""
    tried = stride.checks.get("continuation", {})
    return tried.get("direct_iterations", 0) + tried.get("unsmoothed_iterations", 0)


def _change(pair: tuple[float, float]) -> float:
    """100 (b - a) / |a| of a pair (a, b)."""
    a, b = pair
    return 100.0 * (b - a) / abs(a)


def warm_options(nlp: StrideNLP) -> dict:
    """IPOPT options over `nlp`'s for a solve from a neighbouring stride: the muscles' barrier
    from MUSCLE_WARM_START unless the NLP's own options set one (module docstring); none for
    the torque rungs."""
    if nlp.settings.muscles is None or "mu_init" in (nlp.ipopt or {}):
        return {}
    return dict(MUSCLE_WARM_START)


def refined(nlp: StrideNLP, stride: Stride, source: StrideNLP | None = None, simulate: bool = True,
            continuation: bool = True) -> Stride:
    """`stride` solved again on `nlp` (e.g. its settings on twice the nodes) from itself, at its
    own parameters (module docstring); `source`: an NLP of the stride's transcription and grading
    (default `nlp`'s), whose node times its histories are read at (guess.fitted); `simulate`:
    the forward check. A muscle stride (its activation rates' smoothing > 0) is tried directly
    with IPOPT stopped at its first restoration phase (DIRECT_TRY) and, where that fails,
    `continued`; `continuation` False: the direct solve alone, to its end (a measurement's:
    problems/muscle_mesh.py --direct)."""
    if stride.solved is None:
        raise ValueError("refined: the stride has no solution to start from")
    options = warm_options(nlp)
    nlp = nlp.variant(options) if options else nlp
    par = stride.solved.parameters
    guess = fitted(nlp, stride.solved.blocks, source)
    if not (continuation and nlp.settings.muscles is not None and nlp.settings.activation_rate_smoothing > 0):
        return optimum(nlp, par["speed"], par["slope"], par["mu"], par["cadence"], guess=guess, simulate=simulate)
    direct = nlp.variant(DIRECT_TRY).solve(guess, par["speed"], par["slope"], par["mu"], par["cadence"])
    # converged: summarised as `optimum` would (local.best_of), the touchdown's mode decided under
    # Coulomb with `nlp`'s own options (a sliding solve stopped at a restoration is no answer)
    return best_of(nlp, [direct], simulate) if direct.success else continued(nlp, guess, par, direct, simulate)


def continued(nlp: StrideNLP, guess: dict, parameters: dict, direct: Solved, simulate: bool = True) -> Stride:
    """A muscle stride's refinement where its direct try (`direct`, from `guess`) failed: `guess`
    solved with StrideSettings.activation_rate_smoothing 0 first, then on `nlp` from that solve
    where it converged (else from `guess`); both tries' iterations and status in its
    checks["continuation"].

    Why (docs/concepts/muscles.md, "The refinement's continuation", has the table and commands):
    the forefoot's graded 160-node solves stall directly and converge so in 107-114 s of CPU;
    where the direct solve converges it meets no restoration, and continuing there too gave the
    same strides at 1.3-2.0 times the CPU: so the continuation only after a restoration."""
    p = parameters
    first = nlp.variant(activation_rate_smoothing=0.0).solve(guess, p["speed"], p["slope"], p["mu"], p["cadence"])
    fine = optimum(nlp, p["speed"], p["slope"], p["mu"], p["cadence"],
                   guess=first.blocks if first.success else guess, simulate=simulate)
    fine.checks["continuation"] = {"direct_iterations": direct.iterations, "direct_status": direct.status,
                                   "unsmoothed_iterations": first.iterations, "unsmoothed_status": first.status}
    return fine


def fine_nodes(nodes: int) -> int:
    """2N, the nodes a stride of N is checked on (`mesh_check`); InputError, before any solve,
    where 2N is past the stride's node range (ranges.RANGES)."""
    high = int(RANGES["nodes"].high)
    if 2 * nodes > high:
        raise InputError(f"mesh check: nodes = {nodes} would be checked on {2 * nodes}, past the stride's "
                         f"{high}: check a mesh of at most {high // 2} nodes")
    return 2 * nodes


def mesh_check(nlp: StrideNLP, stride: Stride, simulate: bool = True) -> MeshCheck:
    """`stride` (solved on `nlp`) solved again on twice its nodes from itself (`refined`; its
    forward check with `simulate`, as the stride's own) and what that moved."""
    clock = time.process_time()
    nodes = (nlp.settings.nodes, fine_nodes(nlp.settings.nodes))
    # the warm barrier in the 2N NLP's own options, so that `refined` builds no second variant of it
    fine = refined(nlp.variant(warm_options(nlp), nodes=nodes[1]), stride, nlp, simulate)
    return MeshCheck(nodes=nodes,
                     cadence_spm=(stride.cadence_spm, fine.cadence_spm),
                     objective_value=(stride.objective_value, fine.objective_value),
                     touchdown=(stride.impacts[-1]["mode"], fine.impacts[-1]["mode"]),
                     valid=fine.valid, failed_checks=tuple(fine.failed_checks), success=fine.success,
                     status=fine.status, iterations=fine.iterations + _tries(fine),
                     cpu_s=time.process_time() - clock,
                     coarse_valid=stride.valid, continued="continuation" in fine.checks,
                     mesh="intervals" if nlp.settings.transcription == "hermite-simpson" else "nodes")

