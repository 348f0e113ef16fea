#!/usr/bin/env bash
# Builds the whole GoogleTest suite and the command-line tool with AddressSanitizer and
# UndefinedBehaviorSanitizer (clang, -O1, assertions on) in a separate build folder and runs the
# tests; any report (memory error, leak, undefined behaviour) fails. The examples and the
# benchmarks are left out: they run the same code on the same data as the tests. So are, by
# default, the test programs whose code runs under the sanitizers elsewhere, to keep the build to
# two translation units (CI has two cores): structures_tests (the tables, graph views, octree
# and subdivision on trusted meshes, compared with brute force), input_tests (the readers, which
# the fuzz targets run under AddressSanitizer + UndefinedBehaviorSanitizer from the real files as
# seeds, and which the tool built here runs on every hostile file of tool_tests), repair_tests
# (the weld, the splitter and the fixpoint: the tool built here runs the whole repair on every
# real and hostile file that tool_tests gives it, and the fuzz_pipeline target repairs random
# soups under AddressSanitizer) and parallel_test (run under ThreadSanitizer by
# run_thread_sanitizer.sh). soup_topology_mpi is not built here (Open MPI's own allocations are
# reported as leaks): its tests skip, and run in the Release build.
#   ASAN_BUILD_DIR  build folder (default build-asan)
#   ASAN_TESTS      a CTest regular expression to run a subset (default: every test)
#   ASAN_PROGRAMS   the test programs built, separated by ';' (default: tool_tests);
#                   "all" builds every one
#   JOBS            parallel jobs (default: nproc)
#   ASAN_CXX        the compiler (default clang++, which compiles the package's CGAL code about twice
#                   as fast as g++ and is a second compiler's check of it; g++ works as well)
#   ASAN_DEBUG_INFO debug information (default -g1: the line tables and function names that the
#                   reports' stack traces print, not the variables; -g for a debugger session)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh fuzz
build=${ASAN_BUILD_DIR:-build-asan}
compiler=${ASAN_CXX:-clang++}
jobs=${JOBS:-$(nproc)}
flags="-fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer"
# g++ -O1 with the sanitizers warns about a pair built in CGAL's Epic_converter (a false positive
# in a system header, absent from the Release build).
case $(basename "$compiler") in g++*) flags="$flags -Wno-maybe-uninitialized" ;; esac
debug_info=${ASAN_DEBUG_INFO:--g1}
programs=${ASAN_PROGRAMS:-tool_tests}
[ "$programs" = all ] && programs=""
cmake -S . -B "$build" -G "Unix Makefiles" -DCMAKE_CXX_COMPILER="$compiler" -DCMAKE_BUILD_TYPE=Debug -DCMAKE_CXX_FLAGS_DEBUG="-O1 $debug_info" \
      -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" \
      -DSOUP_TOPOLOGY_BUILD_TESTS=ON -DSOUP_TOPOLOGY_BUILD_EXAMPLES=ON \
      -DSOUP_TOPOLOGY_BUILD_BENCHMARKS=OFF -DSOUP_TOPOLOGY_BUILD_FUZZERS=OFF -DSOUP_TOPOLOGY_WITH_MPI=OFF \
      -DSOUP_TOPOLOGY_TEST_PROGRAMS="$programs" > /dev/null
# The test programs and the tool they call, not the examples; from the test
# folder's Makefile, which builds them in parallel (cmake --build --target a b c builds one after
# the other).
make -C "$build/test" -j "$jobs"
# A report ends the process with a non-zero status: the test fails, and so does this script.
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1:detect_stack_use_after_return=1:check_initialization_order=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# Only a record that TBB keeps of its own is not counted (see the file).
export LSAN_OPTIONS=suppressions=$PWD/scripts/leak_suppressions.txt:print_suppressions=0
ctest --test-dir "$build" --output-on-failure --no-tests=error -j "$jobs" -E '^example\.' ${ASAN_TESTS:+-R "$ASAN_TESTS"}
