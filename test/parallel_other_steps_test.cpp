// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Determinism of the parallel code: every function that takes a ConcurrencyTag gives, with
// CGAL::Parallel_if_available_tag on 1, 2, 3 and 8 threads (8 oversubscribes the machines the
// tests run on), exactly the output of CGAL::Sequential_tag: the points bit for bit, the triangles
// and their order, the reports and the visitor's calls. Built without TBB the parallel tag is the
// sequential one and the tests compare the sequential code with itself.
//
// This program: the orientation, Loop subdivision, the readers and writers, the gap analysis and
// the octree (parallel_test.cpp has the weld, the tables, the pipeline, the robustness soups and
// the checks of the input).

#include "parallel_test_utilities.h"

#include <new>

namespace {

// --- the orientation and subdivision -------------------------------------------------------------

class ParallelRealMesh : public ::testing::TestWithParam<const char*> {};

TEST_P(ParallelRealMesh, OrientTriangleSoup)
{
  Mesh_data m = load(GetParam());
  for(const bool shuffled : {false, true}) {
    if(shuffled) shuffle_triangles(m.triangles, 13);
    auto ep = m.points;
    auto et = m.triangles;
    const ST::Orientation_report expected = ST::orient_triangle_soup(ep, et);
    for_each_thread_count([&](int) {
      auto p = m.points;
      auto t = m.triangles;
      const ST::Orientation_report r = ST::orient_triangle_soup<Parallel>(p, t);
      EXPECT_EQ(std::make_tuple(r.duplicate_triangles, r.orientation_flips, r.duplicated_points),
                std::make_tuple(expected.duplicate_triangles, expected.orientation_flips, expected.duplicated_points));
      EXPECT_EQ(bits(p), bits(ep));
      EXPECT_EQ(t, et);
      // with the tables of the soup at hand
      auto q = m.points;
      auto u = m.triangles;
      const ST::Adjacency_tables tables(u, q.size(), Parallel());
      const ST::Orientation_report w = ST::internal::orient_triangle_soup_with_tables<Parallel>(q, u, &tables);
      EXPECT_EQ(std::make_tuple(w.duplicate_triangles, w.orientation_flips, w.duplicated_points),
                std::make_tuple(expected.duplicate_triangles, expected.orientation_flips, expected.duplicated_points));
      EXPECT_EQ(bits(q), bits(ep));
      EXPECT_EQ(u, et);
    });
  }
}

TEST_P(ParallelRealMesh, LoopSubdivisionAndLimitPoints)
{
  const Mesh_data m = load(GetParam());
  auto ep = m.points;
  auto et = m.triangles;
  ST::Adjacency_tables expected_tables;
  ST::loop_subdivision(ep, et, ST::parameters::output_adjacency_tables(&expected_tables, CGAL::parameters::number_of_iterations(2)));
  // The limit points as bits, or the message of the exception (a refused subdivision matrix).
  const auto limit_points = [&](auto tag) {
    try {
      return std::make_pair(bits(ST::loop_limit_points<decltype(tag)>(m.points, m.triangles)), std::string());
    } catch(const ST::Invalid_input& e) {
      return std::make_pair(std::vector<std::uint64_t>(), std::string(e.what()));
    }
  };
  const auto limit_tangents = [&](auto tag) {
    try {
      std::vector<Point> as_points;
      for(const auto& pair : ST::loop_limit_tangents<decltype(tag)>(m.points, m.triangles))
        for(const auto& v : pair) as_points.push_back(CGAL::ORIGIN + v);
      return std::make_pair(bits(as_points), std::string());
    } catch(const ST::Invalid_input& e) {
      return std::make_pair(std::vector<std::uint64_t>(), std::string(e.what()));
    }
  };
  const auto expected_limit = limit_points(CGAL::Sequential_tag());
  const auto expected_tangents = limit_tangents(CGAL::Sequential_tag());
  for_each_thread_count([&](int) {
    auto p = m.points;
    auto t = m.triangles;
    ST::Adjacency_tables tables;
    ST::loop_subdivision<Parallel>(p, t, ST::parameters::output_adjacency_tables(&tables, CGAL::parameters::number_of_iterations(2)));
    EXPECT_EQ(bits(p), bits(ep));
    EXPECT_EQ(t, et);
    expect_same_tables(tables, expected_tables);
    EXPECT_EQ(limit_points(Parallel()), expected_limit);
    EXPECT_EQ(limit_tangents(Parallel()), expected_tangents);
  });
}

INSTANTIATE_TEST_SUITE_P(Meshes, ParallelRealMesh, ::testing::ValuesIn(real_meshes));

// Loop's level 0 built with the parallel tag from `tables` is `expected` (the sequential one).
void expect_parallel_level_0(const ST::Adjacency_tables& tables, const ST::internal::Loop_level& expected)
{
  ST::internal::Loop_level level;
  level.initialize<Parallel>(tables);
  EXPECT_EQ(level.number_of_edges, expected.number_of_edges);
  EXPECT_TRUE(level.edge_of == expected.edge_of);
  EXPECT_TRUE(level.half1 == expected.half1);
  EXPECT_TRUE(level.half2 == expected.half2);
  EXPECT_TRUE(level.count == expected.count);
  EXPECT_EQ(level.kind, expected.kind);
}

TEST(ParallelLoopSubdivision, FanOfManyFinsOnOneEdge)
{
  // 100,000 triangles on one edge: the halves of a non-manifold edge are found by one sort, not
  // by a search of the triangles around each of them (quadratic: about 20 s a call on this fan).
  const std::size_t k = 100000;
  std::vector<Point> points = {Point(0, 0, 0), Point(0, 0, 1)};
  std::vector<Triangle> fan;
  for(std::size_t j = 0; j < k; ++j) {
    const double a = 6.283185307179586 * double(j) / double(k);
    points.push_back(Point(std::cos(a), std::sin(a), 0.5));
    fan.push_back({j % 2 == 0 ? 0u : 1u, j % 2 == 0 ? 1u : 0u, points.size() - 1}); // both directions
  }
  const ST::Adjacency_tables tables(fan, points.size());
  ST::internal::Loop_level expected;
  expected.initialize(tables);
  // the shared edge is edge 0 of triangle 0, carried by every triangle; each fin adds two edges
  EXPECT_EQ(expected.number_of_edges, 2 * k + 1);
  EXPECT_EQ(expected.edge_of[0], 0u);
  EXPECT_EQ(expected.half1[0], 0u);
  EXPECT_EQ(expected.half2[0], 3u);
  EXPECT_EQ(expected.count[0], 3u);
  EXPECT_EQ(expected.edge_of[3 * (k - 1)], 0u);
  auto ep = points;
  auto et = fan;
  ST::loop_subdivision(ep, et);
  EXPECT_EQ(et.size(), 4 * k);
  for_each_thread_count([&](int) {
    expect_parallel_level_0(tables, expected);
    auto p = points;
    auto t = fan;
    ST::loop_subdivision<Parallel>(p, t);
    EXPECT_EQ(bits(p), bits(ep));
    EXPECT_EQ(t, et);
  });
}

/// the triangles of `triangles` with holes (one triangle in 997 left out) and fins (non-manifold
/// edges of three and four triangles: one fin on edge 0 of every 1499th triangle, two on its edge
/// 1 every other time), their apexes added to `points`, shuffled; `fins` receives their number.
std::vector<Triangle> with_holes_and_fins(std::vector<Point>& points, const std::vector<Triangle>& triangles,
                                          std::size_t& fins)
{
  std::vector<Triangle> soup;
  for(std::size_t t = 0; t < triangles.size(); ++t)
    if(t % 997 != 5) soup.push_back(triangles[t]); // holes
  fins = 0;
  for(std::size_t t = 0; t < triangles.size(); t += 1499) {
    const Triangle& tr = triangles[t];
    const Point apex = CGAL::midpoint(points[tr[0]], points[tr[2]]) + (points[tr[1]] - points[tr[0]]);
    points.push_back(apex);
    soup.push_back({tr[0], tr[1], points.size() - 1});
    ++fins;
    if(t % 2 == 0) {
      points.push_back(apex + (points[tr[2]] - points[tr[1]]));
      soup.push_back({tr[2], tr[1], points.size() - 1});
      points.push_back(apex + (points[tr[1]] - points[tr[2]]));
      soup.push_back({tr[1], tr[2], points.size() - 1});
      fins += 2;
    }
  }
  shuffle_triangles(soup, 29);
  return soup;
}

TEST(ParallelLoopSubdivision, EdgesNumberedByBlocksAcrossBordersAndFins)
{
  // Level 0's edges are numbered by blocks of 16,384 triangles on several threads: a mesh of
  // many blocks with holes (border edges), fins (non-manifold edges of three and four triangles)
  // whose triangles are far from the triangles they meet, and the triangles shuffled, so that an
  // edge's owner and its other halves lie in other blocks.
  const Mesh_data m = load("clean/fandisk.off.xz");
  std::vector<Point> points = m.points;
  std::vector<Triangle> triangles = m.triangles;
  soup_test::subdivide_midpoints(points, triangles);
  soup_test::subdivide_midpoints(points, triangles); // about 100,000 triangles: 7 blocks
  std::size_t fins = 0;
  const std::vector<Triangle> soup = with_holes_and_fins(points, triangles, fins);
  ASSERT_GT(soup.size(), 6 * ST::internal::default_block_size);
  ASSERT_GT(fins, 60u);
  const ST::Adjacency_tables input_tables(soup, points.size());
  ASSERT_GT(input_tables.non_manifold_edges().size(), 60u);
  ASSERT_GT(input_tables.number_of_border_edges(), 200u);
  auto ep = points;
  auto et = soup;
  ST::loop_subdivision(ep, et, CGAL::parameters::number_of_iterations(2));
  const auto expected_limit = bits(ST::loop_limit_points(points, soup));
  // level 0 itself, the second halves of crease edges included (which no rule reads)
  ST::internal::Loop_level expected_level;
  expected_level.initialize(input_tables);
  for_each_thread_count([&](int) {
    expect_parallel_level_0(input_tables, expected_level);
    auto p = points;
    auto t = soup;
    ST::loop_subdivision<Parallel>(p, t, CGAL::parameters::number_of_iterations(2));
    EXPECT_EQ(bits(p), bits(ep));
    EXPECT_EQ(t, et);
    EXPECT_EQ(bits(ST::loop_limit_points<Parallel>(points, soup)), expected_limit);
  });
}

// The ring rows of `level` (stored, or following from the level before) list, for every vertex,
// the edges whose other ends the sequential smoothing adds to it, in the order in which it adds
// them, with those other ends; returns the number of vertices whose row differs.
std::size_t ring_rows_unlike_sequential_sums(const ST::internal::Loop_level& level)
{
  using Level = ST::internal::Loop_level;
  using Kind = ST::internal::Loop_vertex_kind;
  const std::size_t n = level.kind.size();
  if(!level.has_ring_rows(n)) return n;
  std::vector<std::vector<std::pair<Level::Index, Level::Index>>> sums(n);
  for(Level::Index e = 0; e < level.number_of_edges; ++e) {
    const Level::Index a = level.first_vertex(e), b = level.second_vertex(e);
    const Kind kind_of_edge = level.is_crease(e) ? Kind::CREASE : Kind::SMOOTH;
    if(level.kind[a] == kind_of_edge) sums[a].push_back({e, b});
    if(level.kind[b] == kind_of_edge) sums[b].push_back({e, a});
  }
  std::size_t unlike = 0;
  for(std::size_t v = 0; v < n; ++v) {
    std::vector<std::pair<Level::Index, Level::Index>> row;
    level.for_each_ring_entry(static_cast<Level::Index>(v), [&](Level::Index edge, Level::Index other) {
      row.push_back({edge, other});
    });
    if(row != sums[v]) ++unlike;
  }
  return unlike;
}

// A container of triangles whose growth beyond `limit` fails, as a `resize()` does when the
// memory runs out.
struct Triangles_up_to_a_limit : std::vector<Triangle>
{
  std::size_t limit = 0;
  void reserve(std::size_t n)
  {
    if(n > limit) throw std::bad_alloc();
    std::vector<Triangle>::reserve(n);
  }
  void resize(std::size_t n)
  {
    if(n > limit) throw std::bad_alloc();
    std::vector<Triangle>::resize(n);
  }
};

TEST(ParallelLoopSubdivision, AFailedGrowthOfTheTrianglesLeavesTheSoupAsItWas)
{
  // The caller's triangles are grown beside the last level's smoothing on several threads: the
  // failure of that growth reaches the caller, and the points and triangles are those given.
  const Mesh_data m = load("clean/fandisk.off.xz");
  Triangles_up_to_a_limit given;
  given.assign(m.triangles.begin(), m.triangles.end());
  given.limit = 16 * given.size() - 1; // two levels need 16 times the triangles
  for_each_thread_count([&](int threads) {
    std::vector<Point> p = m.points;
    Triangles_up_to_a_limit t = given;
    EXPECT_THROW(ST::loop_subdivision<Parallel>(p, t, CGAL::parameters::number_of_iterations(2)), std::bad_alloc)
      << threads << " threads";
    EXPECT_EQ(bits(p), bits(m.points)) << threads << " threads";
    EXPECT_TRUE(static_cast<const std::vector<Triangle>&>(t) == m.triangles) << threads << " threads";
    // and with room enough, the subdivision of a plain vector
    t.limit = 16 * given.size();
    ST::loop_subdivision<Parallel>(p, t, CGAL::parameters::number_of_iterations(2));
    std::vector<Point> ep = m.points;
    std::vector<Triangle> et = m.triangles;
    ST::loop_subdivision(ep, et, CGAL::parameters::number_of_iterations(2));
    EXPECT_EQ(bits(p), bits(ep)) << threads << " threads";
    EXPECT_TRUE(static_cast<const std::vector<Triangle>&>(t) == et) << threads << " threads";
  });
}

TEST(ParallelLoopSubdivision, RingRowsListTheSequentialSumsAtEveryLevel)
{
  // The smoothing on several threads sums the ring of every vertex over its row: built at level 0
  // from the tables, carried to the next levels by refine(). Every row of levels 0 to 3 against
  // the sums of the sequential pass, on a mesh with borders, fins, creases and corners (level 3's
  // rows not stored: they follow from level 2's); then three levels of subdivision against the
  // sequential ones (the third reads the edges of level 1's rows).
  const Mesh_data m = load("clean/fandisk.off.xz");
  std::vector<Point> points = m.points;
  std::size_t fins = 0;
  const std::vector<Triangle> soup = with_holes_and_fins(points, m.triangles, fins);
  ASSERT_GT(fins, 10u);
  const ST::Adjacency_tables tables(soup, points.size());
  ASSERT_GT(tables.non_manifold_edges().size(), 10u);
  auto ep = points;
  auto et = soup;
  ST::loop_subdivision(ep, et, CGAL::parameters::number_of_iterations(3));
  for_each_thread_count([&](int) {
    ST::internal::Loop_level level;
    level.initialize<Parallel>(tables);
    level.build_ring_rows<Parallel>(tables);
    std::size_t kinds[3] = {0, 0, 0};
    for(const ST::internal::Loop_vertex_kind k : level.kind) ++kinds[std::size_t(k)];
    EXPECT_GT(kinds[std::size_t(ST::internal::Loop_vertex_kind::CREASE)], 40u);
    EXPECT_GT(kinds[std::size_t(ST::internal::Loop_vertex_kind::CORNER)], 10u);
    EXPECT_EQ(ring_rows_unlike_sequential_sums(level), 0u);
    for(int k = 1; k <= 3; ++k) {
      level.refine<Parallel>(level.kind.size(), k < 3);
      EXPECT_EQ(level.stores_ring_rows(level.kind.size()), k < 3) << "level " << k;
      EXPECT_EQ(ring_rows_unlike_sequential_sums(level), 0u) << "level " << k;
    }
    ASSERT_GT(level.number_of_edges, 2 * ST::internal::default_block_size); // refined by several blocks
    // rows that follow from the level before are not carried on: the next level has none
    ST::internal::Loop_level small;
    small.initialize<Parallel>(tables);
    small.build_ring_rows<Parallel>(tables);
    small.refine<Parallel>(small.kind.size(), false);
    EXPECT_TRUE(small.has_ring_rows(small.kind.size()));
    EXPECT_FALSE(small.stores_ring_rows(small.kind.size()));
    EXPECT_EQ(ring_rows_unlike_sequential_sums(small), 0u);
    small.refine<Parallel>(small.kind.size());
    EXPECT_FALSE(small.has_ring_rows(small.kind.size()));
    auto p = points;
    auto t = soup;
    ST::loop_subdivision<Parallel>(p, t, CGAL::parameters::number_of_iterations(3));
    EXPECT_EQ(bits(p), bits(ep));
    EXPECT_EQ(t, et);
  });
}

/// `triangles` with some repeated (in both orientations, some three times more), some reversed,
/// every triangle rotated, all shuffled.
std::vector<Triangle> with_repeats_and_reversals(const std::vector<Triangle>& triangles, unsigned seed)
{
  std::mt19937 rng(seed);
  std::vector<Triangle> out;
  for(Triangle t : triangles) {
    if(rng() % 3 == 0) std::swap(t[1], t[2]);
    out.push_back(t);
    if(rng() % 40 == 0) out.push_back(rng() % 2 ? t : Triangle{t[0], t[2], t[1]});
    if(rng() % 200 == 0)
      for(int k = 0; k < 3; ++k) out.push_back(k % 2 ? t : Triangle{t[0], t[2], t[1]});
  }
  shuffle_triangles(out, seed + 1);
  return out;
}

// The orientation of the soup with `np` on every thread count, with and without its tables at
// hand, against the sequential one: the same points bit for bit, triangles and counts. Returns
// the sequential report.
template <class NamedParameters>
ST::Orientation_report expect_orientation_as_sequential(const std::vector<Point>& points,
                                                        const std::vector<Triangle>& triangles,
                                                        const NamedParameters& np)
{
  auto ep = points;
  auto et = triangles;
  const ST::Orientation_report expected = ST::orient_triangle_soup(ep, et, np);
  const auto counts = [](const ST::Orientation_report& r) {
    return std::make_tuple(r.duplicate_triangles, r.orientation_flips, r.duplicated_points);
  };
  for_each_thread_count([&](int) {
    auto p = points;
    auto t = triangles;
    EXPECT_EQ(counts(ST::orient_triangle_soup<Parallel>(p, t, np)), counts(expected));
    EXPECT_EQ(bits(p), bits(ep));
    EXPECT_EQ(t, et);
    auto q = points;
    auto u = triangles;
    const ST::Adjacency_tables tables(u, q.size(), Parallel());
    EXPECT_EQ(counts(ST::internal::orient_triangle_soup_with_tables<Parallel>(q, u, &tables, np)), counts(expected));
    EXPECT_EQ(bits(q), bits(ep));
    EXPECT_EQ(u, et);
  });
  return expected;
}

TEST(ParallelRobustnessSoup, OrientationOverManyBlocksAndManyPatches)
{
  // A soup large enough for many blocks of triangles and of vertices: the repaired T-junction
  // soup of the elephant split twice, with repeated and reversed triangles; beside it 16 shells
  // of the elephant in pairs, one scaled by half about the centroid (mostly inside the other),
  // each reversed at random, and 3,000 loose triangles (patches of their own): many closed
  // patches whose volumes and nesting depths are computed per patch, many open ones. Every thread
  // count gives the sequential result, with and without the tables at hand.
  Mesh_data m = load("clean/elephant.off");
  const Mesh_data shell = m;
  soup_test::subdivide_midpoints(m.points, m.triangles);
  soup_test::subdivide_midpoints(m.points, m.triangles);
  auto soup = soup_test::t_junction_soup(m.points, m.triangles, 8, 1e-7 * diagonal(m.points) / std::sqrt(3.0), 5);
  ST::reconstruct_topology(soup.points, soup.triangles, CGAL::parameters::snapping_tolerance(1e-6 * diagonal(soup.points)));
  std::vector<Point> points = soup.points;
  std::vector<Triangle> triangles = with_repeats_and_reversals(soup.triangles, 31);
  std::mt19937 rng(37);
  const double d = diagonal(shell.points);
  double c[3] = {0, 0, 0};
  for(const Point& p : shell.points)
    for(int i = 0; i < 3; ++i) c[i] += p[i] / double(shell.points.size());
  for(int k = 0; k < 16; ++k) {
    const double scale = k % 2 ? 0.5 : 1.0, dx = 2 * d * (k / 2 + 1);
    const std::size_t offset = points.size();
    for(const Point& p : shell.points)
      points.emplace_back(c[0] + scale * (p.x() - c[0]) + dx, c[1] + scale * (p.y() - c[1]), c[2] + scale * (p.z() - c[2]));
    const bool reverse = rng() % 2 != 0;
    for(const Triangle& t : shell.triangles)
      triangles.push_back(reverse ? Triangle{t[0] + offset, t[2] + offset, t[1] + offset}
                                  : Triangle{t[0] + offset, t[1] + offset, t[2] + offset});
  }
  for(int k = 0; k < 3000; ++k) {
    const std::size_t offset = points.size();
    for(int i = 0; i < 3; ++i) points.emplace_back(-d - double(rng() % 1000), double(rng() % 1000), double(k));
    triangles.push_back({offset, offset + 1 + (k % 2), offset + 2 - (k % 2)});
  }
  ASSERT_GT(triangles.size(), 10 * ST::internal::default_block_size);
  for(const ST::Orientation_policy policy :
      {ST::Orientation_policy::BOUND_VOLUME, ST::Orientation_policy::KEEP_INPUT, ST::Orientation_policy::OUTWARD}) {
    SCOPED_TRACE("policy " + std::to_string(static_cast<int>(policy)));
    const auto np = ST::parameters::orientation_policy(policy);
    const ST::Orientation_report expected = expect_orientation_as_sequential(points, triangles, np);
    EXPECT_GT(expected.duplicate_triangles, 0u);
    EXPECT_GT(expected.orientation_flips, 0u);
  }
}

TEST(ParallelRobustnessSoup, OrientationOfNonOrientableAndFlatClosedPatches)
{
  // On several threads the patches are joined without being traversed; a patch is traversed
  // only where a decision follows the order of a traversal. This soup has them all: Moebius
  // strips (non-orientable: cut in a canonical traversal), one of them over several blocks;
  // flat closed pillows (a grid and a copy of it with its own inner points, the two sharing
  // their border) on a plane away from the origin, whose volume is 0 but sums to a few units in
  // the last place of either sign depending on the order (the sign of the volume in the order of
  // the traversal decides), one of them over several blocks; and cubes, two of them nested (the
  // winding numbers). Every triangle is reversed at random and the triangles are shuffled. Every
  // thread count gives the sequential result, with and without the tables, for each policy.
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  std::mt19937 rng(41);
  const auto point = [&](double x, double y, double z) {
    points.emplace_back(x, y, z);
    return points.size() - 1;
  };
  const auto add = [&](std::size_t a, std::size_t b, std::size_t c) {
    triangles.push_back(rng() % 2 ? Triangle{a, b, c} : Triangle{a, c, b});
  };
  const auto moebius = [&](double cx, int n) {
    std::vector<std::array<std::size_t, 2>> rung(static_cast<std::size_t>(n));
    for(int i = 0; i < n; ++i) {
      const double a = 2 * 3.14159265358979323846 * i / n;
      for(int side = 0; side < 2; ++side) {
        const double w = side ? 0.3 : -0.3, r = 2 + w * std::cos(a / 2);
        rung[std::size_t(i)][std::size_t(side)] = point(cx + r * std::cos(a), r * std::sin(a), w * std::sin(a / 2));
      }
    }
    for(int i = 0; i < n; ++i) {
      const auto& p = rung[std::size_t(i)];
      // the last rung meets the first one upside down: the half twist
      const std::array<std::size_t, 2> q =
        i + 1 < n ? rung[std::size_t(i + 1)] : std::array<std::size_t, 2>{rung[0][1], rung[0][0]};
      add(p[0], p[1], q[0]);
      add(p[1], q[1], q[0]);
    }
  };
  // a g x g grid on the plane through `o` spanned by u and v, its lower copy on the other
  // diagonals with inner points of its own; the volume terms of its triangles oriented alike
  // (before `add()` reverses some) summed into `sum` and `magnitude`
  double sum = 0, magnitude = 0;
  const auto pillow = [&](std::array<double, 3> o, int g) {
    const double u[3] = {0.31, 0.07, 0.13}, v[3] = {-0.05, 0.29, 0.11};
    std::vector<std::size_t> top, bottom;
    for(int j = 0; j <= g; ++j)
      for(int i = 0; i <= g; ++i) {
        const double x = o[0] + i * u[0] + j * v[0], y = o[1] + i * u[1] + j * v[1], z = o[2] + i * u[2] + j * v[2];
        top.push_back(point(x, y, z));
        const bool border = i == 0 || j == 0 || i == g || j == g;
        bottom.push_back(border ? top.back() : point(x, y, z));
      }
    const auto at = [&](const std::vector<std::size_t>& grid, int i, int j) {
      return grid[std::size_t(j * (g + 1) + i)];
    };
    const auto add_alike = [&](std::size_t a, std::size_t b, std::size_t c) {
      const double term = CGAL::to_double(CGAL::volume(Point(0, 0, 0), points[a], points[b], points[c]));
      sum += term;
      magnitude += std::abs(term);
      add(a, b, c);
    };
    sum = magnitude = 0;
    for(int j = 0; j < g; ++j)
      for(int i = 0; i < g; ++i) {
        add_alike(at(top, i, j), at(top, i + 1, j), at(top, i + 1, j + 1));
        add_alike(at(top, i, j), at(top, i + 1, j + 1), at(top, i, j + 1));
        add_alike(at(bottom, i, j), at(bottom, i, j + 1), at(bottom, i + 1, j));
        add_alike(at(bottom, i + 1, j), at(bottom, i, j + 1), at(bottom, i + 1, j + 1));
      }
  };
  const auto cube = [&](double x, double y, double z, double side) {
    std::array<std::size_t, 8> c;
    for(int k = 0; k < 8; ++k)
      c[std::size_t(k)] = point(x + side * (k & 1), y + side * ((k >> 1) & 1), z + side * ((k >> 2) & 1));
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for(const auto& q : quads) {
      add(c[std::size_t(q[0])], c[std::size_t(q[1])], c[std::size_t(q[2])]);
      add(c[std::size_t(q[0])], c[std::size_t(q[2])], c[std::size_t(q[3])]);
    }
  };
  moebius(0, 12000);
  for(int k = 0; k < 40; ++k) moebius(10 + 6 * k, 10 + k % 7);
  const std::size_t big_pillow_begin = triangles.size();
  pillow({{1000.3, -7.1, 3.3}}, 100);
  const std::size_t big_pillow_end = triangles.size();
  // Its volume, summed in the order of construction, is a cancellation that decides no sign.
  EXPECT_GT(magnitude, 1e3);
  EXPECT_FALSE(ST::internal::sum_has_certain_sign(sum, magnitude, big_pillow_end - big_pillow_begin));
  for(int k = 0; k < 60; ++k) pillow({{-500.7 - 9 * k, 13.9 + k, 101.1}}, 2 + k % 3);
  for(int k = 0; k < 30; ++k) cube(3000 + 3 * k, 0, 0, 1);
  cube(4000, 0, 0, 10);
  cube(4003, 3, 3, 2);
  ASSERT_GT(big_pillow_end - big_pillow_begin, 2 * ST::internal::default_block_size);
  shuffle_triangles(triangles, 43);
  for(const ST::Orientation_policy policy :
      {ST::Orientation_policy::BOUND_VOLUME, ST::Orientation_policy::KEEP_INPUT, ST::Orientation_policy::OUTWARD}) {
    SCOPED_TRACE("policy " + std::to_string(static_cast<int>(policy)));
    const auto np = ST::parameters::orientation_policy(policy);
    const ST::Orientation_report expected = expect_orientation_as_sequential(points, triangles, np);
    EXPECT_GT(expected.duplicated_points, 0u); // the Moebius strips' cuts leave vertices of two fans
  }
}

TEST(ParallelOrientation, VolumeSignsCertainInOneOrderAreTheSignsOfEveryOrder)
{
  // Terms that cancel to various degrees, summed in several orders: whenever the sum in one
  // order is certain (`sum_has_certain_sign()`), every order gives a sum of the same sign, not 0;
  // a sum of pairs that cancel exactly is never certain.
  std::mt19937_64 rng(47);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::size_t certain = 0, uncertain = 0;
  for(int trial = 0; trial < 400; ++trial) {
    const std::size_t count = 2 + rng() % 3000;
    std::vector<double> terms(count);
    for(double& x : terms) x = unit(rng) * std::ldexp(1.0, int(rng() % 60) - 30);
    // shift the total towards 0 by a remainder of the trial's own scale
    double exact_shift = 0;
    for(double x : terms) exact_shift += x;
    terms.push_back(-exact_shift + unit(rng) * std::ldexp(1.0, -int(rng() % 80)));
    std::vector<double> sums;
    double magnitude = 0;
    for(double x : terms) magnitude += std::abs(x);
    for(int order = 0; order < 4; ++order) {
      if(order == 1) std::sort(terms.begin(), terms.end());
      if(order == 2) std::reverse(terms.begin(), terms.end());
      if(order == 3) std::shuffle(terms.begin(), terms.end(), rng);
      double sum = 0;
      for(double x : terms) sum += x;
      sums.push_back(sum);
    }
    for(double sum : sums) {
      if(!ST::internal::sum_has_certain_sign(sum, magnitude, terms.size())) {
        ++uncertain;
        continue;
      }
      ++certain;
      for(double other : sums) EXPECT_EQ(other < 0, sum < 0) << trial;
      for(double other : sums) EXPECT_NE(other, 0.0) << trial;
    }
    std::vector<double> pairs;
    for(std::size_t k = 0; k < count; ++k) {
      pairs.push_back(terms[k]);
      pairs.push_back(-terms[k]);
    }
    std::shuffle(pairs.begin(), pairs.end(), rng);
    double sum = 0, pair_magnitude = 0;
    for(double x : pairs) {
      sum += x;
      pair_magnitude += std::abs(x);
    }
    EXPECT_FALSE(ST::internal::sum_has_certain_sign(sum, pair_magnitude, pairs.size())) << trial;
  }
  EXPECT_GT(certain, 100u);
  EXPECT_GT(uncertain, 100u);
}

TEST(ParallelSTL, WriteTheSameBytesAndRefusals)
{
  Mesh_data m = load("clean/elephant.off");
  soup_test::subdivide_midpoints(m.points, m.triangles);
  soup_test::subdivide_midpoints(m.points, m.triangles);
  ASSERT_GT(m.triangles.size(), std::size_t(1) << 16); // more than one chunk
  m.triangles.push_back(m.triangles[5]);
  for(int k = 0; k < 3; ++k) m.points.push_back(Point(20 + k, 20, 0)); // collinear: degenerate already
  m.triangles.push_back({m.points.size() - 3, m.points.size() - 2, m.points.size() - 1});
  const auto write = [](const auto& points, const auto& triangles, auto tag) {
    std::ostringstream out(std::ios::binary);
    ST::IO::write_triangle_soup<decltype(tag)>(out, "stl", points, triangles);
    return out.str();
  };
  const std::string expected = write(m.points, m.triangles, CGAL::Sequential_tag());
  ASSERT_EQ(expected.size(), 84 + 50 * m.triangles.size());
  std::vector<Epeck::Point_3> exact;
  for(const Point& p : m.points) exact.emplace_back(p.x(), p.y(), p.z());
  const auto refusal = [](const std::vector<Point>& points, const std::vector<Triangle>& triangles, auto tag) {
    try {
      std::ostringstream out(std::ios::binary);
      ST::IO::write_STL_triangle_soup<decltype(tag)>(out, points, triangles);
    } catch(const ST::IO::Write_error& e) {
      return std::string(e.what());
    }
    return std::string("not refused");
  };
  // a triangle late in the range that becomes degenerate in float (its apex 1e-9 off the line of
  // its base, at coordinates near 10), then also a point beyond the float range
  std::vector<Point> degenerate = m.points;
  std::vector<Triangle> with_sliver = m.triangles;
  degenerate.push_back(Point(10, 10, 0));
  degenerate.push_back(Point(11, 10, 0));
  degenerate.push_back(Point(10.5, 10 + 1e-9, 0));
  with_sliver.insert(with_sliver.end() - 1000, Triangle{degenerate.size() - 3, degenerate.size() - 2, degenerate.size() - 1});
  std::vector<Point> beyond = degenerate;
  beyond[m.points.size() - 10] = Point(1e39, 0, 0);
  for_each_thread_count([&](int) {
    EXPECT_EQ(write(m.points, m.triangles, Parallel()), expected);
    EXPECT_EQ(write(exact, m.triangles, Parallel()), expected);
    const std::string sliver = refusal(degenerate, with_sliver, Parallel());
    EXPECT_EQ(sliver, refusal(degenerate, with_sliver, CGAL::Sequential_tag()));
    EXPECT_NE(sliver.find("triangle " + std::to_string(with_sliver.size() - 1001) + " "), std::string::npos) << sliver;
    EXPECT_NE(sliver.find("becomes degenerate in float"), std::string::npos) << sliver;
    const std::string infinite = refusal(beyond, with_sliver, Parallel());
    EXPECT_EQ(infinite, refusal(beyond, with_sliver, CGAL::Sequential_tag()));
    EXPECT_NE(infinite.find("point " + std::to_string(m.points.size() - 10) + " "), std::string::npos) << infinite;
  });
}

TEST(ParallelSTL, BinaryDecode)
{
  // A binary STL made in memory from the subdivided elephant (many blocks), and the pig's file.
  Mesh_data m = load("clean/elephant.off");
  soup_test::subdivide_midpoints(m.points, m.triangles);
  std::string bytes(80, '\0');
  const std::uint32_t n = static_cast<std::uint32_t>(m.triangles.size());
  bytes.append(reinterpret_cast<const char*>(&n), 4);
  for(const Triangle& t : m.triangles) {
    float f[12] = {};
    for(std::size_t k = 0; k < 3; ++k)
      for(int c = 0; c < 3; ++c) f[3 + 3 * k + std::size_t(c)] = static_cast<float>(m.points[t[k]][c]);
    bytes.append(reinterpret_cast<const char*>(f), sizeof f);
    bytes.append(2, '\0');
  }
  for(const std::string& file : {bytes, ST::IO::read_file_contents(soup_test::data_file("cgal_repair/pig.stl.xz"))}) {
    std::vector<std::array<Point, 3>> expected;
    ST::IO::read_STL_triangles(file, expected);
    for_each_thread_count([&](int) {
      std::vector<std::array<Point, 3>> read;
      ST::IO::read_STL_triangles<Parallel>(file, read);
      ASSERT_EQ(read.size(), expected.size());
      std::vector<Point> a, b;
      for(std::size_t i = 0; i < read.size(); ++i)
        for(std::size_t k = 0; k < 3; ++k) {
          a.push_back(read[i][k]);
          b.push_back(expected[i][k]);
        }
      EXPECT_EQ(bits(a), bits(b));
    });
  }
}

TEST(ParallelSTL, ReadTriangleSoupOfEveryFormat)
{
  // The reader's checks and exact weld on TBB's threads: the points, the triangles and the report
  // of the sequential reader, for a binary STL of many blocks (the subdivided elephant, exploded
  // into facets, with a few repeated facets) and a file of every format.
  Mesh_data m = load("clean/elephant.off");
  soup_test::subdivide_midpoints(m.points, m.triangles);
  std::string stl(80, '\0');
  const std::uint32_t n = static_cast<std::uint32_t>(m.triangles.size() + m.triangles.size() / 100);
  stl.append(reinterpret_cast<const char*>(&n), 4);
  for(std::size_t i = 0; i < n; ++i) {
    const Triangle& t = m.triangles[i < m.triangles.size() ? i : 100 * (i - m.triangles.size())];
    float f[12] = {};
    for(std::size_t k = 0; k < 3; ++k)
      for(int c = 0; c < 3; ++c) f[3 + 3 * k + std::size_t(c)] = static_cast<float>(m.points[t[k]][c]);
    stl.append(reinterpret_cast<const char*>(f), sizeof f);
    stl.append(2, '\0');
  }
  std::vector<std::pair<std::string, std::string>> files{{"stl", stl}};
  for(const char* file : {"cgal_repair/pig.stl.xz", "real_defects/openscad/bad-stl-tardis.stl", "clean/elephant.off",
                          "cgal_repair/quads_to_stitch.off", "cad/kicad/SOT-23.wrl", "cad/kicad/TO-220-3_Vertical.wrl"})
  {
    const std::string path = soup_test::data_file(file);
    files.emplace_back(ST::IO::file_extension(path), ST::IO::read_file_contents(path));
  }
  const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\nf 4 5 3\n";
  files.emplace_back("obj", obj);
  files.emplace_back("ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                            "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
                            "0 0 0\n1 0 0\n0 1 0\n1 0 0\n3 0 1 2\n3 3 2 0\n");
  const auto fields = [](const ST::IO::Soup_read_report& r) {
    return std::make_tuple(r.format, r.input_polygons, r.input_vertices, r.input_triangles, r.skipped_polygons,
                           r.non_convex_polygons, r.exact_duplicates, r.collapsed_triangles);
  };
  for(const auto& file : files) {
    // (named references, not a structured binding: C++17 does not let a lambda capture one)
    const std::string& format = file.first;
    const std::string& bytes = file.second;
    SCOPED_TRACE(format + ", " + std::to_string(bytes.size()) + " bytes");
    std::vector<Point> expected_points;
    std::vector<Triangle> expected_triangles;
    const ST::IO::Soup_read_report expected =
      ST::IO::read_triangle_soup(bytes.data(), bytes.size(), format, expected_points, expected_triangles);
    ASSERT_FALSE(expected_triangles.empty());
    for_each_thread_count([&](int) {
      std::vector<Point> points;
      std::vector<Triangle> triangles;
      const ST::IO::Soup_read_report r =
        ST::IO::read_triangle_soup<Parallel>(bytes.data(), bytes.size(), format, points, triangles);
      EXPECT_EQ(fields(r), fields(expected));
      EXPECT_EQ(bits(points), bits(expected_points));
      EXPECT_EQ(triangles, expected_triangles);
    });
  }
  // A non-finite corner: the first one is named, whatever the threads.
  std::string bad = stl;
  const float nan = std::nanf("");
  const std::size_t first_bad = n / 2 + 7;
  for(const std::size_t facet : {first_bad, std::size_t(n) - 5})
    std::memcpy(&bad[84 + 50 * facet + 12 + 4 * 4], &nan, 4);
  for_each_thread_count([&](int) {
    std::vector<Point> points;
    std::vector<Triangle> triangles;
    try {
      ST::IO::read_triangle_soup<Parallel>(bad.data(), bad.size(), "stl", points, triangles, "bad.stl");
      ADD_FAILURE() << "no exception";
    } catch(const ST::Invalid_input& e) {
      EXPECT_EQ(std::string(e.what()), "bad.stl: facet " + std::to_string(first_bad) + " has a non-finite coordinate");
    }
  });
}

TEST(ParallelIndexTriangles, EmptyAndTinySoups)
{
  using Soup = std::vector<std::array<Point, 3>>;
  expect_same_index(Soup());
  expect_same_index(Soup(1, std::array<Point, 3>{Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0)}));
  expect_same_index(Soup(1, std::array<Point, 3>{Point(0, 0, 0), Point(0, 0, 0), Point(0, 1, 0)}));
}

