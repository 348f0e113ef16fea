// Copyright (c) 2024 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Tests of <Soup_topology/Octree.h>: cross-checks against brute force, properties, bad input.

#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/Octree.h>

#include "test_utilities.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/property_map.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

// The names of this file live in a namespace of its own: test/CMakeLists.txt compiles several
// test files as one translation unit.
namespace Octree_test {

namespace ST = Soup_topology;

using SC = CGAL::Simple_cartesian<double>;
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;

namespace {

// ---------------------------------------------------------------------------------------------
// brute force

template <typename K>
std::vector<std::size_t> brute_near_point(const std::vector<typename K::Point_3>& pts,
                                          const typename K::Point_3& q, const typename K::FT& r)
{
  const typename K::FT r2 = r * r;
  std::vector<std::size_t> res;
  for(std::size_t i = 0; i < pts.size(); ++i)
    if(K().compare_squared_distance_3_object()(q, pts[i], r2) != CGAL::LARGER)
      res.push_back(i);
  return res;
}

template <typename K>
std::optional<std::size_t> brute_nearest(const std::vector<typename K::Point_3>& pts,
                                         const typename K::Point_3& q, const typename K::FT& r)
{
  std::optional<std::size_t> best;
  for(std::size_t i : brute_near_point<K>(pts, q, r))
    if(!best || K().compare_distance_3_object()(q, pts[i], pts[*best]) == CGAL::SMALLER)
      best = i;
  return best;
}

template <typename K>
std::vector<std::size_t> brute_near_segment(const std::vector<typename K::Point_3>& pts,
                                            const typename K::Point_3& a,
                                            const typename K::Point_3& b, const typename K::FT& r)
{
  if(a == b)
    return brute_near_point<K>(pts, a, r);
  const typename K::FT r2 = r * r;
  const typename K::Segment_3 s(a, b);
  std::vector<std::size_t> res;
  for(std::size_t i = 0; i < pts.size(); ++i)
    if(K().compare_squared_distance_3_object()(pts[i], s, r2) != CGAL::LARGER)
      res.push_back(i);
  return res;
}

// ---------------------------------------------------------------------------------------------
// point sets (as doubles, converted to the kernel's points)

using Xyz = std::array<double, 3>;

std::vector<Xyz> uniform_points(std::size_t n, unsigned seed)
{
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Xyz> r(n);
  for(Xyz& p : r)
    p = {u(gen), u(gen), u(gen)};
  return r;
}

// tight clusters with exact duplicates, far apart from each other
std::vector<Xyz> clustered_points(std::size_t n, unsigned seed)
{
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-10, 10);
  std::normal_distribution<double> g(0, 1e-3);
  std::vector<Xyz> centres(12);
  for(Xyz& c : centres)
    c = {u(gen), u(gen), u(gen)};
  std::vector<Xyz> r;
  while(r.size() < n)
  {
    if(!r.empty() && gen() % 10 == 0)
    {
      r.push_back(r[gen() % r.size()]);
      continue;
    }
    const Xyz& c = centres[gen() % centres.size()];
    r.push_back({c[0] + g(gen), c[1] + g(gen), c[2] + g(gen)});
  }
  return r;
}

// on the unit sphere (a surface: the octree is mostly empty)
std::vector<Xyz> surface_points(std::size_t n, unsigned seed)
{
  std::mt19937 gen(seed);
  std::normal_distribution<double> g(0, 1);
  std::vector<Xyz> r(n);
  for(Xyz& p : r)
  {
    double x = g(gen), y = g(gen), z = g(gen);
    const double l = std::sqrt(x * x + y * y + z * z);
    p = {x / l, y / l, z / l};
  }
  return r;
}

template <typename K>
std::vector<typename K::Point_3> to_points(const std::vector<Xyz>& xyz)
{
  std::vector<typename K::Point_3> r;
  r.reserve(xyz.size());
  for(const Xyz& p : xyz)
    r.emplace_back(p[0], p[1], p[2]);
  return r;
}

// ---------------------------------------------------------------------------------------------
// the cross-check

template <typename K>
void cross_check(const std::vector<typename K::Point_3>& pts, std::size_t queries_per_radius,
                 unsigned seed, const ST::Octree<K>& tree)
{
  using FT = typename K::FT;
  using P = typename K::Point_3;
  ASSERT_EQ(tree.size(), pts.size());
  if(pts.empty())
    return;

  double lo[3], hi[3];
  for(int k = 0; k < 3; ++k)
    lo[k] = hi[k] = CGAL::to_double(pts[0][k]);
  for(const P& p : pts)
    for(int k = 0; k < 3; ++k)
    {
      lo[k] = std::min(lo[k], CGAL::to_double(p[k]));
      hi[k] = std::max(hi[k], CGAL::to_double(p[k]));
    }
  const double diag = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                (hi[2] - lo[2]) * (hi[2] - lo[2]));

  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(0, 1);
  auto pick = [&]() { return pts[gen() % pts.size()]; };
  auto random_in_box = [&]() {
    return P(lo[0] + u(gen) * (hi[0] - lo[0]) * 1.2 - 0.1 * (hi[0] - lo[0]),
             lo[1] + u(gen) * (hi[1] - lo[1]) * 1.2 - 0.1 * (hi[1] - lo[1]),
             lo[2] + u(gen) * (hi[2] - lo[2]) * 1.2 - 0.1 * (hi[2] - lo[2]));
  };
  auto near = [&](const P& p, double d) {
    return P(CGAL::to_double(p.x()) + d * (u(gen) - 0.5), CGAL::to_double(p.y()) + d * (u(gen) - 0.5),
             CGAL::to_double(p.z()) + d * (u(gen) - 0.5));
  };

