// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The tiled repair against the in-memory one: the same triangles on the same points, in the
// canonical order, for 1 to 64 tiles, on real meshes, generated seams, a shuffled copy, and a
// chain of points that the first halo cannot decide.

#include <Soup_topology/IO/read_triangle_soup.h>
#include <Soup_topology/IO/write_triangle_soup.h>
#include <Soup_topology/reconstruct_topology.h>
#include <Soup_topology/tiled_reconstruct_topology.h>
#include <Soup_topology/internal/tile_parts.h>
#include <Soup_topology/internal/tile_taint.h>

#include "soup_generators.h"
#include "test_utilities.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <mutex>
#include <random>
#include <string>
#include <thread>
#include <vector>

// The names of this file live in a namespace of its own: test/CMakeLists.txt compiles several
// test files as one translation unit.
namespace tiled_reconstruct_topology_test {

namespace {

namespace ST = Soup_topology;
using Point = CGAL::Epick::Point_3;
using Triangle = std::array<std::size_t, 3>;
using Out_triangle = std::array<std::uint32_t, 3>;

struct Soup
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
};

struct Canonical
{
  std::vector<Point> points;
  std::vector<Out_triangle> triangles;
};

double diagonal(const std::vector<Point>& points)
{
  const CGAL::Bbox_3 box = CGAL::bbox_3(points.begin(), points.end());
  return std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) +
                   CGAL::square(box.zmax() - box.zmin()));
}

// The soup of a file, in the canonical order.
Canonical canonical_of_file(const std::string& file)
{
  Soup s;
  ST::IO::read_triangle_soup(file, s.points, s.triangles);
  Canonical c;
  ST::canonical_triangle_soup(s.points, s.triangles, c.points, c.triangles);
  return c;
}

// The in-memory repair, in the canonical order.
template <class NamedParameters>
Canonical in_memory(Soup soup, const NamedParameters& np)
{
  ST::reconstruct_topology(soup.points, soup.triangles, np);
  Canonical c;
  ST::canonical_triangle_soup(soup.points, soup.triangles, c.points, c.triangles);
  return c;
}

template <class NamedParameters>
Canonical tiled(const Soup& soup, std::size_t tiles, const NamedParameters& np, ST::Tiled_reconstruction_report* report = nullptr)
{
  const std::string folder = soup_test::temporary_folder("tiled");
  Canonical c;
  const ST::Tiled_reconstruction_report r = ST::tiled_reconstruct_topology(
    ST::Soup_triangle_source<std::vector<Point>, std::vector<Triangle>>(soup.points, soup.triangles), tiles, folder, c.points,
    c.triangles, np);
  EXPECT_EQ(r.output_triangles, c.triangles.size());
  EXPECT_TRUE(std::filesystem::is_empty(folder)) << "spill files left in " << folder;
  std::filesystem::remove_all(folder);
  if(report != nullptr) *report = r;
  return c;
}

::testing::AssertionResult same(const Canonical& expected, const Canonical& got)
{
  if(expected.points != got.points)
    return ::testing::AssertionFailure() << "points differ: " << expected.points.size() << " expected, " << got.points.size()
                                         << " tiled";
  if(expected.triangles != got.triangles) {
    std::size_t first = 0;
    while(first < std::min(expected.triangles.size(), got.triangles.size()) &&
          expected.triangles[first] == got.triangles[first])
      ++first;
    return ::testing::AssertionFailure() << "triangles differ from the " << first << "th of " << expected.triangles.size()
                                         << " expected (" << got.triangles.size() << " tiled)";
  }
  return ::testing::AssertionSuccess();
}

// A real mesh cut into patches with T-junctions on their borders and jittered copies of their
// vertices.
Soup jittered_seams(const std::string& file, std::size_t patches, double relative_jitter, unsigned seed)
{
  Soup mesh;
  soup_test::read_data_mesh(file, mesh.points, mesh.triangles);
  const auto generated =
    soup_test::t_junction_soup(mesh.points, mesh.triangles, patches, relative_jitter * diagonal(mesh.points), seed);
  return Soup{generated.points, generated.triangles};
}

// The soup of the tool's tests under a memory limit: the elephant subdivided twice (about 90,000
// triangles) cut into 6 patches whose seams are jittered by 1e-6 of the mesh's diagonal, and
// that diagonal.
struct Elephant_seams
{
  Soup soup;
  double diagonal = 0;
};

Elephant_seams elephant_seam_soup()
{
  Soup mesh;
  soup_test::read_data_mesh("clean/elephant.off", mesh.points, mesh.triangles);
  soup_test::subdivide_midpoints(mesh.points, mesh.triangles);
  soup_test::subdivide_midpoints(mesh.points, mesh.triangles);
  const double d = diagonal(mesh.points);
  const auto generated = soup_test::t_junction_soup(mesh.points, mesh.triangles, 6, 1e-6 * d, 3);
  return Elephant_seams{Soup{generated.points, generated.triangles}, d};
}

TEST(TiledReconstruction, JitteredSeamsOfRealMeshesForOneToSixtyFourTiles)
{
  for(const char* file : {"clean/elephant.off", "clean/fandisk.off.xz"}) {
    const Soup soup = jittered_seams(file, 6, 1e-6, 5);
    const double tolerance = 1e-5 * diagonal(soup.points);
    const auto np = CGAL::parameters::snapping_tolerance(tolerance);
    const Canonical expected = in_memory(soup, np);
    ASSERT_GT(expected.triangles.size(), 0u);
    for(std::size_t tiles : {1, 2, 8, 64}) {
      ST::Tiled_reconstruction_report report;
      EXPECT_TRUE(same(expected, tiled(soup, tiles, np, &report))) << file << ", " << tiles << " tiles";
      EXPECT_EQ(report.tiles, tiles);
      EXPECT_FALSE(report.whole_soup) << report.whole_soup_reason;
      EXPECT_GE(report.tile_runs, tiles);
    }
    // A first halo of twice the tolerance: the taint of the region's edge reaches owned triangles,
    // the tiles are repaired again, and the output is the same.
    ST::Tiled_reconstruction_report report;
    EXPECT_TRUE(same(expected, tiled(soup, 8, ST::parameters::tile_halo(2 * tolerance, np), &report))) << file;
    EXPECT_GT(report.repeated_tiles, 0u) << file;
    EXPECT_EQ(report.first_halo, 2 * tolerance);
  }
}

