// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Welds every part of an assembly with its own tolerance: the gap analysis per part
// (`analyze_gaps_per_part()`) suggests a tolerance per part, `per_part_vertex_tolerances()` gives
// it to every point of the part, and `reconstruct_topology()` welds with that map (two points
// within the smaller of their tolerances). Compared with the one tolerance of `analyze_gaps()`.
//
// Usage: weld_parts_with_their_own_tolerances [FILE]. Without a file, an assembly of two parts is
// made here: two squares of side 0.01 with a seam of 1e-6, and two squares of side 10 with a seam
// of 0.05, far apart.

#include <Soup_topology/IO/read_triangle_soup.h>
#include <Soup_topology/analyze_gaps.h>
#include <Soup_topology/reconstruct_topology.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/property_map.h>

#include <array>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace ST = Soup_topology;
using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;
using Triangle = std::array<std::size_t, 3>;

// Two squares of side `side` (two triangles each) side by side, `gap` apart, moved by `offset`.
void add_two_squares(std::vector<Point>& points, std::vector<Triangle>& triangles, double side, double gap,
                     double offset)
{
  const double x[4] = {offset, offset + side, offset + side + gap, offset + 2 * side + gap};
  for(std::size_t k = 0; k < 2; ++k) {
    const std::size_t b = points.size();
    points.emplace_back(x[2 * k], 0, 0);
    points.emplace_back(x[2 * k + 1], 0, 0);
    points.emplace_back(x[2 * k + 1], side, 0);
    points.emplace_back(x[2 * k], side, 0);
    triangles.push_back({b, b + 1, b + 2});
    triangles.push_back({b, b + 2, b + 3});
  }
}

int main(int argc, char** argv)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  if(argc > 1) {
    ST::IO::read_triangle_soup(argv[1], points, triangles);
  } else {
    add_two_squares(points, triangles, 0.01, 1e-6, 0);
    add_two_squares(points, triangles, 10, 0.05, 100);
  }

  // One tolerance for the whole soup.
  const ST::Gap_analysis whole = ST::analyze_gaps(points, triangles);
  std::cout << "one tolerance: " << ST::verdict_name(whole.verdict) << ", " << whole.suggested_tolerance << "\n";

  // One per part, then one per point.
  const std::vector<ST::Part_gap_analysis> parts = ST::analyze_gaps_per_part(points, triangles);
  for(const ST::Part_gap_analysis& part : parts)
    std::cout << "  part of " << part.triangles << " triangles, " << part.points.size() << " points: "
              << ST::verdict_name(part.verdict) << ", " << part.suggested_tolerance << "\n";
  const std::vector<double> tolerances = ST::per_part_vertex_tolerances(parts, points.size());

  std::size_t border_with_one = 0;
  if(whole.has_suggestion()) {
    std::vector<Point> p = points;
    std::vector<Triangle> t = triangles;
    border_with_one =
      ST::reconstruct_topology(p, t, CGAL::parameters::snapping_tolerance(whole.suggested_tolerance)).border_edges_after;
    std::cout << "welded with one tolerance: " << border_with_one << " border edges left\n";
  }
  const ST::Reconstruction_report r = ST::reconstruct_topology(
    points, triangles, ST::parameters::vertex_tolerance_map(CGAL::make_property_map(tolerances)));
  std::cout << "welded with the tolerance of every part: " << r.snapped_vertices << " welds, "
            << r.split_triangles << " splits, " << r.border_edges_after << " border edges left (largest tolerance "
            << r.tolerance << ", largest move " << r.max_displacement << ")\n";

  // The assembly made here: the map closes both seams (the two outlines are left), one tolerance
  // only the small one.
  if(argc <= 1 && (r.border_edges_after != 12 || border_with_one != 14)) return EXIT_FAILURE;
  return EXIT_SUCCESS;
}
