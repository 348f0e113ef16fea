// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Epsilon welding: the patent's cube (tables (8)-(9) back to (5)), ADMesh's block with gaps,
// jittered exploded real meshes, order independence, idempotence, kernels, refusals.

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/index_triangles.h>
#include <Soup_topology/Octree.h>
#include <Soup_topology/snap_vertices.h>
#include <Soup_topology/split_t_junctions.h>
#include <Soup_topology/internal/tolerance_graph.h>

#include "bounded_run.h"
#include "soup_generators.h"
#include "test_utilities.h"

#include <CGAL/Point_set_3.h>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Simple_cartesian.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <ctime>
#include <fstream>
#include <functional>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <tuple>
#include <vector>

// The names of this file live in a namespace of its own: test/CMakeLists.txt compiles several
// test files as one translation unit.
namespace snap_vertices_test {

namespace {

namespace ST = Soup_topology;
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;
using Point = Epick::Point_3;
using Triangle = std::array<std::size_t, 3>;
using Tables = ST::Adjacency_tables;

const std::vector<Triangle> cube_triangles = {
  {0, 1, 3}, {2, 3, 1}, {2, 6, 3}, {7, 3, 6}, {2, 1, 6}, {5, 6, 1},
  {4, 7, 5}, {6, 5, 7}, {1, 0, 5}, {4, 5, 0}, {3, 7, 0}, {4, 0, 7}};
const std::vector<std::array<Tables::size_type, 3>> table_5 = {
  {8, 1, 10}, {2, 0, 4}, {4, 3, 1}, {10, 2, 7}, {1, 5, 2}, {7, 4, 8},
  {11, 7, 9}, {5, 6, 3}, {0, 9, 5}, {6, 8, 11}, {3, 11, 0}, {9, 10, 6}};

template <class P>
std::vector<P> cube_points()
{
  return {P(-1, -1, 1), P(1, -1, 1), P(1, 1, 1), P(-1, 1, 1), P(-1, -1, -1), P(1, -1, -1), P(1, 1, -1), P(-1, 1, -1)};
}

TEST(PatentCube, WeldingV0bRestoresTable5)
{
  // Tables (8)-(9): V0 duplicated into V0b (index 8) for T10 and T11, same coordinates.
  std::vector<Point> points = cube_points<Point>();
  points.push_back(Point(-1, -1, 1));
  std::vector<Triangle> triangles = cube_triangles;
  triangles[10] = {3, 7, 8};
  triangles[11] = {4, 8, 7};
  Tables tables(triangles, points.size());
  ASSERT_EQ(tables.number_of_border_edges(), 4u);
  const ST::Snap_report r = ST::snap_vertices(points, triangles, tables);
  EXPECT_EQ(r.merged_vertices, 1u);
  EXPECT_EQ(r.border_edges_before, 4u);
  EXPECT_EQ(r.border_edges_after, 0u);
  EXPECT_EQ(r.max_displacement, 0.0);
  EXPECT_TRUE(r.ambiguous_sites.empty());
  for(Tables::size_type t = 0; t < 12; ++t)
    for(int i = 0; i < 3; ++i) EXPECT_EQ(tables.neighbor(t, i), table_5[t][i]) << "T" << t << " edge " << i;
  EXPECT_EQ(triangles, cube_triangles);
  EXPECT_TRUE(tables.triangles_around_vertex(8).empty());
}

TEST(PatentCube, NearbyCopyWithinToleranceIsWelded)
{
  // V0b off by 1e-3: welded with tolerance 1e-2, kept with 1e-4.
  for(double tol : {1e-2, 1e-4}) {
    std::vector<Point> points = cube_points<Point>();
    points.push_back(Point(-1 + 1e-3, -1, 1));
    std::vector<Triangle> triangles = cube_triangles;
    triangles[10] = {3, 7, 8};
    triangles[11] = {4, 8, 7};
    const ST::Snap_report r = ST::snap_vertices(points, triangles, CGAL::parameters::snapping_tolerance(tol));
    EXPECT_EQ(r.merged_vertices, tol > 1e-3 ? 1u : 0u);
    EXPECT_EQ(r.border_edges_after, tol > 1e-3 ? 0u : 4u);
    EXPECT_LE(r.max_displacement, tol);
    // The representative is the lexicographically smaller point: V0 = (-1,-1,1) < V0b.
    if(tol > 1e-3) {
      EXPECT_EQ(triangles[10], (Triangle{3, 7, 0}));
    }
  }
}

template <class P>
std::pair<std::vector<P>, std::vector<Triangle>> read_stl(const std::string& relative)
{
  std::vector<P> points;
  std::vector<Triangle> triangles;
  soup_test::read_data_mesh(relative, points, triangles);
  return {points, triangles};
}

TEST(AdmeshBlock, NearbyBadClosesOnceTheToleranceCoversTheGap)
{
  // One corner is written (-1.868, 1.868, 1.868) instead of (-1.9685, 1.9685, 1.9685): 0.1005 off
  // on each axis, 0.174 away. ADMesh closes it with `-t 0.1` because its tolerance is per axis;
  // ours is a Euclidean distance and no vertex may move farther than it, so 0.1 leaves the gap
  // open and 0.2 closes it.
  auto [points, triangles] = read_stl<Point>("real_defects/admesh/block/nearby-bad.stl");
  {
    std::vector<Triangle> t = triangles;
    Tables tables(t, points.size());
    EXPECT_EQ(tables.number_of_border_edges(), 4u);
    const ST::Snap_report r = ST::snap_vertices(points, t, tables, CGAL::parameters::snapping_tolerance(0.1));
    EXPECT_EQ(r.merged_vertices, 0u);
    EXPECT_EQ(r.border_edges_after, 4u);
  }
  Tables tables(triangles, points.size());
  const ST::Snap_report r = ST::snap_vertices(points, triangles, tables, CGAL::parameters::snapping_tolerance(0.2));
  EXPECT_EQ(r.border_edges_after, 0u);
  EXPECT_TRUE(tables.is_closed());
  EXPECT_EQ(r.merged_vertices, 1u);
  EXPECT_NEAR(r.max_displacement, 0.1005039 * std::sqrt(3.0), 1e-5);
}

TEST(AdmeshBlock, ExactBadClosesWithASmallTolerance)
{
  auto [points, triangles] = read_stl<Point>("real_defects/admesh/block/exact-bad.stl");
  Tables tables(triangles, points.size());
  EXPECT_EQ(tables.number_of_border_edges(), 4u);
  const ST::Snap_report r = ST::snap_vertices(points, triangles, tables, CGAL::parameters::snapping_tolerance(1e-3));
  EXPECT_TRUE(tables.is_closed());
  EXPECT_EQ(r.merged_vertices, 1u);
  // Too small a tolerance changes nothing.
  auto [p2, t2] = read_stl<Point>("real_defects/admesh/block/exact-bad.stl");
  Tables tables2(t2, p2.size());
  const ST::Snap_report r2 = ST::snap_vertices(p2, t2, tables2, CGAL::parameters::snapping_tolerance(1e-4));
  EXPECT_EQ(r2.merged_vertices, 0u);
  EXPECT_EQ(tables2.number_of_border_edges(), 4u);
}

// An exploded soup of a real mesh, every corner jittered by up to `jitter` in each coordinate.
template <class P>
std::vector<std::array<P, 3>> jittered_soup(const std::vector<Point>& points, const std::vector<Triangle>& triangles,
                                            double jitter, unsigned seed)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> d(-jitter, jitter);
  std::vector<std::array<P, 3>> soup;
  for(const Triangle& t : triangles) {
    std::array<P, 3> tri;
    for(int k = 0; k < 3; ++k) {
      const Point& p = points[t[k]];
      tri[k] = P(p.x() + d(rng), p.y() + d(rng), p.z() + d(rng));
    }
    soup.push_back(tri);
  }
  return soup;
}

// The triangles as sets of coordinates, rotated to start at the smallest corner: equal for two
// soups that differ only by the order of triangles, the rotation of corners and vertex numbering.
template <class P>
std::multiset<std::array<std::array<double, 3>, 3>> geometric_triangles(const std::vector<P>& points,
                                                                        const std::vector<Triangle>& triangles)
{
  std::multiset<std::array<std::array<double, 3>, 3>> out;
  for(const Triangle& t : triangles) {
    std::array<std::array<double, 3>, 3> c;
    for(int k = 0; k < 3; ++k) {
      const P& p = points[t[k]];
      c[k] = {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
    }
    const int s = static_cast<int>(std::min_element(c.begin(), c.end()) - c.begin());
    out.insert({c[s], c[(s + 1) % 3], c[(s + 2) % 3]});
  }
  return out;
}

struct Weld_result
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  ST::Snap_report report;
  std::size_t border_after = 0;
  std::size_t referenced = 0;
};

std::size_t referenced_vertices(const std::vector<Triangle>& triangles, std::size_t n)
{
  std::vector<bool> used(n, false);
  for(const Triangle& t : triangles) for(std::size_t v : t) used[v] = true;
  return static_cast<std::size_t>(std::count(used.begin(), used.end(), true));
}

Weld_result weld(const std::vector<std::array<Point, 3>>& soup, double tolerance)
{
  Weld_result w;
  ST::index_triangles(soup, w.points, w.triangles);
  Tables tables(w.triangles, w.points.size());
  w.report = ST::snap_vertices(w.points, w.triangles, tables, CGAL::parameters::snapping_tolerance(tolerance));
  w.border_after = tables.number_of_border_edges();
  w.referenced = referenced_vertices(w.triangles, w.points.size());
  // The tables still describe the triangles.
  const Tables rebuilt(w.triangles, w.points.size());
  EXPECT_EQ(rebuilt.number_of_border_edges(), w.border_after);
  return w;
}

class JitteredCleanMesh : public ::testing::TestWithParam<const char*> {};

TEST_P(JitteredCleanMesh, ClosesWithoutMovingAnyVertexMoreThanTheTolerance)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  soup_test::read_data_mesh(GetParam(), points, triangles);
  const Tables original(triangles, points.size());
  const double diag = ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>());
  const auto soup = jittered_soup<Point>(points, triangles, 1e-7 * diag / std::sqrt(3.0), 7);
  const double tol = 1e-6 * diag;
  const Weld_result w = weld(soup, tol);
  EXPECT_EQ(w.border_after, original.number_of_border_edges());
  EXPECT_EQ(w.referenced, referenced_vertices(triangles, points.size()));
  EXPECT_LE(w.report.max_displacement, tol);
  EXPECT_EQ(w.report.refused(), 0u);
  EXPECT_TRUE(w.report.ambiguous_sites.empty());
  // Every triangle's corners stay within the tolerance of the jittered input corners.
  for(std::size_t t = 0; t < w.triangles.size(); ++t)
    for(int k = 0; k < 3; ++k)
      EXPECT_LE(std::sqrt(CGAL::to_double(CGAL::squared_distance(w.points[w.triangles[t][k]], soup[t][k]))), tol);
  // Idempotence: a second run changes nothing.
  std::vector<Triangle> again = w.triangles;
  Tables tables(again, w.points.size());
  const ST::Snap_report r2 = ST::snap_vertices(w.points, again, tables, CGAL::parameters::snapping_tolerance(tol));
  EXPECT_EQ(r2.merged_vertices, 0u);
  EXPECT_EQ(again, w.triangles);
}

