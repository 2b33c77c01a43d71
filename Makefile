# Thin wrapper over CMake; the README's two commands are `make serve` and `make test`
# (every target: docs/cli.md, "Make targets"; the test targets: docs/testing.md).
BUILD ?= build
JOBS ?= 2
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release

# The sanitized build (clang, ASan + UBSan, with the fuzz targets) and the ThreadSanitizer build.
SANITIZE_BUILD ?= build-asan
TSAN_BUILD ?= build-tsan
FUZZ_SECONDS ?= 60
FUZZ_IDLE ?= 20
SANITIZE_FLAGS = -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" \
                 -DRRLAB_WEB_TESTS=OFF -DRRLAB_BUILD_BENCH=OFF -DRRLAB_PYTHON=OFF
# `make test` runs each test once, where it tells the most. These run against
# the Release build: the browser tests and the soak (they need its speed), the
# Dockerfile, docs and Slurm checks (they test no C++ of rrlab's), and the
# long paper reproductions (suites named ...Paper: the same code runs under
# the sanitizers in the methods' unit tests, in a fraction of the time) and
# the checks over many generated cases (...AtScale: 80 witnesses per family
# here and 1,000 under make test-scale, a method's defaults on tens; the same
# checks run on a few cases per family under the sanitizers), and the re-run of a slice of the committed
# benchmark and reproduction sweeps (their rows are the Release build's), and
# the Python package (PythonPackage: its module is built in Release only).
# Every other test (unit, HTTP, command line, Python client) runs against the
# ASan + UBSan build.
RELEASE_TESTS = ^(Web|Docker|Docs|Slurm|Soak|Benchmark|Package|PythonPackage|[A-Za-z]+Paper|[A-Za-z]+AtScale)\.
# What those need of the Release build (the benchmarks are built so they keep compiling).
RELEASE_TARGETS = rrlab rrlab_engine_tests rrlab_soak rrlab_bench rrlab_server_load rrlab_python
TIMED = ./scripts/timed

.PHONY: deps deps-serve configure configure-sanitize build serve demo test test-release-part test-sanitize \
        test-sanitize-part test-release test-web test-scale bench clean fuzz test-tsan python

deps:
	./scripts/install-deps

deps-serve:
	./scripts/install-deps --serve

# configure and build do not install: serve and test choose what they need
configure:
	cmake -S . -B $(BUILD) -G Ninja $(CMAKE_FLAGS)

build: configure
	cmake --build $(BUILD) --parallel $(JOBS)

# Main job: serve the dashboard and API on http://127.0.0.1:8080, runs in data/rrlab.db.
serve: deps-serve
	$(MAKE) build
	$(BUILD)/cli/rrlab serve --db data/rrlab.db

# One command-line run of the planar demo, printing its summary.
demo: deps-serve
	$(MAKE) build
	$(BUILD)/cli/rrlab run scenarios/01_planar7_obstacles.json

# Every test once (see RELEASE_TESTS): the Release part, then the sanitized
# part; screenshots of the browser tests in $(BUILD)/screenshots.
test: deps
	$(MAKE) test-release-part
	$(MAKE) test-sanitize-part

test-release-part: configure
	$(TIMED) "release build" cmake --build $(BUILD) --parallel $(JOBS) --target $(RELEASE_TARGETS)
	$(TIMED) "release tests" ctest --test-dir $(BUILD) --output-on-failure --parallel $(JOBS) -R '$(RELEASE_TESTS)'

# Unit, HTTP, command-line and Python tests built with ASan + UBSan (the HTTP
# tests start the sanitized rrlab); fails on any sanitizer report, in a test or
# in a server it started (reports go to $(SANITIZE_BUILD)/sanitizer-logs/).
test-sanitize: deps
	$(MAKE) test-sanitize-part

test-sanitize-part: configure-sanitize
	$(TIMED) "sanitized build" cmake --build $(SANITIZE_BUILD) --parallel $(JOBS)
	$(TIMED) "sanitized tests" ./.ci/sanitized-ctest $(SANITIZE_BUILD) -E '$(RELEASE_TESTS)'

configure-sanitize:
	CC=clang CXX=clang++ cmake -S . -B $(SANITIZE_BUILD) -G Ninja $(SANITIZE_FLAGS) \
	  -DRRLAB_SANITIZE=address,undefined -DRRLAB_FUZZ=ON

# Every test in the Release build alone (gcc only, no sanitizers): a quicker
# local check than `make test`, not a replacement for it.
test-release: deps
	$(MAKE) build
	ctest --test-dir $(BUILD) --output-on-failure --parallel $(JOBS)

# The long suites at full scale, outside CI (docs/testing.md, "What runs
# where"): the ...AtScale suites with every generated case (RRLAB_TEST_SCALE=full:
# 1,000 witnesses per family, 200 per URDF family) instead of make test's sample.
test-scale: deps
	$(MAKE) configure
	$(TIMED) "release build" cmake --build $(BUILD) --parallel $(JOBS) --target rrlab_engine_tests
	$(TIMED) "scale tests" env RRLAB_TEST_SCALE=full ctest --test-dir $(BUILD) --output-on-failure --parallel $(JOBS) -R 'AtScale\.'

# The browser tests alone.
test-web: deps
	$(MAKE) configure
	cmake --build $(BUILD) --parallel $(JOBS) --target rrlab
	ctest --test-dir $(BUILD) --output-on-failure -R '^Web\.'

# Every libFuzzer target of tests/fuzz, each until it finds no new coverage for
# FUZZ_IDLE s (default 20) or for FUZZ_SECONDS at most (two at a time), in the sanitized build.
fuzz: deps configure-sanitize
	$(TIMED) "fuzz build" cmake --build $(SANITIZE_BUILD) --parallel $(JOBS) --target rrlab_fuzz
	$(TIMED) "fuzzing" env FUZZ_IDLE=$(FUZZ_IDLE) ./tests/fuzz/run $(SANITIZE_BUILD) $(FUZZ_SECONDS)

# The server and storage tests (the concurrent parts) under ThreadSanitizer; fails on any report.
test-tsan: deps
	CC=clang CXX=clang++ cmake -S . -B $(TSAN_BUILD) -G Ninja $(SANITIZE_FLAGS) -DRRLAB_SANITIZE=thread
	$(TIMED) "tsan build" cmake --build $(TSAN_BUILD) --parallel $(JOBS) --target rrlab rrlab_server_tests rrlab_storage_tests
	$(TIMED) "tsan tests" ./.ci/sanitized-ctest $(TSAN_BUILD) -E 'NOT_BUILT|$(RELEASE_TESTS)'

# The rrlab Python package assembled in $(BUILD)/python (PYTHONPATH=$(BUILD)/python
# imports it); docs/python.md installs it with pip.
python: deps
	$(MAKE) configure
	cmake --build $(BUILD) --parallel $(JOBS) --target rrlab_python
	@echo "rrlab Python package in $(BUILD)/python: PYTHONPATH=$(BUILD)/python /usr/bin/python3, or pip install --no-build-isolation ./python"

bench: deps
	$(MAKE) build
	$(BUILD)/bench/rrlab_bench

clean:
	rm -rf $(BUILD) $(SANITIZE_BUILD) $(TSAN_BUILD)
