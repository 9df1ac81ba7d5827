"""The public API: a scene in, a checked result out.

    scene = formopt.load("problems/demo.toml")
    formopt.impact(scene)      # ImpactResult: the indicators of the scene's touchdown
    formopt.simulate(scene)    # Landing: the finite motion from touchdown to both points down
    formopt.solve(scene)       # Optimum: the posture of the [optimize] table
    formopt.sweep(scene, [("ankle_deg", values)], "out/sweep.csv")
    formopt.compare(trial, static, mass=62.0, height=1.81)

Each goes through the scene's factories (formopt.io.scene.Scene), so every [numerics] option
reaches it. Results are dataclasses with `to_dict()` (JSON-ready).
"""

from __future__ import annotations

from .io.scene import Scene, load
from .mechanics.impact import ImpactResult
from .mechanics.landing import Landing, simulate_state
from .optim.solution import Optimum
from .studies.compare import compare
from .studies.stride import StrideStudy
from .studies.stride import run as run_stride
from .studies.sweep import run as sweep

__all__ = ["load", "impact", "simulate", "solve", "sweep", "compare", "stride"]


def impact(scene: Scene) -> ImpactResult:
    """The checked impact indicators of the scene's touchdown.

    Parameters
    ----------
    scene : Scene
        A loaded scene (`formopt.load`).

    Returns
    -------
    ImpactResult
        Energies (J), impulses (N s), critical friction, velocity changes (m/s), validity.
    """
    return scene.impact()(scene.state)


def simulate(scene: Scene) -> Landing:
    """The landing from the scene's touchdown: impacts, contact phase, energy bookkeeping.

    Parameters
    ----------
    scene : Scene
        A scene whose model has a foot (not "effective-mass"); [joints] and [landing] apply.

    Returns
    -------
    Landing
        Time histories (s, m, m/s, J, N), impact events and the checks of its assumptions.
    """
    return simulate_state(scene.landing(), scene.strike, scene.state, scene.friction,
                          scene.integration.dt, scene.integration.duration)


def solve(scene: Scene, progress=None, **overrides) -> Optimum:
    """Optimise the touchdown posture of a scene with an [optimize] table.

    Parameters
    ----------
    scene : Scene
        The scene; its [optimize] table says the variables, bounds, objective, constraints.
    progress : callable, optional
        `progress(k, n, start)` after each start of the multi-start.
    **overrides
        Fields of the scene's Problem to replace (starts, seed, tolerance, ...); None keeps.

    Returns
    -------
    Optimum
        `success` is False unless a start converged (IPOPT's status is kept); the state (SI),
        its checked impact, what holds it (active constraints with multipliers).
    """
    return scene.posture_problem(**overrides).solve(progress)


def stride(scene, speed: float | None = None, strike: str | None = None) -> StrideStudy:
    """The periodic running half stride of a stride scene ([stride] table; issue 23).

    Parameters
    ----------
    scene : StrideScene
        A loaded stride scene (`formopt.load` of a file with a [stride] table).
    speed : float, optional
        m/s, instead of the scene's `speed_mps`.
    strike : str, optional
        "heel", "forefoot", "flat" or "best" (each solved), instead of the scene's.

    Returns
    -------
    StrideStudy
        The strides, the least costly first (`best`), each a `Stride` with cadence, step,
        phases, ground force, energy budget (J) and checks; `to_dict()` is JSON-ready.
    """
    return run_stride(scene, speed, strike)
