# linkcli: set-up and everyday commands.  Every target installs what it needs
# into a local virtual environment, so they work on a fresh machine.
PYTHON ?= python3
VENV   ?= .venv
BIN     = $(VENV)/bin
EXAMPLE ?= mechanisms/padova-2020-02.yaml

.PHONY: run test check explore bench bench-full install clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip

# compileall: start-up stays fast even where Python is told not to write bytecode
$(VENV)/.installed: pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install --quiet -e '.[plot]'
	$(BIN)/python -m compileall -q linkcli
	touch $@

$(VENV)/.installed-test: pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install --quiet -e '.[test]'
	$(BIN)/python -m compileall -q linkcli
	touch $@

install: $(VENV)/.installed

## run: install and solve a shipped example
run: $(VENV)/.installed
	$(BIN)/linkcli solve $(EXAMPLE)

## test: install with test extras, run the test suite (on every core) and check every answer key;
## the keys are checked whatever the tests give, and the status fails if either fails
test: $(VENV)/.installed-test
	@tests=0; keys=0; \
	echo "$(BIN)/python -m pytest -n auto"; $(BIN)/python -m pytest -n auto || tests=$$?; \
	echo "$(BIN)/linkcli check mechanisms/"; $(BIN)/linkcli check mechanisms/ || keys=$$?; \
	echo "make test: test suite $$( [ $$tests -eq 0 ] && echo passed || echo "FAILED (exit $$tests)"), answer keys $$( [ $$keys -eq 0 ] && echo passed || echo "FAILED (exit $$keys)")"; \
	[ $$tests -eq 0 ] && [ $$keys -eq 0 ]

check: $(VENV)/.installed
	$(BIN)/linkcli check mechanisms/

## explore: the property tests of singular positions, the fuzzing, and the invariance of the
## answers: every shipped file turned, moved and scaled, in other units, orders and names,
## and solved by the closed form and by Newton over six turns on a fine grid both ways, with
## new random cases (`make test` runs them derandomized: the same cases every time)
explore: $(VENV)/.installed-test
	LINKCLI_EXPLORE=1 $(BIN)/python -m pytest -n auto tests/test_toggles.py tests/test_fuzz.py \
		tests/test_invariance_geometry.py tests/test_invariance_units.py \
		tests/test_invariance_names.py tests/test_invariance_method.py

## bench: speed against hand-written NumPy and pylinkage, and of linkcli's compiled loop
## (numba and pylinkage installed if PyPI is reachable) at 360 ... 10^7 positions, with
## accuracy and peak memory; where a call's time goes at 360; the periodic regime found directly
## against a hand-written solve_ivp of the transient, a machine's start-up against one of the
## start-up; parameter sweeps and design questions (tables and charts in benchmarks/out/; a
## few minutes)
bench: $(VENV)/.installed-test
	$(BIN)/python -m pip install --quiet pylinkage numba || echo "peers not installed: timed without them"
	$(BIN)/python benchmarks/speed.py
	$(BIN)/python benchmarks/overhead.py
	$(BIN)/python benchmarks/vibration.py
	$(BIN)/python benchmarks/regime.py
	$(BIN)/python benchmarks/questions.py
	$(BIN)/python benchmarks/machine_startup.py
	$(BIN)/python benchmarks/memory.py --quick

## bench-full: also every solver against a 50-digit reference and sweeps of 10^7 positions
bench-full: bench
	$(BIN)/python benchmarks/speed_accuracy.py
	$(BIN)/python benchmarks/memory.py

clean:
	rm -rf $(VENV) build *.egg-info .pytest_cache benchmarks/out
