#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine, builds everything in Release and runs the whole test suite
# (unit tests, examples, the command-line tool), then checks that an installed copy of the
# package is found by a consumer project through find_package(Soup_topology); then the tests under
# AddressSanitizer + UndefinedBehaviorSanitizer and short fuzz runs (SOUP_TOPOLOGY_HARDENING=0 skips
# those two).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
build=${BUILD_DIR:-build}
jobs=${JOBS:-$(nproc)}
# Each step prints the seconds it took, so that a CI log shows where the time goes.
step_start=$SECONDS
step_done() { echo "== $1: $((SECONDS - step_start)) s"; step_start=$SECONDS; }
# Every option that decides what is built is given explicitly, so that a build folder configured
# by another script (run_demo.sh builds only the tool) cannot leave the tests out.
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DSOUP_TOPOLOGY_BUILD_TESTS=ON \
      -DSOUP_TOPOLOGY_BUILD_EXAMPLES=ON -DSOUP_TOPOLOGY_BUILD_BENCHMARKS=ON
step_done "packages and configuration"
cmake --build "$build" -j "$jobs"
step_done "Release build (tests, examples, tool, benchmarks)"
ctest --test-dir "$build" --output-on-failure --no-tests=error -j "$jobs"
step_done "Release tests"
# The installed package works for a user project.
prefix="$PWD/$build/install-prefix"
cmake --install "$build" --prefix "$prefix" > /dev/null
cmake -S test/install_consumer -B "$build/consumer" -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix" > /dev/null
cmake --build "$build/consumer" -j "$jobs" > /dev/null
"$build/consumer/consumer"
step_done "install and consumer project"
# Hardening: the tests under the sanitizers, then the fuzz targets for FUZZ_SECONDS each.
if [ "${SOUP_TOPOLOGY_HARDENING:-1}" != 0 ]; then
  bash scripts/run_sanitizers.sh
  step_done "sanitizer build and tests"
  bash scripts/run_fuzz.sh
  step_done "fuzz build and runs"
fi