// The generated soup of the issue: an exploded torus of 4,000,000 triangles (2,000 x 1,000 quads
// of major radius 1 and minor radius 0.4, every triangle with its own copies of its corners, each
// coordinate moved by up to 1e-6 of the diagonal), repaired in memory and in 2, 8 and 64 tiles
// (on TBB's threads, which give the sequential result): the same mesh each time, closed.
TEST(TiledReconstruction, GeneratedFourMillionTriangleSoupInTwoEightAndSixtyFourTiles)
{
  using Parallel = CGAL::Parallel_if_available_tag;
  constexpr unsigned nu = 2000, nv = 1000;
  const double pi = std::acos(-1.0), major = 1, minor = 0.4;
  const double torus_diagonal = std::sqrt(2 * CGAL::square(2 * (major + minor)) + CGAL::square(2 * minor));
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> move(-1e-6 * torus_diagonal, 1e-6 * torus_diagonal);
  Soup soup;
  soup.points.reserve(6 * std::size_t(nu) * nv);
  soup.triangles.reserve(2 * std::size_t(nu) * nv);
  const auto corner = [&](unsigned i, unsigned j) {
    const double a = 2 * pi * (i % nu) / nu, b = 2 * pi * (j % nv) / nv, w = major + minor * std::cos(b);
    soup.points.emplace_back(w * std::cos(a) + move(rng), w * std::sin(a) + move(rng), minor * std::sin(b) + move(rng));
    return soup.points.size() - 1;
  };
  for(unsigned i = 0; i < nu; ++i)
    for(unsigned j = 0; j < nv; ++j) {
      const std::size_t a = corner(i, j), b = corner(i + 1, j), c = corner(i + 1, j + 1);
      soup.triangles.push_back({a, b, c});
      const std::size_t d = corner(i, j), e = corner(i + 1, j + 1), f = corner(i, j + 1);
      soup.triangles.push_back({d, e, f});
    }
  ASSERT_EQ(soup.triangles.size(), 4000000u);
  // Above the jitter (at most 3.5e-6 of the diagonal between two copies), far below the edges.
  const auto np = CGAL::parameters::snapping_tolerance(1.2e-5 * torus_diagonal);
  Canonical expected;
  {
    Soup repaired = soup;
    const ST::Reconstruction_report r = ST::reconstruct_topology<Parallel>(repaired.points, repaired.triangles, np);
    EXPECT_EQ(r.border_edges_after, 0u);
    ST::canonical_triangle_soup(repaired.points, repaired.triangles, expected.points, expected.triangles);
  }
  ASSERT_EQ(expected.triangles.size(), 4000000u);
  EXPECT_EQ(expected.points.size(), 2000000u);
  for(std::size_t tiles : {2, 8, 64}) {
    const std::string folder = soup_test::temporary_folder("tiled_4m");
    Canonical got;
    const ST::Tiled_reconstruction_report report = ST::tiled_reconstruct_topology<Parallel>(
      ST::Soup_triangle_source<std::vector<Point>, std::vector<Triangle>>(soup.points, soup.triangles), tiles, folder,
      got.points, got.triangles, np);
    EXPECT_TRUE(same(expected, got)) << tiles << " tiles";
    EXPECT_EQ(report.tiles, tiles);
    EXPECT_FALSE(report.whole_soup) << report.whole_soup_reason;
    EXPECT_TRUE(std::filesystem::is_empty(folder));
    std::filesystem::remove_all(folder);
  }
}

TEST(TiledReconstruction, ShuffledSoupGivesTheSameOutput)
{
  const Soup soup = jittered_seams("clean/elephant.off", 4, 1e-6, 9);
  Soup shuffled = soup;
  std::mt19937 rng(3);
  for(Triangle& t : shuffled.triangles) std::rotate(t.begin(), t.begin() + (rng() % 3), t.end());
  std::shuffle(shuffled.triangles.begin(), shuffled.triangles.end(), rng);
  const auto np = CGAL::parameters::snapping_tolerance(1e-5 * diagonal(soup.points));
  EXPECT_TRUE(same(tiled(soup, 8, np), tiled(shuffled, 8, np)));
}

TEST(TiledReconstruction, RealDefectsUnderBothPolicies)
{
  struct Case
  {
    const char* file;
    double tolerance;
  };
  for(const Case c : {Case{"cad/ALSTOM_TEST4.off", 1e-6}, Case{"cgal_repair/pig.stl.xz", 0.3},
                      Case{"cgal_repair/quads_to_stitch.off", 1e-4}}) {
    Soup soup;
    soup_test::read_data_mesh(c.file, soup.points, soup.triangles);
    for(ST::Small_features policy : {ST::Small_features::REFUSE, ST::Small_features::COLLAPSE}) {
      const auto np = ST::parameters::small_features(policy, CGAL::parameters::snapping_tolerance(c.tolerance));
      const Canonical expected = in_memory(soup, np);
      for(std::size_t tiles : {2, 8}) {
        ST::Tiled_reconstruction_report report;
        EXPECT_TRUE(same(expected, tiled(soup, tiles, np, &report)))
          << c.file << ", " << tiles << " tiles, policy " << int(policy);
        if(policy == ST::Small_features::REFUSE) {
          EXPECT_FALSE(report.whole_soup) << c.file;
        }
        EXPECT_TRUE(same(expected, tiled(soup, tiles, ST::parameters::tile_halo(2 * c.tolerance, np))))
          << c.file << ", " << tiles << " tiles, policy " << int(policy) << ", halo 2 t";
      }
    }
  }
}

// Two strips of small triangles (0.5 t wide, 1.5 t high), one above the other, their facing
// borders 0.3 t apart and their border vertices 0.5 t apart: one component of the tolerance graph
// along the whole soup (200 t), longer than the halo of the first runs (about 9 t). The tiles are repaired again on larger regions, and the output
// is still the in-memory one.
TEST(TiledReconstruction, ChainLongerThanTheHaloIsRepairedAgain)
{
  Soup soup;
  const double t = 1e-3, step = 0.5 * t;
  const std::size_t n = 400;
  const double height = 1.5 * t;
  for(double y0 : {0.0, -height - 0.3 * t}) {
    const std::size_t first = soup.points.size();
    for(std::size_t i = 0; i <= n; ++i) {
      soup.points.emplace_back(double(i) * step, y0, 0);
      soup.points.emplace_back(double(i) * step, y0 + height, 0);
    }
    for(std::size_t i = 0; i < n; ++i) {
      const std::size_t a = first + 2 * i;
      soup.triangles.push_back({a, a + 2, a + 3});
      soup.triangles.push_back({a, a + 3, a + 1});
    }
  }
  const auto np = CGAL::parameters::snapping_tolerance(t);
  const Canonical expected = in_memory(soup, np);
  for(std::size_t tiles : {2, 8}) {
    ST::Tiled_reconstruction_report report;
    std::vector<ST::Tile_progress> progress;
    const auto with_progress = ST::parameters::tile_progress([&](const ST::Tile_progress& p) { progress.push_back(p); }, np);
    EXPECT_TRUE(same(expected, tiled(soup, tiles, with_progress, &report))) << tiles << " tiles";
    EXPECT_GT(report.repeated_tiles, 0u) << tiles << " tiles";
    EXPECT_GT(report.discarded_triangles, 0u);
    EXPECT_GT(report.largest_halo, report.first_halo);
    EXPECT_LT(report.first_halo, 20 * t);
    // One call a run; the runs of each round counted up to the round's size; every owned triangle
    // kept in the end.
    ASSERT_EQ(progress.size(), report.tile_runs);
    EXPECT_EQ(progress.front().runs, tiles);
    EXPECT_GT(progress.back().round, 0u);
    for(std::size_t i = 0; i < progress.size(); ++i) {
      EXPECT_LE(progress[i].runs_done, progress[i].runs);
      if(i + 1 < progress.size() && progress[i + 1].round == progress[i].round) {
        EXPECT_EQ(progress[i + 1].runs_done, progress[i].runs_done + 1);
      }
      if(i > 0) {
        EXPECT_GE(progress[i].triangles_done, progress[i - 1].triangles_done);
      }
    }
    EXPECT_EQ(progress.back().runs_done, progress.back().runs);
    EXPECT_EQ(progress.back().triangles_done, soup.triangles.size());
    EXPECT_EQ(progress.back().triangles, soup.triangles.size());
  }
}

