"""compare's stride section (studies.compare_stride, issue 27 item 3): the band's words, the
what-if arithmetic, and one cheap run (18 nodes, the nominal variant only) checked against
independent readings: the imposed cadence against 60 / half-period, per-joint work against the
budget's W+ and W-, the JSON and the table's words."""

from dataclasses import replace
from types import SimpleNamespace

import numpy as np
import pytest

from formopt import load
from formopt.mechanics.body import scaled_body
from formopt.optim.stride import summarise
from formopt.optim.stride.notes import RUNNER_MESH, mesh_note
from formopt.optim.stride.problem import RUNNER_ANKLE
from formopt.report.figures import stride_cadence_figure
from formopt.report.tables import stride_lines
from formopt.studies import compare_band, compare_stride
from formopt.studies.compare_band import Variant, stage_count, stage_shares
from formopt.studies.compare_notes import (
    ENVELOPE,
    HERMITE_NOTE,
    MESH_MOVE_W,
    mesh_what_if_note,
    optima_notes,
    section_notes,
)
from formopt.studies.compare_stride import (
    WHAT_IF_PCT,
    Curve,
    WhatIf,
    answer,
    band_curves,
    band_points,
    family,
    what_ifs,
)
from formopt.studies.pool import Background
from formopt.studies.stride_form import STRIDE_MODEL, STRIDE_MODELS, joint_work, model_of, stride_scene
from formopt.studies.stride_map import warm


def test_a_change_inside_its_band_is_not_advised():
    inside = WhatIf(5.0, 180.0, -2.0, 1.0, -4.0, 1.5, -1.0, 2.0)
    assert not inside.resolvable and inside.words() == "no change the model can resolve"
    assert WhatIf(5.0, 180.0, -2.0, 1.0, -4.0, -0.5, 0, 2).words() == "saves power"
    assert WhatIf(-5.0, 160.0, 3.0, 1.0, 0.5, 4.0, 0, 2).words() == "costs more"


def test_what_ifs_span_every_converged_variant():
    """Changes against the first cadence (the runner's); the band the least and most change."""
    def curve(name, power, impact, ok=True):
        strides = [SimpleNamespace(mechanical_power_W=p, budget={"impacts_J": i}, half_period_s=1.0)
                   for p, i in zip(power, impact)]
        return Curve(name, [170.0, 153.0, 161.5, 178.5, 187.0], None, strides, "" if ok else "failed")

    cadences = [170.0, 153.0, 161.5, 178.5, 187.0]
    got = what_ifs([curve("nominal", [100, 110, 104, 98, 97], [20, 15, 18, 22, 24]),
                    curve("other", [200, 205, 203, 199, 201], [30, 29, 30, 31, 31]),
                    curve("broken", [0, 1e6, 0, 0, 0], [0, 0, 0, 0, 0], ok=False)], cadences)
    assert [w.cadence_change_pct for w in got] == list(WHAT_IF_PCT)
    plus10 = got[-1]
    assert plus10.mechanical_power_change_W == -3 and (plus10.low_W, plus10.high_W) == (-3, 1)
    assert plus10.impact_loss_change_W == 4 and (plus10.impact_low_W, plus10.impact_high_W) == (1, 4)
    assert got[0].low_W == 5 and got[0].resolvable  # -10 %: +10 W and +5 W, the broken one out


def _curve(name, power, part="", objective=None):
    strides = [SimpleNamespace(mechanical_power_W=p, budget={"impacts_J": 1.0}, half_period_s=1.0,
                               objective_value=o, success=True, valid=True, on_bound=[], held=[], cadence_spm=c)
               for p, o, c in zip(power, objective or power, [170.0, 153.0, 161.5, 178.5, 187.0])]
    return Curve(name, [170.0, 153.0, 161.5, 178.5, 187.0], None, strides, part=part)


