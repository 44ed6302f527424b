# Vantage: two commands do all the set-up on a fresh Debian machine.
#   make demo   installs what it needs, builds, and runs the main job on the default scene
#   make test   installs what it needs, builds, and runs the whole test suite
PRESET ?= release
BUILD_DIR := build/$(PRESET)
VANTAGE := $(BUILD_DIR)/apps/vantage/vantage

.PHONY: all deps configure build demo test bench format clean

all: build

deps:
	@scripts/install-deps.sh
	@scripts/fetch-models.sh
	@scripts/fetch-web.sh

configure: deps
	@cmake --preset $(PRESET) >/dev/null

build: configure
	@cmake --build --preset $(PRESET)

# The main job: explore the default table-top scene with the paper's method, 10 scans.
demo: build
	@rm -rf results/demo
	$(VANTAGE) explore --out results/demo
	@echo "pictures: results/demo/unobserved.png, results/demo/map.png"

test: build
	@ctest --preset $(PRESET)

bench: build
	@$(BUILD_DIR)/bench/vantage_bench

format:
	@git ls-files '*.cpp' '*.hpp' | xargs clang-format -i

clean:
	rm -rf build
