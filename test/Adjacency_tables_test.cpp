// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The index representation and the adjacency tables: the patent's cube (Figures 1-5, 7-9, tables
// (1)-(18)), the CGAL non-manifold inputs, property tests on real meshes, bad input, the `stats`
// command, hostile inputs (issue 21) checked against a brute-force computation and within time
// bounds.

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/index_triangles.h>
#include <Soup_topology/reconstruct_topology.h>
#include <Soup_topology/soup_statistics.h>
#include <Soup_topology/internal/separate_non_manifold.h>

#include "bounded_run.h"
#include "test_utilities.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Simple_cartesian.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <vector>

// The names of this file live in a namespace of its own: test/CMakeLists.txt compiles several
// test files as one translation unit.
namespace Adjacency_tables_test {

namespace {

namespace ST = Soup_topology;
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Epick::Point_3;
using Triangle = std::array<std::size_t, 3>;
using Tables = ST::Adjacency_tables;
constexpr Tables::size_type B = Tables::border_edge;

// The cube of Figures 1 and 2: vertices V0..V7 and triangles T0..T11 (edge i = (v_i, v_{i+1})).
const std::array<std::array<double, 3>, 8> cube_vertices = {{
  {-1, -1, +1}, {+1, -1, +1}, {+1, +1, +1}, {-1, +1, +1},
  {-1, -1, -1}, {+1, -1, -1}, {+1, +1, -1}, {-1, +1, -1}}};
const std::vector<Triangle> cube_triangles = {
  {0, 1, 3}, {2, 3, 1}, {2, 6, 3}, {7, 3, 6}, {2, 1, 6}, {5, 6, 1},
  {4, 7, 5}, {6, 5, 7}, {1, 0, 5}, {4, 5, 0}, {3, 7, 0}, {4, 0, 7}};

// Table (5): the edge neighbours of T0..T11.
const std::vector<std::array<Tables::size_type, 3>> table_5 = {
  {8, 1, 10}, {2, 0, 4}, {4, 3, 1}, {10, 2, 7}, {1, 5, 2}, {7, 4, 8},
  {11, 7, 9}, {5, 6, 3}, {0, 9, 5}, {6, 8, 11}, {3, 11, 0}, {9, 10, 6}};

// Figure 3 / table C of Figure 4: the triangles around V0..V7.
const std::vector<std::vector<Tables::size_type>> vertex_table = {
  {0, 8, 9, 10, 11}, {0, 1, 4, 5, 8}, {1, 2, 4}, {0, 1, 2, 3, 10},
  {6, 9, 11}, {5, 6, 7, 8, 9}, {2, 3, 4, 5, 7}, {3, 6, 7, 10, 11}};

template <class K>
std::vector<std::array<typename K::Point_3, 3>> cube_stl()
{
  std::vector<std::array<typename K::Point_3, 3>> stl;
  for(const Triangle& t : cube_triangles) {
    std::array<typename K::Point_3, 3> tri;
    for(int k = 0; k < 3; ++k) {
      const auto& c = cube_vertices[t[k]];
      tri[k] = typename K::Point_3(c[0], c[1], c[2]);
    }
    stl.push_back(tri);
  }
  return stl;
}

void expect_edge_table(const Tables& adj, const std::vector<std::array<Tables::size_type, 3>>& expected)
{
  ASSERT_EQ(adj.number_of_triangles(), expected.size());
  for(Tables::size_type t = 0; t < expected.size(); ++t)
    for(int i = 0; i < 3; ++i)
      EXPECT_EQ(adj.neighbor(t, i), expected[t][i]) << "triangle T" << t << ", edge " << i;
}

std::vector<Tables::size_type> around(const Tables& adj, Tables::size_type v)
{
  const auto r = adj.triangles_around_vertex(v);
  return std::vector<Tables::size_type>(r.begin(), r.end());
}

// Every triangle's neighbour has it as a neighbour across the same two vertices.
void expect_symmetric(const Tables& adj)
{
  for(Tables::size_type t = 0; t < adj.number_of_triangles(); ++t)
    for(int i = 0; i < 3; ++i) {
      const Tables::size_type u = adj.neighbor(t, i);
      const Tables::size_type a = adj.vertex(t, i), b = adj.vertex(t, (i + 1) % 3);
      std::vector<Tables::size_type> others;
      adj.triangles_around_edge(t, i, std::back_inserter(others));
      if(u == Tables::border_edge) { EXPECT_TRUE(others.empty()); continue; }
      if(u == Tables::non_manifold_edge) {
        EXPECT_GE(others.size(), 2u);
        for(Tables::size_type w : others) EXPECT_EQ(adj.neighbor(w, adj.edge_index(w, a, b)), Tables::non_manifold_edge);
        continue;
      }
      ASSERT_EQ(others.size(), 1u);
      EXPECT_EQ(others[0], u);
      const int j = adj.edge_index(u, a, b);
      ASSERT_GE(j, 0);
      EXPECT_EQ(adj.neighbor(u, j), t);
    }
  // The vertex table lists exactly the triangles containing each vertex.
  std::vector<std::vector<Tables::size_type>> expected(adj.number_of_vertices());
  for(Tables::size_type t = 0; t < adj.number_of_triangles(); ++t)
    for(int i = 0; i < 3; ++i) expected[adj.vertex(t, i)].push_back(t);
  for(Tables::size_type v = 0; v < adj.number_of_vertices(); ++v) EXPECT_EQ(around(adj, v), expected[v]) << "vertex " << v;
}

// ---------------------------------------------------------------------------------------------
// The patent's cube

TEST(PatentCube, IndexRepresentationOfFigure2)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  const ST::Index_report r = ST::index_triangles(cube_stl<Epick>(), points, triangles);
  EXPECT_EQ(r.input_corners, 36u);
  EXPECT_EQ(r.collapsed_triangles, 0u);
  ASSERT_EQ(points.size(), 8u);
  // First appearance numbering: the STL of Figure 2 lists V0 V1 V3 first, then V2, ...
  // so the vertex list is a permutation of V0..V7; map it back and compare the triangle table.
  std::vector<std::size_t> to_patent(points.size());
  for(std::size_t i = 0; i < points.size(); ++i) {
    bool found = false;
    for(std::size_t v = 0; v < 8; ++v)
      if(points[i] == Point(cube_vertices[v][0], cube_vertices[v][1], cube_vertices[v][2])) { to_patent[i] = v; found = true; }
    ASSERT_TRUE(found);
  }
  EXPECT_EQ(to_patent[0], 0u);
  EXPECT_EQ(to_patent[1], 1u);
  EXPECT_EQ(to_patent[2], 3u);
  ASSERT_EQ(triangles.size(), 12u);
  for(std::size_t t = 0; t < 12; ++t)
    for(int k = 0; k < 3; ++k) EXPECT_EQ(to_patent[triangles[t][k]], cube_triangles[t][k]) << "T" << t;
}

TEST(PatentCube, VertexNeighbourTableOfFigure3)
{
  const Tables adj(cube_triangles, 8);
  for(Tables::size_type v = 0; v < 8; ++v) EXPECT_EQ(around(adj, v), vertex_table[v]) << "V" << v;
  // Table (2): the candidates for the first edge of T0 are the other triangles of V0.
  EXPECT_EQ(around(adj, 0), (std::vector<Tables::size_type>{0, 8, 9, 10, 11}));
  // The text: V2 is shared among T1, T2 and T4.
  EXPECT_EQ(around(adj, 2), (std::vector<Tables::size_type>{1, 2, 4}));
}

TEST(PatentCube, EdgeNeighbourTable5)
{
  const Tables adj(cube_triangles, 8);
  expect_edge_table(adj, table_5);
  // The text: T4 is connected to T1, T2 and T5.
  std::set<Tables::size_type> n4 = {adj.neighbor(4, 0), adj.neighbor(4, 1), adj.neighbor(4, 2)};
  EXPECT_EQ(n4, (std::set<Tables::size_type>{1, 2, 5}));
  EXPECT_TRUE(adj.is_closed());
  EXPECT_TRUE(adj.border_edges().empty());
  EXPECT_TRUE(adj.non_manifold_edges().empty());
  EXPECT_TRUE(adj.non_manifold_vertices().empty());
  EXPECT_TRUE(adj.inconsistently_oriented_edges().empty());
  EXPECT_EQ(adj.number_of_connected_components(), 1u);
  expect_symmetric(adj);
}

// Tables (8)-(9): V0 duplicated into V0b (index 8) for T10 and T11.
std::vector<Triangle> cube_with_v0b()
{
  std::vector<Triangle> t = cube_triangles;
  t[10] = {3, 7, 8};
  t[11] = {4, 8, 7};
  return t;
}

TEST(PatentCube, DuplicatedVertexTables8And9)
{
  const Tables adj(cube_with_v0b(), 9);
  EXPECT_EQ(around(adj, 0), (std::vector<Tables::size_type>{0, 8, 9}));
  EXPECT_EQ(around(adj, 8), (std::vector<Tables::size_type>{10, 11}));
  std::vector<std::array<Tables::size_type, 3>> table_9 = table_5;
  table_9[0] = {8, 1, B};
  table_9[9] = {6, 8, B};
  table_9[10] = {3, 11, B};
  table_9[11] = {B, 10, 6};
  expect_edge_table(adj, table_9);
  // Exactly four unconnected edges, one in each of T0, T9, T10, T11.
  const std::vector<Tables::Edge> border = adj.border_edges();
  ASSERT_EQ(border.size(), 4u);
  EXPECT_EQ(border[0], (Tables::Edge{0, 2}));
  EXPECT_EQ(border[1], (Tables::Edge{9, 2}));
  EXPECT_EQ(border[2], (Tables::Edge{10, 2}));
  EXPECT_EQ(border[3], (Tables::Edge{11, 0}));
  expect_symmetric(adj);
}

TEST(PatentCube, ReplacingV0bRestoresTable5)
{
  Tables adj(cube_with_v0b(), 9);
  adj.replace_vertex(8, 0);               // rules (a)-(c)
  expect_edge_table(adj, table_5);
  for(Tables::size_type v = 0; v < 8; ++v) EXPECT_EQ(around(adj, v), vertex_table[v]) << "V" << v;
  EXPECT_TRUE(around(adj, 8).empty());
  EXPECT_EQ(adj.triangle(10), (Tables::Triangle{3, 7, 0}));
  EXPECT_EQ(adj.triangle(11), (Tables::Triangle{4, 0, 7}));
  EXPECT_TRUE(adj.is_closed());
  expect_symmetric(adj);
}

// Figure 7: T1 is replaced by T1a = (V2, V8, V1) and T1b = (V2, V3, V8), V8 = (0, 0, 1) lies on
// the edge V1-V3 of T0. Triangle indices: T0 = 0, T1a = 1, T1b = 2, T2..T11 = 3..12; the split
// appends T12 as index 13.
struct Figure7
{
  std::map<std::string, Tables::size_type> id;
  std::vector<Triangle> triangles;
  Figure7()
  {
    triangles.push_back(cube_triangles[0]);
    triangles.push_back({2, 8, 1});
    triangles.push_back({2, 3, 8});
    for(std::size_t t = 2; t < 12; ++t) triangles.push_back(cube_triangles[t]);
    id["T0"] = 0; id["T1a"] = 1; id["T1b"] = 2;
    for(int t = 2; t < 12; ++t) id["T" + std::to_string(t)] = static_cast<Tables::size_type>(t + 1);
    id["T12"] = 13;
  }
};

TEST(PatentCube, TJunctionTables11And13)
{
  const Figure7 f;
  const Tables adj(f.triangles, 9);
  auto& id = f.id;
  // Table (11): three unconnected edges.
  EXPECT_EQ(adj.neighbor(id.at("T0"), 0), id.at("T8"));
  EXPECT_EQ(adj.neighbor(id.at("T0"), 1), B);
  EXPECT_EQ(adj.neighbor(id.at("T0"), 2), id.at("T10"));
  EXPECT_EQ(adj.neighbor(id.at("T1a"), 0), id.at("T1b"));
  EXPECT_EQ(adj.neighbor(id.at("T1a"), 1), B);
  EXPECT_EQ(adj.neighbor(id.at("T1a"), 2), id.at("T4"));
  EXPECT_EQ(adj.neighbor(id.at("T1b"), 0), id.at("T2"));
  EXPECT_EQ(adj.neighbor(id.at("T1b"), 1), B);
  EXPECT_EQ(adj.neighbor(id.at("T1b"), 2), id.at("T1a"));
  EXPECT_EQ(adj.number_of_border_edges(), 3u);
  // Table (13): the triangles of V8.
  EXPECT_EQ(around(adj, 8), (std::vector<Tables::size_type>{id.at("T1a"), id.at("T1b")}));
}

TEST(PatentCube, TJunctionSplitTables14To18)
{
  const Figure7 f;
  Tables adj(f.triangles, 9);
  auto& id = f.id;
  // The unconnected edge V1-V3 is edge 1 of T0: split it at V8 (rule table (15)).
  const Tables::size_type t12 = adj.split_triangle(id.at("T0"), 1, 8);
  EXPECT_EQ(t12, id.at("T12"));
  // Table (14).
  EXPECT_EQ(adj.triangle(id.at("T0")), (Tables::Triangle{0, 1, 8}));
  EXPECT_EQ(adj.triangle(t12), (Tables::Triangle{0, 8, 3}));
  // Table (16) (lists in increasing triangle order).
  auto sorted = [](std::vector<Tables::size_type> v) { std::sort(v.begin(), v.end()); return v; };
  EXPECT_EQ(around(adj, 0), sorted({id.at("T0"), id.at("T8"), id.at("T9"), id.at("T10"), id.at("T11"), id.at("T12")}));
  EXPECT_EQ(around(adj, 1), sorted({id.at("T0"), id.at("T1a"), id.at("T4"), id.at("T5"), id.at("T8")}));
  EXPECT_EQ(around(adj, 3), sorted({id.at("T1b"), id.at("T2"), id.at("T3"), id.at("T10"), id.at("T12")}));
  EXPECT_EQ(around(adj, 8), sorted({id.at("T1a"), id.at("T1b"), id.at("T0"), id.at("T12")}));
  // Table (18).
  EXPECT_EQ(adj.neighbor(id.at("T0"), 0), id.at("T8"));
  EXPECT_EQ(adj.neighbor(id.at("T0"), 1), id.at("T1a"));
  EXPECT_EQ(adj.neighbor(id.at("T0"), 2), id.at("T12"));
  EXPECT_EQ(adj.neighbor(id.at("T1a"), 0), id.at("T1b"));
  EXPECT_EQ(adj.neighbor(id.at("T1a"), 1), id.at("T0"));
  EXPECT_EQ(adj.neighbor(id.at("T1a"), 2), id.at("T4"));
  EXPECT_EQ(adj.neighbor(id.at("T1b"), 0), id.at("T2"));
  EXPECT_EQ(adj.neighbor(id.at("T1b"), 1), id.at("T12"));
  EXPECT_EQ(adj.neighbor(id.at("T1b"), 2), id.at("T1a"));
  EXPECT_EQ(adj.neighbor(t12, 0), id.at("T0"));
  EXPECT_EQ(adj.neighbor(t12, 1), id.at("T1b"));
  EXPECT_EQ(adj.neighbor(t12, 2), id.at("T10"));
  // Figure 9: the cube is closed again, and consistently oriented.
  EXPECT_TRUE(adj.is_closed());
  EXPECT_TRUE(adj.inconsistently_oriented_edges().empty());
  expect_symmetric(adj);
}

TEST(PatentCube, SplitRulesOnEveryEdge)
{
  // Rule table (15) for each of the three edges: the kept triangle replaces v_{i+1}, the new one v_i.
  for(int i = 0; i < 3; ++i) {
    Tables adj(std::vector<Triangle>{{0, 1, 2}}, 4);
    const auto t_new = adj.split_triangle(0, i, 3);
    Tables::Triangle kept = {0, 1, 2}, created = {0, 1, 2};
    kept[(i + 1) % 3] = 3;
    created[i] = 3;
    EXPECT_EQ(adj.triangle(0), kept);
    EXPECT_EQ(adj.triangle(t_new), created);
    EXPECT_EQ(adj.neighbor(0, (i + 1) % 3), t_new);
    expect_symmetric(adj);
  }
}

TEST(PatentCube, SameTablesUnderEveryKernel)
{
  std::vector<Triangle> t1, t2, t3;
  std::vector<CGAL::Simple_cartesian<double>::Point_3> p1;
  std::vector<Epick::Point_3> p2;
  std::vector<CGAL::Exact_predicates_exact_constructions_kernel::Point_3> p3;
  ST::index_triangles(cube_stl<CGAL::Simple_cartesian<double>>(), p1, t1);
  ST::index_triangles(cube_stl<Epick>(), p2, t2);
  ST::index_triangles(cube_stl<CGAL::Exact_predicates_exact_constructions_kernel>(), p3, t3);
  EXPECT_EQ(t1, t2);
  EXPECT_EQ(t1, t3);
  EXPECT_EQ(p3.size(), 8u);
}

// ---------------------------------------------------------------------------------------------
// Bad input

TEST(BadInput, ClearErrorsAndUntouchedData)
{
  std::vector<Triangle> out_of_range = {{0, 1, 2}, {0, 2, 7}};
  try {
    Tables adj(out_of_range, 4);
    FAIL() << "no exception";
  } catch(const ST::Invalid_input& e) {
    EXPECT_NE(std::string(e.what()).find("face 1"), std::string::npos) << e.what();
  }
  std::vector<Triangle> repeated = {{0, 1, 2}, {3, 3, 1}};
  EXPECT_THROW(Tables(repeated, 4), ST::Invalid_input);
  std::vector<std::vector<int>> quad = {{0, 1, 2}, {0, 1, 2, 3}};
  try {
    Tables adj(quad, 4);
    FAIL() << "no exception";
  } catch(const ST::Invalid_input& e) {
    EXPECT_NE(std::string(e.what()).find("face 1 has 4 vertices"), std::string::npos) << e.what();
  }
  std::vector<std::vector<int>> negative = {{0, -1, 2}};
  EXPECT_THROW(Tables(negative, 4), ST::Invalid_input);
  // Empty input is fine: no triangle, nothing to report.
  const Tables empty(std::vector<Triangle>{}, 0);
  EXPECT_EQ(empty.number_of_triangles(), 0u);
  EXPECT_TRUE(empty.is_closed());
  EXPECT_EQ(empty.number_of_connected_components(), 0u);
  // merge_duplicate_points leaves everything as it was when an index is out of range.
  std::vector<Point> points = {Point(0, 0, 0), Point(0, 0, 0), Point(1, 0, 0)};
  std::vector<Triangle> faces = {{0, 1, 2}, {0, 2, 9}};
  const auto points_before = points;
  const auto faces_before = faces;
  EXPECT_THROW(ST::merge_duplicate_points(points, faces), ST::Invalid_input);
  EXPECT_EQ(points, points_before);
  EXPECT_EQ(faces, faces_before);
  // replace_vertex refuses to collapse a triangle, and changes nothing.
  Tables adj(cube_triangles, 8);
  EXPECT_THROW(adj.replace_vertex(1, 0), ST::Invalid_input);
  expect_edge_table(adj, table_5);
  EXPECT_THROW(adj.split_triangle(0, 0, 1), ST::Invalid_input);
  EXPECT_THROW(adj.split_triangle(99, 0, 4), ST::Invalid_input);
}

TEST(IndexTriangles, CollapsedTrianglesAreDroppedAndCounted)
{
  std::vector<std::array<Point, 3>> soup = {
    {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0)},
    {Point(0, 0, 0), Point(0, 0, 0), Point(0, 1, 0)},    // two equal corners
    {Point(1, 0, 0), Point(-0.0, 1, 0), Point(0, 0, 0)}}; // -0.0 equals 0.0
  std::vector<Point> points;
  std::vector<std::vector<int>> faces;
  const ST::Index_report r = ST::index_triangles(soup, points, faces);
  EXPECT_EQ(r.collapsed_triangles, 1u);
  EXPECT_EQ(points.size(), 3u);
  ASSERT_EQ(faces.size(), 2u);
  EXPECT_EQ(faces[1], (std::vector<int>{1, 2, 0}));
}

