"""What compare's stride section says beside its numbers (studies.compare_stride): the nominal
curve's optima (other starts' costlier optima, a free optimum found again from an imposed stride,
a sliding free optimum and its sticking strides' own, the envelope, the families, invalid strides
and bounds), the band's variants off their own envelope, a free optimum far from the runner, the
strikes' validity and the mesh."""

from __future__ import annotations

from typing import TYPE_CHECKING

from ..optim.stride import Stride
from ..optim.stride.notes import mesh_note
from .stride_form import NODES, model_of

if TYPE_CHECKING:
    from .compare_stride import Curve

# a free optimum this far from the runner's cadence (fraction) is beyond the cadences runners
# choose around their own (de Ruiter 2020: optimal 171 +- 8 against preferred 165 +- 8)
FAR = 0.2
# other starts' optima this much costlier (fraction) than the one kept are named in the notes
SPREAD_NOTE = 0.01
# What the mesh did to the section's what-ifs (problems/compare_mesh.py on the three shipped runners,
# Coulomb, each curve stride solved again on 60 nodes as the band's strides are, sticking: each
# change moved 1.3-19.2 W and kept its sign, all but one inside their bands; docs/howto/compare.md,
# 2026-11-28): a change within this of zero may turn on a finer mesh
MESH_MOVE_W = 20.0  # W
# What a mesh-converged transcription says of the same curves (problems/compare_mesh.py
# --transcription hermite-simpson --nodes 24 48 on the three shipped runners: its objective moved
# 0.1-1.5 % from 24 to 48 intervals, its changes 0.1-5.6 W), and the torque scenes' model on it
# (the section run with that model, 40 intervals: 8 of 12 verdicts other; docs/howto/compare.md,
# "Hermite-Simpson under the what-ifs", 2026-11-28)
HERMITE_NOTE = ("on the three shipped runners, Hermite-Simpson at 24 intervals (mesh-converged within 1.5 %) "
                "turned one what-if of twelve, and the torque scenes' model (formopt stride's, stride_model "
                "'scenes', the default: mesh-converged, 5-10 times slower) eight: read the verdicts as this "
                "preview's "
                "(docs/howto/compare.md, 'Two stride models')")
# the envelope: the free optimum's objective at most this (relative) above the least imposed
# stride's; IPOPT's optima are exact to about 1e-6, so a larger gap is another local optimum
ENVELOPE = 1e-3


def mesh_what_if_note(curve: Curve) -> str:
    """The nominal's what-ifs whose change of mechanical power lies within MESH_MOVE_W of zero,
    whose verdict a finer mesh may turn (the band does not hold the mesh), in words ("" when
    none or no curve)."""
    if not curve.ok:
        return ""
    power, runner = curve.power(), curve.cadences[0]
    near = [f"{(c / runner - 1) * 100:+.0f} % ({c:.0f} steps/min)"
            for c, p in zip(curve.cadences[1:], power[1:]) if abs(p - power[0]) < MESH_MOVE_W]
    if not near:
        return ""
    return (f"the what-ifs at {', '.join(near)} change the model's power by less than {MESH_MOVE_W:g} W, about "
            f"what {2 * NODES} nodes moved the three shipped runners' changes from the section's {NODES}, and the band does not "
            "hold the mesh: their verdicts may turn on a finer mesh (docs/howto/compare.md, 'The mesh under the "
            "what-ifs')")


def optima_notes(curve: Curve) -> list[str]:
    """Where other starts ended in costlier local optima, a free optimum found again from an
    imposed cadence's stride, a sliding free optimum, the envelope, the families, invalid
    strides, and the strides on a phase's duration bound (one note per bound) or held by the
    solve's bounds, in words."""
    notes = [f"at {c:.0f} steps/min other starts reached local optima up to {f * 100:.0f} % costlier "
             "(the least costly is used)" for c, f in zip(curve.cadences, curve.spread) if f > SPREAD_NOTE]
    if curve.free_from != "free":
        notes.append(f"the free optimum was found again from the stride at {curve.free_from} steps/min "
                     "(the generic guess's was a costlier local optimum)")
    if curve.own_free is not None and curve.free is not None:
        notes.append(sticking_note(curve.free, curve.own_free, curve.envelope_free))
    gap = curve.envelope_gap
    if gap is not None and gap > ENVELOPE:
        notes.append(f"the free optimum lies {gap * 100:.1f} % above the least costly imposed "
                     f"stride (tolerance {ENVELOPE * 100:g} %): it is a local optimum, not the curve's least")
    others = [f"{c:.0f}" for c, same in zip(curve.cadences, curve.same_family) if not same]
    if curve.family_gap and others:
        notes.append(f"at {', '.join(others)} steps/min the least costly stride found is of another family than "
                     "the free optimum's (continued from it, the stride is costlier or does not converge): "
                     "a what-if between two families says so")
    free = [s for s in (curve.free, curve.own_free) if s is not None]
    invalid = [s for s in free + curve.strides if s.success and not s.valid]
    notes += [f"the stride at {s.cadence_spm:.0f} steps/min is INVALID ({'; '.join(s.failed_checks)}): "
              "read what it says as the model's, not a runner's" for s in invalid]
    bound: dict[str, list[float]] = {}  # one note per bound text, its strides' cadences
    for s in curve.strides:
        if s.on_bound:
            bound.setdefault(s.bound_text(), []).append(s.cadence_spm)
    notes += [f"{_strides(c)}: {text}" for text, c in bound.items()]
    held = [s.cadence_spm for s in curve.strides if s.held]
    if held:
        notes.append(f"the solve's bounds hold {_strides(held)} (each stride's `held` in the JSON; the "
                     "optimum's are printed under it)")
    return notes


