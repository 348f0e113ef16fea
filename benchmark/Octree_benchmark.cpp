// Copyright (c) 2024 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Soup_topology::Octree against CGAL::Octree (Orthtree), CGAL::Kd_tree and brute force, on
// 1M points of a subdivided bunny and on 1M uniform random points: build time, nearest vertex
// within a radius, all vertices within a radius, all vertices near a segment. On clustered
// near-duplicates (every vertex of a real mesh replaced by 20 close copies, as welding sees them):
// the build, the radius query at every point against CGAL::Kd_tree, and the self-join.
//
// Run: Octree_benchmark [--benchmark_filter=...]; data from SOUP_TOPOLOGY_DATA_DIR/clean.

#include <Soup_topology/Octree.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Fuzzy_iso_box.h>
#include <CGAL/Fuzzy_sphere.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Kd_tree.h>
#include <CGAL/Octree.h>
#include <CGAL/Search_traits_3.h>
#include <CGAL/Search_traits_adapter.h>
#include <CGAL/property_map.h>

#include <benchmark/benchmark.h>

#include "../test/test_utilities.h"
#include "benchmark_utilities.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <iterator>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace ST = Soup_topology;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using FT = K::FT;

namespace {

using soup_benchmark::diagonal;

constexpr std::size_t number_of_points = 1000000;
constexpr std::size_t number_of_queries = 20000;

struct Data_set
{
  std::string name;
  std::vector<Point> points;
  std::vector<Point> queries;                        // near the points
  std::vector<std::pair<Point, Point>> segments;     // short segments (mesh edges)
  double radius = 0;
};

// splits every triangle into 4 with its edge midpoints (shared midpoints merged)
void subdivide(std::vector<Point>& points, std::vector<std::array<std::size_t, 3>>& triangles)
{
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> midpoint;
  auto mid = [&](std::size_t a, std::size_t b) {
    const std::pair<std::size_t, std::size_t> key(std::min(a, b), std::max(a, b));
    auto it = midpoint.find(key);
    if(it != midpoint.end())
      return it->second;
    points.push_back(CGAL::midpoint(points[a], points[b]));
    midpoint.emplace(key, points.size() - 1);
    return points.size() - 1;
  };
  std::vector<std::array<std::size_t, 3>> out;
  out.reserve(4 * triangles.size());
  for(const auto& t : triangles)
  {
    const std::size_t m01 = mid(t[0], t[1]), m12 = mid(t[1], t[2]), m20 = mid(t[2], t[0]);
    out.push_back({t[0], m01, m20});
    out.push_back({t[1], m12, m01});
    out.push_back({t[2], m20, m12});
    out.push_back({m01, m12, m20});
  }
  triangles.swap(out);
}

// clean/bunny00.off of the shared data folder (the program stops when it cannot be read)
void read_bunny(std::vector<Point>& points, std::vector<std::array<std::size_t, 3>>& triangles)
{
  const std::string off = soup_test::data_file("clean/bunny00.off.xz");
  if(!CGAL::IO::read_polygon_soup(off, points, triangles))
  {
    std::cerr << "cannot read " << off << "\n";
    std::exit(EXIT_FAILURE);
  }
}

void make_queries(Data_set& d, std::mt19937& gen)
{
  std::uniform_real_distribution<double> u(-1, 1);
  for(std::size_t i = 0; i < number_of_queries; ++i)
  {
    const Point& p = d.points[gen() % d.points.size()];
    d.queries.emplace_back(p.x() + d.radius * u(gen), p.y() + d.radius * u(gen),
                           p.z() + d.radius * u(gen));
  }
}

const Data_set& bunny()
{
  static const Data_set data = [] {
    Data_set d;
    d.name = "bunny";
    std::vector<Point> pts;
    std::vector<std::array<std::size_t, 3>> tris;
    read_bunny(pts, tris);
    // twice gives ~0.6M vertices, a third time ~2.4M: keep 1M of those, at random
    subdivide(pts, tris);
    subdivide(pts, tris);
    std::mt19937 gen(1);
    std::uniform_int_distribution<std::size_t> pick_tri(0, tris.size() - 1);
    for(std::size_t i = 0; i < number_of_queries; ++i)
    {
      const auto& t = tris[pick_tri(gen)];
      const int e = int(gen() % 3);
      d.segments.emplace_back(pts[t[e]], pts[t[(e + 1) % 3]]);
    }
    subdivide(pts, tris);
    std::shuffle(pts.begin(), pts.end(), gen);
    pts.resize(std::min(pts.size(), number_of_points));
    d.points = std::move(pts);
    d.radius = 1e-3 * diagonal(d.points);
    make_queries(d, gen);
    return d;
  }();
  return data;
}

const Data_set& uniform()
{
  static const Data_set data = [] {
    Data_set d;
    d.name = "uniform";
    std::mt19937 gen(2);
    std::uniform_real_distribution<double> u(0, 1);
    for(std::size_t i = 0; i < number_of_points; ++i)
      d.points.emplace_back(u(gen), u(gen), u(gen));
    d.radius = 1e-3 * diagonal(d.points);
    // segments about two point spacings long
    const double l = 2.0 / std::cbrt(double(number_of_points));
    std::uniform_real_distribution<double> v(-l, l);
    for(std::size_t i = 0; i < number_of_queries; ++i)
    {
      const Point a(u(gen), u(gen), u(gen));
      d.segments.emplace_back(a, Point(a.x() + v(gen), a.y() + v(gen), a.z() + v(gen)));
    }
    make_queries(d, gen);
    return d;
  }();
  return data;
}

// the 37,706 vertices of clean/bunny00.off, each replaced by 20 copies moved by up to 5e-7 of the
// bounding-box diagonal, in random order (754,120 points); radius 2e-6 of the diagonal, so that
// every point finds its whole cluster; the queries are the points themselves, in input order
const Data_set& clustered()
{
  static const Data_set data = [] {
    Data_set d;
    d.name = "clustered";
    std::vector<Point> pts;
    std::vector<std::array<std::size_t, 3>> tris;
    read_bunny(pts, tris);
    const double diag = diagonal(pts);
    std::mt19937 gen(3);
    std::uniform_real_distribution<double> u(-1, 1);
    const double move = 5e-7 * diag / std::sqrt(3.0);
    for(const Point& p : pts)
      for(int c = 0; c < 20; ++c)
        d.points.emplace_back(p.x() + move * u(gen), p.y() + move * u(gen), p.z() + move * u(gen));
    std::shuffle(d.points.begin(), d.points.end(), gen);
    d.radius = 2e-6 * diag;
    d.queries = d.points;
    return d;
  }();
  return data;
}

const Data_set& data_set(const benchmark::State& state)
{
  return state.range(0) == 0 ? bunny() : (state.range(0) == 1 ? uniform() : clustered());
}

// --- competitors ----------------------------------------------------------------------------

using Orthtree = CGAL::Octree<K, std::vector<Point>>;

using Index_map = CGAL::Pointer_property_map<Point>::const_type;
using Kd_traits = CGAL::Search_traits_adapter<std::size_t, Index_map, CGAL::Search_traits_3<K>>;
using Kd_tree = CGAL::Kd_tree<Kd_traits>;
using Kd_sphere = CGAL::Fuzzy_sphere<Kd_traits>;
using Kd_box = CGAL::Fuzzy_iso_box<Kd_traits>;

struct Kd
{
  explicit Kd(const std::vector<Point>& pts)
    : tree(boost::counting_iterator<std::size_t>(0), boost::counting_iterator<std::size_t>(pts.size()),
           Kd_tree::Splitter(), Kd_traits(CGAL::make_property_map(pts)))
  {
    tree.build();
  }
  Kd_tree tree;
};

// --- build ----------------------------------------------------------------------------------

void BM_build_soup_octree(benchmark::State& state)
{
  const Data_set& d = data_set(state);
  for(auto _ : state)
  {
    ST::Octree<K> tree(d.points);
    benchmark::DoNotOptimize(tree.number_of_nodes());
  }
  state.SetLabel(d.name);
  state.SetItemsProcessed(std::int64_t(state.iterations() * d.points.size()));
}

void BM_build_cgal_orthtree(benchmark::State& state)
{
  const Data_set& d = data_set(state);
  for(auto _ : state)
  {
    state.PauseTiming();
    std::vector<Point> copy = d.points; // Orthtree reorders its range
    state.ResumeTiming();
    Orthtree tree(copy);
    tree.refine(10, 20);
    benchmark::DoNotOptimize(tree.root());
  }
  state.SetLabel(d.name);
  state.SetItemsProcessed(std::int64_t(state.iterations() * d.points.size()));
}

void BM_build_cgal_kd_tree(benchmark::State& state)
{
  const Data_set& d = data_set(state);
  for(auto _ : state)
  {
    Kd kd(d.points);
    benchmark::DoNotOptimize(kd.tree.size());
  }
  state.SetLabel(d.name);
  state.SetItemsProcessed(std::int64_t(state.iterations() * d.points.size()));
}

// --- nearest vertex within the radius -------------------------------------------------------

void BM_nearest_soup_octree(benchmark::State& state)
{
  const Data_set& d = data_set(state);
  const ST::Octree<K> tree(d.points);
  std::size_t i = 0, found = 0;
  for(auto _ : state)
  {
    const std::optional<std::size_t> v = tree.nearest_vertex(d.queries[i++ % d.queries.size()], d.radius);
    found += v.has_value();
    benchmark::DoNotOptimize(v);
  }
  state.SetLabel(d.name);
  state.counters["found"] = double(found) / double(state.iterations());
  state.SetItemsProcessed(std::int64_t(state.iterations()));
}

void BM_nearest_cgal_orthtree(benchmark::State& state)
{
  const Data_set& d = data_set(state);
  std::vector<Point> copy = d.points;
  Orthtree tree(copy);
  tree.refine(10, 20);
  const FT r2 = d.radius * d.radius;
  std::vector<Point> out;
  std::size_t i = 0, found = 0;
  for(auto _ : state)
  {
    out.clear();
    // the nearest neighbour, then the radius (the sphere overload of nearest_neighbors crashes
    // in CGAL 5.5.1 with its default k)
    const Point& q = d.queries[i++ % d.queries.size()];
    tree.nearest_neighbors(q, 1, std::back_inserter(out));
    found += !out.empty() && CGAL::compare_squared_distance(q, out[0], r2) != CGAL::LARGER;
    benchmark::DoNotOptimize(out.data());
  }
  state.SetLabel(d.name);
  state.counters["found"] = double(found) / double(state.iterations());
  state.SetItemsProcessed(std::int64_t(state.iterations()));
}

void BM_nearest_cgal_kd_tree(benchmark::State& state)
{
  const Data_set& d = data_set(state);
  const Kd kd(d.points);
  std::vector<std::size_t> out;
  std::size_t i = 0, found = 0;
  for(auto _ : state)
  {
    out.clear();
    const Point& q = d.queries[i++ % d.queries.size()];
    kd.tree.search(std::back_inserter(out), Kd_sphere(q, d.radius, 0., kd.tree.traits()));
    std::optional<std::size_t> best;
    for(std::size_t j : out)
      if(!best || CGAL::compare_distance_to_point(q, d.points[j], d.points[*best]) == CGAL::SMALLER ||
         (j < *best && CGAL::compare_distance_to_point(q, d.points[j], d.points[*best]) == CGAL::EQUAL))
        best = j;
    found += best.has_value();
    benchmark::DoNotOptimize(best);
  }
  state.SetLabel(d.name);
  state.counters["found"] = double(found) / double(state.iterations());
  state.SetItemsProcessed(std::int64_t(state.iterations()));
}

void BM_nearest_brute_force(benchmark::State& state)
{
  const Data_set& d = data_set(state);
  const FT r2 = d.radius * d.radius;
  std::size_t i = 0, found = 0;
  for(auto _ : state)
  {
    const Point& q = d.queries[i++ % d.queries.size()];
    std::optional<std::size_t> best;
    for(std::size_t j = 0; j < d.points.size(); ++j)
      if(CGAL::compare_squared_distance(q, d.points[j], r2) != CGAL::LARGER &&
         (!best || CGAL::compare_distance_to_point(q, d.points[j], d.points[*best]) == CGAL::SMALLER))
        best = j;
    found += best.has_value();
    benchmark::DoNotOptimize(best);
  }
  state.SetLabel(d.name);
  state.counters["found"] = double(found) / double(state.iterations());
  state.SetItemsProcessed(std::int64_t(state.iterations()));
}

// --- every vertex within the radius ---------------------------------------------------------

void BM_near_point_soup_octree(benchmark::State& state)
{
  const Data_set& d = data_set(state);
  const ST::Octree<K> tree(d.points);
  std::vector<std::size_t> out;
  std::size_t i = 0, found = 0;
  for(auto _ : state)
  {
    out.clear();
    tree.vertices_near_point(d.queries[i++ % d.queries.size()], d.radius, std::back_inserter(out));
    found += out.size();
  }
  state.SetLabel(d.name);
  state.counters["found"] = double(found) / double(state.iterations());
  state.SetItemsProcessed(std::int64_t(state.iterations()));
}

void BM_near_point_cgal_kd_tree(benchmark::State& state)
{
  const Data_set& d = data_set(state);
  const Kd kd(d.points);
  std::vector<std::size_t> out;
  std::size_t i = 0, found = 0;
  for(auto _ : state)
  {
    out.clear();
    kd.tree.search(std::back_inserter(out),
                   Kd_sphere(d.queries[i++ % d.queries.size()], d.radius, 0., kd.tree.traits()));
    std::sort(out.begin(), out.end());
    found += out.size();
  }
  state.SetLabel(d.name);
  state.counters["found"] = double(found) / double(state.iterations());
  state.SetItemsProcessed(std::int64_t(state.iterations()));
}

// --- every vertex near a segment ------------------------------------------------------------

void segment_soup_octree(benchmark::State& state, ST::Segment_query_strategy strategy)
{
  const Data_set& d = data_set(state);
  const ST::Octree<K> tree(d.points);
  std::vector<std::size_t> out;
  std::size_t i = 0, found = 0;
  for(auto _ : state)
  {
    out.clear();
    const auto& s = d.segments[i++ % d.segments.size()];
    tree.vertices_near_segment(s.first, s.second, d.radius, std::back_inserter(out), strategy);
    found += out.size();
  }
  state.SetLabel(d.name);
  state.counters["found"] = double(found) / double(state.iterations());
  state.SetItemsProcessed(std::int64_t(state.iterations()));
}

void BM_segment_soup_octree_culling(benchmark::State& state)
{
  segment_soup_octree(state, ST::Segment_query_strategy::NEIGHBORHOOD_CULLING);
}

void BM_segment_soup_octree_index_box(benchmark::State& state)
{
  segment_soup_octree(state, ST::Segment_query_strategy::INDEX_SPACE_BOX);
}

CGAL::Bbox_3 grown_box(const std::pair<Point, Point>& s, double r)
{
  const CGAL::Bbox_3 b = s.first.bbox() + s.second.bbox();
  return CGAL::Bbox_3(b.xmin() - r, b.ymin() - r, b.zmin() - r, b.xmax() + r, b.ymax() + r, b.zmax() + r);
}

void BM_segment_cgal_kd_tree(benchmark::State& state)
{
  const Data_set& d = data_set(state);
  const Kd kd(d.points);
  const FT r2 = d.radius * d.radius;
  std::vector<std::size_t> out;
  std::size_t i = 0, found = 0;
  for(auto _ : state)
  {
    out.clear();
    const auto& s = d.segments[i++ % d.segments.size()];
    const CGAL::Bbox_3 b = grown_box(s, d.radius);
    // candidates in the box of the segment grown by the radius, then the exact test
    kd.tree.search(std::back_inserter(out),
                   Kd_box(Point(b.xmin(), b.ymin(), b.zmin()), Point(b.xmax(), b.ymax(), b.zmax()), 0.,
                          kd.tree.traits()));
    const K::Segment_3 seg(s.first, s.second);
    out.erase(std::remove_if(out.begin(), out.end(),
                             [&](std::size_t j) {
                               return K::Compare_squared_distance_3()(d.points[j], seg, r2) == CGAL::LARGER;
                             }),
              out.end());
    std::sort(out.begin(), out.end());
    found += out.size();
  }
  state.SetLabel(d.name);
  state.counters["found"] = double(found) / double(state.iterations());
  state.SetItemsProcessed(std::int64_t(state.iterations()));
}

void BM_segment_cgal_orthtree(benchmark::State& state)
{
  const Data_set& d = data_set(state);
  std::vector<Point> copy = d.points;
  Orthtree tree(copy);
  tree.refine(10, 20);
  const FT r2 = d.radius * d.radius;
  std::vector<Orthtree::Node> nodes;
  std::size_t i = 0, found = 0;
  for(auto _ : state)
  {
    nodes.clear();
    const auto& s = d.segments[i++ % d.segments.size()];
    const CGAL::Bbox_3 b = grown_box(s, d.radius);
    tree.intersected_nodes(K::Iso_cuboid_3(b), std::back_inserter(nodes));
    const K::Segment_3 seg(s.first, s.second);
    std::size_t n = 0;
    for(const Orthtree::Node& node : nodes)
      for(const Point& p : node)
        n += K::Compare_squared_distance_3()(p, seg, r2) != CGAL::LARGER;
    found += n;
  }
  state.SetLabel(d.name);
  state.counters["found"] = double(found) / double(state.iterations());
  state.SetItemsProcessed(std::int64_t(state.iterations()));
}

void BM_segment_brute_force(benchmark::State& state)
{
  const Data_set& d = data_set(state);
  const FT r2 = d.radius * d.radius;
  std::size_t i = 0, found = 0;
  for(auto _ : state)
  {
    const auto& s = d.segments[i++ % d.segments.size()];
    const K::Segment_3 seg(s.first, s.second);
    for(const Point& p : d.points)
      found += K::Compare_squared_distance_3()(p, seg, r2) != CGAL::LARGER;
  }
  state.SetLabel(d.name);
  state.counters["found"] = double(found) / double(state.iterations());
  state.SetItemsProcessed(std::int64_t(state.iterations()));
}

// --- every point of the clustered set: radius queries against the self-join --------------------

void BM_every_point_soup_octree(benchmark::State& state)
{
  const Data_set& d = data_set(state);
  const ST::Octree<K> tree(d.points);
  std::vector<std::size_t> out;
  std::size_t found = 0;
  for(auto _ : state)
    for(const Point& q : d.queries)
    {
      out.clear();
      tree.vertices_near_point(q, d.radius, std::back_inserter(out));
      found += out.size();
    }
  state.SetLabel(d.name);
  state.counters["found"] = double(found) / double(state.iterations());
  state.SetItemsProcessed(std::int64_t(state.iterations() * d.queries.size()));
}

void BM_every_point_cgal_kd_tree(benchmark::State& state)
{
  const Data_set& d = data_set(state);
  const Kd kd(d.points);
  std::vector<std::size_t> out;
  std::size_t found = 0;
  for(auto _ : state)
    for(const Point& q : d.queries)
    {
      out.clear();
      kd.tree.search(std::back_inserter(out), Kd_sphere(q, d.radius, 0., kd.tree.traits()));
      std::sort(out.begin(), out.end());
      found += out.size();
    }
  state.SetLabel(d.name);
  state.counters["found"] = double(found) / double(state.iterations());
  state.SetItemsProcessed(std::int64_t(state.iterations() * d.queries.size()));
}

void BM_self_join_soup_octree(benchmark::State& state)
{
  const Data_set& d = data_set(state);
  const ST::Octree<K> tree(d.points);
  std::size_t found = 0;
  for(auto _ : state)
    tree.for_each_neighborhood(FT(d.radius), [&](std::size_t, const std::vector<std::size_t>& near) {
      found += near.size();
    });
  state.SetLabel(d.name);
  state.counters["found"] = double(found) / double(state.iterations());
  state.SetItemsProcessed(std::int64_t(state.iterations() * d.points.size()));
}

} // namespace

// 0 = subdivided bunny, 1 = uniform
BENCHMARK(BM_build_soup_octree)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->Iterations(5);
BENCHMARK(BM_build_cgal_orthtree)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_build_cgal_kd_tree)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_nearest_soup_octree)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_nearest_cgal_orthtree)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_nearest_cgal_kd_tree)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_nearest_brute_force)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond)->Iterations(50);
BENCHMARK(BM_near_point_soup_octree)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_near_point_cgal_kd_tree)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_segment_soup_octree_culling)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_segment_soup_octree_index_box)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_segment_cgal_orthtree)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_segment_cgal_kd_tree)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_segment_brute_force)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond)->Iterations(50);

// 2 = clustered near-duplicates; one iteration queries every point
BENCHMARK(BM_every_point_soup_octree)->Arg(2)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_every_point_cgal_kd_tree)->Arg(2)->Unit(benchmark::kMillisecond)->Iterations(3);
BENCHMARK(BM_self_join_soup_octree)->Arg(2)->Unit(benchmark::kMillisecond)->Iterations(3);

BENCHMARK_MAIN();
