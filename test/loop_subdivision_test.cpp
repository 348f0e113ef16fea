// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Tests of <Soup_topology/loop_subdivision.h>: Loop's rules against CGAL's Loop_subdivision, the
// boundary and non-manifold rules, the eigen-analysis and the limit points and tangents.

#include <Soup_topology/loop_subdivision.h>
#include <Soup_topology/IO/read_triangle_soup.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Orthogonal_k_neighbor_search.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/Subdivision_method_3/subdivision_methods_3.h>
#include <CGAL/Surface_mesh.h>

#include <gtest/gtest.h>

#include "test_utilities.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

// The names of this file live in a namespace of its own: test/CMakeLists.txt compiles several
// test files as one translation unit.
namespace loop_subdivision_test {

namespace {

namespace ST = Soup_topology;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Vector = K::Vector_3;
using Triangle = std::array<std::size_t, 3>;
using Mesh = CGAL::Surface_mesh<Point>;

const double pi = 3.14159265358979323846;

// Reads a mesh of the shared data folder, decompressing `.xz` files into a temporary folder.
void read_data(const std::string& name, std::vector<Point>& points, std::vector<Triangle>& triangles)
{
  const std::string path = soup_test::data_file("clean/" + name);
  ST::IO::read_triangle_soup(path, points, triangles);
  ASSERT_FALSE(triangles.empty()) << path;
}

double bbox_diagonal(const std::vector<Point>& points)
{
  const CGAL::Bbox_3 b = CGAL::bbox_3(points.begin(), points.end());
  return std::sqrt(CGAL::square(b.xmax() - b.xmin()) + CGAL::square(b.ymax() - b.ymin()) +
                   CGAL::square(b.zmax() - b.zmin()));
}

// For every point of `ours`, the index of the nearest point of `theirs` (a k-d tree search).
std::vector<std::size_t> nearest_indices(const std::vector<Point>& ours, const std::vector<Point>& theirs,
                                         std::vector<double>& distances)
{
  using Point_map = CGAL::Pointer_property_map<Point>::const_type;
  using Traits = CGAL::Search_traits_adapter<std::size_t, Point_map, CGAL::Search_traits_3<K>>;
  using Search = CGAL::Orthogonal_k_neighbor_search<Traits>;
  using Tree = Search::Tree;
  using Distance = Search::Distance;
  const Point_map pm = CGAL::make_property_map(theirs);
  std::vector<std::size_t> ids(theirs.size());
  for(std::size_t i = 0; i < ids.size(); ++i) ids[i] = i;
  Tree tree(ids.begin(), ids.end(), Tree::Splitter(), Traits(pm));
  std::vector<std::size_t> result(ours.size());
  distances.assign(ours.size(), 0.);
  for(std::size_t i = 0; i < ours.size(); ++i) {
    Search search(tree, ours[i], 1, 0, true, Distance(pm));
    result[i] = search.begin()->first;
    distances[i] = std::sqrt(search.begin()->second);
  }
  return result;
}

// The triangles relabelled by `map`, each rotated to start at its smallest index, sorted.
std::vector<Triangle> canonical(const std::vector<Triangle>& triangles, const std::vector<std::size_t>* map)
{
  std::vector<Triangle> result;
  for(Triangle t : triangles) {
    if(map != nullptr) for(std::size_t& v : t) v = (*map)[v];
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    result.push_back(t);
  }
  std::sort(result.begin(), result.end());
  return result;
}

// Subdivides the soup with CGAL's Loop_subdivision on a Surface_mesh and returns it as a soup.
void cgal_loop(const std::vector<Point>& points, const std::vector<Triangle>& triangles, unsigned int levels,
               std::vector<Point>& out_points, std::vector<Triangle>& out_triangles)
{
  Mesh mesh;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, triangles, mesh);
  CGAL::Subdivision_method_3::Loop_subdivision(mesh, CGAL::parameters::number_of_iterations(levels));
  out_points.clear();
  out_triangles.clear();
  for(Mesh::Vertex_index v : mesh.vertices()) {
    ASSERT_EQ(std::size_t(v), out_points.size());
    out_points.push_back(mesh.point(v));
  }
  for(Mesh::Face_index f : mesh.faces()) {
    Triangle t;
    std::size_t k = 0;
    for(Mesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) t[k++] = std::size_t(v);
    out_triangles.push_back(t);
  }
}

// Our subdivision and CGAL's give the same points (1e-12 of the bounding box diagonal) and the
// same triangles once our vertices are mapped to CGAL's nearest ones.
void expect_same_as_cgal(const std::string& name, unsigned int levels)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  read_data(name, points, triangles);
  ASSERT_TRUE(CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh(triangles)) << name;
  std::vector<Point> theirs;
  std::vector<Triangle> their_triangles;
  cgal_loop(points, triangles, levels, theirs, their_triangles);
  ST::loop_subdivision(points, triangles, CGAL::parameters::number_of_iterations(levels));
  ASSERT_EQ(points.size(), theirs.size()) << name;
  ASSERT_EQ(triangles.size(), their_triangles.size()) << name;
  const double tolerance = 1e-12 * bbox_diagonal(theirs);
  std::vector<double> distance;
  const std::vector<std::size_t> map = nearest_indices(points, theirs, distance);
  std::vector<bool> used(theirs.size(), false);
  std::size_t far = 0, shared = 0;
  for(std::size_t i = 0; i < points.size(); ++i) {
    if(distance[i] > tolerance) ++far;
    if(used[map[i]]) ++shared;
    used[map[i]] = true;
  }
  EXPECT_EQ(far, 0u) << name << ": points further than " << tolerance << " from CGAL's";
  EXPECT_EQ(shared, 0u) << name << ": the nearest-point map is not a bijection";
  EXPECT_TRUE(canonical(triangles, &map) == canonical(their_triangles, nullptr)) << name << ": connectivity differs";
}