// Parts that share points on their borders, merged from part files and in memory: the same
// canonical soup, that of the parts' triangles put together; the files are removed with the
// merge's reader, and a truncated file or a triangle on a point the part lacks is refused.
TEST(TiledReconstruction, PartFilesMergeAsThePartsInMemory)
{
  std::mt19937 random(5);
  std::uniform_int_distribution<int> coordinate(0, 6);
  std::vector<ST::internal::Soup_part> parts(5);
  Soup whole;
  for(ST::internal::Soup_part& part : parts) {
    // points on a small grid: many are in several parts, some twice in one triangle's part
    for(int k = 0; k < 40; ++k) {
      const std::array<double, 3> q{{0.5 * coordinate(random), 0.25 * coordinate(random), double(coordinate(random))}};
      if(std::find(part.points.begin(), part.points.end(), q) == part.points.end()) part.points.push_back(q);
    }
    // every point used (as a part's are), then random triangles
    const std::uint32_t n = std::uint32_t(part.points.size());
    std::uniform_int_distribution<std::uint32_t> corner(0, n - 1);
    for(std::uint32_t k = 0; k < n + 60; ++k) {
      using Corners = std::array<std::uint32_t, 3>;
      const Corners t =
        k < n ? Corners{{k, (k + 1) % n, (k + 2) % n}} : Corners{{corner(random), corner(random), corner(random)}};
      part.triangles.push_back(t);
      const std::size_t first = whole.points.size();
      for(std::uint32_t v : t) whole.points.emplace_back(part.points[v][0], part.points[v][1], part.points[v][2]);
      whole.triangles.push_back({first, first + 1, first + 2});
    }
  }
  Canonical expected;
  ST::canonical_triangle_soup(whole.points, whole.triangles, expected.points, expected.triangles);

  const std::string folder = soup_test::temporary_folder("parts");
  std::vector<std::string> files;
  for(std::size_t k = 0; k < parts.size(); ++k) {
    files.push_back(ST::internal::part_file_name(folder, k));
    ST::internal::write_part_file(files.back(), parts[k]);
  }
  Canonical from_files;
  {
    ST::internal::Part_files reader(files);
    EXPECT_EQ(reader.number_of_points(2), parts[2].points.size());
    EXPECT_EQ(reader.number_of_triangles(2), parts[2].triangles.size());
    ST::internal::merge_in_canonical_order(reader, from_files.points, from_files.triangles);
  }
  EXPECT_TRUE(std::filesystem::is_empty(folder)) << "part files left in " << folder;
  Canonical in_memory_parts;
  ST::internal::merge_in_canonical_order(parts, in_memory_parts.points, in_memory_parts.triangles);
  EXPECT_TRUE(same(expected, from_files));
  EXPECT_TRUE(same(expected, in_memory_parts));
  for(const ST::internal::Soup_part& part : parts) EXPECT_TRUE(part.points.empty() && part.triangles.empty());

  ST::internal::Soup_part part;
  part.points = {{{0, 0, 0}}, {{1, 0, 0}}, {{0, 1, 0}}};
  part.triangles = {{{0, 1, 2}}};
  const std::string file = ST::internal::part_file_name(folder, 7);
  ST::internal::write_part_file(file, part);
  std::filesystem::resize_file(file, std::filesystem::file_size(file) - 1);
  EXPECT_THROW(ST::internal::Part_files({file}), ST::IO::Read_error);
  part.triangles = {{{0, 1, 3}}};
  ST::internal::write_part_file(file, part);
  {
    ST::internal::Part_files reader({file});
    Canonical c;
    EXPECT_THROW(ST::internal::merge_in_canonical_order(reader, c.points, c.triangles), ST::IO::Read_error);
  }
  EXPECT_TRUE(std::filesystem::is_empty(folder));
  std::filesystem::remove_all(folder);
}

// A crowd: 6,000 small triangles whose corners all lie within a tenth of the tolerance of each
// other, beside a large triangle. Following the taint there would read the whole crowd at each of
// its points (36 million answers a phase, minutes): the taint gives up within its budget, and the
// soup is repaired whole, as in memory.
TEST(TiledReconstruction, CrowdWithinTheToleranceIsRepairedWhole)
{
  Soup soup;
  const double t = 1e-3;
  std::mt19937 random(11);
  std::uniform_real_distribution<double> offset(0, 0.1 * t);
  for(std::size_t i = 0; i < 6000; ++i) {
    const std::size_t first = soup.points.size();
    for(int k = 0; k < 3; ++k) soup.points.emplace_back(0.5 + offset(random), 0.5 + offset(random), 0.5 + offset(random));
    soup.triangles.push_back({first, first + 1, first + 2});
  }
  const std::size_t first = soup.points.size();
  soup.points.emplace_back(0, 0, 0);
  soup.points.emplace_back(1, 0, 0);
  soup.points.emplace_back(0, 1, 0);
  soup.triangles.push_back({first, first + 1, first + 2});
  for(ST::Small_features policy : {ST::Small_features::COLLAPSE, ST::Small_features::REFUSE}) {
    const auto np = ST::parameters::small_features(policy, CGAL::parameters::snapping_tolerance(t));
    const Canonical expected = in_memory(soup, np);
    ST::Tiled_reconstruction_report report;
    EXPECT_TRUE(same(expected, tiled(soup, 4, np, &report)));
    EXPECT_TRUE(report.whole_soup);
    EXPECT_NE(report.whole_soup_reason.find("crowd"), std::string::npos) << report.whole_soup_reason;
  }
}

// Two strips along x meet at a seam that every tile boundary crosses: the upper strip's border
// has 200 edges, the lower strip's 400, 0.3 t below it and shifted along it by up to half the
// tolerance: welds and T-junctions at every depth of every region's edge, for a halo of twice the
// tolerance and for the default.
TEST(TiledReconstruction, SeamAcrossEveryTileBoundary)
{
  Soup soup;
  const double t = 1e-3;
  const std::size_t n = 200;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> shift(-0.5 * t, 0.5 * t);
  // upper strip: (i / n, 0) and (i / n, 0.01)
  for(std::size_t i = 0; i <= n; ++i) {
    soup.points.emplace_back(double(i) / n, 0, 0);
    soup.points.emplace_back(double(i) / n, 0.01, 0);
  }
  for(std::size_t i = 0; i < n; ++i) {
    const std::size_t a = 2 * i;
    soup.triangles.push_back({a, a + 2, a + 3});
    soup.triangles.push_back({a, a + 3, a + 1});
  }
  // lower strip: its top border has twice the vertices, the odd ones on the middles of the
  // upper strip's edges (T-junctions), all moved along x by up to t / 2
  const std::size_t first = soup.points.size();
  for(std::size_t i = 0; i <= 2 * n; ++i) {
    const double x = double(i) / double(2 * n) + (i == 0 || i == 2 * n ? 0.0 : shift(rng));
    soup.points.emplace_back(x, -0.3 * t, 0);
    soup.points.emplace_back(double(i) / double(2 * n), -0.01, 0);
  }
  for(std::size_t i = 0; i < 2 * n; ++i) {
    const std::size_t a = first + 2 * i;
    soup.triangles.push_back({a, a + 1, a + 3});
    soup.triangles.push_back({a, a + 3, a + 2});
  }
  const auto np = CGAL::parameters::snapping_tolerance(t);
  const Canonical expected = in_memory(soup, np);
  for(std::size_t tiles : {2, 8, 64}) {
    EXPECT_TRUE(same(expected, tiled(soup, tiles, np))) << tiles << " tiles";
    ST::Tiled_reconstruction_report report;
    EXPECT_TRUE(same(expected, tiled(soup, tiles, ST::parameters::tile_halo(2 * t, np), &report))) << tiles << " tiles, halo 2 t";
    EXPECT_GT(report.repeated_tiles, 0u) << tiles << " tiles";
  }
}

// The rules of the taint, one by one, on small soups with given depths (tolerance 1): which
// points each phase taints.
struct Taint_case
{
  std::vector<Point> points;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  std::vector<double> depth;