TEST(MergeDuplicatePoints, PortOfCGALRepairSoupCase)
{
  // 7 points, #3 and #5 equal #2, #6 equals #0 (CGAL's test_repair_polygon_soup case).
  std::vector<Point> points = {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(0, 1, 0),
                               Point(1, 1, 0), Point(0, 1, 0), Point(0, 0, 0)};
  std::vector<std::vector<std::size_t>> polygons = {{0, 1, 2}, {6, 3, 1, 0}, {5}};
  EXPECT_EQ(ST::merge_duplicate_points(points, polygons), 3u);
  EXPECT_EQ(points.size(), 4u);
  EXPECT_EQ(polygons[1], (std::vector<std::size_t>{0, 2, 1, 0}));
  EXPECT_EQ(polygons[2], (std::vector<std::size_t>{2}));
}

// ---------------------------------------------------------------------------------------------
// The CGAL peer inputs, with the counts measured in shared/data/README.md

struct Measured
{
  const char* file;
  std::size_t vertices, triangles, border, non_manifold_edges, components;
};

TEST(PeerData, NonManifoldAndDegenerateCounts)
{
  const Measured cases[] = {
    {"cgal_repair/data_stitching/nm_cubes.off", 15, 28, 0, 2, 1},
    {"cgal_repair/data_stitching/non_manifold.off", 4, 4, 0, 1, 1},
    {"cgal_repair/data_stitching/non_manifold2.off", 4, 4, 0, 1, 1},
    {"cgal_repair/data_repair/nm_edges_triple.off", 12, 10, 15, 1, 1},
    {"cgal_repair/data_repair/three_triangles_sharing_a_vertex.off", 7, 3, 9, 0, 3},
    {"cgal_repair/data_stitching/deg_border.off", 6, 6, 4, 0, 1},
    {"cgal_repair/data_stitching/incidence_3.off", 7, 6, 6, 0, 1},
    {"cgal_repair/data_stitching/pinched.off", 77, 102, 56, 0, 1},
    {"cad/ALSTOM_TEST4.off", 1138, 2033, 231, 0, 6},
    {"cgal_repair/pig.stl.xz", 8642, 16848, 1296, 0, 17},
  };
  for(const Measured& m : cases) {
    SCOPED_TRACE(m.file);
    std::vector<Point> points;
    std::vector<Triangle> triangles;
    soup_test::read_data_mesh(m.file, points, triangles);
    const Tables adj(triangles, points.size());
    EXPECT_EQ(points.size(), m.vertices);
    EXPECT_EQ(adj.number_of_triangles(), m.triangles);
    EXPECT_EQ(adj.number_of_border_edges(), m.border);
    EXPECT_EQ(adj.non_manifold_edges().size(), m.non_manifold_edges);
    EXPECT_EQ(adj.number_of_connected_components(), m.components);
    // Cross-check with the slow independent counts.
    const auto counts = soup_test::count_border_and_non_manifold_edges(triangles);
    EXPECT_EQ(counts.first, m.border);
    EXPECT_EQ(counts.second, m.non_manifold_edges);
    EXPECT_EQ(soup_test::count_components(triangles), m.components);
    expect_symmetric(adj);
  }
  // deg_border.off: one triangle collapses in the exact weld.
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  EXPECT_EQ(soup_test::read_data_mesh("cgal_repair/data_stitching/deg_border.off", points, triangles).collapsed_triangles, 1u);
  // three_triangles_sharing_a_vertex.off: one non-manifold vertex.
  soup_test::read_data_mesh("cgal_repair/data_repair/three_triangles_sharing_a_vertex.off", points, triangles);
  EXPECT_EQ(Tables(triangles, points.size()).non_manifold_vertices().size(), 1u);
  // incoherent_patch_orientation.off: one edge traversed twice in the same direction.
  soup_test::read_data_mesh("cgal_repair/data_stitching/incoherent_patch_orientation.off", points, triangles);
  EXPECT_EQ(Tables(triangles, points.size()).inconsistently_oriented_edges().size(), 1u);
}

