"""The layer rule: every import inside formopt points down the list of layers
(design.md section 4), and mechanics stays free of scenes and files."""

import ast

from helpers import ROOT

# api (formopt.load, impact, simulate, solve, ...) composes the layers below it for users;
# the command line uses it and the reports.
LAYERS = ("mechanics", "optim", "io", "measure", "studies", "api", "report", "cli")
METADATA = ("formopt.__version__",)  # package metadata, not code
PACKAGE = ROOT / "formopt"


def layer(module: str) -> int:
    """Rank of a dotted module inside formopt: its layer, or above all for formopt/__init__.py
    (which re-exports the public API)."""
    parts = module.split(".")
    return LAYERS.index(parts[1]) if len(parts) > 1 and parts[1] in LAYERS else len(LAYERS)


def imports(path):
    """Dotted formopt modules imported by the file at `path`."""
    module = ".".join(path.relative_to(ROOT).with_suffix("").parts)
    package = module if path.name == "__init__.py" else module.rsplit(".", 1)[0]
    package = package.removesuffix(".__init__")
    for node in ast.walk(ast.parse(path.read_text())):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if target.startswith("formopt"):
                yield target, [a.name for a in node.names]
        elif isinstance(node, ast.Import):
            for a in node.names:
                if a.name.startswith("formopt"):
                    yield a.name, []


def test_every_import_points_down_the_layers():
    wrong = []
    for path in sorted(PACKAGE.rglob("*.py")):
        module = ".".join(path.relative_to(ROOT).with_suffix("").parts)
        for target, names in imports(path):
            expand = target == "formopt" or target in (f"formopt.{x}" for x in LAYERS)
            targets = [f"{target}.{n}" for n in names] if expand else [target]
            for t in targets:
                if t not in METADATA and layer(t) > layer(module):
                    wrong.append(f"{module} imports {t}")
    assert not wrong, "\n".join(wrong)


def test_mechanics_reads_no_scenes_or_files():
    """No scene or data file read below io; the one exception is mechanics.compiled's own cache
    (its libraries, their use counts and compile locks, all in compiled.cache_dir())."""
    for path in (PACKAGE / "mechanics").rglob("*.py"):
        text = path.read_text()
        assert "tomllib" not in text, path
        if path.name != "compiled.py":
            assert "open(" not in text.replace("fdopen(", ""), path


def test_the_command_line_starts_without_plotting_or_solving_libraries():
    """`formopt` parses its command line without Matplotlib, scipy.optimize or scipy.integrate
    (0.5 s of imports at every start, before this was checked): each is imported where it is
    used."""
    import subprocess
    import sys

    code = ("import sys\nfrom formopt.cli import parser\nparser()\n"
            "print(' '.join(m for m in ('matplotlib', 'scipy.optimize', 'scipy.integrate') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == ""
