// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The gap analysis against the repair it prepares (issue 17: the analysis of a 1M-triangle soup
// must cost less than the repair itself), in one run on the same soups.
//
// Inputs, made once per process by soup_test::t_junction_soup (8 slabs along x) from
// clean/bunny00.off split 1-to-4 twice (1,206,528 triangles before the T-junction splits), every
// copy of a vertex jittered by up to 1e-7 ("1e-7") or 1e-6 ("1e-6") x the bounding-box diagonal
// on each coordinate (at 1e-5 the jitter reaches a third of the smallest border feature of this
// soup: the analysis finds an overlap and suggests nothing).
//
// Benchmarks (CPU time):
// - BM_analyze_gaps: Soup_topology::analyze_gaps(points, triangles);
// - BM_reconstruct_topology: reconstruct_topology(points, triangles, snapping_tolerance(t)) with
//   the tolerance t the analysis suggests (the soup copied outside the timed region); skipped
//   with an error when the analysis suggests none.
// Counters: "tolerance", "border_edges" (left by the repair; 0 is the answer).
//
// Run: gap_analysis_benchmark [--benchmark_filter=...]; data from SOUP_TOPOLOGY_DATA_DIR.

#include <Soup_topology/analyze_gaps.h>
#include <Soup_topology/reconstruct_topology.h>

#include "../test/soup_generators.h"
#include "../test/test_utilities.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <benchmark/benchmark.h>

#include <array>
#include <map>
#include <string>
#include <vector>

namespace ST = Soup_topology;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Index_triangle = std::array<std::size_t, 3>;

namespace {

struct Input
{
  std::vector<Point> points;
  std::vector<Index_triangle> triangles;
  double tolerance = 0;
};

const Input& input(double relative_jitter)
{
  static std::map<double, Input> cache;
  auto it = cache.find(relative_jitter);
  if(it != cache.end()) return it->second;
  std::vector<Point> points;
  std::vector<Index_triangle> triangles;
  soup_test::read_data_mesh("clean/bunny00.off.xz", points, triangles);
  soup_test::subdivide_midpoints(points, triangles);
  soup_test::subdivide_midpoints(points, triangles);
  const double diagonal = ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>());
  auto soup = soup_test::t_junction_soup(points, triangles, 8, relative_jitter * diagonal, 11);
  Input in;
  in.points = std::move(soup.points);
  in.triangles = std::move(soup.triangles);
  in.tolerance = ST::analyze_gaps(in.points, in.triangles).suggested_tolerance;
  return cache.emplace(relative_jitter, std::move(in)).first->second;
}

void BM_analyze_gaps(benchmark::State& state, double relative_jitter)
{
  const Input& in = input(relative_jitter);
  ST::Gap_analysis a;
  for(auto _ : state) {
    a = ST::analyze_gaps(in.points, in.triangles);
    benchmark::DoNotOptimize(a.suggested_tolerance);
  }
  state.counters["triangles"] = static_cast<double>(in.triangles.size());
  state.counters["border_vertices"] = static_cast<double>(a.border_vertices);
}

void BM_reconstruct_topology(benchmark::State& state, double relative_jitter)
{
  const Input& in = input(relative_jitter);
  if(!(in.tolerance >= 0)) {
    state.SkipWithError("the analysis suggests no tolerance");
    return;
  }
  ST::Reconstruction_report r;
  for(auto _ : state) {
    state.PauseTiming();
    std::vector<Point> points = in.points;
    std::vector<Index_triangle> triangles = in.triangles;
    state.ResumeTiming();
    r = ST::reconstruct_topology(points, triangles, CGAL::parameters::snapping_tolerance(in.tolerance));
    benchmark::DoNotOptimize(r.border_edges_after);
  }
  state.counters["tolerance"] = in.tolerance;
  state.counters["border_edges"] = static_cast<double>(r.border_edges_after);
}

BENCHMARK_CAPTURE(BM_analyze_gaps, 1e-7, 1e-7)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_reconstruct_topology, 1e-7, 1e-7)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_analyze_gaps, 1e-6, 1e-6)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_reconstruct_topology, 1e-6, 1e-6)->Unit(benchmark::kMillisecond)->Iterations(3);

} // namespace

BENCHMARK_MAIN();
