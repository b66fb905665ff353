# fastnms: set-up, tests and demo. Every target that needs tools installs them first.
SHELL := bash
.SHELLFLAGS := -eu -o pipefail -c
.DEFAULT_GOAL := help

VENV    := .venv
PY      := $(VENV)/bin/python
STAMP   := $(VENV)/.installed
JOBS    ?= 2
PYTEST  := $(PY) -m pytest -n $(JOBS) --dist worksteal -q
# The demo: a 1920x1080 scene made from scikit-image's rocket.jpg (flows/demo/scene.py),
# or IMAGE=... for your own; both the OpenCV configuration and the paper's.
DEMO     := build/demo
IMAGE    ?= $(DEMO)/scene_1920x1080.png
DEMO_T   ?= 20

.PHONY: help setup demo test test-full sim golden-test synth-check synth-report lint clean \
	fusesoc-sim vivado-ip vivado-bd vivado-bd-needs-board vivado-ooc check-vivado synth bench regmap

help:
	@echo "make demo       the RTL (simulated) against the golden model and OpenCV on a 1920x1080 photograph, and its ORB descriptors matched to a rotated copy, writes $(DEMO)/*.png"
	@echo "make test       lint, golden tests, cocotb regression, synthesis checks"
	@echo "make test-full  the same plus the 'slow' cases"
	@echo "make sim        cocotb regression only"
	@echo "make lint       vsg (VHDL) and ruff (Python)"
	@echo "make synth-report  LUT/FF/BRAM and logic levels of the detector and core (yosys, xc7)"
	@echo "make synth      top and blocks, 3 configurations at 1920x1080, and the ORB top with its ORB stage and budget: yosys xc7 figures, ECP5 Fmax (nextpnr; the ORB rows on an LFE5U-85F) -> docs/results/synth.json, docs/results.md; rows cached by their inputs in build/synth/cache, ROWS=a,b* runs a subset"
	@echo "make bench      the AXI top in all 8 configurations on 3 photographs at 1920x1080 (fast engine, cocotb engine timed beside it), the ORB top at 2 budgets (every record against the golden), region-NMS memory, software timings -> build/bench/summary.json, docs/results/bench.json, docs/results.md (about 9 min)"
	@echo "make regmap     regenerate the register map files from rtl/top/fastnms_regs.toml"
	@echo "make fusesoc-sim  FuseSoC + GHDL smoke test of fastnms.core"
	@echo "make vivado-ip    package the Vivado IP into build/vivado/ip (needs Vivado)"
	@echo "make vivado-bd BOARD=zedboard|zc702|none  Zynq-7020 block design in build/vivado/zc7z20 (needs Vivado; BD_ARGS=--impl for the bitstream)"
	@echo "make vivado-ooc   out-of-context synthesis + implementation at 142.857 MHz (FCLK_CLK0), reports in build/vivado/ooc (needs Vivado)"

# ---- set-up ----------------------------------------------------------------
setup: $(STAMP) check-ghdl check-verilator

$(STAMP): pyproject.toml requirements.lock VERSION
	@python3 -c 'import sys; sys.exit(sys.version_info < (3, 11))' || { \
	  echo "make: Python >= 3.11 is needed, found $$(python3 --version 2>&1) (Debian 12 has it: apt-get install -y python3)"; exit 1; }
	@python3 -c 'import ensurepip, venv' 2>/dev/null || { \
	  if [ "$$(id -u)" = 0 ]; then apt-get update -qq && apt-get install -y -qq python3-venv; \
	  else echo "make: Python venv support is missing: run 'sudo apt-get install -y python3-venv'"; exit 1; fi; }
	python3 -m venv $(VENV)
	$(VENV)/bin/pip install -q --disable-pip-version-check -r requirements.lock
	$(VENV)/bin/pip install -q --disable-pip-version-check --no-deps --no-build-isolation -e .
	touch $@

.PHONY: check-ghdl
check-ghdl:
	@ver=$$(ghdl --version 2>/dev/null | sed -n '1s/^GHDL \([0-9]*\)\..*/\1/p'); \
	if [ -z "$$ver" ] || [ "$$ver" -lt 2 ]; then \
	  if [ "$$(id -u)" = 0 ]; then \
	    echo "make: installing GHDL with apt-get"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq ghdl >/dev/null; \
	  else echo "make: GHDL >= 2.0 is missing: run 'sudo apt-get install -y ghdl'"; exit 1; fi; \
	fi

# The fast simulation engine: Verilator and a C++ compiler (Debian 12: Verilator 5.006);
# Icarus Verilog runs the ORB units' GHDL netlists (tb/orb/test_orb_netlists.py).
.PHONY: check-verilator
check-verilator:
	@if ! command -v verilator >/dev/null || ! command -v g++ >/dev/null || ! command -v iverilog >/dev/null; then \
	  if [ "$$(id -u)" = 0 ]; then \
	    echo "make: installing Verilator, Icarus Verilog and g++ with apt-get"; \
	    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq verilator iverilog g++ make >/dev/null; \
	  else echo "make: Verilator, Icarus Verilog or g++ is missing: run 'sudo apt-get install -y verilator iverilog g++ make'"; exit 1; fi; \
	fi