// ---------------------------------------------------------------------------------------------
// Small soups built in code

// A cube, 8 points and 12 triangles oriented outwards; `open` removes the top two triangles.
void cube(std::vector<Point>& points, std::vector<Triangle>& triangles, bool open = false)
{
  points = {Point(0, 0, 0), Point(1, 0, 0), Point(1, 1, 0), Point(0, 1, 0),
            Point(0, 0, 1), Point(1, 0, 1), Point(1, 1, 1), Point(0, 1, 1)};
  triangles = {{0, 2, 1}, {0, 3, 2}, {0, 1, 5}, {0, 5, 4}, {1, 2, 6}, {1, 6, 5},
               {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}};
  if(!open) { triangles.push_back({4, 5, 6}); triangles.push_back({4, 6, 7}); }
}

// A closed fan: apex 0 on top of a regular k-gon 1..k, bottom apex k+1 (a bipyramid);
// the apexes have valence k.
void bipyramid(std::size_t k, std::vector<Point>& points, std::vector<Triangle>& triangles)
{
  points = {Point(0.1, -0.2, 1.3)};
  for(std::size_t i = 0; i < k; ++i) {
    const double a = 2 * pi * double(i) / double(k);
    points.push_back(Point(std::cos(a) + 0.05 * double(i % 3), std::sin(a), 0.1 * double(i % 2)));
  }
  points.push_back(Point(0, 0, -1));
  triangles.clear();
  for(std::size_t i = 0; i < k; ++i) {
    const std::size_t a = 1 + i, b = 1 + (i + 1) % k;
    triangles.push_back({0, a, b});
    triangles.push_back({k + 1, b, a});
  }
}

// The closed-form Loop limit of an interior vertex: (1 - k chi) p + chi sum(q), chi = 1 / (3 / (8 beta) + k).
Point closed_form_limit(const Point& p, const std::vector<Point>& ring, double beta)
{
  const double k = double(ring.size()), chi = 1. / (3. / (8. * beta) + k);
  Vector sum = (1. - k * chi) * (p - CGAL::ORIGIN);
  for(const Point& q : ring) sum = sum + chi * (q - CGAL::ORIGIN);
  return CGAL::ORIGIN + sum;
}

} // namespace

// ---------------------------------------------------------------------------------------------
// Comparison with CGAL on closed meshes

TEST(LoopSubdivision, ElephantMatchesCgalOneAndTwoLevels)
{
  expect_same_as_cgal("elephant.off", 1);
  expect_same_as_cgal("elephant.off", 2);
}

TEST(LoopSubdivision, FandiskMatchesCgalOneAndTwoLevels)
{
  expect_same_as_cgal("fandisk.off.xz", 1);
  expect_same_as_cgal("fandisk.off.xz", 2);
}