def test_what_ifs_within_the_meshs_move_of_zero_are_named():
    """The what-ifs whose change lies within MESH_MOVE_W of zero (what 60 nodes moved the shipped
    runners' changes) are named: their words may turn on a finer mesh; none, no note."""
    curve = _curve("nominal", [100, 100 - MESH_MOVE_W - 1, 104, 110, 100 + MESH_MOVE_W + 1])
    assert mesh_what_if_note(curve).startswith("the what-ifs at -5 % (162 steps/min), +5 % (178 steps/min) change "
                                               "the model's power by less than 20 W")
    assert mesh_what_if_note(_curve("nominal", [100, 50, 70, 130, 160])) == ""
    assert mesh_what_if_note(Curve("nominal", curve.cadences, why_not="no convergence")) == ""
    curve.free = SimpleNamespace(objective_value=80.0, cadence_spm=170.0, success=True, valid=True, held=[])
    band = [curve, _curve("friction 1", [100, 110, 104, 98, 97], "friction")]
    for nodes, how, law, curves, said in ((30, "trapezoid", "coulomb", band, True),
                                          (30, "trapezoid", "no-slip", band, False),
                                          (24, "trapezoid", "coulomb", band, False),
                                          (30, "hermite-simpson", "coulomb", band, False),
                                          (30, "trapezoid", "coulomb", band[:1], False)):
        scene = stride_scene(scaled_body(62.0, 1.81), 3.5, "heel", law=law, nodes=nodes, transcription=how,
                             model="quick")
        notes = section_notes(curves, {}, 170.0, scene)  # said only where MESH_MOVE_W was measured
        assert any(n.startswith("the what-ifs at -5 %") for n in notes) is said
        assert (HERMITE_NOTE in notes) is said
    for other in (stride_scene(scaled_body(62.0, 1.81), 3.5, "heel", law="coulomb", tendons=RUNNER_ANKLE, model="quick"),
                  stride_scene(scaled_body(62.0, 1.81), 3.5, "heel", law="coulomb", model="scenes")):
        notes = section_notes(band, {}, 170.0, other)  # another model
        assert not {HERMITE_NOTE, mesh_what_if_note(curve)} & set(notes)
    assert mesh_note(other.settings) in notes and RUNNER_MESH in notes[0]  # the scenes': their own mesh's


def test_the_scenes_model_is_formopt_strides():
    """stride_model "scenes" builds the torque scenes' stride (formopt/scenes/stride_rbds001.toml's
    settings but for the strike, objective and law compare gives), the default; the quick model
    beside it; model_of names either, and nothing for a mesh of its own."""
    body = scaled_body(62.0, 1.81)
    shipped = load("stride_rbds001").settings
    scenes = stride_scene(body, 3.5, "heel", law="coulomb", model="scenes").settings
    keys = ("nodes", "transcription", "tendons", "impact_weight", "approach_speed", "moment_time", "max_iter")
    assert {k: getattr(scenes, k) for k in keys} == {k: getattr(shipped, k) for k in keys}
    assert model_of(scenes) == "scenes" and model_of(stride_scene(body, 3.5, "heel").settings) == STRIDE_MODEL == "scenes"
    assert model_of(stride_scene(body, 3.5, "heel", nodes=18).settings) is None
    assert model_of(stride_scene(body, 3.5, "heel", model="quick").settings) == "quick"
    assert model_of(stride_scene(body, 3.5, "heel", model="scenes", transcription="trapezoid").settings) is None
    assert model_of(stride_scene(body, 3.5, "heel", model="scenes", tendons={"knee": 0.0, "ankle": 4.0}).settings) == "scenes"