def _strides(cadences: list[float]) -> str:
    """"the stride at 171 steps/min", or "the strides at 154, 163 steps/min" (rising)."""
    many = len(cadences) > 1
    return f"the stride{'s' if many else ''} at {', '.join(f'{c:.0f}' for c in sorted(cadences))} steps/min"


def sticking_note(free: Stride, own: Stride, start: Stride | None) -> str:
    """The free optimum slides and the imposed strides stick: their own free optimum `own`, or
    that it did not converge (IPOPT's status) and that the family and the band start from
    `start` (Curve.envelope_free: the least costly imposed stride) instead."""
    said = f"the free optimum's touchdown slides ({'; '.join(free.slides)}); the imposed cadences are solved sticking"
    if own.success:
        return (said + f": their own free optimum is at {own.cadence_spm:.0f} steps/min, "
                f"{own.mechanical_power_W:.0f} W, and the envelope and what-ifs are theirs")
    where = "" if start is None else f" ({start.cadence_spm:.0f} steps/min, {start.mechanical_power_W:.0f} W)"
    return (said + f", and their own free optimum, solved warm from the least costly of them, did not converge "
            f"(IPOPT: {own.status}): no sticking optimum and no envelope; the family and the band's variants "
            f"start from that least costly stride{where}, which is no optimum, and the what-ifs are between "
            "the sticking strides")


def variant_envelope_note(name: str, gap: float) -> str:
    """A band variant (`name`) whose free optimum lies `gap` (relative, Curve.envelope_gap) above
    one of its imposed strides, more than ENVELOPE: each of its strides is one solve warm from
    the nominal's (variant_curve), so a local optimum, and its part of the band measures which
    one as much as the variant. (The
    metabolic variant on RBDS001 T35 and T25: +8.5 % and +51 %, its objectives moving up to
    2-fold under other IPOPT barriers from the same starts: benchmarks/primal_start_options.py,
    2026-11-27.)"""
    return (f"{name}: its free optimum lies {gap * 100:.1f} % above its least costly "
            f"imposed stride (tolerance {ENVELOPE * 100:g} %): its strides, each one solve warm from the "
            "nominal's, are local optima, and its part of the band measures which ones as much as the variant")


def section_notes(curves: list[Curve], best: dict, runner: float, nominal) -> list[str]:
    """The section's notes on the mesh, the nominal's optima, the band's left-out variants and
    those off their envelope, a free optimum far from the runner and the strikes' validity."""
    # MESH_MOVE_W and HERMITE_NOTE were measured on the quick model, under Coulomb, with its band
    settings = nominal.settings
    measured = model_of(settings) == "quick" and settings.law == "coulomb" and len(curves) > 1
    near = [mesh_what_if_note(curves[0]), HERMITE_NOTE] if measured else []
    notes = [mesh_note(settings), *filter(None, near), *optima_notes(curves[0])]
    if not curves[0].ok:
        notes.append(f"the nominal stride did not converge ({curves[0].why_not}): no what-if")
    notes += [f"{cv.name} left out of the band: {cv.why_not}" for cv in curves[1:] if not cv.ok]
    notes += [variant_envelope_note(cv.name, gap) for cv in curves[1:]
              if cv.ok and (gap := cv.envelope_gap) is not None and gap > ENVELOPE]
    if curves[0].free is not None and abs(curves[0].free.cadence_spm / runner - 1) > FAR:
        notes.append(f"the model's free optimum ({curves[0].free.cadence_spm:.0f} steps/min) is "
                     f"{(curves[0].free.cadence_spm / runner - 1) * 100:+.0f} % from the runner's cadence: "
                     "read the what-if as the slope of the cost at the runner's cadence, not as a target")
    solved = [s for s in best.values() if s is not None]
    if solved and not any(s.valid for s in solved):
        notes.append("no strike's free optimum is valid (" + "; ".join(
            f"{s.strike}: {', '.join(s.failed_checks) or s.status}" for s in solved) + "): no best strike")
    return notes
