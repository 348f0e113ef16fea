// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// boost::connected_components on the zero-copy triangle adjacency view, against the same on
// CGAL::Dual<CGAL::Surface_mesh> and on a boost::adjacency_list copy (its construction
// included), on about 1.2M triangles: the bunny subdivided 1-to-4 twice, as an indexed mesh.
//
// Run: Adjacency_graphs_benchmark [--benchmark_filter=...]; data from SOUP_TOPOLOGY_DATA_DIR/clean.

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/IO/read_triangle_soup.h>
#include <Soup_topology/Triangle_adjacency_graph.h>
#include <Soup_topology/Vertex_adjacency_graph.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/Dual.h>

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/connected_components.hpp>
#include <boost/graph/filtered_graph.hpp>

#include <benchmark/benchmark.h>

#include "../test/test_utilities.h"

#include <array>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace ST = Soup_topology;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Face = std::array<std::size_t, 3>;
using Mesh = CGAL::Surface_mesh<Point>;
using Dual = CGAL::Dual<Mesh>;

namespace {

// Splits every triangle into 4 with its edge midpoints (midpoints shared between neighbours).
void subdivide(std::vector<Point>& points, std::vector<Face>& triangles)
{
  std::unordered_map<std::uint64_t, std::size_t> midpoint;
  midpoint.reserve(2 * triangles.size());
  auto mid = [&](std::size_t a, std::size_t b) {
    const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::uint64_t(std::max(a, b));
    const auto [it, inserted] = midpoint.emplace(key, points.size());
    if(inserted) points.push_back(CGAL::midpoint(points[a], points[b]));
    return it->second;
  };
  std::vector<Face> result;
  result.reserve(4 * triangles.size());
  for(const Face& f : triangles) {
    const std::size_t m0 = mid(f[0], f[1]), m1 = mid(f[1], f[2]), m2 = mid(f[2], f[0]);
    result.push_back({f[0], m0, m2});
    result.push_back({m0, f[1], m1});
    result.push_back({m2, m1, f[2]});
    result.push_back({m0, m1, m2});
  }
  triangles.swap(result);
}

struct Data
{
  std::vector<Point> points;
  std::vector<Face> triangles;
  ST::Adjacency_tables tables;
  Mesh mesh;
  bool closed = false;
};

const Data& data()
{
  static const Data d = [] {
    Data r;
    ST::IO::read_triangle_soup(soup_test::data_file("clean/bunny00.off.xz"), r.points, r.triangles);
    subdivide(r.points, r.triangles);
    subdivide(r.points, r.triangles);
    r.tables = ST::Adjacency_tables(r.triangles, r.points.size());
    std::vector<Point> pts = r.points;
    std::vector<Face> tris = r.triangles;
    namespace PMP = CGAL::Polygon_mesh_processing;
    if(!PMP::is_polygon_soup_a_polygon_mesh(tris)) PMP::orient_polygon_soup(pts, tris);
    PMP::polygon_soup_to_polygon_mesh(pts, tris, r.mesh);
    r.closed = CGAL::is_closed(r.mesh);
    std::cout << "bunny00 subdivided twice: " << r.triangles.size() << " triangles, " << r.points.size()
              << " vertices; Surface_mesh: " << r.mesh.number_of_faces() << " faces, "
              << (r.closed ? "closed" : "with borders") << "\n";
    return r;
  }();
  return d;
}

// The dual edges that cross a border edge lead to the null face: CGAL's dual example filters them.
struct Not_border
{
  const Mesh* mesh = nullptr;
  bool operator()(boost::graph_traits<Dual>::edge_descriptor e) const { return !CGAL::is_border(e, *mesh); }
};

void BM_triangle_view(benchmark::State& state)
{
  const Data& d = data();
  std::vector<std::size_t> cc(d.triangles.size());
  for(auto _ : state) {
    const auto g = ST::triangle_adjacency_graph(d.tables);
    const std::size_t n =
      boost::connected_components(g, boost::make_iterator_property_map(cc.begin(), get(boost::vertex_index, g)));
    benchmark::DoNotOptimize(n);
  }
  state.counters["triangles"] = double(d.triangles.size());
}

void BM_CGAL_Dual_Surface_mesh(benchmark::State& state)
{
  const Data& d = data();
  const Dual dual(d.mesh);
  const boost::filtered_graph<Dual, Not_border> finite_dual(dual, Not_border{&d.mesh});
  const auto face_index = get(boost::face_index, d.mesh);
  std::vector<std::size_t> cc(d.mesh.number_of_faces());
  for(auto _ : state) {
    const std::size_t n = boost::connected_components(finite_dual, boost::make_iterator_property_map(cc.begin(), face_index),
                                                      boost::vertex_index_map(face_index));
    benchmark::DoNotOptimize(n);
  }
}

void BM_adjacency_list_copy(benchmark::State& state)
{
  using Graph = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS>;
  const Data& d = data();
  std::vector<std::size_t> cc(d.triangles.size());
  std::vector<std::pair<std::size_t, std::size_t>> edge_list;
  for(auto _ : state) {
    // The copy: every shared edge once, read from the tables, then the adjacency_list.
    edge_list.clear();
    const ST::Adjacency_tables& a = d.tables;
    for(ST::Adjacency_tables::size_type t = 0; t < a.number_of_triangles(); ++t)
      for(int i = 0; i < 3; ++i) {
        const ST::Adjacency_tables::size_type u = a.neighbor(t, i);
        if(u < ST::Adjacency_tables::non_manifold_edge && u > t) edge_list.emplace_back(t, u);
      }
    const Graph g(edge_list.begin(), edge_list.end(), a.number_of_triangles());
    const std::size_t n = boost::connected_components(g, cc.data());
    benchmark::DoNotOptimize(n);
  }
}

void BM_adjacency_list_without_copy(benchmark::State& state)
{
  using Graph = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS>;
  const Data& d = data();
  std::vector<std::pair<std::size_t, std::size_t>> edge_list;
  const auto view = ST::triangle_adjacency_graph(d.tables);
  for(auto [e, end] = edges(view); e != end; ++e) edge_list.emplace_back(source(*e, view), target(*e, view));
  const Graph g(edge_list.begin(), edge_list.end(), d.tables.number_of_triangles());
  std::vector<std::size_t> cc(d.triangles.size());
  for(auto _ : state) {
    const std::size_t n = boost::connected_components(g, cc.data());
    benchmark::DoNotOptimize(n);
  }
}

void BM_tables_number_of_connected_components(benchmark::State& state)
{
  const Data& d = data();
  std::vector<ST::Adjacency_tables::size_type> cc;
  for(auto _ : state) benchmark::DoNotOptimize(d.tables.number_of_connected_components(&cc));
}

void BM_vertex_view(benchmark::State& state)
{
  const Data& d = data();
  std::vector<std::size_t> cc(d.points.size());
  for(auto _ : state) {
    const auto g = ST::vertex_adjacency_graph(d.tables);
    const std::size_t n =
      boost::connected_components(g, boost::make_iterator_property_map(cc.begin(), get(boost::vertex_index, g)));
    benchmark::DoNotOptimize(n);
  }
}

void BM_build_tables(benchmark::State& state)
{
  const Data& d = data();
  for(auto _ : state) {
    const ST::Adjacency_tables tables(d.triangles, d.points.size());
    benchmark::DoNotOptimize(tables.number_of_triangles());
  }
}

} // namespace

BENCHMARK(BM_triangle_view)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CGAL_Dual_Surface_mesh)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_adjacency_list_copy)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_adjacency_list_without_copy)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_tables_number_of_connected_components)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_vertex_view)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_build_tables)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