// ---------------------------------------------------------------------------------------------
// Property tests on real meshes written as exploded soups

class CleanMesh : public ::testing::TestWithParam<const char*> {};

TEST_P(CleanMesh, ExplodedSoupWeldsBackAndTablesAreSymmetricAndStableUnderShuffling)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  soup_test::read_data_mesh(GetParam(), points, triangles);
  std::vector<bool> used(points.size(), false);
  for(const Triangle& t : triangles) for(std::size_t v : t) used[v] = true;
  const std::size_t referenced = static_cast<std::size_t>(std::count(used.begin(), used.end(), true));

  // Exploded soup -> index: the original number of (referenced) vertices comes back.
  const auto soup = soup_test::explode(points, triangles);
  std::vector<Point> welded_points;
  std::vector<Triangle> welded;
  const ST::Index_report r = ST::index_triangles(soup, welded_points, welded);
  EXPECT_EQ(welded_points.size(), referenced);
  EXPECT_EQ(welded.size(), triangles.size());
  EXPECT_EQ(r.collapsed_triangles, 0u);

  const Tables adj(welded, welded_points.size());
  expect_symmetric(adj);
  const auto counts = soup_test::count_border_and_non_manifold_edges(welded);
  EXPECT_EQ(adj.number_of_border_edges(), counts.first);
  EXPECT_EQ(adj.non_manifold_edges().size(), counts.second);

  // Shuffle the triangles and rotate their corners: the tables are the same up to the permutation.
  std::mt19937 rng(42);
  std::vector<std::size_t> perm(welded.size());
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), rng);
  std::vector<int> rotation(welded.size());
  std::vector<Triangle> shuffled(welded.size());
  for(std::size_t k = 0; k < welded.size(); ++k) {
    const Triangle& t = welded[perm[k]];
    rotation[k] = static_cast<int>(rng() % 3);
    shuffled[k] = {t[rotation[k]], t[(rotation[k] + 1) % 3], t[(rotation[k] + 2) % 3]};
  }
  const Tables adj2(shuffled, welded_points.size());
  std::vector<std::size_t> position(welded.size());
  for(std::size_t k = 0; k < perm.size(); ++k) position[perm[k]] = k;
  for(std::size_t k = 0; k < shuffled.size(); ++k)
    for(int i = 0; i < 3; ++i) {
      const int original_edge = (i + rotation[k]) % 3;
      const auto u2 = adj2.neighbor(static_cast<Tables::size_type>(k), i);
      const auto u1 = adj.neighbor(static_cast<Tables::size_type>(perm[k]), original_edge);
      if(u1 >= Tables::non_manifold_edge) EXPECT_EQ(u2, u1);
      else EXPECT_EQ(u2, position[u1]);
    }
  EXPECT_EQ(adj2.number_of_connected_components(), adj.number_of_connected_components());
  EXPECT_EQ(adj2.non_manifold_vertices().size(), adj.non_manifold_vertices().size());
}