def test_the_band_names_each_part_with_its_own_width():
    """Each part's width is the span of the change over the nominal and that part's variants;
    the shares divide the parts' summed widths."""
    got = what_ifs([_curve("nominal", [100, 110, 104, 98, 97]),
                    _curve("friction 0.6", [100, 112, 104, 98, 97], "friction"),
                    _curve("friction 1", [100, 109, 104, 98, 97], "friction"),
                    _curve("metabolic", [200, 216, 203, 199, 201], "objective"),
                    _curve("mass +5 %", [105, 115, 109, 103, 102], "body")], [170.0, 153.0, 161.5, 178.5, 187.0])
    minus10 = got[0]  # changes: nominal +10, friction +12 and +9, objective +16, body +10
    assert dict(minus10.parts) == {"friction": 3.0, "objective": 6.0, "body": 0.0}
    assert minus10.shares() == {"friction": 1 / 3, "objective": 2 / 3, "body": 0.0}
    assert (minus10.low_W, minus10.high_W) == (9, 16) and minus10.same_family
    assert minus10.to_dict()["band_shares"]["objective"] == pytest.approx(2 / 3)


def test_a_what_if_between_two_families_and_a_free_optimum_off_the_envelope_are_said():
    nominal = _curve("nominal", [100, 110, 104, 98, 97], objective=[1.0, 1.2, 1.1, 0.95, 0.97])
    nominal.family_gap = [0.0, None, 0.0, 0.05, 0.0]  # 153: no continuation; 178.5: a costlier one
    nominal.free = SimpleNamespace(objective_value=1.0, cadence_spm=170.0, success=True, valid=True,
                                   held=[{"variable": "knee_R rate", "side": "high", "bound": 15.0,
                                          "unit": "rad/s", "phases": ["heel"], "nodes": 1}])
    nominal.strides[4].on_bound = [{"phase": "flat"}]
    nominal.strides[4].bound_text = lambda: "flat phase 30.0 ms on its low bound (30 ms)"
    got = what_ifs([nominal], nominal.cadences)
    assert [w.same_family for w in got] == [False, True, False, True]
    notes = " ".join(optima_notes(nominal))
    assert "at 153, 178 steps/min the least costly stride found is of another family" in notes
    assert nominal.envelope_gap == pytest.approx(0.05) and nominal.envelope_gap > ENVELOPE
    assert "the free optimum lies 5.0 % above the least costly imposed stride" in notes
    assert "the stride at 187 steps/min: flat phase 30.0 ms on its low bound" in notes
    nominal.strides[1].on_bound, nominal.strides[1].bound_text = nominal.strides[4].on_bound, nominal.strides[4].bound_text
    assert "the strides at 153, 187 steps/min: flat phase 30.0 ms on its low bound" in " ".join(optima_notes(nominal))
    nominal.strides[1].on_bound = []
    nominal.strides[2].held = nominal.free.held
    assert optima_notes(nominal)[-1] == ("the solve's bounds hold the stride at 162 steps/min (each stride's "
                                         "`held` in the JSON; the optimum's are printed under it)")


def test_a_variant_off_its_envelope_is_said():
    """A band variant whose free optimum lies above one of its imposed strides by more than
    ENVELOPE is named: its strides are local optima (one warm solve each)."""
    nominal, metabolic = _curve("nominal", [100, 110, 104, 98, 97]), _curve("metabolic", [200, 216, 203, 199, 201],
                                                                          "objective", [0.17, 0.18, 0.17, 0.15, 0.2])
    nominal.free = SimpleNamespace(objective_value=97.0, cadence_spm=187.0, success=True, valid=True, held=[])
    metabolic.free = SimpleNamespace(objective_value=0.18, success=True)
    scene = stride_scene(scaled_body(62.0, 1.81), 3.5, "heel", nodes=24, model="quick")
    said = [n for n in section_notes([nominal, metabolic], {}, 170.0, scene) if n.startswith("metabolic")]
    assert said == ["metabolic: its free optimum lies 16.7 % above its least costly imposed stride (tolerance 0.1 %): "
                    "its strides, each one solve warm from the nominal's, are local optima, and its part of the band "
                    "measures which ones as much as the variant"]
    metabolic.free.objective_value = 0.15  # on its envelope: nothing said
    assert not [n for n in section_notes([nominal, metabolic], {}, 170.0, scene) if n.startswith("metabolic")]


