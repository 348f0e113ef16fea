# Plots of the robustness experiment (doc/Soup_topology/Robustness.md), from results.csv.
# Run from this folder: gnuplot plot.gp   (scripts/run_robustness_experiment.sh does it).
# Columns of results.csv used: 1 mesh, 3 perturbation, 5 theta_deg, 6 kernel, 7 tolerance_factor,
# 24 correct, 25 time_ms. awk gathers the rotation rows into one line per theta: the sum of column
# `value` for each kernel (in the order of `kernels`) over the rows that match.
kernels = "Simple_cartesian<double> Epick Epeck Simple_cartesian<Exact_rational>"
meshes = "elephant fandisk ALSTOM_TEST4"
factors = "0.5 2 10"
gather(factor, mesh, value) = sprintf("< awk -F, -v f=%s -v m=%s -v c=%d -v ks='%s' '\
  BEGIN { n = split(ks, K, \" \"); for (i = 1; i <= n; ++i) id[K[i]] = i } \
  NR > 1 && $3 == \"rotation\" && $7 == f && (m == \"all\" || $1 == m) { s[$5, id[$6]] += $c; t[$5] = 1 } \
  END { for (x in t) { printf \"%%s\", x; for (i = 1; i <= n; ++i) printf \" %%s\", s[x, i] + 0; print \"\" } }' \
  results.csv | sort -g", factor, mesh, value, kernels)

set terminal pngcairo size 1500,480 font ",10" noenhanced

# Correct runs against theta, one panel per tolerance, one line per kernel; kernel k is drawn
# 0.15 k higher so that equal curves stay visible.
set output "correctness.png"
set multiplot layout 1,3 title "Correct runs (out of 3 meshes x 3 random rotations) against the rotation angle"
set logscale x
set format x "1e%T"
set xrange [5e-13:0.2]
set yrange [-0.5:10.5]
set xlabel "theta (degrees)"
set ylabel "correct runs (kernel k drawn 0.15 k higher)"
set key bottom left
do for [i=1:3] {
  set title sprintf("tolerance = %s x largest displacement", word(factors, i))
  plot for [k=1:4] gather(word(factors, i), "all", 24) using 1:(column(k + 1) + 0.15 * k) \
       with linespoints pt k lw 2 title word(kernels, k)
}
unset multiplot

# Time of reconstruct_topology() against theta per kernel (tolerance 2x), one panel per mesh; the
# mean over the 3 rotations.
set output "time.png"
set multiplot layout 1,3 title "Time of reconstruct_topology() per kernel (tolerance 2 x largest displacement, mean of 3 rotations)"
set logscale y
set yrange [*:*]
set format y "%g"
set ylabel "milliseconds"
set key top left
do for [m=1:3] {
  set title word(meshes, m)
  plot for [k=1:4] gather("2", word(meshes, m), 25) using 1:(column(k + 1) / 3) \
       with linespoints pt k lw 2 title word(kernels, k)
}
unset multiplot