# ---- the two README commands -------------------------------------------------
demo: setup
	@mkdir -p $(DEMO)
	@if [ "$(IMAGE)" = "$(DEMO)/scene_1920x1080.png" ]; then $(PY) -m flows.demo.scene $(IMAGE); fi
	$(VENV)/bin/fastnms compare "$(IMAGE)" -t $(DEMO_T) --score opencv --nms 3x3 \
	  --csv $(DEMO)/opencv_3x3.csv --png $(DEMO)/opencv_3x3.png
	$(VENV)/bin/fastnms compare "$(IMAGE)" -t $(DEMO_T) --score sad --nms region4 \
	  --csv $(DEMO)/paper_sad_region4.csv --png $(DEMO)/paper_sad_region4.png
	$(VENV)/bin/fastnms compare "$(IMAGE)" -t $(DEMO_T) --score opencv --nms 3x3 \
	  --cell 64 --per-cell 4 --csv $(DEMO)/opencv_3x3_budget.csv --png $(DEMO)/opencv_3x3_budget.png
	$(PY) -m flows.demo.orb_match "$(IMAGE)" $(DEMO)/orb_matches.png -t $(DEMO_T)
	@echo "wrote $(DEMO)/opencv_3x3.png, $(DEMO)/paper_sad_region4.png and $(DEMO)/opencv_3x3_budget.png (at most 4 per 64x64 cell) (+ .csv): the corners the RTL emitted; $(DEMO)/orb_matches.png: the RTL's ORB matches to a copy rotated 30 degrees"

test: setup lint
	$(PYTEST) -m "not slow" --durations=60

test-full: setup lint
	$(PYTEST)

# ---- pieces -----------------------------------------------------------------
sim: setup
	$(PYTEST) -m "not slow" tb

golden-test: setup
	$(PYTEST) -m "not slow" golden/tests

synth-check: setup
	$(PYTEST) -m "not slow" flows/synth/test_synth.py

# Resource and logic-depth figures (yosys synth_xilinx, xc7) of the detector,
# of the detector + 3x3 NMS and of the AXI top, both scores, at 1920 pixels.
synth-report: setup
	@for score in opencv sad; do \
	  $(PY) -m flows.synth.synth fastnms_fast_detector MAX_WIDTH=1920 SCORE=$$score; \
	  $(PY) -m flows.synth.synth fastnms_core MAX_WIDTH=1920 SCORE=$$score NMS=3x3; \
	  $(PY) -m flows.synth.axi_top MAX_WIDTH=1920 MAX_HEIGHT=1080 SCORE=$$score NMS=3x3; done

# The register map's generated files, from rtl/top/fastnms_regs.toml.
regmap: setup
	$(PY) -m flows.regmap.regmap

# Measured results (docs/results.md): each target rewrites its own section.
# make synth ROWS=fastnms_fifo-1920,fastnms_orb*: those rows only (names of summary.json's
# `config`, or glob patterns), the others kept from build/synth/cache or the last summary.
ROWS ?=
synth: setup
	$(PY) -m flows.synth.summary --jobs $(JOBS) $(if $(ROWS),--rows '$(ROWS)')

bench: setup
	$(PY) -m flows.bench.bench --jobs $(JOBS)

lint: setup
	$(VENV)/bin/ruff check --quiet .
	$(VENV)/bin/ruff format --check --quiet .
	@out=$$($(VENV)/bin/vsg --configuration vsg.yaml --all_phases -f rtl/*/*.vhd tb/vhdl/*.vhd tb/nms/vhdl/*.vhd sim/*.vhd 2>&1) || \
	  { echo "$$out"; echo "make: vsg found style errors (fix with: $(VENV)/bin/vsg -c vsg.yaml --fix -f FILE)"; exit 1; }
	@echo "lint: ruff and vsg clean"

# ---- FuseSoC and Vivado ----------------------------------------------------
fusesoc-sim: setup
	$(VENV)/bin/fusesoc --cores-root . run --work-root build/fusesoc/sim --target sim ::fastnms:0.2.0

# Vivado is not installed by `make setup`: it must be on PATH (settings64.sh).
VIVADO   ?= vivado
BOARD    ?=
BD_ARGS  ?=
OOC_ARGS ?=
VIVADO_BATCH = $(VIVADO) -mode batch -nojournal -nolog

check-vivado:
	@command -v $(VIVADO) >/dev/null || { echo "make: Vivado is not on PATH (source <Vivado>/settings64.sh)"; exit 1; }

vivado-ip: check-vivado
	$(VIVADO_BATCH) -source vivado/package_ip.tcl

# BOARD is required (no default: Vivado 2022.1+ has ZC702's board files but not ZedBoard's).
vivado-bd: $(if $(BOARD),,vivado-bd-needs-board) vivado-ip
	$(VIVADO_BATCH) -source vivado/create_bd_zc7z20.tcl -tclargs --board $(BOARD) $(BD_ARGS)

vivado-bd-needs-board:
	@echo "make: vivado-bd needs BOARD=zedboard, BOARD=zc702 or BOARD=none (see vivado/README.md)"; exit 1

vivado-ooc: check-vivado
	$(VIVADO_BATCH) -source vivado/synth_ooc.tcl $(if $(OOC_ARGS),-tclargs $(OOC_ARGS))

clean:
	rm -rf build sim_build .pytest_cache .ruff_cache
