# Two commands for a fresh clone: `make demo` and `make test`.
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
STAMP  := $(VENV)/.installed
EMPS   := $(abspath ../shared/data/emps)
export VCNC_EMPS_DIR ?= $(if $(wildcard $(EMPS)/DATA_EMPS.mat),$(EMPS),)
export MPLBACKEND ?= Agg
# pytest-xdist workers for the test targets (one per core by default; 0 runs in this process)
PYTEST_WORKERS ?= auto

# LinuxCNC's interpreter tests (tests/interp, tests/ccomp) for tests/interpolators/test_linuxcnc_interp.py: from the
# linuxcnc source package Debian 12 ships, downloaded from Debian's archive, checked against the SHA-256 its .dsc
# gives, unpacked under .cache (never committed).
LINUXCNC_ORIG   := linuxcnc_2.9.0~pre1+git20230208.f1270d6ed7.orig.tar.xz
LINUXCNC_SHA256 := ac525d977c470edaab728feca30b079fbfb55d71a0495784dfcb7985a5fe1684
LINUXCNC_TESTS  := $(abspath .cache/linuxcnc-tests)
export VCNC_LINUXCNC_TESTS ?= $(LINUXCNC_TESTS)

.PHONY: demo test test-fast lint venv bench clean chromium

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip

$(STAMP): pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install --quiet -e '.[test]'
	touch $(STAMP)

venv: $(STAMP)

demo: $(STAMP)
	$(BIN)/vcnc demo

# The report test renders index.html in Debian's headless Chromium; install it when missing.
chromium:
	@command -v chromium >/dev/null 2>&1 || { apt-get update -qq && apt-get install -y -qq chromium >/dev/null; }

$(LINUXCNC_TESTS)/.unpacked:
	mkdir -p .cache
	curl -fsSL --retry 3 -o .cache/$(LINUXCNC_ORIG) 'http://deb.debian.org/debian/pool/main/l/linuxcnc/$(LINUXCNC_ORIG)'
	echo '$(LINUXCNC_SHA256)  .cache/$(LINUXCNC_ORIG)' | sha256sum -c --quiet -
	rm -rf $(LINUXCNC_TESTS) && mkdir -p $(LINUXCNC_TESTS)
	tar -xJf .cache/$(LINUXCNC_ORIG) -C $(LINUXCNC_TESTS) --strip-components=2 --wildcards '*/tests/interp/*' '*/tests/ccomp/*'
	rm .cache/$(LINUXCNC_ORIG)
	touch $@

test: $(STAMP) chromium $(LINUXCNC_TESTS)/.unpacked
	$(BIN)/ruff check .
	$(BIN)/lint-imports
	$(BIN)/python -m pytest -q -n $(PYTEST_WORKERS)

# The quick loop: everything but the end-to-end tests marked `slow` (`make test` runs them all).
test-fast: $(STAMP) $(LINUXCNC_TESTS)/.unpacked
	$(BIN)/ruff check .
	$(BIN)/lint-imports
	$(BIN)/python -m pytest -q -n $(PYTEST_WORKERS) -m "not slow"

bench: $(STAMP)
	for f in benchmarks/*.py; do echo "== $$f"; $(BIN)/python $$f || exit 1; done

clean:
	rm -rf $(VENV) build *.egg-info .pytest_cache vcnc-demo .cache
