#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine, builds everything in Release and runs the whole test suite
# (unit tests, examples, the command-line tool), then checks that an installed copy of the
# package is found by a consumer project through find_package(Soup_topology), the HTML report in
# headless Chromium and the build without TBB; then the tests under AddressSanitizer +
# UndefinedBehaviorSanitizer, the determinism tests under ThreadSanitizer and short fuzz runs
# (SOUP_TOPOLOGY_HARDENING=0 skips those three).
#   BUILD_DIR     the Release build folder (default build)
#   JOBS          parallel compilations and tests (default: nproc)
#   FUZZ_SECONDS  seconds each fuzz target runs here (default 5: a check that every target still
#                 runs clean from its seeds; README.md "Hardening" has the long runs)
set -euo pipefail
cd "$(dirname "$0")/.."
hardening=${SOUP_TOPOLOGY_HARDENING:-1}
# Every Debian package of the steps below in one apt-get run: the build, clang and libFuzzer for
# the fuzz step, Chromium and Node.js for the browser tests, Open MPI for soup_topology_mpi.
extras=(browser mpi)
[ "$hardening" != 0 ] && extras+=(fuzz)
bash scripts/setup.sh "${extras[@]}"
build=${BUILD_DIR:-build}
jobs=${JOBS:-$(nproc)}
export JOBS=$jobs
# Each step prints the seconds it took, so that a CI log shows where the time goes.
step_start=$SECONDS
step_done() { echo "== $1: $((SECONDS - step_start)) s"; step_start=$SECONDS; }
# Every option that decides what is built is given explicitly, so that a build folder configured
# by another script (run_demo.sh builds only the tool) cannot leave the tests out.
# three.js for the HTML report's viewer (npm ci in viewer/), inlined when the build is configured.
bash scripts/setup_viewer.sh
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DSOUP_TOPOLOGY_BUILD_TESTS=ON \
      -DSOUP_TOPOLOGY_BUILD_TOOL=ON -DSOUP_TOPOLOGY_BUILD_EXAMPLES=OFF -DSOUP_TOPOLOGY_BUILD_BENCHMARKS=OFF
# The benchmarks are run on demand from a Release build (doc/Soup_topology/Performance.md), and
# the examples are short programs that show the API: here both are compiled and linked without
# optimisation (much cheaper to compile), in a folder of their own whose programs are not for
# measuring, and the examples are run there; with clang when it is installed (the fuzz set of
# setup.sh): it compiles them in about half the time of g++, and so the package is compiled by a
# second compiler. (The examples took about 260 s of compilation at -O3 with g++.)
unoptimised_build="$build-unoptimised"
unoptimised_compiler=()
command -v clang++ > /dev/null && unoptimised_compiler=(-DCMAKE_CXX_COMPILER=clang++)
cmake -S . -B "$unoptimised_build" ${unoptimised_compiler[@]+"${unoptimised_compiler[@]}"} \
      -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O0" \
      -DCGAL_DO_NOT_WARN_ABOUT_CMAKE_BUILD_TYPE=TRUE -DSOUP_TOPOLOGY_BUILD_TESTS=OFF -DSOUP_TOPOLOGY_BUILD_TOOL=OFF \
      -DSOUP_TOPOLOGY_BUILD_EXAMPLES=ON -DSOUP_TOPOLOGY_BUILD_BENCHMARKS=ON > /dev/null
step_done "packages and configuration"
cmake --build "$build" -j "$jobs"
step_done "Release build (tests, tool)"
cmake --build "$unoptimised_build" -j "$jobs"
ctest --test-dir "$unoptimised_build" --output-on-failure --no-tests=error -j "$jobs" -R '^example\.'
step_done "benchmarks and examples compiled (unoptimised), examples run"
# The tests run one process each, JOBS at a time; a test that runs the tool waits for it, so
# there are never more than JOBS busy processes.
ctest --test-dir "$build" --output-on-failure --no-tests=error -j "$jobs"
step_done "Release tests"
# The installed package works for a user project.
prefix="$PWD/$build/install-prefix"
cmake --install "$build" --prefix "$prefix" > /dev/null
cmake -S test/install_consumer -B "$build/consumer" -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix" > /dev/null
cmake --build "$build/consumer" -j "$jobs" > /dev/null
"$build/consumer/consumer"
step_done "install and consumer project"

# The HTML report in a real browser (headless Chromium, software GL): a skip is a failure here.
SOUP_TOPOLOGY_REQUIRE_BROWSER=1 BUILD_DIR="$build" bash scripts/run_browser_tests.sh
step_done "browser tests of the HTML report"
# The package without TBB: every function taking a ConcurrencyTag compiles and runs sequentially.
bash scripts/check_without_tbb.sh
step_done "build and determinism tests without TBB"

# Hardening: the tests under the sanitizers, then the fuzz targets for FUZZ_SECONDS each.
if [ "$hardening" != 0 ]; then
  bash scripts/run_sanitizers.sh
  step_done "sanitizer build and tests"
  bash scripts/run_thread_sanitizer.sh
  step_done "determinism tests under ThreadSanitizer"
  FUZZ_SECONDS=${FUZZ_SECONDS:-5} bash scripts/run_fuzz.sh
  step_done "fuzz build and runs"
fi