// --- the gap analysis, and the octree's concurrent searches -------------------------------------

std::uint64_t bits(double x)
{
  std::uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}

std::vector<std::uint64_t> bits(const std::vector<double>& values)
{
  std::vector<std::uint64_t> result(values.size());
  if(!values.empty()) std::memcpy(result.data(), values.data(), values.size() * sizeof(double));
  return result;
}

auto fields(const ST::Size_distribution& d) { return std::make_tuple(d.count, d.minimum, d.median, d.maximum); }

std::vector<std::tuple<double, double, std::size_t>> bins(const std::vector<ST::Gap_histogram_bin>& h)
{
  std::vector<std::tuple<double, double, std::size_t>> result;
  for(const ST::Gap_histogram_bin& b : h) result.emplace_back(b.lower, b.upper, b.count);
  return result;
}

void expect_same_analysis(const ST::Gap_analysis& a, const ST::Gap_analysis& e)
{
  EXPECT_EQ(std::make_tuple(a.vertices, a.triangles, a.border_edges, a.border_vertices, a.degenerate_triangles,
                            a.gaps_beyond_search_radius, a.zero_gaps, a.verdict, a.closed_gaps),
            std::make_tuple(e.vertices, e.triangles, e.border_edges, e.border_vertices, e.degenerate_triangles,
                            e.gaps_beyond_search_radius, e.zero_gaps, e.verdict, e.closed_gaps));
  EXPECT_EQ(bits(std::vector<double>{a.bounding_box_diagonal, a.search_radius, a.feature_bound, a.suggested_tolerance,
                                     a.largest_closed_gap, a.smallest_open_gap, a.closing_margin, a.keeping_margin}),
            bits(std::vector<double>{e.bounding_box_diagonal, e.search_radius, e.feature_bound, e.suggested_tolerance,
                                     e.largest_closed_gap, e.smallest_open_gap, e.closing_margin, e.keeping_margin}));
  EXPECT_EQ(bits(a.gaps), bits(e.gaps));
  EXPECT_EQ(bins(a.gap_histogram), bins(e.gap_histogram));
  EXPECT_EQ(bins(a.feature_histogram), bins(e.feature_histogram));
  EXPECT_EQ(fields(a.shortest_edges), fields(e.shortest_edges));
  EXPECT_EQ(fields(a.smallest_heights), fields(e.smallest_heights));
  EXPECT_EQ(fields(a.border_features), fields(e.border_features));
  EXPECT_EQ(a.reasoning, e.reasoning);
}

