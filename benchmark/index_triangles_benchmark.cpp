// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Index representation and adjacency tables of an exploded soup (issue 2), side by side with the
// CGAL pipeline a user would otherwise write, and with the floor: reading the file.
//
// Input, made once per process: clean/bunny00.off (75,408 triangles) split 1-to-4 twice
// (1,206,528 triangles), coordinates rounded to float (so that the soup in memory and the binary
// STL hold the same points), then exploded: every triangle with its own 3 corners (3.6M corners,
// as an STL export gives). The soup is written once as a binary STL into a temporary folder.
//
// Benchmarks (CPU time; all reading is from a warm file-system cache):
// - BM_read_file: the binary STL into a std::string, nothing else (the floor);
// - BM_read_STL_triangles: the same plus Soup_topology::IO::read_STL_triangles;
// - BM_read_STL_file: Soup_topology::IO::read_STL_file, the same triangles from the file read by
//   blocks (the file's bytes never held whole);
// - BM_index_and_tables: index_triangles + Adjacency_tables on the exploded soup in memory (ours),
//   triangles in mesh order and shuffled (the worst case for every hash and table);
// - BM_non_manifold_vertices: the fans around every vertex of the welded soup, in both orders;
// - BM_read_triangle_soup_and_tables: IO::read_triangle_soup of the binary STL (welded while it
//   is decoded, the path of the command line) + Adjacency_tables, in both orders;
// - BM_ours_from_file: the whole of our path from the file: read, read_STL_triangles,
//   index_triangles, Adjacency_tables;
// - BM_CGAL_merge_orient_to_mesh: the exploded soup as an indexed soup (3 points per triangle),
//   PMP::merge_duplicate_points_in_polygon_soup, PMP::orient_polygon_soup,
//   PMP::polygon_soup_to_polygon_mesh into a Surface_mesh;
// - BM_CGAL_read_STL_orient_to_mesh: CGAL::IO::read_STL of the file (it welds while reading),
//   then orient_polygon_soup and polygon_soup_to_polygon_mesh.
// Counters "*_ms" give the CPU time of each phase (last iteration); "peak_rss_bytes_per_triangle"
// the peak resident memory of the process so far (getrusage) per input triangle, "page_faults"
// (the reads) the minor page faults of an iteration: run one
// benchmark per process (--benchmark_filter) to read it for that benchmark alone. Targets (issue 2): the CGAL
// pipeline at least 15x slower than BM_index_and_tables, BM_index_and_tables at most 2.5x
// BM_read_file.
//
// Run: index_triangles_benchmark [--benchmark_filter=...]; data from SOUP_TOPOLOGY_DATA_DIR/clean.

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/IO/STL.h>
#include <Soup_topology/IO/read_triangle_soup.h>
#include <Soup_topology/index_triangles.h>

#include "../test/soup_generators.h"
#include "../test/test_utilities.h"
#include "benchmark_utilities.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/STL.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Surface_mesh.h>

#include <benchmark/benchmark.h>

#include <sys/resource.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
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
using soup_benchmark::peak_resident_bytes;
using soup_benchmark::minor_page_faults;
using soup_benchmark::write_binary_STL;

struct Input
{
  std::vector<Explicit_triangle> soup;     // exploded, float coordinates, triangles in mesh order
  std::vector<Explicit_triangle> shuffled; // the same triangles in random order
  std::string stl;                         // the soup as a binary STL file
  std::string shuffled_stl;                // the shuffled soup as a binary STL file
  std::uintmax_t stl_bytes = 0;
};

enum class Order { mesh, shuffled };

const Input& input()
{
  static const Input in = [] {
    Input r;
    std::vector<Point> points;
    std::vector<Index_triangle> triangles;
    soup_test::read_data_mesh("clean/bunny00.off.xz", points, triangles);
    soup_test::subdivide_midpoints(points, triangles);
    soup_test::subdivide_midpoints(points, triangles);
    for(Point& p : points)
      p = Point(double(float(p.x())), double(float(p.y())), double(float(p.z())));
    r.soup = soup_test::explode(points, triangles);
    r.shuffled = r.soup;
    std::mt19937_64 rng(2026);
    std::shuffle(r.shuffled.begin(), r.shuffled.end(), rng);
    const std::string folder = soup_test::temporary_folder("index_triangles_benchmark");
    r.stl = folder + "/bunny_exploded.stl";
    r.shuffled_stl = folder + "/bunny_exploded_shuffled.stl";
    write_binary_STL(r.stl, r.soup, "exploded bunny00, subdivided twice");
    write_binary_STL(r.shuffled_stl, r.shuffled, "exploded bunny00, subdivided twice");
    r.stl_bytes = std::filesystem::file_size(r.stl);
    return r;
  }();
  return in;
}

void set_common_counters(benchmark::State& state)
{
  state.counters["triangles"] = static_cast<double>(input().soup.size());
  state.counters["peak_rss_bytes_per_triangle"] = peak_resident_bytes() / static_cast<double>(input().soup.size());
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(input().stl_bytes));
}