  const double fractions[] = {0, 1e-5, 1e-3, 1e-2, 0.1, 1};
  for(double f : fractions)
  {
    const FT r(f * diag);
    const double rd = f * diag;
    for(std::size_t qi = 0; qi < queries_per_radius; ++qi)
    {
      P q;
      switch(qi % 3)
      {
      case 0: q = pick(); break;
      case 1: q = near(pick(), 2 * rd + 1e-9 * diag); break;
      default: q = random_in_box(); break;
      }
      std::vector<std::size_t> got;
      tree.vertices_near_point(q, r, std::back_inserter(got));
      ASSERT_EQ(got, brute_near_point<K>(pts, q, r)) << "radius " << rd << " query " << qi;
      ASSERT_EQ(tree.nearest_vertex(q, r), brute_nearest<K>(pts, q, r))
        << "radius " << rd << " query " << qi;

      P a, b;
      switch(qi % 4)
      {
      case 0: a = pick(); b = pick(); break;
      case 1: a = pick(); b = near(a, 0.05 * diag); break;
      case 2: a = random_in_box(); b = random_in_box(); break;
      default: a = pick(); b = a; break;
      }
      const std::vector<std::size_t> expected = brute_near_segment<K>(pts, a, b, r);
      std::vector<std::size_t> got_a, got_b;
      tree.vertices_near_segment(a, b, r, std::back_inserter(got_a),
                                 ST::Segment_query_strategy::INDEX_SPACE_BOX);
      tree.vertices_near_segment(a, b, r, std::back_inserter(got_b),
                                 ST::Segment_query_strategy::NEIGHBORHOOD_CULLING);
      ASSERT_EQ(got_a, expected) << "index-space box, radius " << rd << " query " << qi;
      ASSERT_EQ(got_b, expected) << "neighbourhood culling, radius " << rd << " query " << qi;
    }
  }
}

template <typename K>
void cross_check(const std::vector<typename K::Point_3>& pts, std::size_t queries_per_radius,
                 unsigned seed)
{
  const ST::Octree<K> tree(pts);
  cross_check<K>(pts, queries_per_radius, seed, tree);
  // a tiny bucket and a shallow tree exercise the deep and the overfull leaves
  const ST::Octree<K> small(pts, ST::parameters::bucket_capacity(1));
  cross_check<K>(pts, queries_per_radius / 4 + 1, seed + 1, small);
  const ST::Octree<K> shallow(pts, ST::parameters::maximum_depth(3));
  cross_check<K>(pts, queries_per_radius / 4 + 1, seed + 2, shallow);
}

template <typename K>
void every_point_is_found(const std::vector<typename K::Point_3>& pts)
{
  const ST::Octree<K> tree(pts);
  for(std::size_t i = 0; i < pts.size(); ++i)
  {
    std::vector<std::size_t> got;
    tree.vertices_near_point(pts[i], typename K::FT(0), std::back_inserter(got));
    ASSERT_TRUE(std::binary_search(got.begin(), got.end(), i)) << "point " << i;
    for(std::size_t j : got)
      ASSERT_TRUE(pts[j] == pts[i]);
    const std::optional<std::size_t> v = tree.nearest_vertex(pts[i], typename K::FT(0));
    ASSERT_TRUE(v.has_value());
    ASSERT_EQ(*v, got.front()) << "ties go to the smallest index";
  }
}

// ---------------------------------------------------------------------------------------------
// real meshes

std::vector<Xyz> read_mesh_vertices(const std::string& name)
{
  const std::string off = soup_test::data_file("clean/" + name);
  std::vector<SC::Point_3> points;
  std::vector<std::vector<std::size_t>> polygons;
  const bool ok = CGAL::IO::read_polygon_soup(off, points, polygons);
  if(!ok)
    return {};
  std::vector<Xyz> r;
  r.reserve(points.size());
  for(const SC::Point_3& p : points)
    r.push_back({p.x(), p.y(), p.z()});
  return r;
}

std::vector<Xyz> subset(const std::vector<Xyz>& v, std::size_t n)
{
  if(v.size() <= n)
    return v;
  std::vector<Xyz> r;
  const double step = double(v.size()) / double(n);
  for(std::size_t i = 0; i < n; ++i)
    r.push_back(v[std::size_t(i * step)]);
  return r;
}

} // namespace

// ---------------------------------------------------------------------------------------------
// cross-checks against brute force

TEST(Octree, MatchesBruteForceUniformSimpleCartesian)
{
  cross_check<SC>(to_points<SC>(uniform_points(5000, 1)), 60, 11);
}

TEST(Octree, MatchesBruteForceUniformEpick)
{
  cross_check<Epick>(to_points<Epick>(uniform_points(5000, 2)), 60, 12);
}

TEST(Octree, MatchesBruteForceUniformEpeck)
{
  cross_check<Epeck>(to_points<Epeck>(uniform_points(1500, 3)), 30, 13);
}

TEST(Octree, MatchesBruteForceClusteredSimpleCartesian)
{
  cross_check<SC>(to_points<SC>(clustered_points(5000, 4)), 60, 14);
}

TEST(Octree, MatchesBruteForceClusteredEpick)
{
  cross_check<Epick>(to_points<Epick>(clustered_points(5000, 5)), 60, 15);
}

TEST(Octree, MatchesBruteForceClusteredEpeck)
{
  cross_check<Epeck>(to_points<Epeck>(clustered_points(1500, 6)), 30, 16);
}

TEST(Octree, MatchesBruteForceSurfaceSimpleCartesian)
{
  cross_check<SC>(to_points<SC>(surface_points(5000, 7)), 60, 17);
}

TEST(Octree, MatchesBruteForceSurfaceEpick)
{
  cross_check<Epick>(to_points<Epick>(surface_points(5000, 8)), 60, 18);
}