/// the nearest border element of every border vertex, as (distance bits, vertex, triangle, index).
std::vector<std::tuple<std::uint64_t, std::size_t, std::size_t, int>>
nearest_elements(const ST::internal::Nearest_border_elements& nearest)
{
  std::vector<std::tuple<std::uint64_t, std::size_t, std::size_t, int>> result;
  for(const ST::internal::Nearest_border_element& e : nearest)
    result.emplace_back(bits(e.distance), e.vertex, std::size_t(e.edge.triangle), e.edge.index);
  return result;
}

/// every corner of `m` its own point, moved by up to `jitter` times the diagonal (0: not moved,
/// the exact weld then merges the copies back).
Mesh_data jittered_exploded(const Mesh_data& m, double jitter, unsigned seed)
{
  Mesh_data out;
  std::mt19937 rng(seed);
  const double j = jitter * diagonal(m.points);
  std::uniform_real_distribution<double> move(-j, j);
  for(const Triangle& t : m.triangles) {
    for(std::size_t k = 0; k < 3; ++k) {
      const Point& p = m.points[t[k]];
      out.points.emplace_back(p.x() + move(rng), p.y() + move(rng), p.z() + move(rng));
    }
    out.triangles.push_back({out.points.size() - 3, out.points.size() - 2, out.points.size() - 1});
  }
  return out;
}

