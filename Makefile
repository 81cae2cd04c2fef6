# SPDX-License-Identifier: MIT
# The two commands: `make` (main job on the built-in default scene) and
# `make test`. Every target installs what is missing first (scripts/setup.sh).
SHELL := /bin/bash
.DEFAULT_GOAL := all

JOBS       ?= 2
COORD_BITS ?= 16
DIR_BITS   ?= 16
SCENE      ?= teapot
SIZE       ?= 256
MODE       ?= conservative

BUILD := build/model
ENV   := scripts/venv-exec.sh
CLI   := $(BUILD)/pluecker
OUT   := out

# The main job's outputs and its report's width sweep.
MAIN_MODEL        = $(OUT)/$(SCENE)_model_$(COORD_BITS)x$(DIR_BITS)$(if $(filter nearest,$(MODE)),_nearest)
MAIN_RTL          = $(OUT)/$(SCENE)_rtl_$(COORD_BITS)x$(DIR_BITS)$(if $(filter nearest,$(MODE)),_nearest)
MAIN_SWEEP_SIZE   ?= 64
MAIN_SWEEP_WIDTHS ?= 8:24:4

# PLAN=FILE includes a plan file written by `make plan` (COORD_BITS := ..,
# or UNIT := local, BOX_BITS := .. when the plan chose the local unit),
# e.g. `make synth PLAN=out/plan.mk`; widths given on the command line
# still win. Its values reach every recipe expanded at run time.
ifdef PLAN
include $(PLAN)
endif

.PHONY: all setup build main test test-cpp test-tb lint contract bench clean

all: main

setup:
	@scripts/setup.sh

build: setup
	@mkdir -p build; cmake -S model -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE=$(CURDIR)/.venv/bin/python > $(BUILD).configure.log 2>&1 \
	  || { cat $(BUILD).configure.log; exit 1; }
	@cmake --build $(BUILD) -j$(JOBS)

# The main job: the golden-model render of SCENE with the fixed-point
# test, the same render with every box test answered by the Verilated RTL
# (sim-render, in the harness section), operands on the datapath's decision
# boundaries through the same RTL against the model (sim-boundary: a render
# alone cannot see an off-by-one in the margin), the renders' byte-for-
# byte comparison (fails loudly), and out/report/main.html, opened in
# headless Chromium (browser-check) before it is announced.
main: build
	@mkdir -p $(OUT)/report
	$(CLI) render --scene $(SCENE) --test fixed --coord-bits $(COORD_BITS) --dir-bits $(DIR_BITS) --mode $(MODE) \
	  --order dsa --size $(SIZE) --quiet --out $(MAIN_MODEL).png --stats $(MAIN_MODEL).json
	@$(MAKE) --no-print-directory sim-render SCENE=$(SCENE) COORD_BITS=$(COORD_BITS) DIR_BITS=$(DIR_BITS) \
	  MODE=$(MODE) SIM_SIZE=$(SIZE)
	@$(MAKE) --no-print-directory sim-boundary COORD_BITS=$(COORD_BITS) DIR_BITS=$(DIR_BITS) MODE=$(MODE)
	@$(ENV) python scripts/main_report.py --scene $(SCENE) --cli $(CLI) --jobs $(JOBS) \
	  --model-png $(MAIN_MODEL).png --model-json $(MAIN_MODEL).json --rtl-png $(MAIN_RTL).png \
	  --rtl-json $(MAIN_RTL).json --out $(OUT)/report/main.html \
	  --sweep-size $(MAIN_SWEEP_SIZE) --sweep-widths $(MAIN_SWEEP_WIDTHS)
	@$(MAKE) --no-print-directory browser-check PAGES=$(OUT)/report/main.html
	@if cmp $(MAIN_MODEL).png $(MAIN_RTL).png; then \
	  echo "main: PASS: the RTL render is bit-identical to the golden model's ($(MAIN_RTL).png)"; \
	  echo "main: report in $(OUT)/report/main.html"; \
	else \
	  echo "main: FAIL: the RTL render $(MAIN_RTL).png differs from the golden model's $(MAIN_MODEL).png" >&2; \
	  echo "main: see $(OUT)/report/main.html" >&2; exit 1; \
	fi

# The whole suite, as .ci/run runs it: C++ tests, lint, the pytest/cocotb
# suite, the C++ tests again under ASan + UBSan (test-sanitize), the
# formal proof of the handshake rules (formal) and a few seeded bugs that
# the tests must catch (mutate-smoke); the last three in sections below.
test: test-cpp lint test-tb test-sanitize formal mutate-smoke

test-cpp: build
	cd $(BUILD) && ctest --output-on-failure -j$(JOBS)

lint: setup
	$(ENV) scripts/lint.sh

# The port contract's generated files (rtl/pluecker_contract_pkg.sv, read by
# the RTL; rtl/pluecker_contract.json, read by scripts/contract.py), written
# from model/core/src/contract.cpp. The test Contract.GeneratedFilesAreCurrent
# fails until they are regenerated after a change of the contract.
contract: build
	$(CLI) contract --write rtl

test-tb: build
	PLUECKER_PY_DIR=$(CURDIR)/$(BUILD) $(ENV) python -m pytest -n $(JOBS) tb

# Benchmarks (print figures; not tests): the software model (build, traversal
# of every configuration, fixed point against float), the Verilator harness
# (SIM_N queries at COORD_BITS/DIR_BITS) and the cocotb bench for comparison.
# Software timings are the best of BENCH_REPEAT runs (the host is shared).
BENCH_COCOTB_N ?= 20000
BENCH_REPEAT ?= 3

bench: build
	$(BUILD)/pluecker_bench --repeat $(BENCH_REPEAT)
	@$(MAKE) --no-print-directory sim-bench
	$(ENV) python scripts/cocotb_bench.py --n $(BENCH_COCOTB_N) --coord-bits $(COORD_BITS) --dir-bits $(DIR_BITS) \
	  --py-dir $(BUILD)

