# bodycheck: every target sets up .venv on first use, then runs.
PYTHON ?= $(shell command -v python3.11 2>/dev/null || command -v python3)
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed

.PHONY: run test checks bench clean

$(STAMP): pyproject.toml
	test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --disable-pip-version-check -e '.[test]'
	touch $(STAMP)

## make run: the main job, the whole catalogue
run: $(STAMP)
	$(BIN)/bodycheck check

## make test: lint, format check and the whole test suite
test: $(STAMP)
	$(BIN)/ruff check .
	$(BIN)/ruff format --check .
	$(BIN)/python -m pytest

## make checks: regenerate CHECKS.md from the registry
checks: $(STAMP)
	$(BIN)/bodycheck catalogue --write CHECKS.md

## make bench: time the kernels (pytest-benchmark, saved for --benchmark-compare), then
## the work-precision study (bodycheck bench: table, JSON and plots in bench-results/)
bench: $(STAMP)
	$(BIN)/python -m pytest tests/benchmarks --benchmark-enable --benchmark-only \
		--benchmark-autosave --benchmark-columns=min,median,max,rounds
	$(BIN)/bodycheck bench --out bench-results

clean:
	rm -rf $(VENV) .pytest_cache .hypothesis .benchmarks .ruff_cache bench-results
