# Thin wrapper over CMake; the README's two commands are `make serve` and `make test`.
BUILD ?= build
JOBS ?= 2
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release

# The sanitized build (clang, ASan + UBSan, with the fuzz targets) and the ThreadSanitizer build.
SANITIZE_BUILD ?= build-asan
TSAN_BUILD ?= build-tsan
FUZZ_SECONDS ?= 60
SANITIZE_FLAGS = -DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" \
                 -DRRLAB_WEB_TESTS=OFF -DRRLAB_BUILD_BENCH=OFF
# Tests that do not run rrlab's code, or test something else than it: the
# browser (off in these builds), the Dockerfile, the docs, the Slurm cluster and
# the soak; and the long paper reproductions (suites named ...Paper), whose
# code the methods' own unit tests run under the sanitizers in a fraction of
# the time (under ASan they were two fifths of the sanitized suite's test time).
SANITIZE_SKIP = ^(Web|Docker|Docs|Slurm|Soak|[A-Za-z]+Paper)\.

.PHONY: deps deps-serve configure build serve demo test test-web bench clean test-sanitize fuzz test-tsan

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
	$(BUILD)/server/rrlab serve --db data/rrlab.db

# One command-line run of the planar demo, printing its summary.
demo: deps-serve
	$(MAKE) build
	$(BUILD)/server/rrlab run scenarios/01_planar7_obstacles.json

# Every test: unit, HTTP and the browser tests of the dashboard (screenshots in $(BUILD)/screenshots).
test: deps
	$(MAKE) build
	ctest --test-dir $(BUILD) --output-on-failure --parallel $(JOBS)

# The browser tests alone.
test-web: deps
	$(MAKE) build
	ctest --test-dir $(BUILD) --output-on-failure -R '^Web\.'

# Unit and HTTP tests built with ASan + UBSan (the HTTP tests start the
# sanitized rrlab); fails on any sanitizer report, in a test or in a server it
# started (reports go to $(SANITIZE_BUILD)/sanitizer-logs/).
test-sanitize: deps
	CC=clang CXX=clang++ cmake -S . -B $(SANITIZE_BUILD) -G Ninja $(SANITIZE_FLAGS) \
	  -DRRLAB_SANITIZE=address,undefined -DRRLAB_FUZZ=ON
	cmake --build $(SANITIZE_BUILD) --parallel $(JOBS)
	./.ci/sanitized-ctest $(SANITIZE_BUILD) -E '$(SANITIZE_SKIP)'

# Every libFuzzer target of tests/fuzz for FUZZ_SECONDS each (two at a time), in the sanitized build.
fuzz: deps
	CC=clang CXX=clang++ cmake -S . -B $(SANITIZE_BUILD) -G Ninja $(SANITIZE_FLAGS) \
	  -DRRLAB_SANITIZE=address,undefined -DRRLAB_FUZZ=ON
	cmake --build $(SANITIZE_BUILD) --parallel $(JOBS) --target rrlab_fuzz
	./tests/fuzz/run $(SANITIZE_BUILD) $(FUZZ_SECONDS)

# The server and storage tests (the concurrent parts) under ThreadSanitizer; fails on any report.
test-tsan: deps
	CC=clang CXX=clang++ cmake -S . -B $(TSAN_BUILD) -G Ninja $(SANITIZE_FLAGS) -DRRLAB_SANITIZE=thread
	cmake --build $(TSAN_BUILD) --parallel $(JOBS) --target rrlab rrlab_server_tests rrlab_storage_tests
	./.ci/sanitized-ctest $(TSAN_BUILD) -E 'NOT_BUILT|$(SANITIZE_SKIP)'

bench: deps
	$(MAKE) build
	$(BUILD)/bench/rrlab_bench

clean:
	rm -rf $(BUILD) $(SANITIZE_BUILD) $(TSAN_BUILD)