// CGAL 5.5.1's Loop_mask_3::border_node uses the midpoint for a border edge and 1/8, 3/4, 1/8
// for a border vertex: the lecture's rules, and ours. So the comparison holds with a hole too.
TEST(LoopSubdivision, DragonWithHoleMatchesCgal)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  read_data("ChineseDragon-10kv.off.xz", points, triangles);
  const ST::Adjacency_tables adj(triangles, points.size());
  ASSERT_GT(adj.number_of_border_edges(), 0u);
  expect_same_as_cgal("ChineseDragon-10kv.off.xz", 1);
  expect_same_as_cgal("ChineseDragon-10kv.off.xz", 2);
}

// Subdivision and limit points are weighted sums of points: on a mesh scaled by a power of two,
// in another unit (2^-900: near 1e-270; 2^1000: near 1e300), they are the points of the mesh at
// its own scale, scaled, to the bit (a product by 2^k commutes with the rounding of + - * / as
// long as no result leaves the normal doubles). The dragon has a border, so the crease rules are
// in it too.
TEST(LoopSubdivision, ResultDoesNotDependOnTheScale)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  read_data("ChineseDragon-10kv.off.xz", points, triangles);
  const auto scaled = [](std::vector<Point> p, int k) {
    for(Point& q : p) q = Point(std::ldexp(q.x(), k), std::ldexp(q.y(), k), std::ldexp(q.z(), k));
    return p;
  };
  std::vector<Point> subdivided = points;
  std::vector<Triangle> subdivided_triangles = triangles;
  ST::loop_subdivision(subdivided, subdivided_triangles, CGAL::parameters::number_of_iterations(2));
  const std::vector<Point> limits = ST::loop_limit_points(points, triangles);
  for(int k : {-900, -140, 140, 1000}) {
    SCOPED_TRACE("2^" + std::to_string(k));
    std::vector<Point> p = scaled(points, k);
    std::vector<Triangle> t = triangles;
    EXPECT_EQ(ST::loop_limit_points(p, t), scaled(limits, k));
    ST::loop_subdivision(p, t, CGAL::parameters::number_of_iterations(2));
    EXPECT_EQ(t, subdivided_triangles);
    EXPECT_EQ(p, scaled(subdivided, k));
  }
}

// The lecture's boundary rules, checked directly on every border edge and vertex of the dragon.
TEST(LoopSubdivision, BoundaryRulesOfTheLecture)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  read_data("ChineseDragon-10kv.off.xz", points, triangles);
  const std::vector<Point> before = points;
  const ST::Adjacency_tables adj(triangles, points.size());
  std::vector<std::vector<std::size_t>> border_ring(points.size());
  for(const ST::Adjacency_tables::Edge& e : adj.border_edges()) {
    const std::size_t a = adj.vertex(e.triangle, e.index), b = adj.vertex(e.triangle, (e.index + 1) % 3);
    border_ring[a].push_back(b);
    border_ring[b].push_back(a);
  }
  const std::vector<Triangle> old_triangles = triangles;
  ST::Adjacency_tables result;
  ST::loop_subdivision(points, triangles, ST::parameters::output_adjacency_tables(&result));
  const double tolerance = 1e-12 * bbox_diagonal(before);
  std::size_t checked = 0;
  for(std::size_t v = 0; v < before.size(); ++v) {
    if(border_ring[v].empty()) continue;
    ASSERT_EQ(border_ring[v].size(), 2u);
    const Point expected = CGAL::ORIGIN + (0.75 * (before[v] - CGAL::ORIGIN) +
                                          0.125 * (before[border_ring[v][0]] - CGAL::ORIGIN) +
                                          0.125 * (before[border_ring[v][1]] - CGAL::ORIGIN));
    EXPECT_LT(std::sqrt(CGAL::squared_distance(points[v], expected)), tolerance) << "vertex " << v;
    ++checked;
  }
  EXPECT_GT(checked, 0u);
  // edge points of border edges are midpoints: the child 4t + i starts with (v_i, e_i)
  for(const ST::Adjacency_tables::Edge& e : adj.border_edges()) {
    const Triangle& child = triangles[4 * e.triangle + std::size_t(e.index)];
    const std::size_t a = old_triangles[e.triangle][std::size_t(e.index)];
    const std::size_t b = old_triangles[e.triangle][(std::size_t(e.index) + 1) % 3];
    EXPECT_EQ(child[0], a);
    EXPECT_LT(std::sqrt(CGAL::squared_distance(points[child[1]], CGAL::midpoint(before[a], before[b]))), tolerance);
  }
  // the output tables describe the result
  EXPECT_EQ(result.number_of_triangles(), triangles.size());
  EXPECT_EQ(result.number_of_vertices(), points.size());
  EXPECT_EQ(result.number_of_border_edges(), 2 * adj.number_of_border_edges());
}

