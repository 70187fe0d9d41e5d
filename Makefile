# bodycheck: every target sets up .venv on first use, then runs.
PYTHON ?= $(shell command -v python3.11 2>/dev/null || command -v python3)
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
LOCK   := requirements/lock.txt
# Python's bytecode caches (and pytest's rewritten test modules, cached beside them) are
# what make a second run start fast: where the environment turns them off
# (PYTHONDONTWRITEBYTECODE, as on these machines) every process recompiles every module,
# and collecting the suite took 16 s per pytest worker instead of 5.6 s
unexport PYTHONDONTWRITEBYTECODE
# the suite's one command line; test-latest and test-oldest run it in their own venvs.
# Tests marked slow (each says why in its docstring: a stiff run, seconds of it) are left
# to `make test-slow`, which .ci/run runs after `make test`.
PYTEST_ARGS := -n auto -m 'not slow'

.PHONY: run test test-slow checks docs bench bench-check lock lock-keep test-latest test-oldest test-matrix clean mutate mutate-plan

# A venv with the lock's uv (hash-checked), installed by the venv's own pip.
define BOOTSTRAP_UV
test -x $(BIN)/python || $(PYTHON) -m venv $(VENV)
test -x $(BIN)/uv || { $(PYTHON) tools/lock.py pin uv > $(VENV)/uv-requirement.txt && \
	$(BIN)/python -m pip install --quiet --disable-pip-version-check --require-hashes \
	-r $(VENV)/uv-requirement.txt; }
endef

# The venv holds exactly the lock (hashes checked), then bodycheck itself, editable.
$(STAMP): pyproject.toml $(LOCK) requirements/tools.in
	$(PYTHON) tools/lock.py check
	$(BOOTSTRAP_UV)
	$(BIN)/uv pip sync --quiet --python $(BIN)/python --require-hashes $(LOCK)
	$(BIN)/uv pip install --quiet --python $(BIN)/python --no-deps --no-build-isolation -e .
	touch $(STAMP)

## make run: the main job, the whole catalogue
run: $(STAMP)
	$(BIN)/bodycheck check

## make test: lint, format check, type check and the whole test suite (in parallel, random order)
test: $(STAMP)
	$(BIN)/ruff check .
	$(BIN)/ruff format --check .
	$(BIN)/mypy
	$(BIN)/python -m pytest $(PYTEST_ARGS)

## make docs: the book's pages (bodycheck site) and, in their api/ folder, the API reference
## (Sphinx with numpydoc, docs/conf.py; warnings and broken references are errors): build/docs
docs: $(STAMP)
	$(BIN)/bodycheck site build/docs --api

## make test-slow: the tests marked slow (a long stiff run; CI runs them after make test)
test-slow: $(STAMP)
	$(BIN)/python -m pytest -n auto -m slow

## make checks: regenerate CHECKS.md from the registry, docs/scene-files.md from the schema,
## the checks' stored steps for the site (identities/data/derivations: runs every check) and
## notebooks/ from the lecture demos (a notebook is executed only when its cells changed)
checks: $(STAMP)
	$(BIN)/bodycheck catalogue --write CHECKS.md
	$(BIN)/bodycheck catalogue --derivations
	$(BIN)/bodycheck scene --schema > docs/scene-files.md
	$(BIN)/bodycheck notebooks --write notebooks

## make lock: re-resolve every dependency to the newest allowed versions and rewrite the lock
## (it works on a stale lock: only the lock's uv pin is read, to bootstrap uv)
lock:
	$(BOOTSTRAP_UV)
	$(PYTHON) tools/lock.py write $(BIN)/uv

## make lock-keep: rewrite the lock for changed inputs (a new extra, a new bound) keeping every
## pin of the current lock that still satisfies them; only the new requirements are resolved
lock-keep:
	$(BOOTSTRAP_UV)
	$(PYTHON) tools/lock.py write $(BIN)/uv --keep

## make test-latest: the suite on the newest versions pyproject allows (no lock), in .venv-latest
test-latest: $(STAMP)
	rm -rf .venv-latest
	$(PYTHON) -m venv .venv-latest
	$(BIN)/uv pip install --quiet --python .venv-latest/bin/python --upgrade -e '.[test]'
	.venv-latest/bin/python -m pip list --format=freeze 2>/dev/null | grep -iE '^(numpy|scipy|sympy|mpmath|hypothesis|matplotlib|pytest)=='
	.venv-latest/bin/python -m pytest $(PYTEST_ARGS) -p no:cacheprovider

## make test-matrix: the suite on every Python of requires-python found on this machine, each
## with the newest versions pyproject allows, in .venv-matrix/3.X (tools/matrix.py); an absent
## Python is skipped with a line
test-matrix: $(STAMP)
	$(PYTHON) tools/matrix.py --uv $(BIN)/uv --pytest-args "$(PYTEST_ARGS)" $(MATRIX)

## make test-oldest: the suite on the lowest versions pyproject allows (the engines' extras too), in .venv-oldest
test-oldest: $(STAMP)
	rm -rf .venv-oldest
	$(PYTHON) -m venv .venv-oldest
	$(BIN)/uv pip install --quiet --python .venv-oldest/bin/python --resolution lowest-direct -e '.[test,engines]'
	.venv-oldest/bin/python -m pip list --format=freeze 2>/dev/null | grep -iE '^(numpy|scipy|sympy|mpmath|hypothesis|matplotlib|pytest)=='
	.venv-oldest/bin/python -m pytest $(PYTEST_ARGS) -p no:cacheprovider

## make bench: time the kernels (pytest-benchmark, saved for --benchmark-compare), then
## the work-precision study (bodycheck bench: table, JSON and plots in bench-results/) and the
## roundoff study of the splittings, plain and compensated (bench/roundoff.py)
## make bench-check: the speed targets as ratios against scipy measured now, at quick sizes
## (bodycheck bench --check, ~3 s); fails naming each figure below its target (.ci/run runs it)
bench-check: $(STAMP)
	$(BIN)/bodycheck bench --check

bench: $(STAMP)
	$(BIN)/python -m pytest tests/benchmarks --benchmark-enable --benchmark-only \
		--benchmark-autosave --benchmark-columns=min,median,max,rounds -p no:randomly
	$(BIN)/bodycheck bench --out bench-results
	$(BIN)/python -m bench.roundoff --out bench-results

## make mutate MODULE=mechanics/rotation.py: mutation testing of one module against the tests
## that cover it (tools/mutation/modules.toml), one mutant at a time; prints the score, counting
## the reviewed equivalents of tools/mutation/equivalent.toml, and the survivors not listed
## (mutmut comes with the lock: the `mutation` extra)
MODULE ?= mechanics/rotation.py
MUTATE_ARGS ?=
mutate: $(STAMP)
	$(BIN)/python tools/mutation/run.py $(MODULE) --mutmut $(BIN)/mutmut --max-children 1 $(MUTATE_ARGS)

## make mutate-plan: every run of tools/mutation/plan.toml (the core modules in full, the rest as
## samples registered by committing the plan), one mutant per core at a time; prints each module's
## score and writes the table of docs/mutation.md from what it measured (--report: from the last runs)
mutate-plan: $(STAMP)
	$(BIN)/python tools/mutation/run.py --plan --mutmut $(BIN)/mutmut \
		--max-children $(shell nproc) $(MUTATE_ARGS)

clean:
	rm -rf $(VENV) .venv-latest .venv-oldest .venv-matrix .pytest_cache .hypothesis .benchmarks \
		.ruff_cache bench-results
