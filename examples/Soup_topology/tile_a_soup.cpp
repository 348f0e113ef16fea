// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Cuts a soup into tiles of balanced triangle counts, writes one spill file per tile (its own
// triangles and those of its halo), reads the files back and prints what each tile holds: the
// first step of a tiled repair. With binary STL files as arguments, they are streamed as one
// assembly; without, a grid of separate triangles is made in memory.

#include <Soup_topology/Soup_tiling.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <array>
#include <cstddef>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

namespace ST = Soup_topology;
using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;

template <class Source>
int tile(const Source& source, double halo)
{
  const ST::Tile_plan plan = ST::plan_tiles(source, 4, halo);
  const std::filesystem::path folder = std::filesystem::temp_directory_path() / "soup_topology_tiles";
  std::filesystem::create_directories(folder);
  const ST::Tile_files files = ST::write_tile_files(source, plan, folder.string());
  std::cout << plan.number_of_triangles() << " triangles in " << plan.number_of_tiles() << " tiles, halo " << halo
            << "\n";
  std::size_t owned = 0;
  for(std::size_t t = 0; t < plan.number_of_tiles(); ++t) {
    const std::vector<ST::Tile_triangle> triangles = ST::read_tile_file(files.files[t]);
    std::cout << "tile " << t << ": cells " << plan.first_cell(t) << " to " << plan.first_cell(t + 1) - 1 << ", "
              << files.owned[t] << " owned, " << files.halo[t] << " in the halo, " << triangles.size() << " in its file\n";
    owned += files.owned[t];
  }
  std::filesystem::remove_all(folder);
  return owned == plan.number_of_triangles() ? 0 : 1;
}

int main(int argc, char** argv)
{
  if(argc > 1)
    return tile(ST::Binary_STL_source(std::vector<std::string>(argv + 1, argv + argc)), 1e-3);
  // 20 x 20 squares of two triangles each, every triangle with its own corners
  std::vector<Point> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  for(int i = 0; i < 20; ++i)
    for(int j = 0; j < 20; ++j) {
      const std::size_t b = points.size();
      for(const auto& c : {std::array<int, 2>{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}})
        points.push_back(Point(0.05 * (i + c[0]), 0.05 * (j + c[1]), 0));
      triangles.push_back({b, b + 1, b + 2});
      triangles.push_back({b + 3, b + 4, b + 5});
    }
  return tile(ST::Soup_triangle_source<std::vector<Point>, std::vector<std::array<std::size_t, 3>>>(points, triangles),
              0.01);
}