INSTANTIATE_TEST_SUITE_P(RealMeshes, JitteredCleanMesh,
                         ::testing::Values("clean/elephant.off", "clean/fandisk.off.xz",
                                           "clean/ChineseDragon-10kv.off.xz", "clean/armadillo.off.xz",
                                           "clean/bunny00.off.xz", "clean/refined_elephant.off.xz"));

TEST(OrderIndependence, ShuffledRotatedRenumberedInputGivesTheSameSoup)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  soup_test::read_data_mesh("clean/fandisk.off.xz", points, triangles);
  const double diag = ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>());
  // A jitter as large as the tolerance: many ambiguous chains, the hardest case for order independence.
  const auto soup = jittered_soup<Point>(points, triangles, 0.6e-6 * diag, 11);
  const double tol = 1e-6 * diag;
  const Weld_result a = weld(soup, tol);

  std::mt19937 rng(3);
  std::vector<std::size_t> perm(soup.size());
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), rng);
  std::vector<std::array<Point, 3>> shuffled;
  for(std::size_t k : perm) {
    const int r = static_cast<int>(rng() % 3);
    shuffled.push_back({soup[k][r], soup[k][(r + 1) % 3], soup[k][(r + 2) % 3]});
  }
  const Weld_result b = weld(shuffled, tol);
  EXPECT_EQ(a.report.merged_vertices, b.report.merged_vertices);
  EXPECT_EQ(a.report.ambiguous_sites.size(), b.report.ambiguous_sites.size());
  EXPECT_EQ(a.border_after, b.border_after);
  EXPECT_EQ(geometric_triangles(a.points, a.triangles), geometric_triangles(b.points, b.triangles));

  // Renumbering the vertices of the indexed soup (not only the triangles) gives the same too.
  std::vector<Point> p0;
  std::vector<Triangle> t0;
  ST::index_triangles(soup, p0, t0);
  std::vector<std::size_t> relabel(p0.size());
  std::iota(relabel.begin(), relabel.end(), 0);
  std::shuffle(relabel.begin(), relabel.end(), rng);
  std::vector<Point> p1(p0.size());
  for(std::size_t i = 0; i < p0.size(); ++i) p1[relabel[i]] = p0[i];
  std::vector<Triangle> t1 = t0;
  for(Triangle& t : t1) for(std::size_t& v : t) v = relabel[v];
  ST::snap_vertices(p1, t1, CGAL::parameters::snapping_tolerance(tol));
  EXPECT_EQ(geometric_triangles(a.points, a.triangles), geometric_triangles(p1, t1));
}

TEST(Kernels, EpickAndEpeckGiveTheSameTopology)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  soup_test::read_data_mesh("clean/elephant.off", points, triangles);
  const double diag = ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>());
  const auto soup = jittered_soup<Point>(points, triangles, 0.5e-6 * diag, 5);
  const double tol = 1e-6 * diag;
  const Weld_result a = weld(soup, tol);

  std::vector<std::array<Epeck::Point_3, 3>> exact_soup;
  for(const auto& t : soup)
    exact_soup.push_back({Epeck::Point_3(t[0].x(), t[0].y(), t[0].z()), Epeck::Point_3(t[1].x(), t[1].y(), t[1].z()),
                          Epeck::Point_3(t[2].x(), t[2].y(), t[2].z())});
  std::vector<Epeck::Point_3> ep;
  std::vector<Triangle> et;
  ST::index_triangles(exact_soup, ep, et);
  Tables tables(et, ep.size());
  const ST::Snap_report r = ST::snap_vertices(ep, et, tables, CGAL::parameters::snapping_tolerance(Epeck::FT(tol)));
  EXPECT_EQ(et, a.triangles);
  EXPECT_EQ(r.merged_vertices, a.report.merged_vertices);
  EXPECT_EQ(tables.number_of_border_edges(), a.border_after);

  std::vector<std::array<CGAL::Simple_cartesian<double>::Point_3, 3>> sc_soup;
  using SP = CGAL::Simple_cartesian<double>::Point_3;
  for(const auto& t : soup)
    sc_soup.push_back({SP(t[0].x(), t[0].y(), t[0].z()), SP(t[1].x(), t[1].y(), t[1].z()), SP(t[2].x(), t[2].y(), t[2].z())});
  std::vector<SP> sp;
  std::vector<Triangle> st;
  ST::index_triangles(sc_soup, sp, st);
  ST::snap_vertices(sp, st, CGAL::parameters::snapping_tolerance(tol));
  EXPECT_EQ(st, a.triangles);
}

TEST(Refusals, VerticesOfOneTriangleAreNeverMerged)
{
  // A thin open triangle whose two vertices are 1e-4 apart, with a tolerance of 1e-3, under
  // Small_features::REFUSE (the default collapses the triangle: small_features_test.cpp).
  std::vector<Point> points = {Point(0, 0, 0), Point(1e-4, 0, 0), Point(0.5, 1, 0)};
  std::vector<Triangle> triangles = {{0, 1, 2}};
  struct Recorder
  {
    std::vector<std::tuple<std::size_t, std::size_t, ST::Refusal_reason>> refusals;
    void on_merge(std::size_t, std::size_t) { ADD_FAILURE() << "no merge expected"; }
    void on_refusal(std::size_t v, std::size_t r, ST::Refusal_reason why) { refusals.emplace_back(v, r, why); }
  } recorder;
  const ST::Snap_report r = ST::snap_vertices(
    points, triangles,
    ST::parameters::small_features(ST::Small_features::REFUSE,
                                   CGAL::parameters::snapping_tolerance(1e-3).visitor(std::ref(recorder))));
  EXPECT_EQ(r.merged_vertices, 0u);
  EXPECT_EQ(r.refused_same_triangle, 1u);
  EXPECT_EQ(r.short_edges, 1u);
  ASSERT_EQ(r.ambiguous_sites.size(), 1u);
  EXPECT_EQ(r.ambiguous_sites[0], 0u);
  ASSERT_EQ(recorder.refusals.size(), 1u);
  EXPECT_EQ(std::get<2>(recorder.refusals[0]), ST::Refusal_reason::SAME_TRIANGLE);
  EXPECT_EQ(triangles, (std::vector<Triangle>{{0, 1, 2}}));
}

TEST(Refusals, NoChainingBeyondTheTolerance)
{
  // Three border vertices on a line, 0.8 apart, tolerance 1: A-B and B-C are within it, A-C not.
  // Each belongs to its own triangle. A (smallest) takes B; C stays; the site is ambiguous. The
  // triangles' top edges are as long as the tolerance: refused, not collapsed.
  std::vector<Point> points = {Point(0, 0, 0), Point(0.8, 0, 0), Point(1.6, 0, 0),
                               Point(0, 5, 0), Point(1, 5, 0), Point(0.8, -5, 0), Point(1.8, -5, 0),
                               Point(1.6, 5, 1), Point(2.6, 5, 1)};
  std::vector<Triangle> triangles = {{0, 4, 3}, {1, 5, 6}, {2, 8, 7}};
  const ST::Snap_report r = ST::snap_vertices(
    points, triangles, ST::parameters::small_features(ST::Small_features::REFUSE, CGAL::parameters::snapping_tolerance(1.0)));
  EXPECT_LE(r.max_displacement, 1.0);
  EXPECT_EQ(triangles[1][0], 0u);   // B merged into A
  EXPECT_EQ(triangles[2][0], 2u);   // C not merged (it is 1.6 from A)
  EXPECT_FALSE(r.ambiguous_sites.empty());
}

TEST(Refusals, Issue13EquallyNearMembersJoinInLexicographicOrderWhateverTheNumbering)
{
  // A at the origin; B = (0, 1, 0) and C = (0, 0, 1) of one triangle, both at distance 1 from A
  // and sqrt(2) from each other; tolerance 1.2. Only one of B and C can join A: the tie of their
  // distances is broken by Less_xyz_3 (C before B), so C moves to A and B is refused, for every
  // numbering of the six points and both orders of the triangles (the rows of the tolerance
  // graph come in the octree's order, not sorted: the members' order must not depend on them).
  const std::array<Point, 6> named = {Point(0, 0, 0),    Point(-10, 0, -10), Point(-10, -10, 0), // A, P1, P2
                                      Point(0, 1, 0),    Point(0, 0, 1),     Point(0, 10, 10)};  // B, C, Q
  const std::array<std::array<int, 3>, 2> named_triangles = {{{0, 1, 2}, {3, 4, 5}}};
  std::array<int, 6> label = {0, 1, 2, 3, 4, 5}; // label[k]: the index of named point k
  std::size_t runs = 0;
  do {
    for(int order = 0; order < 2; ++order) {
      std::vector<Point> points(6);
      for(int k = 0; k < 6; ++k) points[static_cast<std::size_t>(label[static_cast<std::size_t>(k)])] = named[static_cast<std::size_t>(k)];
      std::vector<Triangle> triangles;
      for(int t = 0; t < 2; ++t) {
        const std::array<int, 3>& nt = named_triangles[static_cast<std::size_t>(order == 0 ? t : 1 - t)];
        triangles.push_back({static_cast<std::size_t>(label[static_cast<std::size_t>(nt[0])]),
                             static_cast<std::size_t>(label[static_cast<std::size_t>(nt[1])]),
                             static_cast<std::size_t>(label[static_cast<std::size_t>(nt[2])])});
      }
      const ST::Snap_report r = ST::snap_vertices(points, triangles, CGAL::parameters::snapping_tolerance(1.2));
      ASSERT_EQ(r.merged_vertices, 1u);
      ASSERT_EQ(r.refused_same_triangle, 1u);
      const Triangle& second = triangles[order == 0 ? 1 : 0];
      ASSERT_EQ(points[second[0]], named[3]);
      ASSERT_EQ(points[second[1]], named[0]) << "C moved to A";
      ASSERT_EQ(points[second[2]], named[5]);
      ++runs;
    }
  } while(std::next_permutation(label.begin(), label.end()));
  EXPECT_EQ(runs, 1440u);
}