clean:
	rm -rf build out

# ---- Verilator harness (sim/) ------------------------------------------------
# make sim         builds build/sim/<C>x<D>[_nearest]/pluecker_sim
# make sim-query   streams QUERIES (default: generated) through the RTL, --check
# make sim-render  hardware-in-the-loop render of SCENE at SIM_SIZE into out/
# make sim-bench   RTL throughput (queries per second)
# make sim-boundary  SIM_BOUNDARY_N operands on the decision boundaries (the
#                  margin's bound, the end and origin tests) through the RTL,
#                  --check against the model (part of the main job)
# make sim-array-render  the same render through an array of units (sim/array/,
#                  ARRAY_DSP + ARRAY_LUT lanes; its section below)
# Variables: COORD_BITS, DIR_BITS, MODE (conservative|nearest), SIM_TAG_BITS.
SIM_TAG_BITS ?= 8
SIM_SIZE     ?= $(SIZE)
SIM_N        ?= 2000000
SIM_BOUNDARY_N ?= 20000
SIM_DIR       = build/sim/$(COORD_BITS)x$(DIR_BITS)$(if $(filter nearest,$(MODE)),_nearest)
SIM_BIN       = $(SIM_DIR)/pluecker_sim
SIM_VARS      = COORD_BITS=$(COORD_BITS) DIR_BITS=$(DIR_BITS) MODE=$(MODE) SIM_TAG_BITS=$(SIM_TAG_BITS) \
                MODEL_BUILD=$(BUILD) SIM_JOBS=$(JOBS)

.PHONY: sim sim-query sim-render sim-bench sim-boundary sim-float sim-float-render

sim: build
	@$(SIM_VARS) $(ENV) sim/build.sh

sim-query: sim
	@if [ -n "$(QUERIES)" ]; then q="$(QUERIES)"; else \
	  q=$(SIM_DIR)/queries.txt; $(SIM_BIN) gen --n 20000 --kind mixed --out $$q; fi; \
	$(SIM_BIN) query --check $$q > $(SIM_DIR)/answers.txt && echo "sim-query: answers in $(SIM_DIR)/answers.txt"

sim-render: sim
	@mkdir -p $(OUT)
	$(SIM_BIN) render --scene $(SCENE) --size $(SIM_SIZE) --order dsa \
	  --out $(OUT)/$(SCENE)_rtl_$(notdir $(SIM_DIR)).png --stats $(OUT)/$(SCENE)_rtl_$(notdir $(SIM_DIR)).json

sim-bench: sim
	$(SIM_BIN) bench --n $(SIM_N)

sim-boundary: sim
	@q=$(SIM_DIR)/boundary.txt; $(SIM_BIN) gen --n $(SIM_BOUNDARY_N) --kind boundary --out $$q && \
	$(SIM_BIN) query --check $$q > $(SIM_DIR)/boundary.answers

# make sim-float   builds the harness of a binary32 unit (FLOAT_UNIT float|smits,
#                  FLOAT_MODE nearest|conservative, MUL_DSP) in
#                  build/sim/<unit>[_cons]_dsp<M>/ and checks FLOAT_N mixed
#                  queries through it against the model and exact_hit.
FLOAT_UNIT ?= float
FLOAT_MODE ?= nearest
FLOAT_N    ?= 200000

FLOAT_BUILD = SIM_UNIT=$(FLOAT_UNIT) MODE=$(FLOAT_MODE) SIM_MUL_DSP=$(MUL_DSP) MODEL_BUILD=$(BUILD) SIM_JOBS=$(JOBS) \
	  SIM_TAG_BITS=$(SIM_TAG_BITS) $(ENV) sim/build.sh | tail -1
FLOAT_TEST  = $(if $(filter smits,$(FLOAT_UNIT)),f32-smits,$(if $(filter conservative,$(FLOAT_MODE)),f32-pluecker-cons,f32-pluecker))

sim-float: build
	@bin=$$($(FLOAT_BUILD)) && echo "sim-float: $$bin" && \
	$$bin check --n $(FLOAT_N) --kind mixed --exact

# make sim-float-render  hardware-in-the-loop render of SCENE at SIM_SIZE through that unit,
#                        compared byte for byte with `pluecker render --test f32-...`
sim-float-render: build
	@bin=$$($(FLOAT_BUILD)) && d=$$(dirname $$bin) && \
	$$bin render --scene $(SCENE) --size $(SIM_SIZE) --out $$d/render_rtl.png --stats $$d/render_rtl.json && \
	$(BUILD)/pluecker render --test $(FLOAT_TEST) --scene $(SCENE) --size $(SIM_SIZE) --quiet \
	  --out $$d/render_model.png --stats $$d/render_model.json && \
	cmp $$d/render_rtl.png $$d/render_model.png && \
	echo "sim-float-render: $(FLOAT_TEST) RTL render identical to the model's ($$d/render_rtl.png)"
# ---- The array's harness (sim/array/) -----------------------------------------
# make sim-array         builds build/sim/array_<ARRAY_DSP>x<ARRAY_LUT>[x<ARRAY_ROM>]_<C>x<D>[_nearest][_p<P>]/
#                        pluecker_sim_array: rtl/pluecker_array.sv with ARRAY_DSP units on DSP
#                        multipliers, ARRAY_LUT in fabric (up to 17/17 bits) and ARRAY_ROM on block-RAM
#                        tables (6/6, SIM_PIPELINE=2), one lane each
# make sim-array-render  hardware-in-the-loop render of SCENE at SIM_SIZE, every batch spread over the
#                        lanes, compared byte for byte with `pluecker render --test fixed` at
#                        COORD_BITS/DIR_BITS (fails loudly when they differ)
# make sim-array-check   ARRAY_N queries and operands of every kind through all lanes with
#                        back-pressure, idle inputs and resets mid-stream, against the model
# Variables: ARRAY_DSP, ARRAY_LUT, ARRAY_ROM (default 1, 1, 0), COORD_BITS, DIR_BITS, MODE, SIM_TAG_BITS,
# SIM_PIPELINE (0; 1 or 2 add _p<P> to the build folder).
ARRAY_DSP     ?= 1
ARRAY_LUT     ?= 1
ARRAY_ROM     ?= 0
ARRAY_N       ?= 200000
ARRAY_SIM_DIR  = build/sim/array_$(ARRAY_DSP)x$(ARRAY_LUT)$(if $(filter-out 0,$(ARRAY_ROM)),x$(ARRAY_ROM))_$(COORD_BITS)x$(DIR_BITS)$(if \
                 $(filter nearest,$(MODE)),_nearest)$(if $(filter-out 0,$(SIM_PIPELINE)),_p$(SIM_PIPELINE))
