"""The README and the documentation pages do what they show.

Every fenced block of README.md and docs/**/*.md runs, page by page in a fresh folder:
- ```python blocks in one namespace per page (as a reader would paste them); a ```text block
  right after one is its printed output;
- shell blocks (```console, ```sh): each `$ command` line through bash, with `formopt` and
  `python` the interpreter running these tests; the lines after it, up to the next `$`, are
  its output (stdout and stderr, as a terminal shows them). A plain `formopt ARGS` (no quotes,
  pipes, redirections or variables) runs in this process (`run_formopt`: formopt.cli.main, a
  new interpreter's start and imports, about 1 s of CPU a command, spared; the CLI's entry
  point is tested as a subprocess in tests/io/test_scene.py);
- ```toml blocks parse.
Pages run in a fresh folder that holds `data` (the repository's shipped trials).
Output is compared line by line (trailing spaces ignored; `...` inside a line stands for any
text). A block whose preceding line is `<!-- test: abridged -->` shows only some of the
output: its lines must appear in that order, `...` lines marking the gaps. A block marked
`<!-- test: skip (reason) -->` is not run; the reason is required.

The gallery's freshness (docs/gallery_manifest.py) is checked here as well.
"""

from __future__ import annotations

import contextlib
import io
import os
import re
import runpy
import subprocess
import sys
import tomllib
from dataclasses import dataclass

import pytest
from helpers import ROOT

import formopt
from formopt.cli import main

PAGES = [ROOT / "README.md"] + sorted(p for p in (ROOT / "docs").rglob("*.md")
                                      if "_build" not in p.parts and "auto_examples" not in p.parts)
SHELL = ("console", "sh", "shell", "bash")
MARK = re.compile(r"<!--\s*test:\s*(skip|abridged)\b\s*(.*?)\s*-->")


@dataclass
class Block:
    lang: str
    text: str
    line: int  # 1-based line of the opening fence
    end: int  # 1-based line of the closing fence
    mark: str = ""  # "", "skip" or "abridged"
    reason: str = ""
    output: Block | None = None  # a python block's shown output (the ```text block after it)


def blocks(path) -> list[Block]:
    """The fenced blocks of a Markdown page, with their marks; a ```text block that follows a
    python block (blank lines or a mark between) is attached to it as its output."""
    lines = path.read_text().splitlines()
    found, k = [], 0
    while k < len(lines):
        m = re.match(r"^```\s*([\w+-]*)", lines[k])
        if not m:
            k += 1
            continue
        end = next(j for j in range(k + 1, len(lines)) if lines[j].startswith("```"))
        before = next((lines[j] for j in range(k - 1, -1, -1) if lines[j].strip()), "")
        mark = MARK.search(before)
        block = Block(m.group(1).lower(), "\n".join(lines[k + 1:end]), k + 1, end + 1,
                      *(mark.groups() if mark else ("", "")))
        last = found[-1] if found else None
        if block.lang == "text" and last and last.lang == "python" and \
                all(not line.strip() or MARK.search(line) for line in lines[last.end:k]):
            last.output = block
        else:
            found.append(block)
        k = end + 1
    return found


def matches(shown: str, actual: str, abridged: bool) -> bool:
    """Whether `actual` output is what `shown` shows (module docstring)."""
    def pattern(line):
        return re.compile(".*".join(map(re.escape, line.rstrip().split("..."))) + r"\Z")

    want = [line.rstrip() for line in shown.splitlines()]
    got = [line.rstrip() for line in actual.rstrip("\n").splitlines()]
    if not abridged:
        return len(want) == len(got) and all(pattern(w).match(g) for w, g in zip(want, got))
    k = 0
    for w in (w for w in want if w.strip() and w.strip() != "..."):
        while k < len(got) and not pattern(w).match(got[k]):
            k += 1
        if k == len(got):
            return False
        k += 1
    return True


def commands(text: str) -> list[tuple[str, str]]:
    """[(command, shown output)] of a shell block; without `$` prompts every line is a command."""
    lines = text.splitlines()
    if not any(line.startswith("$ ") for line in lines):
        return [(line, "") for line in lines if line.strip() and not line.startswith("#")]
    out = []
    for line in lines:
        if line.startswith("$ "):
            out.append((line[2:], []))
        elif out:
            out[-1][1].append(line)
    return [(cmd, "\n".join(shown)) for cmd, shown in out]


@pytest.fixture()
def shell_env(tmp_path):
    """PATH with `formopt` and `python` running this interpreter on this source tree; the
    folder holds `data` (a link to the repository's), as a reader at its root has."""
    (tmp_path / "data").symlink_to(ROOT / "data")
    bin_dir = tmp_path / ".bin"
    bin_dir.mkdir()
    for name, target in (("formopt", f'"{sys.executable}" -m formopt.cli'), ("python", f'"{sys.executable}"')):
        shim = bin_dir / name
        shim.write_text(f'#!/bin/sh\nexec {target} "$@"\n')
        shim.chmod(0o755)
    return {**os.environ, "PATH": f"{bin_dir}{os.pathsep}{os.environ['PATH']}",
            "PYTHONPATH": os.pathsep.join([str(ROOT), os.environ.get("PYTHONPATH", "")]),
            "MPLBACKEND": "Agg"}


