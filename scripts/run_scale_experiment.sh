#!/usr/bin/env bash
# The scale experiment of the tiled repair (doc/Soup_topology/Tiled_repair.md, "Scale"): writes an
# assembly of PARTS exploded, jittered tori (2 U V triangles each, one binary STL a part) into a
# temporary folder, repairs it as one soup with `soup_topology repair PART... --max-memory SIZE`,
# prints the report, the time and the peak resident memory, and deletes everything. Not a test:
# the default (4 parts of 10,003,200 triangles) writes 2 GB of input and as much of output.
#   BUILD_DIR   Release build folder (default build-scale)
#   PARTS U V   the assembly (default 4 3200 1563)
#   MAX_MEMORY  the limit given to the tool (default 2G: the output is then oriented in parts)
#   TOLERANCE   the tolerance (default 3e-5: above the jitter's 1.4e-5, far below the edges)
#   WORK_DIR    where the files go (default: a new folder in the temporary directory)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
build=${BUILD_DIR:-build-scale}
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DSOUP_TOPOLOGY_BUILD_TESTS=OFF \
      -DSOUP_TOPOLOGY_BUILD_EXAMPLES=ON -DSOUP_TOPOLOGY_BUILD_BENCHMARKS=ON > /dev/null
cmake --build "$build" --target soup_topology torus_assembly -j "$(nproc)"
work=$(mktemp -d "${WORK_DIR:-${TMPDIR:-/tmp}}/soup_topology_scale.XXXXXX")
trap 'rm -rf "$work"' EXIT
start=$SECONDS
"$build/benchmark/torus_assembly" "$work" "${PARTS:-4}" "${U:-3200}" "${V:-1563}"
echo "== wrote the assembly in $((SECONDS - start)) s: $(du -sh "$work" | cut -f1)"
parts=("$work"/part_*.stl)
command=("$build/tools/soup_topology" repair "${parts[@]}" -o "$work/repaired.stl"
         --tolerance "${TOLERANCE:-3e-5}" --max-memory "${MAX_MEMORY:-2G}" --spill-folder "$work")
if [ -x /usr/bin/time ]; then
  /usr/bin/time -f "== %e s, peak resident memory %M KiB" "${command[@]}"
else
  start=$SECONDS
  "${command[@]}"
  echo "== $((SECONDS - start)) s (install 'time' for the peak memory)"
fi
