# impactcli: `make run` and `make test` work on a fresh machine with only Python 3.11 and pip.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed

.PHONY: run test tables bench lint clean venv

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip

$(STAMP): $(BIN)/python pyproject.toml
	$(BIN)/python -m pip install --quiet -e '.[test,plot,parquet,dask]'
	touch $(STAMP)

venv: $(STAMP)

## run: set up, then print the paper's Tables A1 and A2 (n = 25)
run: $(STAMP)
	$(BIN)/impact tables --n 25 --format table

## test: set up, then lint and run the whole test suite
test: $(STAMP)
	$(BIN)/ruff check impactcli tests
	$(BIN)/python -m pytest -q

## tables: regenerate the committed normalised tables in tables/
tables: $(STAMP)
	$(BIN)/impact tables --n 25 --stage loading --format csv -o tables/table_a1_n25.csv
	$(BIN)/impact tables --n 25 --stage restitution --format csv -o tables/table_a2_n25.csv

## bench: FILM against SciPy, impact batch throughput, tables --n 10^6, cold start; writes the
##        table into README.md (a few minutes)
bench: $(STAMP)
	$(BIN)/python benchmarks/bench.py --readme README.md

lint: $(STAMP)
	$(BIN)/ruff check impactcli tests

clean:
	rm -rf $(VENV) build *.egg-info .pytest_cache .ruff_cache
