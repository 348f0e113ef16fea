// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// What the determinism tests of the parallel code share (parallel_test.cpp and
// parallel_other_steps_test.cpp, two programs so that the builds that compile only these tests,
// without TBB and under ThreadSanitizer, compile them on two cores): the thread counts, the
// comparison of reports and points bit for bit, and the real meshes and robustness soups.

#ifndef SOUP_TOPOLOGY_TEST_PARALLEL_TEST_UTILITIES_H
#define SOUP_TOPOLOGY_TEST_PARALLEL_TEST_UTILITIES_H

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/Octree.h>
#include <Soup_topology/analyze_gaps.h>
#include <Soup_topology/IO/STL.h>
#include <Soup_topology/IO/read_triangle_soup.h>
#include <Soup_topology/IO/write_triangle_soup.h>
#include <Soup_topology/index_triangles.h>
#include <Soup_topology/loop_subdivision.h>
#include <Soup_topology/orient_triangle_soup.h>
#include <Soup_topology/reconstruct_topology.h>
#include <Soup_topology/snap_vertices.h>
#include <Soup_topology/soup_statistics.h>
#include <Soup_topology/split_t_junctions.h>
#include <Soup_topology/internal/first_equal_points_by_blocks.h>
#include <Soup_topology/internal/small_feature_degenerate.h>
#include <Soup_topology/internal/snap_vertices_worker.h>
#include <Soup_topology/internal/tolerance_graph.h>

#include "soup_generators.h"
#include "test_utilities.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>

#if defined(CGAL_LINKED_WITH_TBB)
#include <tbb/global_control.h>
#endif

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

namespace {

namespace ST = Soup_topology;
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;
using Point = Epick::Point_3;
using Triangle = std::array<std::size_t, 3>;
using Parallel = CGAL::Parallel_if_available_tag;

/// The thread counts of the comparisons. Under ThreadSanitizer (whose run is about races, not about
/// the partition into blocks, which the Release run checks on every count) one count only, 8:
/// more threads than the cores of the machines the tests run on. Each thread takes the next block
/// not yet taken: on any count two blocks may run on different threads, where the sanitizer sees
/// a race between them, and on 8 more pairs of blocks do than on 2. A second count would run every
/// test again, the largest part of that build's time, for no kind of race the first cannot show.
#if defined(__SANITIZE_THREAD__)
constexpr int thread_counts[] = {8};
#else
constexpr int thread_counts[] = {1, 2, 3, 8};
#endif

/// calls `f(threads)` with TBB limited to each of `thread_counts` (once, sequentially, without TBB).
template <class F>
void for_each_thread_count(const F& f)
{
#if defined(CGAL_LINKED_WITH_TBB)
  for(const int threads : thread_counts) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(threads));
    SCOPED_TRACE("threads: " + std::to_string(threads));
    f(threads);
  }
#else
  SCOPED_TRACE("built without TBB");
  f(1);
#endif
}

/// the bit patterns of the coordinates (so that -0.0 and 0.0, or two NaNs, are told apart).
inline std::vector<std::uint64_t> bits(const std::vector<Point>& points)
{
  std::vector<std::uint64_t> result;
  result.reserve(3 * points.size());
  for(const Point& p : points)
    for(const double c : {p.x(), p.y(), p.z()}) {
      std::uint64_t u;
      std::memcpy(&u, &c, sizeof u);
      result.push_back(u);
    }
  return result;
}

