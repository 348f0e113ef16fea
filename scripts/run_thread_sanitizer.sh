#!/usr/bin/env bash
# Builds the determinism tests (test/parallel_test.cpp and test/parallel_other_steps_test.cpp,
# two programs compiled at the same time, without the tests' precompiled header, which would be
# compiled first, alone) with ThreadSanitizer in a separate build folder and runs them: every
# function taking a ConcurrencyTag runs on 8 threads (the Release build runs them on 1, 2, 3 and
# 8), and any data race reported fails (halt_on_error=1). No report is suppressed.
# Debian's libtbb is not built with ThreadSanitizer, and TBB hands its tasks over inside the
# library, where the sanitizer sees no synchronisation. So, in this build only, the parallel
# loops of the package (internal/parallel.h, for_each_block) run their blocks on threads of the
# standard library, as many as TBB would use: the same blocks, any two of which may run at the
# same time, with every start and end of a thread seen by the sanitizer.
#   TSAN_BUILD_DIR  build folder (default build-tsan)
#   JOBS            parallel jobs (default: nproc)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
build=${TSAN_BUILD_DIR:-build-tsan}
jobs=${JOBS:-$(nproc)}
flags="-fsanitize=thread -fno-omit-frame-pointer"
cmake -S . -B "$build" -G "Unix Makefiles" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" \
      -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" \
      -DSOUP_TOPOLOGY_WITH_TBB=ON -DSOUP_TOPOLOGY_BUILD_TESTS=ON -DSOUP_TOPOLOGY_BUILD_EXAMPLES=ON \
      -DSOUP_TOPOLOGY_BUILD_BENCHMARKS=OFF -DSOUP_TOPOLOGY_BUILD_FUZZERS=OFF \
      -DSOUP_TOPOLOGY_TEST_PROGRAMS="parallel_test;parallel_other_steps_test" \
      -DSOUP_TOPOLOGY_TEST_PRECOMPILED_HEADER=OFF > /dev/null
# One make for both (cmake --build with two targets builds one after the other).
make -C "$build/test" -j "$jobs"
export TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1"
# One process per test, JOBS at a time (many tests run one thread for a part of their time); a
# report stops its process, so the test fails and ctest prints the report.
ctest --test-dir "$build" --output-on-failure --no-tests=error -j "$jobs" -R '(^|/)Parallel'