def _failed_own_free():
    """Stands for the sticking strides' own free optimum where IPOPT did not converge."""
    return SimpleNamespace(success=False, valid=False, status="Maximum_Iterations_Exceeded", cadence_spm=150.0,
                           mechanical_power_W=999.0, objective_value=0.5, budget={"impacts_J": 9.0},
                           half_period_s=0.4)


def test_a_failed_sticking_free_optimum_is_no_reference(monkeypatch):
    """The free optimum slides, the imposed strides stick and their own free optimum failed: no
    envelope is measured, no cadence is called their optimum, and the family and the band's
    variants start from the least costly imposed stride (review8)."""
    nominal = _curve("nominal", [100, 110, 104, 98, 97], objective=[1.0, 1.2, 1.1, 0.95, 0.97])
    nominal.free = SimpleNamespace(objective_value=0.8, cadence_spm=143.0, success=True, valid=True, held=[],
                                   slides=["forefoot impact of leg L solved sliding under coulomb"])
    nominal.own_free = _failed_own_free()
    least = nominal.strides[3]  # 178.5 steps/min, objective 0.95
    assert nominal.envelope_free is least and nominal.envelope_gap is None
    notes = " ".join(optima_notes(nominal))
    assert ("the imposed cadences are solved sticking, and their own free optimum, solved warm from the least "
            "costly of them, did not converge (IPOPT: Maximum_Iterations_Exceeded): no sticking optimum and no "
            "envelope; the family and the band's variants start from that least costly stride (178 steps/min, "
            "98 W), which is no optimum") in notes
    assert "150 steps/min" not in notes and "above the least costly" not in notes
    monkeypatch.setattr(compare_band, "stride_at", _solved)
    variant, = band_curves(nominal, [Variant("friction 0.6", "friction", "mu")], Background(1), [].append)
    assert variant.free.starts == (nominal.free, least)
    starts = []
    monkeypatch.setattr(compare_stride, "warm", lambda nlp, start, *values: starts.append(start) or start)
    monkeypatch.setattr(compare_stride, "summarise", lambda nlp, solved, simulate: solved)
    family(SimpleNamespace(nlp=lambda: None, slope=0.0, friction=0.6), 3.5, nominal)
    assert starts[0] is least  # the continuation begins at it


def _solved(task):
    """Stands for compare_band.stride_at: which scene, from which starts, at which cadence."""
    scene, starts, cadence = task
    start = starts[0]
    return SimpleNamespace(scene=scene, start=start, starts=starts, success=True,
                           cadence_spm=cadence or start.cadence_spm)


def test_the_band_is_solved_longest_first_and_kept_in_its_order(monkeypatch):
    """band_curves: every variant's solves (compare_band.start_band: the free optimum, then
    each cadence) as tasks on two processes, the objective's first (LONGEST_FIRST); each curve
    assembled from its own solves, in the variants' order, each told once."""
    monkeypatch.setattr(compare_band, "stride_at", _solved)
    cadences = [170.0, 153.0, 187.0]
    nominal = Curve("effort (nominal)", cadences, free=SimpleNamespace(cadence_spm=165.0),
                    strides=[SimpleNamespace(cadence_spm=c) for c in cadences])
    variants = [Variant("friction 0.6", "friction", "mu"), Variant("metabolic", "objective", "met"),
                Variant("legs' mass +5 %", "body", "legs")]
    for workers in (1, 2):
        told: list[str] = []
        with Background(workers) as pool:
            curves = band_curves(nominal, variants, pool, told.append)
        assert told == ["variant metabolic done", "variant legs' mass +5 % done", "variant friction 0.6 done"]
        assert [(c.name, c.part) for c in curves] == [(n, p) for n, p, _ in variants]
        for curve, (_, _, scene) in zip(curves, variants):
            assert curve.ok and curve.free.scene == scene and curve.free.cadence_spm == 165.0
            assert curve.free.starts == (nominal.free, nominal.free)  # no sticking twin: the free optimum
            assert [s.scene for s in curve.strides] == [scene] * 3
            assert [s.cadence_spm for s in curve.strides] == cadences
            assert [s.starts for s in curve.strides] == [(s,) for s in nominal.strides]
    with Background(2) as pool:  # the free optima started before (beside the family): the same curves
        early = band_curves(nominal, variants, pool, [].append,
                            compare_band.start_band(variants, band_points(nominal)[:1], pool))
    assert [(c.free.starts, [s.starts for s in c.strides]) for c in early] == \
        [(c.free.starts, [s.starts for s in c.strides]) for c in curves]
    sticking = SimpleNamespace(cadence_spm=163.0, success=True)
    curves = band_curves(replace(nominal, own_free=sticking), variants, Background(1), [].append)
    assert all(c.free.starts == (nominal.free, sticking) for c in curves)


