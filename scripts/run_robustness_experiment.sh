#!/usr/bin/env bash
# The robustness experiment of doc/Soup_topology/Robustness.md (issue 10), in one command:
#
#   bash scripts/run_robustness_experiment.sh
#
# installs what it needs (the build packages via scripts/setup.sh, and gnuplot-nox), builds
# benchmark/robustness_experiment in Release, runs it (about 3 minutes on 2 cores), and writes
# doc/Soup_topology/robustness/results.csv, correctness.png and time.png (doc/.../plot.gp), and
# prints the summary table of the page. Not part of CI. BUILD_DIR chooses the build folder
# (default build-robustness); the shared meshes are read from shared/data beside the checkout
# (SOUP_TOPOLOGY_DATA_DIR to change it).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
if ! command -v gnuplot > /dev/null; then
  SUDO=""; [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends gnuplot-nox ||
    { $SUDO apt-get update && DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y --no-install-recommends gnuplot-nox; }
fi
build=${BUILD_DIR:-build-robustness}
data_option=()
[ -n "${SOUP_TOPOLOGY_DATA_DIR:-}" ] && data_option=(-DSOUP_TOPOLOGY_DATA_DIR="$SOUP_TOPOLOGY_DATA_DIR")
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release -DSOUP_TOPOLOGY_BUILD_TESTS=OFF \
      -DSOUP_TOPOLOGY_BUILD_EXAMPLES=OFF "${data_option[@]}" > /dev/null
cmake --build "$build" --target robustness_experiment -j "$(nproc)"
out=doc/Soup_topology/robustness
start=$(date +%s)
"$build/benchmark/robustness_experiment" "$out/results.csv" > "$build/robustness_experiment.log"
grep -v "^  not correct" "$build/robustness_experiment.log" || true
echo "== $(grep -c "^  not correct" "$build/robustness_experiment.log" || true) runs not correct (listed in $build/robustness_experiment.log)"
echo "== experiment: $(( $(date +%s) - start )) s"
(cd "$out" && gnuplot plot.gp)
echo "== wrote $out/results.csv, $out/correctness.png, $out/time.png"

# The summary: correct runs per theta (rotation) and for float32, per tolerance, for the four
# kernels (double / Epick / Epeck / rational); then the mean time per kernel and the ratios.
awk -F, '
  BEGIN { split("Simple_cartesian<double> Epick Epeck Simple_cartesian<Exact_rational>", K, " ")
          for (i = 1; i <= 4; ++i) id[K[i]] = i; nf = split("0.5 2 10", F, " ") }
  NR > 1 {
    x = ($3 == "float32") ? "float32" : $5
    if (!(x in seen)) { seen[x] = 1; order[++nx] = x }
    runs[x, $7, id[$6]]++; ok[x, $7, id[$6]] += $24
    time[$1, id[$6]] += $25; count[$1, id[$6]]++
    if (!($1 in mesh_seen)) { mesh_seen[$1] = 1; mesh[++nm] = $1 }
  }
  END {
    printf "| theta (degrees) |"; for (f = 1; f <= nf; ++f) printf " %s x: double / Epick / Epeck / rational |", F[f]; print ""
    printf "|---|"; for (f = 1; f <= nf; ++f) printf "---|"; print ""
    for (j = 1; j <= nx; ++j) {
      x = order[j]; printf "| %s |", x
      for (f = 1; f <= nf; ++f) {
        printf " "
        for (k = 1; k <= 4; ++k) printf "%s%d/%d", (k > 1 ? " / " : ""), ok[x, F[f], k], runs[x, F[f], k]
        printf " |"
      }
      print ""
    }
    print ""
    print "| mesh | double (ms) | Epick (ms) | Epeck (ms) | rational (ms) | Epeck / Epick | rational / Epick | double / Epick |"
    print "|---|---|---|---|---|---|---|---|"
    for (m = 1; m <= nm; ++m) {
      for (k = 1; k <= 4; ++k) mean[k] = time[mesh[m], k] / count[mesh[m], k]
      printf "| %s | %.1f | %.1f | %.1f | %.1f | %.2f | %.2f | %.2f |\n", mesh[m], mean[1], mean[2], mean[3], mean[4],
             mean[3] / mean[2], mean[4] / mean[2], mean[1] / mean[2]
    }
  }' "$out/results.csv"
