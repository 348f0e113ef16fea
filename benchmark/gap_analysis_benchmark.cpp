// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The gap analysis against the repair it prepares (issue 17: the analysis of a 1M-triangle soup
// must cost less than the repair itself), in one run on the same soups.
//
// Inputs, made once per process:
// - "bunny 1e-7", "bunny 1e-6": soup_test::t_junction_soup (8 slabs along x) from
//   clean/bunny00.off split 1-to-4 twice (1,206,528 triangles before the T-junction splits), every
//   copy of a vertex jittered by up to 1e-7 or 1e-6 x the bounding-box diagonal on each coordinate
//   (at 1e-5 the jitter reaches a third of the smallest border feature of this soup: the analysis
//   finds an overlap and suggests nothing). Few border vertices: the seams of 8 slabs.
// - "torus": the exploded, jittered torus of benchmark/exploded_torus.py made in memory (1,000 x
//   500 quads, 1,000,000 triangles in grid order, every triangle with its own corners, each
//   coordinate moved by up to 1e-6 of the diagonal): every vertex is a border vertex, the worst
//   case of the analysis.
//
// Benchmarks (wall-clock time), sequential and with CGAL::Parallel_tag on all cores ("_on_all_cores"):
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
#include <cmath>
#include <map>
#include <random>
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

Input with_suggested_tolerance(std::vector<Point> points, std::vector<Index_triangle> triangles)
{
  Input in;
  in.points = std::move(points);
  in.triangles = std::move(triangles);
  in.tolerance = ST::analyze_gaps(in.points, in.triangles).suggested_tolerance;
  return in;
}

const Input& bunny(double relative_jitter)
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
  return cache.emplace(relative_jitter, with_suggested_tolerance(std::move(soup.points), std::move(soup.triangles)))
    .first->second;
}

// The exploded, jittered torus of exploded_torus.py (major radius 1, minor radius 0.4).
const Input& torus()
{
  static const Input in = [] {
    const std::size_t u = 1000, v = 500;
    const double pi = 3.14159265358979323846;
    const auto at = [&](std::size_t i, std::size_t j) {
      const double a = 2 * pi * double(i % u) / double(u), b = 2 * pi * double(j % v) / double(v);
      return std::array<double, 3>{(1 + 0.4 * std::cos(b)) * std::cos(a), (1 + 0.4 * std::cos(b)) * std::sin(a),
                                   0.4 * std::sin(b)};
    };
    const double diagonal = std::sqrt(2.8 * 2.8 * 2 + 0.8 * 0.8), jitter = 1e-6 * diagonal;
    std::mt19937_64 rng(17);
    std::uniform_real_distribution<double> move(-jitter, jitter);
    std::vector<Point> points;
    std::vector<Index_triangle> triangles;
    points.reserve(6 * u * v);
    triangles.reserve(2 * u * v);
    const auto add = [&](const std::array<double, 3>& p) {
      points.emplace_back(p[0] + move(rng), p[1] + move(rng), p[2] + move(rng));
    };
    for(std::size_t i = 0; i < u; ++i)
      for(std::size_t j = 0; j < v; ++j) {
        for(const auto& c : {at(i, j), at(i + 1, j), at(i + 1, j + 1)}) add(c);
        triangles.push_back({points.size() - 3, points.size() - 2, points.size() - 1});
        for(const auto& c : {at(i, j), at(i + 1, j + 1), at(i, j + 1)}) add(c);
        triangles.push_back({points.size() - 3, points.size() - 2, points.size() - 1});
      }
    return with_suggested_tolerance(std::move(points), std::move(triangles));
  }();
  return in;
}

const Input& input(const std::string& name)
{
  if(name == "torus") return torus();
  return bunny(name == "bunny 1e-7" ? 1e-7 : 1e-6);
}

template <class ConcurrencyTag>
void analyze_gaps(benchmark::State& state, const std::string& name)
{
  const Input& in = input(name);
  ST::Gap_analysis a;
  for(auto _ : state) {
    a = ST::analyze_gaps<ConcurrencyTag>(in.points, in.triangles);
    benchmark::DoNotOptimize(a.suggested_tolerance);
  }
  state.counters["triangles"] = static_cast<double>(in.triangles.size());
  state.counters["border_vertices"] = static_cast<double>(a.border_vertices);
}

template <class ConcurrencyTag>
void reconstruct_topology(benchmark::State& state, const std::string& name)
{
  const Input& in = input(name);
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
    r = ST::reconstruct_topology<ConcurrencyTag>(points, triangles, CGAL::parameters::snapping_tolerance(in.tolerance));
    benchmark::DoNotOptimize(r.border_edges_after);
  }
  state.counters["tolerance"] = in.tolerance;
  state.counters["border_edges"] = static_cast<double>(r.border_edges_after);
}

using Parallel = CGAL::Parallel_if_available_tag;

void BM_analyze_gaps(benchmark::State& state, const std::string& name) { analyze_gaps<CGAL::Sequential_tag>(state, name); }
void BM_reconstruct_topology(benchmark::State& state, const std::string& name)
{
  reconstruct_topology<CGAL::Sequential_tag>(state, name);
}
void BM_analyze_gaps_on_all_cores(benchmark::State& state, const std::string& name) { analyze_gaps<Parallel>(state, name); }
void BM_reconstruct_topology_on_all_cores(benchmark::State& state, const std::string& name)
{
  reconstruct_topology<Parallel>(state, name);
}

#define SOUP_TOPOLOGY_GAP_BENCHMARKS(label, name)                                                              \
  BENCHMARK_CAPTURE(BM_analyze_gaps, label, name)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime(); \
  BENCHMARK_CAPTURE(BM_reconstruct_topology, label, name)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime(); \
  BENCHMARK_CAPTURE(BM_analyze_gaps_on_all_cores, label, name)->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime(); \
  BENCHMARK_CAPTURE(BM_reconstruct_topology_on_all_cores, label, name)                                        \
    ->Unit(benchmark::kMillisecond)->Iterations(3)->UseRealTime()

SOUP_TOPOLOGY_GAP_BENCHMARKS(bunny_jitter_1e-7, "bunny 1e-7");
SOUP_TOPOLOGY_GAP_BENCHMARKS(bunny_jitter_1e-6, "bunny 1e-6");
SOUP_TOPOLOGY_GAP_BENCHMARKS(torus, "torus");

} // namespace

BENCHMARK_MAIN();