// ---------------------------------------------------------------------------------------------
// Rules on small soups

TEST(LoopSubdivision, RequiredUsageCompiles)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  cube(points, triangles);
  Soup_topology::loop_subdivision(points, triangles, CGAL::parameters::number_of_iterations(2));
  std::vector<K::Point_3> limits = Soup_topology::loop_limit_points(points, triangles);
  EXPECT_EQ(triangles.size(), 12u * 16u);
  EXPECT_EQ(points.size(), 8u + 18u + 72u);   // V + E, then again: 26 + 72 edges
  EXPECT_EQ(limits.size(), points.size());
  const ST::Adjacency_tables adj(triangles, points.size());
  EXPECT_TRUE(adj.is_closed());
  EXPECT_TRUE(adj.non_manifold_vertices().empty());
  EXPECT_TRUE(adj.inconsistently_oriented_edges().empty());
}

TEST(LoopSubdivision, WarrenBeta)
{
  for(std::size_t k : {3u, 4u, 5u, 7u}) {
    std::vector<Point> points;
    std::vector<Triangle> triangles;
    bipyramid(k, points, triangles);
    const std::vector<Point> before = points;
    ST::loop_subdivision(points, triangles, ST::parameters::loop_beta(ST::Loop_beta::WARREN));
    const double beta = k == 3 ? 3. / 16. : 3. / (8. * double(k));
    Vector expected = (1. - double(k) * beta) * (before[0] - CGAL::ORIGIN);
    for(std::size_t i = 1; i <= k; ++i) expected = expected + beta * (before[i] - CGAL::ORIGIN);
    EXPECT_LT(std::sqrt(CGAL::squared_distance(points[0], CGAL::ORIGIN + expected)), 1e-14) << k;
  }
}

TEST(LoopSubdivision, ChainsWithCgalParameters)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  cube(points, triangles);
  ST::Adjacency_tables tables;
  ST::loop_subdivision(points, triangles,
                       ST::parameters::output_adjacency_tables(
                         &tables, ST::parameters::loop_beta(ST::Loop_beta::LOOP,
                                                            CGAL::parameters::number_of_iterations(3).geom_traits(K()))));
  EXPECT_EQ(triangles.size(), 12u * 64u);
  EXPECT_EQ(tables.number_of_triangles(), triangles.size());
  EXPECT_TRUE(tables.is_closed());
}

// Three triangles on one edge: the edge gets the midpoint, its end points (one non-manifold edge
// and three border edges each: corners) stay fixed, the other vertices are border crease vertices.
TEST(LoopSubdivision, NonManifoldEdgeIsACrease)
{
  std::vector<Point> points = {Point(0, 0, 0), Point(1, 0, 0), Point(0.5, 1, 0), Point(0.5, -1, 0), Point(0.5, 0, 1)};
  std::vector<Triangle> triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  const std::vector<Point> before = points;
  ST::loop_subdivision(points, triangles);
  ASSERT_EQ(points.size(), 5u + 7u);
  EXPECT_EQ(points[0], before[0]);
  EXPECT_EQ(points[1], before[1]);
  EXPECT_EQ(points[triangles[0][1]], CGAL::midpoint(before[0], before[1]));
  EXPECT_EQ(triangles[0][1], triangles[4][1]);   // one point for the shared edge
  EXPECT_EQ(triangles[0][1], triangles[8][1]);
  // vertex 2: border neighbours 0 and 1
  const Point p2 = CGAL::ORIGIN + (0.75 * (before[2] - CGAL::ORIGIN) + 0.125 * (before[0] - CGAL::ORIGIN) +
                                   0.125 * (before[1] - CGAL::ORIGIN));
  EXPECT_LT(CGAL::squared_distance(points[2], p2), 1e-30);
}