ARRAY_SIM_BIN  = $(ARRAY_SIM_DIR)/pluecker_sim_array
ARRAY_SIM_VARS = SIM_UNIT=array ARRAY_DSP=$(ARRAY_DSP) ARRAY_LUT=$(ARRAY_LUT) ARRAY_ROM=$(ARRAY_ROM) COORD_BITS=$(COORD_BITS) \
                 DIR_BITS=$(DIR_BITS) MODE=$(MODE) SIM_TAG_BITS=$(SIM_TAG_BITS) SIM_PIPELINE=$(SIM_PIPELINE) \
                 MODEL_BUILD=$(BUILD) SIM_JOBS=$(JOBS) SIM_OUT=$(ARRAY_SIM_DIR)
ARRAY_OUT      = $(OUT)/$(SCENE)_$(notdir $(ARRAY_SIM_DIR))

.PHONY: sim-array sim-array-render sim-array-check

sim-array: build
	@$(ARRAY_SIM_VARS) $(ENV) sim/build.sh

sim-array-render: sim-array
	@mkdir -p $(OUT)
	$(ARRAY_SIM_BIN) render --scene $(SCENE) --size $(SIM_SIZE) --order dsa --quiet \
	  --out $(ARRAY_OUT)_rtl.png --stats $(ARRAY_OUT)_rtl.json
	$(CLI) render --scene $(SCENE) --size $(SIM_SIZE) --order dsa --quiet --test fixed --coord-bits $(COORD_BITS) \
	  --dir-bits $(DIR_BITS) --mode $(MODE) --out $(ARRAY_OUT)_model.png --stats $(ARRAY_OUT)_model.json
	@if cmp $(ARRAY_OUT)_model.png $(ARRAY_OUT)_rtl.png; then \
	  echo "sim-array-render: PASS: the array's render is bit-identical to the model's ($(ARRAY_OUT)_rtl.png)"; \
	else echo "sim-array-render: FAIL: $(ARRAY_OUT)_rtl.png differs from $(ARRAY_OUT)_model.png" >&2; exit 1; fi

sim-array-check: sim-array
	$(ARRAY_SIM_BIN) check --n $(ARRAY_N) --kind all --ready 0.5 --valid 0.8 --reset-every 1000

# ---- The cascade's harness (sim/cascade/) -------------------------------------
# make sim-cascade         builds build/sim/cascade_<CASCADE_N>_<NC>x<ND>_<WC>x<WD>[_p<P>]/pluecker_sim_cascade:
#                          rtl/pluecker_cascade.sv with CASCADE_N narrow TERNARY lanes at
#                          NARROW_COORD_BITS/NARROW_DIR_BITS and one wide unit at WIDE_COORD_BITS/WIDE_DIR_BITS
# make sim-cascade-render  hardware-in-the-loop render of SCENE at SIM_SIZE as `pluecker cascade` renders it,
#                          every batch set up in both formats and spread over the lanes: its answers
#                          (escalated count included) must equal `pluecker cascade`'s and its PNG the model's
#                          render on the wide format byte for byte (fails loudly otherwise)
# make sim-cascade-check   CASCADE_CHECK_N float queries of every kind through all lanes with back-pressure
#                          on every output stream, idle inputs and resets mid-stream, against the model
# Variables: CASCADE_N (2), NARROW_COORD_BITS/NARROW_DIR_BITS (8/8), WIDE_COORD_BITS/WIDE_DIR_BITS (16/16),
# SIM_TAG_BITS, SIM_PIPELINE (0); the cascade is conservative only.
CASCADE_N         ?= 2
NARROW_COORD_BITS ?= 8
NARROW_DIR_BITS   ?= 8
WIDE_COORD_BITS   ?= 16
WIDE_DIR_BITS     ?= 16
SIM_PIPELINE      ?= 0
CASCADE_CHECK_N   ?= 200000
CASCADE_NARROW     = $(NARROW_COORD_BITS)x$(NARROW_DIR_BITS)
CASCADE_WIDE       = $(WIDE_COORD_BITS)x$(WIDE_DIR_BITS)
CASCADE_SIM_DIR    = build/sim/cascade_$(CASCADE_N)_$(CASCADE_NARROW)_$(CASCADE_WIDE)$(if $(filter-out 0,$(SIM_PIPELINE)),_p$(SIM_PIPELINE))
CASCADE_SIM_BIN    = $(CASCADE_SIM_DIR)/pluecker_sim_cascade
CASCADE_SIM_VARS   = SIM_UNIT=cascade CASCADE_N=$(CASCADE_N) NARROW_COORD_BITS=$(NARROW_COORD_BITS) \
                     NARROW_DIR_BITS=$(NARROW_DIR_BITS) WIDE_COORD_BITS=$(WIDE_COORD_BITS) \
                     WIDE_DIR_BITS=$(WIDE_DIR_BITS) MODE=conservative SIM_TAG_BITS=$(SIM_TAG_BITS) \
                     SIM_PIPELINE=$(SIM_PIPELINE) MODEL_BUILD=$(BUILD) SIM_JOBS=$(JOBS) SIM_OUT=$(CASCADE_SIM_DIR)
