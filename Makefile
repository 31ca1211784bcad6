# Entry points. `make run` and `make test` do all set-up on a fresh Debian 12 machine (as root).
BUILD_DIR ?= build
BENCH_DIR ?= build-bench
JOBS ?= $(shell nproc)
WERROR ?= OFF
CMAKE_FLAGS ?=

SOURCES = $(shell git ls-files '*.cpp' '*.hpp' 2>/dev/null || find include src apps tests bench -name '*.[ch]pp')

.PHONY: all deps configure build run test bench format format-check lint clean

all: build

deps:
	./scripts/install-deps.sh

configure: deps
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release -DSCANTLING_WERROR=$(WERROR) $(CMAKE_FLAGS)

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

run: build
	./$(BUILD_DIR)/apps/scantling info $(BUILD_DIR)/example/room.pcd

test: build
	ctest --test-dir $(BUILD_DIR) --output-on-failure -j $(JOBS)

bench:
	./scripts/install-deps.sh --bench
	cmake -S . -B $(BENCH_DIR) -DCMAKE_BUILD_TYPE=Release -DSCANTLING_BUILD_BENCH=ON -DSCANTLING_BUILD_TESTS=OFF
	cmake --build $(BENCH_DIR) -j $(JOBS)
	./scripts/run-benchmarks.sh $(BENCH_DIR)

format:
	clang-format -i $(SOURCES)

format-check:
	clang-format --dry-run --Werror $(SOURCES)

lint: configure
	clang-tidy -p $(BUILD_DIR) --quiet $(filter %.cpp,$(SOURCES))

clean:
	rm -rf $(BUILD_DIR) $(BENCH_DIR)