// Two cubes sharing one vertex (a pinch with no crease edge): that vertex is a corner and stays.
TEST(LoopSubdivision, PinchedVertexIsFixed)
{
  std::vector<Point> points, p2;
  std::vector<Triangle> triangles, t2;
  cube(points, triangles);
  cube(p2, t2);
  // vertex 0 of the second cube, moved by (1, 1, 1), is vertex 6 of the first
  for(std::size_t i = 1; i < p2.size(); ++i) points.push_back(p2[i] + Vector(1, 1, 1));
  for(Triangle t : t2) {
    for(std::size_t& v : t) v = (v == 0) ? 6 : v + 7;
    triangles.push_back(t);
  }
  ASSERT_EQ(points.size(), 15u);
  {
    const ST::Adjacency_tables adj(triangles, points.size());
    ASSERT_EQ(adj.non_manifold_vertices(), std::vector<ST::Adjacency_tables::size_type>{6});
  }
  const Point pinch = points[6];
  ST::loop_subdivision(points, triangles, CGAL::parameters::number_of_iterations(2));
  EXPECT_EQ(points[6], pinch);
}

TEST(LoopSubdivision, BadInputThrowsAndLeavesDataUnchanged)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  cube(points, triangles);
  const std::vector<Point> p0 = points;
  std::vector<Triangle> bad = triangles;
  bad.push_back({0, 1, 8});
  const std::vector<Triangle> bad0 = bad;
  EXPECT_THROW(ST::loop_subdivision(points, bad), ST::Invalid_input);
  EXPECT_EQ(points, p0);
  EXPECT_EQ(bad, bad0);
  EXPECT_THROW(ST::loop_limit_points(points, bad), ST::Invalid_input);

  std::vector<std::vector<int>> polygons = {{0, 1, 2, 3}, {0, 4, 5}};
  const auto polygons0 = polygons;
  EXPECT_THROW(ST::loop_subdivision(points, polygons), ST::Invalid_input);
  EXPECT_EQ(polygons, polygons0);
  EXPECT_EQ(points, p0);

  std::vector<std::vector<int>> negative = {{0, -1, 2}};
  EXPECT_THROW(ST::loop_subdivision(points, negative), ST::Invalid_input);
  std::vector<Triangle> repeated = {{0, 0, 2}};
  EXPECT_THROW(ST::loop_subdivision(points, repeated), ST::Invalid_input);
  std::vector<Point> nan_points = p0;
  nan_points[3] = Point(std::nan(""), 0, 0);
  EXPECT_THROW(ST::loop_subdivision(nan_points, triangles), ST::Invalid_input);
  EXPECT_EQ(triangles.size(), 12u);
}

TEST(LoopSubdivision, VectorFacesAndEmptyInput)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  cube(points, triangles);
  std::vector<std::vector<int>> faces;
  for(const Triangle& t : triangles) faces.push_back({int(t[0]), int(t[1]), int(t[2])});
  std::vector<Point> points2 = points;
  ST::loop_subdivision(points, triangles);
  ST::loop_subdivision(points2, faces);
  EXPECT_EQ(points, points2);
  ASSERT_EQ(faces.size(), triangles.size());
  for(std::size_t t = 0; t < faces.size(); ++t)
    for(std::size_t k = 0; k < 3; ++k) EXPECT_EQ(std::size_t(faces[t][k]), triangles[t][k]);

  std::vector<Point> none;
  std::vector<Triangle> no_triangles;
  EXPECT_NO_THROW(ST::loop_subdivision(none, no_triangles));
  EXPECT_TRUE(none.empty());
  EXPECT_TRUE(ST::loop_limit_points(none, no_triangles).empty());
}

// ---------------------------------------------------------------------------------------------
// The eigen-analysis

