# Entry points. `make run` and `make test` do all set-up on a fresh Debian 12 machine (as root).
BUILD_DIR ?= build
BENCH_DIR ?= build-bench
JOBS ?= $(shell nproc)
WERROR ?= OFF
CMAKE_FLAGS ?=

SOURCES = $(shell git ls-files '*.cpp' '*.hpp' 2>/dev/null || find include src apps tests bench -name '*.[ch]pp')

.PHONY: all deps configure build build-app run test bench format format-check lint clean

all: build

deps:
	./scripts/install-deps.sh

configure: deps
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release -DSCANTLING_WERROR=$(WERROR) $(CMAKE_FLAGS)

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

SCENARIO ?= scenarios/hull_sweep_os1.yaml
RECORDING ?= $(BUILD_DIR)/recordings/$(basename $(notdir $(SCENARIO)))

build-app: configure
	cmake --build $(BUILD_DIR) -j $(JOBS) --target scantling scantling_example_cloud

# LiODOM's settings for the default scenario: the hull side is degenerate along the hull for
# LiDAR edges, so the run leans on the recording's VIO there (docs/results.md, "LiODOM").
ODOMETRY_ARGS ?= --config config/odometry/examples/hull_side_vio.yaml --prior vio

# The default job: simulate the default scenario (a drone sweeping a ship hull with an OS1-64),
# run the LiDAR odometry on the recording and print its drift against the ground truth.
run: build-app
	@start=$$(date +%s); \
	./$(BUILD_DIR)/apps/scantling sim $(SCENARIO) --out $(RECORDING) --force && \
	echo "make run: recording in $(RECORDING) ($$(( $$(date +%s) - start )) s); read it with scantling::io::open_recording" && \
	./$(BUILD_DIR)/apps/scantling odometry $(RECORDING) --out $(RECORDING)/odometry.txt $(ODOMETRY_ARGS) && \
	echo "make run: odometry in $(RECORDING)/odometry.txt, drift above ($$(( $$(date +%s) - start )) s in all)"

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
	@clang-format --dry-run --Werror $(SOURCES) && echo "format-check: $(words $(SOURCES)) files clean"

lint: configure
	clang-tidy -p $(BUILD_DIR) --quiet $(filter %.cpp,$(SOURCES))

clean:
	rm -rf $(BUILD_DIR) $(BENCH_DIR)
