"""The forward check's replays (checks.forward: CasADi's CVODES) against the figures scipy's
solve_ivp gave on the same solutions before it replaced it (DOP853 at rtol 1e-10 for the moments,
LSODA at 1e-8 for the excitations), pinned in forward_pins.npz by `python
benchmarks/forward_speed.py pin` (2026-11-27, on the scipy path): the paper's body at 3.5 m/s,
24-node heel, flat and forefoot strikes, a 40-node heel strike, a sliding forefoot strike
(Coulomb, mu 0.3), a Hermite-Simpson heel strike and a 14-node muscle-driven flat strike.
Measured differences: the phases' replays (reset_theta) 6e-9 rad or less, the open loop 1e-6
rad and 3e-4 in its rates and periodicity (the open loop amplifies every difference), the slip
3e-9 m/s."""

import gc
import json
import weakref
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pytest

from formopt.io.muscle_table import body_muscles
from formopt.mechanics.body import paper_body
from formopt.mechanics.joint_space import JointSpace
from formopt.optim.stride import StrideNLP, StrideSettings
from formopt.optim.stride.checks import forward, replayed

PINS = np.load(Path(__file__).with_name("forward_pins.npz"))
CASES = ["heel24", "heel40", "flat24", "forefoot24", "slide24", "hermite24", "muscles14"]


@pytest.fixture(scope="module")
def js():
    return JointSpace(paper_body())


def pinned(js, name: str):
    """(NLP, blocks, parameters, scipy's figures) of a pinned case."""
    meta = json.loads(str(PINS[f"{name}/meta"]))
    fields = dict(meta["fields"])
    if fields.pop("muscles", False):
        fields["muscles"] = body_muscles(paper_body())
    blocks = {k.split("/", 1)[1]: PINS[k] for k in PINS.files if k.startswith(f"{name}/") and not k.endswith("/meta")}
    return StrideNLP(js, StrideSettings(**fields)), blocks, meta["parameters"], meta["figures"]


@pytest.mark.parametrize("name", CASES)
def test_the_replays_reach_scipys_figures(js, name):
    """Each phase's replay (reset_theta, per phase) within 1e-7 rad of scipy's, the open loop
    within 1e-4 relative (theta, theta', the periodicity), the slip within 1e-7 m/s, the muscle
    stride's moments replayed within 1e-7 rad."""
    nlp, blocks, parameters, old = pinned(js, name)
    new = forward(nlp, blocks, parameters)
    assert new.keys() == old.keys()
    for key in ("reset_theta", "reset_per_phase", "moments_reset_theta", "moments_reset_per_phase"):
        if key in old:
            np.testing.assert_allclose(new[key], old[key], rtol=0, atol=1e-7, err_msg=key)
    for key in ("theta", "thetad", "per_phase_theta", "periodicity"):
        np.testing.assert_allclose(new[key], old[key], rtol=1e-4, atol=1e-7, err_msg=key)
    for key in (k for k in old if k.startswith("slip_")):
        assert new[key] == pytest.approx(old[key], abs=1e-7), key


def test_a_failed_integration_is_an_infinite_error(js):
    """Controls the right-hand side cannot take (NaN) in the second phase: its replay and the
    open loop from it fail, counted as infinite; the other phases' replays are unchanged."""
    nlp, blocks, parameters, old = pinned(js, "heel24")
    broken = {**blocks, f"U_{nlp.phases[1].name}": np.full_like(blocks[f"U_{nlp.phases[1].name}"], np.nan)}
    out = forward(nlp, broken, parameters)
    assert out["reset_per_phase"][1] == np.inf and out["periodicity"] == np.inf
    assert out["per_phase_theta"][1:] == [np.inf] * (len(nlp.phases) - 1)
    np.testing.assert_allclose(np.delete(out["reset_per_phase"], 1), np.delete(old["reset_per_phase"], 1), atol=1e-7)


def test_threads_share_an_nlp_safely(js):
    """Four threads forward-checking one NLP at once (a Dask worker's threads; collocation.build
    shares an NLP among them) get the figures one thread gets: each thread its own integrators
    (checks.replay; one CVODES integrator called by two threads at once crashed the process)."""
    nlp, blocks, parameters, _ = pinned(js, "slide24")
    alone = forward(nlp, blocks, parameters)
    with ThreadPoolExecutor(4) as pool:
        together = list(pool.map(lambda _: forward(nlp, blocks, parameters), range(8)))
    assert all(out == alone for out in together)


def test_an_nlps_replays_go_with_it(js):
    """The integrators kept per NLP (checks.replay) do not keep it alive."""
    nlp, blocks, parameters, _ = pinned(js, "heel24")
    forward(nlp, blocks, parameters)
    gone = weakref.ref(nlp)
    del nlp
    gc.collect()
    assert gone() is None


def test_a_muscle_replay_out_of_the_muscles_domain_is_quiet(js, capfd):
    """Activations below zero (NaN in the Hill equilibrium's Jacobian at Newton's steps,
    mechanics.muscles.tendon_force_rate) replay without the rootfinder's evaluation warnings
    (13,748 lines of stderr for this start, as many under scipy's LSODA before); tendon forces
    of 1e6 F_max, where Newton does not converge, fail the replay (None), CasADi's dump of the
    failing call's inputs its one print (26 lines)."""
    nlp, blocks, parameters, _ = pinned(js, "muscles14")
    name = nlp.phases[1].name
    x, z = blocks[f"X_{name}"][:, 0], blocks[f"Z_{name}"][:, 0]
    capfd.readouterr()
    assert replayed(nlp, 1, blocks, parameters, True, np.r_[x, z - 5.0]) is not None
    assert capfd.readouterr().err == ""
    assert replayed(nlp, 1, blocks, parameters, True, np.r_[x, z * 1e6]) is None
    assert len(capfd.readouterr().err.splitlines()) < 100