  // the points tainted by the phase `phase` ("weld" or "split") when `tainted_before` are
  std::vector<std::size_t> tainted_after(const std::string& phase, const std::vector<std::size_t>& tainted_before = {}) const
  {
    ST::internal::Tile_taint<CGAL::Epick> taint(points, depth, 1.0, false, CGAL::Epick());
    const ST::Adjacency_tables tables(triangles, points.size());
    for(std::size_t v : tainted_before) taint.taint(static_cast<ST::Adjacency_tables::size_type>(v));
    if(phase == "weld")
      taint.before_weld(points, tables);
    else
      taint.before_split(points, tables);
    std::vector<std::size_t> out;
    for(std::size_t v = 0; v < points.size(); ++v)
      if(taint.tainted(static_cast<ST::Adjacency_tables::size_type>(v))) out.push_back(v);
    return out;
  }
};

TEST(TiledReconstructionTaint, AWeldUnitWithAShallowMemberIsTainted)
{
  // Two separate triangles whose left corners 0 and 3 are 0.5 apart; a third far away.
  Taint_case c;
  c.points = {Point(0, 0, 0), Point(-10, 0, 0), Point(-10, 10, 0), Point(0.5, 0, 0), Point(10, 0, 0), Point(10, 10, 0),
              Point(100, 0, 0), Point(110, 0, 0), Point(110, 10, 0)};
  c.triangles = {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}};
  c.depth.assign(c.points.size(), 50.0);
  EXPECT_TRUE(c.tainted_after("weld").empty());
  // 3 shallow: its unit {0, 3} is tainted, and so are the units {4} and {5} (border vertices of
  // a triangle with a shallow corner); the far triangle is not.
  c.depth[3] = 0.5;
  EXPECT_EQ(c.tainted_after("weld"), (std::vector<std::size_t>{0, 3, 4, 5}));
  c.depth[3] = 50;
  c.depth[2] = 0.5; // a shallow corner of a triangle of member 0
  EXPECT_EQ(c.tainted_after("weld"), (std::vector<std::size_t>{0, 1, 2, 3}));
}

TEST(TiledReconstructionTaint, UnitsFollowTheToleranceGraphAndTheTrianglesThatAreNotRigid)
{
  // Border vertices 0, 3, 6 in a chain 0.9 apart (0 and 6 are 1.8 apart); 6 is shallow.
  Taint_case c;
  c.points = {Point(0, 0, 0),    Point(-10, 0, 0), Point(-10, 10, 0), Point(0.9, 0, 0), Point(0.9, -10, 0),
              Point(20, -10, 0), Point(1.8, 0, 0), Point(10, 0, 0),   Point(10, 10, 0)};
  c.triangles = {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}};
  c.depth.assign(c.points.size(), 50.0);
  c.depth[8] = 0.5;
  EXPECT_EQ(c.tainted_after("weld"), (std::vector<std::size_t>{0, 3, 6, 7, 8}));
  // A sliver (not rigid) joins a far border vertex 10 to vertex 0's unit; a fat triangle would not.
  Taint_case sliver = c;
  sliver.points[3] = Point(30, 0, 0); // the chain is cut: 0 alone, 6 alone
  sliver.points.push_back(Point(0.5, 20, 0));
  sliver.points.push_back(Point(0.4, 40, 0));
  sliver.depth.assign(sliver.points.size(), 50.0);
  sliver.depth[1] = 0.5;                       // 0's unit is tainted through its triangle
  sliver.triangles.push_back({0, 9, 10});      // a sliver from 0 to the far vertices 9, 10
  EXPECT_EQ(sliver.tainted_after("weld"), (std::vector<std::size_t>{0, 1, 2, 9, 10}));
  Taint_case fat = sliver;
  fat.points[9] = Point(20, 20, 0);
  fat.points[10] = Point(-20, 40, 0);
  EXPECT_EQ(fat.tainted_after("weld"), (std::vector<std::size_t>{0, 1, 2}));
}

TEST(TiledReconstructionTaint, ABorderVertexNearAStarThatMayDifferIsTainted)
{
  // A closed tetrahedron (no border vertex) with vertex 0 tainted, so vertex 1's star may differ
  // (1 may be a border vertex of the whole soup); a separate triangle's vertex 4 is 0.5 from 1.
  Taint_case c;
  c.points = {Point(0, 0, 0),  Point(10, 0, 0),  Point(0, 10, 0), Point(0, 0, 10),
              Point(10.5, 0, 0), Point(30, 0, 0), Point(20, 20, 0)};
  c.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}, {4, 5, 6}};
  c.depth.assign(c.points.size(), 50.0);
  EXPECT_TRUE(c.tainted_after("weld").empty());
  EXPECT_EQ(c.tainted_after("weld", {0}), (std::vector<std::size_t>{0, 4}));
}

TEST(TiledReconstructionTaint, ASplitNearTheRegionsEdgeOrNearTaintIsTainted)
{
  // Triangle 0 1 2 with border edge [0,1]; vertex 3, of another triangle, 0.5 from its middle.
  Taint_case c;
  c.points = {Point(0, 0, 0),    Point(10, 0, 0),  Point(5, 10, 0),   Point(5, -0.5, 0),
              Point(4, -10, 0),  Point(6, -10, 0), Point(50, 50, 0),  Point(60, 50, 0), Point(55, 60, 0)};
  c.triangles = {{0, 1, 2}, {3, 4, 5}, {6, 7, 8}};
  c.depth.assign(c.points.size(), 50.0);
  EXPECT_TRUE(c.tainted_after("split").empty());
  c.depth[3] = 0.8; // the vertex near the edge is shallow: the triangle it may split is tainted
  EXPECT_EQ(c.tainted_after("split"), (std::vector<std::size_t>{0, 1, 2, 3}));
  c.depth[3] = 50;
  c.depth[0] = c.depth[1] = 6; // the edge reaches within twice the tolerance of the region's edge
  EXPECT_EQ(c.tainted_after("split"), (std::vector<std::size_t>{0, 1, 2, 3}));
  c.depth[0] = c.depth[1] = 8; // not any more
  EXPECT_TRUE(c.tainted_after("split").empty());
  // A tainted vertex near the edge: the triangle is tainted (its split may differ).
  EXPECT_EQ(c.tainted_after("split", {3}), (std::vector<std::size_t>{0, 1, 2, 3}));
}

TEST(TiledReconstructionTaint, TaintSpreadsThroughDecisionsOnly)
{
  // Two triangles sharing edge [1,2]; vertex 0 is tainted. With no vertex within the tolerance of
  // an edge, a split phase taints nothing more: no ring of stars spreads.
  Taint_case c;
  c.points = {Point(0, 0, 0), Point(10, 0, 0), Point(5, 10, 0), Point(15, 10, 0), Point(30, 30, 0), Point(40, 30, 0),
              Point(35, 40, 0)};
  c.triangles = {{0, 1, 2}, {1, 3, 2}, {4, 5, 6}};
  c.depth.assign(c.points.size(), 50.0);
  EXPECT_EQ(c.tainted_after("split", {0}), (std::vector<std::size_t>{0}));
  // Vertex 4 a quarter of the tolerance from the shared edge, whose border status may differ (its
  // other triangle has a tainted corner): a split of the neighbour is possible in the whole soup,
  // so the neighbour's corners and vertex 4 are tainted.
  Taint_case near = c;
  near.points[4] = Point(7.5 + 0.25 * 10 / std::sqrt(125.0), 5 + 0.25 * 5 / std::sqrt(125.0), 0);
  EXPECT_EQ(near.tainted_after("split", {0}), (std::vector<std::size_t>{0, 1, 2, 3, 4}));
}