TEST(Octree, MatchesBruteForceSurfaceEpeck)
{
  cross_check<Epeck>(to_points<Epeck>(surface_points(1500, 9)), 30, 19);
}

TEST(Octree, MatchesBruteForceOnRealMeshes)
{
  const char* names[] = {"bunny00.off.xz", "armadillo.off.xz", "ChineseDragon-10kv.off.xz",
                         "elephant.off", "fandisk.off.xz", "refined_elephant.off.xz"};
  unsigned seed = 100;
  for(const char* name : names)
  {
    SCOPED_TRACE(name);
    const std::vector<Xyz> v = read_mesh_vertices(name);
    ASSERT_FALSE(v.empty()) << "cannot read " << name;
    const std::vector<Xyz> s = subset(v, 20000);
    cross_check<Epick>(to_points<Epick>(s), 12, ++seed, ST::Octree<Epick>(to_points<Epick>(s)));
    cross_check<SC>(to_points<SC>(s), 6, ++seed, ST::Octree<SC>(to_points<SC>(s)));
    const std::vector<Xyz> e = subset(v, 1000);
    cross_check<Epeck>(to_points<Epeck>(e), 4, ++seed, ST::Octree<Epeck>(to_points<Epeck>(e)));
  }
}

// ---------------------------------------------------------------------------------------------
// properties

TEST(Octree, FindsEveryPointAtRadiusZero)
{
  every_point_is_found<SC>(to_points<SC>(clustered_points(3000, 21)));
  every_point_is_found<Epick>(to_points<Epick>(clustered_points(3000, 22)));
  every_point_is_found<Epeck>(to_points<Epeck>(clustered_points(500, 23)));
  every_point_is_found<Epick>(to_points<Epick>(uniform_points(3000, 24)));
}

TEST(Octree, FindsPointOnSegmentAtRadiusZero)
{
  // points exactly on segments: dyadic coordinates, so every point is exactly representable
  std::mt19937 gen(31);
  std::uniform_int_distribution<int> c(-1000, 1000);
  std::vector<Epick::Point_3> pts;
  std::vector<std::pair<Epick::Point_3, Epick::Point_3>> segs;
  for(int i = 0; i < 200; ++i)
  {
    const Epick::Point_3 a(c(gen), c(gen), c(gen));
    const Epick::Vector_3 d(c(gen), c(gen), c(gen));
    const int k = 1 + int(gen() % 7);
    pts.push_back(a + d * (k / 8.0));
    segs.emplace_back(a, a + d);
  }
  const ST::Octree<Epick> tree(pts);
  for(std::size_t i = 0; i < segs.size(); ++i)
    for(ST::Segment_query_strategy s : {ST::Segment_query_strategy::INDEX_SPACE_BOX,
                                        ST::Segment_query_strategy::NEIGHBORHOOD_CULLING})
    {
      std::vector<std::size_t> got;
      tree.vertices_near_segment(segs[i].first, segs[i].second, 0, std::back_inserter(got), s);
      EXPECT_TRUE(std::binary_search(got.begin(), got.end(), i)) << "segment " << i;
      EXPECT_EQ(got, brute_near_segment<Epick>(pts, segs[i].first, segs[i].second, 0));
    }

  // Epeck: midpoints constructed exactly
  std::vector<Epeck::Point_3> epts;
  std::vector<std::pair<Epeck::Point_3, Epeck::Point_3>> esegs;
  std::uniform_real_distribution<double> u(-1, 1);
  for(int i = 0; i < 50; ++i)
  {
    const Epeck::Point_3 a(u(gen), u(gen), u(gen)), b(u(gen), u(gen), u(gen));
    epts.push_back(CGAL::midpoint(a, b));
    esegs.emplace_back(a, b);
  }
  const ST::Octree<Epeck> etree(epts);
  for(std::size_t i = 0; i < esegs.size(); ++i)
  {
    std::vector<std::size_t> got;
    etree.vertices_near_segment(esegs[i].first, esegs[i].second, 0, std::back_inserter(got));
    EXPECT_TRUE(std::binary_search(got.begin(), got.end(), i)) << "segment " << i;
  }
}

TEST(Octree, SegmentStrategiesAgree)
{
  const std::vector<Epick::Point_3> pts = to_points<Epick>(surface_points(20000, 41));
  const ST::Octree<Epick> tree(pts);
  std::mt19937 gen(42);
  for(int i = 0; i < 300; ++i)
  {
    const Epick::Point_3& a = pts[gen() % pts.size()];
    const Epick::Point_3& b = pts[gen() % pts.size()];
    const double r = (i % 5) * 0.01;
    std::vector<std::size_t> x, y;
    tree.vertices_near_segment(a, b, r, std::back_inserter(x),
                               ST::Segment_query_strategy::INDEX_SPACE_BOX);
    tree.vertices_near_segment(a, b, r, std::back_inserter(y),
                               ST::Segment_query_strategy::NEIGHBORHOOD_CULLING);
    ASSERT_EQ(x, y);
  }
}