INSTANTIATE_TEST_SUITE_P(RealMeshes, CleanMesh,
                         ::testing::Values("clean/elephant.off", "clean/fandisk.off.xz",
                                           "clean/ChineseDragon-10kv.off.xz", "clean/armadillo.off.xz",
                                           "clean/bunny00.off.xz", "clean/refined_elephant.off.xz"));

TEST(CleanMeshFacts, ClosedAndManifoldAsMeasured)
{
  for(const char* f : {"clean/elephant.off", "clean/fandisk.off.xz", "clean/bunny00.off.xz"}) {
    SCOPED_TRACE(f);
    std::vector<Point> points;
    std::vector<Triangle> triangles;
    soup_test::read_data_mesh(f, points, triangles);
    const Tables adj(triangles, points.size());
    EXPECT_TRUE(adj.is_closed());
    EXPECT_TRUE(adj.non_manifold_edges().empty());
    EXPECT_TRUE(adj.non_manifold_vertices().empty());
    EXPECT_TRUE(adj.inconsistently_oriented_edges().empty());
  }
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  soup_test::read_data_mesh("clean/ChineseDragon-10kv.off.xz", points, triangles);
  EXPECT_EQ(Tables(triangles, points.size()).number_of_border_edges(), 6u);
}

// ---------------------------------------------------------------------------------------------
// The command-line tool

std::string cli() { return SOUP_TOPOLOGY_CLI; }

TEST(CommandLine, StatsJsonMatchesIndependentCounts)
{
  for(const char* f : {"cgal_repair/pig.stl.xz", "cad/ALSTOM_TEST4.off", "real_defects/openscad/bad-stl-tardis.stl",
                       "real_defects/admesh/block/remove-unconnected-bad.stl", "cgal_repair/data_stitching/nm_cubes.off",
                       "cgal_repair/quads_to_stitch.off"}) {
    SCOPED_TRACE(f);
    const std::string path = soup_test::data_file(f);
    const auto [out, code] = soup_test::run_command(cli() + " stats '" + path + "' --json");
    ASSERT_EQ(code, 0) << out;
    std::vector<Point> points;
    std::vector<Triangle> triangles;
    ST::IO::read_triangle_soup(path, points, triangles);
    const auto counts = soup_test::count_border_and_non_manifold_edges(triangles);
    EXPECT_EQ(soup_test::json_integer(out, "vertices"), static_cast<long long>(points.size()));
    EXPECT_EQ(soup_test::json_integer(out, "triangles"), static_cast<long long>(triangles.size()));
    EXPECT_EQ(soup_test::json_integer(out, "border_edges"), static_cast<long long>(counts.first));
    EXPECT_EQ(soup_test::json_integer(out, "non_manifold_edges"), static_cast<long long>(counts.second));
    EXPECT_EQ(soup_test::json_integer(out, "components"), static_cast<long long>(soup_test::count_components(triangles)));
    EXPECT_EQ(soup_test::json_bool(out, "closed"), counts.first == 0);
    EXPECT_GE(soup_test::json_integer(out, "non_manifold_vertices"), 0);
    EXPECT_GE(soup_test::json_integer(out, "degenerate_triangles"), 0);
  }
  // Measured facts: pig.stl has 8642 distinct vertices, B = 1296, 17 components.
  const auto [out, code] = soup_test::run_command(cli() + " stats '" + soup_test::data_file("cgal_repair/pig.stl.xz") + "' --json");
  EXPECT_EQ(code, 0);
  EXPECT_EQ(soup_test::json_integer(out, "vertices"), 8642);
  EXPECT_EQ(soup_test::json_integer(out, "border_edges"), 1296);
  EXPECT_EQ(soup_test::json_integer(out, "components"), 17);
  // issue945f.stl: 1 zero-area triangle.
  const auto [out2, code2] = soup_test::run_command(
    cli() + " stats '" + soup_test::data_file("real_defects/openscad/issue945f.stl") + "' --json");
  EXPECT_EQ(code2, 0);
  EXPECT_EQ(soup_test::json_integer(out2, "degenerate_triangles"), 1);
}

TEST(CommandLine, HumanOutputByDefault)
{
  const auto [out, code] = soup_test::run_command(
    cli() + " stats '" + soup_test::data_file("real_defects/admesh/block/exact-bad.stl") + "'");
  EXPECT_EQ(code, 0);
  EXPECT_NE(out.find("border_edges"), std::string::npos);
  EXPECT_EQ(out.find('{'), std::string::npos);
}

