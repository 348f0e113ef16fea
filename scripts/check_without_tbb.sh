#!/usr/bin/env bash
# Builds the package with TBB turned off (-DSOUP_TOPOLOGY_WITH_TBB=OFF: no target links TBB and
# CGAL_LINKED_WITH_TBB is not defined, so CGAL::Parallel_if_available_tag is the sequential tag)
# in a separate build folder, and runs the determinism tests (parallel_test): every function
# taking a ConcurrencyTag must compile and run sequentially.
#   NO_TBB_BUILD_DIR  build folder (default build-no-tbb)
#   JOBS              parallel jobs (default: nproc)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
build=${NO_TBB_BUILD_DIR:-build-no-tbb}
jobs=${JOBS:-$(nproc)}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DSOUP_TOPOLOGY_WITH_TBB=OFF \
      -DSOUP_TOPOLOGY_BUILD_TESTS=ON -DSOUP_TOPOLOGY_BUILD_EXAMPLES=ON \
      -DSOUP_TOPOLOGY_BUILD_BENCHMARKS=OFF -DSOUP_TOPOLOGY_BUILD_FUZZERS=OFF > /dev/null
if grep -q "TBB::tbb\|CGAL_LINKED_WITH_TBB" "$build/test/CMakeFiles/parallel_test.dir/flags.make" \
                                         "$build/test/CMakeFiles/parallel_test.dir/link.txt"; then
  echo "check_without_tbb: parallel_test is still built with TBB" >&2
  exit 1
fi
cmake --build "$build" --target parallel_test -j "$jobs"
ctest --test-dir "$build" --output-on-failure --no-tests=error -j "$jobs" -R '(^|/)Parallel'
