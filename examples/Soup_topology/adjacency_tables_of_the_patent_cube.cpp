// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The patent's cube given as an STL soup (36 corners): its index representation, then the
// vertex-neighbour and edge-neighbour tables, printed as in the patent's tables.

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/index_triangles.h>

#include <CGAL/Simple_cartesian.h>

#include <array>
#include <cstdlib>
#include <iostream>
#include <vector>

namespace ST = Soup_topology;
using Point = CGAL::Simple_cartesian<double>::Point_3;

int main()
{
  const Point V[8] = {Point(-1, -1, 1), Point(1, -1, 1), Point(1, 1, 1), Point(-1, 1, 1),
                      Point(-1, -1, -1), Point(1, -1, -1), Point(1, 1, -1), Point(-1, 1, -1)};
  const int T[12][3] = {{0, 1, 3}, {2, 3, 1}, {2, 6, 3}, {7, 3, 6}, {2, 1, 6}, {5, 6, 1},
                        {4, 7, 5}, {6, 5, 7}, {1, 0, 5}, {4, 5, 0}, {3, 7, 0}, {4, 0, 7}};
  std::vector<std::array<Point, 3>> stl;
  for(const auto& t : T) stl.push_back({V[t[0]], V[t[1]], V[t[2]]});

  std::vector<Point> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  ST::index_triangles(stl, points, triangles);
  const ST::Adjacency_tables adj(triangles, points.size());

  std::cout << points.size() << " vertices, " << triangles.size() << " triangles\n";
  for(ST::Adjacency_tables::size_type v = 0; v < adj.number_of_vertices(); ++v) {
    std::cout << "V" << v << ":";
    for(auto t : adj.triangles_around_vertex(v)) std::cout << " T" << t;
    std::cout << "\n";
  }
  for(ST::Adjacency_tables::size_type t = 0; t < adj.number_of_triangles(); ++t) {
    std::cout << "T" << t << ":";
    for(int i = 0; i < 3; ++i) {
      const auto u = adj.neighbor(t, i);
      if(u == ST::Adjacency_tables::border_edge) std::cout << " -1";
      else std::cout << " T" << u;
    }
    std::cout << "\n";
  }
  std::cout << (adj.is_closed() ? "closed" : "open") << "\n";
  return adj.is_closed() ? EXIT_SUCCESS : EXIT_FAILURE;
}
