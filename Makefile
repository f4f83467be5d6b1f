# The README's two commands: `make docs` and `make test`. Each creates .venv on first use.
PYTHON ?= python3
VENV   ?= .venv
PY      = $(VENV)/bin/python

.PHONY: test docs bench lint clean

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

test: $(VENV)/.test-stamp
	$(PY) -m pytest

docs: $(VENV)/.docs-stamp
	$(PY) -m sphinx -n -W --keep-going -b html docs docs/_build/html

$(VENV)/.bench-stamp: pyproject.toml $(VENV)/.test-stamp
	$(PY) -m pip install --quiet -e ".[test,engines,bench]"
	touch $@

# every benchmark script, each timing pitheorem against its baselines in the same run
bench: $(VENV)/.bench-stamp
	cd benchmarks && for script in bench_*.py; do echo "== $$script"; ../$(PY) $$script || exit 1; done

lint: $(VENV)/.test-stamp
	$(PY) -m ruff check pitheorem tests matlab_ports benchmarks docs/check_pages.py docs/check_offline.py

clean:
	rm -rf $(VENV) docs/_build docs/jupyter_execute
