# Thin wrapper over CMake; the README's two commands are `make demo` and `make test`.
BUILD ?= build
JOBS ?= 2
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release

.PHONY: deps configure build demo test bench clean

deps:
	./scripts/install-deps

configure: deps
	cmake -S . -B $(BUILD) -G Ninja $(CMAKE_FLAGS)

build: configure
	cmake --build $(BUILD) --parallel $(JOBS)

# Main job (until the server lands): run the planar demo and print its summary.
demo: build
	$(BUILD)/server/rrlab run scenarios/01_planar7_obstacles.json

test: build
	ctest --test-dir $(BUILD) --output-on-failure --parallel $(JOBS)

bench: build
	$(BUILD)/bench/rrlab_bench

clean:
	rm -rf $(BUILD)