inline std::vector<std::uint64_t> bits(const std::vector<Epeck::Point_3>& points)
{
  std::vector<Point> approximate;
  approximate.reserve(points.size());
  for(const auto& p : points) approximate.emplace_back(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
  return bits(approximate);
}

inline auto fields(const ST::Index_report& r)
{
  return std::make_tuple(r.input_triangles, r.input_corners, r.vertices, r.collapsed_triangles);
}

inline auto fields(const ST::Reconstruction_report& r)
{
  return std::make_tuple(r.tolerance, r.input_points, r.input_triangles, r.exact_duplicates, r.collapsed_triangles,
                         r.rounds, r.snapped_vertices, r.clusters, r.refused_same_triangle, r.refused_degenerate,
                         r.refused_flip, r.refused_holds_welds, r.ambiguous_sites, r.short_edges, r.t_junctions,
                         r.split_triangles, r.refused_splits, r.ambiguous_t_junctions, r.border_edges_before,
                         r.border_edges_after, r.non_manifold_edges_before, r.non_manifold_edges_after,
                         r.non_manifold_vertices_after, r.components_before, r.components, r.max_displacement,
                         r.removed_points, r.output_points, r.output_triangles, r.duplicate_triangles,
                         r.orientation_flips, r.duplicated_points, r.triangulated_polygons, r.unclipped_corners);
}

inline auto fields(const ST::Snap_report& r)
{
  return std::make_tuple(r.tolerance, r.candidate_vertices, r.merged_vertices, r.clusters, r.refused_same_triangle,
                         r.refused_degenerate, r.refused_flip, r.refused_holds_welds, r.ambiguous_sites, r.short_edges,
                         r.border_edges_before, r.border_edges_after, r.max_displacement);
}

inline auto fields(const ST::Split_report& r)
{
  return std::make_tuple(r.tolerance, r.t_junctions, r.split_triangles, r.refused_overlap, r.refused_degenerate,
                         r.refused_flip, r.ambiguous, r.border_edges_before, r.border_edges_after);
}

/// every table entry of `a` equals that of `b`.
inline void expect_same_tables(const ST::Adjacency_tables& a, const ST::Adjacency_tables& b)
{
  ASSERT_EQ(a.number_of_vertices(), b.number_of_vertices());
  ASSERT_EQ(a.triangles(), b.triangles());
  std::size_t different = 0;
  for(ST::Adjacency_tables::size_type t = 0; t < a.number_of_triangles(); ++t)
    for(int i = 0; i < 3; ++i) different += a.neighbor(t, i) != b.neighbor(t, i);
  for(ST::Adjacency_tables::size_type v = 0; v < a.number_of_vertices(); ++v) {
    const auto x = a.triangles_around_vertex(v), y = b.triangles_around_vertex(v);
    different += !(x.size() == y.size() && std::equal(x.begin(), x.end(), y.begin()));
  }
  EXPECT_EQ(different, 0u);
}

/// Every call of the weld's visitor, in order.
struct Recording_visitor
{
  std::vector<std::array<std::size_t, 3>> calls;
  void on_merge(std::size_t duplicate, std::size_t representative) { calls.push_back({0, duplicate, representative}); }
  void on_refusal(std::size_t vertex, std::size_t representative, ST::Refusal_reason reason)
  {
    calls.push_back({1 + static_cast<std::size_t>(reason), vertex, representative});
  }
};

struct Mesh_data
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
};

inline Mesh_data load(const std::string& relative)
{
  Mesh_data m;
  soup_test::read_data_mesh(relative, m.points, m.triangles);
  return m;
}

inline double diagonal(const std::vector<Point>& points)
{
  return ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>());
}

/// the triangles in a random order, each with its corners rotated at random.
template <class T>
void shuffle_triangles(std::vector<T>& triangles, unsigned seed)
{
  std::mt19937 rng(seed);
  std::shuffle(triangles.begin(), triangles.end(), rng);
  for(T& t : triangles) std::rotate(t.begin(), t.begin() + static_cast<std::ptrdiff_t>(rng() % 3), t.end());
}

/// The real meshes of the shared data folder (clean, CAD, scanned with defects).
const char* const real_meshes[] = {"clean/elephant.off", "clean/fandisk.off.xz", "clean/ChineseDragon-10kv.off.xz",
                                   "cgal_repair/pig.stl.xz", "cad/ALSTOM_TEST4.off",
                                   "cgal_repair/data_stitching/nm_cubes.off",
                                   "cgal_repair/data_stitching/non_manifold.off"};

/// A T-junction soup (robustness soup of soup_generators.h) from a real mesh.
inline soup_test::T_junction_soup<Point> t_junction_soup(const std::string& relative, int slabs, unsigned seed)
{
  const Mesh_data m = load(relative);
  return soup_test::t_junction_soup(m.points, m.triangles, slabs, 1e-7 * diagonal(m.points) / std::sqrt(3.0), seed);
}

/// index_triangles() of `soup` on every thread count gives the sequential index.
inline void expect_same_index(const std::vector<std::array<Point, 3>>& soup)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  const ST::Index_report expected = ST::index_triangles(soup, points, triangles);
  for_each_thread_count([&](int) {
    std::vector<Point> p;
    std::vector<Triangle> t;
    const ST::Index_report r = ST::index_triangles<Parallel>(soup, p, t);
    EXPECT_EQ(fields(r), fields(expected));
    EXPECT_EQ(bits(p), bits(points));
    EXPECT_EQ(t, triangles);
  });
}

} // namespace

#endif // SOUP_TOPOLOGY_TEST_PARALLEL_TEST_UTILITIES_H