void BM_read_file(benchmark::State& state)
{
  const Input& in = input();
  const double faults = minor_page_faults();
  for(auto _ : state) {
    std::string data = ST::IO::read_file_contents(in.stl);
    benchmark::DoNotOptimize(data.data());
  }
  set_common_counters(state);
  state.counters["page_faults"] = (minor_page_faults() - faults) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_read_file)->Unit(benchmark::kMillisecond)->Iterations(5);

void BM_read_STL_triangles(benchmark::State& state)
{
  const Input& in = input();
  const double faults = minor_page_faults();
  for(auto _ : state) {
    const std::string data = ST::IO::read_file_contents(in.stl);
    std::vector<Explicit_triangle> soup;
    ST::IO::read_STL_triangles(data, soup, in.stl);
    benchmark::DoNotOptimize(soup.data());
  }
  set_common_counters(state);
  state.counters["page_faults"] = (minor_page_faults() - faults) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_read_STL_triangles)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_read_STL_file(benchmark::State& state)
{
  const Input& in = input();
  const double faults = minor_page_faults();
  for(auto _ : state) {
    std::vector<Explicit_triangle> soup;
    ST::IO::read_STL_file(in.stl, soup);
    benchmark::DoNotOptimize(soup.data());
  }
  set_common_counters(state);
  state.counters["page_faults"] = (minor_page_faults() - faults) / static_cast<double>(state.iterations());
}
BENCHMARK(BM_read_STL_file)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_index_and_tables(benchmark::State& state, Order order)
{
  const Input& in = input();
  const std::vector<Explicit_triangle>& soup = order == Order::mesh ? in.soup : in.shuffled;
  double index_ms = 0, tables_ms = 0;
  std::size_t vertices = 0, border = 0;
  for(auto _ : state) {
    const double t0 = thread_cpu_ms();
    std::vector<Point> points;
    std::vector<Index_triangle> triangles;
    ST::index_triangles(soup, points, triangles);
    const double t1 = thread_cpu_ms();
    const ST::Adjacency_tables tables(triangles, points.size());
    const double t2 = thread_cpu_ms();
    index_ms = t1 - t0;
    tables_ms = t2 - t1;
    vertices = points.size();
    border = tables.number_of_border_edges();
    benchmark::DoNotOptimize(tables.number_of_triangles());
  }
  set_common_counters(state);
  state.counters["index_ms"] = index_ms;
  state.counters["tables_ms"] = tables_ms;
  state.counters["vertices"] = static_cast<double>(vertices);
  state.counters["border_edges"] = static_cast<double>(border);
}
BENCHMARK_CAPTURE(BM_index_and_tables, mesh_order, Order::mesh)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_index_and_tables, shuffled, Order::shuffled)->Unit(benchmark::kMillisecond)->Iterations(3);

// The fans around every vertex (`Adjacency_tables::non_manifold_vertices()`, which the pipeline's
// report, the orientation's separation and the statistics of the written file run) on the welded
// soup's tables, in both orders: in random order a walk from triangle to triangle waits for a cache
// miss at every step unless the rows are asked for ahead (issue 13).
void BM_non_manifold_vertices(benchmark::State& state, Order order)
{
  const Input& in = input();
  std::vector<Point> points;
  std::vector<Index_triangle> triangles;
  ST::index_triangles(order == Order::mesh ? in.soup : in.shuffled, points, triangles);
  const ST::Adjacency_tables tables(triangles, points.size());
  std::size_t found = 0;
  for(auto _ : state) {
    found = tables.non_manifold_vertices().size();
    benchmark::DoNotOptimize(found);
  }
  set_common_counters(state);
  state.counters["vertices"] = static_cast<double>(points.size());
  state.counters["non_manifold_vertices"] = static_cast<double>(found);
}
BENCHMARK_CAPTURE(BM_non_manifold_vertices, mesh_order, Order::mesh)->Unit(benchmark::kMillisecond)->Iterations(10);
BENCHMARK_CAPTURE(BM_non_manifold_vertices, shuffled, Order::shuffled)->Unit(benchmark::kMillisecond)->Iterations(10);

// The path of read_triangle_soup() (and of the command line): the binary STL welded while it is
// decoded, then the tables.
void BM_read_triangle_soup_and_tables(benchmark::State& state, Order order)
{
  const Input& in = input();
  const std::string& file = order == Order::mesh ? in.stl : in.shuffled_stl;
  double read_ms = 0, tables_ms = 0;
  for(auto _ : state) {
    const double t0 = thread_cpu_ms();
    std::vector<Point> points;
    std::vector<Index_triangle> triangles;
    ST::IO::read_triangle_soup(file, points, triangles);
    const double t1 = thread_cpu_ms();
    const ST::Adjacency_tables tables(triangles, points.size());
    read_ms = t1 - t0;
    tables_ms = thread_cpu_ms() - t1;
    benchmark::DoNotOptimize(tables.number_of_triangles());
  }
  set_common_counters(state);
  state.counters["read_and_weld_ms"] = read_ms;
  state.counters["tables_ms"] = tables_ms;
}
BENCHMARK_CAPTURE(BM_read_triangle_soup_and_tables, mesh_order, Order::mesh)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK_CAPTURE(BM_read_triangle_soup_and_tables, shuffled, Order::shuffled)->Unit(benchmark::kMillisecond)->Iterations(3);

