"""Output files: a file appears whole or not at all, and only where a file belongs.

Every output of formopt (JSON, CSV, figures) is written to a uniquely named temporary file in
the target folder and renamed over the target, so a crash, a full disk or a second process
writing the same file never leaves a torn or mixed file, and no temporary file is left behind.
A target that exists must be a regular file (never a device node, FIFO, socket, folder or
symbolic link: the rename would replace it); a new file gets the user's umask, a replaced one
keeps its mode.
Sweeps append to a CSV (`append_csv`) that must be formopt's, with the same header.
"""

from __future__ import annotations

import contextlib
import csv
import io
import json
import os
import stat
import tempfile
from pathlib import Path


class OutputError(OSError):
    """An output path that cannot be written: names the path and the reason."""


def check_target(path) -> Path:
    """`path` as a place for an output file: empty, or an existing regular file.

    OutputError for an empty path, a folder, a device node, a FIFO, a socket or a symbolic link
    (a sweep would append through it to a file elsewhere, even a dangling link's target; a
    rename would replace the user's link)."""
    if str(path).strip() == "":
        raise OutputError("an empty output path: give a file or folder name")
    path = Path(path)
    try:
        mode = path.lstat().st_mode
    except FileNotFoundError:
        return path
    except OSError as err:
        raise OutputError(f"{path}: cannot use it ({err.strerror})") from None
    if stat.S_ISLNK(mode):
        raise OutputError(f"{path}: is a symbolic link; formopt writes only regular files it owns "
                          "(give the file it points to, or another name)")
    if stat.S_ISDIR(mode):
        raise OutputError(f"{path}: is a folder, not a file")
    if not stat.S_ISREG(mode):
        kind = ("a device" if stat.S_ISCHR(mode) or stat.S_ISBLK(mode) else
                "a FIFO" if stat.S_ISFIFO(mode) else "a socket" if stat.S_ISSOCK(mode) else
                "not a regular file")
        raise OutputError(f"{path}: is {kind}; formopt writes only regular files it owns")
    return path


def _new_file_mode(path: Path) -> int:
    """The mode an output gets: the replaced file's, or 0o666 less the user's umask."""
    try:
        return stat.S_IMODE(path.stat().st_mode)
    except OSError:
        mask = os.umask(0)
        os.umask(mask)
        return 0o666 & ~mask


def output_folder(path) -> Path:
    """`path` as a folder that exists (created if needed); OutputError if it cannot be."""
    if str(path).strip() == "":
        raise OutputError("an empty output folder: give a folder name")
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
    path = check_target(path)
    folder = output_folder(path.parent)
    file_mode = _new_file_mode(path)
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=folder)
    except OSError as err:
        raise OutputError(f"{path}: cannot write ({err.strerror})") from None
    try:
        with os.fdopen(fd, mode, **kwargs) as fh:
            yield fh
        os.chmod(tmp, file_mode)
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


def append_csv(path, header: list[str]):
    """Open a sweep's CSV to append rows: (file, rows already there as dicts, torn).

    A new or empty file gets `header`. An existing file must start with exactly `header`
    (another grid, or a file that is not a formopt sweep, is refused: nothing in it is
    touched); then a torn last row (no newline: an interrupted write) is cut, and every row
    must have the header's number of fields (else OutputError naming the line). The file is
    created with the user's umask and locked against a second sweep (POSIX)."""
    path = check_target(path)
    output_folder(path.parent)
    try:
        fh = path.open("a+", newline="")
    except OSError as err:
        raise OutputError(f"{path}: cannot write the sweep ({err.strerror})") from None
    try:
        _lock(fh, path)
        fh.seek(0)
        try:
            text = fh.read()
        except UnicodeDecodeError:  # a binary file (an image, an archive): not a sweep's CSV
            raise OutputError(f"{path}: holds something else than this sweep (not text); give "
                              "another --out or remove it") from None
        first = text.split("\n", 1)[0]
        if text and ("\n" not in text or next(csv.reader([first]), []) != list(header)):
            first = first.rstrip("\r")[:80]
            raise OutputError(f"{path}: holds something else than this sweep (its first line is "
                              f"{first!r}); give another --out or remove it")
        torn = bool(text) and not text.endswith("\n")
        if torn:
            fh.truncate(len(text[:text.rfind("\n") + 1].encode()))
            text = text[:text.rfind("\n") + 1]
        fh.seek(0, os.SEEK_END)
        if not text:
            csv.writer(fh).writerow(header)
            fh.flush()
        return fh, _rows(path, text, header), torn
    except BaseException:
        fh.close()
        raise


def _rows(path: Path, text: str, header: list[str]) -> list[dict]:
    """The data rows of a sweep CSV's text as dicts; OutputError at a row of another width."""
    reader = csv.reader(io.StringIO(text))
    next(reader, None)
    rows = []
    for row in reader:
        if len(row) != len(header):
            raise OutputError(f"{path}: line {reader.line_num} has {len(row)} fields where the "
                              f"header has {len(header)}; mend or remove the file")
        rows.append(dict(zip(header, row)))
    return rows


def append_rows(fh, path, rows) -> None:
    """Append CSV rows and flush them to disk; a full disk is an OutputError, and what was
    flushed before stays (a torn last row is cut when the sweep resumes)."""
    try:
        csv.writer(fh).writerows(rows)
        fh.flush()
    except OSError as err:
        with contextlib.suppress(OSError):  # the rows still buffered cannot be written either:
            fh.close()  # closed now (raw file closed), so the caller's close does not raise again
        raise OutputError(f"{path}: cannot append ({err.strerror}); the rows written so far "
                          "are kept and the same command resumes") from None


def _lock(fh, path) -> None:
    """An exclusive lock on the open file, or OutputError if another process holds it."""
    try:
        import fcntl
    except ImportError:  # not a POSIX system: no lock
        return
    try:
        fcntl.flock(fh.fileno(), fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        raise OutputError(f"{path}: another sweep is writing this file; wait for it to end or "
                          "give another --out") from None