TEST(Refusals, AFlipIsRefused)
{
  // Triangle (0,1,2) with vertex 2 near vertex 3 across the edge (0,1): welding 2 onto 3 would
  // reverse the triangle's normal.
  std::vector<Point> points = {Point(0, 0, 0), Point(1, 0, 0), Point(0.5, 0.01, 0), Point(0.5, -0.01, 0),
                               Point(0.5, -1, 0)};
  std::vector<Triangle> triangles = {{0, 1, 2}, {3, 1, 4}};
  // 3 < 2 lexicographically? (0.5,-0.01) < (0.5,0.01): 3 is the representative, 2 would move onto it.
  const ST::Snap_report r = ST::snap_vertices(points, triangles, CGAL::parameters::snapping_tolerance(0.05));
  EXPECT_EQ(r.merged_vertices, 0u);
  EXPECT_EQ(r.refused_flip, 1u);
}

TEST(BadInput, TolerancesAndMismatchedTables)
{
  std::vector<Point> points = cube_points<Point>();
  std::vector<Triangle> triangles = cube_triangles;
  EXPECT_THROW(ST::snap_vertices(points, triangles, CGAL::parameters::snapping_tolerance(-1.0)), ST::Invalid_input);
  EXPECT_THROW(ST::snap_vertices(points, triangles, CGAL::parameters::snapping_tolerance(std::nan(""))), ST::Invalid_input);
  EXPECT_THROW(ST::snap_vertices(points, triangles,
                                 CGAL::parameters::snapping_tolerance(std::numeric_limits<double>::infinity())),
               ST::Invalid_input);
  EXPECT_THROW(ST::snap_vertices(points, triangles, ST::parameters::relative_tolerance(-0.5)), ST::Invalid_input);
  Tables wrong(std::vector<Triangle>{{0, 1, 2}}, 3);
  EXPECT_THROW(ST::snap_vertices(points, triangles, wrong), ST::Invalid_input);
  points[3] = Point(std::nan(""), 0, 0);
  EXPECT_THROW(ST::snap_vertices(points, triangles), ST::Invalid_input);
  EXPECT_EQ(triangles, cube_triangles);
}

TEST(LargeTolerance, DoesNotDestroyTheModel)
{
  // The ADMesh block with a tolerance as large as the whole part: the triangles kept are valid.
  // Under Small_features::REFUSE merges are refused; under COLLAPSE the part is a feature
  // smaller than the tolerance and its triangles collapse.
  for(const ST::Small_features policy : {ST::Small_features::REFUSE, ST::Small_features::COLLAPSE}) {
    auto [points, triangles] = read_stl<Point>("real_defects/admesh/block/nearby-bad.stl");
    const ST::Snap_report r = ST::snap_vertices(
      points, triangles, ST::parameters::small_features(policy, CGAL::parameters::snapping_tolerance(100.0)));
    if(policy == ST::Small_features::REFUSE) {
      EXPECT_GT(r.refused(), 0u);
    }
    EXPECT_LE(r.max_displacement, 100.0);
    Epick::Collinear_3 collinear;
    for(const Triangle& t : triangles) {
      EXPECT_NE(t[0], t[1]);
      EXPECT_FALSE(collinear(points[t[0]], points[t[1]], points[t[2]]));
    }
  }
}

TEST(RelativeTolerance, IsAFractionOfTheDiagonal)
{
  auto [points, triangles] = read_stl<Point>("real_defects/admesh/block/nearby-bad.stl");
  const double diag = ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>());
  const ST::Snap_report r = ST::snap_vertices(points, triangles, ST::parameters::relative_tolerance(0.2 / diag));
  EXPECT_NEAR(r.tolerance, 0.2, 1e-12);
  EXPECT_EQ(r.border_edges_after, 0u);
}

// Issue 21: a dense cluster. `points` corners within 1e-6 of (1, 2, 3). With `shared` true, every
// triangle has its three corners in the cluster (points / 3 triangles); otherwise each triangle
// has one corner there and two far apart corners.
void write_dense_cluster(const std::string& path, std::size_t points, bool shared, unsigned seed)
{
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> near(-5e-7, 5e-7), far(10, 1000);
  const std::size_t triangles = shared ? points / 3 : points;
  std::ofstream out(path);
  out.precision(17);
  out << "OFF\n" << 3 * triangles << ' ' << triangles << " 0\n";
  for(std::size_t t = 0; t < triangles; ++t)
    for(int k = 0; k < 3; ++k) {
      if(shared || k == 0) out << 1 + near(rng) << ' ' << 2 + near(rng) << ' ' << 3 + near(rng) << '\n';
      else out << far(rng) << ' ' << far(rng) << ' ' << far(rng) << '\n';
    }
  for(std::size_t t = 0; t < triangles; ++t) out << "3 " << 3 * t << ' ' << 3 * t + 1 << ' ' << 3 * t + 2 << '\n';
}

TEST(SnapVertices, Issue21DenseCluster)
{
  // Every pair of such a cluster is within the tolerance: the tolerance graph must not be listed
  // (it took 57 s and 2 GB for 20,000 points, and 40,000 ran out of memory).
  const std::string folder = soup_test::temporary_folder("dense_cluster");
  const std::string in = folder + "/cluster.off", out = folder + "/repaired.off";
  for(const auto& [points, shared] : {std::pair<std::size_t, bool>(20000, true), std::pair<std::size_t, bool>(6666, false),
                                      std::pair<std::size_t, bool>(20000, false)}) {
    SCOPED_TRACE(std::to_string(points) + (shared ? " points, triangles inside the cluster" : " points, far corners"));
    write_dense_cluster(in, points, shared, 1);
    const soup_test::Bounded_run r =
      soup_test::run_bounded({SOUP_TOPOLOGY_CLI, "repair", in, "-o", out, "--tolerance", "1e-3"}, 20, 2048);
    EXPECT_TRUE(r.exited_normally()) << r.err;
    EXPECT_EQ(r.exit_code, 0) << r.err;
    // The sanitizers slow everything several times: there the bound of the child process
    // (ten times the time) is the check.
    if(!soup_test::sanitized_build) { EXPECT_LT(r.cpu_seconds, 2.0); }
    EXPECT_LT(r.peak_rss_mb, 500u);
  }
  // 40,000 points: the whole repair within bounds, and the weld and the split within 2 s.
  write_dense_cluster(in, 40000, true, 2);
  const soup_test::Bounded_run r =
    soup_test::run_bounded({SOUP_TOPOLOGY_CLI, "repair", in, "-o", out, "--tolerance", "1e-3"}, 30, 2048);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_LT(r.peak_rss_mb, 500u);
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  ST::IO::read_triangle_soup(in, points, triangles);
  // Under REFUSE the vertices of different triangles are welded. Under COLLAPSE every triangle
  // would collapse onto one point that no triangle keeps: the cluster, a part smaller than the
  // tolerance, is kept as it is (and the refusal costs no more than the weld).
  for(const ST::Small_features policy : {ST::Small_features::REFUSE, ST::Small_features::COLLAPSE}) {
    SCOPED_TRACE(policy == ST::Small_features::REFUSE ? "refuse" : "collapse");
    std::vector<Triangle> welded = triangles;
    Tables tables(welded, points.size());
    const std::clock_t start = std::clock();
    const ST::Snap_report snap = ST::snap_vertices(
      points, welded, tables, ST::parameters::small_features(policy, CGAL::parameters::snapping_tolerance(1e-3)));
    ST::split_t_junctions(points, welded, tables, CGAL::parameters::snapping_tolerance(1e-3));
    const double seconds = double(std::clock() - start) / CLOCKS_PER_SEC;
    if(policy == ST::Small_features::REFUSE) {
      EXPECT_GT(snap.merged_vertices, 20000u);
    } else {
      EXPECT_EQ(snap.merged_vertices, 0u);
      EXPECT_EQ(snap.collapsed_triangles, 0u);
      EXPECT_GT(snap.refused_uncovered_collapse, 20000u);
      EXPECT_EQ(welded, triangles);
    }
    if(!soup_test::sanitized_build) { EXPECT_LT(seconds, 2.0); }
  }
}

