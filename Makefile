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

BUILD := build/model
ENV   := scripts/venv-exec.sh
CLI   := $(BUILD)/pluecker
OUT   := out

.PHONY: all setup build main test test-cpp test-tb lint bench clean

all: main

setup:
	@scripts/setup.sh

build: setup
	@cmake -S model -B $(BUILD) -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE=$(CURDIR)/.venv/bin/python > $(BUILD).configure.log 2>&1 \
	  || { cat $(BUILD).configure.log; exit 1; }
	@cmake --build $(BUILD) -j$(JOBS)

# The main job: golden-model render of the default scene into out/.
main: build
	@mkdir -p $(OUT)
	$(CLI) render --scene $(SCENE) --test fixed --coord-bits $(COORD_BITS) --dir-bits $(DIR_BITS) \
	  --size $(SIZE) --out $(OUT)/$(SCENE)_fixed.png --stats $(OUT)/$(SCENE)_fixed.json
	$(CLI) render --scene $(SCENE) --test pluecker --order dsa \
	  --size $(SIZE) --out $(OUT)/$(SCENE)_pluecker.png --stats $(OUT)/$(SCENE)_pluecker.json
	@echo "main: images and statistics in $(OUT)/"

test: test-cpp lint test-tb

test-cpp: build
	cd $(BUILD) && ctest --output-on-failure -j$(JOBS)

lint: setup
	$(ENV) scripts/lint.sh

test-tb: build
	PLUECKER_PY_DIR=$(CURDIR)/$(BUILD) $(ENV) python -m pytest -n $(JOBS) tb

bench: build
	$(BUILD)/pluecker_bench

clean:
	rm -rf build out
