# Entry points. `make run` and `make test` do all set-up on a fresh Debian 12 machine (as root).
BUILD_DIR ?= build
BENCH_DIR ?= build-bench
JOBS ?= $(shell nproc)
WERROR ?= OFF
CMAKE_FLAGS ?=

SOURCES = $(shell git ls-files '*.cpp' '*.hpp' 2>/dev/null || find include src apps tests bench -name '*.[ch]pp')

.PHONY: all deps configure build build-app run run-odometry test test-asan fuzz bench format format-check lint \
	clean

all: build

deps:
	./scripts/install-deps.sh

configure: deps
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release -DSCANTLING_WERROR=$(WERROR) $(CMAKE_FLAGS)

build: configure
	cmake --build $(BUILD_DIR) -j $(JOBS)

SCENARIO ?= scenarios/hull_sweep_os1.yaml
RECORDING ?= $(BUILD_DIR)/recordings/$(basename $(notdir $(SCENARIO)))
# Beside the recording, not in it: outputs inside an input folder are refused.
ODOMETRY_OUT ?= $(RECORDING)_odometry.txt

build-app: configure
	cmake --build $(BUILD_DIR) -j $(JOBS) --target scantling scantling_example_cloud

# LiODOM's settings for the default scenario: the hull side is degenerate along the hull for
# LiDAR edges, so the run leans on the recording's VIO there (docs/results.md, "LiODOM").
ODOMETRY_ARGS ?= --config config/odometry/examples/hull_side_vio.yaml --prior vio

# The default job: the closed-loop inspection of a hull side in its dry dock (issue 13). The
# drone's own estimate (LiODOM + the cascaded EKFs) drives the VTP follower and the PIDs, under
# collision prevention, in a 5 m/s wind with gusts; it prints the path deviation, the estimate's
# error against the ground truth and the mission's figures. The recording holds the ground
# truth, every sensor, the estimates, commands and events (io/mission_log.hpp).
MISSION ?= scenarios/missions/hull_sweep_closed_loop.yaml
MISSION_OUT ?= $(BUILD_DIR)/recordings/$(basename $(notdir $(MISSION)))
run: build-app
	@start=$$(date +%s); \
	./$(BUILD_DIR)/apps/scantling mission $(MISSION) --out $(MISSION_OUT) --force && \
	echo "make run: closed-loop recording in $(MISSION_OUT) ($$(( $$(date +%s) - start )) s)"

# The open-loop pipeline of earlier stops: simulate the scripted sweep, run LiODOM on the
# recording and print its drift.
run-odometry: build-app
	@start=$$(date +%s); \
	./$(BUILD_DIR)/apps/scantling sim $(SCENARIO) --out $(RECORDING) --force && \
	./$(BUILD_DIR)/apps/scantling odometry $(RECORDING) --out $(ODOMETRY_OUT) $(ODOMETRY_ARGS) && \
	echo "make run-odometry: odometry in $(ODOMETRY_OUT), drift above ($$(( $$(date +%s) - start )) s in all)"

test: build
	ctest --test-dir $(BUILD_DIR) --output-on-failure -j $(JOBS)