CASCADE_OUT        = $(OUT)/$(SCENE)_$(notdir $(CASCADE_SIM_DIR))

.PHONY: sim-cascade sim-cascade-render sim-cascade-check

sim-cascade: build
	@$(CASCADE_SIM_VARS) $(ENV) sim/build.sh

sim-cascade-render: sim-cascade
	@mkdir -p $(OUT)
	$(CASCADE_SIM_BIN) render --scene $(SCENE) --size $(SIM_SIZE) --order dsa --quiet \
	  --out $(CASCADE_OUT)_rtl.png --stats $(CASCADE_OUT)_rtl.json
	$(CLI) cascade --scene $(SCENE) --size $(SIM_SIZE) --order dsa --quiet --narrow $(CASCADE_NARROW) \
	  --wide $(CASCADE_WIDE) --no-alone --threads $(JOBS) --json $(CASCADE_OUT)_model.json > /dev/null
	$(CLI) render --scene $(SCENE) --size $(SIM_SIZE) --order dsa --quiet --test fixed \
	  --coord-bits $(WIDE_COORD_BITS) --dir-bits $(WIDE_DIR_BITS) --out $(CASCADE_OUT)_model.png
	@$(ENV) python -c 'import json, sys; r, m = (json.load(open(f)) for f in sys.argv[1:]); \
	  a, b = r["cascade"]["answers"], m["narrow"][0]["answers"]; \
	  print("sim-cascade-render: %d of %d box queries escalated (model: %d)" % (a["escalated"], a["queries"], \
	        b["escalated"])); \
	  sys.exit(0 if a == b else "sim-cascade-render: FAIL: the cascade answers differ from pluecker cascade")' \
	  $(CASCADE_OUT)_rtl.json $(CASCADE_OUT)_model.json
	@if cmp $(CASCADE_OUT)_model.png $(CASCADE_OUT)_rtl.png; then \
	  echo "sim-cascade-render: PASS: the cascade's render is bit-identical to the model's ($(CASCADE_OUT)_rtl.png)"; \
	else echo "sim-cascade-render: FAIL: $(CASCADE_OUT)_rtl.png differs from $(CASCADE_OUT)_model.png" >&2; exit 1; fi

sim-cascade-check: sim-cascade
	$(CASCADE_SIM_BIN) check --n $(CASCADE_CHECK_N) --kind all --ready 0.5 --valid 0.8 --reset-every 1000

# ---- The local unit's harness (sim/local/) -----------------------------------
# make sim-local         builds build/sim/local_k<K>_d<D>_g<G>_c<C>[_nearest][_<style>]/pluecker_sim_local
# make sim-local-query   LOCAL_QUERIES (default: 20000 generated, mixed and boundary) through the
#                        local unit's RTL, each box in its tight frame, --check
# make sim-local-render  hardware-in-the-loop render of SCENE at SIM_SIZE, compared byte for byte
#                        with `pluecker render --test local` (fails loudly when they differ)
# make sim-local-bench   its throughput (queries per second)
# Variables: BOX_BITS, LOCAL_DIR_BITS (default BOX_BITS + 3), GRID_BITS, CHILDREN,
# LOCAL_MUL_STYLE (auto|dsp|lut), MODE, SIM_TAG_BITS.
BOX_BITS        ?= 8
LOCAL_DIR_BITS  ?= $(shell b=$(BOX_BITS); echo $$(( b + 3 > 24 ? 24 : b + 3 )))
GRID_BITS       ?= 32
CHILDREN        ?= 1
LOCAL_MUL_STYLE ?= auto
LOCAL_SIM_DIR    = build/sim/local_k$(BOX_BITS)_d$(LOCAL_DIR_BITS)_g$(GRID_BITS)_c$(CHILDREN)$(if $(filter nearest,$(MODE)),_nearest)$(if $(filter-out auto,$(LOCAL_MUL_STYLE)),_$(LOCAL_MUL_STYLE))
LOCAL_SIM_BIN    = $(LOCAL_SIM_DIR)/pluecker_sim_local
LOCAL_SIM_VARS   = SIM_UNIT=local BOX_BITS=$(BOX_BITS) DIR_BITS=$(LOCAL_DIR_BITS) GRID_BITS=$(GRID_BITS) \
                   CHILDREN=$(CHILDREN) MUL_STYLE=$(LOCAL_MUL_STYLE) MODE=$(MODE) SIM_TAG_BITS=$(SIM_TAG_BITS) \
                   MODEL_BUILD=$(BUILD) SIM_JOBS=$(JOBS) SIM_OUT=$(LOCAL_SIM_DIR)
LOCAL_OUT        = $(OUT)/$(SCENE)_$(notdir $(LOCAL_SIM_DIR))

.PHONY: sim-local sim-local-query sim-local-render sim-local-bench

sim-local: build
	@$(LOCAL_SIM_VARS) $(ENV) sim/build.sh

sim-local-query: sim-local
	@if [ -n "$(LOCAL_QUERIES)" ]; then q="$(LOCAL_QUERIES)"; else \
	  q=$(LOCAL_SIM_DIR)/queries.txt; $(LOCAL_SIM_BIN) gen --n 10000 --kind mixed --out $$q.mixed && \
	  $(LOCAL_SIM_BIN) gen --n 10000 --kind boundary --out $$q.boundary && cat $$q.mixed $$q.boundary > $$q; fi; \
	$(LOCAL_SIM_BIN) query --check $$q > $(LOCAL_SIM_DIR)/answers.txt && \
	  echo "sim-local-query: answers in $(LOCAL_SIM_DIR)/answers.txt"

