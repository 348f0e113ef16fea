// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The tiled repair (issue 15) side by side, in one run, with the in-memory repair and with the
// CGAL pipeline a user would otherwise write, all from the same binary STL file.
//
// Input, written once per process to a temporary file: a torus of U x V squares (two triangles
// each), every triangle with its own corners, every corner moved by up to 1e-6 x the bounding-box
// diagonal on each coordinate; tolerance 1e-5 x the diagonal (the jittered soup of issue 13).
// Sizes: 1M triangles (1000 x 500) and 250k (500 x 250, for CGAL).
//
// Benchmarks (wall time, one thread):
// - BM_in_memory: read_triangle_soup, then reconstruct_topology on the soup read;
// - BM_tiled/T: tiled_reconstruct_topology from the file streamed (Binary_STL_source), T tiles
//   (the spill files in a temporary folder); counters "tile_runs", "largest_tile_triangles"
//   (the most triangles one repair held: what bounds the memory), "halo_triangles";
// - BM_CGAL_pipeline: CGAL::IO::read_polygon_soup, PMP::repair_polygon_soup, orient_polygon_soup,
//   polygon_soup_to_polygon_mesh, experimental::snap_borders, stitch_borders.
// Counter "triangles": the triangles of the result (the closed torus: 2 U V).
//
// Run: tiled_reconstruct_topology_benchmark [--benchmark_filter=...].

#include <Soup_topology/IO/read_triangle_soup.h>
#include <Soup_topology/reconstruct_topology.h>
#include <Soup_topology/tiled_reconstruct_topology.h>

#include "benchmark_utilities.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/internal/Snapping/snap.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/property_map.h>

#include <benchmark/benchmark.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace {

namespace ST = Soup_topology;
namespace PMP = CGAL::Polygon_mesh_processing;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = std::array<std::uint32_t, 3>;

struct Input
{
  std::string file;
  double tolerance = 0;
  std::size_t triangles = 0;
};

// The jittered exploded torus of u x v squares, written once per size.
const Input& input(std::size_t u, std::size_t v)
{
  static std::map<std::size_t, Input> made;
  Input& in = made[u];
  if(!in.file.empty()) return in;
  const double pi = std::acos(-1.0), big = 1.5, small = 0.5;
  const auto at = [&](std::size_t i, std::size_t j) {
    const double a = 2 * pi * double(i % u) / double(u), b = 2 * pi * double(j % v) / double(v);
    return Point((big + small * std::cos(b)) * std::cos(a), (big + small * std::cos(b)) * std::sin(a), small * std::sin(b));
  };
  const double diagonal = std::sqrt(2 * 4 * 4 + 1.0 * 1.0); // box 4 x 4 x 1
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> jitter(-1e-6 * diagonal, 1e-6 * diagonal);
  const auto moved = [&](const Point& p) { return Point(p.x() + jitter(rng), p.y() + jitter(rng), p.z() + jitter(rng)); };
  std::vector<std::array<Point, 3>> soup;
  soup.reserve(2 * u * v);
  for(std::size_t i = 0; i < u; ++i)
    for(std::size_t j = 0; j < v; ++j) {
      soup.push_back({moved(at(i, j)), moved(at(i + 1, j)), moved(at(i + 1, j + 1))});
      soup.push_back({moved(at(i, j)), moved(at(i + 1, j + 1)), moved(at(i, j + 1))});
    }
  in.file = (std::filesystem::temp_directory_path() / ("soup_topology_tiled_benchmark_" + std::to_string(u) + ".stl")).string();
  soup_benchmark::write_binary_STL(in.file, soup);
  in.tolerance = 1e-5 * diagonal;
  in.triangles = soup.size();
  return in;
}

void BM_in_memory(benchmark::State& state, std::size_t u, std::size_t v)
{
  const Input& in = input(u, v);
  std::size_t triangles_out = 0;
  for(auto _ : state) {
    std::vector<Point> points;
    std::vector<Triangle> triangles;
    ST::IO::read_triangle_soup(in.file, points, triangles);
    ST::reconstruct_topology(points, triangles, CGAL::parameters::snapping_tolerance(in.tolerance));
    triangles_out = triangles.size();
  }
  state.counters["triangles"] = static_cast<double>(triangles_out);
}

void BM_tiled(benchmark::State& state, std::size_t u, std::size_t v)
{
  const Input& in = input(u, v);
  const std::filesystem::path folder = std::filesystem::temp_directory_path() / "soup_topology_tiled_benchmark_tiles";
  std::filesystem::create_directories(folder);
  ST::Tiled_reconstruction_report r;
  std::size_t triangles_out = 0;
  for(auto _ : state) {
    std::vector<Point> points;
    std::vector<Triangle> triangles;
    r = ST::tiled_reconstruct_topology(ST::Binary_STL_source({in.file}), static_cast<std::size_t>(state.range(0)),
                                       folder.string(), points, triangles,
                                       CGAL::parameters::snapping_tolerance(in.tolerance));
    triangles_out = triangles.size();
  }
  std::filesystem::remove_all(folder);
  state.counters["triangles"] = static_cast<double>(triangles_out);
  state.counters["tile_runs"] = static_cast<double>(r.tile_runs);
  state.counters["largest_tile_triangles"] = static_cast<double>(r.largest_tile_triangles);
  state.counters["halo_triangles"] = static_cast<double>(r.halo_triangles);
}

void BM_CGAL_pipeline(benchmark::State& state, std::size_t u, std::size_t v)
{
  using Mesh = CGAL::Surface_mesh<Point>;
  const Input& in = input(u, v);
  std::size_t faces = 0;
  for(auto _ : state) {
    std::vector<Point> points;
    std::vector<std::vector<std::size_t>> polygons;
    CGAL::IO::read_polygon_soup(in.file, points, polygons);
    PMP::repair_polygon_soup(points, polygons);
    PMP::orient_polygon_soup(points, polygons);
    Mesh mesh;
    PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
    PMP::experimental::snap_borders(mesh, CGAL::Constant_property_map<Mesh::Vertex_index, double>(in.tolerance));
    PMP::stitch_borders(mesh);
    faces = mesh.number_of_faces();
  }
  state.counters["triangles"] = static_cast<double>(faces);
}

BENCHMARK_CAPTURE(BM_in_memory, 1M, 1000, 500)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK_CAPTURE(BM_tiled, 1M, 1000, 500)->Arg(8)->Arg(64)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK_CAPTURE(BM_in_memory, 250k, 500, 250)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK_CAPTURE(BM_tiled, 250k, 500, 250)->Arg(8)->Arg(64)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK_CAPTURE(BM_CGAL_pipeline, 250k, 500, 250)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

} // namespace

BENCHMARK_MAIN();