def test_the_band_starts_its_free_optima_beside_the_family_only_when_their_starts_are_known(monkeypatch):
    """compare_stride.answer: the band's free optima start before the family (beside it) from
    the nominal's free optima; where the sticking free optimum failed, their start is the least
    costly imposed stride, which the family may replace: they start after it, from its stride."""
    events = []
    start_band = compare_stride.start_band
    monkeypatch.setattr(compare_stride, "start_band", lambda *a: events.append("band") or start_band(*a))
    monkeypatch.setattr(compare_band, "stride_at", _solved)
    monkeypatch.setattr(compare_stride, "measured_form", lambda c: {"cadence_spm": 170.0, "strike": "heel"})
    monkeypatch.setattr(compare_stride, "stride_scene", lambda *a, **k: SimpleNamespace(
        nlp=lambda: SimpleNamespace(solver=None), settings=SimpleNamespace(nodes=18, transcription="trapezoid")))
    monkeypatch.setattr(compare_stride, "band_variants", lambda scene, body: [Variant("friction 0.6", "friction", "mu")])
    monkeypatch.setattr(compare_stride, "strike_tasks", lambda scene, speed, strikes: [(type, s, "") for s in strikes])
    checked: list = []  # the strides handed to the forward check: the converged free optima only
    monkeypatch.setattr(compare_stride, "check_tasks",
                        lambda scene, strides: checked.append(strides) or [(lambda s: s, s, "") for s in strides])
    monkeypatch.setattr(compare_stride, "section_notes", lambda *a: [])
    monkeypatch.setattr(compare_stride, "what_ifs", lambda *a: [])
    cheaper = SimpleNamespace(objective_value=0.9, success=True, valid=True, cadence_spm=178.5)

    def family(scene, speed, curve):
        events.append("family")
        curve.strides[3] = cheaper  # a continuation better than the curve's stride replaces it

    monkeypatch.setattr(compare_stride, "family", family)
    c = SimpleNamespace(steps=SimpleNamespace(speed=3.5), settings={"body": {"mass_kg": 62.0, "height_m": 1.81, "sex": "male"},
                                                         "friction": 0.8}, law="no-slip")
    sticking = SimpleNamespace(success=True, cadence_spm=163.0)
    for own, first, after in ((sticking, "band", ("band", "family", "band")),
                              (_failed_own_free(), cheaper, ("family", "band", "band"))):
        nominal = _curve("nominal", [100, 110, 104, 98, 97], objective=[1.0, 1.2, 1.1, 0.95, 0.97])
        nominal.free, nominal.own_free = SimpleNamespace(cadence_spm=165.0, success=True), own
        monkeypatch.setattr(compare_stride, "run_curve", lambda *a, curve=nominal: curve)
        events.clear()
        variant = answer(c, workers=1).curves[1]
        assert tuple(events) == after
        assert variant.free.starts == (nominal.free, own if first == "band" else cheaper)
        assert checked[-1] == ([nominal.free, own] if own.success else [nominal.free]) and nominal.own_free is own