class ParallelGapAnalysisOfMesh : public ::testing::TestWithParam<const char*> {};

TEST_P(ParallelGapAnalysisOfMesh, RealMeshAndItsJitteredExplodedSoup)
{
  const Mesh_data m = load(GetParam());
  for(const double jitter : {0.0, 1e-6}) {
    SCOPED_TRACE("jitter " + std::to_string(jitter));
    Mesh_data soup = jitter == 0 ? m : jittered_exploded(m, jitter, 19);
    shuffle_triangles(soup.triangles, 23);
    const ST::Gap_analysis expected = ST::analyze_gaps(soup.points, soup.triangles);
    for_each_thread_count([&](int) { expect_same_analysis(ST::analyze_gaps<Parallel>(soup.points, soup.triangles), expected); });
  }
}

INSTANTIATE_TEST_SUITE_P(Meshes, ParallelGapAnalysisOfMesh, ::testing::ValuesIn(real_meshes));

// An exploded grid whose copies lie at heights that are multiples of 2^-10 (exact in double): a
// border vertex is at exactly the same distance from several copies and several border edges,
// and the answer is decided by the tie-breaks (smaller vertex index, vertex before edge, earlier
// edge), which must not depend on which thread offers which candidate first.
TEST(ParallelGapAnalysis, TiesAreBrokenAsSequentially)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  const int n = 64;
  for(int i = 0; i < n; ++i)
    for(int j = 0; j < n; ++j)
      for(int half = 0; half < 2; ++half) {
        const std::size_t t = triangles.size();
        const double z = double(t % 3) * 0x1.0p-10;
        const std::array<std::array<int, 2>, 3> corners =
          half == 0 ? std::array<std::array<int, 2>, 3>{{{i, j}, {i + 1, j}, {i + 1, j + 1}}}
                    : std::array<std::array<int, 2>, 3>{{{i, j}, {i + 1, j + 1}, {i, j + 1}}};
        for(const auto& c : corners) points.emplace_back(double(c[0]), double(c[1]), z);
        triangles.push_back({points.size() - 3, points.size() - 2, points.size() - 1});
      }
  // The exact weld of the analysis merges the copies at one height: index them as it does.
  std::vector<Point> welded;
  std::vector<Triangle> indexed;
  ST::index_triangles(soup_test::explode(points, triangles), welded, indexed);
  const ST::Adjacency_tables tables(indexed, welded.size());
  const std::vector<std::size_t> border = ST::internal::border_vertices(tables);
  ASSERT_GT(border.size(), 10000u);
  const auto expected = nearest_elements(ST::internal::nearest_border_elements(welded, tables, border, 2.0, Epick()));
  std::size_t ties = 0;
  for(const auto& e : expected) ties += std::get<0>(e) == bits(0x1.0p-10);
  EXPECT_GT(ties, border.size() / 2);
  for_each_thread_count([&](int) {
    EXPECT_EQ(nearest_elements(ST::internal::nearest_border_elements<Parallel>(welded, tables, border, 2.0, Epick())),
              expected);
    expect_same_analysis(ST::analyze_gaps<Parallel>(points, triangles), ST::analyze_gaps(points, triangles));
  });
}