sim-local-render: sim-local
	@mkdir -p $(OUT)
	$(LOCAL_SIM_BIN) render --scene $(SCENE) --size $(SIM_SIZE) --order dsa --quiet \
	  --out $(LOCAL_OUT)_rtl.png --stats $(LOCAL_OUT)_rtl.json
	$(CLI) render --scene $(SCENE) --size $(SIM_SIZE) --order dsa --quiet --test local --box-bits $(BOX_BITS) \
	  --dir-bits $(LOCAL_DIR_BITS) --grid-bits $(GRID_BITS) --mode $(MODE) \
	  --out $(LOCAL_OUT)_model.png --stats $(LOCAL_OUT)_model.json
	@if cmp $(LOCAL_OUT)_model.png $(LOCAL_OUT)_rtl.png; then \
	  echo "sim-local-render: PASS: the RTL render is bit-identical to the model's ($(LOCAL_OUT)_rtl.png)"; \
	else echo "sim-local-render: FAIL: $(LOCAL_OUT)_rtl.png differs from $(LOCAL_OUT)_model.png" >&2; exit 1; fi

sim-local-bench: sim-local
	$(LOCAL_SIM_BIN) bench --n $(SIM_N)

# ---- FPGA flow: ECP5 LFE5U-85F synthesis and place-and-route ---------------
# (scripts/synth.py, fpga/). Results per width pair in
# out/synth/<C>x<D>/summary.json. Extra flags: SYNTH_FLAGS=--no-pnr etc.
# UNIT=float|smits synthesises a binary32 unit instead (MUL_DSP=1|3|4,
# default the port contract's; CONSERVATIVE=1 for the conservative Plücker
# unit): out/synth/<unit>[_cons]_dsp<M>/summary.json. UNIT=local (as a plan
# file choosing the local unit sets it) runs synth-local instead.
# Every Yosys run and every nextpnr run (configurations x speeds x seeds)
# is a job (scripts/jobs.py): here, or on a Dask cluster with
# DASK_SCHEDULER=host:port. SEEDS: N (seeds 1..N) or a list such as 2,3.
SEEDS        ?= 3
SPEEDS       ?= 6 8
FREQ         ?= 250
SYNTH_FLAGS  ?=
UNIT         ?= fixed
MUL_DSP      ?=
CONSERVATIVE ?=

.PHONY: synth synth-smoke

synth: setup
ifeq ($(UNIT),local)
	@$(MAKE) --no-print-directory synth-local
else
	$(ENV) python scripts/synth.py --unit $(UNIT) $(if $(filter fixed,$(UNIT)),--coord-bits $(COORD_BITS) \
	  --dir-bits $(DIR_BITS)) $(if $(MUL_DSP),--mul-dsp $(MUL_DSP)) $(if $(CONSERVATIVE),--conservative $(CONSERVATIVE)) \
	  --seeds $(SEEDS) --speeds "$(SPEEDS)" --freq $(FREQ) --jobs $(JOBS) $(SYNTH_FLAGS)
endif

# make chip   a whole chip: pluecker_array of CHIP (NDSPxNLUT: units with
#             MULT18X18D x units with fabric multipliers; NDSPxNLUTxNROM adds
#             units with block-RAM tables, 6/6 PIPELINE=2) at COORD_BITS/DIR_BITS,
#             placed and routed on the LFE5U-85F (SEEDS, SPEEDS); the array's
#             own box tests per second beside the one-unit extrapolation of
#             out/synth/<C>x<D>/summary.json (make synth first). Results in
#             out/synth/array_<NDSP>x<NLUT>_<C>x<D>[_p<P>]_r3_fp/summary.json. A full chip
#             takes nextpnr minutes to an hour per seed and grade on 2 cores.
#             CASCADE=[M*]N:CxD:WCxWD places M pluecker_cascades instead (N
#             narrow TERNARY lanes at CxD, one wide unit at WCxWD each; e.g.
#             2:8x8:16x16, a few minutes, or a chip of them, 11*2:8x8:16x16;
#             CASCADE=[M*]N:CxD:WCxWD+W adds W plain wide units on the
#             MULT18X18D the cascades leave over, e.g. 4*2:8x8:16x16+9):
#             out/synth/cascade_[<M>x]<N>_<C>x<D>_<WC>x<WD>[_w<W>]/ (a chip of
#             them also against the one-cascade extrapolation: place it alone
#             first).
#             ROUTER: nextpnr's router for whole chips (router2 by default:
#             router1 did not converge on the 13x0 chip in 108 minutes,
#             router2 routed it in 17). PLACER: heap (analytical, the
#             default) or static (electrostatic: places the chips heap
#             stalls on, at a lower Fmax so far; fpga/TIMING.md). More
#             nextpnr options: SYNTH_FLAGS=--nextpnr-arg=--OPTION=VALUE,
#             synth_ecp5 options: SYNTH_FLAGS=--synth-flag=-nolutram
#             (output FIFOs in DP16KD block RAM: chips with fabric units).
#             With SYNTH_FLAGS=--nextpnr-arg=--tmg-ripup the router rips up
#             until every arc meets FREQ, so the Fmax is about FREQ: raise
#             FREQ until the run stops (a rip-up that cannot end is stopped
#             once its failing arcs have not fallen for 100 router
#             iterations and named failed; SYNTH_FLAGS=--ripup-patience=N,
#             0 waits forever). SYNTH_FLAGS=--place-first=K with SEEDS=N > K:
#             place all N seeds without routing, then route only the K
#             whose placement estimates the highest Fmax (summary.json:
#             placement_screen; saves time where routing is most of a run,
#             as on the fabric chips). The best recipe measured
#             for each chip, its Fmax and run time (4 to 26 minutes a
#             seed): README, "Where the whole chips stand"; every chip run
#             so far: fpga/CHIPS.md.
#             RST_STAGES: the reset tree, flops per unit (per cascade) in
#             front of its reset (3 by default; 0: one reset net for the
#             whole chip). FLOORPLAN: dsp (default: each unit's MULT18X18D
#             on consecutive sites, scripts/floorplan.py), grid (CHIP only:
#             as dsp, and each unit without MULT18X18D gets a region of a
#             grid over the die, four of its flip-flops pinned at the
#             region's centre) or none. Both add to the folder's name
#             (_r<K>, _fp or _grid). CLOCKS=2 (a mixed CHIP, or a
#             CASCADE chip with plain wide units, +W): the fabric units
#             (the plain wide units) on a clock of their own (target
#             FREQ_LUT, default FREQ), each kind at its own Fmax; box tests
#             per second NDSP x Fmax + NLUT x Fmax of the fabric clock, or
#             lanes x Fmax + W x Fmax of the plain units' clock (_clk2).
CHIP       ?= 13x0
CLOCKS     ?= 1
ROUTER     ?= router2
PLACER     ?= heap
PIPELINE   ?= 0
RST_STAGES ?= 3
FLOORPLAN  ?= dsp
.PHONY: chip
chip: setup
	$(ENV) python scripts/synth.py $(if $(CASCADE),--cascade '$(CASCADE)',--array $(CHIP) --coord-bits $(COORD_BITS) \
	  --dir-bits $(DIR_BITS)) --pipeline $(PIPELINE) --router $(ROUTER) --placer $(PLACER) --seeds $(SEEDS) --speeds "$(SPEEDS)" \
	  --rst-stages $(RST_STAGES) --floorplan $(FLOORPLAN) --freq $(FREQ) --jobs $(JOBS) \
	  $(if $(filter-out 1,$(CLOCKS)),--clocks $(CLOCKS) $(if $(FREQ_LUT),--freq-lut $(FREQ_LUT))) $(SYNTH_FLAGS)

