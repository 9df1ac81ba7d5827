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

A cluster needs three different points, and a marker tracks one segment (a map is refused
naming the file and the key); that a cluster's points do not lie on a line is checked on the
standing trial.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from ..mechanics.errors import InputError
from . import validate as val

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
    """A shipped map by name (rbds, plugin_gait, ric) or a TOML file; an error names the file
    and the key (io.validate)."""
    path = Path(name_or_file)
    if not path.suffix:
        path = SHIPPED / f"{name_or_file}.toml"
        if not path.exists():
            raise InputError(f"--markers {name_or_file!r}: not a shipped marker map "
                             f"({', '.join(shipped())}) nor a file")
    data = val.read_toml(path, "a marker map")
    try:
        return _parse(data, path)
    except val.ValidationError as err:
        raise err.in_file(path) from None


def shipped() -> list[str]:
    return sorted(p.stem for p in SHIPPED.glob("*.toml"))


LEG_KEYS = (*SEGMENTS, "knee", "ankle", "hip", "heel", "forefoot")


def _parse(data: dict, path: Path) -> MarkerSet:
    """A marker map from its parsed TOML (the schema in the module's docstring)."""
    val.keys(data, "", {"name", "title", "sides", "pelvis", "leg"}, ("sides", "pelvis", "leg"))
    sides = val.table(data, "sides", {"R", "L"}, ("R", "L"))
    for side in sides:
        val.string(sides, side, "sides")
    pelvis = val.table(data, "pelvis", {"cluster", "hip", "asis", "psis"}, ("cluster", "hip"))
    leg = val.table(data, "leg", set(LEG_KEYS), (*SEGMENTS, "knee", "ankle"))
    cluster = val.labels(pelvis, "cluster", "pelvis", at_least=3, distinct=True)
    hip = val.choice(pelvis["hip"], "pelvis.hip", ("harrington", "landmark"))
    asis = psis = None
    if hip == "harrington":
        asis, psis = (val.labels(pelvis, k, "pelvis", at_least=2, distinct=True) for k in ("asis", "psis"))
        for key, pair in (("asis", asis), ("psis", psis)):
            if len(pair) != 2:
                raise val.ValidationError(f"pelvis.{key}", "names the right then the left marker: "
                                                           f"two labels, not {len(pair)}")
    elif "hip" not in leg:
        raise val.ValidationError("leg.hip", "missing: a \"landmark\" hip names its landmarks")
    parsed = {key: val.labels(leg, key, "leg", at_least=3 if key in SEGMENTS else 1,
                              distinct=key in SEGMENTS) for key in LEG_KEYS if key in leg}
    for seg in SEGMENTS:
        refs = [n for n in parsed[seg] if n.startswith("@") and n != JOINT_OF[seg]]
        if refs:
            raise val.ValidationError(f"leg.{seg}", f"{refs[0]!r}: a {seg} cluster may borrow only "
                                                    f"{JOINT_OF[seg]}, the joint centre above it")
    if ("heel" in parsed) != ("forefoot" in parsed):
        raise val.ValidationError("leg.heel", "leg.heel and leg.forefoot go together")
    _one_segment_each(cluster, sides, parsed)
    return MarkerSet(val.string(data, "name", "", path.stem), val.string(data, "title", "", path.stem),
                     str(path), dict(sides), cluster, hip, asis, psis, parsed)


def _one_segment_each(pelvis: tuple[str, ...], sides: dict, leg: dict) -> None:
    """A marker tracks one segment: two segments sharing a marker (a thigh cluster that is the
    shank's markers, both legs under one prefix) move as one and give no angle between them.
    ValidationError naming the second segment's key and the shared label."""
    owner = dict.fromkeys(pelvis, "pelvis.cluster")
    for side, prefix in sides.items():
        for seg in SEGMENTS:
            for label in (prefix + name for name in leg[seg] if not name.startswith("@")):
                if label in owner:
                    raise val.ValidationError(f"leg.{seg}", f"{label!r} (side {side}) is in {owner[label]} "
                                              "too: a marker tracks one segment (give each its own cluster)")
                owner[label] = f"leg.{seg} (side {side})"


def recognise(labels, source: str = "") -> MarkerSet:
    """The shipped map whose running markers a trial's labels hold, or an error naming the
    trial's file (`source`), the closest map and what it misses."""
    labels = set(labels)
    best = None
    for name in shipped():
        ms = load(name)
        missing = [n for n in ms.running() if n not in labels]
        if not missing:
            return ms
        if best is None or len(missing) < len(best[1]):
            best = (ms, missing)
    assert best is not None  # shipped() is never empty
    ms, missing = best
    where = f"{source}: " if source else ""
    raise InputError(f"{where}the markers match no shipped marker map: closest {ms.name}, which misses "
                     f"{', '.join(missing[:6])}{' ...' if len(missing) > 6 else ''}; "
                     f"give one with --markers FILE")
