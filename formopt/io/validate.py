"""One validation vocabulary for every file formopt reads: scenes, compare scenes, marker maps.

Each check either returns the value (as the type the caller needs, SI where it converts) or
raises a ValidationError naming the file, the key (`touchdown.angles_deg.knee`, `[[trial]] 2.
bounds`), the value and the allowed range, on one line; an unknown key or choice is answered
with the closest spelling (difflib). Ranges come from mechanics.limits.
"""

from __future__ import annotations

import difflib
import math
import tomllib
from pathlib import Path

from ..mechanics.errors import InputError, one_line
from ..mechanics.limits import RANGE_OF_MOTION_DEG, Range

MAX_TOML_BYTES = 1_000_000  # a scene or marker map is a page of text; larger is a mistake


class ValidationError(InputError):
    """A value a file cannot hold: `key` names it, `source` the file (both may be empty)."""

    def __init__(self, key: str, message: str, source: str = ""):
        self.key, self.source, self.reason = one_line(key), str(source), one_line(message, 400)
        text = f"{self.key}: {self.reason}" if key else self.reason
        super().__init__(f"{one_line(source, 200)}: {text}" if source else text)

    def in_file(self, source) -> ValidationError:
        """The same error, naming the file it came from."""
        return ValidationError(self.key, self.reason, str(source))


def short(value, limit: int = 60) -> str:
    """A value as it appears in an error: its repr, one line, at most `limit` characters."""
    return one_line(repr(value), limit)


def read_toml(path, what: str) -> dict:
    """The parsed TOML of `path` (`what` it should be: "a scene", "a marker map"), or one line
    saying why not: unreadable, too large, not UTF-8 (UTF-16, binary), not TOML, too deep."""
    path = Path(path)
    try:
        size = path.stat().st_size
        if size > MAX_TOML_BYTES:
            raise ValidationError("", f"is {size / 1e6:.1f} MB: {what} is TOML text of at most "
                                      f"{MAX_TOML_BYTES // 1000} kB", path)
        text = path.read_text(encoding="utf-8")
    except OSError as err:
        raise ValidationError("", f"cannot read: {err.strerror}", path) from None
    except UnicodeDecodeError as err:
        raise ValidationError("", f"not UTF-8 text (byte {err.start}): {what} is a TOML file",
                              path) from None
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as err:
        raise ValidationError("", f"is not valid TOML: {err}", path) from None
    except RecursionError:
        raise ValidationError("", f"values nested too deeply to be {what}", path) from None


def _full(where: str, key: str) -> str:
    return f"{where}.{key}" if where else key


def keys(data: dict, where: str, allowed, required=()) -> None:
    """Refuse a key of `data` not in `allowed` (with the closest spelling) and a missing
    `required` one (checked in the order given)."""
    for key in data:
        if key not in allowed:
            close = difflib.get_close_matches(str(key), sorted(allowed), n=1)
            hint = f" (did you mean {close[0]!r}?)" if close else \
                f" (expected one of: {', '.join(sorted(allowed))})"
            raise ValidationError(_full(where, key), f"unknown key {short(key)}{hint}")
    for key in required if isinstance(required, tuple) else sorted(required):
        if key not in data:
            raise ValidationError(_full(where, key), "missing")


def table(data: dict, key: str, allowed, required=(), where: str = "") -> dict:
    """data[key], which must be a table with only `allowed` keys and every `required` one."""
    full = _full(where, key)
    value = data.get(key)
    if not isinstance(value, dict):
        raise ValidationError(full, "missing" if value is None else
                              f"must be a table, not {type(value).__name__} {short(value)}")
    keys(value, full, allowed, required)
    return value


def value(v, full: str, low=-math.inf, high=math.inf, low_open=False, unit="") -> float:
    """A finite number within [low, high] (low excluded when `low_open`), as float."""
    if v is None:
        raise ValidationError(full, "missing")
    if isinstance(v, bool) or not isinstance(v, (int, float)):
        raise ValidationError(full, f"must be a number, not {type(v).__name__} {short(v)}")
    try:
        v = float(v)
    except OverflowError:
        raise ValidationError(full, f"must be a finite number, not {short(v)}") from None
    if not math.isfinite(v):
        raise ValidationError(full, f"must be finite, not {v}")
    allowed = Range(low, high, unit, low_open)
    if v not in allowed:
        raise ValidationError(full, f"must be {allowed.text()}, not {v:g}")
    return v