// A border vertex exactly between two border edges, nearer to both than to any vertex: the
// answer is the edge of the earlier triangle. The edge of the later triangle is met first in
// Morton order (its first end has the smaller address), so an answer kept by arrival order would
// be the later edge. The pattern is repeated over a grid, in many blocks of the searches.
TEST(ParallelGapAnalysis, EqualEdgesAreBrokenByTheirOrder)
{
  const double h = 0x1.0p-10;
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  const auto add = [&](const Point& a, const Point& b, const Point& c) {
    points.push_back(a);
    points.push_back(b);
    points.push_back(c);
    triangles.push_back({points.size() - 3, points.size() - 2, points.size() - 1});
  };
  const int n = 40;
  for(int i = 0; i < n; ++i)
    for(int j = 0; j < n; ++j) {
      const double x = 10.0 * i, y = 10.0 * j;
      add(Point(x + 2, y, h), Point(x - 2, y, h), Point(x, y, 1));       // border edge 0 above v
      add(Point(x - 2, y, -h), Point(x + 2, y, -h), Point(x, y, -1));    // border edge 0 below v
      add(Point(x, y, 0), Point(x, y - 3, 0), Point(x + 1, y - 3, 0));   // v = (x, y, 0)
    }
  const ST::Adjacency_tables tables(triangles, points.size());
  const std::vector<std::size_t> border = ST::internal::border_vertices(tables);
  ASSERT_EQ(border.size(), points.size());
  const auto sequential = ST::internal::nearest_border_elements(points, tables, border, 0.5, Epick());
  for(std::size_t p = 0; p < triangles.size(); p += 3) {
    const ST::internal::Nearest_border_element& e = sequential[triangles[p + 2][0]];
    EXPECT_EQ(std::make_tuple(e.distance, e.vertex, std::size_t(e.edge.triangle), e.edge.index),
              std::make_tuple(h, static_cast<std::size_t>(-1), p, 0));
  }
  for_each_thread_count([&](int) {
    EXPECT_EQ(nearest_elements(ST::internal::nearest_border_elements<Parallel>(points, tables, border, 0.5, Epick())),
              nearest_elements(sequential));
  });
}

