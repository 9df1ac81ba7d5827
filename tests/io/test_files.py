"""Output files touch only what is theirs: regular files, the user's umask, formopt's own CSV."""

import os
import stat

import pytest

from formopt.io.files import OutputError, append_csv, append_rows, write_text

HEADER = ["speed", "T_c", "error"]


def test_a_device_fifo_or_folder_is_refused_and_left_alone(tmp_path):
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    for target in (fifo, tmp_path, "/dev/null"):
        with pytest.raises(OutputError, match=r"FIFO|folder|device"):
            write_text(target, "x")
    assert stat.S_ISFIFO(fifo.stat().st_mode) and stat.S_ISCHR(os.stat("/dev/null").st_mode)
    with pytest.raises(OutputError, match="empty"):
        write_text("", "x")


def test_new_files_follow_the_umask_and_replaced_ones_keep_their_mode(tmp_path):
    old = os.umask(0o022)
    try:
        assert stat.S_IMODE(write_text(tmp_path / "a.json", "{}").stat().st_mode) == 0o644
        os.chmod(tmp_path / "a.json", 0o640)
        assert stat.S_IMODE(write_text(tmp_path / "a.json", "[]").stat().st_mode) == 0o640
    finally:
        os.umask(old)


def test_a_sweep_appends_only_to_its_own_csv(tmp_path):
    path = tmp_path / "sweep.csv"
    fh, rows, torn = append_csv(path, HEADER)
    append_rows(fh, path, [[1.0, 0.5, ""]])
    fh.close()
    fh, rows, torn = append_csv(path, HEADER)
    fh.close()
    assert rows == [{"speed": "1.0", "T_c": "0.5", "error": ""}] and not torn
    with pytest.raises(OutputError, match="something else"):  # another grid's header
        append_csv(path, ["slope", "T_c", "error"])
    note = tmp_path / "notes.txt"
    note.write_text("a file with no newline")
    with pytest.raises(OutputError, match="something else"):
        append_csv(note, HEADER)
    assert note.read_text() == "a file with no newline"  # not 'repaired'


def test_a_torn_last_row_is_cut_and_a_garbage_row_named(tmp_path):
    path = tmp_path / "sweep.csv"
    path.write_text("speed,T_c,error\n1.0,0.5,\n2.0,0.")
    fh, rows, torn = append_csv(path, HEADER)
    fh.close()
    assert torn and len(rows) == 1 and path.read_text().endswith("0.5,\n")
    path.write_text("speed,T_c,error\n1.0,0.5\n")
    with pytest.raises(OutputError, match="line 2 has 2 fields"):
        append_csv(path, HEADER)
