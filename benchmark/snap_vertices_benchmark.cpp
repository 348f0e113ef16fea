// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Epsilon welding of a jittered exploded soup (issue 4), side by side in one run with the exact
// weld of the same soup without jitter, and with CGAL's snap_borders + stitch_borders.
//
// Inputs, made once per process from clean/bunny00.off (75,408 triangles):
// - "1M": split 1-to-4 twice (1,206,528 triangles), exploded (every triangle with its own 3
//   corners);
// - "100k": split 1-to-4 once (301,632 triangles), the 100,000 triangles of smallest centroid x
//   (a patch of the bunny with a border of its own), exploded;
// - "1M_shuffled": the 1M soups with their triangles in a random order (the same for both):
//   triangles in no spatial order are the worst case of every table the welds read.
// Each exists un-jittered and jittered: every corner moved independently by a uniform random
// amount in [-j, j] on each coordinate, j = 1e-6 x diagonal / sqrt(3) (so by at most 1e-6 x the
// bounding-box diagonal). The tolerance is 1e-5 x the diagonal.
//
// Benchmarks (CPU time; the soups are copied outside the timed region where needed):
// - BM_exact_weld: index_triangles + Adjacency_tables of the un-jittered soup (the reference);
// - BM_epsilon_weld: index_triangles + Adjacency_tables + snap_vertices of the jittered soup;
// - BM_CGAL_snap_borders (100k only): PMP::merge_duplicate_points_in_polygon_soup (CGAL's exact
//   weld), orient_polygon_soup, polygon_soup_to_polygon_mesh, then
//   PMP::experimental::snap_borders with a constant tolerance, then PMP::stitch_borders.
// Counters: "border_edges" left at the end (the un-jittered reference shows the real border of
// the input: 0 at 1M, the border of the patch at 100k), and per-phase CPU times "*_ms".
// Target (issue 4): the epsilon weld closes what the exact weld closes, at most 3x its time.
//
// Run: snap_vertices_benchmark [--benchmark_filter=...]; data from SOUP_TOPOLOGY_DATA_DIR/clean.

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/index_triangles.h>
#include <Soup_topology/parameters.h>
#include <Soup_topology/snap_vertices.h>

#include "../test/soup_generators.h"
#include "../test/test_utilities.h"
#include "benchmark_utilities.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/internal/Snapping/snap.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/property_map.h>

#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <ctime>
#include <random>
#include <string>
#include <vector>

namespace ST = Soup_topology;
namespace PMP = CGAL::Polygon_mesh_processing;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Explicit_triangle = std::array<Point, 3>;
using Index_triangle = std::array<std::size_t, 3>;
using Mesh = CGAL::Surface_mesh<Point>;