// The grid's components are those of the tolerance graph listed pair by pair: dense clusters
// (one cell, several cells, two clusters just beyond the tolerance) among sparse points.
TEST(SnapVertices, Issue21ToleranceGridComponentsAreExact)
{
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> unit(0, 1);
  const double eps = 1e-2;
  std::vector<Point> points;
  auto blob = [&](double x, double y, double z, double radius, std::size_t n) {
    for(std::size_t i = 0; i < n; ++i)
      points.emplace_back(x + radius * (2 * unit(rng) - 1), y + radius * (2 * unit(rng) - 1), z + radius * (2 * unit(rng) - 1));
  };
  blob(0.5, 0.5, 0.5, 1e-6, 300);                  // one cell
  blob(0.2, 0.2, 0.2, 0.4 * eps, 400);             // several cells
  blob(0.8, 0.2, 0.2, 1e-7, 200);                  // two clusters 1.0001 eps apart
  blob(0.8 + 1.0001 * eps, 0.2, 0.2, 1e-7, 200);
  blob(0.2, 0.8, 0.8, 1e-7, 200);                  // two clusters 0.9999 eps apart
  blob(0.2 + 0.9999 * eps, 0.8, 0.8, 1e-7, 200);
  for(int i = 0; i < 3000; ++i) points.emplace_back(unit(rng), unit(rng), unit(rng));
  ST::internal::Tolerance_grid<Epick> grid(points, Epick::FT(eps), Epick());
  ASSERT_TRUE(grid.usable());
  EXPECT_GT(grid.largest_cell(), ST::internal::dense_cell_size);
  ST::internal::Union_find fast(points.size()), slow(points.size());
  grid.unite_components(fast);
  Epick::Compare_squared_distance_3 compare_sq;
  for(std::uint32_t i = 0; i < points.size(); ++i)
    for(std::uint32_t j = i + 1; j < points.size(); ++j)
      if(compare_sq(points[i], points[j], eps * eps) != CGAL::LARGER) slow.unite(i, j);
  std::size_t sets = 0;
  for(std::uint32_t i = 0; i < points.size(); ++i) {
    EXPECT_EQ(fast.find(i), slow.find(i)) << "point " << i;
    if(slow.find(i) == i) ++sets;
  }
  EXPECT_LT(sets, points.size() - 1000);
}

// Issue 21 (the ambiguous count of item 13): the report does not depend on the order of the
// triangles, the rotation of their corners or the numbering of the vertices (the sites, listed by
// vertex, follow the numbering). A dense cluster whose triangles all lie inside it, beside two
// small ones, and ALSTOM_TEST4 at 1e-2 of its diagonal.
struct Permuted_run
{
  ST::Snap_report snap;
  ST::Split_report split;
  std::multiset<std::array<std::array<double, 3>, 3>> geometry;
  std::set<std::array<double, 3>> site_points;
};

Permuted_run run_permuted(const std::vector<Point>& points, const std::vector<Triangle>& triangles, double tol,
                          unsigned seed)
{
  std::mt19937 rng(seed);
  std::vector<std::size_t> relabel(points.size());
  std::iota(relabel.begin(), relabel.end(), 0);
  std::vector<Triangle> t = triangles;
  if(seed != 0) {
    std::shuffle(relabel.begin(), relabel.end(), rng);
    std::shuffle(t.begin(), t.end(), rng);
    for(Triangle& x : t) std::rotate(x.begin(), x.begin() + rng() % 3, x.end());
  }
  std::vector<Point> p(points.size());
  for(std::size_t i = 0; i < points.size(); ++i) p[relabel[i]] = points[i];
  for(Triangle& x : t) for(std::size_t& v : x) v = relabel[v];
  Tables tables(t, p.size());
  Permuted_run run;
  run.snap = ST::snap_vertices(p, t, tables, CGAL::parameters::snapping_tolerance(tol));
  run.split = ST::split_t_junctions(p, t, tables, CGAL::parameters::snapping_tolerance(tol));
  run.geometry = geometric_triangles(p, t);
  for(std::size_t v : run.snap.ambiguous_sites) run.site_points.insert({p[v].x(), p[v].y(), p[v].z()});
  return run;
}

void expect_same_reports(const std::vector<Point>& points, const std::vector<Triangle>& triangles, double tol)
{
  const Permuted_run a = run_permuted(points, triangles, tol, 0);
  for(unsigned seed = 1; seed <= 4; ++seed) {
    SCOPED_TRACE("permutation " + std::to_string(seed));
    const Permuted_run b = run_permuted(points, triangles, tol, seed);
    EXPECT_EQ(a.snap.candidate_vertices, b.snap.candidate_vertices);
    EXPECT_EQ(a.snap.merged_vertices, b.snap.merged_vertices);
    EXPECT_EQ(a.snap.clusters, b.snap.clusters);
    EXPECT_EQ(a.snap.refused_same_triangle, b.snap.refused_same_triangle);
    EXPECT_EQ(a.snap.refused_degenerate, b.snap.refused_degenerate);
    EXPECT_EQ(a.snap.refused_flip, b.snap.refused_flip);
    EXPECT_EQ(a.snap.refused_holds_welds, b.snap.refused_holds_welds);
    EXPECT_EQ(a.snap.ambiguous_sites.size(), b.snap.ambiguous_sites.size());
    EXPECT_EQ(a.site_points, b.site_points);
    EXPECT_EQ(a.snap.short_edges, b.snap.short_edges);
    EXPECT_EQ(a.snap.border_edges_after, b.snap.border_edges_after);
    EXPECT_EQ(a.snap.max_displacement, b.snap.max_displacement);
    EXPECT_EQ(a.split.t_junctions, b.split.t_junctions);
    EXPECT_EQ(a.split.split_triangles, b.split.split_triangles);
    EXPECT_EQ(a.split.refused_overlap, b.split.refused_overlap);
    EXPECT_EQ(a.split.refused_degenerate, b.split.refused_degenerate);
    EXPECT_EQ(a.split.refused_flip, b.split.refused_flip);
    EXPECT_EQ(a.split.ambiguous, b.split.ambiguous);
    EXPECT_EQ(a.split.border_edges_after, b.split.border_edges_after);
    EXPECT_EQ(a.geometry, b.geometry);
  }
}

TEST(SnapVertices, Issue21ReportDoesNotDependOnOrderInADenseCluster)
{
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> near(-5e-7, 5e-7);
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  for(std::size_t t = 0; t < 400; ++t) {
    for(int k = 0; k < 3; ++k) points.emplace_back(1 + near(rng), 2 + near(rng), 3 + near(rng));
    triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
  }
  // Two triangles whose corners are pairwise within the tolerance: a short-edge site.
  for(const double x : {5.0, 5.0005}) {
    const std::size_t v = points.size();
    points.emplace_back(x, 0, 0);
    points.emplace_back(x + 0.0004, 0.0003, 0);
    points.emplace_back(x, 0.0006, 0.0002);
    triangles.push_back({v, v + 1, v + 2});
  }
  expect_same_reports(points, triangles, 1e-3);
}

TEST(SnapVertices, Issue21ReportDoesNotDependOnOrderOnAlstom)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  soup_test::read_data_mesh("cad/ALSTOM_TEST4.off", points, triangles);
  const double diag = ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>());
  expect_same_reports(points, triangles, 1e-2 * diag);
}

// Issue 20: points read through property maps of every kind give the results of plain points.
using Coordinate_triple = std::array<double, 3>;

/// a readable map that constructs the point: `get` returns by value.
struct By_value_point_map
{
  using key_type = Coordinate_triple;
  using value_type = Point;
  using reference = Point;
  using category = boost::readable_property_map_tag;
  friend Point get(const By_value_point_map&, const Coordinate_triple& c) { return Point(c[0], c[1], c[2]); }
};

/// the same, readable and writable.
struct Read_write_point_map
{
  using key_type = Coordinate_triple;
  using value_type = Point;
  using reference = Point;
  using category = boost::read_write_property_map_tag;
  friend Point get(const Read_write_point_map&, const Coordinate_triple& c) { return Point(c[0], c[1], c[2]); }
  friend void put(const Read_write_point_map&, Coordinate_triple& c, const Point& p) { c = {p.x(), p.y(), p.z()}; }
};

struct By_value_kind
{
  using Range = std::vector<Coordinate_triple>;
  using Map = By_value_point_map;
  static Range make(const std::vector<Point>& p)
  {
    Range r;
    for(const Point& q : p) r.push_back({q.x(), q.y(), q.z()});
    return r;
  }
  static Map map(const Range&) { return Map(); }
};
struct Read_write_kind : By_value_kind
{
  using Map = Read_write_point_map;
  static Map map(const Range&) { return Map(); }
};
struct Reference_kind
{
  using Range = std::vector<std::pair<Point, int>>;
  using Map = CGAL::First_of_pair_property_map<std::pair<Point, int>>;
  static Range make(const std::vector<Point>& p)
  {
    Range r;
    for(const Point& q : p) r.emplace_back(q, 0);
    return r;
  }
  static Map map(const Range&) { return Map(); }
};
struct Point_set_kind
{
  using Range = CGAL::Point_set_3<Point>;
  using Map = Range::Point_map;
  static Range make(const std::vector<Point>& p)
  {
    Range r;
    for(const Point& q : p) r.insert(q);
    return r;
  }
  static Map map(const Range& r) { return r.point_map(); }
};

template <class Kind>
class PointMaps : public ::testing::Test {};
using Map_kinds = ::testing::Types<By_value_kind, Read_write_kind, Reference_kind, Point_set_kind>;
TYPED_TEST_SUITE(PointMaps, Map_kinds);

