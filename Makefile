# camlab: two commands on a fresh machine with only python3 and make.
#   make lab    set up .venv and open the course in JupyterLab (LAB_ARGS=--no-browser for headless)
#   make test   set up .venv with the test extra and run everything
PYTHON ?= python3
VENV   := .venv
BIN    := $(VENV)/bin
LAB_ARGS ?=
PYTEST_ARGS ?=

.PHONY: lab test test-fast bench bench-browser strip browser-deps clean

$(BIN)/python:
	$(PYTHON) -m venv $(VENV)
	$(BIN)/python -m pip install --quiet --upgrade pip

# (The distribution was called `camlab` before 0.1.0 became camlab-course: drop a stale one.)
$(VENV)/.installed-lab: pyproject.toml setup.py | $(BIN)/python
	@$(BIN)/python -m pip uninstall --quiet --yes camlab 2>/dev/null || true
	$(BIN)/python -m pip install --quiet -e .
	touch $@

$(VENV)/.installed-test: pyproject.toml setup.py | $(BIN)/python
	@$(BIN)/python -m pip uninstall --quiet --yes camlab 2>/dev/null || true
	$(BIN)/python -m pip install --quiet -e ".[test,class]"
	touch $(VENV)/.installed-lab $@

lab: $(VENV)/.installed-lab
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

# Unit, property, doctest, widget, exercise, lesson (nbval) and browser tests in one run.
test: $(VENV)/.installed-test browser-deps hub-deps site-deps
	$(BIN)/python -m pytest -n 2 --dist loadfile --nbval-lax $(PYTEST_ARGS)

# Everything but the notebooks and the browser: the quick loop while editing.
test-fast: $(VENV)/.installed-test
	$(BIN)/python -m pytest -n 2 --dist loadfile -m "not browser" camlab tests $(PYTEST_ARGS)

bench: $(VENV)/.installed-test
	$(BIN)/python benchmarks/run.py

# Slider keydown to changed canvas pixels in JupyterLab, headless Chromium, one demo per lesson.
bench-browser: $(VENV)/.installed-test browser-deps
	$(BIN)/python benchmarks/latency.py --browser

# Lessons are committed without outputs, execution counts or widget state.
strip: $(VENV)/.installed-lab
	$(BIN)/python tools/strip_notebooks.py lessons/*.ipynb

clean:
	rm -rf $(VENV) build *.egg-info

# Teaching a class (docs/teaching.md). Lecture mode: one lesson's demos without code, in Voila.
.PHONY: present
LESSON ?= 00
present: $(VENV)/.installed-test
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
class-load: $(VENV)/.installed-test hub-deps
	$(BIN)/python benchmarks/class_load.py --students $(N) $(if $(DRAG),--drag $(DRAG)) $(LESSONS)

# Binder's install step and the hub image's RUN steps (docs/teaching.md) in fresh venvs, then
# every lesson from a folder outside the repository. Minutes, not seconds: CI runs it.
.PHONY: test-binder
test-binder: $(VENV)/.installed-test
	CAMLAB_TEST_BINDER=1 $(BIN)/python -m pytest -p no:randomly tests/test_binder.py $(PYTEST_ARGS)

# The course as a static website in site/ (issue 17): every lesson executed, maths typeset
# by a local MathJax 3 from the npm registry (axe-core comes along for the accessibility test).
NPM_DIR := build/npm
.PHONY: site site-deps test-site
$(NPM_DIR)/.installed:
	npm install --prefix $(NPM_DIR) --no-audit --no-fund --no-save --silent mathjax@3.2.2 axe-core@4.10.3
	touch $@

site-deps: $(NPM_DIR)/.installed

site: $(VENV)/.installed-test site-deps
	$(BIN)/python tools/site/build.py site

# The site's own tests on the site just built (CI runs this after `make site`).
test-site: site browser-deps
	CAMLAB_SITE_DIR=site $(BIN)/python -m pytest -p no:randomly tests/test_site.py $(PYTEST_ARGS)