// A team of threads, one per "process", sharing a folder: the exchanges of the team protocol
// (a broadcast from rank 0, a gather of every rank's values) through a barrier.
class Thread_team_state
{
public:
  explicit Thread_team_state(std::size_t size)
    : size_(size), values_(size)
  {}
  std::size_t size() const { return size_; }
  void broadcast(std::size_t rank, std::vector<char>& bytes)
  {
    std::unique_lock<std::mutex> lock(mutex_);
    if(rank == 0) bytes_ = bytes;
    wait_for_all(lock);
    if(rank != 0) bytes = bytes_;
    wait_for_all(lock);
  }
  std::vector<std::uint64_t> all_gather(std::size_t rank, const std::vector<std::uint64_t>& mine)
  {
    std::unique_lock<std::mutex> lock(mutex_);
    values_[rank] = mine;
    wait_for_all(lock);
    std::vector<std::uint64_t> all;
    for(const auto& v : values_) all.insert(all.end(), v.begin(), v.end());
    wait_for_all(lock);
    return all;
  }
private:
  void wait_for_all(std::unique_lock<std::mutex>& lock)
  {
    const std::size_t generation = generation_;
    if(++arrived_ == size_) {
      arrived_ = 0;
      ++generation_;
      all_arrived_.notify_all();
    } else {
      all_arrived_.wait(lock, [&] { return generation_ != generation; });
    }
  }
  std::size_t size_, arrived_ = 0, generation_ = 0;
  std::mutex mutex_;
  std::condition_variable all_arrived_;
  std::vector<char> bytes_;
  std::vector<std::vector<std::uint64_t>> values_;
};

struct Thread_team
{
  Thread_team_state* state;
  std::size_t my_rank;
  std::size_t rank() const { return my_rank; }
  std::size_t size() const { return state->size(); }
  void broadcast(std::vector<char>& bytes) { state->broadcast(my_rank, bytes); }
  std::vector<std::uint64_t> all_gather(const std::vector<std::uint64_t>& v) { return state->all_gather(my_rank, v); }
};

// `tiled_reconstruct_topology()` by a team of `size` threads, one a process: the outputs and the
// reports, by rank.
template <class Source, class NamedParameters>
void run_in_team(std::size_t size, const Source& source, std::size_t tiles, const std::string& folder,
                 const NamedParameters& np, std::vector<Canonical>& outputs,
                 std::vector<ST::Tiled_reconstruction_report>& reports)
{
  Thread_team_state state(size);
  outputs.assign(size, Canonical());
  reports.assign(size, ST::Tiled_reconstruction_report());
  std::vector<std::thread> threads;
  for(std::size_t rank = 0; rank < size; ++rank)
    threads.emplace_back([&, rank] {
      Thread_team team{&state, rank};
      reports[rank] =
        ST::tiled_reconstruct_topology(team, source, tiles, folder, outputs[rank].points, outputs[rank].triangles, np);
    });
  for(std::thread& thread : threads) thread.join();
}

// The tiled repair by teams of 2, 3 and 5 threads gives the single process's output and report:
// the tiles repaired again (a first halo of twice the tolerance), a soup repaired whole (a crowd),
// and more processes than tiles.
TEST(TiledReconstruction, TeamsGiveTheSingleProcessResult)
{
  const Soup seams = jittered_seams("clean/elephant.off", 6, 1e-6, 5);
  const double t = 1e-5 * diagonal(seams.points);
  Soup crowd = seams;
  std::mt19937 random(4);
  std::uniform_real_distribution<double> offset(0, 0.1 * t);
  const Point centre = seams.points[seams.triangles[0][0]];
  for(std::size_t i = 0; i < 2000; ++i) {
    const std::size_t first = crowd.points.size();
    for(int k = 0; k < 3; ++k)
      crowd.points.emplace_back(centre.x() + offset(random), centre.y() + offset(random), centre.z() + offset(random));
    crowd.triangles.push_back({first, first + 1, first + 2});
  }
  struct Case
  {
    const Soup* soup;
    std::size_t tiles;
    bool whole;
  };
  for(const Case& c : {Case{&seams, 8, false}, Case{&crowd, 8, true}, Case{&seams, 2, false}}) {
    const auto np = ST::parameters::tile_halo(2 * t, CGAL::parameters::snapping_tolerance(t));
    ST::Tiled_reconstruction_report expected_report;
    const Canonical expected = tiled(*c.soup, c.tiles, np, &expected_report);
    EXPECT_EQ(expected_report.whole_soup, c.whole);
    if(!c.whole) {
      EXPECT_GT(expected_report.repeated_tiles, 0u);
    }
    const ST::Soup_triangle_source<std::vector<Point>, std::vector<Triangle>> source(c.soup->points, c.soup->triangles);
    for(std::size_t size : {2, 3, 5}) {
      const std::string folder = soup_test::temporary_folder("tiled_team");
      std::vector<Canonical> outputs;
      std::vector<ST::Tiled_reconstruction_report> reports;
      run_in_team(size, source, c.tiles, folder, np, outputs, reports);
      EXPECT_TRUE(same(expected, outputs[0])) << size << " processes, " << c.tiles << " tiles";
      const ST::Tiled_reconstruction_report& r = reports[0];
      EXPECT_EQ(r.tile_runs, expected_report.tile_runs) << size;
      EXPECT_EQ(r.repeated_tiles, expected_report.repeated_tiles) << size;
      EXPECT_EQ(r.discarded_triangles, expected_report.discarded_triangles) << size;
      EXPECT_EQ(r.largest_tile_triangles, expected_report.largest_tile_triangles) << size;
      EXPECT_EQ(r.largest_halo, expected_report.largest_halo) << size;
      EXPECT_EQ(r.halo_triangles, expected_report.halo_triangles) << size;
      EXPECT_EQ(r.whole_soup_reason, expected_report.whole_soup_reason) << size;
      for(std::size_t rank = 1; rank < size; ++rank) {
        EXPECT_TRUE(outputs[rank].triangles.empty());
        // The run of the whole soup is rank 0's alone.
        EXPECT_EQ(reports[rank].tile_runs + (r.whole_soup ? 1 : 0), r.tile_runs);
      }
      EXPECT_TRUE(std::filesystem::is_empty(folder)) << "files left in " << folder;
      std::filesystem::remove_all(folder);
    }
  }
}

// The tool: `repair --tiles N` writes the mesh that `repair` writes, triangle for triangle (the
// order aside): the pig (a binary STL, streamed) and ALSTOM_TEST4.off (read whole).
TEST(TiledReconstruction, ToolWritesTheSameMeshWithTiles)
{
  struct Case
  {
    std::string file, tolerance;
  };
  const std::string folder = soup_test::temporary_folder("tiled_tool");
  for(const Case& c : {Case{soup_test::data_file("cgal_repair/pig.stl.xz"), "0.3"},
                       Case{soup_test::data_file("cad/ALSTOM_TEST4.off"), "1e-6"}}) {
    std::vector<Canonical> written;
    for(const std::string tiles : {"", " --tiles 8"}) {
      const std::string out = folder + "/out.off";
      const auto r = soup_test::run_command("'" + std::string(SOUP_TOPOLOGY_CLI) + "' repair '" + c.file + "' -o '" + out +
                                            "' --json --tolerance " + c.tolerance + tiles + " 2>&1");
      ASSERT_EQ(r.second, 0) << r.first;
      if(!tiles.empty()) {
        EXPECT_EQ(soup_test::json_integer(r.first, "tiles"), 8) << r.first;
      }
      Soup soup;
      ST::IO::read_triangle_soup(out, soup.points, soup.triangles);
      written.emplace_back();
      ST::canonical_triangle_soup(soup.points, soup.triangles, written.back().points, written.back().triangles);
    }
    EXPECT_TRUE(same(written[0], written[1])) << c.file;
  }
  const auto bad = soup_test::run_command("'" + std::string(SOUP_TOPOLOGY_CLI) + "' repair '" +
                                          soup_test::data_file("cad/ALSTOM_TEST4.off") + "' -o '" + folder +
                                          "/out.off' --relative-tolerance 1e-6 --tiles 8 2>&1");
  EXPECT_EQ(bad.second, 2) << bad.first;
  EXPECT_NE(bad.first.find("--tiles needs an absolute --tolerance"), std::string::npos) << bad.first;
  std::filesystem::remove_all(folder);
}

