// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Tests of the Boost.Graph views Triangle_adjacency_graph and Vertex_adjacency_graph.

#include <cstddef>

// The number of triangles the views scan to list the triangles of non-manifold edges.
namespace {
std::size_t graph_view_scanned_triangles = 0;
}
#define SOUP_TOPOLOGY_GRAPH_VIEW_SCAN(number_of_triangles) (graph_view_scanned_triangles += (number_of_triangles))

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/IO/read_triangle_soup.h>
#include <Soup_topology/Triangle_adjacency_graph.h>
#include <Soup_topology/Vertex_adjacency_graph.h>
#include <Soup_topology/index_triangles.h>
#if __has_include(<Soup_topology/IO/VRML.h>)
#include <Soup_topology/IO/VRML.h>
#define SOUP_TOPOLOGY_TEST_VRML 1
#endif

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <boost/graph/breadth_first_search.hpp>
#include <boost/graph/connected_components.hpp>
#include <boost/graph/dijkstra_shortest_paths.hpp>
#include <boost/graph/filtered_graph.hpp>
#include <boost/graph/graph_concepts.hpp>
#include <boost/property_map/function_property_map.hpp>

#include <gtest/gtest.h>

#include "test_utilities.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <map>
#include <numeric>
#include <set>
#include <string>
#include <utility>
#include <vector>

