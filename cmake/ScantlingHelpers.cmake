# Uniform per-target settings: warnings, -Werror under SCANTLING_WERROR. No global flags.
# scantling_set_target_options(<target> [PCH_FROM <host>]): PCH_FROM reuses the host's
# precompiled header instead of compiling one for the target (scantling_add_pch_hosts).
function(scantling_set_target_options target)
  cmake_parse_arguments(ARG "" "PCH_FROM" "" ${ARGN})
  scantling_set_compile_options(${target})
  if(SCANTLING_PCH AND ARG_PCH_FROM)
    target_precompile_headers(${target} REUSE_FROM ${ARG_PCH_FROM})
  else()
    scantling_apply_precompiled_headers(${target})
  endif()
endfunction()

function(scantling_set_compile_options target)
  target_compile_features(${target} PUBLIC cxx_std_20)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow)
  if(SCANTLING_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
  scantling_apply_sanitizers(${target})
endfunction()

# SCANTLING_PCH: the headers nearly every file includes, parsed once per target instead of once
# per file (Eigen alone is ~2 s of front-end per file under the sanitizers; docs/benchmarks.md,
# "Build time"). Off for a tree that must prove each file includes what it uses.
function(scantling_apply_precompiled_headers target)
  if(SCANTLING_PCH)
    target_precompile_headers(${target} PRIVATE <Eigen/Core> <Eigen/Geometry> <fmt/format.h>
      <algorithm> <cmath> <memory> <optional> <string> <string_view> <vector>)
  endif()
endfunction()

# Two targets that only compile the precompiled header, one for the modules (-fPIC, fmt as a
# shared library) and one for the test executables (-fPIE): a .gch is valid only where the
# code-generation flags and the macros it reads match, and within each group they do. Sharing
# saves 23 header compilations (~9 s each in Release) and 2.7 GB per tree (docs/fuzzing.md,
# "Cost in CI"); GCC's -Winvalid-pch, which CMake adds, turns a mismatch into a warning, an
# error under SCANTLING_WERROR.
function(scantling_add_pch_hosts)
  if(NOT SCANTLING_PCH)
    return()
  endif()
  add_library(scantling_pch_module OBJECT ${PROJECT_SOURCE_DIR}/cmake/pch_host.cpp)
  target_link_libraries(scantling_pch_module PRIVATE Eigen3::Eigen fmt::fmt)
  scantling_set_target_options(scantling_pch_module)
  add_executable(scantling_pch_test ${PROJECT_SOURCE_DIR}/cmake/pch_host.cpp)
  target_link_libraries(scantling_pch_test PRIVATE Eigen3::Eigen)
  scantling_set_target_options(scantling_pch_test)
endfunction()

# Sanitizers on one target (SCANTLING_SANITIZE, e.g. "address,undefined": `make test-asan`,
# `make fuzz`; docs/fuzzing.md). A library hands the sanitizer runtime on to whatever links it
# (tests, the CLI, an installed find_package consumer), since its objects call into it.
# SCANTLING_NO_SANITIZE takes checks back out of that set. SCANTLING_FUZZ adds libFuzzer's
# coverage instrumentation (clang only) without its main().
function(scantling_apply_sanitizers target)
  if(SCANTLING_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=${SCANTLING_SANITIZE}
      -fno-sanitize-recover=all -fno-omit-frame-pointer)
    if(SCANTLING_NO_SANITIZE)
      # After -fsanitize=, so that it wins (e.g. `make test-asan`: null,alignment,vptr).
      target_compile_options(${target} PRIVATE -fno-sanitize=${SCANTLING_NO_SANITIZE})
    endif()
    get_target_property(type ${target} TYPE)
    if(type STREQUAL "EXECUTABLE")
      target_link_options(${target} PRIVATE -fsanitize=${SCANTLING_SANITIZE})
    else()
      target_link_options(${target} INTERFACE -fsanitize=${SCANTLING_SANITIZE})
    endif()
  endif()
  if(SCANTLING_FUZZ)
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link)
  endif()
endfunction()

# scantling_add_module(<name> SOURCES a.cpp ... PUBLIC_DEPS ... PRIVATE_DEPS ...)
# Declares library scantling_<name> with alias scantling::<name>.
function(scantling_add_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  set(target scantling_${name})
  add_library(${target} ${ARG_SOURCES})
  add_library(scantling::${name} ALIAS ${target})
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:include>)
  target_link_libraries(${target} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
  scantling_set_target_options(${target} PCH_FROM scantling_pch_module)
  set_property(GLOBAL APPEND PROPERTY SCANTLING_MODULE_TARGETS ${target})
endfunction()

# scantling_add_test(<module> SOURCES ... DEPS ... [FIXTURE name]): one gtest executable per
# module; FIXTURE makes every test of it require that ctest fixture (e.g. a simulated recording).
function(scantling_add_test module)
  cmake_parse_arguments(ARG "" "FIXTURE" "SOURCES;DEPS" ${ARGN})
  set(target scantling_${module}_tests)
  add_executable(${target} ${ARG_SOURCES})
  target_link_libraries(${target} PRIVATE ${ARG_DEPS} GTest::gtest_main)
  target_compile_definitions(${target} PRIVATE
    SCANTLING_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    SCANTLING_SHARED_DATA_DIR="${SCANTLING_SHARED_DATA_DIR}")
  scantling_set_target_options(${target} PCH_FROM scantling_pch_test)
  if(ARG_FIXTURE)
    gtest_discover_tests(${target} DISCOVERY_TIMEOUT 60
      PROPERTIES LABELS ${module} FIXTURES_REQUIRED ${ARG_FIXTURE})
  else()
    gtest_discover_tests(${target} DISCOVERY_TIMEOUT 60 PROPERTIES LABELS ${module})
  endif()
endfunction()

# scantling_add_recording_fixture(<test-name> SCENARIO <file> OUT <dir> FIXTURE <name>
#                                 LABEL <label>): a ctest that records SCENARIO with the CLI into
# OUT before the tests that require FIXTURE (a module test may not include the simulator:
# tests/arch). The recording is rewritten on every run (--force).
function(scantling_add_recording_fixture name)
  cmake_parse_arguments(ARG "" "SCENARIO;OUT;FIXTURE;LABEL" "" ${ARGN})
  add_test(NAME ${name}
    COMMAND scantling sim ${ARG_SCENARIO} --out ${ARG_OUT} --force --no-progress)
  set_tests_properties(${name} PROPERTIES FIXTURES_SETUP ${ARG_FIXTURE} LABELS ${ARG_LABEL})
endfunction()