TEST(CommandLine, BadFilesExitWithCode2AndAMessage)
{
  const std::string dir = soup_test::temporary_folder("cli_bad");
  auto write = [&](const std::string& name, const std::string& content) {
    std::ofstream(dir + "/" + name, std::ios::binary) << content;
    return dir + "/" + name;
  };
  std::string truncated(84, '\0');
  truncated[80] = 10; // announces 10 facets, holds none
  const std::pair<std::string, std::string> cases[] = {
    {write("truncated.stl", truncated), "truncated"},
    {write("garbage.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 zero\n"), ":4:"},
    {write("noend.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendfacet\n"),
     "endloop"},
    {write("bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"), "bad.off:6: face 0 of 1 has vertex index 7, out of range"},
    {write("nan.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 nan\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid\n"),
     "non-finite"},
    {dir + "/missing.stl", "cannot open"},
    {write("model.xyz", "1 2 3\n"), "unknown file extension"},
  };
  for(const auto& c : cases) {
    SCOPED_TRACE(c.first);
    const auto [out, code] = soup_test::run_command(cli() + " stats '" + c.first + "' 2>&1");
    EXPECT_EQ(code, 2) << out;
    EXPECT_NE(out.find(c.second), std::string::npos) << out;
  }
  const auto [out, code] = soup_test::run_command(cli() + " frobnicate 2>&1");
  EXPECT_EQ(code, 2);
  EXPECT_NE(out.find("unknown command"), std::string::npos);
}

// ---------------------------------------------------------------------------------------------
// Issue 21: hostile inputs (many triangles on one edge, vertices of high degree) cost linear time,
// and the tables are those of an obviously correct slow computation.

using size_type = Tables::size_type;

// The tables computed the slow way, from the definitions.
struct Reference
{
  std::vector<std::array<size_type, 3>> neighbors;
  std::vector<std::vector<size_type>> around;
  std::vector<Tables::Edge> non_manifold_edges, inconsistent_edges;
  std::vector<size_type> non_manifold_vertices, component;
  std::size_t components = 0, border_edges = 0;
};

Reference brute_force(const std::vector<Tables::Triangle>& tris, std::size_t nv)
{
  const size_type n = static_cast<size_type>(tris.size());
  auto has = [&](size_type t, size_type v) { return tris[t][0] == v || tris[t][1] == v || tris[t][2] == v; };
  // All the triangles other than t containing edge i of t.
  auto others = [&](size_type t, int i) {
    std::vector<size_type> r;
    const size_type a = tris[t][i], b = tris[t][(i + 1) % 3];
    for(size_type u = 0; u < n; ++u) if(u != t && has(u, a) && has(u, b)) r.push_back(u);
    return r;
  };
  Reference ref;
  ref.neighbors.resize(n);
  ref.around.resize(nv);
  for(size_type t = 0; t < n; ++t)
    for(int i = 0; i < 3; ++i) {
      const std::vector<size_type> o = others(t, i);
      ref.neighbors[t][i] = o.empty() ? Tables::border_edge : o.size() == 1 ? o[0] : Tables::non_manifold_edge;
      if(o.empty()) ++ref.border_edges;
      if(o.size() >= 2 && o[0] > t) ref.non_manifold_edges.push_back(Tables::Edge{t, i});
      if(o.size() == 1 && o[0] > t) {
        const size_type u = o[0], a = tris[t][i], b = tris[t][(i + 1) % 3];
        for(int j = 0; j < 3; ++j)
          if(tris[u][j] == a && tris[u][(j + 1) % 3] == b) ref.inconsistent_edges.push_back(Tables::Edge{t, i});
      }
      ref.around[tris[t][i]].push_back(t);
    }
  // Components: breadth-first search from each triangle not reached yet, in increasing order,
  // across every pair of triangles with two common vertices.
  auto common = [&](size_type t, size_type u) {
    int c = 0;
    for(size_type v : tris[t]) if(has(u, v)) ++c;
    return c;
  };
  ref.component.assign(n, Tables::border_edge);
  for(size_type seed = 0; seed < n; ++seed) {
    if(ref.component[seed] != Tables::border_edge) continue;
    const size_type id = static_cast<size_type>(ref.components++);
    std::vector<size_type> queue = {seed};
    ref.component[seed] = id;
    for(std::size_t q = 0; q < queue.size(); ++q)
      for(size_type u = 0; u < n; ++u)
        if(ref.component[u] == Tables::border_edge && common(queue[q], u) >= 2) { ref.component[u] = id; queue.push_back(u); }
  }
  // Non-manifold vertices: the triangles of v, joined across the edges {v, w} of exactly two
  // triangles, form more than one group.
  std::map<std::pair<size_type, size_type>, std::size_t> on_edge;
  for(const Tables::Triangle& t : tris)
    for(int i = 0; i < 3; ++i) ++on_edge[std::minmax(t[i], t[(i + 1) % 3])];
  for(size_type v = 0; v < nv; ++v) {
    const std::vector<size_type>& tv = ref.around[v];
    if(tv.size() < 2) continue;
    std::vector<char> reached(tv.size(), 0);
    std::vector<std::size_t> queue = {0};
    reached[0] = 1;
    for(std::size_t q = 0; q < queue.size(); ++q)
      for(std::size_t y = 0; y < tv.size(); ++y)
        for(size_type w : tris[tv[queue[q]]])
          if(!reached[y] && w != v && has(tv[y], w) && on_edge[std::minmax(v, w)] == 2) { reached[y] = 1; queue.push_back(y); }
    if(queue.size() != tv.size()) ref.non_manifold_vertices.push_back(v);
  }
  return ref;
}

void expect_tables_match_reference(const Tables& adj, const std::vector<Tables::Triangle>& tris, std::size_t nv)
{
  ASSERT_EQ(std::vector<Tables::Triangle>(adj.triangles().begin(), adj.triangles().end()), tris);
  ASSERT_EQ(adj.number_of_vertices(), nv);
  const Reference ref = brute_force(tris, nv);
  for(size_type t = 0; t < tris.size(); ++t)
    for(int i = 0; i < 3; ++i) {
      ASSERT_EQ(adj.neighbor(t, i), ref.neighbors[t][i]) << "triangle " << t << ", edge " << i;
      std::vector<size_type> around_edge, expected;
      adj.triangles_around_edge(t, i, std::back_inserter(around_edge));
      for(size_type u : ref.around[tris[t][i]])
        if(u != t && adj.local_index(u, tris[t][(i + 1) % 3]) >= 0) expected.push_back(u);
      ASSERT_EQ(around_edge, expected) << "triangle " << t << ", edge " << i;
    }
  for(size_type v = 0; v < nv; ++v) ASSERT_EQ(around(adj, v), ref.around[v]) << "vertex " << v;
  EXPECT_EQ(adj.non_manifold_edges(), ref.non_manifold_edges);
  EXPECT_EQ(adj.inconsistently_oriented_edges(), ref.inconsistent_edges);
  EXPECT_EQ(adj.non_manifold_vertices(), ref.non_manifold_vertices);
  EXPECT_EQ(adj.number_of_border_edges(), ref.border_edges);
  EXPECT_EQ(adj.is_closed(), ref.border_edges == 0);
  std::vector<size_type> component;
  EXPECT_EQ(adj.number_of_connected_components(&component), ref.components);
  EXPECT_EQ(component, ref.component);
}