// `repair --max-memory SIZE`: in memory when the model says the soup fits, in tiles when it does
// not (the same mesh), refused when SIZE is below what the output needs. A soup of about 90,000
// triangles (the elephant, subdivided twice, cut into patches with jittered seams), written as a
// binary STL: the tool reads its number of triangles from the header.
TEST(TiledReconstruction, ToolChoosesTheTilesForAMemoryLimit)
{
  auto [soup, d] = elephant_seam_soup();
  for(Point& p : soup.points) p = soup_test::rounded_to_float(p);
  const std::string folder = soup_test::temporary_folder("tiled_memory");
  const std::string in = folder + "/soup.stl";
  ST::IO::write_triangle_soup(in, soup.points, soup.triangles);
  char tolerance[32];
  std::snprintf(tolerance, sizeof tolerance, "%.17g", 1e-5 * d);
  const auto repair = [&](const std::string& limit, const std::string& out) {
    return soup_test::run_command("'" + std::string(SOUP_TOPOLOGY_CLI) + "' repair '" + in + "' -o '" + out +
                                  "' --json --tolerance " + tolerance + " --max-memory " + limit + " 2>&1");
  };
  const auto whole = repair("2G", folder + "/whole.off");
  ASSERT_EQ(whole.second, 0) << whole.first;
  EXPECT_EQ(soup_test::json_integer(whole.first, "tiles"), -1) << "in memory: " << whole.first;
  EXPECT_GT(soup_test::json_integer(whole.first, "modelled_peak"), 0) << whole.first;
  const Canonical expected = canonical_of_file(folder + "/whole.off");
  ASSERT_GT(expected.triangles.size(), 80000u);
  // Between the output's need and the whole soup's: tiles, the fewer the larger the limit.
  long long previous_tiles = 0;
  std::filesystem::create_directory(folder + "/spill");
  for(const std::string& limit : {std::string("50M"), "42M --spill-folder '" + folder + "/spill'"}) {
    const auto tiled_run = repair(limit, folder + "/tiled.off");
    ASSERT_EQ(tiled_run.second, 0) << tiled_run.first;
    const long long tiles = soup_test::json_integer(tiled_run.first, "tiles");
    EXPECT_GT(tiles, 1) << limit << ": " << tiled_run.first;
    EXPECT_GT(tiles, previous_tiles) << limit;
    previous_tiles = tiles;
    EXPECT_LE(soup_test::json_integer(tiled_run.first, "modelled_peak"),
              soup_test::json_integer(tiled_run.first, "max_memory")) << tiled_run.first;
    EXPECT_EQ(tiled_run.first.find("warning"), std::string::npos) << "a closed mesh is within the model: " << tiled_run.first;
    EXPECT_TRUE(same(expected, canonical_of_file(folder + "/tiled.off"))) << limit;
  }
  EXPECT_TRUE(std::filesystem::is_empty(folder + "/spill"));
  const auto too_small = repair("20M", folder + "/small.off");
  EXPECT_EQ(too_small.second, 2) << too_small.first;
  EXPECT_NE(too_small.first.find("too small"), std::string::npos) << too_small.first;
  EXPECT_FALSE(std::filesystem::exists(folder + "/small.off"));
  const auto with_tiles = repair("1G --tiles 4", folder + "/both.off");
  EXPECT_EQ(with_tiles.second, 2) << with_tiles.first;
  std::filesystem::remove_all(folder);
}

// Under `--max-memory`, an output whose orientation as a whole would not fit is oriented one part
// (whole components) at a time: the file of `--tiles N`, byte for byte. Four copies of the soup
// of ToolChoosesTheTilesForAMemoryLimit side by side (about 360,000 triangles): under 40M the
// whole output needs about 48 MB, its parts of one copy about 36 MB.
TEST(TiledReconstruction, ToolOrientsTheOutputInPartsUnderAMemoryLimit)
{
  const auto [copy, d] = elephant_seam_soup();
  Soup assembly;
  for(int k = 0; k < 4; ++k) {
    const std::size_t first = assembly.points.size();
    for(const Point& p : copy.points)
      assembly.points.push_back(soup_test::rounded_to_float(Point(p.x() + 2 * k * d, p.y(), p.z())));
    for(const auto& t : copy.triangles) assembly.triangles.push_back({first + t[0], first + t[1], first + t[2]});
  }
  const std::string folder = soup_test::temporary_folder("tiled_output_parts");
  const std::string in = folder + "/assembly.stl";
  ST::IO::write_triangle_soup(in, assembly.points, assembly.triangles);
  char tolerance[32];
  std::snprintf(tolerance, sizeof tolerance, "%.17g", 1e-5 * d);
  const auto repair = [&](const std::string& options, const std::string& out) {
    return soup_test::run_command("'" + std::string(SOUP_TOPOLOGY_CLI) + "' repair '" + in + "' -o '" + out +
                                  "' --json --tolerance " + tolerance + " " + options + " 2>&1");
  };
  const auto limited = repair("--max-memory 40M", folder + "/limited.stl");
  ASSERT_EQ(limited.second, 0) << limited.first;
  const long long tiles = soup_test::json_integer(limited.first, "tiles");
  EXPECT_GT(tiles, 1) << limited.first;
  EXPECT_EQ(soup_test::json_integer(limited.first, "output_parts"), 4) << limited.first;
  EXPECT_EQ(soup_test::json_integer(limited.first, "components"), 4) << limited.first;
  EXPECT_LE(soup_test::json_integer(limited.first, "modelled_peak"),
            soup_test::json_integer(limited.first, "max_memory"));
  EXPECT_EQ(limited.first.find("warning"), std::string::npos) << limited.first;
  const auto forced = repair("--tiles " + std::to_string(tiles), folder + "/forced.stl");
  ASSERT_EQ(forced.second, 0) << forced.first;
  EXPECT_EQ(soup_test::json_integer(forced.first, "output_parts"), -1) << "oriented whole: " << forced.first;
  std::ifstream a(folder + "/limited.stl", std::ios::binary), b(folder + "/forced.stl", std::ios::binary);
  const std::string limited_bytes((std::istreambuf_iterator<char>(a)), std::istreambuf_iterator<char>()),
    forced_bytes((std::istreambuf_iterator<char>(b)), std::istreambuf_iterator<char>());
  EXPECT_GT(limited_bytes.size(), 84u + 50u * 300000u);
  EXPECT_TRUE(limited_bytes == forced_bytes);
  for(const char* key :
      {"orientation_flips", "duplicated_points", "border_edges", "non_manifold_vertices", "output_vertices"})
    EXPECT_EQ(soup_test::json_integer(limited.first, key), soup_test::json_integer(forced.first, key)) << key;
  std::filesystem::remove_all(folder);
}

