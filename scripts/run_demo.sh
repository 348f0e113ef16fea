#!/usr/bin/env bash
# Sets up a fresh Debian 12 machine, builds the command-line tool, and repairs the bundled real
# mesh data/pig.stl.xz (17 non-conforming patches), printing the report.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
# A folder of its own: the test script's build folder keeps its options whichever runs first.
build=${DEMO_BUILD_DIR:-build-demo}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DSOUP_TOPOLOGY_BUILD_TESTS=OFF -DSOUP_TOPOLOGY_BUILD_BENCHMARKS=OFF > /dev/null
cmake --build "$build" --target soup_topology -j "$(nproc)"
mkdir -p "$build/demo"
xz -dc data/pig.stl.xz > "$build/demo/pig.stl"
echo "== the soup as read (exact weld only)"
"$build/tools/soup_topology" stats "$build/demo/pig.stl"
echo "== repaired with tolerance 0.3 (0.26% of the bounding-box diagonal)"
"$build/tools/soup_topology" repair "$build/demo/pig.stl" -o "$build/demo/pig_repaired.off" --tolerance 0.3 --check