# make chip-effective   each chip's useful box tests per second on every
#             scene (REPORT_SCENES, REPORT_SIZE): its raw rate / (1 + the
#             extra box tests of its answers), cascades also limited by
#             their wide units (scripts/chip_effective.py). CHIPS: summary
#             folders of placed chips (make chip) or of one unit / one
#             cascade (extrapolated); default every out/synth/array_* and
#             cascade_* summary. A minute or two at 128x128 (the dragon the
#             longest). Output: out/chip-effective/.
CHIPS ?= $(patsubst %/summary.json,%,$(wildcard $(OUT)/synth/array_*/summary.json $(OUT)/synth/cascade_*/summary.json))
.PHONY: chip-effective
chip-effective: build
	@test -n "$(strip $(CHIPS))" || { echo "chip-effective: no chip summary in $(OUT)/synth (make chip first, or give CHIPS=...)" >&2; exit 2; }
	$(ENV) python scripts/chip_effective.py --cli $(CLI) --scenes $(REPORT_SCENES) --size $(REPORT_SIZE) \
	  --jobs $(JOBS) --out $(OUT)/chip-effective $(CHIPS)

# Default widths, one seed, speed grade 8: a quick check that the RTL still
# synthesises, places and routes (out/synth-smoke/).
synth-smoke: setup
	$(ENV) python scripts/synth.py --smoke --freq $(FREQ) $(SYNTH_FLAGS)

# The local unit (out/synth/local_k<K>_d<D>_g<G>_c<C>[_<style>]/summary.json;
# SYNTH_LOCAL_PART=child: its child datapath alone). LOCAL_WIDTHS (KxDxG
# list) overrides BOX_BITS/LOCAL_DIR_BITS/GRID_BITS.
LOCAL_WIDTHS     ?= $(BOX_BITS)x$(LOCAL_DIR_BITS)x$(GRID_BITS)
SYNTH_LOCAL_PART ?= unit

.PHONY: synth-local

synth-local: setup
	$(ENV) python scripts/synth.py --local --local-widths $(LOCAL_WIDTHS) --children $(CHILDREN) \
	  --mul-style $(LOCAL_MUL_STYLE) --part $(SYNTH_LOCAL_PART) --seeds $(SEEDS) --speeds "$(SPEEDS)" \
	  --freq $(FREQ) --jobs $(JOBS) $(SYNTH_FLAGS)

# ---- Hostile input: fuzzing, sanitizers, the hostile-input table ------------
# (scripts/fuzz.sh, model/fuzz/,
# model/tests/test_hostile.cpp, scripts/hostile_table.py)
# make fuzz            libFuzzer targets of model/fuzz/ (clang, ASan + UBSan) in
#                      build/fuzz, FUZZ_SECONDS each; findings in build/fuzz/artifacts/
# make test-sanitize   the whole ctest suite built with ASan + UBSan (gcc) in
#                      build/sanitize; SANITIZE_CTEST_ARGS filters (e.g. -LE slow)
# make hostile-table   docs/hostile-input.md from real runs of the CLI
FUZZ_SECONDS        ?= 60
SANITIZE_BUILD      := build/sanitize
SANITIZE_CTEST_ARGS ?=

.PHONY: fuzz test-sanitize hostile-table

fuzz: setup
	FUZZ_SECONDS=$(FUZZ_SECONDS) FUZZ_JOBS=$(JOBS) scripts/fuzz.sh

test-sanitize: setup
	@mkdir -p build; start=$$(date +%s); \
	cmake -S model -B $(SANITIZE_BUILD) -DPLUECKER_SANITIZE=ON -DPLUECKER_PYTHON=OFF \
	  -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g" \
	  -DCMAKE_CXX_FLAGS="-fsanitize=float-cast-overflow" \
	  > $(SANITIZE_BUILD).configure.log 2>&1 || { cat $(SANITIZE_BUILD).configure.log; exit 1; }; \
	cmake --build $(SANITIZE_BUILD) -j$(JOBS) --target model_tests pluecker || exit 1; \
	built=$$(date +%s); \
	cd $(SANITIZE_BUILD) && \
	ASAN_OPTIONS=detect_leaks=1:check_initialization_order=1:strict_init_order=1 \
	LSAN_OPTIONS=suppressions=$(CURDIR)/model/fuzz/lsan.supp:print_suppressions=0 \
	UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	ctest --output-on-failure -j$(JOBS) $(SANITIZE_CTEST_ARGS); rc=$$?; \
	done=$$(date +%s); \
	echo "test-sanitize: build $$((built - start)) s, ctest $$((done - built)) s"; exit $$rc

