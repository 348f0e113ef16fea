// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Reproducers of what the robustness experiment (benchmark/robustness_experiment.cpp,
// doc/Soup_topology/Robustness.md) found in the library. Each soup was cut out of a failing run by
// delta debugging (triangles removed while the failure stays) and is written with hexadecimal
// floating-point literals, so the coordinates are the experiment's bit for bit.

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/reconstruct_topology.h>
#include <Soup_topology/snap_vertices.h>

#include "test_utilities.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <random>
#include <set>
#include <vector>

// The names of this file live in a namespace of its own: test/CMakeLists.txt compiles several
// test files as one translation unit.
namespace robustness_regression_test {

namespace {

namespace ST = Soup_topology;
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;
using Triangle = std::array<std::size_t, 3>;
using Coordinates = std::array<double, 3>;
using Geometric_triangle = std::array<Coordinates, 3>;

/// the triangles as geometric triangles, each from its smallest corner (orientation kept),
/// sorted: the same list means the same surface whatever the numbering.
template <class Point>
std::vector<Geometric_triangle> geometry(const std::vector<Point>& points, const std::vector<Triangle>& triangles)
{
  std::vector<Geometric_triangle> result;
  for(const Triangle& t : triangles) {
    Geometric_triangle g;
    for(std::size_t k = 0; k < 3; ++k) {
      const Point& p = points[t[k]];
      g[k] = {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
    }
    std::rotate(g.begin(), std::min_element(g.begin(), g.end()), g.end());
    result.push_back(g);
  }
  std::sort(result.begin(), result.end());
  return result;
}

template <class Kernel>
std::vector<typename Kernel::Point_3> make_points(const std::vector<Coordinates>& c)
{
  std::vector<typename Kernel::Point_3> points;
  for(const Coordinates& p : c) points.emplace_back(p[0], p[1], p[2]);
  return points;
}

/// the results of `repair` over every order of the triangles (all permutations).
template <class Repair>
std::set<std::vector<Geometric_triangle>> results_over_all_orders(const std::vector<Coordinates>& c,
                                                                  const std::vector<Triangle>& triangles,
                                                                  const Repair& repair)
{
  std::set<std::vector<Geometric_triangle>> results;
  std::vector<std::size_t> order(triangles.size());
  for(std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  do {
    auto points = make_points<Epeck>(c);
    std::vector<Triangle> soup;
    for(std::size_t i : order) soup.push_back(triangles[i]);
    repair(points, soup);
    results.insert(geometry(points, soup));
  } while(std::next_permutation(order.begin(), order.end()));
  return results;
}

// ALSTOM_TEST4 cut into patches, rotated by 0.1 degree, tolerance 10x the largest displacement
// (seed 0 of the experiment), reduced to 5 triangles. Points 0 and 1 are corners of one triangle
// 0.84 eps apart (a short edge: the minimum feature separation is not met); 4 is a copy of 0
// (0.004 eps away), 6 and 9 are copies of 1 (0.03 eps away).
const std::vector<Coordinates> alstom_points = {
  {0x1.9ac4d4ee52318p+6, 0x1.b90b50530b159p+6, 0x1.873adc863676fp+8},
  {0x1.9a931ec7aaba7p+6, 0x1.cdd9db512ba02p+6, 0x1.8374f8c1b77cbp+8},
  {0x1.1468bddb62569p+6, 0x1.d8f67a6a69d8p+6, 0x1.87a4c1ac441c5p+8},
  {0x1.57d702605deaep+6, 0x1.beb7765010d5bp+6, 0x1.8957ace65c8a9p+8},
  {0x1.9ae60acf2b522p+6, 0x1.b91205c573e18p+6, 0x1.8738ff82a4e4dp+8},
  {0x1.148f95da4acadp+6, 0x1.d913dabe293fep+6, 0x1.87a7aaa24aac3p+8},
  {0x1.9a880c12ef1bcp+6, 0x1.ce8ce82880f8ap+6, 0x1.8353e4965b9efp+8},
  {0x1.579cfcc08820fp+6, 0x1.d3d335e3762f2p+6, 0x1.857caa50cd591p+8},
  {0x1.f598f7ac9e09cp+5, 0x1.e831dcd758359p+6, 0x1.85de3cce705cep+8},
  {0x1.9aaa63a6c5772p+6, 0x1.ce929108c31e6p+6, 0x1.8351a9ff5005fp+8}};
const std::vector<Triangle> alstom_triangles = {{0, 1, 2}, {3, 4, 5}, {2, 1, 6}, {5, 7, 8}, {7, 9, 8}};
const double alstom_eps = 0x1.e8553dd9ce2a7p+2;

// Issue 21 (item 13): ALSTOM_TEST4 at 1e-2 of its diagonal, triangles shuffled and rotated: the
// number of ambiguous sites differed from one order to the next (57, 45, 47, 44, ...): a site
// was listed by its smallest vertex index, so two sites sharing that vertex under one numbering
// were one site, and two under another. Every count of the report must be the same.
TEST(RobustnessRegression, Issue21AmbiguousCountDoesNotDependOnTriangleOrder)
{
  std::vector<Epick::Point_3> points;
  std::vector<Triangle> triangles;
  soup_test::read_data_mesh("cad/ALSTOM_TEST4.off", points, triangles);
  auto repair = [&](unsigned seed) {
    std::vector<Epick::Point_3> p = points;
    std::vector<Triangle> t = triangles;
    std::mt19937 rng(seed);
    if(seed != 0) {
      std::shuffle(t.begin(), t.end(), rng);
      for(Triangle& x : t) std::rotate(x.begin(), x.begin() + rng() % 3, x.end());
    }
    const ST::Reconstruction_report r = ST::reconstruct_topology(p, t, ST::parameters::relative_tolerance(1e-2));
    return std::make_pair(r, geometry(p, t));
  };
  const auto [a, a_geometry] = repair(0);
  EXPECT_GT(a.ambiguous_sites, 0u);
  for(unsigned seed = 1; seed <= 6; ++seed) {
    SCOPED_TRACE("order " + std::to_string(seed));
    const auto [b, b_geometry] = repair(seed);
    EXPECT_EQ(a.ambiguous_sites, b.ambiguous_sites);
    EXPECT_EQ(a.ambiguous_t_junctions, b.ambiguous_t_junctions);
    EXPECT_EQ(a.snapped_vertices, b.snapped_vertices);
    EXPECT_EQ(a.clusters, b.clusters);
    EXPECT_EQ(a.refused_same_triangle, b.refused_same_triangle);
    EXPECT_EQ(a.refused_flip, b.refused_flip);
    EXPECT_EQ(a.refused_degenerate, b.refused_degenerate);
    EXPECT_EQ(a.t_junctions, b.t_junctions);
    EXPECT_EQ(a.split_triangles, b.split_triangles);
    EXPECT_EQ(a.rounds, b.rounds);
    EXPECT_EQ(a.border_edges_after, b.border_edges_after);
    EXPECT_EQ(a_geometry, b_geometry);
  }
}

} // namespace

// reconstruct_topology() promises a result independent of the order of the triangles, also at
// ambiguous sites (decided by a documented rule). Here, with Epeck (exact predicates and
// constructions), the 120 orders of 5 triangles give 2 different surfaces: one with the triangle
// (2 3 1) twice, the other with (7 1 6) twice (in the numbering above), after 3 or 4 rounds.
TEST(RobustnessRegression, PipelineResultDoesNotDependOnTriangleOrderAtAShortEdge)
{
  const auto results = results_over_all_orders(alstom_points, alstom_triangles, [](auto& points, auto& soup) {
    ST::reconstruct_topology(points, soup, CGAL::parameters::snapping_tolerance(Epeck::FT(alstom_eps)));
  });
  EXPECT_EQ(results.size(), 1u);
}

// The same failure narrowed to one step: the soup after the first weld/split round of the case
// above (which is order-independent) given to snap_vertices() alone. Its 5040 orders give 2
// different welds: in one, point 4 (0.004 eps from point 0) and point 5 go to points 6 and 2.
TEST(RobustnessRegression, SnapVerticesDoesNotDependOnTriangleOrderAtAShortEdge)
{
  const std::vector<Triangle> after_first_round = {{0, 1, 3}, {1, 2, 3}, {1, 6, 7}, {1, 7, 2},
                                                   {3, 4, 5}, {5, 7, 8}, {6, 8, 7}};
  const auto results = results_over_all_orders(alstom_points, after_first_round, [](auto& points, auto& soup) {
    ST::snap_vertices(points, soup, CGAL::parameters::snapping_tolerance(Epeck::FT(alstom_eps)));
  });
  EXPECT_EQ(results.size(), 1u);
}

// Epick's predicates are exact, so every decision should be the one Epeck takes. fandisk cut into
// patches, rotated by 0.1 degree, tolerance 10x the largest displacement (seed 1), reduced to 7
// triangles: Epick and Epeck return different surfaces. A decision taken on a constructed number
// (a squared distance in Epick's double FT) instead of a predicate: split_t_junctions() compares
// the squared distances of a vertex to two border edges with CGAL::compare(squared_distance(...)).
TEST(RobustnessRegression, EpickDecidesAsEpeck)
{
  const std::vector<Coordinates> c = {
    {-0x1.3c277801edabdp-2, -0x1.9dc74cb85b59dp-6, -0x1.a956e4dfff6fp-6},
    {-0x1.3e876414b447ep-2, -0x1.5953eb3064ce6p-5, -0x1.8dc9abc88f646p-6},
    {-0x1.4f9c3357ca421p-2, -0x1.9d692e9a58a56p-6, -0x1.a92b3bba5a553p-6},
    {-0x1.3faa40cef5937p-2, -0x1.9ef52806e6aeep-5, -0x1.7f31b3fe525a4p-6},
    {-0x1.51ad82b43fe74p-2, -0x1.59f7515d56cfbp-5, -0x1.8d9f2fe55ac17p-6},
    {-0x1.40cd1d8936df1p-2, -0x1.e49664dd688f5p-5, -0x1.7099bc3415501p-6},
    {-0x1.39ce70958929p-2, -0x1.382c3156b8e11p-4, -0x1.51db68c53ae6ep-6},
    {-0x1.4312db40ebd34p-2, -0x1.385569fdb2b24p-4, -0x1.51c6db4ed50bp-6},
    {-0x1.53a497845f591p-2, -0x1.e53a8941d5327p-5, -0x1.706ff0cc1522cp-6}};
  const std::vector<Triangle> triangles = {{0, 1, 2}, {1, 3, 4}, {3, 5, 4}, {1, 4, 2}, {6, 7, 5}, {5, 7, 8}, {5, 8, 4}};
  const double eps = 0x1.9bc43fd1c2b0ap-7;
  auto inexact = make_points<Epick>(c);
  auto exact = make_points<Epeck>(c);
  std::vector<Triangle> t1 = triangles, t2 = triangles;
  ST::reconstruct_topology(inexact, t1, CGAL::parameters::snapping_tolerance(eps));
  ST::reconstruct_topology(exact, t2, CGAL::parameters::snapping_tolerance(Epeck::FT(eps)));
  EXPECT_EQ(geometry(inexact, t1), geometry(exact, t2));
}

} // namespace robustness_regression_test
