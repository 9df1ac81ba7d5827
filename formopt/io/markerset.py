"""Marker maps: which markers track each segment and which landmarks place its joint centres.

A marker map is a TOML file (shipped ones in io/markersets/, chosen with `--markers NAME|FILE`
or recognised from a trial's labels):

    name = "rbds"
    sides = { R = "R.", L = "L." }          # each side's label prefix
    [pelvis]
    cluster = ["R.ASIS", ...]               # full labels: at least three markers
    hip = "harrington"                      # or "landmark": [leg] hip names it
    asis = ["R.ASIS", "L.ASIS"]             # right then left (harrington only)
    psis = ["R.PSIS", "L.PSIS"]
    [leg]                                   # labels without the side prefix
    thigh, shank, foot = [...]              # tracking clusters; "@hip", "@knee", "@ankle" stand
                                            # for a joint centre carried by the segment above
    knee, ankle = [...]                     # landmarks averaged into the joint centre (standing
                                            # trial; they may be missing while running)
    hip = [...]                             # "landmark" hips
    heel, forefoot = [...]                  # optional; else from the foot's geometry

A cluster needs three points that do not lie on a line; a map is refused naming the key.
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass
from pathlib import Path

from ..mechanics.errors import InputError

SHIPPED = Path(__file__).parent / "markersets"
SIDES = ("R", "L")  # the sides a map names (its `sides` prefixes), right first
SEGMENTS = ("thigh", "shank", "foot")
JOINT_OF = {"thigh": "@hip", "shank": "@knee", "foot": "@ankle"}  # what each segment may borrow
# Without heel and toe markers (Winter 2009, Biomechanics and Motor Control of Human Movement,
# 4th ed., fig. 4.1: foot length 0.152 H): the heel lies 0.2 foot lengths behind the ankle
# centre, the metatarsal heads 0.75 foot lengths ahead of the heel, both at the height of the
# foot's lowest marker when standing.
FOOT_GEOMETRY = {"foot_length_per_height": 0.152, "heel_behind_ankle": 0.2, "forefoot_from_heel": 0.75}


@dataclass(frozen=True)
class MarkerSet:
    name: str
    title: str
    source: str  # the TOML file
    sides: dict  # {"R": prefix, "L": prefix}
    pelvis: tuple[str, ...]
    hip: str  # "harrington" or "landmark"
    asis: tuple[str, str] | None
    psis: tuple[str, str] | None
    leg: dict  # key -> tuple of unprefixed labels

    def label(self, side: str, name: str) -> str:
        """A full label ("R.Knee"); joint references ("@hip") stay as they are."""
        return name if name.startswith("@") else self.sides[side] + name

    def cluster(self, side: str, segment: str) -> tuple[str, ...]:
        return tuple(self.label(side, n) for n in self.leg[segment])

    def landmarks(self, side: str, key: str) -> tuple[str, ...]:
        return tuple(self.label(side, n) for n in self.leg.get(key, ()))

    def running(self) -> list[str]:
        """Labels a running trial must hold."""
        names = list(self.pelvis)
        for s in self.sides:
            names += [n for seg in SEGMENTS for n in self.cluster(s, seg) if not n.startswith("@")]
        return names

    def standing(self) -> list[str]:
        """Labels a standing trial must hold: the running ones and the landmarks."""
        names = self.running()
        for s in self.sides:
            for key in ("hip", "knee", "ankle", "heel", "forefoot"):
                names += [n for n in self.landmarks(s, key) if n not in names]
        return names


def load(name_or_file) -> MarkerSet:
    """A shipped map by name (rbds, plugin_gait, ric) or a TOML file."""
    path = Path(name_or_file)
    if not path.suffix:
        path = SHIPPED / f"{name_or_file}.toml"
        if not path.exists():
            raise InputError(f"--markers {name_or_file!r}: not a shipped marker map "
                             f"({', '.join(shipped())}) nor a file")
    try:
        data = tomllib.loads(path.read_text())
    except (OSError, tomllib.TOMLDecodeError) as err:
        raise InputError(f"{path}: not a readable marker map ({err})") from None
    return _parse(data, path)


def shipped() -> list[str]:
    return sorted(p.stem for p in SHIPPED.glob("*.toml"))


def _parse(data: dict, path: Path) -> MarkerSet:
    def need(table, key, where, kind=list):
        value = table.get(key)
        if not isinstance(value, kind) or (kind is list and not all(isinstance(v, str) for v in value)):
            raise InputError(f"{path}: {where}{key} must be "
                             f"{'a list of labels' if kind is list else 'a ' + kind.__name__}")
        return value

    known = {"name", "title", "sides", "pelvis", "leg"}
    unknown = set(data) - known
    if unknown:
        raise InputError(f"{path}: unknown key {sorted(unknown)[0]!r} (keys: {', '.join(sorted(known))})")
    sides = need(data, "sides", "", dict)
    if set(sides) != {"R", "L"}:
        raise InputError(f"{path}: sides must give the R and L label prefixes")
    pelvis = need(data, "pelvis", "", dict)
    leg = need(data, "leg", "", dict)
    cluster = need(pelvis, "cluster", "pelvis.")
    hip = pelvis.get("hip")
    if hip not in ("harrington", "landmark"):
        raise InputError(f"{path}: pelvis.hip must be \"harrington\" or \"landmark\", not {hip!r}")
    asis = psis = None
    if hip == "harrington":
        asis, psis = (tuple(need(pelvis, k, "pelvis.")) for k in ("asis", "psis"))
        if len(asis) != 2 or len(psis) != 2:
            raise InputError(f"{path}: pelvis.asis and pelvis.psis name the right then the left marker")
    elif "hip" not in leg:
        raise InputError(f"{path}: a \"landmark\" hip needs leg.hip")
    if len(cluster) < 3:
        raise InputError(f"{path}: pelvis.cluster needs at least three markers")
    parsed = {}
    for key in (*SEGMENTS, "knee", "ankle", "hip", "heel", "forefoot"):
        if key in leg:
            parsed[key] = tuple(need(leg, key, "leg."))
        elif key in (*SEGMENTS, "knee", "ankle"):
            raise InputError(f"{path}: leg.{key} is missing")
    unknown = set(leg) - set(parsed)
    if unknown:
        raise InputError(f"{path}: unknown key leg.{sorted(unknown)[0]}")
    for seg in SEGMENTS:
        refs = [n for n in parsed[seg] if n.startswith("@")]
        if any(r != JOINT_OF[seg] for r in refs) or len(parsed[seg]) < 3:
            raise InputError(f"{path}: leg.{seg} needs three points (markers, or {JOINT_OF[seg]})")
    if ("heel" in parsed) != ("forefoot" in parsed):
        raise InputError(f"{path}: leg.heel and leg.forefoot go together")
    return MarkerSet(data.get("name", path.stem), data.get("title", path.stem), str(path),
                     dict(sides), tuple(cluster), hip, asis, psis, parsed)


def recognise(labels) -> MarkerSet:
    """The shipped map whose running markers a trial's labels hold, or an error naming the
    closest map and what it misses."""
    labels = set(labels)
    best = None
    for name in shipped():
        ms = load(name)
        missing = [n for n in ms.running() if n not in labels]
        if not missing:
            return ms
        if best is None or len(missing) < len(best[1]):
            best = (ms, missing)
    ms, missing = best
    raise InputError(f"the markers match no shipped marker map: closest {ms.name}, which misses "
                     f"{', '.join(missing[:6])}{' ...' if len(missing) > 6 else ''}; "
                     f"give one with --markers FILE")