TYPED_TEST(PointMaps, Issue20ByValuePointMap)
{
  // ALSTOM_TEST4: welds and T-junctions at 1e-3 of its diagonal.
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  soup_test::read_data_mesh("cad/ALSTOM_TEST4.off", points, triangles);
  const double diag = ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>());
  const double tol = 1e-3 * diag;

  std::vector<Triangle> plain_triangles = triangles;
  Tables plain_tables(plain_triangles, points.size());
  const ST::Snap_report plain_snap =
    ST::snap_vertices(points, plain_triangles, plain_tables, CGAL::parameters::snapping_tolerance(tol));
  const ST::Split_report plain_split =
    ST::split_t_junctions(points, plain_triangles, plain_tables, CGAL::parameters::snapping_tolerance(tol));
  ASSERT_GT(plain_snap.merged_vertices, 0u);
  ASSERT_GT(plain_split.split_triangles, 0u);

  const typename TypeParam::Range range = TypeParam::make(points);
  const auto map = TypeParam::map(range);
  std::vector<Triangle> mapped_triangles = triangles;
  Tables mapped_tables(mapped_triangles, points.size());
  const ST::Snap_report snap = ST::snap_vertices(range, mapped_triangles, mapped_tables,
                                                 CGAL::parameters::snapping_tolerance(tol).point_map(map));
  const ST::Split_report split = ST::split_t_junctions(range, mapped_triangles, mapped_tables,
                                                       CGAL::parameters::snapping_tolerance(tol).point_map(map));
  EXPECT_EQ(snap.merged_vertices, plain_snap.merged_vertices);
  EXPECT_EQ(snap.clusters, plain_snap.clusters);
  EXPECT_EQ(snap.ambiguous_sites, plain_snap.ambiguous_sites);
  EXPECT_EQ(snap.short_edges, plain_snap.short_edges);
  EXPECT_EQ(snap.refused(), plain_snap.refused());
  EXPECT_EQ(split.t_junctions, plain_split.t_junctions);
  EXPECT_EQ(split.split_triangles, plain_split.split_triangles);
  EXPECT_EQ(split.ambiguous, plain_split.ambiguous);
  EXPECT_EQ(mapped_triangles, plain_triangles);

  // The octree over the mapped range answers as over the points.
  const ST::Octree<Epick> plain_tree(points);
  const ST::Octree<Epick, typename TypeParam::Map> tree(range, map);
  for(std::size_t i = 0; i < points.size(); i += 7) {
    std::vector<std::size_t> expected, found;
    plain_tree.vertices_near_point(points[i], tol, std::back_inserter(expected));
    tree.vertices_near_point(points[i], tol, std::back_inserter(found));
    EXPECT_EQ(found, expected);
    EXPECT_EQ(tree.nearest_vertex(points[i], tol), plain_tree.nearest_vertex(points[i], tol));
    const Point& a = points[i];
    const Point& b = points[(i + 1) % points.size()];
    expected.clear();
    found.clear();
    plain_tree.vertices_near_segment(a, b, tol, std::back_inserter(expected));
    tree.vertices_near_segment(a, b, tol, std::back_inserter(found));
    EXPECT_EQ(found, expected);
  }
}

// Issue 19: the decisions on real meshes, pinned: every field of the report and a digest of the
// welded triangles (their coordinates, in the canonical form of `geometric_triangles`), the same
// for the soup as given and shuffled, rotated and renumbered. The jitter is drawn from the raw
// output of `std::mt19937_64`, which the standard fixes, so the soups are the same everywhere.
std::vector<std::array<Point, 3>> portable_jittered_soup(const std::vector<Point>& points,
                                                         const std::vector<Triangle>& triangles, double jitter,
                                                         unsigned seed)
{
  std::mt19937_64 rng(seed);
  const auto offset = [&] { return jitter * (2 * (static_cast<double>(rng() >> 11) * 0x1.0p-53) - 1); };
  std::vector<std::array<Point, 3>> soup;
  for(const Triangle& t : triangles) {
    std::array<Point, 3> tri;
    for(int k = 0; k < 3; ++k) {
      const Point& p = points[t[k]];
      const double x = p.x() + offset(), y = p.y() + offset(), z = p.z() + offset();
      tri[k] = Point(x, y, z);
    }
    soup.push_back(tri);
  }
  return soup;
}

std::uint64_t geometry_digest(const std::vector<Point>& points, const std::vector<Triangle>& triangles)
{
  std::uint64_t h = 1469598103934665603ull; // FNV-1a over the bits of the coordinates
  for(const auto& triangle : geometric_triangles(points, triangles))
    for(const auto& corner : triangle)
      for(const double c : corner) {
        std::uint64_t bits;
        std::memcpy(&bits, &c, sizeof bits);
        h = (h ^ bits) * 1099511628211ull;
      }
  return h;
}

struct Pinned_weld
{
  std::size_t candidate_vertices, merged_vertices, clusters, refused_same_triangle, refused_degenerate,
    refused_flip, ambiguous_sites, short_edges, border_edges_after;
  double max_displacement;
  std::uint64_t digest;
};

void expect_pinned(const ST::Snap_report& r, const std::uint64_t digest, const Pinned_weld& expected)
{
  EXPECT_EQ(r.candidate_vertices, expected.candidate_vertices);
  EXPECT_EQ(r.merged_vertices, expected.merged_vertices);
  EXPECT_EQ(r.clusters, expected.clusters);
  EXPECT_EQ(r.refused_same_triangle, expected.refused_same_triangle);
  EXPECT_EQ(r.refused_degenerate, expected.refused_degenerate);
  EXPECT_EQ(r.refused_flip, expected.refused_flip);
  EXPECT_EQ(r.refused_holds_welds, 0u);
  EXPECT_EQ(r.ambiguous_sites.size(), expected.ambiguous_sites);
  EXPECT_EQ(r.short_edges, expected.short_edges);
  EXPECT_EQ(r.border_edges_after, expected.border_edges_after);
  EXPECT_NEAR(r.max_displacement, expected.max_displacement, 1e-5 * expected.max_displacement);
  EXPECT_EQ(digest, expected.digest); // the welded coordinates, bit for bit
}

TEST(SnapVertices, Issue19DecisionsArePinnedOnAJitteredFandisk)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  soup_test::read_data_mesh("clean/fandisk.off.xz", points, triangles);
  const double diag = ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>());
  // A jitter close to the tolerance: chains, ambiguous sites and partial clusters.
  const auto soup = portable_jittered_soup(points, triangles, 0.6e-6 * diag, 19);
  const double tol = 1e-6 * diag;
  const Pinned_weld expected{38838, 25928, 9568, 0, 0, 0, 5151, 0, 25588, 1.45208e-06, 7516485718312082217ull};
  const Weld_result a = weld(soup, tol);
  expect_pinned(a.report, geometry_digest(a.points, a.triangles), expected);

  std::mt19937 rng(5);
  std::vector<std::array<Point, 3>> shuffled = soup;
  std::shuffle(shuffled.begin(), shuffled.end(), rng);
  for(auto& t : shuffled) std::rotate(t.begin(), t.begin() + rng() % 3, t.end());
  const Weld_result b = weld(shuffled, tol);
  expect_pinned(b.report, geometry_digest(b.points, b.triangles), expected);
}

TEST(SnapVertices, Issue19DecisionsArePinnedOnAlstom)
{
  // A CAD model welded at 1e-3 of its diagonal: refusals of every geometric kind and short
  // edges under Small_features::REFUSE; under COLLAPSE the short edges among the border vertices
  // collapse, which closes 7 more border edges and leaves no refusal.
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  soup_test::read_data_mesh("cad/ALSTOM_TEST4.off", points, triangles);
  const double tol = 1e-3 * ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>());
  const Pinned_weld refused{231, 18, 16, 17, 0, 2, 5, 33, 217, 0.876195, 15065967198876123558ull};
  const Pinned_weld collapsed{231, 26, 20, 0, 0, 0, 3, 33, 210, 0.876195, 897685457778439310ull};
  for(unsigned k = 0; k < 6; ++k) {
    const unsigned seed = k % 3;
    const ST::Small_features policy = k < 3 ? ST::Small_features::REFUSE : ST::Small_features::COLLAPSE;
    const Pinned_weld& expected = k < 3 ? refused : collapsed;
    SCOPED_TRACE("permutation " + std::to_string(seed) + (k < 3 ? ", refuse" : ", collapse"));
    std::mt19937 rng(seed);
    std::vector<std::size_t> relabel(points.size());
    std::iota(relabel.begin(), relabel.end(), 0);
    std::vector<Triangle> t = triangles;
    if(seed != 0) {
      std::shuffle(relabel.begin(), relabel.end(), rng);
      std::shuffle(t.begin(), t.end(), rng);
      for(Triangle& x : t) std::rotate(x.begin(), x.begin() + rng() % 3, x.end());
    }
    std::vector<Point> p(points.size());
    for(std::size_t i = 0; i < points.size(); ++i) p[relabel[i]] = points[i];
    for(Triangle& x : t) for(std::size_t& v : x) v = relabel[v];
    const ST::Snap_report r =
      ST::snap_vertices(p, t, ST::parameters::small_features(policy, CGAL::parameters::snapping_tolerance(tol)));
    expect_pinned(r, geometry_digest(p, t), expected);
  }
}

// Issue 19: a visitor given by value is copied (the caller's object is not told), one given as
// `std::ref` is told of every decision; both see the same decisions.
struct Counting_visitor
{
  std::size_t merges = 0, refusals = 0;
  std::size_t* shared_merges = nullptr;
  void on_merge(std::size_t, std::size_t) { ++merges; if(shared_merges != nullptr) ++*shared_merges; }
  void on_refusal(std::size_t, std::size_t, ST::Refusal_reason) { ++refusals; }
};

TEST(SnapVertices, Issue19VisitorIsCopiedUnlessGivenByReference)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  soup_test::read_data_mesh("cad/ALSTOM_TEST4.off", points, triangles);
  const double tol = 1e-3 * ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>());
  std::size_t merges_seen_by_copy = 0;
  Counting_visitor by_value;
  by_value.shared_merges = &merges_seen_by_copy;
  std::vector<Triangle> t1 = triangles;
  // Small_features::REFUSE, for refusals to be told.
  const ST::Snap_report r1 = ST::snap_vertices(
    points, t1,
    ST::parameters::small_features(ST::Small_features::REFUSE, CGAL::parameters::visitor(by_value).snapping_tolerance(tol)));
  EXPECT_EQ(by_value.merges, 0u);
  EXPECT_EQ(merges_seen_by_copy, r1.merged_vertices);
  Counting_visitor by_reference;
  std::vector<Triangle> t2 = triangles;
  const ST::Snap_report r2 = ST::snap_vertices(
    points, t2,
    ST::parameters::small_features(ST::Small_features::REFUSE,
                                   CGAL::parameters::snapping_tolerance(tol).visitor(std::ref(by_reference))));
  EXPECT_EQ(by_reference.merges, r2.merged_vertices);
  EXPECT_EQ(by_reference.refusals, r2.refused());
  EXPECT_GT(r2.refused(), 0u);
  EXPECT_EQ(t1, t2);
}

// Issue 14: the merges of a weld that rebuilds its tables are told by blocks when the visitor
// takes them in any order (the default one), on one thread in index order to any other visitor;
// both give the same report, to the bit of the largest displacement, and the same soup. A visitor
// that says it takes them in any order (`tells_merges_concurrently`) is told of every merge once.
struct Merge_recording_visitor
{
  std::vector<std::size_t>* representative_of = nullptr; // by duplicate
  void on_merge(std::size_t duplicate, std::size_t representative) { (*representative_of)[duplicate] = representative; }
  void on_refusal(std::size_t, std::size_t, ST::Refusal_reason) {}
};
struct Merge_recording_visitor_in_any_order : Merge_recording_visitor
{
  static constexpr bool tells_merges_concurrently = true;
};