def test_a_variant_starts_from_the_first_solution_of_its_own_nlp(monkeypatch):
    """compare_band.stride_at: warm (with multipliers) from the first start converged on the
    variant's NLP (its layout: the nominal's sticking free optimum where the nominal's slides),
    else from the first start's primal values (another objective's NLP, or the sticking twin
    failed)."""
    seen = []
    monkeypatch.setattr(compare_band, "warm", lambda nlp, start, *values: seen.append((start, values)) or start)
    monkeypatch.setattr(compare_band, "summarise", lambda nlp, solved, simulate: solved)
    scene = SimpleNamespace(nlp=lambda: SimpleNamespace(layout="sticking"), speed=3.5, slope=0.0, friction=0.6)
    sliding = SimpleNamespace(success=True, solved=SimpleNamespace(layout="sliding"))
    sticking = SimpleNamespace(success=True, solved=SimpleNamespace(layout="sticking"))
    failed = SimpleNamespace(success=False, solved=SimpleNamespace(layout="sticking"))
    unsolved = SimpleNamespace(success=True, solved=None)
    assert compare_band.stride_at((scene, (sliding, sticking), None)) is sticking
    assert compare_band.stride_at((scene, (sticking, sliding), 170.0)) is sticking
    assert compare_band.stride_at((scene, (sliding, failed), None)) is sliding  # a failed twin: no start
    assert compare_band.stride_at((scene, (sliding, unsolved), None)) is sliding
    assert compare_band.stride_at((scene, (unsolved, sliding), None)) is unsolved
    assert [values for _, values in seen] == [(3.5, 0.0, 0.6, None), (3.5, 0.0, 0.6, 170.0)] + [(3.5, 0.0, 0.6, None)] * 3


def test_each_stage_told_has_its_share_of_the_time():
    """The progress bar's shares (io.progress.Stages), each stride model's: one per stage told,
    the band's first variant's wait the longest of the band's."""
    for model in STRIDE_MODELS:
        for band in (True, False):
            shares = stage_shares(band, model)
            assert len(shares) == stage_count(band) and min(shares) >= 0
        shares = stage_shares(model=model)
        assert sum(shares) == pytest.approx(1.0) and shares[4] == max(shares[4:])


CHANGES = (-5.0, 5.0)  # the section's what-ifs, two of WHAT_IF_PCT's four (the time: 3 cadences, not 5)


@pytest.fixture(scope="module")
def section():
    """The section for a runner like RBDS001 at 3.5 m/s (heel), nominal variant, 18 nodes,
    no-slip impacts (Coulomb's sliding variant has tests of its own, optim/test_stride_slide.py;
    here it would only add a second NLP: 7.8 s against 13.7 s)."""
    side = SimpleNamespace(side="R", point="heel", steps=[0, 1])
    tds = [SimpleNamespace(hip_from_point={"heel": (x, 0.9), "forefoot": (x - 0.2, 0.9)}) for x in (-0.16, -0.18)]
    c = SimpleNamespace(steps=SimpleNamespace(speed=3.5, cadence_spm=171.4, touchdowns=tds), main_side=side,
                        settings={"body": {"mass_kg": 62.0, "height_m": 1.81, "sex": "male"},
                                  "friction": 0.8}, law="no-slip", measurement=knee_flexing(171.4))
    return answer(c, nodes=18, band=False, changes=CHANGES, model="quick")


def knee_flexing(cadence: float):
    """A measurement's stand-in whose right knee flexes to 40 deg at 14 % of each of 3 cycles
    (measure.stance_knee_deg reads its kinematics and touchdowns)."""
    cycle = 120.0 / cadence
    t = np.linspace(0.0, 3 * cycle, 601)
    knee = np.radians(25.0 + 15.0 * np.sin(2 * np.pi * (t % cycle) / cycle / 0.56))
    steps = SimpleNamespace(cadence_spm=cadence, valid=[SimpleNamespace(side="R", time=k * cycle) for k in range(4)])
    angles = {"R.thigh": knee, "R.shank": 0 * t, "R.foot": 0 * t, "trunk": 0 * t}
    return SimpleNamespace(steps=steps, kinematics=SimpleNamespace(t=t, angles=angles))


