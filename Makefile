# Thin wrapper over CMake; the README's two commands are `make serve` and `make test`.
BUILD ?= build
JOBS ?= 2
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release

.PHONY: deps deps-serve configure build serve demo test test-web bench clean

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

bench: deps
	$(MAKE) build
	$(BUILD)/bench/rrlab_bench

clean:
	rm -rf $(BUILD)
