// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Read time of the largest KiCad VRML file (Infineon_EasyPIM-2B, 194708 triangles) with
// Soup_topology::IO::read_VRML, against reading the same geometry as OFF with CGAL's IO
// (CGAL::IO::read_polygon_soup and CGAL::IO::read_OFF). The file is decompressed, and the OFF
// written, once before any timing; every benchmark then reads from the file system (warm cache).
// Compare the "s_per_triangle" counters.

#include <Soup_topology/IO/VRML.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/OFF.h>
#include <CGAL/IO/polygon_soup_io.h>

#include <benchmark/benchmark.h>

#include "../test/test_utilities.h"

#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = std::array<std::size_t, 3>;

struct Input
{
  std::string wrl;
  std::string off;
  std::size_t triangles = 0;
};

const Input& input()
{
  static const Input in = [] {
    namespace fs = std::filesystem;
    Input r;
    const fs::path dir = fs::temp_directory_path() / "soup_topology_VRML_benchmark";
    fs::create_directories(dir);
    r.wrl = soup_test::data_file("cad/kicad/Infineon_EasyPIM-2B.wrl.xz");
    r.off = (dir / "Infineon_EasyPIM-2B.off").string();
    std::vector<Point> points;
    std::vector<Triangle> triangles;
    Soup_topology::IO::read_VRML(r.wrl, points, triangles);
    r.triangles = triangles.size();
    // the VRML file has at most 6 significant digits: precision 6 writes the same numbers
    if(!CGAL::IO::write_polygon_soup(r.off, points, triangles, CGAL::parameters::stream_precision(6)))
      throw std::runtime_error("cannot write " + r.off);
    return r;
  }();
  return in;
}

void set_counters(benchmark::State& state, std::size_t triangles, const std::string& file)
{
  state.counters["triangles"] = static_cast<double>(triangles);
  // seconds per triangle (CPU time), printed with an SI prefix: "190n" is 190 ns
  state.counters["s_per_triangle"] = benchmark::Counter(
    static_cast<double>(triangles),
    benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations())
                          * static_cast<std::int64_t>(std::filesystem::file_size(file)));
}

void BM_read_VRML(benchmark::State& state)
{
  const Input& in = input();
  std::size_t n = 0;
  for(auto _ : state)
  {
    std::vector<Point> points;
    std::vector<Triangle> triangles;
    const auto result = Soup_topology::IO::read_VRML(in.wrl, points, triangles);
    benchmark::DoNotOptimize(result.number_of_triangles);
    n = triangles.size();
  }
  set_counters(state, n, in.wrl);
}
BENCHMARK(BM_read_VRML)->Unit(benchmark::kMillisecond);

// the parser alone, from a string already in memory
void BM_read_VRML_from_memory(benchmark::State& state)
{
  const Input& in = input();
  std::ifstream file(in.wrl, std::ios::binary);
  std::ostringstream text;
  text << file.rdbuf();
  const std::string content = text.str();
  std::size_t n = 0;
  for(auto _ : state)
  {
    std::istringstream stream(content);
    std::vector<Point> points;
    std::vector<Triangle> triangles;
    Soup_topology::IO::read_VRML(stream, points, triangles);
    n = triangles.size();
  }
  set_counters(state, n, in.wrl);
}
BENCHMARK(BM_read_VRML_from_memory)->Unit(benchmark::kMillisecond);

void BM_CGAL_read_polygon_soup_OFF(benchmark::State& state)
{
  const Input& in = input();
  std::size_t n = 0;
  for(auto _ : state)
  {
    std::vector<Point> points;
    std::vector<std::vector<std::size_t>> polygons;
    if(!CGAL::IO::read_polygon_soup(in.off, points, polygons))
      state.SkipWithError("CGAL::IO::read_polygon_soup failed");
    n = polygons.size();
  }
  if(n != in.triangles)
    state.SkipWithError("CGAL read a different number of triangles");
  set_counters(state, n, in.off);
}
BENCHMARK(BM_CGAL_read_polygon_soup_OFF)->Unit(benchmark::kMillisecond);

void BM_CGAL_read_OFF_arrays(benchmark::State& state)
{
  const Input& in = input();
  std::size_t n = 0;
  for(auto _ : state)
  {
    std::vector<Point> points;
    std::vector<Triangle> triangles;
    if(!CGAL::IO::read_OFF(in.off, points, triangles))
      state.SkipWithError("CGAL::IO::read_OFF failed");
    n = triangles.size();
  }
  set_counters(state, n, in.off);
}
BENCHMARK(BM_CGAL_read_OFF_arrays)->Unit(benchmark::kMillisecond);

} // namespace

BENCHMARK_MAIN();