hostile-table: build
	$(ENV) python scripts/hostile_table.py --cli $(CLI)

# ---- Width study, plan and report -------------------------------------------
# make report   speed-for-accuracy report of every scene (teapot, spheres,
#               ../shared/scenes/* when present) over REPORT_WIDTHS at
#               REPORT_SIZE: out/report/report.html + report.json. The
#               studies, harness builds and RTL checks are jobs
#               (scripts/jobs.py; DASK_SCHEDULER=host:port: on a cluster).
#               REPORT_SYNTH=1 runs `make synth` for widths not measured yet;
#               REPORT_RTL_WIDTHS: widths of the RTL vs model check;
#               REPORT_LOCAL: local-frame box widths K beside them (study
#               --local; the local unit's hardware from make synth-local).
# make plan     the narrowest widths whose extra box tests on SCENE stay within
#               MAX_EXTRA_WORK percent; writes PLAN_OUT (make variables).
#               PLAN_LOCAL=A:B (box widths K) also plans the local unit and
#               chooses the one with more effective box tests per second
#               per chip (both synthesised; else the global one, said so).
REPORT_WIDTHS     ?= 6:24:2
REPORT_SIZE       ?= 128
REPORT_SYNTH      ?= 0
REPORT_SCENES     ?= auto
REPORT_RTL_WIDTHS ?= 8 16 24
REPORT_RTL_SIZE   ?= 48
REPORT_LOCAL      ?= 8:12:2
MAX_EXTRA_WORK    ?= 1
PLAN_WIDTHS       ?= 6:24
PLAN_SIZE         ?= 128
PLAN_OUT          ?= $(OUT)/plan.mk
PLAN_LOCAL        ?=

.PHONY: report plan

report: build
	$(ENV) python scripts/report.py --cli $(CLI) --size $(REPORT_SIZE) --widths $(REPORT_WIDTHS) \
	  --scenes $(REPORT_SCENES) --synth $(REPORT_SYNTH) --rtl-widths "$(REPORT_RTL_WIDTHS)" \
	  --rtl-size $(REPORT_RTL_SIZE) --local "$(REPORT_LOCAL)" --jobs $(JOBS) --out $(OUT)/report
	@$(MAKE) --no-print-directory browser-check PAGES=$(OUT)/report/report.html