namespace {

using soup_benchmark::thread_cpu_ms;
using soup_benchmark::diagonal;

struct Soups
{
  std::vector<Explicit_triangle> exact;      // exploded, un-jittered
  std::vector<Explicit_triangle> jittered;   // the same, every corner jittered
  double tolerance = 0;                      // 1e-5 x diagonal
};

enum class Size { one_million, hundred_thousand, one_million_shuffled };

Soups make_soups(Size size)
{
  std::vector<Point> points;
  std::vector<Index_triangle> triangles;
  soup_test::read_data_mesh("clean/bunny00.off.xz", points, triangles);
  soup_test::subdivide_midpoints(points, triangles);
  if(size == Size::one_million) soup_test::subdivide_midpoints(points, triangles);
  else {
    // The 100,000 triangles of smallest centroid x: one patch with one border.
    auto cx = [&](const Index_triangle& t) { return points[t[0]].x() + points[t[1]].x() + points[t[2]].x(); };
    std::nth_element(triangles.begin(), triangles.begin() + 100000, triangles.end(),
                     [&](const Index_triangle& a, const Index_triangle& b) { return cx(a) < cx(b); });
    triangles.resize(100000);
  }
  const double diag = diagonal(points);
  Soups s;
  s.tolerance = 1e-5 * diag;
  s.exact = soup_test::explode(points, triangles);
  s.jittered = s.exact;
  std::mt19937_64 rng(2026);
  const double j = 1e-6 * diag / std::sqrt(3.0);
  std::uniform_real_distribution<double> d(-j, j);
  for(Explicit_triangle& t : s.jittered)
    for(Point& p : t) p = Point(p.x() + d(rng), p.y() + d(rng), p.z() + d(rng));
  return s;
}

const Soups& soups(Size size)
{
  if(size == Size::one_million) {
    static const Soups big = make_soups(Size::one_million);
    return big;
  }
  if(size == Size::one_million_shuffled) {
    static const Soups shuffled = [] {
      Soups s = soups(Size::one_million);
      std::vector<std::size_t> order(s.exact.size());
      for(std::size_t i = 0; i < order.size(); ++i) order[i] = i;
      std::shuffle(order.begin(), order.end(), std::mt19937_64(2027));
      Soups out;
      out.tolerance = s.tolerance;
      for(std::size_t i : order) {
        out.exact.push_back(s.exact[i]);
        out.jittered.push_back(s.jittered[i]);
      }
      return out;
    }();
    return shuffled;
  }
  static const Soups small = make_soups(Size::hundred_thousand);
  return small;
}

void BM_exact_weld(benchmark::State& state, Size size)
{
  const Soups& in = soups(size);
  double index_ms = 0, tables_ms = 0;
  std::size_t border = 0, vertices = 0;
  for(auto _ : state) {
    const double t0 = thread_cpu_ms();
    std::vector<Point> points;
    std::vector<Index_triangle> triangles;
    ST::index_triangles(in.exact, points, triangles);
    const double t1 = thread_cpu_ms();
    const ST::Adjacency_tables tables(triangles, points.size());
    tables_ms = thread_cpu_ms() - t1;
    index_ms = t1 - t0;
    border = tables.number_of_border_edges();
    vertices = points.size();
  }
  state.counters["triangles"] = static_cast<double>(in.exact.size());
  state.counters["index_ms"] = index_ms;
  state.counters["tables_ms"] = tables_ms;
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["border_edges"] = static_cast<double>(border);
}
BENCHMARK_CAPTURE(BM_exact_weld, 1M, Size::one_million)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_exact_weld, 100k, Size::hundred_thousand)->Unit(benchmark::kMillisecond)->Iterations(5);
BENCHMARK_CAPTURE(BM_exact_weld, 1M_shuffled, Size::one_million_shuffled)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_epsilon_weld(benchmark::State& state, Size size)
{
  const Soups& in = soups(size);
  double index_ms = 0, tables_ms = 0, snap_ms = 0;
  std::size_t border_before = 0, border = 0, vertices = 0;
  ST::Snap_report report;
  for(auto _ : state) {
    const double t0 = thread_cpu_ms();
    std::vector<Point> points;
    std::vector<Index_triangle> triangles;
    ST::index_triangles(in.jittered, points, triangles);
    const double t1 = thread_cpu_ms();
    ST::Adjacency_tables tables(triangles, points.size());
    const double t2 = thread_cpu_ms();
    report = ST::snap_vertices(points, triangles, tables, CGAL::parameters::snapping_tolerance(in.tolerance));
    snap_ms = thread_cpu_ms() - t2;
    tables_ms = t2 - t1;
    index_ms = t1 - t0;
    border_before = report.border_edges_before;
    border = tables.number_of_border_edges();
    vertices = points.size() - report.merged_vertices;
  }
  state.counters["triangles"] = static_cast<double>(in.jittered.size());
  state.counters["index_ms"] = index_ms;
  state.counters["tables_ms"] = tables_ms;
  state.counters["snap_ms"] = snap_ms;
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["border_before"] = static_cast<double>(border_before);
  state.counters["border_edges"] = static_cast<double>(border);
  state.counters["ambiguous"] = static_cast<double>(report.ambiguous_sites.size());
  state.counters["refused"] = static_cast<double>(report.refused());
}
BENCHMARK_CAPTURE(BM_epsilon_weld, 1M, Size::one_million)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_epsilon_weld, 100k, Size::hundred_thousand)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_epsilon_weld, 1M_shuffled, Size::one_million_shuffled)->Unit(benchmark::kMillisecond)
  ->Iterations(3);

std::size_t border_edges(const Mesh& mesh)
{
  std::size_t n = 0;
  for(Mesh::Halfedge_index h : mesh.halfedges())
    if(mesh.is_border(h)) ++n;
  return n;
}

void BM_CGAL_snap_borders(benchmark::State& state, Size size)
{
  const Soups& in = soups(size);
  double weld_ms = 0, mesh_ms = 0, snap_ms = 0, stitch_ms = 0;
  std::size_t border_after_mesh = 0, border = 0, snapped = 0;
  for(auto _ : state) {
    state.PauseTiming();
    std::vector<Point> points;
    std::vector<Index_triangle> polygons;
    for(const Explicit_triangle& t : in.jittered) {
      const std::size_t i = points.size();
      points.insert(points.end(), t.begin(), t.end());
      polygons.push_back({i, i + 1, i + 2});
    }
    state.ResumeTiming();
    const double t0 = thread_cpu_ms();
    PMP::merge_duplicate_points_in_polygon_soup(points, polygons);
    const double t1 = thread_cpu_ms();
    Mesh mesh;
    PMP::orient_polygon_soup(points, polygons);
    PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
    const double t2 = thread_cpu_ms();
    border_after_mesh = border_edges(mesh);
    const double t3 = thread_cpu_ms();
    snapped = PMP::experimental::snap_borders(
      mesh, CGAL::Constant_property_map<Mesh::Vertex_index, double>(in.tolerance));
    const double t4 = thread_cpu_ms();
    PMP::stitch_borders(mesh);
    const double t5 = thread_cpu_ms();
    weld_ms = t1 - t0;
    mesh_ms = t2 - t1;
    snap_ms = t4 - t3;
    stitch_ms = t5 - t4;
    border = border_edges(mesh);
  }
  state.counters["triangles"] = static_cast<double>(in.jittered.size());
  state.counters["weld_ms"] = weld_ms;
  state.counters["to_mesh_ms"] = mesh_ms;
  state.counters["snap_ms"] = snap_ms;
  state.counters["stitch_ms"] = stitch_ms;
  state.counters["snapped"] = static_cast<double>(snapped);
  state.counters["border_before"] = static_cast<double>(border_after_mesh);
  state.counters["border_edges"] = static_cast<double>(border);
}
BENCHMARK_CAPTURE(BM_CGAL_snap_borders, 100k, Size::hundred_thousand)
  ->Unit(benchmark::kMillisecond)
  ->Iterations(1);

} // namespace

BENCHMARK_MAIN();