TEST(SnapVertices, Issue14MergesToldByBlocksGiveTheReportOfTheVisitorsLoop)
{
  static_assert(ST::internal::tells_merges_concurrently<ST::Default_snap_visitor>::value, "");
  static_assert(!ST::internal::tells_merges_concurrently<Merge_recording_visitor>::value, "");
  static_assert(ST::internal::tells_merges_concurrently<Merge_recording_visitor_in_any_order>::value, "");
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  soup_test::read_data_mesh("clean/fandisk.off.xz", points, triangles);
  const double diag = ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>());
  const auto soup = portable_jittered_soup(points, triangles, 0.6e-6 * diag, 19);
  std::vector<Point> p;
  std::vector<Triangle> t;
  ST::index_triangles(soup, p, t);
  const auto np = CGAL::parameters::snapping_tolerance(1e-6 * diag);
  const auto run = [&](const auto& parameters, auto tag) {
    Weld_result w;
    w.points = p;
    w.triangles = t;
    Tables tables(w.triangles, w.points.size());
    w.report = ST::snap_vertices<decltype(tag)>(w.points, w.triangles, tables, parameters);
    return w;
  };
  std::vector<std::size_t> told(p.size(), std::size_t(-1)), told_in_any_order(p.size(), std::size_t(-1));
  Merge_recording_visitor in_order;
  in_order.representative_of = &told;
  Merge_recording_visitor_in_any_order any_order;
  any_order.representative_of = &told_in_any_order;
  const Weld_result expected = run(np.visitor(std::ref(in_order)), CGAL::Sequential_tag());
  ASSERT_GT(expected.report.merged_vertices, t.size() / 16 + 64); // (the tables are rebuilt)
  EXPECT_EQ(std::size_t(std::count_if(told.begin(), told.end(), [](std::size_t r) { return r != std::size_t(-1); })),
            expected.report.merged_vertices);
  const auto bits = [](double x) {
    std::uint64_t b = 0;
    std::memcpy(&b, &x, sizeof b);
    return b;
  };
  const auto same = [&](const Weld_result& w) {
    EXPECT_EQ(w.report.merged_vertices, expected.report.merged_vertices);
    EXPECT_EQ(w.report.clusters, expected.report.clusters);
    EXPECT_EQ(bits(w.report.max_displacement), bits(expected.report.max_displacement));
    EXPECT_EQ(w.triangles, expected.triangles);
  };
  same(run(np, CGAL::Sequential_tag()));
  same(run(np, CGAL::Parallel_if_available_tag()));
  same(run(np.visitor(std::ref(any_order)), CGAL::Parallel_if_available_tag()));
  EXPECT_EQ(told_in_any_order, told);
}

// Issue 13: soups on which each cancellation of the guard makes one more cancellation necessary,
// so that the guard needs one pass per link of the chain. The indices of the vertices of link i
// are given by the functions below, for the expected decisions.
struct Guard_chain
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  double tolerance = 0;
  std::vector<std::size_t> moving, representative; // link i: vertex moving[i] would go to representative[i]
};

// A chain of flips. Vertices a_i = (i, 0, 0), i = 0..n, and triangles (a_i, a_(i+1), r_i) with
// r_i = (i + 2.5, 0.01, 0): thin triangles whose edge [a_i, a_(i+1)] may move up by 0.005 as a
// whole, but not one end alone (the triangle would flip). Each a_i, i >= 1, has a copy
// b_i = a_i + (-0.001, 0.005, 0) in a triangle of its own, lexicographically smaller: a_i would
// move to b_i. a_0 has none, so the triangle (a_0, a_1, r_0) flips and cancels the move of a_1,
// which makes (a_1, a_2, r_1) flip, and so on: n passes of the guard, each cancelling one move.
Guard_chain flip_chain(std::size_t n)
{
  Guard_chain c;
  c.tolerance = 0.006;
  for(std::size_t i = 0; i <= n; ++i) c.points.push_back(Point(double(i), 0, 0));
  for(std::size_t i = 0; i < n; ++i) {
    c.points.push_back(Point(i + 2.5, 0.01, 0));
    c.triangles.push_back({i, i + 1, n + 1 + i});
  }
  for(std::size_t i = 1; i <= n; ++i) {
    const std::size_t b = c.points.size();
    const double x = i - 0.001;
    c.points.push_back(Point(x, 0.005, 0));
    c.points.push_back(Point(x + 0.3, 0.005, 1));
    c.points.push_back(Point(x, 0.305, 1));
    c.triangles.push_back({b, b + 1, b + 2});
    c.moving.push_back(i);
    c.representative.push_back(b);
  }
  return c;
}

// A chain of uncovered collapses (Small_features::COLLAPSE). Vertices b_i = (i, 0, 0), i = 0..n,
// and a_i = b_i + (0.01, 0.01, 0), i = 1..n, which would merge into b_i; a_0 = (0, 0.5, 0) far
// from everything. The sliver t_i = (a_i, b_i, b_(i-1)) collapses onto the edge [b_(i-1), b_i],
// which only K_i = (a_(i-1), b_i, z_i) covers, through the move of a_(i-1) to b_(i-1) (z_i far
// away). a_0 does not move, so t_1 is uncovered and the move of a_1 is cancelled, which uncovers
// t_2, and so on: n passes, each cancelling one move.
Guard_chain collapse_chain(std::size_t n)
{
  Guard_chain c;
  c.tolerance = 0.05;
  for(std::size_t i = 0; i <= n; ++i) c.points.push_back(Point(double(i), 0, 0));       // b_i: i
  c.points.push_back(Point(0, 0.5, 0));                                                 // a_0: n + 1
  for(std::size_t i = 1; i <= n; ++i) c.points.push_back(Point(i + 0.01, 0.01, 0));     // a_i: n + 1 + i
  for(std::size_t i = 1; i <= n; ++i) c.points.push_back(Point(i - 0.5, 5, 0));         // z_i: 2n + 1 + i
  for(std::size_t i = 1; i <= n; ++i) {
    c.triangles.push_back({n + 1 + i, i, i - 1});
    c.triangles.push_back({n + i, i, 2 * n + 1 + i});
    c.moving.push_back(n + 1 + i);
    c.representative.push_back(i);
  }
  return c;
}

struct Decision_recorder
{
  std::vector<std::pair<std::size_t, std::size_t>> merges;
  std::vector<std::tuple<std::size_t, std::size_t, ST::Refusal_reason>> refusals;
  void on_merge(std::size_t v, std::size_t r) { merges.emplace_back(v, r); }
  void on_refusal(std::size_t v, std::size_t r, ST::Refusal_reason why) { refusals.emplace_back(v, r, why); }
};

// Welds `chain` under `policy`; every link is refused for `reason`, in the order of the chain (one
// pass each), nothing is merged and the triangles are unchanged. Returns the processor time.
double expect_chain_refused(const Guard_chain& chain, ST::Small_features policy, ST::Refusal_reason reason)
{
  std::vector<Triangle> triangles = chain.triangles;
  Decision_recorder recorder;
  const std::clock_t start = std::clock();
  const ST::Snap_report r = ST::snap_vertices(
    chain.points, triangles,
    ST::parameters::small_features(
      policy, CGAL::parameters::snapping_tolerance(chain.tolerance).visitor(std::ref(recorder))));
  const double seconds = double(std::clock() - start) / CLOCKS_PER_SEC;
  const std::size_t n = chain.moving.size();
  EXPECT_EQ(r.merged_vertices, 0u);
  EXPECT_EQ(r.clusters, 0u);
  EXPECT_EQ(r.collapsed_triangles, 0u);
  EXPECT_EQ(r.refused(), n);
  EXPECT_EQ(r.refused_flip, reason == ST::Refusal_reason::FLIP ? n : 0u);
  EXPECT_EQ(r.refused_uncovered_collapse, reason == ST::Refusal_reason::UNCOVERED_COLLAPSE ? n : 0u);
  EXPECT_EQ(r.refused_same_triangle, reason == ST::Refusal_reason::SAME_TRIANGLE ? n : 0u);
  EXPECT_TRUE(recorder.merges.empty());
  EXPECT_EQ(triangles, chain.triangles);
  if(reason != ST::Refusal_reason::SAME_TRIANGLE) {
    EXPECT_TRUE(r.ambiguous_sites.empty()); // each component went to one representative
    std::vector<std::tuple<std::size_t, std::size_t, ST::Refusal_reason>> expected;
    for(std::size_t i = 0; i < n; ++i) expected.emplace_back(chain.moving[i], chain.representative[i], reason);
    EXPECT_EQ(recorder.refusals, expected);
  }
  return seconds;
}

TEST(SnapVertices, Issue13ChainOfFlipsIsRefusedLinkByLink)
{
  const Guard_chain small = flip_chain(5);
  for(const ST::Small_features policy : {ST::Small_features::REFUSE, ST::Small_features::COLLAPSE})
    expect_chain_refused(small, policy, ST::Refusal_reason::FLIP);
  // One pass per link: a pass after the first checks the triangles the previous one changed,
  // not every moved triangle, so the chain costs time linear in its length.
  const Guard_chain chain = flip_chain(32000);
  for(const ST::Small_features policy : {ST::Small_features::REFUSE, ST::Small_features::COLLAPSE}) {
    const double seconds = expect_chain_refused(chain, policy, ST::Refusal_reason::FLIP);
    if(!soup_test::sanitized_build) { EXPECT_LT(seconds, 5.0); }
  }
}