// The lecture's regular-vertex matrix, derived from the masks: row 0 is (10, 1, ..., 1) / 16,
// row i is 6/16 for the centre and q_i and 2/16 for q_{i-1} and q_{i+1}.
TEST(LoopEigenAnalysis, RegularMatrixOfTheLecture)
{
  const Eigen::MatrixXd M = 16. * ST::internal::loop_subdivision_matrix(6, ST::internal::loop_beta_value(ST::Loop_beta::LOOP, 6));
  Eigen::MatrixXd expected(7, 7);
  expected << 10, 1, 1, 1, 1, 1, 1,
               6, 6, 2, 0, 0, 0, 2,
               6, 2, 6, 2, 0, 0, 0,
               6, 0, 2, 6, 2, 0, 0,
               6, 0, 0, 2, 6, 2, 0,
               6, 0, 0, 0, 2, 6, 2,
               6, 2, 0, 0, 0, 2, 6;
  EXPECT_EQ(M, expected);
  const ST::internal::Loop_eigen_analysis a = ST::internal::analyze_subdivision_matrix(M / 16., true, "regular");
  const double lambda[7] = {1, 0.5, 0.5, 0.25, 0.25, 0.25, 0.125};
  for(int i = 0; i < 7; ++i) EXPECT_NEAR(a.eigenvalues(i), lambda[i], 1e-13) << i;
  EXPECT_NEAR(a.limit(0), 0.5, 1e-13);
  for(int i = 1; i < 7; ++i) EXPECT_NEAR(a.limit(i), 1. / 12., 1e-13);
}

// 1, 5/8 - k beta and 3/8 + 1/4 cos(2 pi j / k), j = 1..k-1, for both betas and k = 3..12; the
// limit mask equals the closed form and the tangent masks are cos and sin.
TEST(LoopEigenAnalysis, SpectrumLimitAndTangentMasksForValences3To12)
{
  for(ST::Loop_beta choice : {ST::Loop_beta::LOOP, ST::Loop_beta::WARREN})
    for(std::size_t k = 3; k <= 12; ++k) {
      const double beta = ST::internal::loop_beta_value(choice, k);
      const ST::internal::Loop_eigen_analysis a =
        ST::internal::analyze_subdivision_matrix(ST::internal::loop_subdivision_matrix(k, beta), true, "test");
      std::vector<double> expected = {1., 5. / 8. - double(k) * beta};
      for(std::size_t j = 1; j < k; ++j) expected.push_back(3. / 8. + 0.25 * std::cos(2 * pi * double(j) / double(k)));
      std::sort(expected.begin(), expected.end(), [](double x, double y) { return std::abs(x) > std::abs(y); });
      ASSERT_EQ(std::size_t(a.eigenvalues.size()), k + 1);
      std::vector<double> got(a.eigenvalues.data(), a.eigenvalues.data() + k + 1);
      std::sort(got.begin(), got.end());
      std::sort(expected.begin(), expected.end());
      for(std::size_t i = 0; i <= k; ++i) EXPECT_NEAR(got[i], expected[i], 1e-12) << "k=" << k << " i=" << i;
      const double chi = 1. / (3. / (8. * beta) + double(k));
      EXPECT_NEAR(a.limit(0), 1. - double(k) * chi, 1e-12) << k;
      for(std::size_t i = 1; i <= k; ++i) EXPECT_NEAR(a.limit(Eigen::Index(i)), chi, 1e-12) << k;
      EXPECT_NEAR(a.tangent1(0), 0., 1e-12);
      EXPECT_NEAR(a.tangent2(0), 0., 1e-12);
      for(std::size_t i = 0; i < k; ++i) {
        EXPECT_NEAR(a.tangent1(Eigen::Index(i + 1)), std::cos(2 * pi * double(i) / double(k)), 1e-12) << k;
        EXPECT_NEAR(a.tangent2(Eigen::Index(i + 1)), std::sin(2 * pi * double(i) / double(k)), 1e-12) << k;
      }
    }
}

TEST(LoopEigenAnalysis, BoundaryMask)
{
  const ST::internal::Loop_eigen_analysis a =
    ST::internal::analyze_subdivision_matrix(ST::internal::crease_subdivision_matrix(), false, "crease");
  EXPECT_NEAR(a.eigenvalues(0), 1., 1e-14);
  EXPECT_NEAR(a.eigenvalues(1), 0.5, 1e-14);
  EXPECT_NEAR(a.eigenvalues(2), 0.25, 1e-14);
  EXPECT_NEAR(a.limit(0), 2. / 3., 1e-12);
  EXPECT_NEAR(a.limit(1), 1. / 6., 1e-12);
  EXPECT_NEAR(a.limit(2), 1. / 6., 1e-12);
  EXPECT_NEAR(a.tangent1(0), 0., 1e-12);
  EXPECT_NEAR(a.tangent1(1), 1., 1e-12);
  EXPECT_NEAR(a.tangent1(2), -1., 1e-12);
}