// Under `--max-memory`, a soup the tiles cannot decide (here one at 2^-900, in another unit) is
// repaired as one tile: the tool writes the result of the repair in memory and says on standard
// error that the limit was not allowed for.
TEST(TiledReconstruction, ToolWarnsWhenTheSoupIsRepairedWholeUnderAMemoryLimit)
{
  // (large enough for the limit to choose tiles: the soup of ToolChoosesTheTilesForAMemoryLimit)
  const Soup seams = elephant_seam_soup().soup;
  Soup far;
  for(const Point& p : seams.points)
    far.points.emplace_back(std::ldexp(p.x(), -900), std::ldexp(p.y(), -900), std::ldexp(p.z(), -900));
  far.triangles = seams.triangles;
  const std::string folder = soup_test::temporary_folder("tiled_whole_limit");
  const std::string in = folder + "/far.off";
  ST::IO::write_triangle_soup(in, far.points, far.triangles);
  char tolerance[32];
  std::snprintf(tolerance, sizeof tolerance, "%.17g", std::ldexp(1e-5 * diagonal(seams.points), -900));
  const auto repair = [&](const std::string& options, const std::string& out) {
    return soup_test::run_command("'" + std::string(SOUP_TOPOLOGY_CLI) + "' repair '" + in + "' -o '" + out +
                                  "' --json --tolerance " + tolerance + " " + options + " 2>&1");
  };
  const auto in_memory_run = repair("", folder + "/memory.off");
  ASSERT_EQ(in_memory_run.second, 0) << in_memory_run.first;
  const auto limited = repair("--max-memory 60M", folder + "/limited.off");
  ASSERT_EQ(limited.second, 0) << limited.first;
  EXPECT_GT(soup_test::json_integer(limited.first, "tiles"), 1) << limited.first;
  EXPECT_NE(limited.first.find("\"whole_soup\": true"), std::string::npos) << limited.first;
  EXPECT_NE(limited.first.find("warning: the soup was repaired as one tile (coordinates that reach"), std::string::npos)
    << limited.first;
  const Canonical ca = canonical_of_file(folder + "/memory.off");
  EXPECT_LT(ca.points.size(), far.points.size()); // (welded)
  EXPECT_TRUE(same(ca, canonical_of_file(folder + "/limited.off")));
  // With --tiles N and no limit, nothing to warn about.
  const auto forced = repair("--tiles 4", folder + "/forced.off");
  ASSERT_EQ(forced.second, 0) << forced.first;
  EXPECT_EQ(forced.first.find("warning:"), std::string::npos) << forced.first;
  std::filesystem::remove_all(folder);
}

// The files of an assembly given together (`repair A.stl B.stl -o OUT --tiles N`) are streamed
// as one soup: the pig cut into two binary STL files gives the file of the whole pig, byte for
// byte. Without tiles, or with a file that is not a binary STL, the tool refuses.
// The model of `--max-memory` takes one output point for two triangles, as on a closed mesh. A soup
// of 300,000 loose triangles keeps three points a triangle: the tool repairs it in tiles within
// the limit, then says on standard error that its output step needs more than the limit.
TEST(TiledReconstruction, ToolWarnsWhenTheOutputNeedsMoreThanTheModel)
{
  Soup loose;
  for(std::size_t k = 0; k < 300000; ++k) {
    const double x = double(k % 600), y = double(k / 600);
    const std::size_t first = loose.points.size();
    loose.points.emplace_back(x, y, 0);
    loose.points.emplace_back(x + 0.5, y, 0);
    loose.points.emplace_back(x, y + 0.5, 0);
    loose.triangles.push_back({first, first + 1, first + 2});
  }
  const std::string folder = soup_test::temporary_folder("tiled_loose");
  ST::IO::write_triangle_soup(folder + "/loose.stl", loose.points, loose.triangles);
  const auto run = soup_test::run_command("'" + std::string(SOUP_TOPOLOGY_CLI) + "' repair '" + folder + "/loose.stl' -o '" +
                                          folder + "/out.stl' --json --tolerance 1e-3 --max-memory 60M 2>&1");
  ASSERT_EQ(run.second, 0) << run.first;
  EXPECT_GT(soup_test::json_integer(run.first, "tiles"), 1) << run.first;
  EXPECT_EQ(soup_test::json_integer(run.first, "output_vertices"), 900000) << run.first;
  EXPECT_NE(run.first.find("warning: the repaired soup has 900000 points for 300000 triangles"), std::string::npos)
    << run.first;
  EXPECT_NE(run.first.find("above --max-memory 60M"), std::string::npos) << run.first;
  std::filesystem::remove_all(folder);
}

TEST(TiledReconstruction, ToolRepairsTheFilesOfAnAssemblyTogether)
{
  Soup pig;
  soup_test::read_data_mesh("cgal_repair/pig.stl.xz", pig.points, pig.triangles);
  const std::string folder = soup_test::temporary_folder("tiled_assembly");
  const std::size_t half = pig.triangles.size() / 2;
  const std::vector<Triangle> first(pig.triangles.begin(), pig.triangles.begin() + std::ptrdiff_t(half)),
    second(pig.triangles.begin() + std::ptrdiff_t(half), pig.triangles.end());
  ST::IO::write_triangle_soup(folder + "/whole.stl", pig.points, pig.triangles);
  ST::IO::write_triangle_soup(folder + "/front.stl", pig.points, first);
  ST::IO::write_triangle_soup(folder + "/back.stl", pig.points, second);
  const std::string tool = "'" + std::string(SOUP_TOPOLOGY_CLI) + "' repair ";
  const auto whole = soup_test::run_command(tool + "'" + folder + "/whole.stl' -o '" + folder +
                                            "/whole.off' --tolerance 0.3 --tiles 4 2>&1");
  ASSERT_EQ(whole.second, 0) << whole.first;
  for(const std::string limit : {"--tiles 4", "--max-memory 1G"}) {
    const auto parts = soup_test::run_command(tool + "'" + folder + "/front.stl' '" + folder + "/back.stl' -o '" + folder +
                                              "/parts.off' --json --tolerance 0.3 " + limit + " 2>&1");
    ASSERT_EQ(parts.second, 0) << parts.first;
    EXPECT_NE(parts.first.find("front.stl " + folder + "/back.stl\""), std::string::npos) << parts.first;
    EXPECT_EQ(soup_test::json_integer(parts.first, "input_triangles"), static_cast<long long>(pig.triangles.size()));
    std::ifstream a(folder + "/whole.off"), b(folder + "/parts.off");
    const std::string whole_text((std::istreambuf_iterator<char>(a)), std::istreambuf_iterator<char>()),
      parts_text((std::istreambuf_iterator<char>(b)), std::istreambuf_iterator<char>());
    if(limit == "--tiles 4") {
      EXPECT_EQ(whole_text, parts_text);
    } else {
      // In one tile: the same mesh, in the canonical order too.
      EXPECT_EQ(soup_test::json_integer(parts.first, "tiles"), 1) << parts.first;
      EXPECT_TRUE(same(canonical_of_file(folder + "/whole.off"), canonical_of_file(folder + "/parts.off")));
    }
  }
  const auto untiled = soup_test::run_command(tool + "'" + folder + "/front.stl' '" + folder + "/back.stl' -o '" + folder +
                                              "/x.off' --tolerance 0.3 2>&1");
  EXPECT_EQ(untiled.second, 2) << untiled.first;
  EXPECT_NE(untiled.first.find("--tiles N or --max-memory"), std::string::npos) << untiled.first;
  const auto mixed = soup_test::run_command(tool + "'" + folder + "/front.stl' '" + soup_test::data_file("cad/ALSTOM_TEST4.off") +
                                            "' -o '" + folder + "/x.off' --tolerance 0.3 --tiles 2 2>&1");
  EXPECT_EQ(mixed.second, 2) << mixed.first;
  EXPECT_NE(mixed.first.find("not a binary STL"), std::string::npos) << mixed.first;
  const auto onto_input = soup_test::run_command(tool + "'" + folder + "/front.stl' '" + folder + "/back.stl' -o '" + folder +
                                                 "/back.stl' --tolerance 0.3 --tiles 2 2>&1");
  EXPECT_EQ(onto_input.second, 2) << onto_input.first;
  EXPECT_FALSE(std::filesystem::exists(folder + "/x.off"));
  std::filesystem::remove_all(folder);
}