// With an exact kernel the measures that compare or construct points are sequential (lazily
// exact numbers share state between points): the same analysis, without a race.
TEST(ParallelGapAnalysis, ExactKernel)
{
  const Mesh_data m = load("cad/ALSTOM_TEST4.off");
  std::vector<Epeck::Point_3> points;
  for(const Point& p : m.points) points.emplace_back(p.x(), p.y(), p.z());
  const ST::Gap_analysis expected = ST::analyze_gaps(points, m.triangles);
  EXPECT_EQ(expected.verdict, ST::Gap_verdict::SUGGESTED) << expected.reasoning;
  for_each_thread_count([&](int) { expect_same_analysis(ST::analyze_gaps<Parallel>(points, m.triangles), expected); });
}

TEST(ParallelGapAnalysis, SortSizesIsStdSort)
{
  std::mt19937_64 rng(3);
  for(const std::size_t n : {std::size_t(10), std::size_t(70000), std::size_t(300000)}) {
    std::vector<double> sizes(n);
    for(std::size_t i = 0; i < n; ++i) {
      const std::uint64_t r = rng();
      // repeated values, zeros, tiny and huge magnitudes
      sizes[i] = r % 7 == 0 ? 0.0 : r % 5 == 0 ? 1.5 : std::ldexp(double(r >> 40), int(r % 200) - 100);
    }
    std::vector<double> expected = sizes;
    std::sort(expected.begin(), expected.end());
    for_each_thread_count([&](int) {
      std::vector<double> sorted = sizes;
      ST::internal::sort_sizes<Parallel>(sorted);
      EXPECT_EQ(bits(sorted), bits(expected));
    });
    // a negative zero or a negative value: the comparison sort, whose result is kept
    sizes[n / 2] = -0.0;
    sizes[n / 3] = -2.0;
    expected = sizes;
    std::sort(expected.begin(), expected.end());
    std::vector<double> sorted = sizes;
    ST::internal::sort_sizes<Parallel>(sorted);
    EXPECT_EQ(bits(sorted), bits(expected));
  }
}