// Where the structure the limit relies on does not hold, the analysis says so.
TEST(LoopEigenAnalysis, FailsClearlyWithoutTheEigenStructure)
{
  // beta = 0: 5/8 is above the pair 1/2 (no subdominant pair)
  EXPECT_THROW(ST::internal::analyze_subdivision_matrix(ST::internal::loop_subdivision_matrix(6, 0.), true, "beta 0"),
               ST::Invalid_input);
  // beta = 0.3 at valence 6: 5/8 - 1.8 = -1.175, outside the unit circle
  EXPECT_THROW(ST::internal::analyze_subdivision_matrix(ST::internal::loop_subdivision_matrix(6, 0.3), true, "beta 0.3"),
               ST::Invalid_input);
  // the identity: 1 is not simple
  EXPECT_THROW(ST::internal::analyze_subdivision_matrix(Eigen::MatrixXd::Identity(4, 4), true, "identity"),
               ST::Invalid_input);
}

// ---------------------------------------------------------------------------------------------
// Limit points and tangents on meshes

TEST(LoopLimit, LimitPointsEqualTheClosedFormMasks)
{
  for(std::size_t k = 3; k <= 12; ++k) {
    std::vector<Point> points;
    std::vector<Triangle> triangles;
    bipyramid(k, points, triangles);
    for(ST::Loop_beta choice : {ST::Loop_beta::LOOP, ST::Loop_beta::WARREN}) {
      const std::vector<Point> limits = ST::loop_limit_points(points, triangles, ST::parameters::loop_beta(choice));
      const double beta = ST::internal::loop_beta_value(choice, k);
      std::vector<Point> ring(points.begin() + 1, points.begin() + 1 + std::ptrdiff_t(k));
      EXPECT_LT(std::sqrt(CGAL::squared_distance(limits[0], closed_form_limit(points[0], ring, beta))), 1e-12) << k;
      EXPECT_LT(std::sqrt(CGAL::squared_distance(limits[k + 1], closed_form_limit(points[k + 1], ring, beta))), 1e-12) << k;
    }
  }
  // boundary: the open cube's top vertices have the mask (1/6, 2/3, 1/6) along the border
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  cube(points, triangles, true);
  const std::vector<Point> limits = ST::loop_limit_points(points, triangles);
  const std::size_t border[4] = {4, 5, 6, 7};
  for(std::size_t i = 0; i < 4; ++i) {
    const Point& p = points[border[i]];
    const Point& a = points[border[(i + 1) % 4]];
    const Point& b = points[border[(i + 3) % 4]];
    const Point expected = CGAL::ORIGIN + ((2. / 3.) * (p - CGAL::ORIGIN) + (1. / 6.) * (a - CGAL::ORIGIN) +
                                           (1. / 6.) * (b - CGAL::ORIGIN));
    EXPECT_LT(std::sqrt(CGAL::squared_distance(limits[border[i]], expected)), 1e-12) << border[i];
  }
}

TEST(LoopLimit, TangentsAreTheCosineAndSineMasks)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  bipyramid(7, points, triangles);
  const auto tangents = ST::loop_limit_tangents(points, triangles);
  Vector c = CGAL::NULL_VECTOR, s = CGAL::NULL_VECTOR;
  for(std::size_t i = 0; i < 7; ++i) {   // ring of the apex in the fan order of triangle (0, 1, 2)
    c = c + std::cos(2 * pi * double(i) / 7.) * (points[1 + i] - CGAL::ORIGIN);
    s = s + std::sin(2 * pi * double(i) / 7.) * (points[1 + i] - CGAL::ORIGIN);
  }
  EXPECT_LT(std::sqrt((tangents[0][0] - c).squared_length()), 1e-12);
  EXPECT_LT(std::sqrt((tangents[0][1] - s).squared_length()), 1e-12);
  EXPECT_GT(CGAL::cross_product(tangents[0][0], tangents[0][1]).z(), 0.);   // outward at the top apex
  // border vertices: the crease tangent and a null vector
  cube(points, triangles, true);
  const auto open = ST::loop_limit_tangents(points, triangles);
  EXPECT_NEAR(std::abs(open[4][0].x()) + std::abs(open[4][0].y()), 2., 1e-12);   // c_0 - c_1 = +-(1,-1,0)
  EXPECT_EQ(open[4][1], CGAL::NULL_VECTOR);
}

