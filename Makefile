# Vantage: two commands do all the set-up on a fresh Debian machine.
#   make demo   installs what it needs, builds, and runs the main job on the default scene
#   make test   installs what it needs, builds, and runs the quick suite (all but label `slow`)
#   make test-slow  the slow tests (scene oracles, renders, sweeps); CI runs both
#   make fuzz   builds the libFuzzer harnesses (clang) and runs each for FUZZ_SECONDS (docs/fuzzing.md)
#   make tsan   the parallel parts under ThreadSanitizer, against a TBB built with it (docs/fuzzing.md)
PRESET ?= release
BUILD_DIR := build/$(PRESET)
VANTAGE := $(BUILD_DIR)/apps/vantage/vantage
FUZZ_SECONDS ?= 60

.PHONY: all deps configure build demo test test-slow bench fuzz tsan format clean

all: build

deps:
	@scripts/install-deps.sh
	@scripts/fetch-models.sh
	@scripts/fetch-web.sh
	@scripts/fetch-mcap-writer.sh

configure: deps
	@cmake --preset $(PRESET) >/dev/null

build: configure
	@cmake --build --preset $(PRESET)

# The main job: explore the default table-top scene with the default method (latombe+surface: the
# surface model, its rates fitted online, ranked by travel), 10 scans.
demo: build
	@rm -rf results/demo
	$(VANTAGE) explore --out results/demo
	@echo "pictures: results/demo/unobserved.png, results/demo/map.png"

test: build
	@ctest --preset $(PRESET) --label-exclude slow

test-slow: build
	@ctest --preset $(PRESET) --label-regex slow

bench: build
	@$(BUILD_DIR)/bench/vantage_bench

# Each file reader under libFuzzer with ASan and UBSan for FUZZ_SECONDS; fails on any finding.
fuzz:
	@scripts/install-deps.sh fuzz
	@cmake --preset fuzz >/dev/null
	@cmake --build --preset fuzz
	@scripts/run-fuzzers.sh build/fuzz $(FUZZ_SECONDS)

# The tsan preset's tests, with libtbb built with -fsanitize=thread (scripts/build-tsan-tbb.sh).
tsan:
	@scripts/build-tsan-tbb.sh >/dev/null
	@cmake --preset tsan >/dev/null
	@cmake --build --preset tsan
	@ctest --preset tsan

format:
	@git ls-files '*.cpp' '*.hpp' | xargs clang-format -i

clean:
	rm -rf build