# The whole test suite under AddressSanitizer + UndefinedBehaviorSanitizer (g++, -O1, no debug
# information: line tables cost 27 % of the build (local_ekf.cpp 39.5 -> 31.1 s, 2026-11-28);
# reports still name the functions, and `make test-asan ASAN_CXX_FLAGS="-O1 -g1 -DNDEBUG"`
# replays a finding with file and line). UBSan's null, alignment
# and vptr checks instrument every dereference of Eigen-heavy code and double the build (62 s
# -> 35 s for one file): ASan reports a null dereference itself, and the fuzzers keep all three
# on the readers, where misaligned reads could come from. docs/fuzzing.md.
ASAN_DIR ?= build-asan
SANITIZE ?= address,undefined
NO_SANITIZE ?= null,alignment,vptr
ASAN_CXX_FLAGS ?= -O1 -g0 -DNDEBUG
# Statistical studies over hundreds of Stein-ICP runs (7 CPU-min under the sanitizers, a third of
# the suite's time): their code paths run under the sanitizers in the lighter Stein tests
# (same seed, reduced 3-DoF, front faces), and the studies themselves run in `make test`.
# Likewise two whole-recording runs of the localiser (the column's 3-DoF tracking over 80 s and
# the VIO-velocity input over the mock-up flight, twice): their code runs under the sanitizers
# in ColumnRegistrationSim.RegistersFrames* and the VelocityOdometry unit tests.
# And the closed-loop flights of 7 to 16 s (ClosedLoop.*, ClosedLoopSafety.*, four of
# ClosedLoopFaults.*: LiODOM + EKFs in the loop): the loop, the fault injection and the stack's
# input screening run under the sanitizers in ClosedLoopFaults.NanSamplesAreDroppedAndReported
# (6 s), the scenario parsing and the mission log in the other mission tests. The ROV's survey
# loops (RovHullSurvey.*) and the crawler's (CrawlerMission.*: the particle filter, the
# follower, no LiDAR) run under the sanitizers, and so does the stop-and-map in the loop
# (CrawlerStopAndMap.StopsMaps*, 21 s); two longer crawler runs (64 s and 39 s under the
# sanitizers, stop 29) are left to `make test`: the flight around a mesh hole (its planning is
# under the sanitizers in the other CrawlerBadInput tests) and the pause for and the detour
# around an obstacle (the stop-and-map's code in StopsMaps*, the detour's in Detour.*); so are
# the three stiffener drives (CrawlerTasks.Drives*, 3-4 s each in Release: the corridor's code
# runs under the sanitizers in FaceCorridor.* and CrawlerTasks.NoCorridor*). The exploration of
# the test room (ExplorationMission.MapsTheRoom*, 13-19 s in Release) too: the planner explores
# rooms under the sanitizers in NbvExploration.*, and the loop runs in the other
# ExplorationMission tests.
ASAN_SKIP_TESTS ?= ExplorationMission\.MapsTheRoom|CrawlerBadInput\.ARectangleAroundTheHoleIsFlown|CrawlerTasks\.(Drives|OnTheMoebius)|CrawlerStopAndMap\.AnObstacleOnThePath|ClosedLoop\.|ClosedLoopSafety\.|ClosedLoopFaults\.(LidarDropout|ShortImuGap|LongImuGap|AnOperatorCommandEndsTheCoast)|SteinIcp\.(CovarianceDescribesTheError|ModeRecoversKnownPose|SymmetricRoomGivesTwo|SpreadAlongCorridor)|CliRegister\.SteinReportsParticle|ColumnRegistrationSim\.LocalizerWithColumnTracking|LocalizerTest\.VioVelocityAlone
# Also set while building: gtest_discover_tests runs each test executable after linking it.
SANITIZER_ENV = ASAN_OPTIONS=$(ASAN_OPTIONS_DEFAULT) UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	LSAN_OPTIONS=suppressions=$(CURDIR)/scripts/sanitizers/lsan.supp:print_suppressions=0
ASAN_OPTIONS_DEFAULT = detect_leaks=1:check_initialization_order=1:strict_init_order=1:detect_stack_use_after_return=1
test-asan: deps
	cmake -S . -B $(ASAN_DIR) -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="$(ASAN_CXX_FLAGS)" \
	  -DSCANTLING_SANITIZE=$(SANITIZE) -DSCANTLING_NO_SANITIZE=$(NO_SANITIZE) -DSCANTLING_WERROR=OFF \
	  $(CMAKE_FLAGS)
	env $(SANITIZER_ENV) cmake --build $(ASAN_DIR) -j $(JOBS)
	env $(SANITIZER_ENV) ctest --test-dir $(ASAN_DIR) --output-on-failure -j $(JOBS) \
	  -E '$(ASAN_SKIP_TESTS)'

# libFuzzer targets, one per reader (clang, ASan + UBSan), each run FUZZ_SECONDS on a seed
# corpus built from ../shared/data and the repository's files; fails with the reproducer's path.
FUZZ_DIR ?= build-fuzz
FUZZ_SECONDS ?= 60
fuzz: deps
	FUZZ_DIR=$(FUZZ_DIR) FUZZ_SECONDS=$(FUZZ_SECONDS) FUZZ_TARGETS="$(FUZZ_TARGETS)" JOBS=$(JOBS) \
	  ./scripts/run-fuzzers.sh

bench:
	./scripts/install-deps.sh --bench
	cmake -S . -B $(BENCH_DIR) -DCMAKE_BUILD_TYPE=Release -DSCANTLING_BUILD_BENCH=ON -DSCANTLING_BUILD_TESTS=OFF
	cmake --build $(BENCH_DIR) -j $(JOBS)
	./scripts/run-benchmarks.sh $(BENCH_DIR)
	./scripts/odometry-vs-kiss.sh $(BENCH_DIR)

format:
	clang-format -i $(SOURCES)

format-check:
	@clang-format --dry-run --Werror $(SOURCES) && echo "format-check: $(words $(SOURCES)) files clean"

lint: configure
	clang-tidy -p $(BUILD_DIR) --quiet $(filter %.cpp,$(SOURCES))

clean:
	rm -rf $(BUILD_DIR) $(BENCH_DIR) $(ASAN_DIR) $(FUZZ_DIR)
