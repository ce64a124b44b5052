# The two commands of the README: `make demo` and `make test`. Both set themselves up, and so
# does `make test-fast` (CONTRIBUTING.md).
# `make demo` installs the package alone; `make test` (and `make setup`) everything the tests
# use: every extra, torch's CPU build, the dev tools and a browser (scripts/setup.sh).
VENV := .venv
BIN := $(VENV)/bin
DEMO_STAMP := $(VENV)/.demo-installed
STAMP := $(VENV)/.installed
SETUP := pyproject.toml scripts/setup.sh scripts/setup-lib.sh
SRC := src oracle_training tests

.PHONY: setup demo test test-fast lint bench clean

$(DEMO_STAMP): $(SETUP)
	bash scripts/setup.sh demo
	touch $(DEMO_STAMP)

$(STAMP): $(SETUP)
	bash scripts/setup.sh dev
	touch $(STAMP) $(DEMO_STAMP)

setup: $(STAMP)

demo: $(DEMO_STAMP)
	$(BIN)/vlln demo --out out/demo

lint: $(STAMP)
	$(BIN)/ruff check $(SRC)
	$(BIN)/ruff format --check $(SRC)
	$(BIN)/mypy

# The whole suite, slow tests included: what CI runs (.ci/run). Two worker processes
# (pytest-xdist): the tests are bound by one core each, so two cores finish in about 60 % of
# the time; an idle worker takes queued tests from the busy one (worksteal), and the 20
# slowest tests are listed at the end. `$(BIN)/python -m pytest` alone runs them in one process.
PYTEST := $(BIN)/python -m pytest -q -n 2 --dist worksteal --durations=20

test: lint
	$(PYTEST)

# The fast lane while working: every test package, without the tests marked slow and without
# lint (run `make lint` for that).
test-fast: $(STAMP)
	$(PYTEST) -m "not slow"

bench: $(DEMO_STAMP)
	$(BIN)/vlln bench sim --json

clean:
	rm -rf $(VENV) out .mypy_cache .ruff_cache .pytest_cache