TEST(Octree, LeafAddressesAndLeafPoints)
{
  const std::vector<Epick::Point_3> pts = to_points<Epick>(clustered_points(4000, 51));
  const ST::Octree<Epick> tree(pts, ST::parameters::maximum_depth(12, ST::parameters::bucket_capacity(4)));
  EXPECT_EQ(tree.bucket_capacity(), 4u);
  EXPECT_EQ(tree.maximum_depth(), 12u);
  std::vector<int> seen(pts.size(), 0);
  for(std::size_t i = 0; i < pts.size(); ++i)
  {
    const auto leaf = tree.leaf(i);
    ASSERT_TRUE(tree.is_leaf(leaf));
    const auto range = tree.points(leaf);
    ASSERT_NE(std::find(range.begin(), range.end(), std::uint32_t(i)), range.end());
    // every point of the leaf shares the leaf's address prefix
    const unsigned shift = unsigned(tree.maximum_depth() - tree.depth(leaf));
    const auto a = tree.address(i);
    for(std::uint32_t j : range)
    {
      const auto b = tree.address(j);
      for(int k = 0; k < 3; ++k)
        ASSERT_EQ(a[k] >> shift, b[k] >> shift);
    }
    // a leaf holds at most the capacity, unless its points share one address
    if(range.size() > 4)
    {
      for(std::uint32_t j : range)
        ASSERT_EQ(tree.morton_code(j), tree.morton_code(i));
    }
    // the address is the normalised coordinate, scaled and rounded down
    for(int k = 0; k < 3; ++k)
    {
      const double t = (pts[i][k] - tree.workspace_origin()[k]) / tree.workspace_side() * 4096.0;
      EXPECT_LE(std::abs(double(a[k]) - std::min(std::floor(t), 4095.0)), 1.0);
    }
  }
  // the leaves partition the points
  for(std::size_t n = 0; n < tree.number_of_nodes(); ++n)
    if(tree.is_leaf(std::uint32_t(n)))
    {
      for(std::uint32_t j : tree.points(std::uint32_t(n)))
        ++seen[j];
    }
  for(int s : seen)
    ASSERT_EQ(s, 1);
}

// ---------------------------------------------------------------------------------------------
// degenerate and bad input

TEST(Octree, EmptyRange)
{
  const std::vector<Epick::Point_3> pts;
  const ST::Octree<Epick> tree(pts);
  EXPECT_TRUE(tree.empty());
  const Epick::Point_3 q(0, 0, 0);
  EXPECT_FALSE(tree.nearest_vertex(q, 1.0));
  std::vector<std::size_t> out;
  tree.vertices_near_point(q, 1.0, std::back_inserter(out));
  tree.vertices_near_segment(q, Epick::Point_3(1, 1, 1), 1.0, std::back_inserter(out));
  EXPECT_TRUE(out.empty());
}

TEST(Octree, SinglePoint)
{
  const std::vector<Epick::Point_3> pts = {Epick::Point_3(1, 2, 3)};
  const ST::Octree<Epick> tree(pts);
  EXPECT_EQ(tree.nearest_vertex(pts[0], 0), std::optional<std::size_t>(0));
  EXPECT_FALSE(tree.nearest_vertex(Epick::Point_3(1, 2, 4), 0.999));
  EXPECT_EQ(tree.nearest_vertex(Epick::Point_3(1, 2, 4), 1.0), std::optional<std::size_t>(0));
  cross_check<Epick>(pts, 12, 61, tree);
}

TEST(Octree, AllPointsEqual)
{
  const std::vector<Epick::Point_3> pts(1000, Epick::Point_3(0.1, 0.2, 0.3));
  const ST::Octree<Epick> tree(pts, ST::parameters::bucket_capacity(2));
  std::vector<std::size_t> got;
  tree.vertices_near_point(pts[0], 0, std::back_inserter(got));
  EXPECT_EQ(got.size(), pts.size());
  EXPECT_EQ(tree.nearest_vertex(pts[0], 0), std::optional<std::size_t>(0));
  cross_check<Epick>(pts, 12, 62, tree);
}

TEST(Octree, CollinearPoints)
{
  std::vector<Epick::Point_3> pts;
  for(int i = 0; i < 2000; ++i)
    pts.emplace_back(0.5 + i * 1e-3, 0.5 + i * 2e-3, -0.25 + i * 3e-3);
  for(int i = 0; i < 200; ++i)
    pts.push_back(pts[std::size_t(i * 7)]);
  cross_check<Epick>(pts, 30, 63);
  cross_check<SC>(to_points<SC>(std::vector<Xyz>(1, Xyz{0, 0, 0})), 3, 64);
}

TEST(Octree, CoordinatesFromTinyToHuge)
{
  std::mt19937 gen(71);
  std::uniform_int_distribution<int> e(-9, 9);
  std::uniform_real_distribution<double> m(1, 10);
  std::vector<Xyz> xyz;
  for(int i = 0; i < 3000; ++i)
  {
    Xyz p;
    for(double& c : p)
      c = (gen() % 2 ? 1 : -1) * m(gen) * std::pow(10.0, e(gen));
    xyz.push_back(p);
  }
  // a cloud at 1e-9 scale near the origin and another one around 1e9
  for(int i = 0; i < 500; ++i)
  {
    xyz.push_back({1e-9 * m(gen), 1e-9 * m(gen), 1e-9 * m(gen)});
    xyz.push_back({1e9 + m(gen), 1e9 + m(gen), 1e9 + m(gen)});
  }
  cross_check<Epick>(to_points<Epick>(xyz), 30, 72);
  cross_check<SC>(to_points<SC>(xyz), 30, 73);
  cross_check<Epeck>(to_points<Epeck>(subset(xyz, 400)), 8, 74);
  every_point_is_found<Epick>(to_points<Epick>(xyz));
  // a model living entirely around 1e9 with a tiny extent
  std::vector<Xyz> far;
  for(int i = 0; i < 1000; ++i)
    far.push_back({1e9 + 1e-6 * m(gen), 1e9 + 1e-6 * m(gen), 1e9 + 1e-6 * m(gen)});
  cross_check<Epick>(to_points<Epick>(far), 30, 75);
  every_point_is_found<Epick>(to_points<Epick>(far));
}