TEST(AdjacencyTables, Issue21BruteForceCrossCheckWithLocalUpdates)
{
  std::mt19937 rng(2126);
  auto pick = [&](std::size_t n) { return static_cast<size_type>(rng() % n); };
  for(int soup = 0; soup < 250; ++soup) {
    SCOPED_TRACE("soup " + std::to_string(soup));
    // Few vertices, many triangles, copies in every rotation and direction: many non-manifold
    // edges and repeated triangles. Six spare vertices are there for the splits.
    const std::size_t used = 4 + rng() % 5, nv = used + 6;
    std::vector<Tables::Triangle> tris;
    const std::size_t count = 1 + rng() % 30;
    while(tris.size() < count) {
      if(!tris.empty() && rng() % 3 == 0) {
        Tables::Triangle t = tris[pick(tris.size())];
        std::rotate(t.begin(), t.begin() + rng() % 3, t.end());
        if(rng() % 2) std::swap(t[0], t[1]);
        tris.push_back(t);
        continue;
      }
      const Tables::Triangle t = {pick(used), pick(used), pick(used)};
      if(t[0] != t[1] && t[1] != t[2] && t[2] != t[0]) tris.push_back(t);
    }
    Tables adj(tris, nv);
    expect_tables_match_reference(adj, tris, nv);
    if(HasFatalFailure()) return;
    for(int step = 0; step < 12; ++step) {
      if(rng() % 5 < 3) {
        const size_type t = pick(tris.size());
        const int i = static_cast<int>(rng() % 3);
        const size_type v = pick(nv);
        if(adj.local_index(t, v) >= 0) {
          EXPECT_THROW(adj.split_triangle(t, i, v), ST::Invalid_input);
        } else {
          Tables::Triangle created = tris[t];
          created[static_cast<std::size_t>(i)] = v;
          tris[t][static_cast<std::size_t>((i + 1) % 3)] = v;
          tris.push_back(created);
          EXPECT_EQ(adj.split_triangle(t, i, v), tris.size() - 1);
        }
      } else {
        const size_type duplicate = pick(nv), original = pick(nv);
        bool together = false;
        for(const Tables::Triangle& t : tris)
          together |= duplicate != original && std::count(t.begin(), t.end(), duplicate) + std::count(t.begin(), t.end(), original) == 2;
        if(together) {
          EXPECT_THROW(adj.replace_vertex(duplicate, original), ST::Invalid_input);
        } else {
          for(Tables::Triangle& t : tris) for(size_type& v : t) if(v == duplicate) v = original;
          adj.replace_vertex(duplicate, original);
        }
      }
      SCOPED_TRACE("after update " + std::to_string(step));
      expect_tables_match_reference(adj, tris, nv);
      if(HasFatalFailure()) return;
    }
  }
}

// Runs `work` in a child process limited to `cpu_seconds` of processor time (ten times more in
// sanitizer builds); returns "" if it finished and returned true, else what happened.
std::string run_with_cpu_bound(double cpu_seconds, const std::function<bool()>& work)
{
  const pid_t pid = fork();
  if(pid < 0) return "fork failed";
  if(pid == 0) {
    const double bound = soup_test::sanitized_build ? 10 * cpu_seconds : cpu_seconds;
    rlimit limit;
    limit.rlim_cur = static_cast<rlim_t>(std::ceil(bound));
    limit.rlim_max = limit.rlim_cur + 1;
    setrlimit(RLIMIT_CPU, &limit);
    bool ok = false;
    try { ok = work(); } catch(...) { ok = false; }
    _exit(ok ? 0 : 1);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  if(WIFSIGNALED(status)) return "killed by signal " + std::to_string(WTERMSIG(status)) + " (processor time bound exceeded)";
  if(!WIFEXITED(status) || WEXITSTATUS(status) != 0) return "wrong result";
  return "";
}

bool same(std::size_t value, std::size_t expected, const char* what)
{
  if(value != expected) std::fprintf(stderr, "%s: %zu, expected %zu\n", what, value, expected);
  return value == expected;
}

// The edges of a vertex are grouped by a sort in place when they are few (up to
// `sorted_row_limit`, 32 edges to later vertices) and by buckets when they are more: the two
// groupings must give the same tables. A soup in random order whose vertices have from 1 to 60
// such edges, with repeated triangles and non-manifold edges, against a brute-force table.
TEST(AdjacencyTables, Issue13FewAndManyEdgesOfAVertexGroupAlike)
{
  std::mt19937 rng(1313);
  std::vector<Tables::Triangle> tris;
  // vertex 0: 30 triangles on ten other vertices (60 edges to later vertices); vertices 11..40,
  // a strip; the rest at random among 41..60, and a few copies of earlier triangles
  for(size_type k = 0; k < 30; ++k) tris.push_back({0, 1 + k % 10, 1 + (k + 1 + k / 10) % 10});
  for(size_type k = 11; k + 2 <= 40; ++k) tris.push_back({k, k + 1, k + 2});
  while(tris.size() < 200) {
    if(rng() % 5 == 0) {
      tris.push_back(tris[rng() % tris.size()]);
      continue;
    }
    const size_type a = 41 + rng() % 20, b = 41 + rng() % 20, c = 41 + rng() % 20;
    if(a != b && b != c && c != a) tris.push_back({a, b, c});
  }
  std::shuffle(tris.begin(), tris.end(), rng);
  const Tables adj(tris, 61);
  std::size_t long_rows = 0, short_rows = 0;
  for(size_type v = 0; v < 61; ++v) {
    std::size_t edges = 0; // with their copies
    for(size_type t : adj.triangles_around_vertex(v)) {
      const int i = adj.local_index(t, v);
      edges += (adj.vertex(t, (i + 1) % 3) > v ? 1 : 0) + (adj.vertex(t, (i + 2) % 3) > v ? 1 : 0);
    }
    (edges > 32 ? long_rows : short_rows) += edges > 0 ? 1 : 0;
  }
  EXPECT_GE(long_rows, 1u);
  EXPECT_GE(short_rows, 20u);
  for(size_type t = 0; t < tris.size(); ++t)
    for(int i = 0; i < 3; ++i) {
      const size_type a = tris[t][std::size_t(i)], b = tris[t][std::size_t((i + 1) % 3)];
      std::vector<size_type> with_edge;
      for(size_type u = 0; u < tris.size(); ++u) {
        const auto& tr = tris[u];
        if(std::count(tr.begin(), tr.end(), a) == 1 && std::count(tr.begin(), tr.end(), b) == 1 && u != t)
          with_edge.push_back(u);
      }
      const size_type expected = with_edge.empty() ? Tables::border_edge
                                 : with_edge.size() == 1 ? with_edge[0] : Tables::non_manifold_edge;
      EXPECT_EQ(adj.neighbor(t, i), expected) << "triangle " << t << ", edge " << i;
    }
  std::vector<Tables::Edge> non_manifold = adj.non_manifold_edges();
  EXPECT_FALSE(non_manifold.empty());
  EXPECT_TRUE(std::is_sorted(non_manifold.begin(), non_manifold.end()));
}

// The fans of every vertex are walked with the rows of the triangles of the vertices ahead asked
// for in advance (`for_each_vertex_of_several_fans()`): the vertices found with several fans
// must be those of the brute force, whatever the order of the triangles and however many
// vertices have fewer than two triangles between those walked. A grid surface with pinched
// vertices (two fans each), repeated triangles (non-manifold edges), holes, a fan of 80
// triangles around one vertex, and unused vertex numbers between the used ones; its triangles
// in grid order and shuffled. Then the same walk across the edges a predicate links, against
// the fans of `fans_around_vertex()` with the complementary edges cut.
TEST(AdjacencyTables, Issue13FansFoundAheadOfTheWalkAsByBruteForce)
{
  std::mt19937 rng(1317);
  const size_type side = 24, spread = 3; // grid vertex (i, j) is vertex spread * (i side + j)
  auto grid = [&](size_type i, size_type j) { return spread * (i * side + j); };
  std::vector<Tables::Triangle> tris;
  for(size_type i = 0; i + 1 < side; ++i)
    for(size_type j = 0; j + 1 < side; ++j) {
      if(rng() % 40 == 0) continue; // a hole
      tris.push_back({grid(i, j), grid(i + 1, j), grid(i + 1, j + 1)});
      tris.push_back({grid(i, j), grid(i + 1, j + 1), grid(i, j + 1)});
    }
  // pinched vertices: a vertex of a corner triangle elsewhere replaced by an interior vertex
  for(int pinch = 0; pinch < 6; ++pinch) {
    Tables::Triangle& t = tris[rng() % tris.size()];
    const size_type v = grid(2 + rng() % (side - 4), 2 + rng() % (side - 4));
    if(std::find(t.begin(), t.end(), v) == t.end()) t[rng() % 3] = v;
  }
  for(int copy = 0; copy < 8; ++copy) tris.push_back(tris[rng() % tris.size()]);
  const size_type hub = spread * side * side + 1; // a closed fan of 80 triangles (vertex hub)
  for(size_type k = 0; k < 80; ++k)
    tris.push_back({hub, hub + 1 + k, hub + 1 + (k + 1) % 80});
  const std::size_t nv = hub + 81 + 5;
  for(int order = 0; order < 2; ++order) {
    SCOPED_TRACE(order == 0 ? "grid order" : "shuffled");
    if(order == 1) std::shuffle(tris.begin(), tris.end(), rng);
    const Tables adj(tris, nv);
    const std::vector<size_type> expected = brute_force(tris, nv).non_manifold_vertices;
    EXPECT_GE(expected.size(), 3u);
    EXPECT_EQ(adj.non_manifold_vertices(), expected);
    EXPECT_EQ(adj.non_manifold_vertices<CGAL::Parallel_if_available_tag>(), expected);
    // in pieces: every range of vertices gives its own
    std::vector<size_type> by_ranges;
    for(std::size_t begin = 0; begin < nv; begin += 37)
      adj.for_each_vertex_of_several_fans(begin, std::min(nv, begin + 37), [](size_type, int) { return true; },
                                          [&](size_type v) { by_ranges.push_back(v); });
    EXPECT_EQ(by_ranges, expected);
    // across the edges a predicate links: one cut per pair of neighbours, on both sides
    std::vector<char> cut(3 * tris.size(), 0);
    for(size_type t = 0; t < tris.size(); ++t)
      for(int i = 0; i < 3; ++i) {
        const size_type u = adj.neighbor(t, i);
        if(u < t || u >= Tables::non_manifold_edge || rng() % 6 != 0) continue;
        cut[3 * std::size_t(t) + std::size_t(i)] = 1;
        cut[3 * std::size_t(u) + std::size_t(adj.edge_index(u, tris[t][std::size_t(i)], tris[t][std::size_t((i + 1) % 3)]))] = 1;
      }
    std::vector<size_type> several, by_search;
    adj.for_each_vertex_of_several_fans(0, nv, [&](size_type t, int i) { return cut[3 * std::size_t(t) + std::size_t(i)] == 0; },
                                        [&](size_type v) { several.push_back(v); });
    std::vector<std::size_t> fan, stack;
    for(size_type v = 0; v < nv; ++v)
      if(adj.degree(v) >= 2 && ST::internal::fans_around_vertex(adj, cut, v, fan, stack) > 1) by_search.push_back(v);
    EXPECT_GT(by_search.size(), expected.size());
    EXPECT_EQ(several, by_search);
  }
}

TEST(AdjacencyTables, Issue21RepeatedTriangle)
{
  // One triangle 100,000 times: every pair of copies shares three edges.
  EXPECT_EQ(run_with_cpu_bound(2, [] {
    const std::vector<Point> points = {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0)};
    const std::vector<Triangle> triangles(100000, Triangle{0, 1, 2});
    const Tables adj(triangles, points.size());
    const ST::Soup_statistics s = ST::compute_statistics(points, adj);
    std::vector<size_type> others;
    adj.triangles_around_edge(0, 0, std::back_inserter(others));
    return same(s.triangles, 100000, "triangles") && same(s.border_edges, 0, "border edges") &&
           same(s.non_manifold_edges, 3, "non-manifold edges") &&
           same(s.non_manifold_vertices, 3, "non-manifold vertices") &&
           same(s.inconsistent_edges, 0, "inconsistent edges") && same(s.components, 1, "components") &&
           same(others.size(), 99999, "triangles around edge") && s.closed;
  }), "");
}

