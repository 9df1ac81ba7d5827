"""The public API: a scene in, a checked result out.

    scene = formopt.load("demo")        # a shipped scene's name (formopt.scenes()) or a path
    formopt.impact(scene)      # ImpactResult: the indicators of the scene's touchdown
    formopt.simulate(scene)    # Landing: the finite motion from touchdown to both points down
    formopt.solve(scene)       # Optimum: the posture of the [optimize] table
    formopt.sweep(scene, [("ankle_deg", values)], "out/sweep.csv")   # a list of row dicts
    formopt.compare("run.c3d", "static.c3d", mass=62.0, height=1.81, friction=0.8)

Each goes through the scene's factories (formopt.io.scene.Scene), so every [numerics] option
reaches it. Results are dataclasses.
"""

from __future__ import annotations

import re
from os import PathLike
from pathlib import Path

from .io import mocap
from .io.scene import Scene, SceneError, landing_scene
from .io.scene import load as load_file
from .io.stride_scene import StrideScene
from .mechanics.impact import ImpactResult
from .mechanics.landing import Landing, simulate_state
from .optim.solution import Optimum
from .studies import compare as studies_compare
from .studies.stride import StrideStudy
from .studies.stride import run as run_stride
from .studies.sweep import run as sweep

__all__ = ["load", "scenes", "scene_path", "impact", "simulate", "solve", "sweep", "compare", "stride"]

SCENES = Path(__file__).resolve().parent / "scenes"  # the shipped scenes (package data)


def scenes() -> dict[str, str]:
    """The shipped scenes: {name: the first sentence of its header comment, at most 100
    characters}."""
    def title(path: Path) -> str:
        lines = path.read_text().splitlines()
        header = " ".join(line.lstrip("# ").strip() for line in
                          lines[:next((k for k, line in enumerate(lines) if not line.startswith("#")),
                                      len(lines))])
        first = re.split(r"(?<!et al)\. ", header)[0].rstrip(".")  # "Fukuchi et al. 2017" is one sentence
        return first if len(first) <= 100 else first[:99].rstrip() + "…"
    return {p.stem: title(p) for p in sorted(SCENES.glob("*.toml"))}


def scene_path(scene: str | PathLike) -> Path:
    """The file of `scene`: a path as given when it is a file, else a shipped scene's name
    (`demo` or `demo.toml`); SceneError naming the shipped names otherwise."""
    path = Path(scene)
    if path.is_file() or path.parent != Path("."):
        return path
    shipped = SCENES / f"{path.stem}.toml"
    if path.suffix in ("", ".toml") and shipped.exists():
        return shipped
    raise SceneError("", f"{scene}: no such file, and not a shipped scene "
                         f"({', '.join(scenes())}; `formopt scenes` lists them)")


def load(scene: str | PathLike) -> Scene | StrideScene:
    """Read and validate a scene: a TOML file, or a shipped scene by name (`load("demo")`).

    Parameters
    ----------
    scene : str or path-like
        A scene file, or the name of a shipped scene (`formopt.scenes()` lists them).

    Returns
    -------
    Scene or StrideScene
        The typed SI scene with its factories (impact, landing, posture problem; a stride
        scene's NLP).
    """
    return load_file(scene_path(scene))


def compare(trial, static, mass: float, height: float, forces=None,
            **settings) -> studies_compare.Comparison:
    """A measured runner against the optimum for their body (formopt.studies.compare.compare).

    Parameters
    ----------
    trial, static : str, path-like or formopt.io.mocap.Trial
        The running trial (C3D, or RBDS marker text) and the standing calibration trial; a
        path is read with `formopt.io.mocap.read`.
    mass, height : float
        The runner's mass (kg) and stature (m).
    forces : str or path-like, optional
        The force text file of a text trial (RBDS layout).
    **settings
        The keyword arguments of `formopt.studies.compare.compare` (sex, friction, law, ...).

    Returns
    -------
    Comparison
        The measured touchdowns, their impacts and the gait-anchored optimum.
    """
    def read(t, extra=None):
        return t if isinstance(t, mocap.Trial) else mocap.read(t, extra)
    return studies_compare.compare(read(trial, forces), read(static), mass, height, **settings)


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
    scene = landing_scene(scene, "impact")
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
    scene = landing_scene(scene, "simulate")
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
    return landing_scene(scene, "solve").posture_problem(**overrides).solve(progress)


def stride(scene, speed: float | None = None, strike: str | None = None,
           progress=None) -> StrideStudy:
    """The periodic running half stride of a stride scene ([stride] table; issue 23).

    Parameters
    ----------
    scene : StrideScene
        A loaded stride scene (`formopt.load` of a file with a [stride] table).
    speed : float, optional
        m/s, instead of the scene's `speed_mps`.
    strike : str, optional
        "heel", "forefoot", "flat" or "best" (each solved), instead of the scene's.
    progress : callable, optional
        `progress(text)` before each strike is solved.

    Returns
    -------
    StrideStudy
        The strides, the best first (`best`: valid before invalid, then the least costly;
        optim.stride.rank), each a `Stride` with `valid`, `failed_checks`, cadence, step,
        phases, ground force, energy budget (J) and checks (with the scene's `mesh_check`, its
        `mesh_check`: what solving it again on twice its nodes moved, optim.stride.refine);
        `to_dict()` is JSON-ready.
    """
    return run_stride(scene, speed, strike, progress=progress)