TEST(Octree, RejectsNonFiniteCoordinates)
{
  std::vector<Epick::Point_3> pts = {Epick::Point_3(0, 0, 0), Epick::Point_3(1, 1, 1),
                                     Epick::Point_3(0, std::numeric_limits<double>::quiet_NaN(), 0)};
  try
  {
    ST::Octree<Epick> tree(pts);
    FAIL() << "no exception";
  }
  catch(const ST::Invalid_input& e)
  {
    EXPECT_NE(std::string(e.what()).find("point 2"), std::string::npos) << e.what();
  }
  pts[2] = Epick::Point_3(std::numeric_limits<double>::infinity(), 0, 0);
  EXPECT_THROW(ST::Octree<Epick>{pts}, ST::Invalid_input);
  std::vector<SC::Point_3> spts = {SC::Point_3(0, 0, -std::numeric_limits<double>::infinity())};
  EXPECT_THROW(ST::Octree<SC>{spts}, ST::Invalid_input);
}

TEST(Octree, RejectsBadRadiusAndParameters)
{
  const std::vector<Epick::Point_3> pts = to_points<Epick>(uniform_points(100, 81));
  const ST::Octree<Epick> tree(pts);
  std::vector<std::size_t> out;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(tree.nearest_vertex(pts[0], -1.0), ST::Invalid_input);
  EXPECT_THROW(tree.nearest_vertex(pts[0], nan), ST::Invalid_input);
  EXPECT_THROW(tree.vertices_near_point(pts[0], -1e-300, std::back_inserter(out)),
               ST::Invalid_input);
  EXPECT_THROW(tree.vertices_near_segment(pts[0], pts[1], nan, std::back_inserter(out)),
               ST::Invalid_input);
  EXPECT_THROW(ST::Octree<Epick>(pts, ST::parameters::bucket_capacity(0)), ST::Invalid_input);
  EXPECT_THROW(ST::Octree<Epick>(pts, ST::parameters::maximum_depth(22)), ST::Invalid_input);
  const std::vector<Epeck::Point_3> epts = to_points<Epeck>(uniform_points(10, 82));
  const ST::Octree<Epeck> etree(epts);
  EXPECT_THROW(etree.nearest_vertex(epts[0], Epeck::FT(-1) / 3), ST::Invalid_input);
  EXPECT_THROW(tree.address(pts.size()), ST::Invalid_input);
  // the package's exception is a std::invalid_argument
  EXPECT_THROW(tree.nearest_vertex(pts[0], -1.0), std::invalid_argument);
}

TEST(Octree, NamedParametersAndPointMap)
{
  using Pair = std::pair<Epick::Point_3, int>;
  std::vector<Pair> items;
  for(const Epick::Point_3& p : to_points<Epick>(uniform_points(2000, 91)))
    items.emplace_back(p, 0);
  using Map = CGAL::First_of_pair_property_map<Pair>;
  const ST::Octree<Epick, Map> tree(
    items, ST::parameters::segment_query_strategy(ST::Segment_query_strategy::NEIGHBORHOOD_CULLING,
                                                  ST::parameters::bucket_capacity(8))
             .point_map(Map())
             .geom_traits(Epick()));
  EXPECT_EQ(tree.segment_query_strategy(), ST::Segment_query_strategy::NEIGHBORHOOD_CULLING);
  EXPECT_EQ(ST::Octree<Epick>(std::vector<Epick::Point_3>()).segment_query_strategy(),
            ST::Segment_query_strategy::INDEX_SPACE_BOX);
  EXPECT_EQ(tree.bucket_capacity(), 8u);
  const ST::Octree<Epick, Map> tree2(items, Map());
  std::vector<Epick::Point_3> pts;
  for(const Pair& p : items)
    pts.push_back(p.first);
  for(std::size_t i = 0; i < 50; ++i)
  {
    std::vector<std::size_t> x, y;
    tree.vertices_near_segment(pts[i], pts[i + 50], 0.1, std::back_inserter(x));
    tree2.vertices_near_segment(pts[i], pts[i + 50], 0.1, std::back_inserter(y));
    EXPECT_EQ(x, brute_near_segment<Epick>(pts, pts[i], pts[i + 50], 0.1));
    EXPECT_EQ(y, x);
  }
}

// The self-join answers, for every point, what vertices_near_point() answers, and visits every
// point once.
template <typename K>
void check_self_join(const std::vector<Xyz>& xyz, std::size_t capacity)
{
  const std::vector<typename K::Point_3> pts = to_points<K>(xyz);
  const ST::Octree<K> tree(pts, ST::parameters::bucket_capacity(capacity));
  for(double r : {0.0, 1e-6, 1e-3, 2e-2, 0.3})
  {
    std::vector<int> visits(pts.size(), 0);
    std::optional<std::pair<std::uint64_t, std::size_t>> previous; // points come in (Morton code, index) order
    tree.for_each_neighborhood(typename K::FT(r), [&](std::size_t i, const std::vector<std::size_t>& near) {
      ++visits[i];
      const std::pair<std::uint64_t, std::size_t> current(tree.morton_code(i), i);
      ASSERT_TRUE(!previous || *previous < current) << "point " << i << " radius " << r;
      previous = current;
      std::vector<std::size_t> expected;
      tree.vertices_near_point(pts[i], typename K::FT(r), std::back_inserter(expected));
      ASSERT_EQ(near, expected) << "point " << i << " radius " << r;
    });
    for(int v : visits)
      ASSERT_EQ(v, 1);
    // unsorted: the same sets
    tree.for_each_neighborhood(typename K::FT(r), [&](std::size_t i, const std::vector<std::size_t>& near) {
      ++visits[i];
      std::vector<std::size_t> sorted = near, expected;
      std::sort(sorted.begin(), sorted.end());
      tree.vertices_near_point(pts[i], typename K::FT(r), std::back_inserter(expected));
      ASSERT_EQ(sorted, expected) << "point " << i << " radius " << r << ", in the tree's order";
    }, ST::Neighborhood_order::TREE);
    for(int v : visits)
      ASSERT_EQ(v, 2);
  }
}

