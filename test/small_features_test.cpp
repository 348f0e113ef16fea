// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Features smaller than the tolerance (issue 18): soups cut from real meshes into patches whose
// seams hold T-junction points within the tolerance of an edge's end point, repaired under the
// two policies of `small_features`.

#include <Soup_topology/internal/small_feature_degenerate.h>
#include <Soup_topology/orient_triangle_soup.h>
#include <Soup_topology/reconstruct_topology.h>

#include "soup_generators.h"
#include "test_utilities.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/distance.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <vector>

// The names of this file live in a namespace of its own: test/CMakeLists.txt compiles several
// test files as one translation unit.
namespace small_features_test {

namespace ST = Soup_topology;
namespace PMP = CGAL::Polygon_mesh_processing;
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Epick::Point_3;
using Triangle = std::array<std::size_t, 3>;
using Mesh = CGAL::Surface_mesh<Point>;
using Coordinates = std::array<double, 3>;
using Geometric_triangle = std::array<Coordinates, 3>;

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
         std::to_string(o.written_non_manifold) + ", rounds " + std::to_string(r.rounds) + ", collapsed " +
         std::to_string(r.small_feature_collapsed_triangles) + ", resolved " + std::to_string(r.small_features_resolved) +
         ", max displacement / tolerance " + std::to_string(r.max_displacement / r.tolerance);
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


// The choice of the default: on the generated soups, refusing small features leaves the seams
// open where collapsing them closes everything (the figures are printed for the manual).
TEST(SmallFeaturesPolicy, CollapseClosesWhatRefusingLeavesOpen)
{
  for(const char* file : {"clean/elephant.off", "clean/fandisk.off.xz"}) {
    SCOPED_TRACE(file);
    const Generated g = generate(file, 18);
    std::cout << file << ": " << g.soup.triangles.size() << " triangles, " << g.soup.t_junctions << " T-junctions, "
              << g.soup.near_end_t_junctions << " within the tolerance of an end point\n";
    const Outcome refused = repair(g.soup.points, g.soup.triangles,
                                   ST::parameters::small_features(ST::Small_features::REFUSE,
                                                                  CGAL::parameters::snapping_tolerance(g.tolerance)));
    const Outcome collapsed = repair(g.soup.points, g.soup.triangles,
                                     ST::parameters::small_features(ST::Small_features::COLLAPSE,
                                                                    CGAL::parameters::snapping_tolerance(g.tolerance)));
    std::cout << "  refuse:   " << describe(refused) << "\n  collapse: " << describe(collapsed) << "\n";
    EXPECT_GT(refused.written_border, 0u);
    EXPECT_GT(refused.report.ambiguous_sites, 0u);
    EXPECT_EQ(collapsed.written_border, 0u);
    EXPECT_EQ(collapsed.written_non_manifold, 0u);
    EXPECT_EQ(collapsed.report.ambiguous_sites, 0u);
  }
}

// ---------------------------------------------------------------------------------------------
// Helpers of the checks.

/// the triangles as geometric triangles, each from its smallest corner (orientation kept),
/// sorted: the same list means the same surface whatever the numbering.
std::vector<Geometric_triangle> geometry(const std::vector<Point>& points, const std::vector<Triangle>& triangles)
{
  std::vector<Geometric_triangle> result;
  for(const Triangle& t : triangles) {
    Geometric_triangle g;
    for(std::size_t k = 0; k < 3; ++k) g[k] = {points[t[k]].x(), points[t[k]].y(), points[t[k]].z()};
    std::rotate(g.begin(), std::min_element(g.begin(), g.end()), g.end());
    result.push_back(g);
  }
  std::sort(result.begin(), result.end());
  return result;
}

/// the soup with its points renumbered, its triangles reordered and their corners rotated.
void shuffle(std::vector<Point>& points, std::vector<Triangle>& triangles, unsigned seed)
{
  std::mt19937 rng(seed);
  std::vector<std::size_t> order(points.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<Point> shuffled(points.size());
  std::vector<std::size_t> new_index(points.size());
  for(std::size_t i = 0; i < order.size(); ++i) { shuffled[i] = points[order[i]]; new_index[order[i]] = i; }
  for(Triangle& t : triangles) {
    for(std::size_t& v : t) v = new_index[v];
    std::rotate(t.begin(), t.begin() + static_cast<std::ptrdiff_t>(rng() % 3), t.end());
  }
  std::shuffle(triangles.begin(), triangles.end(), rng);
  points.swap(shuffled);
}

Mesh to_mesh(std::vector<Point> points, std::vector<Triangle> triangles)
{
  Mesh mesh;
  std::vector<std::vector<std::size_t>> polygons;
  for(const Triangle& t : triangles) polygons.push_back({t[0], t[1], t[2]});
  PMP::orient_polygon_soup(points, polygons);
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  return mesh;
}

/// points on every face of `mesh`: its corners, the midpoints of its edges and its centroid.
std::vector<Point> samples(const Mesh& mesh)
{
  std::vector<Point> result;
  for(auto f : faces(mesh)) {
    std::vector<Point> c;
    for(auto v : vertices_around_face(halfedge(f, mesh), mesh)) c.push_back(mesh.point(v));
    for(std::size_t k = 0; k < 3; ++k) {
      result.push_back(c[k]);
      result.push_back(CGAL::midpoint(c[k], c[(k + 1) % 3]));
    }
    result.push_back(CGAL::centroid(c[0], c[1], c[2]));
  }
  return result;
}

/// the larger of the two one-sided distances between the surfaces, measured at `samples()`.
double hausdorff(const Mesh& a, const Mesh& b)
{
  return std::max(PMP::max_distance_to_triangle_mesh<CGAL::Sequential_tag>(samples(a), b),
                  PMP::max_distance_to_triangle_mesh<CGAL::Sequential_tag>(samples(b), a));
}

const auto collapse = ST::Small_features::COLLAPSE;
const auto refuse = ST::Small_features::REFUSE;

// ---------------------------------------------------------------------------------------------
// A sliver at a seam: the split point m of one side lies 0.05 from the end point a of the
// shared edge, and the other side's copy of a lies between them; tolerance 0.1.

void sliver_at_a_seam(std::vector<Point>& points, std::vector<Triangle>& triangles)
{
  points = {Point(0, 0, 0), Point(0.05, 0, 0), Point(1, 0, 0), Point(0.5, 1, 0),      // a, m, b, c
            Point(0.01, 0, 0), Point(1, 0, 0.01), Point(0.5, -1, 0)};                // a', b', d
  triangles = {{0, 1, 3}, {1, 2, 3}, {4, 6, 5}};
}

TEST(SmallFeaturesSliver, RefuseKeepsTheSliver)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  sliver_at_a_seam(points, triangles);
  const ST::Reconstruction_report r = ST::reconstruct_topology(
    points, triangles, ST::parameters::small_features(refuse, CGAL::parameters::snapping_tolerance(0.1)));
  EXPECT_EQ(r.small_features, refuse);
  EXPECT_GT(r.refused_same_triangle, 0u);
  EXPECT_EQ(r.small_feature_collapsed_triangles, 0u);
  EXPECT_EQ(r.small_features_resolved, 0u);
  EXPECT_GE(triangles.size(), 3u);
  EXPECT_EQ(count_degenerate(points, triangles), 0u);
}

TEST(SmallFeaturesSliver, CollapseRemovesTheSliverAndClosesTheSeam)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  sliver_at_a_seam(points, triangles);
  const ST::Reconstruction_report r = ST::reconstruct_topology(
    points, triangles, ST::parameters::small_features(collapse, CGAL::parameters::snapping_tolerance(0.1)));
  EXPECT_EQ(r.small_features, collapse);
  EXPECT_EQ(r.small_feature_collapsed_triangles, 1u);
  EXPECT_EQ(r.small_features_resolved, 1u);
  EXPECT_EQ(r.refused_welds(), 0u);
  EXPECT_EQ(r.ambiguous_sites, 0u);
  ASSERT_EQ(triangles.size(), 2u);
  EXPECT_EQ(r.border_edges_after, 4u);
  EXPECT_EQ(r.non_manifold_edges_after, 0u);
  EXPECT_LE(r.max_displacement, 0.1);
  EXPECT_EQ(count_degenerate(points, triangles), 0u);
  // a (the lexicographically smallest) and b are the representatives: the square (a, d, b, c).
  const std::vector<Geometric_triangle> expected =
    geometry({Point(0, 0, 0), Point(1, 0, 0), Point(0.5, 1, 0), Point(0.5, -1, 0)}, {{0, 1, 2}, {0, 3, 1}});
  EXPECT_EQ(geometry(points, triangles), expected);
}

