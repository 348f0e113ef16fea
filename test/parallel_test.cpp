// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Determinism of the parallel code: every function that takes a ConcurrencyTag gives, with
// CGAL::Parallel_if_available_tag on 1, 2, 3 and 8 threads (8 oversubscribes the machines the
// tests run on), exactly the output of CGAL::Sequential_tag: the points bit for bit, the triangles
// and their order, the reports and the visitor's calls. Built without TBB the parallel tag is the
// sequential one and the tests compare the sequential code with itself.
//
// This program: the exact weld, the tables, the pipeline, the robustness soups and the checks of
// the input; parallel_other_steps_test.cpp has the rest. The two programs instantiate
// different parts of the package, so that they compile in about the same time on two cores.

#include "parallel_test_utilities.h"

#include <atomic>
#include <chrono>
#include <deque>
#include <numeric>
#include <stdexcept>
#include <thread>
#include <utility>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

namespace {

// --- index_triangles and the exact weld ----------------------------------------------------------

class ParallelRealMesh : public ::testing::TestWithParam<const char*> {};

TEST_P(ParallelRealMesh, IndexTrianglesOfTheExplodedMesh)
{
  const Mesh_data m = load(GetParam());
  auto soup = soup_test::explode(m.points, m.triangles);
  expect_same_index(soup);
  shuffle_triangles(soup, 5);
  expect_same_index(soup);
}

// The exact weld by blocks against the single table of `first_equal_points()`, an independent
// implementation (and a map, on the small soup), on corner lists of many blocks: an exploded
// mesh in file order (most copies of a corner in its block), the same corners shuffled (nearly
// every point its block's representative: several rounds of copies), and points repeated over
// the whole range with -0.0 beside 0.0. Every budget of copies, on every number of threads.
std::vector<Point> exploded_corners(const std::string& relative, bool shuffled)
{
  Mesh_data m = load(relative);
  soup_test::subdivide_midpoints(m.points, m.triangles);
  std::vector<Point> corners;
  for(const Triangle& t : m.triangles)
    for(std::size_t v : t) corners.push_back(m.points[v]);
  if(shuffled) std::shuffle(corners.begin(), corners.end(), std::mt19937(11));
  return corners;
}

std::vector<Point> repeated_points_far_apart()
{
  std::vector<Point> points;
  const std::size_t n = 3 * ST::internal::default_block_size + 7;
  for(std::size_t i = 0; i < n; ++i) {
    const double a = static_cast<double>((i * 7919) % 97), b = static_cast<double>(i % 5);
    // the sign of zero changes every other period of 97
    const double zero = (i / 97) % 2 == 0 ? 0.0 : -0.0;
    points.emplace_back(a, b == 0 ? zero : b, zero);
  }
  return points;
}

TEST(ParallelExactWeld, ByBlocksGivesTheFirstPointOfTheSingleTable)
{
  const std::vector<std::vector<Point>> lists = {exploded_corners("clean/ChineseDragon-10kv.off.xz", false),
                                                 exploded_corners("clean/ChineseDragon-10kv.off.xz", true),
                                                 repeated_points_far_apart()};
  for(const std::vector<Point>& points : lists) {
    const std::size_t n = points.size();
    ASSERT_GT(n, 2 * ST::internal::default_block_size);
    auto point = [&](std::size_t i) -> const Point& { return points[i]; };
    const auto table = ST::internal::first_equal_points(n, point);
    const std::vector<std::uint32_t> expected(table.begin(), table.end());
    if(n < 100000) {
      std::map<std::array<double, 3>, std::uint32_t> first;
      for(std::size_t i = 0; i < n; ++i) {
        // (0.0 + x turns -0.0 into 0.0: the two are equal points)
        const std::array<double, 3> key = {0.0 + points[i].x(), 0.0 + points[i].y(), 0.0 + points[i].z()};
        first.emplace(key, static_cast<std::uint32_t>(i));
        ASSERT_EQ(expected[i], first.at(key)) << i;
      }
    }
    // the first points of every block, counted by the last pass when asked
    std::vector<std::size_t> expected_firsts(ST::internal::number_of_blocks(n), 0);
    for(std::size_t i = 0; i < n; ++i)
      expected_firsts[i / ST::internal::default_block_size] += expected[i] == i ? 1 : 0;
    for(const std::size_t budget : {std::size_t(0), ST::internal::default_block_size, n / 3, n}) {
      SCOPED_TRACE("points: " + std::to_string(n) + ", budget: " + std::to_string(budget));
      const auto sequential = ST::internal::first_equal_points_by_blocks<CGAL::Sequential_tag>(n, point, budget);
      EXPECT_EQ(std::vector<std::uint32_t>(sequential.begin(), sequential.end()), expected);
      for_each_thread_count([&](int) {
        ST::internal::Exact_weld_extras extras;
        extras.firsts_by_block.assign(3, 99); // replaced whole
        extras.all_finite = false;
        const auto parallel = ST::internal::first_equal_points_by_blocks<Parallel>(n, point, budget, &extras);
        EXPECT_EQ(std::vector<std::uint32_t>(parallel.begin(), parallel.end()), expected);
        EXPECT_EQ(extras.firsts_by_block, expected_firsts);
        EXPECT_TRUE(extras.all_finite);
        // without the last pass: the same first points and counts; every other entry names a
        // smaller index, the class's first or a point of its block that names the first
        ST::internal::Exact_weld_extras links;
        links.links_to_block_representatives = true;
        const auto linked = ST::internal::first_equal_points_by_blocks<Parallel>(n, point, budget, &links);
        EXPECT_EQ(links.firsts_by_block, expected_firsts);
        std::size_t wrong = 0, through_a_representative = 0;
        for(std::size_t i = 0; i < n; ++i) {
          const std::uint32_t r = linked[i];
          if(r == expected[i]) continue;
          ++through_a_representative;
          const bool good = r < i && r / ST::internal::default_block_size == i / ST::internal::default_block_size &&
                            linked[r] == expected[i];
          wrong += good ? 0 : 1;
        }
        EXPECT_EQ(wrong, 0u);
        if(budget == 0) {
          EXPECT_GT(through_a_representative, 0u); // (the links are taken: the test sees them)
        }
      });
    }
    // a range of one block is welded by one table: its first points counted too
    const std::size_t small = ST::internal::default_block_size - 5;
    ST::internal::Exact_weld_extras extras;
    const auto one_block = ST::internal::first_equal_points_by_blocks<Parallel>(small, point, 0, &extras);
    EXPECT_EQ(std::vector<std::uint32_t>(one_block.begin(), one_block.end()),
              std::vector<std::uint32_t>(expected.begin(), expected.begin() + static_cast<std::ptrdiff_t>(small)));
    std::size_t small_firsts = 0;
    for(std::size_t i = 0; i < small; ++i) small_firsts += expected[i] == i ? 1 : 0;
    EXPECT_EQ(extras.firsts_by_block, std::vector<std::size_t>(1, small_firsts));
    EXPECT_TRUE(extras.all_finite);
  }
}

TEST_P(ParallelRealMesh, AdjacencyTables)
{
  Mesh_data m = load(GetParam());
  const ST::Adjacency_tables expected(m.triangles, m.points.size());
  for_each_thread_count([&](int) { expect_same_tables(ST::Adjacency_tables(m.triangles, m.points.size(), Parallel()), expected); });
  shuffle_triangles(m.triangles, 7);
  const ST::Adjacency_tables shuffled(m.triangles, m.points.size());
  for_each_thread_count([&](int) { expect_same_tables(ST::Adjacency_tables(m.triangles, m.points.size(), Parallel()), shuffled); });
}

// The parallel build cuts the vertices into buckets (more than 2^10 vertices each past 4 Mi
// vertices) and the triangles into at most 64 blocks (more than 2^14 triangles each past 1 Mi
// triangles), and groups the edges of each vertex by a sort past 32 of them. A soup of 4.5 M
// vertices, most of them in no triangle, and 1.1 M triangles in random order: a strip, a fan of
// 100,000 triangles around the last vertex, a non-manifold edge of 40 triangles, a triangle
// repeated 10 times, and random triangles across all the buckets: the tables of the sequential
// build on any number of threads.
TEST(ParallelTables, ManyBucketsManyBlocksLongRowsAndNonManifoldEdges)
{
  const std::size_t nv = 4'500'000;
  std::vector<Triangle> triangles;
  for(std::size_t i = 0; i < 300'000; ++i)
    triangles.push_back(i % 2 == 0 ? Triangle{i, i + 1, i + 2} : Triangle{i + 1, i, i + 2});
  for(std::size_t j = 0; j < 100'000; ++j) triangles.push_back({nv - 1, 3'000'000 + j, 3'000'000 + j + 1});
  for(std::size_t k = 0; k < 40; ++k) triangles.push_back({2'000'000, 2'000'001, 2'000'002 + k});
  for(std::size_t k = 0; k < 10; ++k) triangles.push_back({1'000'000, 1'000'001, 1'000'002});
  std::mt19937_64 random(5);
  std::uniform_int_distribution<std::size_t> vertex(0, nv - 1);
  while(triangles.size() < 1'100'000) {
    const Triangle t{vertex(random), vertex(random), vertex(random)};
    if(t[0] != t[1] && t[1] != t[2] && t[2] != t[0]) triangles.push_back(t);
  }
  shuffle_triangles(triangles, 13);
  const ST::Adjacency_tables expected(triangles, nv);
  ASSERT_EQ(expected.triangles_around_vertex(nv - 1).size(), 100'000u);
  ASSERT_GE(expected.triangles_around_vertex(2'000'001).size(), 40u);
  ASSERT_FALSE(expected.non_manifold_edges().empty());
  for_each_thread_count([&](int) { expect_same_tables(ST::Adjacency_tables(triangles, nv, Parallel()), expected); });
}

// The global queries of the tables and the statistics, on the mesh, its exploded soup (one
// component per triangle) and the mesh with repeated, reversed and fanned triangles added
// (non-manifold edges and vertices, inconsistent orientations): the same lists, counts and ids
// on any number of threads. The exploded soups of the larger meshes span many blocks.
void expect_same_global_queries(const std::vector<Point>& points, const std::vector<Triangle>& triangles)
{
  const ST::Adjacency_tables tables(triangles, points.size());
  std::vector<ST::Adjacency_tables::size_type> component;
  const std::size_t components = tables.number_of_connected_components(&component);
  const auto non_manifold = tables.non_manifold_vertices();
  const auto inconsistent = tables.inconsistently_oriented_edges();
  const ST::Soup_statistics statistics = ST::compute_statistics(points, tables);
  EXPECT_EQ(statistics.components, components);
  for_each_thread_count([&](int) {
    std::vector<ST::Adjacency_tables::size_type> c;
    EXPECT_EQ(tables.number_of_connected_components<Parallel>(&c), components);
    EXPECT_EQ(c, component);
    EXPECT_EQ(tables.number_of_connected_components<Parallel>(), components);
    EXPECT_EQ(tables.non_manifold_vertices<Parallel>(), non_manifold);
    EXPECT_EQ(tables.inconsistently_oriented_edges<Parallel>(), inconsistent);
    const ST::Soup_statistics s = ST::compute_statistics<Parallel>(points, tables);
    EXPECT_EQ(soup_test::statistics_fields(s), soup_test::statistics_fields(statistics));
  });
}

TEST_P(ParallelRealMesh, GlobalQueriesOfTheTables)
{
  Mesh_data m = load(GetParam());
  expect_same_global_queries(m.points, m.triangles);
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  for(const auto& corners : soup_test::explode(m.points, m.triangles)) {
    points.insert(points.end(), corners.begin(), corners.end());
    triangles.push_back({points.size() - 3, points.size() - 2, points.size() - 1});
  }
  expect_same_global_queries(points, triangles);
  // every 7th triangle repeated reversed, every 11th fanned by a triangle to a new point
  const std::size_t n = m.triangles.size();
  for(std::size_t t = 0; t < n; ++t) {
    const Triangle tr = m.triangles[t];
    if(t % 7 == 0) m.triangles.push_back({tr[0], tr[2], tr[1]});
    if(t % 11 == 0) {
      m.points.push_back(Point(m.points[tr[0]].x() + 1, m.points[tr[0]].y(), m.points[tr[0]].z()));
      m.triangles.push_back({tr[0], tr[1], m.points.size() - 1});
    }
  }
  shuffle_triangles(m.triangles, 11);
  expect_same_global_queries(m.points, m.triangles);
}

TEST_P(ParallelRealMesh, ReconstructTopologyOfTheJitteredExplodedMesh)
{
  const Mesh_data m = load(GetParam());
  // Every corner its own point, moved by up to 1e-7 of the diagonal: the exact weld merges
  // nothing and the epsilon weld does all the work.
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  std::mt19937 rng(11);
  const double d = diagonal(m.points), jitter = 1e-7 * d;
  std::uniform_real_distribution<double> move(-jitter, jitter);
  for(const Triangle& t : m.triangles) {
    for(std::size_t k = 0; k < 3; ++k) {
      const Point& p = m.points[t[k]];
      points.emplace_back(p.x() + move(rng), p.y() + move(rng), p.z() + move(rng));
    }
    triangles.push_back({points.size() - 3, points.size() - 2, points.size() - 1});
  }
  for(const bool shuffled : {false, true}) {
    SCOPED_TRACE(shuffled ? "shuffled" : "in file order");
    if(shuffled) shuffle_triangles(triangles, 3);
    Recording_visitor expected_calls;
    auto ep = points;
    auto et = triangles;
    const ST::Reconstruction_report expected =
      ST::reconstruct_topology(ep, et, CGAL::parameters::snapping_tolerance(1e-5 * d).visitor(std::ref(expected_calls)));
    for_each_thread_count([&](int) {
      Recording_visitor calls;
      auto p = points;
      auto t = triangles;
      const ST::Reconstruction_report r = ST::reconstruct_topology<Parallel>(
        p, t, CGAL::parameters::snapping_tolerance(1e-5 * d).visitor(std::ref(calls)));
      EXPECT_EQ(fields(r), fields(expected));
      EXPECT_EQ(bits(p), bits(ep));
      EXPECT_EQ(t, et);
      EXPECT_EQ(calls.calls, expected_calls.calls);
    });
  }
}

TEST_P(ParallelRealMesh, ReconstructTopologyIntoAFaceGraph)
{
  const Mesh_data m = load(GetParam());
  const auto np = CGAL::parameters::snapping_tolerance(1e-4 * diagonal(m.points));
  CGAL::Surface_mesh<Point> expected;
  const ST::Reconstruction_report re = ST::reconstruct_topology(m.points, m.triangles, expected, np);
  for_each_thread_count([&](int) {
    CGAL::Surface_mesh<Point> mesh;
    const ST::Reconstruction_report r = ST::reconstruct_topology<Parallel>(m.points, m.triangles, mesh, np);
    EXPECT_EQ(fields(r), fields(re));
    ASSERT_EQ(mesh.number_of_vertices(), expected.number_of_vertices());
    ASSERT_EQ(mesh.number_of_faces(), expected.number_of_faces());
    std::vector<Point> a(mesh.points().begin(), mesh.points().end()), b(expected.points().begin(), expected.points().end());
    EXPECT_EQ(bits(a), bits(b));
    std::size_t different = 0;
    for(const auto f : faces(mesh)) {
      auto h = halfedge(f, mesh), g = halfedge(f, expected);
      for(int k = 0; k < 3; ++k, h = next(h, mesh), g = next(g, expected))
        different += target(h, mesh) != target(g, expected);
    }
    EXPECT_EQ(different, 0u);
  });
}

INSTANTIATE_TEST_SUITE_P(Meshes, ParallelRealMesh, ::testing::ValuesIn(real_meshes));

// --- the robustness soups ------------------------------------------------------------------------

class ParallelTJunctionSoup : public ::testing::TestWithParam<const char*> {};

TEST_P(ParallelTJunctionSoup, ReconstructSnapAndSplit)
{
  auto soup = t_junction_soup(GetParam(), 5, 17);
  ASSERT_GT(soup.t_junctions, 10u);
  const double eps = 1e-6 * diagonal(soup.points);
  const auto np = CGAL::parameters::snapping_tolerance(eps);
  for(const bool shuffled : {false, true}) {
    SCOPED_TRACE(shuffled ? "shuffled" : "generated order");
    if(shuffled) shuffle_triangles(soup.triangles, 23);
    auto ep = soup.points;
    auto et = soup.triangles;
    Recording_visitor expected_calls;
    const ST::Reconstruction_report expected =
      ST::reconstruct_topology(ep, et, CGAL::parameters::snapping_tolerance(eps).visitor(std::ref(expected_calls)));
    auto st = soup.triangles;
    const ST::Snap_report expected_snap = ST::snap_vertices(soup.points, st, np);
    auto tt = soup.triangles;
    const ST::Split_report expected_split = ST::split_t_junctions(soup.points, tt, np);
    for_each_thread_count([&](int) {
      auto p = soup.points;
      auto t = soup.triangles;
      Recording_visitor calls;
      const ST::Reconstruction_report r =
        ST::reconstruct_topology<Parallel>(p, t, CGAL::parameters::snapping_tolerance(eps).visitor(std::ref(calls)));
      EXPECT_EQ(fields(r), fields(expected));
      EXPECT_EQ(bits(p), bits(ep));
      EXPECT_EQ(t, et);
      EXPECT_EQ(calls.calls, expected_calls.calls);

      auto s = soup.triangles;
      const ST::Snap_report snap = ST::snap_vertices<Parallel>(soup.points, s, np);
      EXPECT_EQ(fields(snap), fields(expected_snap));
      EXPECT_EQ(snap.ambiguous_sites, expected_snap.ambiguous_sites);
      EXPECT_EQ(s, st);

      auto u = soup.triangles;
      const ST::Split_report split = ST::split_t_junctions<Parallel>(soup.points, u, np);
      EXPECT_EQ(fields(split), fields(expected_split));
      EXPECT_EQ(u, tt);
    });
  }
}

INSTANTIATE_TEST_SUITE_P(Meshes, ParallelTJunctionSoup,
                         ::testing::Values("clean/elephant.off", "clean/fandisk.off.xz", "clean/ChineseDragon-10kv.off.xz"));

TEST(ParallelRobustnessSoup, SubdividedTJunctionSoupOverManyBlocks)
{
  // Large enough for every parallel helper to cut many blocks.
  Mesh_data m = load("clean/elephant.off");
  soup_test::subdivide_midpoints(m.points, m.triangles);
  soup_test::subdivide_midpoints(m.points, m.triangles);
  auto soup = soup_test::t_junction_soup(m.points, m.triangles, 8, 1e-7 * diagonal(m.points) / std::sqrt(3.0), 5);
  const auto np = CGAL::parameters::snapping_tolerance(1e-6 * diagonal(soup.points));
  auto ep = soup.points;
  auto et = soup.triangles;
  const ST::Reconstruction_report expected = ST::reconstruct_topology(ep, et, np);
  const auto exploded = soup_test::explode(soup.points, soup.triangles);
  expect_same_index(exploded);
  for_each_thread_count([&](int) {
    auto p = soup.points;
    auto t = soup.triangles;
    const ST::Reconstruction_report r = ST::reconstruct_topology<Parallel>(p, t, np);
    EXPECT_EQ(fields(r), fields(expected));
    EXPECT_EQ(bits(p), bits(ep));
    EXPECT_EQ(t, et);
  });
}

TEST(ParallelUnionFind, ConcurrentUnionsGiveTheSequentialSetsAndRoots)
{
  // Random unions (long chains and many small sets) from all threads at once: the same sets,
  // each with its smallest element as root, as the sequential union-find.
  const std::uint32_t n = 200000;
  std::mt19937 rng(3);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for(std::uint32_t i = 0; i + 1 < n; i += 2 + rng() % 5) pairs.emplace_back(i, i + 1 + rng() % 3);
  for(int k = 0; k < 150000; ++k) pairs.emplace_back(rng() % n, rng() % n);
  for(auto& [a, b] : pairs) b = std::min(b, n - 1);
  ST::internal::Union_find expected(n);
  for(const auto& [a, b] : pairs) expected.unite(a, b);
  for_each_thread_count([&](int) {
    ST::internal::Concurrent_union_find concurrent(n);
    ST::internal::for_each_index<Parallel>(pairs.size(), [&](std::size_t k) { concurrent.unite(pairs[k].first, pairs[k].second); }, 1024);
    ST::internal::Union_find sets, by_blocks;
    concurrent.into(sets);
    // handed over by blocks on the threads, then read as roots (`take_roots()`: one pass)
    concurrent.into(by_blocks, [](std::size_t size, const auto& f) {
      ST::internal::for_each_block<Parallel>(size, 1000, f);
    });
    const ST::internal::Union_find::Parents roots = by_blocks.take_roots();
    std::size_t different = 0;
    for(std::uint32_t i = 0; i < n; ++i) different += sets.find(i) != expected.find(i) || roots[i] != expected.find(i);
    EXPECT_EQ(different, 0u);
  });
}

TEST(ParallelUnionFind, ParitiesByBlocksAsByAColouringOfTheGraph)
{
  // A graph whose every id has a label (0 or 1) and whose edges say whether their ends' labels
  // differ; the components without a wrong edge are two-coloured by the labels, each wrong edge
  // (a parity contradicting the labels) makes its component contradictory. The components are
  // groups of ids: runs of consecutive ids in the lower half (mostly inside a block), ids spread
  // over the whole upper half in the others (across every block), each a random spanning tree
  // and more edges, one group in seven with a wrong edge. The unions are made by blocks of ids on
  // the threads, each alone with the edges inside it, then one thread with the edges between
  // blocks, as the orientation makes them; the finds run on every thread at once. Expected, from
  // a breadth-first search: every id's root is the smallest id of its component, its parity the
  // labels' difference where the component has no contradiction, and the contradictions reported
  // are those of the components holding a wrong edge.
  const std::uint32_t n = 150000, block = 4096, run = 500, spread = 150;
  std::mt19937 rng(11);
  std::vector<char> label(n);
  for(char& l : label) l = static_cast<char>(rng() % 2);
  struct Edge { std::uint32_t a, b; bool differ; };
  std::vector<Edge> edges;
  const auto add = [&](std::uint32_t a, std::uint32_t b, bool wrong) {
    if(a == b) return;
    edges.push_back(Edge{a, b, (label[a] != label[b]) != wrong});
  };
  std::vector<std::vector<std::uint32_t>> groups((n / 2) / run + spread);
  for(std::uint32_t x = 0; x < n; ++x) groups[x < n / 2 ? x / run : (n / 2) / run + x % spread].push_back(x);
  for(std::size_t g = 0; g < groups.size(); ++g) {
    std::vector<std::uint32_t> members = groups[g];
    std::shuffle(members.begin(), members.end(), rng);
    for(std::size_t k = 1; k < members.size(); ++k) add(members[rng() % k], members[k], false);
    for(std::size_t k = 0; k < members.size() / 2; ++k) {
      const std::uint32_t a = members[rng() % members.size()];
      add(a, members[rng() % members.size()], false);
    }
    if(g % 7 == 3) add(members[0], members[members.size() / 2], true);
  }
  std::shuffle(edges.begin(), edges.end(), rng);
  // The expected components (smallest id) and contradictions, by a breadth-first search.
  std::vector<std::vector<std::pair<std::uint32_t, bool>>> adjacent(n);
  for(const Edge& e : edges) {
    adjacent[e.a].emplace_back(e.b, e.differ);
    adjacent[e.b].emplace_back(e.a, e.differ);
  }
  std::vector<std::uint32_t> component(n, n);
  std::vector<char> parity(n, 0), contradictory(n, 0);
  for(std::uint32_t s = 0; s < n; ++s) {
    if(component[s] != n) continue;
    std::vector<std::uint32_t> queue{s};
    component[s] = s;
    for(std::size_t h = 0; h < queue.size(); ++h)
      for(const auto& [w, differ] : adjacent[queue[h]]) {
        const char expected = static_cast<char>(parity[queue[h]] != (differ ? 1 : 0));
        if(component[w] == n) {
          component[w] = s;
          parity[w] = expected;
          queue.push_back(w);
        } else if(parity[w] != expected) {
          contradictory[s] = 1;
        }
      }
  }
  ASSERT_GT(std::count(contradictory.begin(), contradictory.end(), char(1)), 30);
  ASSERT_GT(std::count(component.begin(), component.end(), std::uint32_t(0)), 400);
  for_each_thread_count([&](int) {
    ST::internal::Parity_union_find sets(n);
    const std::size_t blocks = ST::internal::number_of_blocks(n, block);
    std::vector<std::vector<Edge>> inside(blocks);
    std::vector<Edge> between;
    for(const Edge& e : edges) {
      const std::uint32_t lo = std::min(e.a, e.b), hi = std::max(e.a, e.b);
      if(lo / block == hi / block) inside[lo / block].push_back(e);
      else between.push_back(e);
    }
    std::vector<std::vector<std::uint32_t>> refused(blocks + 1);
    ST::internal::for_each_block<Parallel>(n, block, [&](std::size_t b, std::size_t begin, std::size_t end) {
      sets.make_singletons(begin, end);
      for(const Edge& e : inside[b])
        if(!sets.unite_alone(e.a, e.b, e.differ)) refused[b].push_back(e.a);
    });
    for(const Edge& e : between)
      if(!sets.unite_alone(e.a, e.b, e.differ)) refused[blocks].push_back(e.a);
    std::vector<std::uint32_t> root(n);
    std::vector<char> found_parity(n);
    ST::internal::for_each_index<Parallel>(n, [&](std::size_t x) {
      const auto [r, p] = sets.find(static_cast<std::uint32_t>(x));
      root[x] = r;
      found_parity[x] = p ? 1 : 0;
    }, 512);
    std::size_t wrong_roots = 0, wrong_parities = 0;
    for(std::uint32_t x = 0; x < n; ++x) {
      wrong_roots += root[x] != component[x];
      wrong_parities += !contradictory[component[x]] && found_parity[x] != parity[x];
      EXPECT_LE(sets.parent(x).first, x);
    }
    EXPECT_EQ(wrong_roots, 0u);
    EXPECT_EQ(wrong_parities, 0u);
    std::vector<char> reported(n, 0);
    for(const auto& list : refused)
      for(std::uint32_t x : list) reported[component[x]] = 1;
    EXPECT_EQ(reported, contradictory);
  });
}

TEST(ParallelSortByKey, StableAndTheSequentialOrder)
{
  // Keys with many repeats (stability shows), some digits shared by all keys (skipped passes),
  // and enough items for the blocks; then the densest tolerance cell of a clustered cloud.
  struct Item
  {
    std::uint64_t key;
    std::uint32_t id;
  };
  std::mt19937_64 rng(5);
  std::vector<Item> items((std::size_t(1) << 20) + 4321);
  for(std::size_t i = 0; i < items.size(); ++i)
    items[i] = {(std::uint64_t(0xabcd) << 48) | (rng() % 5000) << 20 | (rng() % 3), static_cast<std::uint32_t>(i)};
  std::vector<Item> expected = items;
  std::stable_sort(expected.begin(), expected.end(), [](const Item& a, const Item& b) { return a.key < b.key; });
  std::vector<Point> cloud;
  for(int c = 0; c < 300000; ++c) {
    const double x = double(rng() % 1000), y = double(rng() % 1000), z = double(rng() % 1000);
    for(int k = 0; k < 1 + c % 7; ++k) cloud.emplace_back(x + 1e-4 * k, y, z - 1e-4 * k);
  }
  const std::size_t expected_cell = ST::internal::largest_tolerance_cell(cloud, 0.01);
  ASSERT_GE(expected_cell, 7u);
  // The sequential sort, by digits and (on a prefix of fewer than 4096 items) by comparisons.
  for(const std::size_t size : {items.size(), std::size_t(4095)}) {
    std::vector<Item> sorted(items.begin(), items.begin() + std::ptrdiff_t(size)), buffer;
    std::vector<Item> stable = sorted;
    std::stable_sort(stable.begin(), stable.end(), [](const Item& a, const Item& b) { return a.key < b.key; });
    ST::internal::sort_by_key<CGAL::Sequential_tag>(sorted, buffer);
    std::size_t different = 0;
    for(std::size_t i = 0; i < size; ++i) different += sorted[i].id != stable[i].id;
    EXPECT_EQ(different, 0u) << size << " items";
  }
  for_each_thread_count([&](int) {
    std::vector<Item> sorted = items, buffer;
    ST::internal::sort_by_key<Parallel>(sorted, buffer);
    std::size_t different = 0;
    for(std::size_t i = 0; i < sorted.size(); ++i) different += sorted[i].id != expected[i].id;
    EXPECT_EQ(different, 0u);
    // the same with scratch space that is not zeroed first
    ST::internal::Uninitialized_vector<Item> unzeroed(items.begin(), items.end()), unzeroed_buffer;
    ST::internal::sort_by_key<Parallel>(unzeroed, unzeroed_buffer);
    different = 0;
    for(std::size_t i = 0; i < unzeroed.size(); ++i) different += unzeroed[i].id != expected[i].id;
    EXPECT_EQ(different, 0u);
    EXPECT_EQ(ST::internal::largest_tolerance_cell<Parallel>(cloud, 0.01), expected_cell);
  });
}

TEST(ParallelSideBySide, BothRunAndNeitherRunsOnAfterAnError)
{
  // Two independent tasks, the second itself parallel; then either one throwing while the other
  // is still at work: the error reaches the caller only once the other has ended (or, cancelled
  // before it started, never ran). Sequentially the first runs before the second.
  const std::size_t n = 9 * ST::internal::default_block_size + 5;
  const auto sum_of_squares = [&] {
    std::vector<std::uint64_t> squares(n);
    ST::internal::for_each_index<Parallel>(n, [&](std::size_t i) { squares[i] = std::uint64_t(i) * i; });
    return std::accumulate(squares.begin(), squares.end(), std::uint64_t(0));
  };
  const std::uint64_t expected = sum_of_squares();
  bool first_ran = false, first_seen_by_second = false;
  ST::internal::run_side_by_side<CGAL::Sequential_tag>([&] { first_ran = true; },
                                                       [&] { first_seen_by_second = first_ran; });
  EXPECT_TRUE(first_seen_by_second);
  for_each_thread_count([&](int threads) {
    std::uint64_t side = 0, main = 0;
    ST::internal::run_side_by_side<Parallel>([&] { side = sum_of_squares(); }, [&] { main = sum_of_squares(); });
    EXPECT_EQ(side, expected) << threads << " threads";
    EXPECT_EQ(main, expected) << threads << " threads";
    for(const bool first_throws : {true, false}) {
      std::atomic<int> started{0}, ended{0};
      const auto slow = [&] {
        ++started;
        std::this_thread::sleep_for(std::chrono::milliseconds(30));
        ++ended;
      };
      const auto throws = [] { throw std::runtime_error("side by side"); };
      try {
        if(first_throws) ST::internal::run_side_by_side<Parallel>(throws, slow);
        else ST::internal::run_side_by_side<Parallel>(slow, throws);
        ADD_FAILURE() << "no exception, " << threads << " threads";
      } catch(const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "side by side");
      }
      EXPECT_EQ(started.load(), ended.load()) << threads << " threads, the first throws: " << first_throws;
    }
  });
}

TEST(ParallelLargest, TheLargestOfAllBlocksWhereverItIs)
{
  // The largest value placed in the first element, inside a block, at a block's end and at the
  // last element of a range of many blocks; an empty range and a range of negative values give
  // the floor (`smallest`).
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> value(-1., 1.);
  const std::size_t n = 37 * ST::internal::default_block_size + 11;
  std::vector<double> values(n);
  for(double& x : values) x = value(rng);
  const std::size_t places[] = {0, 5 * ST::internal::default_block_size + 77, 2 * ST::internal::default_block_size - 1,
                                n - 1};
  for(const std::size_t place : places) {
    std::vector<double> v = values;
    v[place] = 2. + static_cast<double>(place % 7);
    const auto value_of = [&](std::size_t i) { return v[i]; };
    EXPECT_EQ((ST::internal::largest_by_blocks<CGAL::Sequential_tag>(n, value_of)), v[place]);
    // (the values before `place`: their largest, or the floor 0 when all are negative)
    EXPECT_EQ((ST::internal::largest_by_blocks<CGAL::Sequential_tag>(place, value_of)),
              place == 0 ? 0. : std::max(0., *std::max_element(v.begin(), v.begin() + std::ptrdiff_t(place))));
    for_each_thread_count([&](int threads) {
      EXPECT_EQ((ST::internal::largest_by_blocks<Parallel>(n, value_of)), v[place]) << threads << " threads";
    });
  }
  const auto negative = [&](std::size_t i) { return -1.5 + values[i] / 4; };
  for_each_thread_count([&](int threads) {
    EXPECT_EQ((ST::internal::largest_by_blocks<Parallel>(0, negative, -7.)), -7.) << threads << " threads";
    EXPECT_EQ((ST::internal::largest_by_blocks<Parallel>(n, negative)), 0.) << threads << " threads";
    EXPECT_EQ((ST::internal::largest_by_blocks<Parallel>(n, negative, -7.)),
              -1.5 + *std::max_element(values.begin(), values.end()) / 4)
      << threads << " threads";
  });
}

// Blocks of many sizes filled with a pattern and freed: the allocator hands the same memory out
// again to the next blocks of these sizes, so that an entry of an `Uninitialized_vector` that a
// pass forgot to write shows as the pattern, not as a lucky zero of fresh memory.
void leave_a_pattern_in_freed_memory()
{
  std::vector<void*> blocks;
  for(std::size_t bytes = 1024; bytes <= (std::size_t(1) << 17); bytes *= 2)
    for(int k = 0; k < 3; ++k) {
      void* block = std::malloc(bytes + 16 * std::size_t(k));
      if(block == nullptr) continue;
      std::memset(block, 0xA5, bytes + 16 * std::size_t(k));
#if defined(__GNUC__)
      asm volatile("" : : "r"(block) : "memory"); // the filled block is used: keep the writes
#endif
      blocks.push_back(block);
    }
  for(void* block : blocks) std::free(block);
}

// Whether this process can see the huge-page advice of its mappings: the package advises them
// (Linux), the kernel has transparent huge pages, and no sanitizer's allocator lays the memory out
// its own way (clang says so by __has_feature only).
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define PARALLEL_TEST_SANITIZED_ALLOCATOR 1
#endif
#endif
bool huge_page_advice_is_visible()
{
#if defined(SOUP_TOPOLOGY_HUGE_PAGES) && !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__) && \
  !defined(PARALLEL_TEST_SANITIZED_ALLOCATOR)
  std::ifstream thp("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string modes;
  return thp && std::getline(thp, modes) && modes.find("[never]") == std::string::npos;
#else
  return false;
#endif
}

// Whether the huge page of this process that starts at or after `block` lies in a mapping
// flagged "hg" in /proc/self/smaps.
testing::AssertionResult first_huge_page_is_advised(const void* block)
{
  const std::size_t huge_page = ST::internal::huge_page_bytes;
  const std::uintptr_t address = (reinterpret_cast<std::uintptr_t>(block) + huge_page - 1) & ~(huge_page - 1);
  const std::vector<soup_test::Memory_mapping> mappings = soup_test::memory_mappings();
  if(mappings.empty()) return testing::AssertionFailure() << "no /proc/self/smaps";
  const auto holding = std::find_if(mappings.begin(), mappings.end(), [&](const soup_test::Memory_mapping& m) {
    return m.begin <= address && address < m.end;
  });
  if(holding == mappings.end()) return testing::AssertionFailure() << "no mapping holds the block";
  if(!holding->advised_for_huge_pages) return testing::AssertionFailure() << "the block's mapping is not advised";
  return testing::AssertionSuccess();
}

// Blocks of an `Uninitialized_vector` from 4 MiB on are asked for in transparent huge pages on
// Linux (aligned to 2 MiB, advised MADV_HUGEPAGE), smaller ones come from `std::allocator`: the
// contents survive growth and shrinking across that size, each block freed as it was allocated
// (the sanitizer jobs would see a mismatch), and a large block is advised where the kernel has
// huge pages.
TEST(ParallelUninitializedTables, LargeTablesInHugePages)
{
  using Vector = ST::internal::Uninitialized_vector<std::uint64_t>;
  const std::size_t small = (std::size_t(1) << 20) / sizeof(std::uint64_t); // 1 MiB
  const std::size_t large = 24 * small;                                      // 24 MiB
  Vector v;
  for(std::size_t i = 0; i < small; ++i) v.push_back(7 * i);
  v.resize(large);
  for(std::size_t i = small; i < large; ++i) v[i] = 7 * i;
  std::size_t wrong = 0;
  for(std::size_t i = 0; i < large; ++i) wrong += v[i] != 7 * i;
  EXPECT_EQ(wrong, 0u);
  v.resize(small);
  v.shrink_to_fit();
  for(std::size_t i = 0; i < small; ++i) wrong += v[i] != 7 * i;
  EXPECT_EQ(wrong, 0u);
  Vector copy = v;
  copy.insert(copy.end(), v.begin(), v.end());
  EXPECT_EQ(copy.size(), 2 * small);
  EXPECT_TRUE(std::equal(v.begin(), v.end(), copy.begin() + std::ptrdiff_t(small)));
#if defined(SOUP_TOPOLOGY_HUGE_PAGES)
  EXPECT_TRUE(ST::internal::is_huge_page_block(large * sizeof(std::uint64_t)));
  EXPECT_FALSE(ST::internal::is_huge_page_block(small * sizeof(std::uint64_t)));
  Vector table(large);
  const auto address = reinterpret_cast<std::uintptr_t>(table.data());
  EXPECT_EQ(address % (std::size_t(2) << 20), 0u);
  for(std::size_t i = 0; i < large; ++i) table[i] = i;
  // (the table starts a huge page)
  if(huge_page_advice_is_visible()) {
    EXPECT_TRUE(first_huge_page_is_advised(table.data())) << "a 24 MiB table";
  }
  EXPECT_EQ(table[large - 1], large - 1);
#endif
}

// The size of the system's pages.
std::size_t page_bytes()
{
#if defined(__linux__)
  const long size = sysconf(_SC_PAGESIZE);
  if(size > 0) return static_cast<std::size_t>(size);
#endif
  return 4096;
}

// The number of the system's pages inside the `bytes` bytes at `block` that are resident.
std::size_t resident_pages(const void* block, std::size_t bytes)
{
  std::size_t resident = 0;
#if defined(__linux__)
  const std::uintptr_t page = page_bytes();
  const std::uintptr_t first = (reinterpret_cast<std::uintptr_t>(block) + page - 1) & ~(page - 1);
  const std::uintptr_t last = (reinterpret_cast<std::uintptr_t>(block) + bytes) & ~(page - 1);
  if(first >= last) return 0;
  std::vector<unsigned char> in_core((last - first) / page);
  if(mincore(reinterpret_cast<void*>(first), last - first, in_core.data()) == 0)
    for(const unsigned char c : in_core) resident += c & 1u;
#else
  (void)block;
  (void)bytes;
#endif
  return resident;
}

// A large table that passes on TBB's threads write whole is faulted in first, by one call on one
// thread (`internal::fault_in_pages()`): the elements stay as they were, and where the kernel
// populates (MADV_POPULATE_WRITE, Linux 5.14) every page of a fresh block is resident afterwards
// while a fresh block that nothing touched has none. The blocks are of 64 MiB, beyond the sizes
// that glibc serves again from freed memory: each is a fresh mapping.
TEST(ParallelUninitializedTables, LargeTablesAreFaultedInBeforeTheirPasses)
{
  const std::size_t large = (std::size_t(64) << 20) / sizeof(std::uint64_t);
  ST::internal::Uninitialized_vector<std::uint64_t> kept(large);
  for(std::size_t i = 0; i < large; ++i) kept[i] = 7 * i;
  ST::internal::fault_in_pages(kept);
  std::size_t wrong = 0;
  for(std::size_t i = 0; i < large; ++i) wrong += kept[i] != 7 * i;
  EXPECT_EQ(wrong, 0u) << "the elements of a table already written";
  std::vector<std::uint64_t> callers(1000, 5);
  ST::internal::fault_in_pages(callers); // (a small block: nothing to do)
  EXPECT_EQ(callers, std::vector<std::uint64_t>(1000, 5));
#if defined(SOUP_TOPOLOGY_HUGE_PAGES) && defined(MADV_POPULATE_WRITE)
  if(huge_page_advice_is_visible()) {
    // whether this kernel populates at all (an older one refuses the advice)
    const std::size_t page = page_bytes();
    void* probe = mmap(nullptr, page, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    ASSERT_NE(probe, MAP_FAILED);
    const bool populates = madvise(probe, page, MADV_POPULATE_WRITE) == 0;
    munmap(probe, page);
    const std::size_t bytes = large * sizeof(std::uint64_t), pages = bytes / page;
    ST::internal::Uninitialized_vector<std::uint64_t> untouched(large), fresh(large);
    EXPECT_EQ(resident_pages(untouched.data(), bytes), 0u) << "a fresh block that nothing touched";
    ST::internal::fault_in_pages(fresh);
    if(populates) {
      EXPECT_EQ(resident_pages(fresh.data(), bytes), pages) << "a fresh block faulted in";
    }
  }
#endif
}

// The caller's vectors that the package grows (the exact weld's points and triangles, the
// triangles that a T-junction split appends, Loop's points and triangles) get their room in a new
// block whose huge pages are advised before anything touches them
// (`internal::reserve_in_huge_pages()`): the elements and the size survive the move, a vector with
// room enough keeps its block, a range of another type is given `reserve()` where it has one.
TEST(ParallelUninitializedTables, CallersVectorsGrowIntoHugePages)
{
  const std::size_t small = (std::size_t(1) << 20) / sizeof(std::uint64_t); // 1 MiB
  const std::size_t large = 24 * small;                                      // 24 MiB
  std::vector<std::uint64_t> v(small);
  for(std::size_t i = 0; i < small; ++i) v[i] = 7 * i;
  ST::internal::reserve_in_huge_pages(v, large, 2 * large);
  EXPECT_EQ(v.size(), small);
  EXPECT_GE(v.capacity(), 2 * large);
  std::size_t wrong = 0;
  for(std::size_t i = 0; i < small; ++i) wrong += v[i] != 7 * i;
  EXPECT_EQ(wrong, 0u);
  const std::uint64_t* const block = v.data();
  ST::internal::reserve_in_huge_pages(v, large);
  EXPECT_EQ(v.data(), block) << "a vector with room enough is moved";
  v.resize(large, 1);
  if(huge_page_advice_is_visible()) {
    EXPECT_TRUE(first_huge_page_is_advised(v.data())) << "a caller's 48 MiB vector";
  }

  // A move that may throw is not used: the elements are copied, and a copy that throws leaves the
  // vector as it was.
  struct Copy_may_throw
  {
    int value;
    explicit Copy_may_throw(int v) : value(v) {}
    Copy_may_throw(const Copy_may_throw& other) : value(other.value)
    {
      if(--copies_left() < 0) throw std::runtime_error("copy");
    }
    Copy_may_throw(Copy_may_throw&& other) : value(other.value) { other.value = -1; }
    Copy_may_throw& operator=(const Copy_may_throw&) = default;
    static int& copies_left()
    {
      static int left = 0;
      return left;
    }
  };
  std::vector<Copy_may_throw> fragile;
  fragile.reserve(1000);
  for(int i = 0; i < 1000; ++i) fragile.emplace_back(i);
  Copy_may_throw::copies_left() = 500;
  EXPECT_THROW(ST::internal::reserve_in_huge_pages(fragile, 5000), std::runtime_error);
  EXPECT_EQ(fragile.size(), 1000u);
  EXPECT_EQ(fragile.capacity(), 1000u);
  wrong = 0;
  for(int i = 0; i < 1000; ++i) wrong += fragile[std::size_t(i)].value != i;
  EXPECT_EQ(wrong, 0u);
  Copy_may_throw::copies_left() = 1000;
  ST::internal::reserve_in_huge_pages(fragile, 5000);
  EXPECT_GE(fragile.capacity(), 5000u);
  for(int i = 0; i < 1000; ++i) wrong += fragile[std::size_t(i)].value != i;
  EXPECT_EQ(wrong, 0u);

  std::deque<int> no_reserve{1, 2, 3};
  ST::internal::reserve_in_huge_pages(no_reserve, 100);
  EXPECT_EQ(no_reserve, (std::deque<int>{1, 2, 3}));
  ST::internal::Uninitialized_vector<std::uint32_t> other_allocator(3, 5u);
  ST::internal::reserve_in_huge_pages(other_allocator, 1000);
  EXPECT_GE(other_allocator.capacity(), 1000u);
  EXPECT_EQ(std::vector<std::uint32_t>(other_allocator.begin(), other_allocator.end()),
            (std::vector<std::uint32_t>{5, 5, 5}));

  // The package's growth of the caller's vectors: Loop (two levels of the bunny: 1.1M triangles,
  // 0.55M points, more than 4 MiB each), the exact weld of that mesh exploded, and the T-junction
  // split of two patches of the bunny split once (0.3M triangles, copied: no room for the new ones).
  const Mesh_data m = load("clean/bunny00.off.xz");
  std::vector<Point> loop_points = m.points;
  std::vector<Triangle> loop_triangles = m.triangles;
  ST::loop_subdivision<Parallel>(loop_points, loop_triangles, CGAL::parameters::number_of_iterations(2));
  ASSERT_GT(loop_points.size() * sizeof(Point), ST::internal::huge_page_block_bytes);
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  ST::index_triangles<Parallel>(soup_test::explode(loop_points, loop_triangles), points, triangles);
  EXPECT_EQ(points.size(), loop_points.size());
  EXPECT_EQ(triangles.size(), loop_triangles.size());
  std::vector<Point> split_once_points = m.points;
  std::vector<Triangle> split_once_triangles = m.triangles;
  soup_test::subdivide_midpoints(split_once_points, split_once_triangles);
  const auto soup = soup_test::t_junction_soup(split_once_points, split_once_triangles, 2, 0.0, 17);
  ASSERT_GT(soup.triangles.size() * sizeof(Triangle), ST::internal::huge_page_block_bytes);
  const auto np = CGAL::parameters::snapping_tolerance(1e-9);
  std::vector<Triangle> split = soup.triangles, split_with_room;
  ASSERT_EQ(split.capacity(), split.size());
  const ST::Split_report report = ST::split_t_junctions<Parallel>(soup.points, split, np);
  EXPECT_GT(report.split_triangles, 0u);
  EXPECT_EQ(split.size(), soup.triangles.size() + report.split_triangles);
  split_with_room.reserve(2 * soup.triangles.size());
  split_with_room.assign(soup.triangles.begin(), soup.triangles.end());
  ST::split_t_junctions<Parallel>(soup.points, split_with_room, np);
  EXPECT_EQ(split, split_with_room);
  if(huge_page_advice_is_visible()) {
    EXPECT_TRUE(first_huge_page_is_advised(loop_points.data())) << "Loop's points";
    EXPECT_TRUE(first_huge_page_is_advised(loop_triangles.data())) << "Loop's triangles";
    EXPECT_TRUE(first_huge_page_is_advised(points.data())) << "the exact weld's points";
    EXPECT_TRUE(first_huge_page_is_advised(triangles.data())) << "the exact weld's triangles";
    EXPECT_TRUE(first_huge_page_is_advised(split.data())) << "the triangles a split appended to";
  }
}

TEST(ParallelUninitializedTables, NoEntryIsLeftUnwritten)
{
  // The arrays that the passes write whole are not zeroed first (`internal::Uninitialized_vector`):
  // built over memory that holds a pattern, the weld, the tables and Loop's levels are those of
  // the sequential code, on any number of threads.
  ST::internal::Uninitialized_vector<std::uint32_t> filled(3, 7u);
  filled.resize(5, 9u);
  EXPECT_EQ(std::vector<std::uint32_t>(filled.begin(), filled.end()), (std::vector<std::uint32_t>{7, 7, 7, 9, 9}));
  filled.assign(2, 4u);
  EXPECT_EQ(std::vector<std::uint32_t>(filled.begin(), filled.end()), (std::vector<std::uint32_t>{4, 4}));

  const Mesh_data m = load("clean/elephant.off");
  const auto soup = soup_test::explode(m.points, m.triangles);
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  const ST::Index_report expected = ST::index_triangles(soup, points, triangles);
  leave_a_pattern_in_freed_memory();
  const ST::Adjacency_tables expected_tables(triangles, points.size());
  std::vector<Point> loop_points = m.points;
  std::vector<Triangle> loop_triangles = m.triangles;
  leave_a_pattern_in_freed_memory();
  ST::loop_subdivision(loop_points, loop_triangles, CGAL::parameters::number_of_iterations(2));
  for_each_thread_count([&](int) {
    for(int round = 0; round < 2; ++round) {
      std::vector<Point> p;
      std::vector<Triangle> t;
      leave_a_pattern_in_freed_memory();
      const ST::Index_report r = ST::index_triangles<Parallel>(soup, p, t);
      EXPECT_EQ(fields(r), fields(expected));
      EXPECT_EQ(bits(p), bits(points));
      EXPECT_EQ(t, triangles);
      leave_a_pattern_in_freed_memory();
      expect_same_tables(ST::Adjacency_tables(t, p.size(), Parallel()), expected_tables);
      std::vector<Point> lp = m.points;
      std::vector<Triangle> lt = m.triangles;
      leave_a_pattern_in_freed_memory();
      ST::loop_subdivision<Parallel>(lp, lt, CGAL::parameters::number_of_iterations(2));
      EXPECT_EQ(bits(lp), bits(loop_points));
      EXPECT_EQ(lt, loop_triangles);
    }
  });
}

TEST(ParallelRobustnessSoup, ClustersWithRefusalsAndCollapsesOverManyBlocks)
{
  // The clusters are formed by blocks of whole components. A small-feature soup (seams split
  // near an end: two vertices of one triangle within the tolerance) with every seam copy
  // jittered: same-triangle refusals (REFUSE) or collapsed triangles (COLLAPSE) in many blocks.
  // Each policy gives the sequential triangles, report and visitor calls in the same order.
  Mesh_data m = load("clean/elephant.off");
  soup_test::subdivide_midpoints(m.points, m.triangles);
  soup_test::subdivide_midpoints(m.points, m.triangles);
  const double eps = 1e-4 * diagonal(m.points);
  auto soup = soup_test::small_feature_soup(m.points, m.triangles, 400, 0.05 * eps, 0.5, eps, 41);
  ASSERT_GT(soup.near_end_t_junctions, 1000u);
  for(const ST::Small_features policy : {ST::Small_features::REFUSE, ST::Small_features::COLLAPSE}) {
    SCOPED_TRACE(policy == ST::Small_features::REFUSE ? "refuse" : "collapse");
    auto et = soup.triangles;
    Recording_visitor expected_calls;
    const ST::Snap_report expected = ST::snap_vertices(
      soup.points, et, ST::parameters::small_features(policy, CGAL::parameters::snapping_tolerance(eps).visitor(std::ref(expected_calls))));
    ASSERT_GT(expected.candidate_vertices, 4u * 4096u);
    ASSERT_GT(expected.merged_vertices, 1000u);
    ASSERT_GT(policy == ST::Small_features::REFUSE ? expected.refused_same_triangle : expected.collapsed_triangles, 100u);
    for_each_thread_count([&](int) {
      auto t = soup.triangles;
      Recording_visitor calls;
      const ST::Snap_report r = ST::snap_vertices<Parallel>(
        soup.points, t, ST::parameters::small_features(policy, CGAL::parameters::snapping_tolerance(eps).visitor(std::ref(calls))));
      EXPECT_EQ(fields(r), fields(expected));
      EXPECT_EQ(std::make_pair(r.collapsed_triangles, r.small_features_resolved),
                std::make_pair(expected.collapsed_triangles, expected.small_features_resolved));
      EXPECT_EQ(t, et);
      EXPECT_EQ(calls.calls, expected_calls.calls);
    });
  }
}

TEST(ParallelRobustnessSoup, RowsSpreadOverManyBuffersGiveTheSameWeld)
{
  // The rows of the tolerance graph start at 4-byte offsets: a buffer of rows holds at most
  // `row_buffer_limit` entries and the rows go on in a new one. With a limit of 40 entries the
  // rows of this soup (sequential and on each thread) spread over thousands of buffers; the weld
  // is the one of a single buffer.
  Mesh_data m = load("clean/elephant.off");
  soup_test::subdivide_midpoints(m.points, m.triangles);
  const double eps = 1e-4 * diagonal(m.points);
  const auto soup = soup_test::small_feature_soup(m.points, m.triangles, 200, 0.05 * eps, 0.5, eps, 43);
  for(const ST::Small_features policy : {ST::Small_features::REFUSE, ST::Small_features::COLLAPSE}) {
    SCOPED_TRACE(policy == ST::Small_features::REFUSE ? "refuse" : "collapse");
    auto expected_triangles = soup.triangles;
    Recording_visitor expected_calls;
    const ST::Snap_report expected = ST::snap_vertices(
      soup.points, expected_triangles,
      ST::parameters::small_features(policy, CGAL::parameters::snapping_tolerance(eps).visitor(std::ref(expected_calls))));
    ASSERT_GT(expected.merged_vertices, 1000u);
    const std::size_t limit = ST::internal::row_buffer_limit;
    ST::internal::row_buffer_limit = 40;
    for(const bool parallel : {false, true}) {
      SCOPED_TRACE(parallel ? "parallel" : "sequential");
      auto t = soup.triangles;
      Recording_visitor calls;
      const auto np = ST::parameters::small_features(policy, CGAL::parameters::snapping_tolerance(eps).visitor(std::ref(calls)));
      const ST::Snap_report r = parallel ? ST::snap_vertices<Parallel>(soup.points, t, np) : ST::snap_vertices(soup.points, t, np);
      EXPECT_EQ(fields(r), fields(expected));
      EXPECT_EQ(t, expected_triangles);
      EXPECT_EQ(calls.calls, expected_calls.calls);
    }
    ST::internal::row_buffer_limit = limit;
  }
}
TEST(ParallelRobustnessSoup, NonManifoldVerticesSeparatedInEveryBlock)
{
  // A chain of 3,000 closed cubes, cube n on [n, n + 1]^3, consecutive cubes sharing one corner:
  // 2,999 non-manifold vertices, the triangles shuffled so that the corners to move lie in every
  // block. The fan with the canonically smallest triangle (the lower cube) keeps each shared
  // point; the upper cube's corners move to a copy, and the copies are appended in the order of
  // the shared vertices. Every thread count, with and without the tables at hand, gives that.
  constexpr std::size_t cubes = 3000;
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  std::vector<std::size_t> shared; // shared[n]: the corner of cubes n and n + 1
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  std::size_t lowest = 0; // the index of corner (n, n, n) of cube n
  for(std::size_t n = 0; n < cubes; ++n) {
    std::array<std::size_t, 8> corner;
    for(int c = 0; c < 8; ++c) {
      if(c == 0 && n > 0) {
        corner[0] = lowest;
        continue;
      }
      corner[std::size_t(c)] = points.size();
      points.emplace_back(double(n) + (c & 1), double(n) + ((c >> 1) & 1), double(n) + ((c >> 2) & 1));
    }
    if(n + 1 < cubes) shared.push_back(corner[7]);
    lowest = corner[7];
    for(const auto& q : quads) {
      triangles.push_back({corner[std::size_t(q[0])], corner[std::size_t(q[1])], corner[std::size_t(q[2])]});
      triangles.push_back({corner[std::size_t(q[0])], corner[std::size_t(q[2])], corner[std::size_t(q[3])]});
    }
  }
  std::mt19937 rng(5);
  std::shuffle(triangles.begin(), triangles.end(), rng);
  ASSERT_GT(triangles.size(), 2 * ST::internal::default_block_size);
  const std::size_t input_points = points.size();
  // What the separation must give, checked on the sequential result: the copies in the order of
  // the shared vertices, the upper cube's corners on the copy, every cube closed and outward.
  auto ep = points;
  auto et = triangles;
  const ST::Orientation_report expected = ST::orient_triangle_soup(ep, et);
  EXPECT_EQ(expected.duplicated_points, cubes - 1);
  EXPECT_EQ(expected.duplicate_triangles, 0u);
  ASSERT_EQ(ep.size(), input_points + cubes - 1);
  for(std::size_t k = 0; k + 1 < cubes; ++k) EXPECT_EQ(ep[input_points + k], ep[shared[k]]) << k;
  std::vector<double> volume(cubes, 0.0);
  for(const Triangle& t : et) {
    const Point& a = ep[t[0]];
    const Point& b = ep[t[1]];
    const Point& c = ep[t[2]];
    // the mean of the centroid's coordinates lies strictly within (n, n + 1) on cube n's faces
    const double mean = (a.x() + b.x() + c.x() + a.y() + b.y() + c.y() + a.z() + b.z() + c.z()) / 9;
    const std::size_t cube = static_cast<std::size_t>(std::floor(mean));
    ASSERT_LT(cube, cubes);
    for(std::size_t v : t) {
      if(v < input_points) {
        // a shared point stays only on the lower cube
        const auto at = std::find(shared.begin(), shared.end(), v);
        if(at != shared.end()) {
          EXPECT_EQ(std::size_t(at - shared.begin()), cube);
        }
      } else {
        EXPECT_EQ(v - input_points + 1, cube) << "a copy on the upper cube of its shared vertex";
      }
    }
    volume[cube] += CGAL::to_double(CGAL::volume(Point(0, 0, 0), a, b, c));
  }
  for(std::size_t n = 0; n < cubes; ++n) EXPECT_NEAR(volume[n], 1.0, 1e-9) << n;
  const ST::Adjacency_tables output(et, ep.size());
  EXPECT_TRUE(output.non_manifold_vertices().empty());
  EXPECT_EQ(output.number_of_border_edges(), 0u);
  EXPECT_EQ(output.number_of_connected_components(), cubes);
  for_each_thread_count([&](int) {
    auto p = points;
    auto t = triangles;
    const ST::Orientation_report r = ST::orient_triangle_soup<Parallel>(p, t);
    EXPECT_EQ(r.duplicated_points, expected.duplicated_points);
    EXPECT_EQ(r.orientation_flips, expected.orientation_flips);
    EXPECT_EQ(bits(p), bits(ep));
    EXPECT_EQ(t, et);
    auto q = points;
    auto u = triangles;
    const ST::Adjacency_tables tables(u, q.size(), Parallel());
    const ST::Orientation_report w = ST::internal::orient_triangle_soup_with_tables<Parallel>(q, u, &tables);
    EXPECT_EQ(w.duplicated_points, expected.duplicated_points);
    EXPECT_EQ(bits(q), bits(ep));
    EXPECT_EQ(u, et);
  });
}

TEST(ParallelRobustnessSoup, ExactKernelAndCollapsedTriangles)
{
  // Epeck: the tables and the bookkeeping run in parallel, the geometric steps sequentially.
  auto soup = t_junction_soup("clean/fandisk.off.xz", 4, 9);
  std::vector<Epeck::Point_3> points;
  for(const Point& p : soup.points) points.emplace_back(p.x(), p.y(), p.z());
  // some exact duplicates and a collapsed triangle
  for(std::size_t i = 0; i + 7 < points.size(); i += 7) points[i + 1] = points[i];
  const double eps = 1e-6 * diagonal(soup.points);
  auto ep = points;
  auto et = soup.triangles;
  const ST::Reconstruction_report expected = ST::reconstruct_topology(ep, et, CGAL::parameters::snapping_tolerance(eps));
  for_each_thread_count([&](int) {
    auto p = points;
    auto t = soup.triangles;
    const ST::Reconstruction_report r = ST::reconstruct_topology<Parallel>(p, t, CGAL::parameters::snapping_tolerance(eps));
    EXPECT_EQ(fields(r), fields(expected));
    EXPECT_EQ(bits(p), bits(ep));
    EXPECT_EQ(t, et);
  });
}

// A grid of 240 x 240 unit squares whose every third square (19,200) has its diagonal split at
// its midpoint (exact in double) by a zero-area triangle, flippable with the triangle across the
// diagonal; in every seventh row these are doubled back to back (2,800 more, on a non-manifold
// diagonal, which no flip removes and the triangle across the diagonal covers): 22,000
// degenerate triangles over the 10 blocks of the soup. The scans and the tables of the flips, and the removal of
// the covered ones, on any number of threads: the same lists, flips, removals and triangles.
TEST(ParallelRobustnessSoup, DegenerateTrianglesFlippedAndRemovedOverManyBlocks)
{
  const std::size_t n = 240;
  std::vector<Point> points;
  for(std::size_t y = 0; y <= n; ++y)
    for(std::size_t x = 0; x <= n; ++x) points.emplace_back(double(x), double(y), 0.0);
  auto at = [&](std::size_t x, std::size_t y) { return y * (n + 1) + x; };
  std::vector<Triangle> triangles;
  for(std::size_t y = 0; y < n; ++y)
    for(std::size_t x = 0; x < n; ++x) {
      const std::size_t p00 = at(x, y), p10 = at(x + 1, y), p11 = at(x + 1, y + 1), p01 = at(x, y + 1);
      triangles.push_back({p00, p11, p01});
      if((x + y) % 3 != 0) {
        triangles.push_back({p00, p10, p11});
        continue;
      }
      const std::size_t m = points.size();
      points.emplace_back(double(x) + 0.5, double(y) + 0.5, 0.0);
      triangles.push_back({p00, p10, m});
      triangles.push_back({p10, p11, m});
      triangles.push_back({p11, p00, m});
      if(y % 7 == 0) triangles.push_back({p00, p11, m});
    }
  const std::vector<ST::Adjacency_tables::size_type> degenerate =
    ST::internal::degenerate_triangles(points, triangles, Epick());
  ASSERT_EQ(degenerate.size(), 22000u);
  auto expected = triangles;
  const auto flips = ST::internal::flip_degenerate_triangles(points, expected, Epick());
  const std::size_t removed = ST::internal::remove_covered_degenerate_triangles(points, expected, Epick());
  ASSERT_GT(flips.flipped, 15000u);
  ASSERT_GT(removed, 2000u);
  for_each_thread_count([&](int) {
    EXPECT_EQ(ST::internal::degenerate_triangles<Parallel>(points, triangles, Epick()), degenerate);
    auto t = triangles;
    const auto f = ST::internal::flip_degenerate_triangles<Parallel>(points, t, Epick());
    EXPECT_EQ(std::make_pair(f.flipped, f.remaining), std::make_pair(flips.flipped, flips.remaining));
    EXPECT_EQ(ST::internal::remove_covered_degenerate_triangles<Parallel>(points, t, Epick()), removed);
    EXPECT_EQ(t, expected);
  });
}

TEST(ParallelIndexTriangles, DuplicatesCollapsedTrianglesAndSignedZeros)
{
  std::mt19937 rng(1);
  std::uniform_int_distribution<int> coordinate(-20, 20);
  std::vector<std::array<Point, 3>> soup(200000);
  for(auto& t : soup)
    for(Point& p : t) p = Point(coordinate(rng) * 0.25, coordinate(rng) == 0 ? -0.0 : 0.0, coordinate(rng) % 5);
  expect_same_index(soup);
  // the error names the first bad corner, whatever the threads
  soup[150000][2] = Point(std::nan(""), 0, 0);
  soup[190000][1] = Point(0, HUGE_VAL, 0);
  for_each_thread_count([&](int) {
    std::vector<Point> p;
    std::vector<Triangle> t;
    try {
      ST::index_triangles<Parallel>(soup, p, t);
      ADD_FAILURE() << "no exception";
    } catch(const ST::Invalid_input& e) {
      EXPECT_EQ(std::string(e.what()), "triangle 150000, corner 2: non-finite coordinate");
    }
  });
  // the weld's first pass finds them (by blocks, or in a soup of one block): the first one named,
  // the output left as it was
  std::vector<std::array<Point, 3>> small(soup.begin(), soup.begin() + 100);
  small[57][1] = Point(1, 2, -HUGE_VAL);
  small[99][0] = Point(std::nan(""), 0, 0);
  soup[150000][2] = soup[150001][2];
  soup.back()[2] = Point(0, 0, HUGE_VAL);
  const std::vector<std::pair<const std::vector<std::array<Point, 3>>*, std::string>> refused = {
    {&small, "triangle 57, corner 1: non-finite coordinate"},
    {&soup, "triangle 190000, corner 1: non-finite coordinate"}};
  for_each_thread_count([&](int) {
    for(const auto& [bad_soup, message] : refused) {
      std::vector<Point> p(2, Point(1, 1, 1));
      std::vector<Triangle> t(1, Triangle{0, 1, 0});
      try {
        ST::index_triangles<Parallel>(*bad_soup, p, t);
        ADD_FAILURE() << "no exception";
      } catch(const ST::Invalid_input& e) {
        EXPECT_EQ(std::string(e.what()), message);
      }
      EXPECT_EQ(p, std::vector<Point>(2, Point(1, 1, 1)));
      EXPECT_EQ(t, std::vector<Triangle>(1, Triangle{0, 1, 0}));
    }
  });
  // A hostile soup: every corner the same NaN (one hash, equal to nothing). The weld stops at the
  // first one instead of probing its tables in quadratic time; the first corner is named.
  const Point nan_point(std::nan(""), std::nan(""), std::nan(""));
  const std::vector<std::array<Point, 3>> all_nan(400000, {nan_point, nan_point, nan_point});
  const std::vector<Point> nan_points(1000000, nan_point);
  for_each_thread_count([&](int) {
    std::vector<Point> p;
    std::vector<Triangle> t;
    EXPECT_THROW(
      try { ST::index_triangles<Parallel>(all_nan, p, t); } catch(const ST::Invalid_input& e) {
        EXPECT_EQ(std::string(e.what()), "triangle 0, corner 0: non-finite coordinate");
        throw;
      },
      ST::Invalid_input);
    std::vector<Point> q = nan_points;
    std::vector<Triangle> u(1, Triangle{0, 1, 2});
    EXPECT_THROW(
      try { ST::internal::merge_duplicate_points_and_map<Parallel>(q, u); } catch(const ST::Invalid_input& e) {
        EXPECT_EQ(std::string(e.what()), "point 0 has a non-finite coordinate");
        throw;
      },
      ST::Invalid_input);
  });
}

// The binary STL written on threads: the same bytes (several chunks of facets, with a repeated
// and a degenerate triangle, which is not refused), and the same first refusal when float rounding would change the
// soup (a point beyond the float range, a triangle that flips, each late in its range; the
// point first). With Epeck points the records are made on one thread, the same bytes again.
TEST(ParallelChecks, TheFirstBadFaceOrPointIsNamed)
{
  // The entry checks run by blocks on threads: the face or point named is the first one, with
  // the message of the sequential check, whatever the threads.
  Mesh_data m = load("clean/elephant.off");
  soup_test::subdivide_midpoints(m.points, m.triangles);
  soup_test::subdivide_midpoints(m.points, m.triangles);
  ASSERT_GT(m.triangles.size(), 80000u);
  const auto message = [](const auto& run) {
    try {
      run();
    } catch(const ST::Invalid_input& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  std::vector<std::vector<Triangle>> bad_soups(3, m.triangles);
  bad_soups[0][60001][2] = bad_soups[0][60001][0];                 // a repeated index
  bad_soups[0][70000][1] = m.points.size();                        // after it: out of range
  bad_soups[1][50000][0] = m.points.size() + 5;                    // out of range
  bad_soups[1][79999][2] = bad_soups[1][79999][1];
  bad_soups[2][m.triangles.size() - 1][1] = bad_soups[2][m.triangles.size() - 1][0]; // the last face
  std::vector<Point> bad_points = m.points;
  const std::size_t first_bad_point = bad_points.size() / 2 + 3;
  bad_points[first_bad_point] = Point(0, 0, std::nan(""));
  bad_points[bad_points.size() - 2] = Point(HUGE_VAL, 0, 0);
  // the exact weld of an indexed soup checks its indices by blocks and its points in its first pass
  const std::string out_of_range = "face 50000: vertex index " + std::to_string(m.points.size() + 5) +
                                   " is out of range (" + std::to_string(m.points.size()) + " points)";
  const std::string non_finite = "point " + std::to_string(first_bad_point) + " has a non-finite coordinate";
  for(const auto& [soup, pts, expected] : {std::make_tuple(&bad_soups[1], &m.points, out_of_range),
                                           std::make_tuple(&m.triangles, &bad_points, non_finite)}) {
    const auto merged = [&, soup = soup, pts = pts](auto tag) {
      std::vector<Point> p = *pts;
      std::vector<Triangle> t = *soup;
      const std::string what = message([&] { ST::internal::merge_duplicate_points_and_map<decltype(tag)>(p, t); });
      EXPECT_EQ(bits(p), bits(*pts)); // nothing changed
      EXPECT_EQ(t, *soup);
      return what;
    };
    EXPECT_EQ(merged(CGAL::Sequential_tag()), expected);
    for_each_thread_count([&, expected = expected](int) { EXPECT_EQ(merged(Parallel()), expected); });
  }
  for(const std::vector<Triangle>& soup : bad_soups) {
    const std::string expected = message([&] { ST::Adjacency_tables(soup, m.points.size()); });
    ASSERT_NE(expected.find("face "), std::string::npos) << expected;
    for_each_thread_count([&](int) {
      EXPECT_EQ(message([&] { ST::Adjacency_tables(soup, m.points.size(), Parallel()); }), expected);
      std::vector<Point> p = m.points;
      std::vector<Triangle> t = soup;
      EXPECT_EQ(message([&] { ST::orient_triangle_soup<Parallel>(p, t); }), expected);
    });
  }
  // Faces of signed indices and of any size (the tables check and copy them in one pass by
  // blocks): the good soup gives the sequential tables, a bad one the sequential message.
  std::vector<std::vector<int>> signed_soup;
  for(const Triangle& t : m.triangles)
    signed_soup.push_back({static_cast<int>(t[0]), static_cast<int>(t[1]), static_cast<int>(t[2])});
  const ST::Adjacency_tables signed_tables(signed_soup, m.points.size());
  std::vector<std::vector<std::vector<int>>> bad_signed_soups(3, signed_soup);
  bad_signed_soups[0][65000][1] = -3;                                // a negative index
  bad_signed_soups[1][40000].push_back(7);                           // a quad
  bad_signed_soups[1][75000][0] = -1;                                // after it: a negative index
  bad_signed_soups[2][30000].pop_back();                             // a segment
  bad_signed_soups[2][30001][0] = static_cast<int>(m.points.size()); // after it: out of range
  const std::vector<std::string> expected_signed = {"face 65000: negative vertex index -3",
                                                    "face 40000 has 4 vertices; a triangle soup needs exactly 3",
                                                    "face 30000 has 2 vertices; a triangle soup needs exactly 3"};
  for(std::size_t k = 0; k < bad_signed_soups.size(); ++k)
    EXPECT_EQ(message([&] { ST::Adjacency_tables(bad_signed_soups[k], m.points.size()); }), expected_signed[k]);
  for_each_thread_count([&](int) {
    expect_same_tables(ST::Adjacency_tables(signed_soup, m.points.size(), Parallel()), signed_tables);
    for(std::size_t k = 0; k < bad_signed_soups.size(); ++k)
      EXPECT_EQ(message([&] { ST::Adjacency_tables(bad_signed_soups[k], m.points.size(), Parallel()); }),
                expected_signed[k]);
  });
  const std::string expected = message([&] {
    std::vector<Point> p = bad_points;
    std::vector<Triangle> t = m.triangles;
    ST::reconstruct_topology(p, t, CGAL::parameters::snapping_tolerance(0.0));
  });
  EXPECT_EQ(expected, "point " + std::to_string(first_bad_point) + " has a non-finite coordinate");
  for_each_thread_count([&](int) {
    std::vector<Point> p = bad_points;
    std::vector<Triangle> t = m.triangles;
    EXPECT_EQ(message([&] { ST::reconstruct_topology<Parallel>(p, t, CGAL::parameters::snapping_tolerance(0.0)); }),
              expected);
    EXPECT_EQ(message([&] { ST::orient_triangle_soup<Parallel>(p, t); }), expected);
  });
}

} // namespace