TEST(Octree, SelfJoinMatchesPointQueries)
{
  check_self_join<Epick>(uniform_points(3000, 5), 16);
  check_self_join<Epick>(clustered_points(3000, 6), 4);
  check_self_join<Epick>(surface_points(3000, 7), 1);
  check_self_join<Epeck>(clustered_points(500, 8), 16);
  check_self_join<SC>(uniform_points(2000, 9), 8);
}

// The double filter of the radius queries decides only what the kernel's exact predicate decides:
// points at relative distances 1 - d and 1 + d of the radius from a centre, d from 0 to 1e-9 (the
// filter's margin is 1e-12, the rounding of the coordinates about 1e-16), at three scales; the
// point queries (from the centre and from the other points) and the self-join equal brute force.
template <typename K>
void check_filter_at_the_boundary(unsigned seed, double scale)
{
  using FT = typename K::FT;
  std::mt19937 gen(seed);
  std::normal_distribution<double> g(0, 1);
  std::uniform_real_distribution<double> u(-1, 1);
  const double offsets[] = {0, 1e-17, 1e-16, 3e-16, 1e-15, 1e-13, 1e-12, 2e-12, 1e-11, 1e-9};
  for(int trial = 0; trial < 12; ++trial)
  {
    const Xyz c = {scale * u(gen), scale * u(gen), scale * u(gen)};
    const double r = scale * std::pow(10.0, -3.0 + 3.0 * u(gen)); // 1e-6 to 1 of the scale
    std::vector<Xyz> xyz{c, {c[0] + r, c[1], c[2]}, {c[0], c[1] - r, c[2]}};
    for(double d : offsets)
      for(double side : {-1.0, 1.0})
        for(int k = 0; k < 4; ++k)
        {
          double v[3] = {g(gen), g(gen), g(gen)};
          const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
          const double t = r * (1 + side * d) / l;
          xyz.push_back({c[0] + t * v[0], c[1] + t * v[1], c[2] + t * v[2]});
        }
    const std::vector<typename K::Point_3> pts = to_points<K>(xyz);
    for(std::size_t capacity : {1, 16})
    {
      const ST::Octree<K> tree(pts, ST::parameters::bucket_capacity(capacity));
      for(std::size_t i = 0; i < pts.size(); i += 7)
      {
        std::vector<std::size_t> got;
        tree.vertices_near_point(pts[i], FT(r), std::back_inserter(got));
        ASSERT_EQ(got, brute_near_point<K>(pts, pts[i], FT(r))) << "trial " << trial << " point " << i;
        ASSERT_EQ(tree.number_of_vertices_near_point(pts[i], FT(r)), got.size());
      }
      tree.for_each_neighborhood(FT(r), [&](std::size_t i, const std::vector<std::size_t>& near) {
        ASSERT_EQ(near, brute_near_point<K>(pts, pts[i], FT(r))) << "trial " << trial << " point " << i;
      });
    }
  }
}

TEST(Octree, DoubleFilterAgreesWithExactPredicate)
{
  for(double scale : {1e-6, 1.0, 1e6})
  {
    check_filter_at_the_boundary<Epick>(61, scale);
    check_filter_at_the_boundary<Epeck>(62, scale);
  }
}

// The segment queries of for_each_segment_neighborhood() answer, for every segment between two
// points of the tree, what vertices_near_segment() and a brute-force search answer, once per
// segment, with both strategies: short segments (the edges of a triangulated surface, most queries
// inside one leaf or a few), long ones (from the root), and degenerate ones (both ends equal).
// Returns the number of estimates of squared distances checked.
template <typename K>
std::size_t check_segment_join(const std::vector<Xyz>& xyz, std::size_t capacity, ST::Segment_query_strategy strategy)
{
  const std::vector<typename K::Point_3> pts = to_points<K>(xyz);
  const ST::Octree<K> tree(pts, ST::parameters::segment_query_strategy(strategy, ST::parameters::bucket_capacity(capacity)));
  std::mt19937 gen(5);
  std::vector<std::array<std::size_t, 2>> segments;
  for(std::size_t i = 0; i + 1 < pts.size(); ++i)
  {
    // the nearest other point: a short segment
    std::optional<std::size_t> near;
    std::vector<std::size_t> around;
    tree.vertices_near_point(pts[i], typename K::FT(0.05), std::back_inserter(around));
    for(std::size_t j : around)
      if(j != i)
        near = j;
    segments.push_back({i, near ? *near : i + 1});
    if(i % 97 == 0)
      segments.push_back({i, std::size_t(gen() % pts.size())});
    if(i % 101 == 0)
      segments.push_back({i, i});
  }
  std::size_t estimated = 0;
  for(double r : {0.0, 1e-6, 1e-3, 2e-2, 0.2})
  {
    std::vector<int> visits(segments.size(), 0);
    tree.for_each_segment_neighborhood(segments, typename K::FT(r), [&](std::size_t s, const std::vector<std::size_t>& near) {
      ++visits[s];
      const auto& a = pts[segments[s][0]];
      const auto& b = pts[segments[s][1]];
      std::vector<std::size_t> expected;
      tree.vertices_near_segment(a, b, typename K::FT(r), std::back_inserter(expected));
      ASSERT_EQ(near, expected) << "segment " << s << " radius " << r;
      if(s % 7 == 0)
      {
        ASSERT_EQ(near, brute_near_segment<K>(pts, a, b, r)) << "segment " << s << " radius " << r;
      }
    });
    for(int v : visits)
      EXPECT_EQ(v, 1);
    // unsorted: the same sets
    tree.for_each_segment_neighborhood(segments, typename K::FT(r), [&](std::size_t s, const std::vector<std::size_t>& near) {
      ++visits[s];
      std::vector<std::size_t> sorted = near, expected;
      std::sort(sorted.begin(), sorted.end());
      tree.vertices_near_segment(pts[segments[s][0]], pts[segments[s][1]], typename K::FT(r), std::back_inserter(expected));
      ASSERT_EQ(sorted, expected) << "segment " << s << " radius " << r << ", in the tree's order";
    }, ST::Neighborhood_order::TREE);
    for(int v : visits)
      EXPECT_EQ(v, 2);
    // with the estimates of the squared distances: the same answers, each estimate beside its
    // point (sorted along with it) and, with double coordinates, within the documented margin
    // of the kernel's distance
    tree.for_each_segment_neighborhood(
      segments, typename K::FT(r),
      [&](std::size_t s, const std::vector<std::size_t>& near, const std::vector<double>& d2) {
        ++visits[s];
        const auto& a = pts[segments[s][0]];
        const auto& b = pts[segments[s][1]];
        std::vector<std::size_t> expected;
        tree.vertices_near_segment(a, b, typename K::FT(r), std::back_inserter(expected));
        ASSERT_EQ(near, expected) << "segment " << s << " radius " << r << ", with the estimates";
        ASSERT_EQ(d2.size(), near.size());
        if constexpr(std::is_same<typename K::FT, double>::value)
        {
          const double length = std::sqrt(CGAL::to_double(CGAL::squared_distance(a, b)));
          for(std::size_t i = 0; i < near.size(); ++i)
          {
            if(std::isnan(d2[i]))
              continue;
            ++estimated;
            const typename K::Segment_3 segment(a, b);
            const double kernel = std::sqrt(CGAL::to_double(CGAL::squared_distance(pts[near[i]], segment)));
            EXPECT_LE(std::abs(std::sqrt(d2[i]) - kernel), 1e-13 * (length + kernel))
              << "segment " << s << " radius " << r << ", point " << near[i];
          }
        }
      });
    for(int v : visits)
      EXPECT_EQ(v, 3);
  }
  return estimated;
}