TEST(SmallFeaturesSliver, SnapVerticesAloneCollapsesAndReports)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  sliver_at_a_seam(points, triangles);
  const ST::Snap_report r = ST::snap_vertices(
    points, triangles, ST::parameters::small_features(collapse, CGAL::parameters::snapping_tolerance(0.1)));
  EXPECT_EQ(r.collapsed_triangles, 1u);
  EXPECT_EQ(r.small_features_resolved, 1u);
  EXPECT_EQ(r.refused_same_triangle, 0u);
  EXPECT_EQ(triangles.size(), 2u);
  EXPECT_TRUE(r.ambiguous_sites.empty());
}

TEST(SmallFeaturesSliver, AnEdgeLongerThanTheToleranceIsNotCollapsed)
{
  // u and w, the ends of an edge 0.16 long, are both within the tolerance 0.1 of r: merging
  // both into r would collapse an edge longer than the tolerance. The nearer of the two
  // (ties: the lexicographically smaller, u) joins r, w is refused.
  std::vector<Point> points = {Point(0.01, -0.08, 0), Point(0.01, 0.08, 0), Point(1, 0, 0),  // u, w, c
                               Point(0, 0, 0), Point(-1, 0.5, 0), Point(-1, -0.5, 0)};      // r, d, e
  std::vector<Triangle> triangles = {{0, 2, 1}, {3, 4, 5}};
  const ST::Snap_report r = ST::snap_vertices(
    points, triangles, ST::parameters::small_features(collapse, CGAL::parameters::snapping_tolerance(0.1)));
  EXPECT_EQ(r.collapsed_triangles, 0u);
  EXPECT_EQ(r.small_features_resolved, 0u);
  EXPECT_EQ(r.merged_vertices, 1u);
  EXPECT_EQ(r.refused_same_triangle, 1u);
  EXPECT_EQ(triangles.size(), 2u);
  EXPECT_EQ((triangles[0]), (Triangle{3, 2, 1}));
}

