// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Two levels of Loop subdivision: Soup_topology::loop_subdivision on an indexed soup versus
// CGAL::Subdivision_method_3::Loop_subdivision on a Surface_mesh, side by side in one run.
// Input: clean/bunny00.off.xz (37,706 points, 75,408 triangles), or argv[1] (OFF, OBJ, PLY or
// STL); two levels give 1,206,528 triangles. Copies of the input are made outside the timing.

#include <Soup_topology/IO/read_triangle_soup.h>
#include <Soup_topology/loop_subdivision.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Subdivision_method_3/subdivision_methods_3.h>
#include <CGAL/Surface_mesh.h>

#include <benchmark/benchmark.h>

#include "../test/test_utilities.h"

#include <array>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Triangle = std::array<std::size_t, 3>;
using Mesh = CGAL::Surface_mesh<Point>;

std::string input_file = std::string(SOUP_TOPOLOGY_DATA_DIR) + "/clean/bunny00.off.xz";

struct Input
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
};

const Input& input()
{
  static const Input data = [] {
    Input in;
    Soup_topology::IO::read_triangle_soup(soup_test::decompressed_file(input_file), in.points, in.triangles);
    return in;
  }();
  return data;
}

void BM_soup_topology_loop_subdivision(benchmark::State& state)
{
  const Input& in = input();
  std::size_t triangles = 0;
  for(auto _ : state) {
    state.PauseTiming();
    std::vector<Point> points = in.points;
    std::vector<Triangle> faces = in.triangles;
    state.ResumeTiming();
    Soup_topology::loop_subdivision(points, faces, CGAL::parameters::number_of_iterations(2));
    triangles = faces.size();
    benchmark::DoNotOptimize(points.data());
  }
  state.counters["input_triangles"] = double(in.triangles.size());
  state.counters["output_triangles"] = double(triangles);
}

void BM_cgal_Loop_subdivision_Surface_mesh(benchmark::State& state)
{
  const Input& in = input();
  std::size_t triangles = 0;
  for(auto _ : state) {
    state.PauseTiming();
    Mesh mesh;
    CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(in.points, in.triangles, mesh);
    state.ResumeTiming();
    CGAL::Subdivision_method_3::Loop_subdivision(mesh, CGAL::parameters::number_of_iterations(2));
    triangles = mesh.number_of_faces();
    benchmark::DoNotOptimize(&mesh);
  }
  state.counters["input_triangles"] = double(in.triangles.size());
  state.counters["output_triangles"] = double(triangles);
}

} // namespace

BENCHMARK(BM_soup_topology_loop_subdivision)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_cgal_Loop_subdivision_Surface_mesh)->Unit(benchmark::kMillisecond)->Iterations(1);

int main(int argc, char** argv)
{
  benchmark::Initialize(&argc, argv);
  if(argc > 1) input_file = argv[1];
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
