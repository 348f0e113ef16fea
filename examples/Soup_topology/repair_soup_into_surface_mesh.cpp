// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Reads a broken STL soup, repairs it (exact and tolerance welding, T-junction splitting) into a
// CGAL::Surface_mesh and prints one line of what changed.
//   repair_soup_into_surface_mesh [file.stl [tolerance]]

#include <Soup_topology/IO/read_triangle_soup.h>
#include <Soup_topology/reconstruct_topology.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <array>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace ST = Soup_topology;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;

int main(int argc, char** argv)
{
  const std::string file = argc > 1 ? argv[1] : std::string(SOUP_TOPOLOGY_DATA_DIR) + "/cad/ALSTOM_TEST4.off";
  const double relative_tolerance = argc > 2 ? std::atof(argv[2]) : 1e-4;

  std::vector<K::Point_3> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  ST::IO::read_triangle_soup(file, points, triangles);

  CGAL::Surface_mesh<K::Point_3> mesh;
  const ST::Reconstruction_report report =
    ST::reconstruct_topology(points, triangles, mesh, ST::parameters::relative_tolerance(relative_tolerance));

  std::cout << file << ": " << report.input_triangles << " triangles, border edges " << report.border_edges_before
            << " -> " << report.border_edges_after << " (" << report.snapped_vertices << " vertices welded, "
            << report.split_triangles << " T-junction splits), " << num_faces(mesh) << " faces, valid: "
            << std::boolalpha << CGAL::is_valid_polygon_mesh(mesh) << "\n";
  return CGAL::is_valid_polygon_mesh(mesh) ? EXIT_SUCCESS : EXIT_FAILURE;
}