TEST(AdjacencyTables, Issue21ManyTrianglesOnOneEdge)
{
  // 20,000 triangles on the edge {0, 1}; then 2,000 of them are split on that edge, each at its
  // own new vertex (the edge is resolved again at every split).
  EXPECT_EQ(run_with_cpu_bound(2, [] {
    const size_type n = 20000, splits = 2000;
    std::vector<Point> points = {Point(0, 0, 0), Point(1, 0, 0)};
    std::vector<Triangle> triangles;
    for(size_type k = 0; k < n; ++k) {
      points.push_back(Point(0.5, k + 1, k % 7));
      triangles.push_back({0, 1, 2 + std::size_t(k)});
    }
    for(size_type k = 0; k < splits; ++k) points.push_back(Point(0.5 + (k + 1) * 1e-6, 0, 0));
    Tables adj(triangles, points.size());
    ST::Soup_statistics s = ST::compute_statistics(points, adj);
    bool ok = same(s.non_manifold_edges, 1, "non-manifold edges") && same(s.border_edges, 2 * n, "border edges") &&
              same(s.non_manifold_vertices, 2, "non-manifold vertices") && same(s.components, 1, "components");
    for(size_type k = 0; k < splits; ++k) adj.split_triangle(k, 0, 2 + n + k);
    s = ST::compute_statistics(points, adj);
    // Each split pair hangs on nothing but itself: a component of its own.
    return ok && same(s.triangles, n + splits, "triangles") && same(s.non_manifold_edges, 1, "non-manifold edges") &&
           same(s.border_edges, 2 * n + 2 * splits, "border edges") && same(s.components, 1 + splits, "components") &&
           same(adj.number_of_connected_components(), 1 + splits, "components");
  }), "");
}

TEST(AdjacencyTables, Issue21FanAroundOneVertex)
{
  // A closed fan of 100,000 triangles around vertex 0, built in two halves around 0 and around a
  // copy of it that is welded back; then 1,000 single triangles welded onto 0 and 10,000 splits
  // of rim edges (0 is a vertex of every split triangle).
  EXPECT_EQ(run_with_cpu_bound(2, [] {
    const size_type n = 100000, copies = 1000, splits = 10000;
    const size_type copy = n + 1, extra = n + 2;
    std::vector<Point> points(extra + 3 * copies + splits, Point(0, 0, 0));
    std::vector<Triangle> triangles;
    for(size_type k = 0; k < n; ++k)
      triangles.push_back({k < n / 2 ? 0 : copy, 1 + std::size_t(k), 1 + std::size_t((k + 1) % n)});
    for(size_type j = 0; j < copies; ++j)
      triangles.push_back({extra + 3 * std::size_t(j), extra + 3 * std::size_t(j) + 1, extra + 3 * std::size_t(j) + 2});
    Tables adj(triangles, points.size());
    bool ok = same(adj.non_manifold_vertices().size(), 2, "non-manifold vertices (two open fans)");
    adj.replace_vertex(copy, 0);
    for(size_type j = 0; j < copies; ++j) adj.replace_vertex(extra + 3 * j, 0);
    ok = ok && same(adj.degree(0), n + copies, "degree") && same(adj.number_of_border_edges(), n + 3 * copies, "border edges") &&
         same(adj.non_manifold_vertices().size(), 1, "non-manifold vertices (the fan and the welded triangles)") &&
         same(adj.number_of_connected_components(), 1 + copies, "components");
    for(size_type k = 0; k < splits; ++k) adj.split_triangle(10 * k, 1, extra + 3 * copies + k);
    const ST::Soup_statistics s = ST::compute_statistics(points, adj);
    return ok && same(s.triangles, n + copies + splits, "triangles") &&
           same(s.border_edges, n + 3 * copies + splits, "border edges") && same(s.non_manifold_edges, 0, "non-manifold edges") &&
           same(s.non_manifold_vertices, 1, "non-manifold vertices") && same(s.components, 1 + copies, "components") &&
           same(adj.degree(0), n + copies + splits, "degree");
  }), "");
}