// ---------------------------------------------------------------------------------------------
// Generated soups from real meshes (issue 18).

class SmallFeaturesGenerated : public ::testing::TestWithParam<const char*> {};

TEST_P(SmallFeaturesGenerated, CollapseClosesWithinTheToleranceAndIsOrderIndependent)
{
  const Generated g = generate(GetParam(), 18);
  ASSERT_GT(g.soup.near_end_t_junctions, 20u);
  const auto np = ST::parameters::small_features(collapse, CGAL::parameters::snapping_tolerance(g.tolerance));
  const Outcome o = repair(g.soup.points, g.soup.triangles, np);
  SCOPED_TRACE(describe(o));
  EXPECT_EQ(o.border, 0u);
  EXPECT_EQ(o.non_manifold, 0u);
  EXPECT_EQ(o.degenerate, 0u);
  EXPECT_EQ(o.written_border, 0u);
  EXPECT_EQ(o.written_non_manifold, 0u);
  EXPECT_EQ(o.report.non_manifold_vertices_after, 0u);
  EXPECT_LE(o.report.max_displacement, g.tolerance);
  EXPECT_GT(o.report.small_feature_collapsed_triangles, 0u);
  // Within the tolerance of the unperturbed surface, both ways.
  const Mesh original = to_mesh(g.mesh_points, g.mesh_triangles);
  const Mesh repaired = to_mesh(o.points, o.triangles);
  EXPECT_LE(hausdorff(original, repaired), g.tolerance);
  // The same surface for a shuffled input.
  std::vector<Point> points = g.soup.points;
  std::vector<Triangle> triangles = g.soup.triangles;
  shuffle(points, triangles, 7);
  const Outcome shuffled = repair(points, triangles, np);
  EXPECT_EQ(geometry(shuffled.points, shuffled.triangles), geometry(o.points, o.triangles));
}