# make browser-check   opens PAGES (default: every out/report/*.html) in
#               headless Chromium (Debian's chromium, over the DevTools
#               pipe; no network): fails on an image that does not decode
#               (or a PNG that is not whole) and on a link to a missing file
#               or id; writes a full-page screenshot of each page to
#               out/report/screenshots/. About 5 s per page.
PAGES ?= $(wildcard $(OUT)/report/*.html)
.PHONY: browser-check
browser-check: setup
	@test -n "$(PAGES)" || { echo "browser-check: no pages (run make or make report first, or give PAGES=...)" >&2; exit 2; }
	@$(ENV) python scripts/browser_check.py $(PAGES) --shots $(OUT)/report/screenshots

plan: build
	@mkdir -p $(dir $(PLAN_OUT))
	$(CLI) plan --scene $(SCENE) --max-extra-work $(MAX_EXTRA_WORK) --widths $(PLAN_WIDTHS) \
	  --size $(PLAN_SIZE) --out $(PLAN_OUT) $(if $(PLAN_LOCAL),--local $(PLAN_LOCAL) --children $(CHILDREN))

# ---- Report tables and Embree peer ------------------------------------------
# make tables   the four tables of Mahovsky's 2005 report (box test, child
#               order, median vs SAH BVH, BVH vs K-D tree), every
#               configuration one after another on teapot, spheres,
#               ../shared/scenes/* when present and a synthetic scene of
#               TABLES_SYNTH triangles; TABLES_SIZE^2 renders, best of
#               TABLES_REPEAT, one thread. A benchmark, not a test (2-4
#               minutes on 2 shared cores at the defaults). Results in
#               out/tables/ (tables.json, tables.md, one PNG a scene).
#               TABLES_SCENES=a,b,... replaces the scene list.
# make peer     Embree 3 against our best configurations on the same rays
#               (installs libembree-dev with apt when missing and run as
#               root; otherwise says which command to run). Builds
#               build/peer with -DPLUECKER_PEER=ON; results in out/peer/.
#               PEER_SIZE^2 render rays + PEER_RANDOM random rays a scene
#               (about 6 minutes at the defaults, the build not counted).
#               docs/report-tables.md: how to read both, measured figures.
TABLES_SIZE   ?= 512
TABLES_REPEAT ?= 3
TABLES_SYNTH  ?= 4000000
TABLES_SCENES ?=
PEER_SIZE     ?= 1024
PEER_RANDOM   ?= 1000000
PEER_REPEAT   ?= 2
PEER_SCENES   ?=
PEER_BUILD    := build/peer

.PHONY: tables peer

tables: build
	$(BUILD)/pluecker_tables --size $(TABLES_SIZE) --repeat $(TABLES_REPEAT) --synthetic $(TABLES_SYNTH) \
	  --shared ../shared/scenes --out $(OUT)/tables $(if $(TABLES_SCENES),--scenes $(TABLES_SCENES))

peer: setup
	@mkdir -p build
	@if ! dpkg -s libembree-dev > /dev/null 2>&1; then \
	  if [ "$$(id -u)" = 0 ]; then \
	    echo "peer: installing libembree-dev"; \
	    DEBIAN_FRONTEND=noninteractive apt-get install -y libembree-dev > build/peer-apt.log 2>&1 \
	      || { apt-get update > /dev/null 2>&1 && DEBIAN_FRONTEND=noninteractive apt-get install -y libembree-dev \
	           > build/peer-apt.log 2>&1; } || { cat build/peer-apt.log; exit 1; }; \
	  else \
	    echo "peer: Embree 3 is missing; install it with: sudo apt-get install libembree-dev" >&2; exit 1; \
	  fi; \
	fi
	@cmake -S model -B $(PEER_BUILD) -DCMAKE_BUILD_TYPE=Release -DPLUECKER_PEER=ON -DPLUECKER_PYTHON=OFF \
	  > $(PEER_BUILD).configure.log 2>&1 || { cat $(PEER_BUILD).configure.log; exit 1; }
	@cmake --build $(PEER_BUILD) -j$(JOBS) --target pluecker_peer -- --no-print-directory
	$(PEER_BUILD)/pluecker_peer --size $(PEER_SIZE) --random $(PEER_RANDOM) --repeat $(PEER_REPEAT) \
	  --synthetic $(TABLES_SYNTH) --shared ../shared/scenes --out $(OUT)/peer $(if $(PEER_SCENES),--scenes $(PEER_SCENES))

# ---- Reliability: long regression and formal ----------------------------------
# (scripts/regress.py, fpga/formal/, tb/pluecker_intersector/test_stress.py,
# model/tests/test_extremes.cpp, model/tests/test_margin_bound.cpp; the short
# versions of all of them run in `make test`)
# make sim-regress  the long versions, as independent jobs (scripts/jobs.py:
#                   JOBS at a time here, or on the Dask cluster of
#                   DASK_SCHEDULER=host:port; a progress line per
#                   finished job): 1M extreme + 1M transformed queries
#                   through `fixed` at every width pair of {6,9,..,24}^2 and the
#                   margin's boundary suites (PLUECKER_LONG=1 model_tests),
#                   REGRESS_N extreme, set-up, decision-boundary and
#                   full-port-range queries through the Verilated RTL at
#                   REGRESS_WIDTHS (built with ASSERT_ON in build/regress/sim;
#                   zero mismatches against the model, zero false misses
#                   against exact for the float queries), the long cocotb stress bench (its
#                   sizes scale with REGRESS_N) and the long cocotb sweeps
#                   (PLUECKER_LONG=1: the intersector at every width pair of
#                   its sweep in both modes, the multipliers, the binary32
#                   units and their primitives; not yet timed at full size),
#                   and REGRESS_FLOAT_N queries through each binary32 unit's
#                   harness (extreme and random also against exact, raw bit
#                   patterns, operands around 2^-126). Summary in
#                   build/regress/summary.txt, every finished job's
#                   result in build/regress/jobs.jsonl. About 20 min on 2
#                   quiet cores, 45 min on loaded ones (model 3 min, RTL 8
#                   min with its builds, cocotb 7..35 min; timed before the
#                   split into jobs); REGRESS_N=20000 is a quick end-to-end
#                   check (13 min loaded, builds included).
#                   The local unit: 2.5 REGRESS_LOCAL_N queries (extreme,
#                   set-up, boundary, random) through its RTL at each of
#                   REGRESS_LOCAL_CONFIGS (KxDxG, c CHILDREN, n nearest), 10^7
#                   at the defaults, 0 mismatches and 0 false misses
#                   against exact; the local benches' long sweeps.
# make formal       SymbiYosys (YoWASP) + z3: unbounded proof (1-step
#                   k-induction) of the handshake and flow-control properties
#                   at 6/6, 6/6 PIPELINE=1, 6/18 and 18/18 (S2x stages 0, 1,
#                   1, 2; MUL_ADD 0, 0, 1, 2), cover at 6/6: about 2.5 CPU
#                   minutes, 5-6 min on 2 loaded cores (fpga/formal/README.md).
#                   Logs in build/formal/. Its seeded handshake bugs are
#                   among make mutate's.
# make mutate       seeded bugs (scripts/mutate.py: the RTL's margin, plane,
#                   end and origin tests, flow control, LATENCY +-1, the
#                   multipliers' signs, the model's set-up roundings and
#                   clip, planes per class, the port encoding, the formal
#                   harness's handshake bugs), each applied to a copy of the
#                   tree (build/mutate/tree) and run against the tests that
#                   must catch it, after a baseline run of those tests on the
#                   unmodified copy; prints mutant -> caught by -> time and
#                   fails when one survives. MUTANTS=a,b runs those only.
#                   16 min on 2 loaded cores with the copy's builds cached,
#                   about 35 min on the first run (README, Verification).
# make mutate-smoke the fast mutants (the RTL margin's +1 through the
#                   harness's boundary check, the model's segment-end
#                   rounding through its pinning test), in `make test`.
REGRESS_N      ?= 1000000
REGRESS_FLOAT_N ?= 10000000
REGRESS_WIDTHS ?= 6x6 9x15 16x16 20x8 22x22 23x23 24x24 16x16n 7x22n
REGRESS_LOCAL_N ?= 1000000
REGRESS_LOCAL_CONFIGS ?= 8x11x32c1 8x11x32c2 12x15x32c2 4x7x6c1

MUTANTS        ?=

.PHONY: sim-regress formal mutate mutate-smoke

sim-regress: build
	@MODEL_BUILD=$(BUILD) JOBS=$(JOBS) REGRESS_N=$(REGRESS_N) REGRESS_WIDTHS="$(REGRESS_WIDTHS)" \
	  REGRESS_FLOAT_N=$(REGRESS_FLOAT_N) \
	  REGRESS_LOCAL_N=$(REGRESS_LOCAL_N) REGRESS_LOCAL_CONFIGS="$(REGRESS_LOCAL_CONFIGS)" \
	  $(ENV) python scripts/regress.py

formal: setup
	@$(ENV) fpga/formal/run.sh

mutate: build
	@$(ENV) python scripts/mutate.py --jobs $(JOBS) --model-build $(BUILD) $(if $(MUTANTS),--only $(MUTANTS))

mutate-smoke: build
	@$(ENV) python scripts/mutate.py --smoke --jobs $(JOBS) --model-build $(BUILD)
