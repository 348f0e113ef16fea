#!/usr/bin/env bash
# Builds the package with TBB turned off (-DSOUP_TOPOLOGY_WITH_TBB=OFF: no target links TBB and
# CGAL_LINKED_WITH_TBB is not defined, so CGAL::Parallel_if_available_tag is the sequential tag)
# in a separate build folder, and runs the determinism tests (parallel_test and
# parallel_other_steps_test): every function taking a ConcurrencyTag must compile and run
# sequentially. The two programs compile at the same time, each on its own core; without the
# tests' precompiled header, which would be compiled first, alone, for two programs only. At -O1
# (with NDEBUG, as in Release): about half the compilation of -O3 (parallel_test: 69 s instead of
# about 150 s), and the tests take as long (8 s).
#   NO_TBB_BUILD_DIR  build folder (default build-no-tbb)
#   JOBS              parallel jobs (default: nproc)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
build=${NO_TBB_BUILD_DIR:-build-no-tbb}
jobs=${JOBS:-$(nproc)}
programs=(parallel_test parallel_other_steps_test)
cmake -S . -B "$build" -G "Unix Makefiles" -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" \
      -DSOUP_TOPOLOGY_WITH_TBB=OFF \
      -DSOUP_TOPOLOGY_BUILD_TESTS=ON -DSOUP_TOPOLOGY_BUILD_EXAMPLES=ON \
      -DSOUP_TOPOLOGY_BUILD_BENCHMARKS=OFF -DSOUP_TOPOLOGY_BUILD_FUZZERS=OFF \
      -DSOUP_TOPOLOGY_TEST_PRECOMPILED_HEADER=OFF \
      -DSOUP_TOPOLOGY_TEST_PROGRAMS="$(IFS=";"; echo "${programs[*]}")" > /dev/null
for program in "${programs[@]}"; do
  if grep -q "TBB::tbb\|CGAL_LINKED_WITH_TBB" "$build/test/CMakeFiles/$program.dir/flags.make" \
                                           "$build/test/CMakeFiles/$program.dir/link.txt"; then
    echo "check_without_tbb: $program is still built with TBB" >&2
    exit 1
  fi
done
# One make for both (cmake --build with two targets builds one after the other).
make -C "$build/test" -j "$jobs"
ctest --test-dir "$build" --output-on-failure --no-tests=error -j "$jobs" -R '(^|/)Parallel'