TEST(TiledReconstruction, CanonicalOrder)
{
  // Two triangles on a repeated point and an unused one; the same soup reindexed, rotated and
  // reordered has the same canonical order; a reversed triangle does not.
  const std::vector<Point> points = {Point(1, 0, 0), Point(0, 0, 0), Point(9, 9, 9), Point(0, 1, 0), Point(1, 0, 0),
                                     Point(1, 1, 0)};
  const std::vector<Triangle> triangles = {{1, 0, 3}, {4, 5, 3}};
  Canonical c;
  ST::canonical_triangle_soup(points, triangles, c.points, c.triangles);
  EXPECT_EQ(c.points, (std::vector<Point>{Point(0, 0, 0), Point(0, 1, 0), Point(1, 0, 0), Point(1, 1, 0)}));
  EXPECT_EQ(c.triangles, (std::vector<Out_triangle>{{0, 2, 1}, {1, 2, 3}}));
  const std::vector<Point> other_points = {Point(1, 1, 0), Point(0, 1, 0), Point(1, 0, 0), Point(0, 0, 0)};
  Canonical d;
  ST::canonical_triangle_soup(other_points, std::vector<Triangle>{{1, 2, 0}, {2, 1, 3}}, d.points, d.triangles);
  EXPECT_TRUE(same(c, d));
  ST::canonical_triangle_soup(other_points, std::vector<Triangle>{{1, 2, 0}, {1, 2, 3}}, d.points, d.triangles);
  EXPECT_FALSE(same(c, d));
}

// Coordinates beyond 2^128 or below 2^-128 (a file in another unit): the tiles' plan, halos and
// taint work at the input's scale (near 1e-270 the squared lengths rounded to 0 and nothing was
// welded; such a soup was then refused). It is repaired as one tile, scaled by a power of two as
// in memory: the in-memory result, which is the soup at a moderate scale repaired and scaled, on
// one process and in a team of three.
TEST(TiledReconstruction, SoupAtAnExtremeScaleIsRepairedWholeAsInMemory)
{
  const Soup seams = jittered_seams("clean/elephant.off", 6, 1e-6, 5);
  const double t = 1e-5 * diagonal(seams.points);
  const Canonical moderate = in_memory(seams, CGAL::parameters::snapping_tolerance(t));
  ASSERT_LT(moderate.points.size(), seams.points.size()); // (the tolerance welds)
  for(int k : {-900, -140, 140, 1000}) {
    SCOPED_TRACE("2^" + std::to_string(k));
    Soup far;
    for(const Point& p : seams.points)
      far.points.emplace_back(std::ldexp(p.x(), k), std::ldexp(p.y(), k), std::ldexp(p.z(), k));
    far.triangles = seams.triangles;
    const auto np = CGAL::parameters::snapping_tolerance(std::ldexp(t, k));
    const Canonical expected = in_memory(far, np);
    Canonical scaled_moderate;
    for(const Point& p : moderate.points)
      scaled_moderate.points.emplace_back(std::ldexp(p.x(), k), std::ldexp(p.y(), k), std::ldexp(p.z(), k));
    scaled_moderate.triangles = moderate.triangles;
    EXPECT_TRUE(same(scaled_moderate, expected));
    ST::Tiled_reconstruction_report report;
    EXPECT_TRUE(same(expected, tiled(far, 8, np, &report)));
    EXPECT_TRUE(report.whole_soup);
    EXPECT_NE(report.whole_soup_reason.find("beyond 2^128 or below 2^-128"), std::string::npos)
      << report.whole_soup_reason;
    EXPECT_EQ(report.tile_runs, 1u);

    const ST::Soup_triangle_source<std::vector<Point>, std::vector<Triangle>> source(far.points, far.triangles);
    const std::string folder = soup_test::temporary_folder("tiled_extreme_team");
    constexpr std::size_t size = 3;
    std::vector<Canonical> outputs;
    std::vector<ST::Tiled_reconstruction_report> reports;
    run_in_team(size, source, 8, folder, np, outputs, reports);
    EXPECT_TRUE(same(expected, outputs[0]));
    for(std::size_t rank = 0; rank < size; ++rank) {
      EXPECT_EQ(reports[rank].whole_soup_reason, report.whole_soup_reason) << rank;
      if(rank > 0) {
        EXPECT_TRUE(outputs[rank].triangles.empty()) << rank;
      }
    }
    EXPECT_TRUE(std::filesystem::is_empty(folder)) << "files left in " << folder;
    std::filesystem::remove_all(folder);
  }
}

TEST(TiledReconstruction, BadArgumentsAreRefused)
{
  Soup soup;
  soup.points = {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0)};
  soup.triangles = {{0, 1, 2}};
  const std::string folder = soup_test::temporary_folder("tiled_bad");
  std::vector<Point> points;
  std::vector<Out_triangle> triangles;
  ST::Soup_triangle_source<std::vector<Point>, std::vector<Triangle>> source(soup.points, soup.triangles);
  EXPECT_THROW(ST::tiled_reconstruct_topology(source, 2, folder, points, triangles, CGAL::parameters::snapping_tolerance(-1.0)),
               ST::Invalid_input);
  EXPECT_THROW(ST::tiled_reconstruct_topology(source, 0, folder, points, triangles, CGAL::parameters::snapping_tolerance(1.0)),
               ST::Invalid_input);
  // A tolerance whose doubled square overflows is refused; a tiny one is the exact weld, as in
  // memory.
  try {
    ST::tiled_reconstruct_topology(source, 2, folder, points, triangles, CGAL::parameters::snapping_tolerance(1e160));
    ADD_FAILURE() << "not refused";
  } catch(const ST::Invalid_input& e) {
    EXPECT_NE(std::string(e.what()).find("is too large"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(std::filesystem::is_empty(folder)) << "spilled before the refusal";
  EXPECT_NO_THROW(ST::tiled_reconstruct_topology(source, 2, folder, points, triangles,
                                                 CGAL::parameters::snapping_tolerance(1e-160)));
  Soup near;
  for(const Point& p : soup.points) near.points.emplace_back(std::ldexp(p.x(), 120), std::ldexp(p.y(), 120), 0);
  near.triangles = soup.triangles;
  ST::Soup_triangle_source<std::vector<Point>, std::vector<Triangle>> near_source(near.points, near.triangles);
  ST::Tiled_reconstruction_report report;
  EXPECT_NO_THROW(report = ST::tiled_reconstruct_topology(near_source, 2, folder, points, triangles,
                                                          CGAL::parameters::snapping_tolerance(std::ldexp(1e-3, 120))));
  EXPECT_FALSE(report.whole_soup) << report.whole_soup_reason;
  std::filesystem::remove_all(folder);
}

} // namespace

} // namespace tiled_reconstruct_topology_test
