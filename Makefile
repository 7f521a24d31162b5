# camlab: two commands on a fresh machine with only python3 and make.
#   make lab    set up .venv and open the course in JupyterLab (LAB_ARGS=--no-browser for headless)
#   make test   set up .venv with the test extra and run everything
# LOCKED=1 installs the exact versions of requirements/lock.txt (the environment for a class).
PYTHON ?= python3
# One BLAS thread per process: the tests run two pytest workers (and their notebook kernels) on
# two cores, and OpenBLAS's own threads on top oversubscribe them (J^T J of a 12000 x 40
# Jacobian measured 1.4 ms on one thread, 186 ms on two, under load). The course's matrices are
# small: one thread loses nothing in the lab either. Set them in the shell to override.
export OPENBLAS_NUM_THREADS ?= 1
export OMP_NUM_THREADS ?= 1
VENV   := .venv
BIN    := $(VENV)/bin
UV     := $(BIN)/uv
LAB_ARGS ?=
PYTEST_ARGS ?=
LOCKED ?=
LOCK   := requirements/lock.txt
PIN    := $(if $(LOCKED),-c $(LOCK),)
STAMP  := $(if $(LOCKED),-locked,)
# installing one flavour (locked or not) invalidates the other's stamps
OTHER_STAMPS := $(if $(LOCKED),$(VENV)/.installed-lab $(VENV)/.installed-test,$(VENV)/.installed-lab-locked $(VENV)/.installed-test-locked)

.PHONY: lab test test-browser test-fast test-wheel test-oldest lint format lock binder-link bench bench-browser strip browser-deps clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip

# (The distribution was called `camlab` before 0.1.0 became camlab-course: drop a stale one.)
$(VENV)/.installed-lab$(STAMP): pyproject.toml setup.py $(LOCK) | $(BIN)/python
	@$(BIN)/python -m pip uninstall --quiet --yes camlab 2>/dev/null || true
	$(BIN)/python -m pip install --quiet -e . $(PIN)
	rm -f $(OTHER_STAMPS)
	touch $@

$(VENV)/.installed-test$(STAMP): pyproject.toml setup.py $(LOCK) | $(BIN)/python
	@$(BIN)/python -m pip uninstall --quiet --yes camlab 2>/dev/null || true
	$(BIN)/python -m pip install --quiet -e ".[test,class]" $(PIN)
	rm -f $(OTHER_STAMPS)
	touch $(VENV)/.installed-lab$(STAMP) $@

lab: $(VENV)/.installed-lab$(STAMP)
	$(BIN)/jupyter lab lessons/00_start_here.ipynb $(LAB_ARGS)

