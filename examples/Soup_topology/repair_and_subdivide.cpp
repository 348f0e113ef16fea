// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Reads a broken STL soup, rebuilds its topology, subdivides it twice with Loop's scheme and
// computes the limit positions of its vertices.
// Usage: repair_and_subdivide [file.stl|off|obj|ply]

#include <Soup_topology/IO/read_triangle_soup.h>
#include <Soup_topology/loop_subdivision.h>
#include <Soup_topology/parameters.h>
#include <Soup_topology/reconstruct_topology.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <array>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <string>
#include <vector>

namespace ST = Soup_topology;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;

int main(int argc, char** argv)
{
  const std::string filename =
    argc > 1 ? argv[1] : std::string(SOUP_TOPOLOGY_DATA_DIR) + "/real_defects/openscad/bad-stl-pcbvicebar.stl";
  std::vector<K::Point_3> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  try {
    const ST::IO::Soup_read_report read = ST::IO::read_triangle_soup(filename, points, triangles);   // exact weld
    const std::size_t facets = read.input_triangles;
    ST::reconstruct_topology(points, triangles, ST::parameters::relative_tolerance(1e-6));
    const ST::Adjacency_tables repaired(triangles, points.size());
    const std::size_t border = repaired.number_of_border_edges();
    const std::size_t repaired_triangles = triangles.size();

    ST::Adjacency_tables result;
    ST::loop_subdivision(points, triangles,
                         ST::parameters::output_adjacency_tables(&result, CGAL::parameters::number_of_iterations(2)));
    const std::vector<K::Point_3> limits = ST::loop_limit_points(points, triangles);

    std::cout << filename << ": " << facets << " facets -> " << repaired_triangles << " triangles, "
              << border << " border edges after repair -> " << triangles.size() << " triangles, " << points.size()
              << " points, " << result.number_of_border_edges() << " border edges after 2 Loop levels ("
              << limits.size() << " limit points)" << std::endl;
  } catch(const std::exception& e) {
    std::cerr << filename << ": " << e.what() << std::endl;
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