TEST(Octree, SegmentJoinMatchesSegmentQueries)
{
  for(const auto strategy : {ST::Segment_query_strategy::INDEX_SPACE_BOX, ST::Segment_query_strategy::NEIGHBORHOOD_CULLING})
  {
    // (the short segments of a surface share their candidates: their estimates are given)
    EXPECT_GT(check_segment_join<Epick>(surface_points(3000, 51), 8, strategy), 1000u);
    check_segment_join<Epick>(clustered_points(2000, 52), 4, strategy);
    check_segment_join<Epeck>(surface_points(500, 53), 16, strategy);
    check_segment_join<SC>(uniform_points(2000, 54), 1, strategy);
  }
}

// A grid of short segments beside a crowd: the short segments of a leaf share the candidates of
// the union of their boxes, except near the crowd, where that union holds too many points and
// each segment is queried alone; the long segments are queried alone everywhere. Every way
// answers what the single queries and the brute force answer.
std::vector<Xyz> grid_beside_a_crowd(unsigned seed, int side, int crowd)
{
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> u(-1e-7, 1e-7);
  std::vector<Xyz> r;
  for(int i = 0; i < side; ++i)
    for(int j = 0; j < side; ++j)
      r.push_back({0.01 * i + u(gen), 0.01 * j + u(gen), u(gen)});
  for(int k = 0; k < crowd; ++k)
    r.push_back({0.2 + u(gen), 0.2 + u(gen), 0.002 + u(gen)});
  std::shuffle(r.begin(), r.end(), gen);
  return r;
}

TEST(Octree, SegmentJoinBesideACrowdMatchesSegmentQueries)
{
  for(const auto strategy : {ST::Segment_query_strategy::INDEX_SPACE_BOX, ST::Segment_query_strategy::NEIGHBORHOOD_CULLING})
  {
    check_segment_join<Epick>(grid_beside_a_crowd(56, 30, 300), 8, strategy);
    check_segment_join<Epick>(grid_beside_a_crowd(57, 30, 300), 32, strategy);
    check_segment_join<Epeck>(grid_beside_a_crowd(58, 20, 200), 16, strategy);
  }
}

// Points of a lattice of step 1/8, and copies of them moved by exactly 2^-20 along one axis: many
// coordinates are equal along every axis, so that the short segments of a leaf (the lattice's
// edges and diagonals) put many of their shared candidates on the faces of their boxes and on
// the same coordinate along the side cut into slabs. At radii 0, 2^-20 and 1/8 many candidates
// lie at exactly the radius. Every segment's answer, in the tree's order and sorted, is the
// brute force's.
TEST(Octree, SegmentJoinOnALatticeMatchesTheBruteForce)
{
  std::vector<Epick::Point_3> pts;
  for(int i = 0; i < 12; ++i)
    for(int j = 0; j < 12; ++j)
      for(int k = 0; k < 3; ++k)
      {
        pts.emplace_back(i / 8.0, j / 8.0, k / 8.0);
        if((i + j + k) % 3 == 0)
          pts.emplace_back(i / 8.0 + std::ldexp(1.0, -20), j / 8.0, k / 8.0);
      }
  std::mt19937 gen(60);
  std::shuffle(pts.begin(), pts.end(), gen);
  std::map<std::array<double, 3>, std::size_t> index;
  for(std::size_t p = 0; p < pts.size(); ++p)
    index[{pts[p].x(), pts[p].y(), pts[p].z()}] = p;
  std::vector<std::array<std::size_t, 2>> segments;
  for(std::size_t p = 0; p < pts.size(); ++p)
    for(const std::array<double, 3>& step : {std::array<double, 3>{1, 0, 0}, std::array<double, 3>{0, 1, 0},
                                             std::array<double, 3>{1, 1, 0}, std::array<double, 3>{0, 1, 1}})
    {
      const auto other = index.find({pts[p].x() + step[0] / 8, pts[p].y() + step[1] / 8, pts[p].z() + step[2] / 8});
      if(other != index.end())
        segments.push_back({p, other->second});
    }
  ASSERT_GT(segments.size(), 1000u);
  for(std::size_t capacity : {8, 32})
  {
    const ST::Octree<Epick> tree(pts, ST::parameters::bucket_capacity(capacity));
    for(double r : {0.0, std::ldexp(1.0, -20), 0.125})
    {
      std::vector<int> visits(segments.size(), 0);
      tree.for_each_segment_neighborhood(segments, r, [&](std::size_t s, const std::vector<std::size_t>& near) {
        ++visits[s];
        std::vector<std::size_t> sorted = near;
        std::sort(sorted.begin(), sorted.end());
        ASSERT_EQ(sorted, brute_near_segment<Epick>(pts, pts[segments[s][0]], pts[segments[s][1]], r))
          << "segment " << s << ", radius " << r << ", capacity " << capacity;
      }, ST::Neighborhood_order::TREE);
      for(int v : visits)
        ASSERT_EQ(v, 1);
    }
  }
}