INSTANTIATE_TEST_SUITE_P(RealMeshes, SmallFeaturesGenerated,
                         ::testing::Values("clean/elephant.off", "clean/fandisk.off.xz"));

// ---------------------------------------------------------------------------------------------
// Where nothing is below the tolerance the two policies agree, triangle for triangle; on the
// real meshes, collapsing is no worse than refusing.

template <class NamedParameters>
void expect_same_result_under_both_policies(const std::vector<Point>& points, const std::vector<Triangle>& triangles,
                                            const NamedParameters& np, bool closed_today)
{
  const Outcome refused = repair(points, triangles, ST::parameters::small_features(refuse, np));
  const Outcome collapsed = repair(points, triangles, ST::parameters::small_features(collapse, np));
  if(closed_today) {
    EXPECT_EQ(refused.border, 0u);
    EXPECT_EQ(refused.report.short_edges, 0u);
  }
  EXPECT_EQ(collapsed.report.small_feature_collapsed_triangles, 0u);
  EXPECT_EQ(geometry(collapsed.points, collapsed.triangles), geometry(refused.points, refused.triangles));
}

TEST(SmallFeaturesPolicy, TJunctionSoupsClosedTodayKeepTheirTriangles)
{
  for(const char* file : {"clean/elephant.off", "clean/fandisk.off.xz"}) {
    SCOPED_TRACE(file);
    auto [points, triangles] = load<Point>(file);
    const double diag = diagonal(points);
    const auto soup = soup_test::t_junction_soup(points, triangles, 5, 1e-7 * diag / std::sqrt(3.0), 17);
    expect_same_result_under_both_policies(soup.points, soup.triangles, CGAL::parameters::snapping_tolerance(1e-6 * diag),
                                           true);
  }
}

