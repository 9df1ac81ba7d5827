"""Atomic output files: a file appears whole or not at all.

Every output of formopt (JSON, CSV, figures) is written to a uniquely named temporary file in
the target folder and renamed over the target, so a crash, a full disk or a second process
writing the same file never leaves a torn or mixed file, and no temporary file is left behind.
"""

from __future__ import annotations

import contextlib
import csv
import io
import json
import os
import tempfile
from pathlib import Path


class OutputError(OSError):
    """An output path that cannot be written: names the path and the reason."""


def output_folder(path) -> Path:
    """`path` as a folder that exists (created if needed); OutputError if it cannot be."""
    path = Path(path)
    try:
        path.mkdir(parents=True, exist_ok=True)
    except FileExistsError:
        raise OutputError(f"{path}: is a file, not a folder") from None
    except OSError as err:
        raise OutputError(f"{path}: cannot create the folder ({err.strerror})") from None
    return path


@contextlib.contextmanager
def atomic(path, mode: str = "w", **kwargs):
    """Open a temporary file beside `path`; on success it replaces `path`, on failure it is
    removed. `mode` "w" (text, newline="" for CSV is the caller's) or "wb"."""
    path = Path(path)
    folder = output_folder(path.parent)
    if path.is_dir():
        raise OutputError(f"{path}: is a folder, not a file")
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=folder)
    except OSError as err:
        raise OutputError(f"{path}: cannot write ({err.strerror})") from None
    try:
        with os.fdopen(fd, mode, **kwargs) as fh:
            yield fh
        os.replace(tmp, path)
    except OSError as err:
        Path(tmp).unlink(missing_ok=True)
        raise OutputError(f"{path}: cannot write ({err.strerror})") from None
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def write_text(path, text: str) -> Path:
    with atomic(path) as fh:
        fh.write(text)
    return Path(path)


def write_json(path, data) -> Path:
    """`data` as indented JSON (NaN and inf are refused: they are not JSON)."""
    return write_text(path, json.dumps(data, indent=2, allow_nan=False) + "\n")


def write_csv(path, rows) -> Path:
    """Rows (the first one the header) as CSV."""
    with atomic(path, newline="") as fh:
        csv.writer(fh).writerows(rows)
    return Path(path)


def save_figure(fig, path, **kwargs) -> Path:
    """A Matplotlib figure to `path` (its format from the suffix), atomically."""
    path = Path(path)
    buffer = io.BytesIO()
    fig.savefig(buffer, format=path.suffix.lstrip(".") or "png", **kwargs)
    with atomic(path, "wb") as fh:
        fh.write(buffer.getvalue())
    return path