def number(data: dict, key: str, where: str, default=None, low=-math.inf, high=math.inf,
           low_open=False, limit: Range | None = None) -> float:
    """data[key] (or `default`) checked by `value`; `limit` gives the range with its unit."""
    if limit is not None:
        low, high, low_open = limit.low, limit.high, limit.low_open
    return value(data.get(key, default), _full(where, key), low, high, low_open,
                 limit.unit if limit else "")


def integer(data: dict, key: str, where: str, default, low: int, high: int) -> int:
    """A whole number within [low, high]."""
    v = data.get(key, default)
    if isinstance(v, bool) or not isinstance(v, int):
        raise ValidationError(_full(where, key), f"must be a whole number, not {short(v)}")
    if not low <= v <= high:
        raise ValidationError(_full(where, key), f"must be between {low} and {high}, not {v}")
    return v


def pair(data: dict, key: str, where: str, limit=math.inf) -> tuple[float, float]:
    """A list of two finite numbers, each within [-limit, limit]."""
    full = _full(where, key)
    v = data.get(key)
    if not isinstance(v, list) or len(v) != 2:
        raise ValidationError(full, f"must be a pair of numbers, not {short(v)}")
    low, high = (value(x, f"{full}[{i}]", low=-limit, high=limit) for i, x in enumerate(v))
    return low, high


def string(data: dict, key: str, where: str, default=None) -> str:
    """A non-empty string."""
    v = data.get(key, default)
    if not isinstance(v, str) or not v.strip():
        raise ValidationError(_full(where, key), f"must be a non-empty string, not {short(v)}")
    return v


def flag(data: dict, key: str, where: str, default: bool) -> bool:
    """true or false."""
    v = data.get(key, default)
    if not isinstance(v, bool):
        raise ValidationError(_full(where, key), f"must be true or false, not {short(v)}")
    return v


def labels(data: dict, key: str, where: str, at_least: int = 1, distinct: bool = False) -> tuple:
    """A list of at least `at_least` non-empty strings (all different when `distinct`: a
    marker cluster of one marker named three times spans no plane)."""
    full = _full(where, key)
    v = data.get(key)
    if not isinstance(v, list) or not all(isinstance(x, str) and x.strip() for x in v):
        raise ValidationError(full, f"must be a list of labels, not {short(v)}")
    if len(v) < at_least:
        raise ValidationError(full, f"needs at least {at_least} labels, not {len(v)}")
    if distinct and len(set(v)) != len(v):
        twice = next(x for x in v if v.count(x) > 1)
        raise ValidationError(full, f"names {twice!r} more than once: a cluster needs "
                                    f"{at_least} different markers")
    return tuple(v)


def choice(v, key: str, choices):
    """One of `choices` (with the closest spelling when not)."""
    if not isinstance(v, (str, int, float)) or isinstance(v, bool) or v not in choices:
        close = difflib.get_close_matches(str(v), [str(c) for c in choices], n=1)
        hint = f" (did you mean {close[0]!r}?)" if close else ""
        raise ValidationError(key, f"must be one of {', '.join(map(str, choices))}, "
                                   f"not {short(v)}{hint}")
    return v


def joint_bounds(v, full: str, joint: str) -> tuple[float, float]:
    """[lo, hi] in deg for `joint`, lo < hi, within the joint's range of motion (limits)."""
    if not isinstance(v, (list, tuple)) or len(v) != 2:
        raise ValidationError(full, f"must be [lo, hi] in deg, not {short(v)}")
    rom = RANGE_OF_MOTION_DEG[joint]
    lo, hi = (value(x, f"{full}[{i}]") for i, x in enumerate(v))
    if not rom[0] <= lo < hi <= rom[1]:
        raise ValidationError(full, f"[{lo:g}, {hi:g}] needs {rom[0]:g} <= lo < hi <= {rom[1]:g} "
                                    f"deg (the {joint}'s range of motion, AAOS)")
    return lo, hi