TEST(SmallFeaturesPolicy, RealMeshesNoWorseThanRefusing)
{
  // The tolerance: absolute, or relative to the diagonal.
  struct Case { const char* file; double absolute, relative; };
  for(const Case& c : {Case{"cgal_repair/pig.stl.xz", 0.3, 0}, Case{"cgal_repair/pig.stl.xz", 0.001, 0},
                       Case{"cad/ALSTOM_TEST4.off", 0, 1e-4}, Case{"cad/ALSTOM_TEST4.off", 0, 2e-4}}) {
    const auto [points, triangles] = load<Point>(c.file);
    const double tolerance = c.absolute > 0 ? c.absolute : c.relative * diagonal(points);
    SCOPED_TRACE(std::string(c.file) + " at " + std::to_string(tolerance));
    const auto np = CGAL::parameters::snapping_tolerance(tolerance);
    const Outcome refused = repair(points, triangles, ST::parameters::small_features(refuse, np));
    const Outcome collapsed = repair(points, triangles, ST::parameters::small_features(collapse, np));
    std::cout << c.file << " at " << tolerance << "\n  refuse:   " << describe(refused)
              << "\n  collapse: " << describe(collapsed) << "\n";
    EXPECT_LE(collapsed.border, refused.border);
    EXPECT_LE(collapsed.non_manifold, refused.non_manifold);
    EXPECT_LE(collapsed.written_border, refused.written_border);
    EXPECT_EQ(collapsed.degenerate, 0u);
    EXPECT_LE(collapsed.report.max_displacement, collapsed.report.tolerance);
    if(collapsed.report.small_features_resolved == 0 && collapsed.report.small_feature_collapsed_triangles == 0) {
      EXPECT_EQ(geometry(collapsed.points, collapsed.triangles), geometry(refused.points, refused.triangles));
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Degenerate triangles of the input (zero area) removed by edge flips
// (`internal::flip_degenerate_triangles()`, called by `reconstruct_topology()` under
// `Small_features::COLLAPSE` before the tables are built).

double total_area(const std::vector<Point>& points, const std::vector<Triangle>& triangles)
{
  double area = 0;
  for(const Triangle& t : triangles)
    area += std::sqrt(CGAL::to_double(CGAL::squared_area(points[t[0]], points[t[1]], points[t[2]])));
  return area;
}

TEST(SmallFeaturesDegenerate, FlipsRemoveZeroAreaTrianglesWithoutMovingTheSurface)
{
  // A triangle (0, 1, 2) whose corner 2 lies on its edge [0,1], and the triangle (1, 0, 3)
  // across that edge: the flip gives (1, 2, 3) and (2, 0, 3).
  std::vector<Point> points = {Point(0, 0, 0), Point(2, 0, 0), Point(1, 0, 0), Point(1, -1, 0)};
  std::vector<Triangle> triangles = {{0, 1, 2}, {1, 0, 3}};
  const auto counts = ST::internal::flip_degenerate_triangles(points, triangles, Epick());
  EXPECT_EQ(counts.flipped, 1u);
  EXPECT_EQ(counts.remaining, 0u);
  EXPECT_EQ(triangles, (std::vector<Triangle>{{1, 2, 3}, {2, 0, 3}}));
}

TEST(SmallFeaturesDegenerate, RealDefectFiles)
{
  for(const char* file :
      {"real_defects/admesh/conveyor/nearby-bad.stl.xz", "real_defects/admesh/conveyor/fill-holes-bad.stl.xz",
       "real_defects/openscad/issue945f.stl", "real_defects/openscad/issue1580-zero-area-triangle.stl",
       "real_defects/openscad/issue1580-back-to-back.stl", "real_defects/openscad/issue1580-back-to-back2.stl"}) {
    SCOPED_TRACE(file);
    auto [points, triangles] = load<Point>(file);
    const std::size_t before = count_degenerate(points, triangles);
    const auto [border, non_manifold] = soup_test::count_border_and_non_manifold_edges(triangles);
    const double area = total_area(points, triangles);
    const std::size_t n = triangles.size();
    const auto counts = ST::internal::flip_degenerate_triangles(points, triangles, Epick());
    std::cout << file << ": " << before << " degenerate, " << counts.flipped << " flipped, " << counts.remaining
              << " left\n";
    EXPECT_GT(before, 0u);
    EXPECT_EQ(counts.flipped + counts.remaining, before);
    EXPECT_EQ(count_degenerate(points, triangles), counts.remaining);
    EXPECT_EQ(triangles.size(), n);
    EXPECT_EQ(soup_test::count_border_and_non_manifold_edges(triangles), std::make_pair(border, non_manifold));
    EXPECT_NEAR(total_area(points, triangles), area, 1e-9 * area);
  }
}

// OpenSCAD's back-to-back files: two degenerate triangles glued to each other (the same
// corners in opposite orders, or along their long edge), each beside non-degenerate triangles
// along its two short edges. No flip applies; both are covered and removed.
TEST(SmallFeaturesDegenerate, BackToBackTrianglesAreRemovedWhereTheOthersCoverThem)
{
  for(const char* file :
      {"real_defects/openscad/issue1580-back-to-back.stl", "real_defects/openscad/issue1580-back-to-back2.stl"}) {
    SCOPED_TRACE(file);
    auto [points, triangles] = load<Point>(file);
    ASSERT_EQ(count_degenerate(points, triangles), 2u);
    const double area = total_area(points, triangles);
    const std::size_t n = triangles.size();
    EXPECT_EQ(ST::internal::flip_degenerate_triangles(points, triangles, Epick()).flipped, 0u);
    EXPECT_EQ(ST::internal::remove_covered_degenerate_triangles(points, triangles, Epick()), 2u);
    EXPECT_EQ(triangles.size(), n - 2);
    EXPECT_EQ(count_degenerate(points, triangles), 0u);
    EXPECT_NEAR(total_area(points, triangles), area, 1e-12 * area);
  }
}

TEST(SmallFeaturesDegenerate, AnUncoveredDegenerateTriangleIsKept)
{
  // (0, 1, 2) with 2 on [0,1]; only [0,2] is an edge of another triangle: [2,1] and [0,1]
  // are not covered, so removing it would remove the segment ]2,1].
  std::vector<Point> points = {Point(0, 0, 0), Point(2, 0, 0), Point(1, 0, 0), Point(0.5, 1, 0)};
  std::vector<Triangle> triangles = {{0, 1, 2}, {0, 2, 3}};
  EXPECT_EQ(ST::internal::remove_covered_degenerate_triangles(points, triangles, Epick()), 0u);
  EXPECT_EQ(triangles.size(), 2u);
}

// The pipeline flips them away, or removes them where that is covered, under the default policy,
// and leaves them under REFUSE. No point moves, and no file is left more open than it was.
TEST(SmallFeaturesDegenerate, ReconstructTopologyResolvesThemUnderCollapse)
{
  for(const char* file :
      {"real_defects/admesh/conveyor/nearby-bad.stl.xz", "real_defects/admesh/conveyor/nearby-good.stl.xz",
       "real_defects/admesh/conveyor/fill-holes-bad.stl.xz", "real_defects/admesh/conveyor/fill-holes-good.stl.xz",
       "real_defects/admesh/conveyor/normal-directions-bad.stl.xz",
       "real_defects/admesh/conveyor/normal-directions-good.stl.xz",
       "real_defects/admesh/conveyor/remove-unconnected-bad.stl.xz",
       "real_defects/admesh/conveyor/remove-unconnected-good.stl.xz", "real_defects/openscad/issue945f.stl",
       "real_defects/openscad/issue1580-zero-area-triangle.stl", "real_defects/openscad/issue1580-back-to-back.stl",
       "real_defects/openscad/issue1580-back-to-back2.stl"}) {
    SCOPED_TRACE(file);
    auto [points, triangles] = load<Point>(file);
    const std::size_t before = count_degenerate(points, triangles);
    ASSERT_GT(before, 0u);
    auto refused_points = points;
    auto refused_triangles = triangles;
    const ST::Reconstruction_report collapsed = ST::reconstruct_topology(points, triangles);
    EXPECT_EQ(collapsed.flipped_degenerate_triangles + collapsed.removed_degenerate_triangles, before);
    EXPECT_EQ(collapsed.degenerate_triangles_after, 0u);
    EXPECT_EQ(count_degenerate(points, triangles), 0u);
    EXPECT_EQ(collapsed.max_displacement, 0.0);
    EXPECT_LE(collapsed.border_edges_after, collapsed.border_edges_before);
    EXPECT_LE(collapsed.non_manifold_edges_after, collapsed.non_manifold_edges_before);
    const ST::Reconstruction_report refused = ST::reconstruct_topology(
      refused_points, refused_triangles, ST::parameters::small_features(ST::Small_features::REFUSE));
    EXPECT_EQ(refused.flipped_degenerate_triangles, 0u);
    EXPECT_EQ(refused.removed_degenerate_triangles, 0u);
    EXPECT_EQ(refused.degenerate_triangles_after, before);
  }
}

// The back-to-back files come out closed and manifold: the pyramid the triangles make.
TEST(SmallFeaturesDegenerate, BackToBackFilesComeOutClosed)
{
  for(const char* file :
      {"real_defects/openscad/issue1580-back-to-back.stl", "real_defects/openscad/issue1580-back-to-back2.stl"}) {
    SCOPED_TRACE(file);
    auto [points, triangles] = load<Point>(file);
    const ST::Reconstruction_report r = ST::reconstruct_topology(points, triangles);
    EXPECT_EQ(r.removed_degenerate_triangles, 2u);
    EXPECT_EQ(r.border_edges_after, 0u);
    EXPECT_EQ(r.non_manifold_edges_after, 0u);
    EXPECT_EQ(r.non_manifold_vertices_after, 0u);
    EXPECT_EQ(r.degenerate_triangles_after, 0u);
  }
}

// ---------------------------------------------------------------------------------------------
// Parts smaller than the tolerance: a collapse keeps a triangle's points on the surface (the edge
// or point it collapses onto is on a kept triangle), so such a part is kept, not removed, and
// the output stays within the tolerance of the input both ways.

/// the largest distance from a point of `from` (corners, edge midpoints, centroids) to the
/// surface `to`; infinite when `to` is empty and `from` is not.
double one_sided_distance(const std::vector<Point>& from_points, const std::vector<Triangle>& from_triangles,
                          const std::vector<Point>& to_points, const std::vector<Triangle>& to_triangles)
{
  if(from_triangles.empty()) return 0;
  if(to_triangles.empty()) return std::numeric_limits<double>::infinity();
  std::vector<Epick::Triangle_3> surface;
  for(const Triangle& t : to_triangles) surface.emplace_back(to_points[t[0]], to_points[t[1]], to_points[t[2]]);
  double largest = 0;
  for(const Triangle& t : from_triangles) {
    const Point c[3] = {from_points[t[0]], from_points[t[1]], from_points[t[2]]};
    for(const Point& p : {c[0], c[1], c[2], CGAL::midpoint(c[0], c[1]), CGAL::midpoint(c[1], c[2]),
                          CGAL::midpoint(c[2], c[0]), CGAL::centroid(c[0], c[1], c[2])}) {
      double nearest = std::numeric_limits<double>::infinity();
      for(const Epick::Triangle_3& s : surface)
        nearest = std::min(nearest, std::sqrt(CGAL::to_double(CGAL::squared_distance(p, s))));
      largest = std::max(largest, nearest);
    }
  }
  return largest;
}

/// repairs (`points`, `triangles`) under COLLAPSE at `tolerance` and checks that the result is
/// within the tolerance of the input both ways, has no degenerate triangle, and is the same
/// surface for a shuffled input; returns the report.
ST::Reconstruction_report expect_within_tolerance_both_ways(std::vector<Point>& points, std::vector<Triangle>& triangles,
                                                           double tolerance)
{
  const std::vector<Point> input_points = points;
  const std::vector<Triangle> input_triangles = triangles;
  const auto np = ST::parameters::small_features(collapse, CGAL::parameters::snapping_tolerance(tolerance));
  const ST::Reconstruction_report r = ST::reconstruct_topology(points, triangles, np);
  EXPECT_LE(r.max_displacement, tolerance);
  EXPECT_EQ(count_degenerate(points, triangles), 0u);
  EXPECT_LE(one_sided_distance(input_points, input_triangles, points, triangles), tolerance);
  EXPECT_LE(one_sided_distance(points, triangles, input_points, input_triangles), tolerance);
  for(unsigned seed : {3u, 11u}) {
    std::vector<Point> shuffled_points = input_points;
    std::vector<Triangle> shuffled_triangles = input_triangles;
    shuffle(shuffled_points, shuffled_triangles, seed);
    const ST::Reconstruction_report s = ST::reconstruct_topology(shuffled_points, shuffled_triangles, np);
    EXPECT_EQ(geometry(shuffled_points, shuffled_triangles), geometry(points, triangles));
    EXPECT_EQ(s.refused_uncovered_collapse, r.refused_uncovered_collapse);
    EXPECT_EQ(s.small_feature_collapsed_triangles, r.small_feature_collapsed_triangles);
  }
  return r;
}

TEST(SmallFeaturesSmallParts, TwoUnitSquaresAtToleranceThirtyAreKept)
{
  // Two unit squares side by side with a gap of 0.01: every vertex is within the tolerance of
  // every other, so every triangle would collapse onto one point that no triangle keeps.
  std::vector<Point> points{Point(0, 0, 0), Point(1, 0, 0), Point(1, 1, 0), Point(0, 1, 0),
                            Point(1.01, 0, 0), Point(2, 0, 0), Point(2, 1, 0), Point(1.01, 1, 0)};
  std::vector<Triangle> triangles{{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}};
  const ST::Reconstruction_report r = expect_within_tolerance_both_ways(points, triangles, 30.0);
  EXPECT_EQ(triangles.size(), 4u);
  EXPECT_GT(r.refused_uncovered_collapse, 0u);
  EXPECT_EQ(r.small_feature_collapsed_triangles, 0u);
}

TEST(SmallFeaturesSmallParts, ALoneSliverIsKept)
{
  // A triangle alone, two of whose corners are within the tolerance: collapsing it would remove
  // a triangle 1 long. (The soup of `ReconstructTopology.Issue20AnyGeomTraitsAndChainedParameters`.)
  std::vector<Point> points = {Point(0, 0, 0),      Point(1, 0, 0), Point(0, 1, 0),      Point(1.0001, 0, 0),
                               Point(0, 1.0001, 0), Point(1, 1, 0), Point(5, 5, 0),      Point(5.0001, 5, 0),
                               Point(5, 6, 0)};
  std::vector<Triangle> triangles = {{0, 1, 2}, {4, 3, 5}, {6, 7, 8}};
  const double tolerance = 1e-4 * diagonal(points);
  const ST::Reconstruction_report r = expect_within_tolerance_both_ways(points, triangles, tolerance);
  EXPECT_EQ(r.snapped_vertices, 2u); // 3 into 1, 4 into 2
  EXPECT_EQ(r.small_feature_collapsed_triangles, 0u);
  EXPECT_EQ(r.rounds, 2u);
  EXPECT_EQ(r.refused_uncovered_collapse, 2u); // 7 into 6, refused in each round
  EXPECT_EQ(triangles.size(), 3u);
}

TEST(SmallFeaturesSmallParts, AThinStripIsNotRemoved)
{
  // A strip 10 long and 0.05 wide, open all around, at tolerance 0.1: its two sides are within
  // the tolerance of each other, and collapsing them would leave nothing of the strip.
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  for(int i = 0; i <= 20; ++i) {
    points.emplace_back(0.5 * i, 0, 0);
    points.emplace_back(0.5 * i, 0.05, 0);
  }
  for(std::size_t i = 0; i < 20; ++i)
    triangles.insert(triangles.end(), {Triangle{2 * i, 2 * i + 2, 2 * i + 3}, Triangle{2 * i, 2 * i + 3, 2 * i + 1}});
  const ST::Reconstruction_report r = expect_within_tolerance_both_ways(points, triangles, 0.1);
  EXPECT_FALSE(triangles.empty());
  EXPECT_GT(r.refused_uncovered_collapse, 0u);
}

TEST(SmallFeaturesSmallParts, TinyTetrahedraBesideALargePart)
{
  // A large part with an open seam (two 10 x 10 squares 0.02 apart), a tiny closed tetrahedron
  // beside the middle of the seam and a tiny open one (three faces) farther away, at tolerance 0.1.
  // The seam closes; the closed tetrahedron has no border and is not touched; the open one would
  // collapse onto a point that no triangle keeps, so it is kept.
  std::vector<Point> points{Point(0, 0, 0), Point(10, 0, 0), Point(10, 10, 0), Point(0, 10, 0),
                            Point(10.02, 0, 0), Point(20, 0, 0), Point(20, 10, 0), Point(10.02, 10, 0)};
  std::vector<Triangle> triangles{{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}};
  auto add_tetrahedron = [&](double x, double y, double z, double size, bool closed) {
    const std::size_t first = points.size();
    points.insert(points.end(), {Point(x, y, z), Point(x + size, y, z), Point(x, y + size, z), Point(x, y, z + size)});
    triangles.insert(triangles.end(), {Triangle{first, first + 2, first + 1}, Triangle{first, first + 1, first + 3},
                                       Triangle{first, first + 3, first + 2}});
    if(closed) triangles.push_back({first + 1, first + 2, first + 3});
  };
  add_tetrahedron(10.01, 5, 0.05, 0.03, true);
  add_tetrahedron(5, 20, 0, 0.03, false);
  const ST::Reconstruction_report r = expect_within_tolerance_both_ways(points, triangles, 0.1);
  EXPECT_EQ(triangles.size(), 4u + 4u + 3u);
  EXPECT_EQ(r.components, 3u);
  EXPECT_EQ(r.border_edges_after, 6u + 3u); // the outline of the welded squares, the open tetrahedron's rim
  EXPECT_GT(r.refused_uncovered_collapse, 0u);
}

} // namespace small_features_test
