# Thin wrapper over CMake; the README's two commands are `make serve` and `make test`.
BUILD ?= build
JOBS ?= 2
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release

.PHONY: deps configure build serve demo test test-web bench clean

deps:
	./scripts/install-deps

configure: deps
	cmake -S . -B $(BUILD) -G Ninja $(CMAKE_FLAGS)

build: configure
	cmake --build $(BUILD) --parallel $(JOBS)

# Main job: serve the dashboard and API on http://127.0.0.1:8080, runs in data/rrlab.db.
serve: build
	$(BUILD)/server/rrlab serve --db data/rrlab.db

# One command-line run of the planar demo, printing its summary.
demo: build
	$(BUILD)/server/rrlab run scenarios/01_planar7_obstacles.json

test: build
	ctest --test-dir $(BUILD) --output-on-failure --parallel $(JOBS)

# Browser test of the dashboard: Debian's chromium + playwright-core from npm (opt-in).
test-web:
	./scripts/install-deps --web
	cmake -S . -B $(BUILD) -G Ninja $(CMAKE_FLAGS) -DRRLAB_WEB_TESTS=ON
	cmake --build $(BUILD) --parallel $(JOBS)
	ctest --test-dir $(BUILD) --output-on-failure -R '^Web\.'

bench: build
	$(BUILD)/bench/rrlab_bench

clean:
	rm -rf $(BUILD)