#if !defined(__SANITIZE_THREAD__) && !defined(__SANITIZE_ADDRESS__)
// The candidates are counted by all the threads together: a border too crowded to analyse is
// refused as sequentially (the soup of GapAnalysis.CrowdedBordersStopAtTheCandidateBudget).
TEST(ParallelGapAnalysis, CrowdedBordersAreRefusedOnAnyNumberOfThreads)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  soup_test::crowded_scattered_soup(20000, points, triangles);
  std::string expected;
  try {
    ST::analyze_gaps(points, triangles);
  } catch(const ST::Invalid_input& e) {
    expected = e.what();
  }
  ASSERT_NE(expected.find("too crowded"), std::string::npos) << expected;
  try {
    ST::analyze_gaps<Parallel>(points, triangles);
    ADD_FAILURE() << "not refused";
  } catch(const ST::Invalid_input& e) {
    EXPECT_EQ(std::string(e.what()), expected);
  }
}
#endif

// The octree built on TBB's threads is the sequential tree: the same workspace, nodes, leaves,
// order of the points and the same first non-finite point named.
template <class Kernel>
void expect_same_tree(const ST::Octree<Kernel>& a, const ST::Octree<Kernel>& b, std::size_t n)
{
  EXPECT_EQ(bits(std::vector<double>{a.workspace_origin()[0], a.workspace_origin()[1], a.workspace_origin()[2],
                                     a.workspace_side()}),
            bits(std::vector<double>{b.workspace_origin()[0], b.workspace_origin()[1], b.workspace_origin()[2],
                                     b.workspace_side()}));
  ASSERT_EQ(a.number_of_nodes(), b.number_of_nodes());
  std::size_t different = 0;
  for(std::uint32_t node = 0; node < a.number_of_nodes(); ++node) {
    const auto pa = a.points(node), pb = b.points(node);
    different += a.is_leaf(node) != b.is_leaf(node) || a.depth(node) != b.depth(node) ||
                 !std::equal(pa.begin(), pa.end(), pb.begin(), pb.end());
  }
  for(std::size_t i = 0; i < n; ++i)
    different += a.morton_code(i) != b.morton_code(i) || a.leaf(i) != b.leaf(i) || !(a.point(i) == b.point(i));
  EXPECT_EQ(different, 0u);
}