// The names of this file live in a namespace of its own: test/CMakeLists.txt compiles several
// test files as one translation unit.
namespace Adjacency_graphs_test {

namespace {

namespace ST = Soup_topology;
namespace fs = std::filesystem;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Face = std::array<std::size_t, 3>;
using size_type = ST::Adjacency_tables::size_type;
using TG = ST::Triangle_adjacency_graph;
using VG = ST::Vertex_adjacency_graph;

BOOST_CONCEPT_ASSERT((boost::VertexListGraphConcept<TG>));
BOOST_CONCEPT_ASSERT((boost::IncidenceGraphConcept<TG>));
BOOST_CONCEPT_ASSERT((boost::BidirectionalGraphConcept<TG>));
BOOST_CONCEPT_ASSERT((boost::AdjacencyGraphConcept<TG>));
BOOST_CONCEPT_ASSERT((boost::EdgeListGraphConcept<TG>));
BOOST_CONCEPT_ASSERT((boost::ReadablePropertyGraphConcept<TG, boost::graph_traits<TG>::vertex_descriptor, boost::vertex_index_t>));
BOOST_CONCEPT_ASSERT((boost::ReadablePropertyGraphConcept<TG, boost::graph_traits<TG>::edge_descriptor, boost::edge_index_t>));
BOOST_CONCEPT_ASSERT((boost::VertexListGraphConcept<VG>));
BOOST_CONCEPT_ASSERT((boost::IncidenceGraphConcept<VG>));
BOOST_CONCEPT_ASSERT((boost::BidirectionalGraphConcept<VG>));
BOOST_CONCEPT_ASSERT((boost::AdjacencyGraphConcept<VG>));
BOOST_CONCEPT_ASSERT((boost::EdgeListGraphConcept<VG>));
BOOST_CONCEPT_ASSERT((boost::ReadablePropertyGraphConcept<VG, boost::graph_traits<VG>::vertex_descriptor, boost::vertex_index_t>));
BOOST_CONCEPT_ASSERT((boost::ReadablePropertyGraphConcept<VG, boost::graph_traits<VG>::edge_descriptor, boost::edge_index_t>));

struct Soup
{
  std::string name;
  std::vector<Point> points;
  std::vector<Face> triangles;
};

// ---------------------------------------------------------------------------------------------
// Reference computations, from the triangle list only (no Adjacency_tables).

// Sorted vertex pair -> the triangles containing that edge.
std::map<std::pair<std::size_t, std::size_t>, std::vector<std::size_t>> edge_map(const std::vector<Face>& triangles)
{
  std::map<std::pair<std::size_t, std::size_t>, std::vector<std::size_t>> m;
  for(std::size_t t = 0; t < triangles.size(); ++t)
    for(int i = 0; i < 3; ++i) {
      std::size_t a = triangles[t][std::size_t(i)], b = triangles[t][std::size_t((i + 1) % 3)];
      if(a > b) std::swap(a, b);
      m[{a, b}].push_back(t);
    }
  return m;
}

struct Union_find
{
  std::vector<std::size_t> parent;
  explicit Union_find(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), std::size_t(0)); }
  std::size_t find(std::size_t x)
  {
    while(parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(std::size_t a, std::size_t b) { parent[find(a)] = find(b); }
};

// Triangle -> triangles sharing an edge with it (with multiplicity: one entry per shared edge).
std::vector<std::vector<std::size_t>> reference_triangle_neighbors(const std::vector<Face>& triangles)
{
  std::vector<std::vector<std::size_t>> nb(triangles.size());
  for(const auto& entry : edge_map(triangles))
    for(std::size_t a : entry.second)
      for(std::size_t b : entry.second)
        if(a != b) nb[a].push_back(b);
  for(auto& l : nb) std::sort(l.begin(), l.end());
  return nb;
}

// Relabels a partition by order of first appearance, so that two labellings can be compared.
template <class Labels>
std::vector<std::size_t> canonical_labels(const Labels& labels)
{
  std::map<std::size_t, std::size_t> first;
  std::vector<std::size_t> out;
  for(auto l : labels) out.push_back(first.emplace(std::size_t(l), first.size()).first->second);
  return out;
}

Point centroid(const Soup& s, std::size_t t)
{
  return CGAL::centroid(s.points[s.triangles[t][0]], s.points[s.triangles[t][1]], s.points[s.triangles[t][2]]);
}

// ---------------------------------------------------------------------------------------------
// Small soups built in code.

// A unit cube, 8 vertices and 12 triangles.
Soup cube()
{
  Soup s;
  s.name = "cube";
  for(int k = 0; k < 8; ++k) s.points.emplace_back(k & 1, (k >> 1) & 1, (k >> 2) & 1);
  s.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                 {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return s;
}

// An n x n grid of the unit square with two triangles per cell, plus two "fin" triangles standing
// on the grid edge between vertices (1,1) and (2,1), which makes it non-manifold (4 triangles),
// plus a separate triangle far away, and an isolated vertex.
Soup grid_with_fins(int n)
{
  Soup s;
  s.name = "grid_with_fins";
  auto id = [n](int i, int j) { return std::size_t(j * (n + 1) + i); };
  for(int j = 0; j <= n; ++j)
    for(int i = 0; i <= n; ++i) s.points.emplace_back(i, j + 0.1 * ((i * 7 + j * 3) % 5), 0.05 * i * j);
  for(int j = 0; j < n; ++j)
    for(int i = 0; i < n; ++i) {
      s.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  const std::size_t top1 = s.points.size();
  s.points.emplace_back(1.5, 1, 2);
  const std::size_t top2 = s.points.size();
  s.points.emplace_back(1.5, 1.5, -2);
  s.triangles.push_back({id(1, 1), id(2, 1), top1});
  s.triangles.push_back({id(2, 1), id(1, 1), top2});
  const std::size_t far = s.points.size();
  s.points.emplace_back(100, 100, 100);
  s.points.emplace_back(101, 100, 100);
  s.points.emplace_back(100, 101, 100);
  s.triangles.push_back({far, far + 1, far + 2});
  s.points.emplace_back(-50, -50, -50);   // isolated
  return s;
}

// ---------------------------------------------------------------------------------------------
// The real meshes.

bool read_soup(const fs::path& file, Soup& soup)
{
  const fs::path path = soup_test::decompressed_file(file.string());
  const std::string name = path.filename().string();
  soup.name = fs::relative(file, SOUP_TOPOLOGY_DATA_DIR).string();
  const std::string ext = ST::IO::file_extension(name);
  if(ext == "wrl") {
#if defined(SOUP_TOPOLOGY_TEST_VRML)
    ST::IO::read_VRML(path.string(), soup.points, soup.triangles);
    ST::merge_duplicate_points(soup.points, soup.triangles);
    ST::remove_collapsed_triangles(soup.triangles);
    return true;
#else
    return false;
#endif
  }
  if(ext != "off" && ext != "stl" && ext != "obj" && ext != "ply") return false;
  ST::IO::read_triangle_soup(path.string(), soup.points, soup.triangles);
  return true;
}

std::vector<fs::path> data_files()
{
  std::vector<fs::path> files;
  for(const auto& entry : fs::recursive_directory_iterator(SOUP_TOPOLOGY_DATA_DIR))
    if(entry.is_regular_file() && entry.path().extension() != ".md") files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

// ---------------------------------------------------------------------------------------------
// Checks shared by the soups built in code and the real meshes.

// Triangle view: components, edges, degrees, indices, against the reference computations.
// Returns the number of components.
std::size_t check_triangle_view(const Soup& s)
{
  SCOPED_TRACE(s.name);
  const ST::Adjacency_tables adj(s.triangles, s.points.size());
  const TG g = ST::triangle_adjacency_graph(adj);
  const std::size_t n = s.triangles.size();
  EXPECT_EQ(num_vertices(g), n);

  // Components: Boost.Graph on the view, the tables, and an independent union-find.
  std::vector<std::size_t> cc(num_vertices(g));
  const std::size_t count =
    boost::connected_components(g, boost::make_iterator_property_map(cc.begin(), get(boost::vertex_index, g)));
  std::vector<size_type> table_cc;
  EXPECT_EQ(count, adj.number_of_connected_components(&table_cc));
  EXPECT_EQ(canonical_labels(cc), canonical_labels(table_cc));
  const auto em = edge_map(s.triangles);
  Union_find uf(n);
  std::size_t reference_edges = 0;
  for(const auto& entry : em) {
    const std::size_t k = entry.second.size();
    reference_edges += k * (k - 1) / 2;
    for(std::size_t t : entry.second) uf.unite(t, entry.second.front());
  }
  std::vector<std::size_t> roots(n);
  for(std::size_t t = 0; t < n; ++t) roots[t] = uf.find(t);
  EXPECT_EQ(canonical_labels(cc), canonical_labels(roots));

  // Edges: every graph edge once, in its canonical orientation, with distinct bounded indices.
  EXPECT_EQ(num_edges(g), reference_edges);
  const std::size_t bound = edge_index_upper_bound(g);
  std::vector<bool> seen(bound, false);
  std::size_t listed = 0;
  const auto index = get(boost::edge_index, g);
  for(auto [e, e_end] = edges(g); e != e_end; ++e, ++listed) {
    EXPECT_LT(source(*e, g), target(*e, g));
    const std::size_t id = get(index, *e);
    EXPECT_LT(id, bound);
    if(id < bound) { EXPECT_FALSE(seen[id]); seen[id] = true; }
  }
  EXPECT_EQ(listed, reference_edges);

  // Incidence: out-edges, in-edges and adjacent vertices list the reference neighbours.
  const auto reference = reference_triangle_neighbors(s.triangles);
  for(size_type t = 0; t < n; ++t) {
    std::vector<std::size_t> out, in, adjacent;
    for(auto [e, e_end] = out_edges(t, g); e != e_end; ++e) {
      EXPECT_EQ(source(*e, g), t);
      EXPECT_TRUE(seen[get(index, *e)]);   // the same edge as listed by edges()
      EXPECT_EQ(get(boost::edge_index, g, *e), get(index, *e));
      out.push_back(target(*e, g));
    }
    for(auto [e, e_end] = in_edges(t, g); e != e_end; ++e) {
      EXPECT_EQ(target(*e, g), t);
      in.push_back(source(*e, g));
    }
    for(auto [v, v_end] = adjacent_vertices(t, g); v != v_end; ++v) adjacent.push_back(*v);
    std::sort(out.begin(), out.end());
    std::sort(in.begin(), in.end());
    std::sort(adjacent.begin(), adjacent.end());
    EXPECT_EQ(out, reference[t]);
    EXPECT_EQ(in, reference[t]);
    EXPECT_EQ(adjacent, reference[t]);
    EXPECT_EQ(out_degree(t, g), reference[t].size());
    EXPECT_EQ(in_degree(t, g), reference[t].size());
    EXPECT_EQ(degree(t, g), reference[t].size());
  }
  return count;
}

// Vertex view: degrees, edges, components. `triangle_components` is the count of the triangle view.
void check_vertex_view(const Soup& s, std::size_t triangle_components)
{
  SCOPED_TRACE(s.name);
  const ST::Adjacency_tables adj(s.triangles, s.points.size());
  const VG g = ST::vertex_adjacency_graph(adj);
  const std::size_t nv = s.points.size();
  EXPECT_EQ(num_vertices(g), nv);

  const auto em = edge_map(s.triangles);
  std::vector<std::set<std::size_t>> neighbours(nv);
  for(const auto& entry : em) {
    neighbours[entry.first.first].insert(entry.first.second);
    neighbours[entry.first.second].insert(entry.first.first);
  }
  EXPECT_EQ(num_edges(g), em.size());
  std::size_t listed = 0;
  std::vector<bool> seen(edge_index_upper_bound(g), false);
  for(auto [e, e_end] = edges(g); e != e_end; ++e, ++listed) {
    const std::size_t a = source(*e, g), b = target(*e, g);
    EXPECT_EQ(em.count({std::min(a, b), std::max(a, b)}), 1u);
    const std::size_t id = get(get(boost::edge_index, g), *e);
    ASSERT_LT(id, seen.size());
    EXPECT_FALSE(seen[id]);
    seen[id] = true;
  }
  EXPECT_EQ(listed, em.size());

  for(size_type v = 0; v < nv; ++v) {
    std::vector<std::size_t> out, in, adjacent;
    for(auto [e, e_end] = out_edges(v, g); e != e_end; ++e) {
      EXPECT_EQ(source(*e, g), v);
      EXPECT_TRUE(seen[get(boost::edge_index, g, *e)]);
      out.push_back(target(*e, g));
    }
    for(auto [e, e_end] = in_edges(v, g); e != e_end; ++e) {
      EXPECT_EQ(target(*e, g), v);
      in.push_back(source(*e, g));
    }
    for(auto [w, w_end] = adjacent_vertices(v, g); w != w_end; ++w) adjacent.push_back(*w);
    std::sort(out.begin(), out.end());
    std::sort(in.begin(), in.end());
    std::sort(adjacent.begin(), adjacent.end());
    const std::vector<std::size_t> expected(neighbours[v].begin(), neighbours[v].end());
    EXPECT_EQ(out, expected);   // distinct neighbours, each once
    EXPECT_EQ(in, expected);
    EXPECT_EQ(adjacent, expected);
    EXPECT_EQ(out_degree(v, g), expected.size());
    EXPECT_EQ(degree(v, g), expected.size());
  }

  // Components over the vertices in some triangle, against an independent union-find; they equal
  // the triangle components when no vertex is shared by two triangle components.
  std::vector<std::size_t> cc(nv);
  boost::connected_components(g, boost::make_iterator_property_map(cc.begin(), get(boost::vertex_index, g)));
  std::set<std::size_t> used_components;
  for(size_type v = 0; v < nv; ++v)
    if(degree(v, g) > 0) used_components.insert(cc[v]);
  Union_find uf(nv);
  for(const Face& f : s.triangles) { uf.unite(f[0], f[1]); uf.unite(f[1], f[2]); }
  std::set<std::size_t> reference_components;
  for(std::size_t v = 0; v < nv; ++v)
    if(!neighbours[v].empty()) reference_components.insert(uf.find(v));
  EXPECT_EQ(used_components.size(), reference_components.size());
  std::vector<std::size_t> triangle_cc;
  Union_find tuf(s.triangles.size());
  for(const auto& entry : em)
    for(std::size_t t : entry.second) tuf.unite(t, entry.second.front());
  std::vector<std::size_t> component_of_vertex(nv, std::numeric_limits<std::size_t>::max());
  bool vertex_shared_by_components = false;
  for(std::size_t t = 0; t < s.triangles.size(); ++t)
    for(std::size_t v : s.triangles[t]) {
      const std::size_t c = tuf.find(t);
      if(component_of_vertex[v] == std::numeric_limits<std::size_t>::max()) component_of_vertex[v] = c;
      else if(component_of_vertex[v] != c) vertex_shared_by_components = true;
    }
  if(!vertex_shared_by_components) {
    EXPECT_EQ(used_components.size(), triangle_components);
  }
}

// ---------------------------------------------------------------------------------------------

TEST(AdjacencyGraphs, IssueUsageCompiles)
{
  const Soup s = cube();
  Soup_topology::Adjacency_tables adj(s.triangles, s.points.size());
  Soup_topology::Triangle_adjacency_graph g(adj);
  std::vector<std::size_t> cc(num_vertices(g));
  const std::size_t count =
    boost::connected_components(g, boost::make_iterator_property_map(cc.begin(), get(boost::vertex_index, g)));
  EXPECT_EQ(count, 1u);
  EXPECT_EQ(num_edges(g), 18u);
  EXPECT_EQ(edge_index_upper_bound(g), 36u);
  for(auto [v, v_end] = vertices(g); v != v_end; ++v) EXPECT_EQ(out_degree(*v, g), 3u);
}

TEST(AdjacencyGraphs, CubeViews)
{
  const Soup s = cube();
  EXPECT_EQ(check_triangle_view(s), 1u);
  check_vertex_view(s, 1);
  const ST::Adjacency_tables adj(s.triangles, s.points.size());
  const VG g(adj);
  EXPECT_EQ(num_edges(g), 18u);   // 12 cube edges + 6 face diagonals
}

TEST(AdjacencyGraphs, NonManifoldEdgeIsAClique)
{
  const Soup s = grid_with_fins(4);
  EXPECT_EQ(check_triangle_view(s), 2u);
  check_vertex_view(s, 2);
  const ST::Adjacency_tables adj(s.triangles, s.points.size());
  const TG g(adj);
  // 4 triangles on one edge: 6 graph edges there, and edge indices in 3 layers of 3 n.
  EXPECT_EQ(edge_index_upper_bound(g), 3 * s.triangles.size() * 3);
  std::size_t non_manifold = 0;
  for(auto [e, e_end] = edges(g); e != e_end; ++e)
    if(!ST::is_manifold_edge(*e, g)) {
      ++non_manifold;
      const ST::Adjacency_tables::Edge h = ST::halfedge_in_smaller_triangle(*e, g);
      EXPECT_EQ(h.triangle, source(*e, g));
      EXPECT_TRUE(adj.is_non_manifold_edge(h.triangle, h.index));
    }
  EXPECT_EQ(non_manifold, 6u);
}

TEST(AdjacencyGraphs, FilteredGraphWalksManifoldEdgesOnly)
{
  const fs::path file = fs::path(SOUP_TOPOLOGY_DATA_DIR) / "cgal_repair/data_stitching/nm_cubes.off";
  Soup s;
  ASSERT_TRUE(read_soup(file, s));
  const ST::Adjacency_tables adj(s.triangles, s.points.size());
  const TG g(adj);
  struct Manifold_only
  {
    const TG* g = nullptr;
    bool operator()(const TG::Edge& e) const { return ST::is_manifold_edge(e, *g); }
  };
  const boost::filtered_graph<TG, Manifold_only> fg(g, Manifold_only{&g});
  std::vector<std::size_t> cc(num_vertices(g));
  EXPECT_EQ(boost::connected_components(g, boost::make_iterator_property_map(cc.begin(), get(boost::vertex_index, g))), 1u);
  EXPECT_EQ(boost::connected_components(fg, boost::make_iterator_property_map(cc.begin(), get(boost::vertex_index, g))), 2u);
}

// A vertex in 100,000 triangles whose edges are non-manifold: its out-edges in the vertex view
// are found by scanning the short lists of its neighbours, not its own list once per edge.
TEST(AdjacencyGraphs, OutEdgesOfAHighDegreeVertexScanLinearly)
{
  const std::size_t m = 50000;   // centre 0, ring 1..m, fins m+1..2m
  std::vector<Face> triangles;
  for(std::size_t j = 1; j < m; ++j) triangles.push_back({0, j, j + 1});
  for(std::size_t j = 1; j <= m; ++j) triangles.push_back({0, j, m + j});
  const ST::Adjacency_tables adj(triangles, 2 * m + 1);
  ASSERT_EQ(adj.degree(0), 2 * m - 1);
  ASSERT_TRUE(adj.is_non_manifold_edge(0, 2));   // edge (2, 0) of triangle (0, 1, 2) is in 3 triangles
  const VG g(adj);
  graph_view_scanned_triangles = 0;
  std::size_t count = 0;
  for(auto [e, e_end] = out_edges(0, g); e != e_end; ++e) {
    EXPECT_EQ(source(*e, g), 0u);
    ++count;
  }
  EXPECT_EQ(count, 2 * m);
  EXPECT_EQ(out_degree(0, g), 2 * m);
  // Two scans per non-manifold edge at 0 (out_edges and out_degree), of at most 3 triangles.
  EXPECT_LE(graph_view_scanned_triangles, 2 * 4 * 3 * m);
}

// A triangle adjacent to 100,000 others across one edge whose first vertex is in 400,000 more
// triangles: its out-edges are found by scanning the list of the other end once.
TEST(AdjacencyGraphs, OutEdgesOfAHighDegreeTriangleScanLinearly)
{
  const std::size_t k = 100001;   // pages (0, 1, p) on the spine (0, 1)
  const std::size_t fan = 400000; // fan (0, q, q + 1) away from the spine
  std::vector<Face> triangles;
  for(std::size_t p = 2; p < k + 2; ++p) triangles.push_back({0, 1, p});
  for(std::size_t q = k + 2; q < k + 2 + fan; ++q) triangles.push_back({0, q, q + 1});
  const ST::Adjacency_tables adj(triangles, k + 3 + fan);
  const TG g(adj);
  const size_type t = static_cast<size_type>(k / 2);
  graph_view_scanned_triangles = 0;
  std::size_t count = 0;
  for(auto [e, e_end] = out_edges(t, g); e != e_end; ++e) {
    EXPECT_EQ(source(*e, g), t);
    EXPECT_FALSE(ST::is_manifold_edge(*e, g));
    ++count;
  }
  EXPECT_EQ(count, k - 1);
  EXPECT_LE(graph_view_scanned_triangles, adj.degree(1));
  graph_view_scanned_triangles = 0;
  EXPECT_EQ(out_degree(t, g), k - 1);
  EXPECT_LE(graph_view_scanned_triangles, adj.degree(1));
}

TEST(AdjacencyGraphs, EmptySoup)
{
  const ST::Adjacency_tables adj(std::vector<Face>(), 3);
  const TG tg(adj);
  const VG vg(adj);
  EXPECT_EQ(num_vertices(tg), 0u);
  EXPECT_EQ(num_edges(tg), 0u);
  EXPECT_TRUE(edges(tg).first == edges(tg).second);
  EXPECT_EQ(num_vertices(vg), 3u);
  EXPECT_EQ(num_edges(vg), 0u);
  EXPECT_TRUE(edges(vg).first == edges(vg).second);
  EXPECT_EQ(degree(1, vg), 0u);
}

TEST(AdjacencyGraphs, BreadthFirstSearchMatchesReference)
{
  for(const Soup& s : {cube(), grid_with_fins(6)}) {
    SCOPED_TRACE(s.name);
    const ST::Adjacency_tables adj(s.triangles, s.points.size());
    const TG g(adj);
    const std::size_t n = num_vertices(g);
    const std::size_t unreached = std::numeric_limits<std::size_t>::max();
    std::vector<std::size_t> hops(n, unreached);
    hops[0] = 0;
    boost::breadth_first_search(
      g, size_type(0),
      boost::visitor(boost::make_bfs_visitor(boost::record_distances(
        boost::make_iterator_property_map(hops.begin(), get(boost::vertex_index, g)), boost::on_tree_edge()))));
    // Reference: a plain BFS over the neighbour lists computed from the triangle list.
    const auto nb = reference_triangle_neighbors(s.triangles);
    std::vector<std::size_t> expected(n, unreached);
    std::vector<std::size_t> queue{0};
    expected[0] = 0;
    for(std::size_t k = 0; k < queue.size(); ++k)
      for(std::size_t u : nb[queue[k]])
        if(expected[u] == unreached) { expected[u] = expected[queue[k]] + 1; queue.push_back(u); }
    EXPECT_EQ(hops, expected);
  }
}

// Dijkstra with the distance between triangle centroids as edge weight, from every source,
// against Floyd-Warshall on the neighbour lists computed from the triangle list.
TEST(AdjacencyGraphs, DijkstraMatchesFloydWarshall)
{
  for(const Soup& s : {cube(), grid_with_fins(5)}) {
    SCOPED_TRACE(s.name);
    const ST::Adjacency_tables adj(s.triangles, s.points.size());
    const TG g(adj);
    const std::size_t n = num_vertices(g);
    const auto weight = boost::make_function_property_map<TG::Edge, double>([&](const TG::Edge& e) {
      return std::sqrt(CGAL::to_double(CGAL::squared_distance(centroid(s, source(e, g)), centroid(s, target(e, g)))));
    });
    const double inf = std::numeric_limits<double>::infinity();
    std::vector<std::vector<double>> floyd(n, std::vector<double>(n, inf));
    const auto nb = reference_triangle_neighbors(s.triangles);
    for(std::size_t a = 0; a < n; ++a) {
      floyd[a][a] = 0;
      for(std::size_t b : nb[a])
        floyd[a][b] = std::sqrt(CGAL::to_double(CGAL::squared_distance(centroid(s, a), centroid(s, b))));
    }
    for(std::size_t k = 0; k < n; ++k)
      for(std::size_t a = 0; a < n; ++a)
        for(std::size_t b = 0; b < n; ++b) floyd[a][b] = std::min(floyd[a][b], floyd[a][k] + floyd[k][b]);

    for(size_type src = 0; src < n; ++src) {
      std::vector<double> distance(n);
      std::vector<size_type> predecessor(n);
      boost::dijkstra_shortest_paths(
        g, src,
        boost::weight_map(weight)
          .distance_map(boost::make_iterator_property_map(distance.begin(), get(boost::vertex_index, g)))
          .predecessor_map(boost::make_iterator_property_map(predecessor.begin(), get(boost::vertex_index, g))));
      for(std::size_t b = 0; b < n; ++b) {
        if(floyd[src][b] == inf) {
          EXPECT_EQ(distance[b], (std::numeric_limits<double>::max)());
        } else {
          EXPECT_NEAR(distance[b], floyd[src][b], 1e-9 * (1 + floyd[src][b]));
        }
      }
    }
  }
}

TEST(AdjacencyGraphs, RealMeshes)
{
  std::size_t checked = 0, skipped = 0;
  std::string skipped_names;
  for(const fs::path& file : data_files()) {
    Soup s;
    bool ok = false;
    try {
      ok = read_soup(file, s);
    } catch(const std::exception& e) {
      ADD_FAILURE() << file << ": " << e.what();
      continue;
    }
    if(!ok) { ++skipped; skipped_names += " " + file.filename().string(); continue; }
    const std::size_t components = check_triangle_view(s);
    check_vertex_view(s, components);
    ++checked;
  }
  std::cout << "[ checked ] " << checked << " real meshes; skipped " << skipped << ":" << skipped_names << "\n";
  EXPECT_GT(checked, 30u);
}

} // namespace

} // namespace Adjacency_graphs_test
