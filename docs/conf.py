"""Sphinx configuration of formopt's documentation (make docs).

Sphinx, because the docstrings are numpydoc (numpydoc renders them as they are written) and
sphinx-gallery runs examples/*.py at every build, so the gallery cannot go stale; pages are
Markdown (MyST), the same format as the README, so that tests/test_docs.py runs the code of
both with one parser.
"""

import shutil
import sys
from pathlib import Path

from docutils import nodes
from docutils.parsers.rst import Directive

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

import formopt  # noqa: E402

project = "formopt"
author = "the formopt developers"
copyright = "2026, the formopt developers"  # Sphinx's name for it
release = formopt.__version__

# sphinx-mathjax-offline (its import name has hyphens) copies MathJax 3 from its own package
# into _static/mathjax and points Sphinx there: the math renders with no network
extensions = ["myst_parser", "numpydoc", "sphinx.ext.autodoc", "sphinx.ext.autosummary",
              "sphinx.ext.mathjax", "sphinx-mathjax-offline", "sphinx_gallery.gen_gallery"]
source_suffix = {".md": "markdown", ".rst": "restructuredtext"}
myst_enable_extensions = ["dollarmath", "amsmath"]
myst_heading_anchors = 3
exclude_patterns = ["_build", "generated/*.csv", "gallery/*.csv", "auto_examples/*.ipynb", "auto_examples/*.py",
                    "auto_examples/*.zip", "auto_examples/*.json", "auto_examples/*.md5",
                    "sg_execution_times.rst"]
# the gallery's hooks are functions, which Sphinx cannot pickle into its environment cache
# (sphinx-gallery's documented set-up); no intersphinx, so the build needs no network
suppress_warnings = ["config.cache"]
html_theme = "alabaster"
html_static_path = ["_static"]
html_css_files = ["formopt.css"]  # wide console blocks scroll instead of being cut
html_theme_options = {"description": "The running form that wastes the least energy at foot strike",
                      "fixed_sidebar": True}

numpydoc_show_class_members = False
numpydoc_validation_checks: set = set()
autodoc_typehints = "none"
autosummary_generate = True  # one page per module of the API table (docs/generated, rebuilt)
templates_path = ["_templates"]  # autosummary/module.rst: the page of a module (`module-text`)

class ModuleText(Directive):
    """`.. module-text:: NAME`: a module's docstring and each public name's signature and
    docstring, as written (plain text with equations, not reStructuredText)."""

    required_arguments = 1

    def run(self):
        import importlib
        import inspect

        def text(obj):  # wrapped, not highlighted
            return nodes.literal_block(text=inspect.getdoc(obj) or "", language="text", classes=["docstring"])

        module = importlib.import_module(self.arguments[0])
        out = [text(module)]
        for name, obj in vars(module).items():
            if name.startswith("_") or getattr(obj, "__module__", None) != module.__name__ or \
                    not (inspect.isclass(obj) or inspect.isfunction(obj)):
                continue
            try:
                head = f"{name}{inspect.signature(obj)}"
            except (TypeError, ValueError):
                head = name
            section = nodes.section(ids=[f"{module.__name__}.{name}"])
            section += nodes.title("", "", nodes.literal(text=("class " if inspect.isclass(obj) else "") + head))
            section += text(obj)
            out.append(section)
        return out


def setup(app):
    app.add_directive("module-text", ModuleText)


OUT = ROOT / "docs" / "_build" / "gallery-out"  # where the examples write their files


def pngs_written(block, block_vars, gallery_conf):
    """sphinx-gallery scraper for figures saved to files (formopt's figures never use
    pyplot): the PNGs an example wrote to OUT, moved beside the gallery page."""
    from sphinx_gallery.scrapers import figure_rst

    paths = []
    for png, target in zip(sorted(OUT.rglob("*.png")), block_vars["image_path_iterator"]):
        shutil.move(png, target)
        paths.append(target)
    return figure_rst(paths, gallery_conf["src_dir"])


def fresh_out(gallery_conf, fname, when=None):
    """Reset OUT before each example, so that each page shows its own figures."""
    shutil.rmtree(OUT, ignore_errors=True)
    OUT.mkdir(parents=True)


sphinx_gallery_conf = {
    "examples_dirs": str(ROOT / "examples"),
    "gallery_dirs": "auto_examples",
    "filename_pattern": r".*\.py",
    "reset_argv": lambda gallery_conf, script_vars: [str(OUT)],
    "image_scrapers": (pngs_written,),
    "reset_modules": (fresh_out,),
    "download_all_examples": False,
    "remove_config_comments": True,
    "abort_on_example_error": True,
    "only_warn_on_example_error": False,
}
