# woundroll: set-up and everyday commands. Everything runs inside .venv.
PY ?= python3
VENV := .venv
BIN := $(VENV)/bin
STAMP := $(VENV)/.installed

.PHONY: demo test test-all lint bench docs records clean

$(BIN)/python:
	$(PY) -m venv $(VENV)
	$(BIN)/python -m pip install -q --upgrade pip

$(STAMP): pyproject.toml | $(BIN)/python
	$(BIN)/python -m pip install -q -e '.[test]'
	touch $(STAMP)

demo: $(STAMP)
	$(BIN)/python -c "from woundroll.winding import _kernels_aot as A; print('compiled winding kernels:', 'loaded' if A.load() else 'unavailable: numba loads them')"
	MPLBACKEND=Agg $(BIN)/woundroll run pet1-26.7N --out out/demo
	@echo "Figures and result.json written to out/demo/"

test: $(STAMP)
	@command -v chromium >/dev/null && command -v chromedriver >/dev/null || echo "note: chromium/chromedriver not installed: the browser tests (tests/web/test_browser.py) are SKIPPED (apt-get install chromium chromium-driver)"
	MPLBACKEND=Agg $(BIN)/python -m pytest -q

test-all: $(STAMP)
	MPLBACKEND=Agg $(BIN)/python -m pytest -q -m ''

lint: $(STAMP)
	$(BIN)/ruff check src tests benchmarks examples
	$(BIN)/ruff format --check src tests benchmarks examples

bench: $(STAMP)
	$(BIN)/python benchmarks/run_all.py

# the expensive studies' records (docs/data/*.json; hours on 2 cores), then the pages
records: $(STAMP)
	MPLBACKEND=Agg $(BIN)/python docs/scripts/records.py --all
	MPLBACKEND=Agg $(BIN)/python docs/scripts/regenerate.py

docs: $(STAMP)
	MPLBACKEND=Agg $(BIN)/python docs/scripts/regenerate.py

clean:
	rm -rf $(VENV) out .pytest_cache .ruff_cache
