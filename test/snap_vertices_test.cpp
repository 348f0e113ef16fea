// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Epsilon welding: the patent's cube (tables (8)-(9) back to (5)), ADMesh's block with gaps,
// jittered exploded real meshes, order independence, idempotence, kernels, refusals.

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/index_triangles.h>
#include <Soup_topology/snap_vertices.h>

#include "test_utilities.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Simple_cartesian.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <functional>
#include <numeric>
#include <random>
#include <set>
#include <tuple>
#include <vector>

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
  // A thin open triangle whose two vertices are 1e-4 apart, with a tolerance of 1e-3.
  std::vector<Point> points = {Point(0, 0, 0), Point(1e-4, 0, 0), Point(0.5, 1, 0)};
  std::vector<Triangle> triangles = {{0, 1, 2}};
  struct Recorder
  {
    std::vector<std::tuple<std::size_t, std::size_t, ST::Refusal_reason>> refusals;
    void on_merge(std::size_t, std::size_t) { ADD_FAILURE() << "no merge expected"; }
    void on_refusal(std::size_t v, std::size_t r, ST::Refusal_reason why) { refusals.emplace_back(v, r, why); }
  } recorder;
  const ST::Snap_report r = ST::snap_vertices(points, triangles,
                                              CGAL::parameters::snapping_tolerance(1e-3).visitor(std::ref(recorder)));
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
  // Each belongs to its own triangle. A (smallest) takes B; C stays; the site is ambiguous.
  std::vector<Point> points = {Point(0, 0, 0), Point(0.8, 0, 0), Point(1.6, 0, 0),
                               Point(0, 5, 0), Point(1, 5, 0), Point(0.8, -5, 0), Point(1.8, -5, 0),
                               Point(1.6, 5, 1), Point(2.6, 5, 1)};
  std::vector<Triangle> triangles = {{0, 4, 3}, {1, 5, 6}, {2, 8, 7}};
  const ST::Snap_report r = ST::snap_vertices(points, triangles, CGAL::parameters::snapping_tolerance(1.0));
  EXPECT_LE(r.max_displacement, 1.0);
  EXPECT_EQ(triangles[1][0], 0u);   // B merged into A
  EXPECT_EQ(triangles[2][0], 2u);   // C not merged (it is 1.6 from A)
  EXPECT_FALSE(r.ambiguous_sites.empty());
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
  // The ADMesh block with a tolerance as large as the whole part: triangles are kept valid.
  auto [points, triangles] = read_stl<Point>("real_defects/admesh/block/nearby-bad.stl");
  const ST::Snap_report r = ST::snap_vertices(points, triangles, CGAL::parameters::snapping_tolerance(100.0));
  EXPECT_GT(r.refused(), 0u);
  Epick::Collinear_3 collinear;
  for(const Triangle& t : triangles) {
    EXPECT_NE(t[0], t[1]);
    EXPECT_FALSE(collinear(points[t[0]], points[t[1]], points[t[2]]));
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

} // namespace
