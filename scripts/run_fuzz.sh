#!/usr/bin/env bash
# Builds the libFuzzer targets of fuzz/ (clang, AddressSanitizer + UndefinedBehaviorSanitizer) and
# runs each for FUZZ_SECONDS from its seeds: the small files of fuzz/corpus/<target>/ and the
# files of the shared data folder of the same format, taken at run time. A crash, a leak, a
# timeout, an allocation beyond the limits or a broken invariant fails the script; the input
# that caused it is left in $build/artifacts/. README.md ("Hardening") describes a long run.
#   FUZZ_SECONDS     seconds per target (default 30)
#   FUZZ_TARGETS     targets to run (default: all, "stl_binary stl_ascii off obj ply vrml triangulate pipeline")
#   FUZZ_TIMEOUT     seconds one input may take before it counts as a hang (default 10: every
#                    reader bounds its work by the input's size, 64 KB at most here)
#   FUZZ_RSS_MB      resident memory beyond which the run fails (default 2048)
#   FUZZ_BUILD_DIR   build folder (default build-fuzz)
#   JOBS             targets built, and run, at the same time (default: nproc); each run is one
#                    process on one core, so FUZZ_SECONDS per target holds whatever JOBS is
# The VRML target gets a dictionary of the grammar (fuzz/vrml.dict) besides its seeds (DEF/USE
# DAGs and chains, nested transforms, shared Coordinates, non-convex polygons).
# A nightly run of the VRML reader and the triangulator, about 8 hours:
#   FUZZ_SECONDS=14400 FUZZ_TARGETS="vrml triangulate" bash scripts/run_fuzz.sh
#   SOUP_TOPOLOGY_DATA_DIR  the shared data folder (default ../shared/data)
set -euo pipefail
cd "$(dirname "$0")/.."
# The build packages, clang and libFuzzer from Debian.
bash scripts/setup.sh fuzz

build=${FUZZ_BUILD_DIR:-build-fuzz}
seconds=${FUZZ_SECONDS:-30}
targets=${FUZZ_TARGETS:-"stl_binary stl_ascii off obj ply vrml triangulate pipeline"}
timeout=${FUZZ_TIMEOUT:-10}
rss_mb=${FUZZ_RSS_MB:-2048}
jobs=${JOBS:-$(nproc)}
data=${SOUP_TOPOLOGY_DATA_DIR:-../shared/data}

# Only the chosen fuzz targets are configured: the default target builds them all, in parallel.
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
      -DSOUP_TOPOLOGY_BUILD_TESTS=OFF -DSOUP_TOPOLOGY_BUILD_EXAMPLES=OFF -DSOUP_TOPOLOGY_BUILD_BENCHMARKS=OFF \
      -DSOUP_TOPOLOGY_BUILD_FUZZERS=ON -DSOUP_TOPOLOGY_FUZZ_TARGETS="$(echo $targets | tr ' ' ';')" > /dev/null
cmake --build "$build" -j "$jobs"

# Seeds: ours, then the shared files of the target's format up to 64 KB (read in place, not copied
# into the repository: some carry GPL or CC-BY-SA terms).
seeds_from_data() {
  local target=$1
  [ -d "$data" ] || return 0
  case $target in
    stl_binary|stl_ascii) find "$data" -name '*.stl' -size -64k ;;
    off) find "$data" -name '*.off' -size -64k ;;
    obj) find "$data" -name '*.obj' -size -64k ;;
    ply) find "$data" -name '*.ply' -size -64k ;;
    vrml) find "$data" -name '*.wrl' -size -64k ;;
  esac
}

# One target's run; its log and its result ("ok" or "failed") are left in $build.
run_target() {
  local t=$1 seeds="$build/seeds/$1" corpus="$build/corpus/$1" max_len extra=()
  case $t in pipeline) max_len=512 ;; triangulate) max_len=16384 ;; *) max_len=65536 ;; esac
  [ -f "fuzz/$t.dict" ] && extra+=("-dict=fuzz/$t.dict")
  if "$build/fuzz/fuzz_$t" "$corpus" "$seeds" -max_total_time="$seconds" -max_len="$max_len" \
       -timeout="$timeout" -rss_limit_mb="$rss_mb" -malloc_limit_mb=1024 -print_final_stats=1 \
       ${extra[@]+"${extra[@]}"} -artifact_prefix="$build/artifacts/$t-" > "$build/fuzz_$t.log" 2>&1; then
    echo ok > "$build/fuzz_$t.result"
  else
    echo failed > "$build/fuzz_$t.result"
  fi
}

mkdir -p "$build/artifacts"
for t in $targets; do
  seeds="$build/seeds/$t"
  rm -rf "$seeds" "$build/fuzz_$t.result"
  mkdir -p "$seeds" "$build/corpus/$t"
  cp fuzz/corpus/"$t"/* "$seeds"/
  for f in $(seeds_from_data "$t"); do cp "$f" "$seeds/data_$(basename "$f")"; done
  echo "fuzz_$t: ${seconds} s, seeds: $(ls "$seeds" | wc -l) files"
  run_target "$t" &
  while [ "$(jobs -rp | wc -l)" -ge "$jobs" ]; do wait -n || true; done
done
wait

status=0
for t in $targets; do
  log="$build/fuzz_$t.log"
  if [ "$(cat "$build/fuzz_$t.result" 2>/dev/null)" != ok ]; then
    echo "fuzz_$t FAILED, see $log:"
    grep -E "ERROR|invariant violated|SUMMARY|Test unit written" "$log" | head -20 || true
    status=1
  fi
  echo "fuzz_$t:"
  grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "$log" | sed "s/^/  /" || true
done
exit $status
