# make demo: set up .venv when missing, install formopt, optimise the demo scene's posture
# (prints the result, writes figures and JSON to out/demo).
# make test: the same set-up, then the whole test suite on 2 workers (pytest-xdist; tests/conftest.py
# keeps each file on one worker and the Dask tests together).
# make docs: the documentation site (docs/_build/html), warnings as errors; runs the examples.
# make gallery: the figures in docs/gallery, redrawn by the examples, and their manifest.
PYTHON ?= python3.11
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: demo test bench gallery docs clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV) || python3 -m venv $(VENV)

$(STAMP): $(BIN)/python pyproject.toml
	$(BIN)/python -m pip install --quiet --upgrade pip
	$(BIN)/python -m pip install --quiet -e '.[test]'
	touch $(STAMP)

demo: $(STAMP)
	$(BIN)/formopt solve demo --out out/demo

test: $(STAMP)
	$(BIN)/python -m pytest -q -n 2 --dist loadfile

bench: $(STAMP)
	$(BIN)/formopt bench
	$(BIN)/python benchmarks/impact_speed.py
	$(BIN)/python benchmarks/contact_laws_speed.py
	$(BIN)/python benchmarks/solve_speed.py
	$(BIN)/python benchmarks/landing_speed.py
	$(BIN)/python benchmarks/sweep_scaling.py

gallery: $(STAMP)
	for f in examples/*.py; do $(BIN)/python $$f docs/gallery || exit 1; done
	$(BIN)/python docs/gallery_manifest.py write

DOCS_STAMP := $(VENV)/.docs-installed

$(DOCS_STAMP): $(STAMP) pyproject.toml
	$(BIN)/python -m pip install --quiet -e '.[docs]'
	touch $(DOCS_STAMP)

docs: $(DOCS_STAMP)
	$(BIN)/python -m sphinx -W --keep-going -q -b html docs docs/_build/html

clean:
	rm -rf $(VENV) build *.egg-info docs/_build docs/auto_examples