PLAIN = re.compile(r"formopt(\s+[\w./=:-]+)*")  # `formopt ARGS` that bash would pass on unchanged


def run_formopt(command: str) -> tuple[int, str]:
    """A plain `formopt ARGS` run by formopt.cli.main in this process: its exit status and its
    standard output and error in one stream, as a terminal shows them."""
    printed = io.StringIO()
    with contextlib.redirect_stdout(printed), contextlib.redirect_stderr(printed):
        code = main(command.split()[1:])
    return code, printed.getvalue()


def run_shell(command: str, env: dict) -> tuple[int, str]:
    """A shell command: plain `formopt ARGS` in this process (run_formopt), any other through
    bash; its exit status and printed output (stdout and stderr in one stream)."""
    if PLAIN.fullmatch(command.strip()):
        return run_formopt(command)
    run = subprocess.run(["bash", "-c", command], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                         text=True, env=env, timeout=300)
    return run.returncode, run.stdout


def run_python(block: Block, namespace: dict) -> str:
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(block.text, f"<block at line {block.line}>", "exec"), namespace)
    return out.getvalue()


TESTED = [p for p in PAGES if any(b.lang in ("python", "toml", *SHELL) for b in blocks(p))]


@pytest.mark.parametrize("page", TESTED, ids=[str(p.relative_to(ROOT)) for p in TESTED])
def test_page_does_what_it_shows(page, tmp_path, shell_env, monkeypatch):
    monkeypatch.chdir(tmp_path)
    namespace: dict = {"__name__": "__main__"}
    where = page.relative_to(ROOT)
    for block in blocks(page):
        if block.mark == "skip":
            assert block.reason.strip("() "), f"{where}:{block.line}: a skipped block says why"
            continue
        abridged = block.mark == "abridged"
        if block.lang == "python":
            printed = run_python(block, namespace)
            if block.output is not None:
                assert matches(block.output.text, printed, block.output.mark == "abridged"), \
                    f"{where}:{block.line}: printed\n{printed}"
        elif block.lang == "toml":
            tomllib.loads(block.text)
        elif block.lang in SHELL:
            for cmd, shown in commands(block.text):
                code, printed = run_shell(cmd, shell_env)
                assert shown or code == 0, f"{where}:{block.line}: {cmd}\n{printed}"
                assert not shown or matches(shown, printed, abridged), \
                    f"{where}:{block.line}: {cmd} printed\n{printed}"


def test_readme_is_a_front_page():
    """At most about 200 lines, with the two set-up commands written out."""
    text = (ROOT / "README.md").read_text()
    assert len(text.splitlines()) <= 200
    assert "make demo" in text and "make test" in text
    # the package index shows the README without the repository: no link or image into it
    assert not re.findall(r"\]\((?!https?://)[^)]*\)", text), "a relative link or image"
    # it leads with the runner's question, then the stride, then the impact
    order = [text.index(s) for s in ("What does my running form cost", "formopt stride", "formopt compare",
                                     "## The impact in detail")]
    assert order == sorted(order)


def test_readme_python_names_exist():
    """Every `formopt.NAME` the README and the getting-started page use is importable."""
    import formopt

    for page in (ROOT / "README.md", ROOT / "docs" / "getting-started.md"):
        for name in set(re.findall(r"\bformopt\.([A-Za-z_]\w*)\(", page.read_text())):
            assert hasattr(formopt, name), f"{page.name}: formopt.{name}"


def test_gallery_is_drawn_by_the_current_code():
    """docs/gallery was redrawn after the last change to the code that draws it (else: make
    gallery)."""
    manifest = runpy.run_path(str(ROOT / "docs" / "gallery_manifest.py"))
    assert not manifest["stale"](), "stale gallery, run `make gallery`: " + ", ".join(manifest["stale"]())


def test_compare_reads_file_paths():
    """`formopt.compare("run.c3d", "static.c3d", mass=..., height=...)`, as the docs show:
    paths are read (a missing one named in an InputError), the result is a Comparison."""
    import formopt

    with pytest.raises(formopt.InputError, match=r"run.c3d: no such file"):
        formopt.compare("run.c3d", "static.c3d", mass=62, height=1.81, friction=0.8)
    ric = ROOT / "data" / "ric"
    c = formopt.compare(str(ric / "20160226T120637_run.c3d"), ric / "20160226T120637_static.c3d",
                        mass=79, height=1.77, friction=0.8, starts=1, per_step=False)
    assert isinstance(c, formopt.Comparison) and c.strike == "heel" and c.optimum.success


def test_the_api_reference_documents_every_public_name():
    """docs/api.rst has a directive for each name of formopt.__all__ (the version aside)."""
    text = (ROOT / "docs" / "api.rst").read_text()
    missing = [n for n in formopt.__all__ if n != "__version__" and f":: formopt.{n}\n" not in text]
    assert not missing, f"docs/api.rst leaves out {missing}"