def test_the_section_against_its_own_strides(section):
    s = section
    nominal = s.nominal
    assert nominal.ok, nominal.why_not
    runner = 171.4
    for stride, cadence in zip(nominal.strides, nominal.cadences):
        assert stride.success and stride.cadence_spm == pytest.approx(cadence, rel=1e-6)
        assert 60.0 / stride.half_period_s == pytest.approx(cadence, rel=1e-6)
    assert nominal.cadences == pytest.approx([runner * (1 + p / 100) for p in (0, *CHANGES)])
    work = joint_work(nominal.free)
    joints = [k for k in work if not k.startswith("stance_")]
    budget = nominal.free.budget  # the same trapezoidal rule, summed joint by joint
    assert sum(work[j]["positive_J"] for j in joints) == pytest.approx(budget["positive_work_J"], rel=1e-9)
    assert sum(work[j]["negative_J"] for j in joints) == pytest.approx(budget["negative_work_J"], rel=1e-9)
    for j in ("hip", "knee", "ankle"):
        assert 0 <= work[f"stance_{j}"]["negative_J"] <= work[f"{j}_R"]["negative_J"] + 1e-12
    # the envelope: the free optimum is the curve's least; the family walked from it
    assert nominal.envelope_gap <= ENVELOPE and nominal.own_free is None  # no-slip: no sliding free optimum
    assert len(nominal.family_gap) == len(nominal.cadences)
    # without the band, every band is the nominal change itself
    for w in s.what_if:
        assert w.low_W == w.high_W == w.mechanical_power_change_W


def test_total_mass_scales_the_power_and_the_legs_share_moves_the_stride(section):
    """Why the band varies the legs' share of the mass and not the total (LEG_MASS_BAND): the
    stride's dynamics are nearly homogeneous in mass (only the passive joint moments are not
    scaled), so +5 % of mass is about +5 % of power at nearly the same cadence, while the legs'
    mass +-5 % (the total kept) moves the power and the cadence."""
    free = section.nominal.free

    def warm_on(body):
        nlp = stride_scene(body, 3.5, "heel", nodes=18, model="quick").nlp()
        stride = summarise(nlp, warm(nlp, free, 3.5, 0.0, 0.8, None), False)
        assert stride.success
        return stride.mechanical_power_W / free.mechanical_power_W, stride.cadence_spm / free.cadence_spm

    power, cadence = warm_on(scaled_body(62.0 * 1.05, 1.81))
    assert 1.04 < power < 1.07 and cadence == pytest.approx(1.0, abs=5e-3)  # 1.057 and 0.998
    lighter, heavier = warm_on(scaled_body(62.0, 1.81, legs=0.95)), warm_on(scaled_body(62.0, 1.81, legs=1.05))
    assert lighter[0] < 0.99 < 1.01 < heavier[0] and heavier[1] < 1.0 < lighter[1]  # 0.976 / 1.023, 1.008 / 0.992
    total = [sum(seg.mass for seg in scaled_body(62.0, 1.81, legs=f).segments.values()) for f in (0.95, 1.0)]
    assert total[0] == pytest.approx(total[1], rel=1e-12)