void BM_ours_from_file(benchmark::State& state)
{
  const Input& in = input();
  double read_ms = 0, parse_ms = 0, index_ms = 0, tables_ms = 0;
  for(auto _ : state) {
    const double t0 = thread_cpu_ms();
    std::vector<Explicit_triangle> soup;
    {
      const std::string data = ST::IO::read_file_contents(in.stl);
      const double t1 = thread_cpu_ms();
      ST::IO::read_STL_triangles(data, soup, in.stl);
      read_ms = t1 - t0;
      parse_ms = thread_cpu_ms() - t1;
    }
    const double t2 = thread_cpu_ms();
    std::vector<Point> points;
    std::vector<Index_triangle> triangles;
    ST::index_triangles(soup, points, triangles);
    const double t3 = thread_cpu_ms();
    const ST::Adjacency_tables tables(triangles, points.size());
    tables_ms = thread_cpu_ms() - t3;
    index_ms = t3 - t2;
    benchmark::DoNotOptimize(tables.number_of_triangles());
  }
  set_common_counters(state);
  state.counters["read_ms"] = read_ms;
  state.counters["parse_ms"] = parse_ms;
  state.counters["index_ms"] = index_ms;
  state.counters["tables_ms"] = tables_ms;
}
BENCHMARK(BM_ours_from_file)->Unit(benchmark::kMillisecond)->Iterations(3);

// orient_polygon_soup + polygon_soup_to_polygon_mesh, with per-phase timings.
void CGAL_orient_to_mesh(std::vector<Point>& points, std::vector<Index_triangle>& polygons, double& orient_ms,
                         double& mesh_ms, std::size_t& faces)
{
  const double t0 = thread_cpu_ms();
  PMP::orient_polygon_soup(points, polygons);
  const double t1 = thread_cpu_ms();
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  mesh_ms = thread_cpu_ms() - t1;
  orient_ms = t1 - t0;
  faces = mesh.number_of_faces();
  benchmark::DoNotOptimize(mesh.number_of_vertices());
}

void BM_CGAL_merge_orient_to_mesh(benchmark::State& state)
{
  const Input& in = input();
  double merge_ms = 0, orient_ms = 0, mesh_ms = 0;
  std::size_t faces = 0;
  for(auto _ : state) {
    state.PauseTiming();
    std::vector<Point> points;
    std::vector<Index_triangle> polygons;
    points.reserve(3 * in.soup.size());
    polygons.reserve(in.soup.size());
    for(const Explicit_triangle& t : in.soup) {
      const std::size_t i = points.size();
      points.insert(points.end(), t.begin(), t.end());
      polygons.push_back({i, i + 1, i + 2});
    }
    state.ResumeTiming();
    const double t0 = thread_cpu_ms();
    PMP::merge_duplicate_points_in_polygon_soup(points, polygons);
    merge_ms = thread_cpu_ms() - t0;
    CGAL_orient_to_mesh(points, polygons, orient_ms, mesh_ms, faces);
  }
  set_common_counters(state);
  state.counters["merge_ms"] = merge_ms;
  state.counters["orient_ms"] = orient_ms;
  state.counters["to_mesh_ms"] = mesh_ms;
  state.counters["faces"] = static_cast<double>(faces);
}
BENCHMARK(BM_CGAL_merge_orient_to_mesh)->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_CGAL_read_STL_orient_to_mesh(benchmark::State& state)
{
  const Input& in = input();
  double read_ms = 0, orient_ms = 0, mesh_ms = 0;
  std::size_t faces = 0;
  for(auto _ : state) {
    const double t0 = thread_cpu_ms();
    std::vector<Point> points;
    std::vector<Index_triangle> polygons;
    if(!CGAL::IO::read_STL(in.stl, points, polygons)) {
      state.SkipWithError("CGAL::IO::read_STL failed");
      break;
    }
    read_ms = thread_cpu_ms() - t0;
    CGAL_orient_to_mesh(points, polygons, orient_ms, mesh_ms, faces);
  }
  set_common_counters(state);
  state.counters["read_STL_ms"] = read_ms;
  state.counters["orient_ms"] = orient_ms;
  state.counters["to_mesh_ms"] = mesh_ms;
  state.counters["faces"] = static_cast<double>(faces);
}
BENCHMARK(BM_CGAL_read_STL_orient_to_mesh)->Unit(benchmark::kMillisecond)->Iterations(1);

} // namespace

BENCHMARK_MAIN();
