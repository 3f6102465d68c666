#!/usr/bin/env bash
# Builds samples/embed as a separate project the way a host would, then runs the embedding
# test (test_embed, validation on) against that binary.
#   build_and_run.sh install    SOURCE BUILD WORK TEST_EMBED  - cmake --install BUILD into
#                               WORK/prefix, then find_package(jade) from tests/consumer/core_only
#                               (core alone) and from the sample (with io)
#   build_and_run.sh subdirectory SOURCE BUILD WORK TEST_EMBED - add_subdirectory(SOURCE)
# Fails on the first failing step (set -e); each step's output goes to the ctest log.
set -euo pipefail
mode=$1 source=$2 build=$3 work=$4 test_embed=$5
# The consumer's build folder is kept between runs (incremental); the prefix and output are not.
rm -rf "$work/prefix" "$work/out" "$work/core_build"
mkdir -p "$work"
generator=()
command -v ninja >/dev/null && generator=(-G Ninja)
# A consumer of the installed static libraries compiles and links with the flags they were
# built with (the asan preset's sanitizers, whose runtime they call), and gets the same
# project-include hook (tests/sanitizers/asan.cmake, keep_loaded.c in its executables).
cache_value() { sed -n "s/^$1:[A-Z]*=//p" "$build/CMakeCache.txt"; }
same_flags=(-DCMAKE_CXX_FLAGS="$(cache_value CMAKE_CXX_FLAGS)" -DCMAKE_EXE_LINKER_FLAGS="$(cache_value CMAKE_EXE_LINKER_FLAGS)")
hook=$(cache_value CMAKE_PROJECT_jade_INCLUDE)
[ -n "$hook" ] && same_flags+=(-DCMAKE_PROJECT_INCLUDE="$hook")
case "$mode" in
install)
  cmake --install "$build" --prefix "$work/prefix" >/dev/null
  test -f "$work/prefix/lib/cmake/jade/jadeConfig.cmake"
  test -f "$work/prefix/lib/cmake/jade/jadeConfigVersion.cmake"
  test -f "$work/prefix/include/jade/render.hpp"
  # Core only: no io dependencies needed, jade::io not imported.
  cmake -S "$source/tests/consumer/core_only" -B "$work/core_build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
        -DCMAKE_PREFIX_PATH="$work/prefix" "${same_flags[@]}" >/dev/null
  cmake --build "$work/core_build" >/dev/null
  "$work/core_build/core_consumer"
  cmake -S "$source/samples/embed" -B "$work/build" "${generator[@]}" -DCMAKE_BUILD_TYPE=Release \
        -DCMAKE_PREFIX_PATH="$work/prefix" "${same_flags[@]}" >/dev/null
  ;;
subdirectory)
  # Jade's sources are compiled again here: without optimisation (about half the compile time;
  # the sample's sphere is small) and without debug information.
  cmake -S "$source/samples/embed" -B "$work/build" "${generator[@]}" -DCMAKE_BUILD_TYPE=None \
        -DCMAKE_CXX_FLAGS=-O0 -DJADE_SOURCE_DIR="$source" >/dev/null
  # A parent project must not get Jade's samples or tests by default.
  if grep -q "^JADE_BUILD_TESTS:BOOL=ON" "$work/build/CMakeCache.txt"; then echo "JADE_BUILD_TESTS is on"; exit 1; fi
  if grep -q "^JADE_BUILD_SAMPLES:BOOL=ON" "$work/build/CMakeCache.txt"; then echo "JADE_BUILD_SAMPLES is on"; exit 1; fi
  ;;
*) echo "unknown mode $mode"; exit 1 ;;
esac
cmake --build "$work/build" --target jade_embed -j "${JADE_CONSUMER_JOBS:-2}"
JADE_EMBED="$work/build/jade_embed" JADE_TEST_OUT="$work/out" \
  "$test_embed" --gtest_filter='Embed.SampleDrawsTheTranslucentSphereIntoTheHostsFrame'