TEST(SnapVertices, Issue13ChainOfUncoveredCollapsesIsRefusedLinkByLink)
{
  const Guard_chain small = collapse_chain(5);
  expect_chain_refused(small, ST::Small_features::COLLAPSE, ST::Refusal_reason::UNCOVERED_COLLAPSE);
  // Under REFUSE each a_i shares the sliver with b_i: refused, and no guard.
  expect_chain_refused(small, ST::Small_features::REFUSE, ST::Refusal_reason::SAME_TRIANGLE);
  // Linear in the length of the chain, as above.
  const Guard_chain chain = collapse_chain(32000);
  const double seconds = expect_chain_refused(chain, ST::Small_features::COLLAPSE, ST::Refusal_reason::UNCOVERED_COLLAPSE);
  if(!soup_test::sanitized_build) { EXPECT_LT(seconds, 5.0); }
}

// The weld and the splitter read the points once; a vector of points under the identity map (the
// pipeline's case) is used as it is, any other point map gives a copy of the points it reads.
TEST(SnapVertices, Issue13PointsUnderTheIdentityMapAreNotCopied)
{
  const std::vector<Point> points = {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0)};
  std::vector<Point> storage;
  const auto identity = CGAL::parameters::default_values();
  using Identity_helper = ST::internal::Soup_np_helper<std::vector<Point>, std::decay_t<decltype(identity)>>;
  EXPECT_EQ(&Identity_helper::points_as_vector(points, identity, storage), &points);
  EXPECT_TRUE(storage.empty());
  const auto by_value = CGAL::parameters::point_map(CGAL::Identity_property_map_no_lvalue<Point>());
  using By_value_helper = ST::internal::Soup_np_helper<std::vector<Point>, std::decay_t<decltype(by_value)>>;
  const std::vector<Point>& read = By_value_helper::points_as_vector(points, by_value, storage);
  EXPECT_EQ(&read, &storage);
  EXPECT_EQ(read, points);
}

