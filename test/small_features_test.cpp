// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Features smaller than the tolerance (issue 18): soups cut from real meshes into patches whose
// seams hold T-junction points within the tolerance of an edge's end point, repaired under the
// two policies of `small_features`.

#include <Soup_topology/orient_triangle_soup.h>
#include <Soup_topology/reconstruct_topology.h>

#include "soup_generators.h"
#include "test_utilities.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace {

namespace ST = Soup_topology;
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Epick::Point_3;
using Triangle = std::array<std::size_t, 3>;

template <class P>
std::pair<std::vector<P>, std::vector<Triangle>> load(const std::string& relative)
{
  std::vector<P> points;
  std::vector<Triangle> triangles;
  soup_test::read_data_mesh(relative, points, triangles);
  return {points, triangles};
}

double diagonal(const std::vector<Point>& points)
{
  return ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>());
}

std::size_t count_degenerate(const std::vector<Point>& points, const std::vector<Triangle>& triangles)
{
  const Epick::Collinear_3 collinear;
  std::size_t n = 0;
  for(const Triangle& t : triangles)
    if(t[0] == t[1] || t[1] == t[2] || t[2] == t[0] || collinear(points[t[0]], points[t[1]], points[t[2]])) ++n;
  return n;
}

// What a repair left: counted on the soup, before and after the separation of non-manifold
// vertices and edges that the command-line tool does before writing (`orient_triangle_soup()`).
struct Outcome
{
  ST::Reconstruction_report report;
  std::size_t border = 0, non_manifold = 0, degenerate = 0;
  std::size_t written_border = 0, written_non_manifold = 0;
  std::vector<Point> points;
  std::vector<Triangle> triangles;
};

template <class NamedParameters>
Outcome repair(std::vector<Point> points, std::vector<Triangle> triangles, const NamedParameters& np)
{
  Outcome o;
  o.report = ST::reconstruct_topology(points, triangles, np);
  std::tie(o.border, o.non_manifold) = soup_test::count_border_and_non_manifold_edges(triangles);
  o.degenerate = count_degenerate(points, triangles);
  o.points = points;
  o.triangles = triangles;
  ST::orient_triangle_soup(points, triangles);
  std::tie(o.written_border, o.written_non_manifold) = soup_test::count_border_and_non_manifold_edges(triangles);
  return o;
}

std::string describe(const Outcome& o)
{
  const ST::Reconstruction_report& r = o.report;
  return "border " + std::to_string(r.border_edges_before) + " -> " + std::to_string(o.border) +
         ", non-manifold " + std::to_string(o.non_manifold) + ", degenerate " + std::to_string(o.degenerate) +
         ", ambiguous sites " + std::to_string(r.ambiguous_sites) + " + " + std::to_string(r.ambiguous_t_junctions) +
         ", refused welds " + std::to_string(r.refused_welds()) + ", refused splits " + std::to_string(r.refused_splits) +
         ", written border " + std::to_string(o.written_border) + ", written non-manifold " +
         std::to_string(o.written_non_manifold) + ", rounds " + std::to_string(r.rounds);
}

// The generated soup of a mesh: 10 patches, jitter 1e-5 of the diagonal per coordinate, the
// tolerance 8 times the jitter, half the split points within the tolerance of an end point.
struct Generated
{
  std::vector<Point> mesh_points;
  std::vector<Triangle> mesh_triangles;
  soup_test::Small_feature_soup<Point> soup;
  double tolerance = 0;
};

Generated generate(const std::string& file, unsigned seed)
{
  Generated g;
  std::tie(g.mesh_points, g.mesh_triangles) = load<Point>(file);
  const double jitter = 1e-5 * diagonal(g.mesh_points);
  g.tolerance = 8 * jitter;
  g.soup = soup_test::small_feature_soup(g.mesh_points, g.mesh_triangles, 10, jitter, 0.5, g.tolerance, seed);
  return g;
}

// Today's outcome on the generated soups, printed (the figures of the issue come from the
// larger meshes: run with --gtest_also_run_disabled_tests).
void print_outcomes(const std::string& file)
{
  const Generated g = generate(file, 18);
  std::cout << file << ": " << g.soup.triangles.size() << " triangles, " << g.soup.t_junctions << " T-junctions, "
            << g.soup.near_end_t_junctions << " within the tolerance of an end point\n";
  const Outcome o = repair(g.soup.points, g.soup.triangles, CGAL::parameters::snapping_tolerance(g.tolerance));
  std::cout << "  " << describe(o) << "\n";
}

TEST(SmallFeaturesMeasure, GeneratedSoups)
{
  for(const char* file : {"clean/elephant.off", "clean/fandisk.off.xz"}) print_outcomes(file);
}

TEST(SmallFeaturesMeasure, DISABLED_LargeGeneratedSoups)
{
  for(const char* file : {"clean/armadillo.off.xz", "clean/bunny00.off.xz", "clean/refined_elephant.off.xz"})
    print_outcomes(file);
}

} // namespace
