# The README's two commands: `make docs` and `make test`. Each creates .venv on first use.
PYTHON ?= python3
VENV   ?= .venv
PY      = $(VENV)/bin/python

.PHONY: test coverage docs notebooks bench lint clean mutation

$(VENV)/.test-stamp: pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e ".[test,engines]"
	touch $@

$(VENV)/.docs-stamp: pyproject.toml
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	$(PY) -m pip install --quiet -e ".[test,docs,engines]"
	touch $@

# on every core (pytest-xdist), each test file whole on one worker, so that its module-scoped caches
# (the engine corpus, SUPERball's runs) are built once; `pytest tests/test_x.py` alone runs serially.
test: $(VENV)/.test-stamp
	$(PY) -m pytest -n auto --dist loadfile

# The same run under branch coverage (pytest-cov, settings in pyproject.toml): a table of the modules
# below 100% and the TOTAL line.  Coverage measures through Python's trace function (Python 3.11 has no
# cheaper hook), which makes every run about 40% slower, so it is a target of its own; CI runs both.
coverage: $(VENV)/.test-stamp
	$(PY) -m pytest -n auto --dist loadfile --cov --cov-branch --cov-report=term

docs: $(VENV)/.docs-stamp
	rm -rf docs/reference/generated  # autosummary stubs of renamed or removed names would fail -W
	$(PY) -m sphinx -n -W --keep-going -b html docs docs/_build/html

# Executed Jupyter notebooks (.ipynb) of every tutorial, for readers who want to run them in
# Jupyter: jupytext turns each MyST file into a notebook and executes it with tutorials/ as the
# working folder (as the docs build does) and the checkout on the path (for matlab_ports/).
# They go to a build folder, never beside the sources: docs/conf.py excludes stray notebooks
# from the docs anyway, and none is committed.
NOTEBOOKS ?= docs/_build/notebooks
notebooks: $(VENV)/.docs-stamp
	mkdir -p $(NOTEBOOKS)
	for f in tutorials/[0-9]*.md; do \
	  PYTHONPATH="$(CURDIR)" $(VENV)/bin/jupytext --to ipynb --execute --run-path tutorials \
	    --output "$(NOTEBOOKS)/$$(basename $$f .md).ipynb" "$$f" || exit 1; \
	done
	@echo "Executed notebooks are in $(NOTEBOOKS)/ (open them with: jupyter lab $(NOTEBOOKS))"

$(VENV)/.bench-stamp: pyproject.toml $(VENV)/.test-stamp
	$(PY) -m pip install --quiet -e ".[test,engines,bench]"
	touch $@

# every benchmark script, each timing pitheorem against its baselines in the same run
bench: $(VENV)/.bench-stamp
	cd benchmarks && for script in bench_*.py; do echo "== $$script"; ../$(PY) $$script || exit 1; done

$(VENV)/.mutation-stamp: pyproject.toml $(VENV)/.test-stamp
	$(PY) -m pip install --quiet -e ".[test,engines,mutation]"
	touch $@

# Mutation testing with mutmut (not part of `make test` or CI): the core modules and the tests listed
# under [tool.mutmut] in pyproject.toml.  MUTANTS narrows it to a glob of mutant names, e.g.
# make mutation MUTANTS='pitheorem.linalg.*'; JOBS sets the parallel workers.  Results are kept in
# mutants/ (a second run retests only what changed); benchmarks/MUTATION.md records the figures.
MUTANTS ?=
JOBS ?= 2
mutation: $(VENV)/.mutation-stamp
	$(VENV)/bin/mutmut run --max-children $(JOBS) $(MUTANTS)
	$(VENV)/bin/mutmut export-cicd-stats && cat mutants/mutmut-cicd-stats.json && echo
	$(VENV)/bin/mutmut results

# ruff's linter and its formatter (style.md): `ruff format` on the same paths fixes what --check reports
LINTED = pitheorem tests matlab_ports benchmarks docs/conf.py docs/check_pages.py docs/check_offline.py
lint: $(VENV)/.test-stamp
	$(PY) -m ruff check $(LINTED)
	$(PY) -m ruff format --check $(LINTED)

clean:
	rm -rf $(VENV) docs/_build docs/jupyter_execute
