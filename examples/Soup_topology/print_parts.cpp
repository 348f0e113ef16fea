// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Reads a multi-part model, rebuilds its topology and prints its parts (edge-connected
// components) with their triangle counts and bounding boxes, using Boost.Graph on the
// triangle adjacency view.

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/IO/read_triangle_soup.h>
#include <Soup_topology/Triangle_adjacency_graph.h>

#include <CGAL/Bbox_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <boost/graph/connected_components.hpp>

#include <array>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace ST = Soup_topology;
using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;

int main(int argc, char** argv)
{
  const std::string file = argc > 1 ? argv[1] : SOUP_TOPOLOGY_DATA_DIR "/cad/ALSTOM_TEST4.off";
  std::vector<Point> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  ST::IO::read_triangle_soup(file, points, triangles);
  const ST::Adjacency_tables adj(triangles, points.size());
  const auto g = ST::triangle_adjacency_graph(adj);

  std::vector<std::size_t> part(num_vertices(g));
  const auto index = get(boost::vertex_index, g);
  const std::size_t parts = boost::connected_components(g, boost::make_iterator_property_map(part.begin(), index));

  std::vector<std::size_t> size(parts, 0);
  std::vector<CGAL::Bbox_3> box(parts);
  for(auto [t, end] = vertices(g); t != end; ++t) {
    const std::size_t p = part[get(index, *t)];
    ++size[p];
    for(std::size_t v : triangles[get(index, *t)]) box[p] += points[v].bbox();
  }
  std::cout << file << ": " << triangles.size() << " triangles, " << parts << " parts\n";
  for(std::size_t p = 0; p < parts; ++p)
    std::cout << "  part " << p << ": " << size[p] << " triangles, bbox [" << box[p].xmin() << ' ' << box[p].ymin()
              << ' ' << box[p].zmin() << "] - [" << box[p].xmax() << ' ' << box[p].ymax() << ' ' << box[p].zmax()
              << "]\n";
  return EXIT_SUCCESS;
}