def test_the_section_json_and_words(section):
    d = section.to_dict()
    assert d["measured_cadence_spm"] == 171.4 and d["measured_strike"] == "heel"
    assert d["measured_placement_m"] == pytest.approx(0.17)
    assert d["measured_step_length_m"] == pytest.approx(3.5 * 60 / 171.4)
    assert d["measured_stance_knee_deg"] == pytest.approx(40.0, abs=0.1)  # knee_flexing's
    assert d["optimum_stance_knee_deg"] == section.nominal.free.stance_knee_deg
    assert d["optimum_cadence_spm"] == pytest.approx(section.nominal.free.cadence_spm)
    assert [w["cadence_change_pct"] for w in d["what_if"]] == list(CHANGES)
    for w in d["what_if"]:
        assert set(w) >= {"cadence_change_pct", "mechanical_power_change_W", "impact_loss_change_W",
                          "low_W", "high_W"}
        assert np.isfinite([w["low_W"], w["high_W"]]).all()
    assert d["best_strike"] == "heel" and d["strikes"]["forefoot"] is None  # band=False: one strike
    text = "\n".join(stride_lines(d))
    assert "the runner:  cadence  171.4" in text and "heel strike, stance knee 40 deg" in text
    assert "(trapezoid at 18 intervals, no-slip impacts" in text and d["transcription"] == "trapezoid"
    assert d["model"] is None  # 18 nodes: neither of stride_form.STRIDE_MODELS
    assert "(model quick: trapezoid at 30 intervals" in "\n".join(stride_lines({**d, "model": "quick", "nodes": 30}))
    assert f"stance knee {d['optimum_stance_knee_deg']:.0f} deg; mechanical power" in text
    assert all(f"{p:+5.0f} %" in text for p in CHANGES)


def test_the_optimum_line_carries_its_remarks(section):
    """A free optimum held by a bound or sliding says so under its own line, and the sticking
    strides' own optimum is named where the what-ifs are measured from it."""
    d = {**section.to_dict(), "optimum_remarks": ["forefoot impact of leg L solved sliding under coulomb: it "
                                                  "slides 28 ms and 5.1 cm"],
         "sticking_optimum_cadence_spm": 167.0, "sticking_optimum_mechanical_power_W": 275.0}
    lines = stride_lines(d)
    k = next(i for i, line in enumerate(lines) if line.startswith("    the optimum"))
    assert lines[k + 1] == "      (forefoot impact of leg L solved sliding under coulomb: it slides 28 ms and 5.1 cm)"
    assert "the sticking strides' optimum (the what-ifs' reference): cadence  167.0" in lines[k + 2]


def test_the_free_optimum_is_forward_checked_and_an_invalid_strike_says_why(section):
    """compare's free optimum carries the forward check (optim.stride.forward_checked), and a
    strike whose free optimum fails a check names it where the strikes are listed."""
    assert "forward_theta" in section.nominal.free.checks
    d = section.to_dict()
    assert d["strikes"]["heel"]["failed_checks"] == section.nominal.free.failed_checks
    d["strikes"]["flat"] = {**d["strikes"]["heel"], "valid": False, "failed_checks": ["forward_theta 0.291 > 0.1"]}
    assert "(INVALID: forward_theta 0.291 > 0.1)" in "\n".join(stride_lines(d))


def test_a_failed_sticking_free_optimum_reads_as_failed(section):
    """The JSON, the table and the figure of a section whose sticking strides' own free
    optimum did not converge: its status, no cadence of it, no envelope gap."""
    nominal = replace(section.nominal, own_free=_failed_own_free())
    d = replace(section, curves=[nominal, *section.curves[1:]]).to_dict()
    assert d["sticking_optimum_status"] == "Maximum_Iterations_Exceeded"
    assert d["sticking_optimum_cadence_spm"] is d["sticking_optimum_mechanical_power_W"] is None
    curve = d["curves"][0]
    assert curve["own_free_status"] == "Maximum_Iterations_Exceeded" and curve["envelope_gap"] is None
    assert curve["own_free_cadence_spm"] is curve["own_free_mechanical_power_W"] is None
    assert "sticking strides' optimum" not in "\n".join(stride_lines(d))
    power = stride_cadence_figure(d).axes[0]
    line = next(ln for ln in power.lines if ln.get_marker() == "o")
    assert sorted(line.get_xdata()) == sorted(nominal.cadences)  # through no free optimum
    assert section.to_dict()["sticking_optimum_status"] is None  # no-slip: none solved
