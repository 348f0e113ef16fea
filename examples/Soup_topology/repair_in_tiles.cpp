// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Repairs a soup tile by tile (tiled_reconstruct_topology()) and checks that the result is the
// one of reconstruct_topology() on the whole soup, both in the canonical order. With a binary STL
// file and a tolerance as arguments, the file is streamed (never held whole by the tiled repair);
// without, a grid of squares whose triangles have jittered copies of their corners is made.
//   repair_in_tiles [FILE.stl TOLERANCE [TILES]]

#include <Soup_topology/IO/read_triangle_soup.h>
#include <Soup_topology/reconstruct_topology.h>
#include <Soup_topology/tiled_reconstruct_topology.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <array>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <random>
#include <string>
#include <vector>

namespace ST = Soup_topology;
using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;
using Triangle = std::array<std::uint32_t, 3>;

template <class Source>
int compare(const Source& source, std::vector<Point> points, std::vector<Triangle> triangles, double tolerance,
            std::size_t tiles)
{
  const std::filesystem::path folder = std::filesystem::temp_directory_path() / "soup_topology_repair_in_tiles";
  std::filesystem::create_directories(folder);
  std::vector<Point> tiled_points;
  std::vector<Triangle> tiled_triangles;
  const ST::Tiled_reconstruction_report r = ST::tiled_reconstruct_topology(
    source, tiles, folder.string(), tiled_points, tiled_triangles, CGAL::parameters::snapping_tolerance(tolerance));
  std::filesystem::remove_all(folder);
  std::cout << r.input_triangles << " triangles in " << r.tiles << " tiles: " << r.tile_runs << " runs ("
            << r.repeated_tiles << " tiles repaired again), halo " << r.first_halo << " to " << r.largest_halo
            << ", at most " << r.largest_tile_triangles << " triangles at once; " << r.output_triangles
            << " triangles on " << r.output_points << " points\n";

  // The same repair on the whole soup, in the same order.
  ST::reconstruct_topology(points, triangles, CGAL::parameters::snapping_tolerance(tolerance));
  std::vector<Point> whole_points;
  std::vector<Triangle> whole_triangles;
  ST::canonical_triangle_soup(points, triangles, whole_points, whole_triangles);
  const bool same = whole_points == tiled_points && whole_triangles == tiled_triangles;
  std::cout << (same ? "the same as the repair of the whole soup\n" : "NOT the repair of the whole soup\n");
  return same ? 0 : 1;
}

int main(int argc, char** argv)
{
  if(argc > 2) {
    std::vector<Point> points;
    std::vector<Triangle> triangles;
    ST::IO::read_triangle_soup(argv[1], points, triangles);
    const std::size_t tiles = argc > 3 ? std::strtoul(argv[3], nullptr, 10) : 8;
    return compare(ST::Binary_STL_source({argv[1]}), points, triangles, std::atof(argv[2]), tiles);
  }
  // 60 x 60 squares of two triangles each; every triangle has its own corners, moved by up to
  // 1e-5 along each axis: the tolerance 1e-4 closes the seams.
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> jitter(-1e-5, 1e-5);
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  for(int i = 0; i < 60; ++i)
    for(int j = 0; j < 60; ++j) {
      const std::uint32_t b = static_cast<std::uint32_t>(points.size());
      for(const auto& c : {std::array<int, 2>{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}})
        points.push_back(Point(0.01 * (i + c[0]) + jitter(rng), 0.01 * (j + c[1]) + jitter(rng), jitter(rng)));
      triangles.push_back({b, b + 1, b + 2});
      triangles.push_back({b + 3, b + 4, b + 5});
    }
  return compare(ST::Soup_triangle_source<std::vector<Point>, std::vector<Triangle>>(points, triangles), points, triangles,
                 1e-4, 8);
}