# Debian's chromium serves the browser test; never `playwright install` (it downloads).
browser-deps:
	@command -v chromium >/dev/null 2>&1 || [ -x /usr/bin/chromium ] || { \
	  if [ "$$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then \
	    echo "installing Debian chromium for the browser test"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null; \
	  else \
	    echo "chromium is missing: install it (apt-get install chromium) or set CAMLAB_SKIP_BROWSER=1"; \
	  fi; }

# Unit, property, doctest, widget, exercise, lesson (nbval), hub and one real-browser test in one
# run, about 11 minutes on 2 cores. The long Chromium suites (test-browser) and the website's tests
# (test-site) are their own targets: together they doubled this one. `.ci/run` runs all three.
QUICK_MARKS := not long_browser and not site
test: $(VENV)/.installed-test$(STAMP) browser-deps hub-deps
	$(BIN)/python -m pytest -n 2 --dist loadfile --nbval-lax -m "$(QUICK_MARKS)" $(PYTEST_ARGS)

# Every browser-drawn demo's keydown and picture, the drags, lecture mode, the upload, and every
# demo's fit at 1400 px: JupyterLab and Voila in headless Chromium.
test-browser: $(VENV)/.installed-test$(STAMP) browser-deps site-deps
	$(BIN)/python -m pytest -n 2 --dist loadfile -m long_browser tests $(PYTEST_ARGS)

# Everything but the notebooks and the browser: the quick loop while editing.
test-fast: $(VENV)/.installed-test$(STAMP)
	$(BIN)/python -m pytest -n 2 --dist loadfile -m "not browser" camlab tests $(PYTEST_ARGS)

# The installed course: build the wheel and sdist, check they carry lessons, data, licences
# and py.typed (tools/check_dist.py), install the wheel (not editable) into a fresh venv, and
# from an unrelated temporary folder copy the lessons (`camlab lessons`) and run every one.
# WHEEL_PYTHON picks the interpreter of that venv (test-py3NN sets it).
WHEEL_VENV ?= build/venv-wheel
WHEEL_PYTHON ?= $(BIN)/python
test-wheel: $(VENV)/.installed-test$(STAMP)
	rm -rf dist $(WHEEL_VENV) && mkdir -p build
	$(BIN)/python -m build --outdir dist . > build/build.log 2>&1 || { cat build/build.log; exit 1; }
	$(BIN)/python tools/check_dist.py dist
	$(UV) venv --quiet --no-python-downloads --python $(WHEEL_PYTHON) $(WHEEL_VENV)
	$(UV) pip install --quiet --python $(WHEEL_VENV)/bin/python dist/*.whl nbval pytest pytest-xdist pytest-timeout $(PIN)
	$(call run-lessons-outside,$(WHEEL_VENV))

# $(call run-lessons-outside,VENV): from an unrelated temporary folder, copy the lessons with
# VENV's `camlab lessons` and run every one with nbval against VENV's installed camlab.
define run-lessons-outside
	@set -e; here=$$(pwd); work=$$(mktemp -d); trap 'rm -rf "$$work"' EXIT; cd "$$work"; \
	  "$$here/$(1)/bin/camlab" --version; "$$here/$(1)/bin/camlab" lessons course; cd course; \
	  "$$here/$(1)/bin/python" -c "import camlab; assert camlab.__file__.startswith('$$here/$(1)/'), camlab.__file__"; \
	  "$$here/$(1)/bin/python" -m pytest -p no:cacheprovider -n 2 --dist loadfile --timeout 300 --nbval-lax --nbval-current-env lessons
endef

# test-wheel on another CPython, found as python3.NN on PATH (pyenv's shims) or in ~/.pyenv:
# `make test-py312`, `make test-py313` (both in CI). Fails, naming what it looked for, where it is missing.
test-py3%:
	@py=; for c in $$(command -v python3.$*) $$(ls -d $$HOME/.pyenv/versions/3.$*.*/bin/python3.$* 2>/dev/null | sort -rV); do \
	  if "$$c" -c pass 2>/dev/null; then py=$$c; break; fi; done; \
	[ -n "$$py" ] || { echo "$@: no working CPython 3.$* (looked for python3.$* on PATH and in" \
	  "~/.pyenv/versions/3.$*.*): install it (pyenv install 3.$*, or apt-get install python3.$*)" >&2; exit 1; }; \
	echo "$@: $$py ($$("$$py" -V))"; \
	$(MAKE) --no-print-directory test-wheel WHEEL_PYTHON="$$py" WHEEL_VENV=build/venv-py3$*

# The lowest versions pyproject.toml declares (requirements/oldest.txt pins them; a test keeps
# the two in step): the fast tests plus three lessons, in their own venv. The class extra
# (nbgrader, voila) needs JupyterLab >= 4.2, so its tests, like the hub, Binder and site tests
# (their own installs and builds), run only in the newest environment. So does the live-frame
# comparison (tests/test_live_frames.py): its list of known differences is measured with the
# newest matplotlib; 3.9.4 draws three more demos differently (disparity_depth, full_panorama,
# parallax_ghosting, 0.1-0.3 % of pixels), which issues 28/29 triage with the others.
OLDEST_VENV := .venv-oldest
OLDEST_LESSONS := lessons/00_start_here.ipynb lessons/07_homographies.ipynb lessons/09_image_stitching.ipynb lessons/11_stereo_rectification.ipynb
$(OLDEST_VENV)/.installed: pyproject.toml setup.py requirements/oldest.txt | $(VENV)/.installed-test$(STAMP)
	rm -rf $(OLDEST_VENV)
	$(UV) venv --quiet --python $(BIN)/python $(OLDEST_VENV)
	$(UV) pip install --quiet --python $(OLDEST_VENV)/bin/python -e ".[test]" -c requirements/oldest.txt
	touch $@

test-oldest: $(OLDEST_VENV)/.installed
	$(OLDEST_VENV)/bin/python -m pytest -n 2 -m "not browser" --nbval-lax camlab tests $(OLDEST_LESSONS) \
	  --ignore=camlab/classroom --ignore=tests/test_present.py --ignore=tests/test_assignments.py \
	  --ignore=tests/test_hub.py --ignore=tests/test_binder.py --ignore=tests/test_site.py \
	  --ignore=tests/test_live_frames.py $(PYTEST_ARGS)

# pyflakes rules (unused imports, undefined names, ...): configured in pyproject.toml.
lint: $(VENV)/.installed-test$(STAMP)
	$(BIN)/ruff check .
	$(BIN)/ruff format --check .

# Lay out every Python file the way `make lint` checks (ruff's formatter; lessons are notebooks)
format: $(VENV)/.installed-test$(STAMP)
	$(BIN)/ruff format .

# Re-pin both locks from pyproject.toml, for Python 3.11 on every platform: requirements/lock.txt
# with every extra (CI, developers, instructors: LOCKED=1) and requirements/students.txt with
# none (what Binder and hub/Dockerfile install: the course and JupyterLab). The students' lock is
# resolved within the full one (-c), so a package in both has one version (tests/test_package.py).
STUDENTS_LOCK := requirements/students.txt
COMPILE := $(UV) pip compile pyproject.toml --universal --python-version 3.11 --quiet --no-header \
  --custom-compile-command "make lock"
lock: $(VENV)/.installed-test$(STAMP)
	$(COMPILE) --all-extras -o $(LOCK)
	$(COMPILE) -c $(LOCK) --annotation-style line -o $(STUDENTS_LOCK)

# The Binder link and README badge for this clone's GitHub remote (origin; REMOTE=upstream for another).
REMOTE ?= origin
binder-link:
	@$(PYTHON) tools/binder_link.py $(REMOTE)

bench: $(VENV)/.installed-test$(STAMP) browser-deps
	$(BIN)/python benchmarks/run.py

# Slider keydown to changed canvas pixels in JupyterLab, headless Chromium, one demo per lesson.
bench-browser: $(VENV)/.installed-test$(STAMP) browser-deps
	$(BIN)/python benchmarks/browser_latency.py

# Lessons are committed without outputs, execution counts or widget state.
strip: $(VENV)/.installed-lab$(STAMP)
	$(BIN)/python tools/strip_notebooks.py lessons/*.ipynb

clean:
	rm -rf $(VENV) $(OLDEST_VENV) build dist *.egg-info

# Teaching a class (docs/teaching.md). Lecture mode: one lesson's demos without code, in Voila.
.PHONY: present
LESSON ?= 00
present: $(VENV)/.installed-test$(STAMP)
	$(BIN)/camlab present $(LESSON)

# configurable-http-proxy (npm registry) for the JupyterHub test, in a local prefix.
CHP := $(VENV)/chp/node_modules/.bin/configurable-http-proxy
.PHONY: hub-deps class-load
hub-deps: $(CHP)
$(CHP): | $(BIN)/python
	npm install --prefix $(VENV)/chp --no-audit --no-fund --loglevel=error configurable-http-proxy@5

# A real hub with N students running lessons at once; prints the sizing table (docs/teaching.md).
N ?= 8
LESSONS ?=
DRAG ?= transformation_hierarchy
class-load: $(VENV)/.installed-test$(STAMP) hub-deps
	$(BIN)/python benchmarks/class_load.py --students $(N) $(if $(DRAG),--drag $(DRAG)) $(LESSONS)

# Binder's install step (read from repo2docker's Dockerfile) into a fresh venv and the hub
# image's RUN steps (hub/Dockerfile) into another, then every lesson from a folder outside
# the repository against the Binder venv. Minutes, not seconds: CI runs it.
BINDER_VENV := build/venv-binder
.PHONY: test-binder
test-binder: $(VENV)/.installed-test$(STAMP)
	rm -rf $(BINDER_VENV) && mkdir -p build
	CAMLAB_TEST_BINDER=1 CAMLAB_BINDER_VENV=$(BINDER_VENV) $(BIN)/python -m pytest -p no:randomly tests/test_binder.py $(PYTEST_ARGS)
	$(UV) pip install --quiet --python $(BINDER_VENV)/bin/python nbval pytest pytest-xdist pytest-timeout $(PIN)
	$(call run-lessons-outside,$(BINDER_VENV))

# The course as a static website in site/ (issue 17): every lesson executed, maths typeset
# by a local MathJax 3 from the npm registry (axe-core comes along for the accessibility test).
NPM_DIR := build/npm
.PHONY: site site-deps test-site
$(NPM_DIR)/.installed:
	npm install --prefix $(NPM_DIR) --no-audit --no-fund --no-save --silent mathjax@3.2.2 axe-core@4.10.3
	touch $@

site-deps: $(NPM_DIR)/.installed

site: $(VENV)/.installed-test$(STAMP) site-deps
	$(BIN)/python tools/site/build.py site

# The course website built (every lesson executed, a few minutes), then its own tests.
test-site: site browser-deps
	CAMLAB_SITE_DIR=site $(BIN)/python -m pytest -p no:randomly tests/test_site.py $(PYTEST_ARGS)