TEST(ParallelOctree, BuildGivesTheSequentialTree)
{
  // More than 2^20 points (the parallel radix sort), and a small cloud with duplicates and zeros
  // of both signs on an extreme coordinate (the box put together from the blocks' boxes).
  Mesh_data m = load("clean/elephant.off");
  for(int level = 0; level < 3; ++level) soup_test::subdivide_midpoints(m.points, m.triangles);
  const Mesh_data soup = jittered_exploded(m, 1e-6, 31);
  ASSERT_GT(soup.points.size(), std::size_t(1) << 20);
  std::vector<Point> small;
  std::mt19937 rng(5);
  for(int i = 0; i < 50000; ++i)
    small.emplace_back(i % 7 == 0 ? -0.0 : double(rng() % 100), i % 11 == 0 ? 0.0 : double(rng() % 3), double(rng() % 1000) / 7);
  // The nodes split by subtrees: three tight clusters and a few points far apart, whose 64
  // subtrees are found deep below chains of single nodes; three small clusters, which never give
  // 64 subtrees at one level (the subtrees are those of the deepest level with nodes to split);
  // a few points, one leaf (no subtree).
  const auto clustered = [&](int size) {
    std::vector<Point> out;
    for(int c = 0; c < 3; ++c)
      for(int i = 0; i < size; ++i)
        out.emplace_back(c + 1e-7 * double(rng() % 1000), 2 * c + 1e-7 * double(rng() % 1000),
                         1e-7 * double(rng() % 1000));
    for(int i = 0; i < 5; ++i) out.emplace_back(100.0 * i, -50.0, 3.0 * i);
    return out;
  };
  const std::vector<Point> clusters = clustered(4000), small_clusters = clustered(40);
  const std::vector<Point> one_leaf(small.begin(), small.begin() + 7);
  const std::vector<Point>& small_cloud = small;
  for(const std::vector<Point>* points : {&soup.points, &small_cloud, &clusters, &small_clusters, &one_leaf}) {
    SCOPED_TRACE(points->size());
    const ST::Octree<Epick> expected(*points);
    const ST::Octree<Epick> expected_np(*points, ST::parameters::bucket_capacity(32));
    for_each_thread_count([&](int) {
      const ST::Octree<Epick> tree(*points, CGAL::Identity_property_map<Point>(), Epick(), Parallel());
      expect_same_tree(tree, expected, points->size());
      const ST::Octree<Epick> tree_np(*points, ST::parameters::bucket_capacity(32), Parallel());
      expect_same_tree(tree_np, expected_np, points->size());
    });
  }
  // Exact coordinates: built sequentially whatever the tag, the same tree.
  std::vector<Epeck::Point_3> exact;
  for(std::size_t i = 0; i < 5000; ++i) exact.emplace_back(small[i].x(), small[i].y(), small[i].z());
  const ST::Octree<Epeck> exact_expected(exact);
  const ST::Octree<Epeck> exact_tree(exact, CGAL::Identity_property_map<Epeck::Point_3>(), Epeck(), Parallel());
  expect_same_tree(exact_tree, exact_expected, exact.size());
  // The first non-finite point is named, whatever the threads.
  std::vector<Point> bad = soup.points;
  bad[700000] = Point(0, std::nan(""), 0);
  bad[900000] = Point(HUGE_VAL, 0, 0);
  for_each_thread_count([&](int) {
    try {
      const ST::Octree<Epick> tree(bad, CGAL::Identity_property_map<Point>(), Epick(), Parallel());
      ADD_FAILURE() << "no exception";
    } catch(const ST::Invalid_input& e) {
      EXPECT_EQ(std::string(e.what()), "Soup_topology::Octree: point 700000 has a non-finite coordinate");
    }
  });
}

// The concurrent searches of the octree hand over the answers of the sequential ones: each
// point's neighbourhood, each segment's, exactly once.
TEST(ParallelOctree, ConcurrentSearchesGiveTheSequentialAnswers)
{
  const Mesh_data m = load("clean/elephant.off");
  const Mesh_data soup = jittered_exploded(m, 1e-5, 29);
  const double r = 1e-3 * diagonal(soup.points);
  const ST::Octree<Epick> tree(soup.points);
  std::vector<std::vector<std::size_t>> expected(soup.points.size());
  tree.for_each_neighborhood(r, [&](std::size_t k, const std::vector<std::size_t>& near) { expected[k] = near; });
  std::vector<std::array<std::size_t, 2>> segments;
  for(const Triangle& t : soup.triangles) segments.push_back({t[0], t[1]});
  segments.push_back({0, 0}); // a segment of one point: a radius query
  std::vector<std::vector<std::size_t>> expected_segments(segments.size());
  tree.for_each_segment_neighborhood(segments, r, [&](std::size_t s, const std::vector<std::size_t>& near) {
    expected_segments[s] = near;
  });
  std::vector<std::vector<std::size_t>> expected_in_tree_order(soup.points.size());
  tree.for_each_neighborhood(r, [&](std::size_t k, const std::vector<std::size_t>& near) { expected_in_tree_order[k] = near; },
                             ST::Neighborhood_order::TREE);
  std::vector<std::vector<std::size_t>> expected_segments_in_tree_order(segments.size());
  tree.for_each_segment_neighborhood(segments, r, [&](std::size_t s, const std::vector<std::size_t>& near) {
    expected_segments_in_tree_order[s] = near;
  }, ST::Neighborhood_order::TREE);
  for(std::size_t k = 0; k < expected.size(); ++k) {
    std::vector<std::size_t> sorted = expected_in_tree_order[k];
    std::sort(sorted.begin(), sorted.end());
    ASSERT_EQ(sorted, expected[k]) << k;
  }
  for_each_thread_count([&](int) {
    std::vector<std::vector<std::size_t>> found(soup.points.size());
    std::vector<std::atomic<int>> calls(soup.points.size());
    tree.for_each_neighborhood_concurrently<Parallel>(r, [&](std::size_t k, const std::vector<std::size_t>& near) {
      ++calls[k];
      found[k] = near;
    });
    EXPECT_EQ(found, expected);
    EXPECT_TRUE(std::all_of(calls.begin(), calls.end(), [](const std::atomic<int>& c) { return c == 1; }));
    std::vector<std::vector<std::size_t>> found_segments(segments.size());
    tree.for_each_segment_neighborhood_concurrently<Parallel>(segments, r, [&](std::size_t s, const std::vector<std::size_t>& near) {
      found_segments[s] = near;
    });
    EXPECT_EQ(found_segments, expected_segments);
    // unsorted: the order of the sequential search in the tree's order, on any number of threads
    std::vector<std::vector<std::size_t>> found_in_tree_order(soup.points.size());
    tree.for_each_neighborhood_concurrently<Parallel>(r, [&](std::size_t k, const std::vector<std::size_t>& near) {
      found_in_tree_order[k] = near;
    }, ST::Neighborhood_order::TREE);
    EXPECT_EQ(found_in_tree_order, expected_in_tree_order);
    std::vector<std::vector<std::size_t>> segments_in_tree_order(segments.size());
    tree.for_each_segment_neighborhood_concurrently<Parallel>(segments, r, [&](std::size_t s, const std::vector<std::size_t>& near) {
      segments_in_tree_order[s] = near;
    }, ST::Neighborhood_order::TREE);
    EXPECT_EQ(segments_in_tree_order, expected_segments_in_tree_order);
  });
}

} // namespace