// point(i) gives back point i of the range, also after the range is gone (the weld frees its
// candidates' copy once the tree is built), and refuses an index out of range.
TEST(Octree, PointByIndexOutlivesTheRange)
{
  const std::vector<Xyz> xyz = clustered_points(3000, 59);
  std::optional<ST::Octree<Epeck>> exact;
  std::optional<ST::Octree<Epick>> tree;
  {
    const std::vector<Epick::Point_3> pts = to_points<Epick>(xyz);
    const std::vector<Epeck::Point_3> epts = to_points<Epeck>(xyz);
    tree.emplace(pts, ST::parameters::bucket_capacity(4));
    exact.emplace(epts);
  }
  for(std::size_t i = 0; i < xyz.size(); ++i)
  {
    ASSERT_EQ(tree->point(i), Epick::Point_3(xyz[i][0], xyz[i][1], xyz[i][2])) << i;
    ASSERT_EQ(exact->point(i), Epeck::Point_3(xyz[i][0], xyz[i][1], xyz[i][2])) << i;
  }
  EXPECT_THROW(tree->point(xyz.size()), ST::Invalid_input);
}

// After `number_points_in_tree_order()` point i is the i-th in Morton order, which was point
// `order[i]`: every answer is the former one renumbered (checked against brute force on the
// range permuted by `order`), the self-join visits the points 0, 1, 2, ... in turn, and the
// order is the one `points(0)` listed before.
template <typename K>
void check_numbering_in_tree_order(const std::vector<Xyz>& xyz, std::size_t capacity, double r)
{
  using FT = typename K::FT;
  const std::vector<typename K::Point_3> pts = to_points<K>(xyz);
  ST::Octree<K> tree(pts, ST::parameters::bucket_capacity(capacity));
  const std::vector<std::uint32_t> listed(tree.points(0).begin(), tree.points(0).end());
  const auto order = tree.number_points_in_tree_order();
  ASSERT_EQ(std::vector<std::uint32_t>(order.begin(), order.end()), listed);
  std::vector<std::uint32_t> sorted(order.begin(), order.end());
  std::sort(sorted.begin(), sorted.end());
  for(std::size_t i = 0; i < sorted.size(); ++i)
    ASSERT_EQ(sorted[i], i); // a permutation
  std::vector<typename K::Point_3> permuted;
  for(std::uint32_t id : order) permuted.push_back(pts[id]);
  for(std::size_t i = 0; i < permuted.size(); ++i)
  {
    ASSERT_EQ(tree.point(i), permuted[i]) << i;
    ASSERT_EQ(*(tree.points(0).begin() + std::ptrdiff_t(i)), i);
  }
  std::size_t next = 0;
  tree.for_each_neighborhood(FT(r), [&](std::size_t i, const std::vector<std::size_t>& near) {
    ASSERT_EQ(i, next++);
    ASSERT_EQ(near, brute_near_point<K>(permuted, permuted[i], FT(r))) << i;
  });
  EXPECT_EQ(next, permuted.size());
  for(std::size_t i = 0; i < permuted.size(); i += 13)
  {
    std::vector<std::size_t> got;
    tree.vertices_near_point(permuted[i], FT(r), std::back_inserter(got));
    std::sort(got.begin(), got.end());
    ASSERT_EQ(got, brute_near_point<K>(permuted, permuted[i], FT(r))) << i;
  }
}

TEST(Octree, Issue13NumberingInTreeOrderRenumbersEveryAnswer)
{
  check_numbering_in_tree_order<Epick>(clustered_points(3000, 63), 4, 0.01);
  check_numbering_in_tree_order<Epick>(uniform_points(2000, 64), 16, 0.05);
  check_numbering_in_tree_order<Epeck>(clustered_points(400, 65), 8, 0.01);
}

TEST(Octree, SegmentJoinRejectsIndicesOutOfRange)
{
  const std::vector<Epick::Point_3> pts = to_points<Epick>(uniform_points(10, 55));
  const ST::Octree<Epick> tree(pts);
  const std::vector<std::array<std::size_t, 2>> bad{{0, 10}};
  EXPECT_THROW(tree.for_each_segment_neighborhood(bad, 0.1, [](std::size_t, const std::vector<std::size_t>&) {}),
               ST::Invalid_input);
  std::size_t calls = 0;
  tree.for_each_segment_neighborhood(std::vector<std::array<std::size_t, 2>>(), 0.1,
                                     [&](std::size_t, const std::vector<std::size_t>&) { ++calls; });
  EXPECT_EQ(calls, 0u);
}

} // namespace Octree_test