// A triangle (a, b, apex) with `n` collinear points on its edge [a, b], and on the other side of
// that edge a strip of 2 (n + 1) triangles through those points: T-junction splitting makes a fan
// of n + 1 triangles around the apex.
void t_junction_strip(std::size_t n, std::vector<Point>& points, std::vector<Triangle>& triangles)
{
  points = {Point(0, 0, 0), Point(1, 0, 0), Point(0.5, 1, 0)};
  triangles = {{0, 1, 2}};
  std::vector<std::size_t> chain = {0};
  for(std::size_t k = 1; k <= n; ++k) {
    chain.push_back(points.size());
    points.push_back(Point(double(k) / double(n + 1), 0, 0));
  }
  chain.push_back(1);
  const std::size_t below = points.size();
  for(std::size_t k = 0; k <= n + 1; ++k) points.push_back(Point(double(k) / double(n + 1), -0.01, 0));
  for(std::size_t k = 0; k + 1 < chain.size(); ++k) {
    triangles.push_back({chain[k + 1], chain[k], below + k});
    triangles.push_back({chain[k + 1], below + k, below + k + 1});
  }
}

TEST(AdjacencyTables, Issue21TJunctionsAlongOneEdge)
{
  // The splits that T-junction repair makes on this soup, in its order: along [a, b], each split
  // continues in the new triangle. The apex gains a triangle at every split.
  EXPECT_EQ(run_with_cpu_bound(2, [] {
    const std::size_t n = 100000;
    std::vector<Point> points;
    std::vector<Triangle> triangles;
    t_junction_strip(n, points, triangles);
    Tables adj(triangles, points.size());
    size_type t = 0;
    for(size_type c = 3; c < 3 + n; ++c) t = adj.split_triangle(t, 0, c);
    const ST::Soup_statistics s = ST::compute_statistics(points, adj);
    return same(s.triangles, 3 * n + 3, "triangles") && same(s.border_edges, n + 5, "border edges") &&
           same(s.non_manifold_edges, 0, "non-manifold edges") && same(s.non_manifold_vertices, 0, "non-manifold vertices") &&
           same(s.inconsistent_edges, 0, "inconsistent edges") && same(s.components, 1, "components") &&
           same(s.zero_area_triangles, 0, "zero-area triangles") && same(adj.degree(2), n + 1, "degree of the apex");
  }), "");
  // The whole repair. The bound is looser: most of the time goes to finding the T-junctions
  // (exact predicates on collinear points), not to the tables.
  EXPECT_EQ(run_with_cpu_bound(15, [] {
    const std::size_t n = 100000;
    std::vector<Point> points;
    std::vector<Triangle> triangles;
    t_junction_strip(n, points, triangles);
    const ST::Reconstruction_report r =
      ST::reconstruct_topology(points, triangles, CGAL::parameters::snapping_tolerance(1e-9));
    return same(r.t_junctions, n, "T-junctions") && same(r.split_triangles, n, "splits") &&
           same(r.output_triangles, 3 * n + 3, "triangles") && same(r.border_edges_after, n + 5, "border edges") &&
           same(r.components, 1, "components");
  }), "");
}

TEST(CommandLine, Issue21HostileStatsWithinTwoSecondsAnd500MB)
{
  const std::string dir = soup_test::temporary_folder("issue21_stats");
  struct Case { std::string name; long long triangles, border, non_manifold_edges, non_manifold_vertices, components; };
  std::vector<Case> cases;
  {
    std::ofstream out(dir + "/repeated.off");
    out << "OFF\n3 100000 0\n0 0 0\n1 0 0\n0 1 0\n";
    for(int k = 0; k < 100000; ++k) out << "3 0 1 2\n";
    cases.push_back({"repeated.off", 100000, 0, 3, 3, 1});
  }
  {
    std::ofstream out(dir + "/one_edge.off");
    out << "OFF\n20002 20000 0\n0 0 0\n1 0 0\n";
    for(int k = 0; k < 20000; ++k) out << "0.5 " << k + 1 << " " << k % 7 << "\n";
    for(int k = 0; k < 20000; ++k) out << "3 0 1 " << k + 2 << "\n";
    cases.push_back({"one_edge.off", 20000, 40000, 1, 2, 1});
  }
  {
    const int n = 100000;
    std::ofstream out(dir + "/fan.off");
    out.precision(17);
    out << "OFF\n" << n + 1 << " " << n << " 0\n0 0 0\n";
    for(int k = 0; k < n; ++k) out << std::cos(2 * CGAL_PI * k / n) << " " << std::sin(2 * CGAL_PI * k / n) << " 0\n";
    for(int k = 0; k < n; ++k) out << "3 0 " << 1 + k << " " << 1 + (k + 1) % n << "\n";
    cases.push_back({"fan.off", n, n, 0, 0, 1});
  }
  {
    std::ofstream out(dir + "/face.obj");
    out << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf";
    for(int k = 0; k < 50000; ++k) out << " " << 1 + k % 4;
    out << "\n";
    // A polygon that repeats a vertex is not simple: the reader skips it and counts it, in linear
    // time, rather than fanning it into triangles piled on the same edges.
    cases.push_back({"face.obj", 0, 0, 0, 0, 0});
  }
  for(const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const soup_test::Bounded_run r = soup_test::run_bounded({cli(), "stats", dir + "/" + c.name, "--json"}, 2, 500);
    ASSERT_TRUE(r.exited_normally()) << "signal " << r.signal << "\n" << r.err;
    ASSERT_EQ(r.exit_code, 0) << r.err;
    if(!soup_test::sanitized_build) { EXPECT_LT(r.cpu_seconds, 2.0); }
    EXPECT_LT(r.peak_rss_mb, 500u);
    if(c.triangles >= 0) { EXPECT_EQ(soup_test::json_integer(r.out, "triangles"), c.triangles); }
    EXPECT_EQ(soup_test::json_integer(r.out, "border_edges"), c.border);
    EXPECT_EQ(soup_test::json_integer(r.out, "non_manifold_edges"), c.non_manifold_edges);
    EXPECT_EQ(soup_test::json_integer(r.out, "non_manifold_vertices"), c.non_manifold_vertices);
    EXPECT_EQ(soup_test::json_integer(r.out, "components"), c.components);
    if(c.name == "face.obj") { EXPECT_EQ(soup_test::json_integer(r.out, "non_simple_polygons"), 1); }
  }
}

// ---------------------------------------------------------------------------------------------
// Issue 20: NaN coordinates are refused by name, and the caller's data is left as it was.

TEST(BadInput, Issue20NaNCoordinatesAreRefused)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<Point> points = {Point(0, 0, 0), Point(1, 0, 0), Point(0, nan, 0), Point(0, 0, 0)};
  std::vector<Triangle> faces = {{0, 1, 2}, {3, 1, 2}};
  const auto points_before = points;
  const auto faces_before = faces;
  try {
    ST::merge_duplicate_points(points, faces);
    FAIL() << "no exception";
  } catch(const ST::Invalid_input& e) {
    EXPECT_NE(std::string(e.what()).find("point 2"), std::string::npos) << e.what();
  }
  ASSERT_EQ(points.size(), points_before.size());
  for(std::size_t i = 0; i < points.size(); ++i)
    if(i != 2) { EXPECT_EQ(points[i], points_before[i]); }
  EXPECT_TRUE(std::isnan(points[2].y()));
  EXPECT_EQ(faces, faces_before);

  const std::vector<std::array<Point, 3>> soup = {
    {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0)},
    {Point(0, 0, 0), Point(1, 0, 0), Point(0, 0, std::numeric_limits<double>::infinity())}};
  std::vector<Point> indexed_points = {Point(5, 5, 5)};
  std::vector<Triangle> indexed = {{0, 0, 0}};
  try {
    ST::index_triangles(soup, indexed_points, indexed);
    FAIL() << "no exception";
  } catch(const ST::Invalid_input& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 1, corner 2"), std::string::npos) << e.what();
  }
  EXPECT_EQ(indexed_points, (std::vector<Point>{Point(5, 5, 5)}));
  EXPECT_EQ(indexed, (std::vector<Triangle>{{0, 0, 0}}));
}

} // namespace

} // namespace Adjacency_tables_test