// The weld numbers its candidates in the octree's order while it forms the clusters, and by
// vertex again before it tells its merges; the same-triangle pairs keep their vertex order. A
// soup of slivers at random places (vertex order and Morton order unrelated), each with two
// corners within the tolerance, and a loose triangle on copies of two of its corners: the merges are told in
// increasing vertex order; under REFUSE the first refusals are the same-triangle pairs, each told
// once as (larger vertex, smaller vertex), exactly the pairs found by brute force; under COLLAPSE
// `small_features_resolved` counts the pairs whose two vertices end at one vertex.
TEST(SnapVertices, Issue13CandidatesInTreeOrderTellDecisionsByVertex)
{
  const double tol = 0.01;
  std::mt19937 gen(1313);
  std::uniform_real_distribution<double> place(0, 10), jitter(-0.1 * tol, 0.1 * tol);
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  for(std::size_t i = 0; i < 400; ++i) {
    const Point p(place(gen), place(gen), place(gen));
    const std::size_t a = points.size();
    points.push_back(p);
    points.push_back(Point(p.x() + 0.3 * tol, p.y() + jitter(gen), p.z()));
    points.push_back(Point(p.x(), p.y() + 0.05, p.z() + 0.02));
    triangles.push_back({a, a + 1, a + 2});
    // (a copy of the sliver's first and third corners: the sliver's collapse onto its edge is
    // covered by this triangle, so that COLLAPSE keeps it)
    points.push_back(Point(p.x() + jitter(gen), p.y() + jitter(gen), p.z() - 0.2 * tol));
    points.push_back(Point(p.x() + jitter(gen), p.y() + 0.05 + jitter(gen), p.z() + 0.02));
    points.push_back(Point(p.x() + 0.04, p.y() + 0.03, p.z() - 0.03));
    triangles.push_back({a + 3, a + 4, a + 5});
  }
  // Shuffled points, so that the vertex order is unrelated to the places.
  std::vector<std::size_t> new_index(points.size());
  std::iota(new_index.begin(), new_index.end(), std::size_t(0));
  std::shuffle(new_index.begin(), new_index.end(), gen);
  std::vector<Point> shuffled(points.size());
  for(std::size_t i = 0; i < points.size(); ++i) shuffled[new_index[i]] = points[i];
  for(Triangle& t : triangles)
    for(std::size_t& v : t) v = new_index[v];
  // Brute force: the pairs of corners of one triangle within the tolerance, (larger, smaller).
  std::set<std::pair<std::size_t, std::size_t>> pairs;
  for(const Triangle& t : triangles)
    for(int i = 0; i < 3; ++i) {
      const std::size_t u = t[std::size_t(i)], v = t[std::size_t((i + 1) % 3)];
      if(CGAL::squared_distance(shuffled[u], shuffled[v]) <= tol * tol) pairs.emplace(std::max(u, v), std::min(u, v));
    }
  ASSERT_EQ(pairs.size(), 400u);
  for(const ST::Small_features policy : {ST::Small_features::REFUSE, ST::Small_features::COLLAPSE}) {
    SCOPED_TRACE(policy == ST::Small_features::REFUSE ? "refuse" : "collapse");
    std::vector<Triangle> welded = triangles;
    Decision_recorder recorder;
    const ST::Snap_report r = ST::snap_vertices(
      shuffled, welded,
      ST::parameters::small_features(policy, CGAL::parameters::snapping_tolerance(tol).visitor(std::ref(recorder))));
    ASSERT_GE(recorder.merges.size(), 100u);
    for(std::size_t k = 1; k < recorder.merges.size(); ++k)
      ASSERT_LT(recorder.merges[k - 1].first, recorder.merges[k].first) << k;
    std::vector<std::size_t> final_vertex(shuffled.size());
    std::iota(final_vertex.begin(), final_vertex.end(), std::size_t(0));
    for(const auto& [v, rep] : recorder.merges) final_vertex[v] = rep;
    if(policy == ST::Small_features::REFUSE) {
      ASSERT_GE(recorder.refusals.size(), pairs.size());
      std::set<std::pair<std::size_t, std::size_t>> told;
      for(std::size_t k = 0; k < pairs.size(); ++k) {
        const auto& [v, rep, why] = recorder.refusals[k];
        EXPECT_EQ(why, ST::Refusal_reason::SAME_TRIANGLE);
        EXPECT_GT(v, rep);
        told.emplace(v, rep);
      }
      EXPECT_EQ(told, pairs);
      EXPECT_EQ(r.small_features_resolved, 0u);
    } else {
      std::size_t resolved = 0;
      for(const auto& [u, v] : pairs) resolved += final_vertex[u] == final_vertex[v];
      EXPECT_GT(resolved, 0u);
      EXPECT_EQ(r.small_features_resolved, resolved);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Per-vertex tolerances (`vertex_tolerance_map`): a pair u, v is within tolerance when
// |uv| <= min(t_u, t_v).

// Everything a weld visitor is told, in order: (0, duplicate, representative, 0) for a merge,
// (1, vertex, representative, reason) for a refusal.
struct Weld_log
{
  std::vector<std::array<std::size_t, 4>> told;
  void on_merge(std::size_t d, std::size_t r) { told.push_back({0, d, r, 0}); }
  void on_refusal(std::size_t v, std::size_t r, ST::Refusal_reason why)
  { told.push_back({1, v, r, static_cast<std::size_t>(why)}); }
};

void expect_same_snap_report(const ST::Snap_report& a, const ST::Snap_report& b)
{
  EXPECT_EQ(a.tolerance, b.tolerance);
  EXPECT_EQ(a.candidate_vertices, b.candidate_vertices);
  EXPECT_EQ(a.merged_vertices, b.merged_vertices);
  EXPECT_EQ(a.clusters, b.clusters);
  EXPECT_EQ(a.refused_same_triangle, b.refused_same_triangle);
  EXPECT_EQ(a.refused_degenerate, b.refused_degenerate);
  EXPECT_EQ(a.refused_flip, b.refused_flip);
  EXPECT_EQ(a.refused_holds_welds, b.refused_holds_welds);
  EXPECT_EQ(a.ambiguous_sites, b.ambiguous_sites);
  EXPECT_EQ(a.short_edges, b.short_edges);
  EXPECT_EQ(a.border_edges_before, b.border_edges_before);
  EXPECT_EQ(a.border_edges_after, b.border_edges_after);
  EXPECT_EQ(a.max_displacement, b.max_displacement);
  EXPECT_EQ(a.small_features_resolved, b.small_features_resolved);
  EXPECT_EQ(a.collapsed_triangles, b.collapsed_triangles);
  EXPECT_EQ(a.refused_uncovered_collapse, b.refused_uncovered_collapse);
}

// The weld with the map of constant value `tol` and with `snapping_tolerance(tol)`, under both
// policies: the same triangles, the same visitor calls in the same order, the same report.
void expect_constant_map_welds_as_one_tolerance(const std::vector<Point>& points, const std::vector<Triangle>& triangles,
                                                double tol)
{
  const std::vector<double> constant(points.size(), tol);
  for(const ST::Small_features policy : {ST::Small_features::REFUSE, ST::Small_features::COLLAPSE}) {
    SCOPED_TRACE(policy == ST::Small_features::REFUSE ? "refuse" : "collapse");
    std::vector<Triangle> t1 = triangles, t2 = triangles;
    Weld_log v1, v2;
    const ST::Snap_report r1 = ST::snap_vertices(
      points, t1, ST::parameters::small_features(policy, CGAL::parameters::snapping_tolerance(tol).visitor(std::ref(v1))));
    const ST::Snap_report r2 = ST::snap_vertices(
      points, t2,
      ST::parameters::small_features(
        policy, ST::parameters::vertex_tolerance_map(CGAL::make_property_map(constant)).visitor(std::ref(v2))));
    EXPECT_GT(r1.merged_vertices, 0u);
    EXPECT_EQ(t1, t2);
    EXPECT_EQ(v1.told, v2.told);
    expect_same_snap_report(r1, r2);
  }
}

TEST(VertexToleranceMap, ConstantMapWeldsAsOneToleranceOnRealAndGeneratedSoups)
{
  {
    SCOPED_TRACE("ALSTOM_TEST4 at 1e-3 of its diagonal");
    std::vector<Point> points;
    std::vector<Triangle> triangles;
    soup_test::read_data_mesh("cad/ALSTOM_TEST4.off", points, triangles);
    expect_constant_map_welds_as_one_tolerance(
      points, triangles, 1e-3 * ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>()));
  }
  std::vector<Point> elephant;
  std::vector<Triangle> elephant_triangles;
  soup_test::read_data_mesh("clean/elephant.off", elephant, elephant_triangles);
  const double diag = ST::internal::bounding_box_diagonal(elephant, CGAL::Identity_property_map<Point>());
  {
    SCOPED_TRACE("elephant exploded and jittered by about the tolerance");
    std::vector<Point> points;
    std::vector<Triangle> triangles;
    ST::index_triangles(jittered_soup<Point>(elephant, elephant_triangles, 0.6e-6 * diag, 11), points, triangles);
    expect_constant_map_welds_as_one_tolerance(points, triangles, 1e-6 * diag);
  }
  {
    SCOPED_TRACE("elephant cut into patches with T-junctions");
    const auto soup = soup_test::t_junction_soup(elephant, elephant_triangles, 5, 1e-7 * diag, 17);
    expect_constant_map_welds_as_one_tolerance(soup.points, soup.triangles, 1e-6 * diag);
  }
  {
    SCOPED_TRACE("elephant with features smaller than the tolerance");
    const double jitter = 1e-5 * diag;
    const auto soup = soup_test::small_feature_soup(elephant, elephant_triangles, 10, jitter, 0.5, 8 * jitter, 3);
    expect_constant_map_welds_as_one_tolerance(soup.points, soup.triangles, 8 * jitter);
  }
}

// The patent's cube with V0 copied 1e-3 away (V0b, index 8): welded only when the tolerances of
// both V0 and V0b reach 1e-3; a large tolerance on one side does not pull the other.
TEST(VertexToleranceMap, APairIsWeldedOnlyWithinTheSmallerOfItsTolerances)
{
  std::vector<Point> points = cube_points<Point>();
  points.push_back(Point(-1 + 1e-3, -1, 1));
  std::vector<Triangle> base = cube_triangles;
  base[10] = {3, 7, 8};
  base[11] = {4, 8, 7};
  struct Case
  {
    double t0, t8;
    std::size_t merged;
  };
  for(const Case& c : {Case{1e-2, 1e-4, 0}, Case{1e-4, 1e-2, 0}, Case{1e-2, 1e-2, 1}, Case{2e-3, 1.5e-3, 1},
                       Case{1e-2, 0, 0}}) {
    SCOPED_TRACE("t(V0) = " + std::to_string(c.t0) + ", t(V0b) = " + std::to_string(c.t8));
    std::vector<double> t(points.size(), 0.5);  // the other vertices: within 0.5 of no border vertex
    t[0] = c.t0;
    t[8] = c.t8;
    std::vector<Triangle> triangles = base;
    Weld_log log;
    const ST::Snap_report r = ST::snap_vertices(
      points, triangles, ST::parameters::vertex_tolerance_map(CGAL::make_property_map(t)).visitor(std::ref(log)));
    EXPECT_EQ(r.merged_vertices, c.merged);
    EXPECT_EQ(r.tolerance, 0.5);  // the largest of the map
    if(c.merged == 1) {
      EXPECT_EQ(triangles[10], (Triangle{3, 7, 0}));
      EXPECT_EQ(r.border_edges_after, 0u);
      EXPECT_EQ(log.told, (std::vector<std::array<std::size_t, 4>>{{0, 8, 0, 0}}));
      EXPECT_LE(r.max_displacement, std::min(c.t0, c.t8));
    } else {
      EXPECT_EQ(triangles, base);
      EXPECT_EQ(r.border_edges_after, 4u);
      EXPECT_TRUE(log.told.empty());
    }
  }
}

// The short edges (two vertices of one triangle within the tolerance of the pair) against a brute
// force over every edge, and every weld within the tolerances of both of its vertices, on an
// exploded elephant (every edge a border edge) with tolerances drawn per point around the
// jitter; shuffling the triangles, rotating their corners and renumbering the points (the map
// follows) gives the same surface, and a second run changes nothing.
TEST(VertexToleranceMap, DecisionsFollowThePairRuleWhateverTheOrder)
{
  std::vector<Point> mesh;
  std::vector<Triangle> mesh_triangles;
  soup_test::read_data_mesh("clean/elephant.off", mesh, mesh_triangles);
  const double diag = ST::internal::bounding_box_diagonal(mesh, CGAL::Identity_property_map<Point>());
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  ST::index_triangles(jittered_soup<Point>(mesh, mesh_triangles, 0.6e-6 * diag, 5), points, triangles);
  // Tolerances from 0 to 4e-6 of the diagonal, and, for the corners of every 50th triangle, as
  // long as the edges (short edges appear).
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> draw(0, 4e-6 * diag);
  std::vector<double> t(points.size());
  for(double& x : t) x = draw(rng);
  for(std::size_t f = 0; f < triangles.size(); f += 50)
    for(std::size_t v : triangles[f]) t[v] = 2e-2 * diag;

  std::size_t short_edges = 0;
  for(const Triangle& f : triangles)
    for(int k = 0; k < 3; ++k) {
      const std::size_t u = f[k], v = f[(k + 1) % 3];
      const double e = std::min(t[u], t[v]);
      if(CGAL::compare(CGAL::squared_distance(points[u], points[v]), e * e) != CGAL::LARGER) ++short_edges;
    }
  EXPECT_GT(short_edges, 0u);

  std::vector<Triangle> welded = triangles;
  Weld_log log;
  const auto np = ST::parameters::vertex_tolerance_map(CGAL::make_property_map(t));
  const ST::Snap_report r = ST::snap_vertices(points, welded, np.visitor(std::ref(log)));
  EXPECT_EQ(r.short_edges, short_edges);
  EXPECT_GT(r.merged_vertices, points.size() / 3);
  EXPECT_EQ(r.tolerance, *std::max_element(t.begin(), t.end()));
  std::size_t merges = 0;
  for(const auto& x : log.told) {
    if(x[0] != 0) continue;
    ++merges;
    const double e = std::min(t[x[1]], t[x[2]]);
    EXPECT_NE(CGAL::compare(CGAL::squared_distance(points[x[1]], points[x[2]]), e * e), CGAL::LARGER);
  }
  EXPECT_EQ(merges, r.merged_vertices);
  // An edge closes where both pairs of its ends are within their tolerances.
  EXPECT_LT(r.border_edges_after, r.border_edges_before);

  // On TBB's threads: the same triangles, visitor calls and report.
  std::vector<Triangle> welded_in_parallel = triangles;
  Weld_log parallel_log;
  const ST::Snap_report rp = ST::snap_vertices<CGAL::Parallel_if_available_tag>(
    points, welded_in_parallel, np.visitor(std::ref(parallel_log)));
  EXPECT_EQ(welded_in_parallel, welded);
  EXPECT_EQ(parallel_log.told, log.told);
  expect_same_snap_report(rp, r);

  // A second run changes nothing.
  std::vector<Triangle> again = welded;
  EXPECT_EQ(ST::snap_vertices(points, again, np).merged_vertices, 0u);
  EXPECT_EQ(again, welded);

  // Shuffled triangles, rotated corners, renumbered points (the map renumbered with them).
  std::vector<std::size_t> relabel(points.size());
  std::iota(relabel.begin(), relabel.end(), 0);
  std::shuffle(relabel.begin(), relabel.end(), rng);
  std::vector<Point> p2(points.size());
  std::vector<double> t2(points.size());
  for(std::size_t i = 0; i < points.size(); ++i) {
    p2[relabel[i]] = points[i];
    t2[relabel[i]] = t[i];
  }
  std::vector<Triangle> tri2 = triangles;
  std::shuffle(tri2.begin(), tri2.end(), rng);
  for(Triangle& f : tri2) {
    std::rotate(f.begin(), f.begin() + static_cast<std::ptrdiff_t>(rng() % 3), f.end());
    for(std::size_t& v : f) v = relabel[v];
  }
  const ST::Snap_report r2 = ST::snap_vertices(p2, tri2, ST::parameters::vertex_tolerance_map(CGAL::make_property_map(t2)));
  EXPECT_EQ(r2.merged_vertices, r.merged_vertices);
  EXPECT_EQ(r2.short_edges, r.short_edges);
  EXPECT_EQ(r2.refused(), r.refused());
  EXPECT_EQ(r2.ambiguous_sites.size(), r.ambiguous_sites.size());
  EXPECT_EQ(r2.border_edges_after, r.border_edges_after);
  EXPECT_EQ(geometric_triangles(points, welded), geometric_triangles(p2, tri2));
}

TEST(VertexToleranceMap, BadValuesAndOtherToleranceParametersAreRefused)
{
  std::vector<Point> points = cube_points<Point>();
  std::vector<Triangle> triangles = cube_triangles;
  for(const double bad : {-1e-3, std::nan(""), std::numeric_limits<double>::infinity(), 1e300}) {
    SCOPED_TRACE(bad);
    std::vector<double> t(points.size(), 1e-3);
    t[5] = bad;
    const auto np = ST::parameters::vertex_tolerance_map(CGAL::make_property_map(t));
    EXPECT_THROW(ST::snap_vertices(points, triangles, np), ST::Invalid_input);
    Tables tables(triangles, points.size());
    EXPECT_THROW(ST::split_t_junctions(points, triangles, tables, np), ST::Invalid_input);
  }
  const std::vector<double> t(points.size(), 1e-3);
  const auto map = CGAL::make_property_map(t);
  EXPECT_THROW(ST::snap_vertices(points, triangles, ST::parameters::vertex_tolerance_map(
                                                      map, CGAL::parameters::snapping_tolerance(1e-3))),
               ST::Invalid_input);
  EXPECT_THROW(ST::snap_vertices(points, triangles,
                                 ST::parameters::relative_tolerance(1e-3, ST::parameters::vertex_tolerance_map(map))),
               ST::Invalid_input);
  EXPECT_EQ(triangles, cube_triangles);
  // A zero tolerance everywhere welds nothing that is not equal (the cube has no such vertex).
  const std::vector<double> zero(points.size(), 0.0);
  const ST::Snap_report r = ST::snap_vertices(points, triangles, ST::parameters::vertex_tolerance_map(CGAL::make_property_map(zero)));
  EXPECT_EQ(r.merged_vertices, 0u);
  EXPECT_EQ(r.tolerance, 0.0);
}

} // namespace

} // namespace snap_vertices_test