// Repeated subdivision converges to the limit points: closer after 6 levels than after 3, and
// within 1e-3 of the edge length after 6 (smooth vertices of valences 4 and 5, border vertices).
TEST(LoopLimit, SubdivisionConvergesToTheLimitPoints)
{
  for(bool open : {false, true}) {
    std::vector<Point> points;
    std::vector<Triangle> triangles;
    cube(points, triangles, open);
    const std::vector<Point> limits = ST::loop_limit_points(points, triangles);
    std::vector<Point> p3 = points, p6 = points;
    std::vector<Triangle> t3 = triangles, t6 = triangles;
    ST::loop_subdivision(p3, t3, CGAL::parameters::number_of_iterations(3));
    ST::loop_subdivision(p6, t6, CGAL::parameters::number_of_iterations(6));
    EXPECT_EQ(t6.size(), triangles.size() * 4096);
    const double edge = 1.;
    for(std::size_t v = 0; v < points.size(); ++v) {
      const double d3 = std::sqrt(CGAL::squared_distance(p3[v], limits[v]));
      const double d6 = std::sqrt(CGAL::squared_distance(p6[v], limits[v]));
      EXPECT_LT(d6, d3) << "vertex " << v << (open ? " (open)" : "");
      EXPECT_LT(d6, 1e-3 * edge) << "vertex " << v << (open ? " (open)" : "");
    }
    // The limit of the subdivided mesh is the same surface: the limit points of the level-3
    // mesh at the original vertices are the original limit points.
    const std::vector<Point> limits3 = ST::loop_limit_points(p3, t3);
    for(std::size_t v = 0; v < points.size(); ++v)
      EXPECT_LT(std::sqrt(CGAL::squared_distance(limits3[v], limits[v])), 1e-12) << v;
  }
}

// The edges of a refined level, derived without a search, are those a search finds.
TEST(LoopLevel, RefinedEdgesAreConsistent)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  cube(points, triangles, true);
  triangles.push_back({0, 1, 6});   // a fin: non-manifold edges (0, 1) and (1, 6)
  const ST::Adjacency_tables adj(triangles, points.size());
  ST::internal::Loop_level level;
  level.initialize(adj);
  std::size_t n = points.size();
  for(int it = 0; it < 3; ++it) {
    const std::size_t E = level.number_of_edges;
    level.refine(n);
    n += E;
    ST::internal::Loop_level copy = level;
    copy.compute_halves();
    EXPECT_EQ(copy.half1, level.half1) << it;
    EXPECT_EQ(copy.half2, level.half2) << it;
    EXPECT_EQ(copy.count, level.count) << it;
    // every triangle edge carries the two end vertices of its edge
    for(std::size_t h = 0; h < level.edge_of.size(); ++h) {
      const auto e = level.edge_of[h];
      const auto& tr = level.triangles[h / 3];
      std::array<std::uint32_t, 2> mine = {tr[h % 3], tr[(h + 1) % 3]};
      std::array<std::uint32_t, 2> first = {level.first_vertex(e), level.second_vertex(e)};
      std::sort(mine.begin(), mine.end());
      std::sort(first.begin(), first.end());
      EXPECT_EQ(mine, first);
    }
    // and the same edges as the adjacency tables of the refined triangles
    const ST::Adjacency_tables refined(level.triangles, n);
    for(std::size_t h = 0; h < level.edge_of.size(); ++h) {
      const auto t = static_cast<std::uint32_t>(h / 3);
      const auto u = refined.neighbor(t, int(h % 3));
      const auto e = level.edge_of[h];
      if(u == ST::Adjacency_tables::border_edge) EXPECT_EQ(level.count[e], 1);
      else if(u == ST::Adjacency_tables::non_manifold_edge) EXPECT_EQ(level.count[e], 3);
      else {
        EXPECT_EQ(level.count[e], 2);
        const auto other = level.half1[e] / 3 == t ? level.half2[e] : level.half1[e];
        EXPECT_EQ(other / 3, u);
      }
    }
  }
}

} // namespace loop_subdivision_test
