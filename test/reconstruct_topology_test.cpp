// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// T-junction splitting and the whole pipeline: the patent's Figure 7, CGAL's snapping and
// stitching inputs, CAD patches, generated T-junction soups, FaceGraph output.

#include <Soup_topology/reconstruct_topology.h>
#include <Soup_topology/split_t_junctions.h>

#include "soup_generators.h"
#include "test_utilities.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/internal/Snapping/snap.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numeric>
#include <random>
#include <set>
#include <vector>

// The headers of the issue-20 part below, included here too: no #include may be inside the
// namespace that holds the whole file.
#include <CGAL/Point_set_3.h>
#include <CGAL/Polygon_mesh_processing/polygon_mesh_to_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Simple_cartesian.h>
#include <Soup_topology/internal/triangulate_polygon.h>

// The names of this file live in a namespace of its own: test/CMakeLists.txt compiles several
// test files as one translation unit.
namespace reconstruct_topology_test {

namespace {

namespace ST = Soup_topology;
namespace PMP = CGAL::Polygon_mesh_processing;
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;
using Point = Epick::Point_3;
using Triangle = std::array<std::size_t, 3>;
using Tables = ST::Adjacency_tables;
using Mesh = CGAL::Surface_mesh<Point>;

std::size_t border_edges(const Mesh& m)
{
  std::size_t n = 0;
  for(auto h : halfedges(m)) if(is_border(h, m)) ++n;
  return n;
}

std::size_t count_border(const std::vector<Triangle>& t) { return soup_test::count_border_and_non_manifold_edges(t).first; }

// ---------------------------------------------------------------------------------------------
// The patent's Figure 7: V8 = (0,0,1) on the edge V1-V3 of T0.

TEST(PatentCube, Figure7SplitGivesTables16To18AndClosesTheCube)
{
  std::vector<Point> points = {Point(-1, -1, 1), Point(1, -1, 1), Point(1, 1, 1), Point(-1, 1, 1), Point(-1, -1, -1),
                               Point(1, -1, -1), Point(1, 1, -1), Point(-1, 1, -1), Point(0, 0, 1)};
  // T0, T1a, T1b, T2..T11 (indices 0, 1, 2, 3..12).
  std::vector<Triangle> triangles = {{0, 1, 3}, {2, 8, 1}, {2, 3, 8}, {2, 6, 3}, {7, 3, 6}, {2, 1, 6}, {5, 6, 1},
                                     {4, 7, 5}, {6, 5, 7}, {1, 0, 5}, {4, 5, 0}, {3, 7, 0}, {4, 0, 7}};
  Tables tables(triangles, points.size());
  ASSERT_EQ(tables.number_of_border_edges(), 3u);
  const ST::Split_report r = ST::split_t_junctions(points, triangles, tables);
  EXPECT_EQ(r.t_junctions, 1u);
  EXPECT_EQ(r.split_triangles, 1u);
  EXPECT_EQ(r.border_edges_after, 0u);
  ASSERT_EQ(triangles.size(), 14u);
  EXPECT_EQ(triangles[0], (Triangle{0, 1, 8}));   // T0 of table (14)
  EXPECT_EQ(triangles[13], (Triangle{0, 8, 3}));  // T12
  // Table (18): T0 -> T8 T1a T12, T1a -> T1b T0 T4, T1b -> T2 T12 T1a, T12 -> T0 T1b T10.
  const std::array<std::array<Tables::size_type, 3>, 4> expected = {{{9, 1, 13}, {2, 0, 5}, {3, 13, 1}, {0, 2, 11}}};
  const Tables::size_type rows[4] = {0, 1, 2, 13};
  for(std::size_t k = 0; k < 4; ++k)
    for(std::size_t i = 0; i < 3; ++i)
      EXPECT_EQ(tables.neighbor(rows[k], static_cast<int>(i)), expected[k][i]) << "row " << k << " edge " << i;
  EXPECT_TRUE(tables.is_closed());
  EXPECT_EQ(Tables(triangles, points.size()).number_of_border_edges(), 0u);
}

TEST(SplitTJunctions, SeveralVerticesOnOneEdgeAreSplitInOrder)
{
  // A big triangle (0,1,2) whose edge (0,1) meets a strip of three small triangles from below.
  std::vector<Point> points = {Point(0, 0, 0), Point(4, 0, 0), Point(2, 3, 0), Point(3, 0, 0), Point(1, 0, 0),
                               Point(2, 0, 0), Point(2, -2, 0)};
  std::vector<Triangle> triangles = {{0, 1, 2}, {4, 0, 6}, {5, 4, 6}, {3, 5, 6}, {1, 3, 6}};
  Tables tables(triangles, points.size());
  const ST::Split_report r = ST::split_t_junctions(points, triangles, tables);
  EXPECT_EQ(r.t_junctions, 3u);
  EXPECT_EQ(r.split_triangles, 3u);
  EXPECT_EQ(triangles.size(), 8u);
  EXPECT_EQ(count_border(triangles), 4u); // only the outer boundary is left
  EXPECT_TRUE(Tables(triangles, points.size()).inconsistently_oriented_edges().empty());
}

TEST(SplitTJunctions, NoSplitWhereTheOtherSideOverlapsOrIsAway)
{
  // Vertices 3 and 4 lie on edge (0,1), but their triangle (3,4,5) lies on the same side as
  // triangle (0,1,2): an overlap, refused.
  std::vector<Point> points = {Point(0, 0, 0), Point(4, 0, 0), Point(2, 3, 0), Point(2, 0, 0), Point(3, 0, 0),
                               Point(2.5, 1, 0)};
  std::vector<Triangle> triangles = {{0, 1, 2}, {3, 4, 5}};
  const ST::Split_report r = ST::split_t_junctions(points, triangles);
  EXPECT_EQ(r.split_triangles, 0u);
  EXPECT_EQ(r.refused_overlap, 2u);
  // A vertex near the edge without a border edge running along it is not a T-junction.
  std::vector<Point> p2 = {Point(0, 0, 0), Point(4, 0, 0), Point(2, 3, 0), Point(2, 0, 0), Point(2, -1, 5), Point(3, -1, 5)};
  std::vector<Triangle> t2 = {{0, 1, 2}, {3, 5, 4}};
  EXPECT_EQ(ST::split_t_junctions(p2, t2).split_triangles, 0u);
}

// ---------------------------------------------------------------------------------------------
// The pipeline

template <class P>
std::pair<std::vector<P>, std::vector<Triangle>> load(const std::string& relative)
{
  std::vector<P> points;
  std::vector<Triangle> triangles;
  soup_test::read_data_mesh(relative, points, triangles);
  return {points, triangles};
}

void expect_no_degenerate(const std::vector<Point>& points, const std::vector<Triangle>& triangles)
{
  Epick::Collinear_3 collinear;
  std::size_t degenerate = 0;
  for(const Triangle& t : triangles) if(collinear(points[t[0]], points[t[1]], points[t[2]])) ++degenerate;
  EXPECT_EQ(degenerate, 0u);
}

TEST(Pipeline, PigWithTheGoodToleranceBeatsCGALSnapAndStitch)
{
  auto [points, triangles] = load<Point>("cgal_repair/pig.stl.xz");
  // CGAL: the soup as a mesh, then snap_borders + stitch_borders with the same tolerance.
  Mesh cgal;
  {
    auto p = points;
    std::vector<std::vector<std::size_t>> polygons;
    for(const Triangle& t : triangles) polygons.push_back({t[0], t[1], t[2]});
    PMP::orient_polygon_soup(p, polygons);
    PMP::polygon_soup_to_polygon_mesh(p, polygons, cgal);
    PMP::experimental::snap_borders(cgal, CGAL::Constant_property_map<Mesh::Vertex_index, double>(0.3));
    PMP::stitch_borders(cgal);
  }
  const std::size_t cgal_border = border_edges(cgal);

  Mesh ours;
  const ST::Reconstruction_report r =
    ST::reconstruct_topology(points, triangles, ours, CGAL::parameters::snapping_tolerance(0.3));
  EXPECT_TRUE(CGAL::is_valid_polygon_mesh(ours));
  EXPECT_EQ(r.border_edges_before, 1296u);
  EXPECT_LT(r.border_edges_after, r.border_edges_before / 4);
  EXPECT_LE(border_edges(ours), cgal_border) << "CGAL leaves " << cgal_border << " border edges";
  EXPECT_LE(r.max_displacement, 0.3);
  EXPECT_GT(r.t_junctions, 0u);
  RecordProperty("cgal_border_edges", static_cast<int>(cgal_border));
  RecordProperty("our_border_edges", static_cast<int>(border_edges(ours)));
  // The soup version: no degenerate triangle.
  auto [p2, t2] = load<Point>("cgal_repair/pig.stl.xz");
  const ST::Reconstruction_report r2 = ST::reconstruct_topology(p2, t2, CGAL::parameters::snapping_tolerance(0.3));
  expect_no_degenerate(p2, t2);
  EXPECT_EQ(r2.border_edges_after, r.border_edges_after);
}

TEST(Pipeline, PigWithATooSmallToleranceIsNotHarmed)
{
  auto [points, triangles] = load<Point>("cgal_repair/pig.stl.xz");
  const auto before = triangles;
  const ST::Reconstruction_report r = ST::reconstruct_topology(points, triangles, CGAL::parameters::snapping_tolerance(0.001));
  expect_no_degenerate(points, triangles);
  EXPECT_LE(r.border_edges_after, r.border_edges_before);
  EXPECT_LE(r.max_displacement, 0.001);
  Mesh mesh;
  ST::reconstruct_topology(load<Point>("cgal_repair/pig.stl.xz").first, before, mesh,
                           CGAL::parameters::snapping_tolerance(0.001));
  EXPECT_TRUE(CGAL::is_valid_polygon_mesh(mesh));
}

TEST(Pipeline, AlstomCadPatchesCloseTheirTJunctions)
{
  auto [points, triangles] = load<Point>("cad/ALSTOM_TEST4.off");
  const double diag = ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>());
  Mesh mesh;
  const ST::Reconstruction_report r =
    ST::reconstruct_topology(points, triangles, mesh, ST::parameters::relative_tolerance(1e-4));
  EXPECT_EQ(r.border_edges_before, 231u);
  // The 6 patches become at most 2 pieces; what stays open is the part's own boundary (its
  // border vertices are farther than the tolerance from any other border edge) and 12 vertices
  // within twice the tolerance of an edge's end point, where the minimum feature separation is
  // not met (ALSTOM's shortest edges are about 1e-4 of the diagonal): left alone, reported.
  EXPECT_LE(r.border_edges_after, 218u);
  EXPECT_GE(r.t_junctions, 15u);
  EXPECT_LE(r.components, 2u);
  EXPECT_GT(r.ambiguous_t_junctions, 0u);
  // With twice the tolerance the patches become one piece.
  auto [p2, t2] = load<Point>("cad/ALSTOM_TEST4.off");
  const ST::Reconstruction_report r2 = ST::reconstruct_topology(p2, t2, ST::parameters::relative_tolerance(2e-4));
  EXPECT_EQ(r2.components, 1u);
  EXPECT_LT(r2.border_edges_after, r.border_edges_after);
  EXPECT_LE(r.max_displacement, 1e-4 * diag);
  EXPECT_TRUE(CGAL::is_valid_polygon_mesh(mesh));
  RecordProperty("border_edges_after", static_cast<int>(r.border_edges_after));
}

TEST(Pipeline, ATrueCrackWiderThanTheToleranceStaysOpen)
{
  // Two squares 0.01 apart; tolerance 0.001: nothing is glued.
  std::vector<Point> points = {Point(0, 0, 0), Point(1, 0, 0), Point(1, 1, 0), Point(0, 1, 0),
                               Point(1.01, 0, 0), Point(2, 0, 0), Point(2, 1, 0), Point(1.01, 1, 0)};
  std::vector<Triangle> triangles = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}};
  const ST::Reconstruction_report r = ST::reconstruct_topology(points, triangles, CGAL::parameters::snapping_tolerance(0.001));
  EXPECT_EQ(r.snapped_vertices, 0u);
  EXPECT_EQ(r.split_triangles, 0u);
  EXPECT_EQ(r.border_edges_after, 8u);
  EXPECT_EQ(r.components, 2u);
  // With 0.02 it closes the seam.
  const ST::Reconstruction_report r2 = ST::reconstruct_topology(points, triangles, CGAL::parameters::snapping_tolerance(0.02));
  EXPECT_EQ(r2.border_edges_after, 6u);
  EXPECT_EQ(r2.components, 1u);
}

// Generated T-junction soups from every clean mesh.
class TJunctionSoup : public ::testing::TestWithParam<const char*> {};

TEST_P(TJunctionSoup, ClosedManifoldOrientedAndOrderIndependent)
{
  auto [points, triangles] = load<Point>(GetParam());
  const double diag = ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>());
  const Tables original(triangles, points.size());
  auto soup = soup_test::t_junction_soup(points, triangles, 5, 1e-7 * diag / std::sqrt(3.0), 17);
  ASSERT_GT(soup.t_junctions, 10u);
  const std::vector<Point> input_points = soup.points;
  const auto np = CGAL::parameters::snapping_tolerance(1e-6 * diag);

  auto p = soup.points;
  auto t = soup.triangles;
  const ST::Reconstruction_report r = ST::reconstruct_topology(p, t, np);
  EXPECT_EQ(r.border_edges_after, original.number_of_border_edges());
  EXPECT_EQ(r.non_manifold_edges_after, 0u);
  EXPECT_EQ(r.split_triangles, soup.t_junctions);
  EXPECT_LE(r.max_displacement, 1e-6 * diag);
  EXPECT_EQ(r.refused_welds(), 0u);
  // Every output point is one of the input points: nothing is constructed.
  {
    std::set<std::array<double, 3>> in;
    for(const Point& q : input_points) in.insert({q.x(), q.y(), q.z()});
    for(const Point& q : p) EXPECT_TRUE(in.count({q.x(), q.y(), q.z()}));
  }

  Mesh mesh;
  ST::reconstruct_topology(soup.points, soup.triangles, mesh, np);
  EXPECT_TRUE(CGAL::is_valid_polygon_mesh(mesh));
  if(original.is_closed()) {
    EXPECT_TRUE(CGAL::is_closed(mesh));
    EXPECT_TRUE(PMP::is_outward_oriented(mesh));
  }

  // Shuffled triangles and rotated corners: the same triangles.
  std::mt19937 rng(5);
  std::vector<std::size_t> perm(soup.triangles.size());
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), rng);
  std::vector<Triangle> shuffled;
  for(std::size_t k : perm) {
    const Triangle& q = soup.triangles[k];
    const std::size_t s = static_cast<std::size_t>(rng() % 3);
    shuffled.push_back({q[s], q[(s + 1) % 3], q[(s + 2) % 3]});
  }
  auto p2 = soup.points;
  ST::reconstruct_topology(p2, shuffled, np);
  auto canonical = [](const std::vector<Point>& pts, const std::vector<Triangle>& tris) {
    std::multiset<std::array<std::array<double, 3>, 3>> out;
    for(const Triangle& q : tris) {
      std::array<std::array<double, 3>, 3> c;
      for(std::size_t k = 0; k < 3; ++k) c[k] = {pts[q[k]].x(), pts[q[k]].y(), pts[q[k]].z()};
      const std::size_t s = static_cast<std::size_t>(std::min_element(c.begin(), c.end()) - c.begin());
      out.insert({c[s], c[(s + 1) % 3], c[(s + 2) % 3]});
    }
    return out;
  };
  EXPECT_EQ(canonical(p, t), canonical(p2, shuffled));
}

INSTANTIATE_TEST_SUITE_P(RealMeshes, TJunctionSoup,
                         ::testing::Values("clean/elephant.off", "clean/fandisk.off.xz",
                                           "clean/ChineseDragon-10kv.off.xz", "clean/armadillo.off.xz",
                                           "clean/bunny00.off.xz", "clean/refined_elephant.off.xz"));

// CGAL's stitching inputs: every pair CGAL's own test stitches is stitched by us too.
TEST(Pipeline, CGALStitchingInputs)
{
  struct Case { const char* file; std::size_t cgal_stitched_pairs; };
  const Case cases[] = {
    {"cgal_repair/data_stitching/pinched.off", 2}, {"cgal_repair/quads_to_stitch.off", 4},
    {"cgal_repair/data_stitching/incidence_3.off", 3}, {"cgal_repair/data_stitching/incoherent_patch_orientation.off", 1},
    {"cgal_repair/data_stitching/non_manifold.off", 0}, {"cgal_repair/data_stitching/non_manifold2.off", 0},
    {"cgal_repair/data_stitching/nm_cubes.off", 4}, {"cgal_repair/data_stitching/deg_border.off", 2},
  };
  for(const Case& c : cases) {
    SCOPED_TRACE(c.file);
    // The raw file, as CGAL reads it: border edges before any weld.
    std::vector<Point> raw_points;
    std::vector<std::vector<std::size_t>> raw_polygons;
    ASSERT_TRUE(CGAL::IO::read_polygon_soup(soup_test::data_file(c.file), raw_points, raw_polygons));
    std::vector<Triangle> raw;
    for(const auto& poly : raw_polygons)
      for(std::size_t k = 1; k + 1 < poly.size(); ++k) raw.push_back({poly[0], poly[k], poly[k + 1]});
    const std::size_t raw_border = count_border(raw);
    Mesh mesh;
    const ST::Reconstruction_report r = ST::reconstruct_topology(raw_points, raw, mesh);
    EXPECT_TRUE(CGAL::is_valid_polygon_mesh(mesh));
    // Each stitched pair removes two border edges.
    EXPECT_LE(r.border_edges_after + 2 * c.cgal_stitched_pairs, raw_border)
      << "raw " << raw_border << ", after " << r.border_edges_after;
  }
}

TEST(Pipeline, PolyhedronAndEpeck)
{
  auto [points, triangles] = load<Point>("cgal_repair/pig.stl.xz");
  CGAL::Polyhedron_3<Epick> poly;
  const ST::Reconstruction_report r = ST::reconstruct_topology(points, triangles, poly, CGAL::parameters::snapping_tolerance(0.3));
  EXPECT_TRUE(CGAL::is_valid_polygon_mesh(poly));
  EXPECT_EQ(num_faces(poly), r.output_triangles - r.duplicate_triangles);

  // Epeck gives the same decisions as Epick on the same coordinates.
  std::vector<Epeck::Point_3> ep;
  for(const Point& p : points) ep.emplace_back(p.x(), p.y(), p.z());
  auto t1 = triangles;
  auto t2 = triangles;
  auto p1 = points;
  const ST::Reconstruction_report a = ST::reconstruct_topology(p1, t1, CGAL::parameters::snapping_tolerance(0.3));
  const ST::Reconstruction_report b = ST::reconstruct_topology(ep, t2, CGAL::parameters::snapping_tolerance(Epeck::FT(0.3)));
  EXPECT_EQ(t1, t2);
  EXPECT_EQ(a.split_triangles, b.split_triangles);
  EXPECT_EQ(a.snapped_vertices, b.snapped_vertices);
  CGAL::Surface_mesh<Epeck::Point_3> exact_mesh;
  ST::reconstruct_topology(ep, t2, exact_mesh);
  EXPECT_TRUE(CGAL::is_valid_polygon_mesh(exact_mesh));
}

TEST(Pipeline, RunningTwiceChangesNothing)
{
  auto [points, triangles] = load<Point>("cgal_repair/pig.stl.xz");
  ST::reconstruct_topology(points, triangles, CGAL::parameters::snapping_tolerance(0.3));
  const auto p1 = points;
  const auto t1 = triangles;
  const ST::Reconstruction_report r = ST::reconstruct_topology(points, triangles, CGAL::parameters::snapping_tolerance(0.3));
  EXPECT_EQ(r.snapped_vertices, 0u);
  EXPECT_EQ(r.split_triangles, 0u);
  EXPECT_EQ(points, p1);
  EXPECT_EQ(triangles, t1);
}

TEST(Pipeline, BadInputLeavesTheDataUnchanged)
{
  std::vector<Point> points = {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0)};
  std::vector<Triangle> triangles = {{0, 1, 2}, {0, 1, 5}};
  const auto p0 = points;
  const auto t0 = triangles;
  EXPECT_THROW(ST::reconstruct_topology(points, triangles), ST::Invalid_input);
  EXPECT_EQ(points, p0);
  EXPECT_EQ(triangles, t0);
  triangles = {{0, 1, 2}};
  EXPECT_THROW(ST::reconstruct_topology(points, triangles, CGAL::parameters::snapping_tolerance(-1.0)), ST::Invalid_input);
  points[1] = Point(std::numeric_limits<double>::quiet_NaN(), 0, 0);
  EXPECT_THROW(ST::reconstruct_topology(points, triangles), ST::Invalid_input);
  std::vector<Point> none;
  std::vector<Triangle> no_triangles;
  const ST::Reconstruction_report r = ST::reconstruct_topology(none, no_triangles);
  EXPECT_EQ(r.output_triangles, 0u);
}

} // namespace

// ---------------------------------------------------------------------------------------------
// The `repair` command

namespace cli_test {

std::string cli() { return SOUP_TOPOLOGY_CLI; }

TEST(RepairCommand, RoundTripOnEveryFormat)
{
  const std::string dir = soup_test::temporary_folder("repair");
  const std::string pig = soup_test::data_file("cgal_repair/pig.stl.xz");
  // pig.stl -> each output format, then each output read back: closed, same counts.
  for(const char* ext : {"off", "obj", "ply", "stl"}) {
    SCOPED_TRACE(ext);
    const std::string out = dir + "/pig." + ext;
    const auto [json, code] = soup_test::run_command(cli() + " repair '" + pig + "' -o '" + out + "' --tolerance 0.3 --json --check");
    ASSERT_EQ(code, 0) << json;
    EXPECT_EQ(soup_test::json_integer(json, "border_edges_before"), 1296);
    EXPECT_EQ(soup_test::json_integer(json, "border_edges_after"), 0);
    EXPECT_TRUE(soup_test::json_bool(json, "closed"));
    EXPECT_GT(soup_test::json_integer(json, "split_triangles"), 0);
    EXPECT_GE(soup_test::json_integer(json, "t_junctions"), 0);
    EXPECT_EQ(soup_test::json_integer(json, "non_manifold_edges_after"), 0);
    EXPECT_EQ(soup_test::json_integer(json, "components"), 1);
    const auto [stats, code2] = soup_test::run_command(cli() + " stats '" + out + "' --json");
    ASSERT_EQ(code2, 0) << stats;
    EXPECT_EQ(soup_test::json_integer(stats, "border_edges"), 0);
    EXPECT_EQ(soup_test::json_integer(stats, "inconsistently_oriented_edges"), 0);
    EXPECT_EQ(soup_test::json_integer(stats, "triangles"), soup_test::json_integer(json, "output_triangles"));
  }
  // Input formats: OFF, ASCII STL, VRML.
  for(const char* f : {"cad/ALSTOM_TEST4.off", "real_defects/admesh/block/nearby-bad.stl", "cad/kicad/TO-220-3_Vertical.wrl"}) {
    SCOPED_TRACE(f);
    const auto [json, code] = soup_test::run_command(cli() + " repair '" + soup_test::data_file(f) + "' -o '" + dir +
                                                     "/out.off' --relative-tolerance 1e-4 --report '" + dir + "/r.json'");
    EXPECT_EQ(code, 0) << json;
    std::ifstream report(dir + "/r.json");
    std::string line;
    std::getline(report, line);
    EXPECT_GE(soup_test::json_integer(line, "border_edges_after"), 0);
    EXPECT_LE(soup_test::json_integer(line, "border_edges_after"), soup_test::json_integer(line, "border_edges_before"));
  }
  // The TO-220 gaps close with 1e-6 of the diagonal.
  const auto [json, code] = soup_test::run_command(cli() + " repair '" + soup_test::data_file("cad/kicad/TO-220-3_Vertical.wrl") +
                                                   "' -o '" + dir + "/to220.ply' --relative-tolerance 1e-6 --json --check");
  EXPECT_EQ(code, 0) << json;
  EXPECT_EQ(soup_test::json_integer(json, "border_edges_before"), 10);
  EXPECT_EQ(soup_test::json_integer(json, "border_edges_after"), 0);
  // --check fails (exit 1) where the result stays open.
  const auto [json2, code2] = soup_test::run_command(cli() + " repair '" + pig + "' -o '" + dir + "/open.off' --check");
  EXPECT_EQ(code2, 1) << json2;
}

TEST(RepairCommand, RefusesBadInputAndNeverTouchesTheOutput)
{
  const std::string dir = soup_test::temporary_folder("repair_bad");
  const std::string existing = dir + "/existing.off";
  std::ofstream(existing) << "keep me\n";
  auto write = [&](const std::string& name, const std::string& content) {
    std::ofstream(dir + "/" + name, std::ios::binary) << content;
    return dir + "/" + name;
  };
  std::string truncated(84 + 50, '\0');
  truncated[80] = 2; // announces 2 facets, holds 1
  const std::string good = soup_test::data_file("real_defects/admesh/block/exact-bad.stl");
  struct Case { std::string args; std::string message; };
  const Case cases[] = {
    {"'" + write("truncated.stl", truncated) + "' -o '" + existing + "'", "truncated"},
    {"'" + write("nan.stl", "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 nan\nvertex 1 0 0\nvertex 0 1 0\n"
                            "endloop\nendfacet\nendsolid\n") + "' -o '" + existing + "'", "non-finite"},
    {"'" + good + "' -o '" + existing + "' --tolerance -1", "tolerance"},
    {"'" + good + "' -o '" + existing + "' --tolerance nan", "tolerance"},
    {"'" + dir + "/missing.stl' -o '" + existing + "'", "cannot open"},
    {"'" + good + "' -o '" + dir + "/no/such/folder/out.off'", "folder does not exist"},
    {"'" + good + "' -o '" + dir + "/out.xyz'", "unknown output extension"},
    {"'" + good + "' -o '" + good + "'", "the output file is the input file"},
    {"'" + good + "'", "no output file"},
    {"'" + good + "' -o '" + existing + "' --tolerance 1 --relative-tolerance 1", "not both"},
  };
  for(const Case& c : cases) {
    SCOPED_TRACE(c.args);
    const auto [out, code] = soup_test::run_command(cli() + " repair " + c.args + " 2>&1");
    EXPECT_EQ(code, 2) << out;
    EXPECT_NE(out.find(c.message), std::string::npos) << out;
    std::ifstream in(existing);
    std::string content;
    std::getline(in, content);
    EXPECT_EQ(content, "keep me");
  }
  // A read-only folder: the output cannot be written, nothing is left behind.
  if(geteuid() != 0) {
    const std::string locked = dir + "/locked";
    std::filesystem::create_directories(locked);
    std::filesystem::permissions(locked, std::filesystem::perms::owner_read | std::filesystem::perms::owner_exec);
    const auto [out, code] = soup_test::run_command(cli() + " repair '" + good + "' -o '" + locked + "/out.off' 2>&1");
    EXPECT_EQ(code, 2) << out;
    EXPECT_TRUE(std::filesystem::is_empty(locked));
  }
}

} // namespace cli_test

// ---------------------------------------------------------------------------------------------
// Issue 20: what a CGAL user reaches for (named parameters, meshes as input, self-intersections).

#include <CGAL/Point_set_3.h>
#include <CGAL/Polygon_mesh_processing/polygon_mesh_to_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Simple_cartesian.h>

#include <Soup_topology/internal/triangulate_polygon.h>

namespace issue20 {

namespace ST = Soup_topology;
namespace PMP = CGAL::Polygon_mesh_processing;
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Epick::Point_3;
using Triangle = std::array<std::size_t, 3>;
using Mesh = CGAL::Surface_mesh<Point>;

// Two triangles of a square whose shared edge was written twice, 1e-4 apart (2 welds), and a
// thin triangle whose two close corners may not be welded (a refusal).
struct Weld_soup
{
  std::vector<Point> points = {Point(0, 0, 0),      Point(1, 0, 0), Point(0, 1, 0),      Point(1.0001, 0, 0),
                               Point(0, 1.0001, 0), Point(1, 1, 0), Point(5, 5, 0),      Point(5.0001, 5, 0),
                               Point(5, 6, 0)};
  std::vector<Triangle> triangles = {{0, 1, 2}, {4, 3, 5}, {6, 7, 8}};
};

struct Counting_visitor
{
  std::vector<std::pair<std::size_t, std::size_t>> merges, refusals;
  void on_merge(std::size_t d, std::size_t r) { merges.emplace_back(d, r); }
  void on_refusal(std::size_t v, std::size_t r, ST::Refusal_reason) { refusals.emplace_back(v, r); }
};

void expect_same_report(const ST::Reconstruction_report& a, const ST::Reconstruction_report& b)
{
  EXPECT_EQ(a.tolerance, b.tolerance);
  EXPECT_EQ(a.input_points, b.input_points);
  EXPECT_EQ(a.input_triangles, b.input_triangles);
  EXPECT_EQ(a.exact_duplicates, b.exact_duplicates);
  EXPECT_EQ(a.snapped_vertices, b.snapped_vertices);
  EXPECT_EQ(a.refused_welds(), b.refused_welds());
  EXPECT_EQ(a.split_triangles, b.split_triangles);
  EXPECT_EQ(a.border_edges_before, b.border_edges_before);
  EXPECT_EQ(a.border_edges_after, b.border_edges_after);
  EXPECT_EQ(a.non_manifold_edges_after, b.non_manifold_edges_after);
  EXPECT_EQ(a.components, b.components);
  EXPECT_EQ(a.output_points, b.output_points);
  EXPECT_EQ(a.output_triangles, b.output_triangles);
  EXPECT_EQ(a.max_displacement, b.max_displacement);
  EXPECT_EQ(a.duplicate_triangles, b.duplicate_triangles);
  EXPECT_EQ(a.duplicated_points, b.duplicated_points);
}

TEST(ReconstructTopology, Issue20VisitorCalledForEveryWeldAndRefusal)
{
  // Under Small_features::REFUSE the sliver (6, 7, 8) is refused and the refusal told; the
  // default collapses it (small_features_test.cpp).
  Weld_soup s;
  Counting_visitor v;
  const ST::Reconstruction_report r = ST::reconstruct_topology(
    s.points, s.triangles,
    ST::parameters::small_features(ST::Small_features::REFUSE,
                                   CGAL::parameters::snapping_tolerance(1e-3).visitor(std::ref(v))));
  EXPECT_EQ(r.snapped_vertices, 2u);
  EXPECT_GE(r.refused_welds(), 1u);
  EXPECT_EQ(v.merges.size(), r.snapped_vertices);
  EXPECT_EQ(v.refusals.size(), r.refused_welds());
  // The indices are those of the input points.
  std::sort(v.merges.begin(), v.merges.end());
  EXPECT_EQ(v.merges, (std::vector<std::pair<std::size_t, std::size_t>>{{3, 1}, {4, 2}}));
  for(const auto& pr : v.refusals) {
    EXPECT_TRUE(pr.first == 6 || pr.first == 7);
    EXPECT_TRUE(pr.second == 6 || pr.second == 7);
  }
  // Given by copy, the visitor is still called (on the copy): the result is the same.
  Weld_soup s2;
  const ST::Reconstruction_report r2 = ST::reconstruct_topology(
    s2.points, s2.triangles,
    ST::parameters::small_features(ST::Small_features::REFUSE,
                                   CGAL::parameters::snapping_tolerance(1e-3).visitor(Counting_visitor())));
  EXPECT_EQ(s2.triangles, s.triangles);
  EXPECT_EQ(r2.snapped_vertices, r.snapped_vertices);
}

// Points stored as plain arrays: get builds a Point_3, put writes it back.
struct Array_point_map
{
  using key_type = std::array<double, 3>;
  using value_type = Point;
  using reference = Point;
  using category = boost::read_write_property_map_tag;
  friend Point get(const Array_point_map&, const key_type& a) { return Point(a[0], a[1], a[2]); }
  friend void put(const Array_point_map&, key_type& a, const Point& p) { a = {p.x(), p.y(), p.z()}; }
};

TEST(ReconstructTopology, Issue20PointMapOnArraysAndPointSet)
{
  auto [points, triangles] = load<Point>("cgal_repair/pig.stl.xz");
  const auto np = CGAL::parameters::snapping_tolerance(0.3);
  std::vector<Point> p0 = points;
  std::vector<Triangle> t0 = triangles;
  const ST::Reconstruction_report r0 = ST::reconstruct_topology(p0, t0, np);

  std::vector<std::array<double, 3>> arrays;
  for(const Point& p : points) arrays.push_back({p.x(), p.y(), p.z()});
  std::vector<Triangle> t1 = triangles;
  const ST::Reconstruction_report r1 =
    ST::reconstruct_topology(arrays, t1, CGAL::parameters::snapping_tolerance(0.3).point_map(Array_point_map()));
  expect_same_report(r0, r1);
  EXPECT_EQ(t1, t0);
  ASSERT_EQ(arrays.size(), p0.size());
  for(std::size_t i = 0; i < p0.size(); ++i) EXPECT_EQ(Point(arrays[i][0], arrays[i][1], arrays[i][2]), p0[i]);

  CGAL::Point_set_3<Point> set;
  for(const Point& p : points) set.insert(p);
  std::vector<Triangle> t2 = triangles;
  const ST::Reconstruction_report r2 =
    ST::reconstruct_topology(set, t2, CGAL::parameters::snapping_tolerance(0.3).point_map(set.point_map()));
  expect_same_report(r0, r2);
  EXPECT_EQ(t2, t0);
  ASSERT_EQ(set.size(), p0.size());
  std::size_t k = 0;
  for(auto idx : set) EXPECT_EQ(set.point(idx), p0[k++]);

  // The soup-to-mesh overload reads through the map too.
  Mesh m0, m1;
  ST::reconstruct_topology(points, triangles, m0, np);
  std::vector<std::array<double, 3>> arrays_in;
  for(const Point& p : points) arrays_in.push_back({p.x(), p.y(), p.z()});
  ST::reconstruct_topology(arrays_in, triangles, m1, CGAL::parameters::snapping_tolerance(0.3).point_map(Array_point_map()));
  EXPECT_EQ(num_vertices(m1), num_vertices(m0));
  EXPECT_EQ(num_faces(m1), num_faces(m0));
}

TEST(ReconstructTopology, Issue20AnyGeomTraitsAndChainedParameters)
{
  using SC = CGAL::Simple_cartesian<double>;
  Weld_soup s0, s1, s2, s3;
  const ST::Reconstruction_report r0 = ST::reconstruct_topology(s0.points, s0.triangles, CGAL::parameters::snapping_tolerance(1e-3));
  const ST::Reconstruction_report r1 =
    ST::reconstruct_topology(s1.points, s1.triangles, CGAL::parameters::snapping_tolerance(1e-3).geom_traits(SC()));
  expect_same_report(r0, r1);
  EXPECT_EQ(s1.triangles, s0.triangles);
  EXPECT_EQ(s1.points, s0.points);
  // A package parameter wraps a CGAL chain, and CGAL members may follow it.
  const double diag = ST::internal::bounding_box_diagonal(s0.points, CGAL::Identity_property_map<Point>());
  (void)diag;
  const ST::Reconstruction_report r2 =
    ST::reconstruct_topology(s2.points, s2.triangles, ST::parameters::relative_tolerance(1e-4).geom_traits(SC()));
  const ST::Reconstruction_report r3 = ST::reconstruct_topology(
    s3.points, s3.triangles, ST::parameters::relative_tolerance(1e-4, CGAL::parameters::geom_traits(SC())));
  expect_same_report(r2, r3);
  // 3 into 1 and 4 into 2. The lone sliver (6, 7, 8) is kept: it would collapse onto an edge that
  // no kept triangle has (Refusal_reason::UNCOVERED_COLLAPSE), which would take it off the surface.
  EXPECT_EQ(r2.snapped_vertices, 2u);
  EXPECT_EQ(r2.small_feature_collapsed_triangles, 0u);
  EXPECT_GT(r2.refused_uncovered_collapse, 0u);
  // Exact points through an inexact traits, and inexact points through exact traits.
  std::vector<Epeck::Point_3> exact;
  Weld_soup s4;
  for(const Point& p : s4.points) exact.emplace_back(p.x(), p.y(), p.z());
  const ST::Reconstruction_report r4 =
    ST::reconstruct_topology(exact, s4.triangles, CGAL::parameters::snapping_tolerance(1e-3).geom_traits(Epick()));
  EXPECT_EQ(s4.triangles, s0.triangles);
  EXPECT_EQ(r4.snapped_vertices, r0.snapped_vertices);
  Weld_soup s5;
  ST::reconstruct_topology(s5.points, s5.triangles, CGAL::parameters::snapping_tolerance(1e-3).geom_traits(Epeck()));
  EXPECT_EQ(s5.triangles, s0.triangles);
  EXPECT_EQ(s5.points, s0.points);
}

// CGAL's stitching inputs loaded as meshes: the same result as the detour through a soup.
TEST(ReconstructTopology, Issue20MeshInputEqualsTheSoupDetour)
{
  struct Case { const char* file; long stitch_borders_left; };
  const Case cases[] = {
    {"cgal_repair/quads_to_stitch.off", 12}, {"cgal_repair/data_stitching/incidence_3.off", 6},
    {"cgal_repair/data_stitching/pinched.off", 56}, {"cgal_repair/data_stitching/deg_border.off", -1},
    {"cgal_repair/data_stitching/incoherent_patch_orientation.off", -1},
    {"cgal_repair/data_stitching/nm_cubes.off", -1}, {"cgal_repair/data_stitching/non_manifold.off", -1},
    {"cgal_repair/data_stitching/non_manifold2.off", -1},
  };
  std::size_t loaded = 0;
  for(const Case& c : cases) {
    SCOPED_TRACE(c.file);
    Mesh mesh;
    if(!CGAL::IO::read_polygon_mesh(soup_test::data_file(c.file), mesh)) {
      EXPECT_EQ(c.stitch_borders_left, -1) << "the trial loaded it as a mesh";
      continue;
    }
    ++loaded;
    // The detour.
    std::vector<Point> points;
    std::vector<std::vector<std::size_t>> polygons;
    PMP::polygon_mesh_to_polygon_soup(mesh, points, polygons);
    std::vector<Triangle> triangles;
    for(const auto& poly : polygons)
      if(poly.size() == 3) triangles.push_back({poly[0], poly[1], poly[2]});
      else ST::internal::triangulate_polygon(points, poly, triangles);
    Mesh detour;
    const ST::Reconstruction_report expected = ST::reconstruct_topology(points, triangles, detour);

    Mesh copy = mesh;
    const ST::Reconstruction_report r = ST::reconstruct_topology(mesh);
    expect_same_report(r, expected);
    EXPECT_TRUE(CGAL::is_valid_polygon_mesh(mesh));
    EXPECT_EQ(num_vertices(mesh), num_vertices(detour));
    EXPECT_EQ(num_faces(mesh), num_faces(detour));
    EXPECT_EQ(border_edges(mesh), border_edges(detour));
    if(c.stitch_borders_left >= 0) {
      EXPECT_EQ(border_edges(mesh), static_cast<std::size_t>(c.stitch_borders_left));
      PMP::stitch_borders(copy);
      EXPECT_EQ(border_edges(copy), static_cast<std::size_t>(c.stitch_borders_left));
    }
    // A Polyhedron_3 with its own point type gives the same.
    CGAL::Polyhedron_3<Epeck> poly;
    ASSERT_TRUE(CGAL::IO::read_polygon_mesh(soup_test::data_file(c.file), poly));
    const ST::Reconstruction_report rp = ST::reconstruct_topology(poly);
    expect_same_report(rp, expected);
    EXPECT_TRUE(CGAL::is_valid_polygon_mesh(poly));
  }
  EXPECT_GE(loaded, 3u);

  // A user vertex point map and a tolerance: the mesh keeps its map.
  Mesh m;
  ASSERT_TRUE(CGAL::IO::read_polygon_mesh(soup_test::data_file("cgal_repair/quads_to_stitch.off"), m));
  auto moved = m.add_property_map<Mesh::Vertex_index, Point>("v:moved").first;
  for(auto v : vertices(m)) moved[v] = m.point(v) + Epick::Vector_3(10, 0, 0);
  const ST::Reconstruction_report r =
    ST::reconstruct_topology(m, CGAL::parameters::vertex_point_map(moved).snapping_tolerance(1e-6));
  EXPECT_TRUE(CGAL::is_valid_polygon_mesh(m));
  EXPECT_EQ(num_faces(m), r.output_triangles - r.duplicate_triangles);
  for(auto v : vertices(m)) EXPECT_GE(moved[v].x(), 9.0);
}

TEST(ReconstructTopology, Issue20CountsSelfIntersectingPairs)
{
  // Two triangles crossing, two sharing an edge and folded onto each other, two sharing a vertex only.
  std::vector<Point> points = {Point(0, 0, 0), Point(2, 0, 0), Point(0, 2, 0), Point(0.5, 0.5, -1), Point(0.5, 0.5, 1),
                               Point(1, 1, 1)};
  std::vector<Triangle> crossing = {{0, 1, 2}, {3, 4, 5}};
  auto p = points;
  ST::Reconstruction_report r = ST::reconstruct_topology(p, crossing, ST::parameters::count_self_intersections(true));
  EXPECT_TRUE(r.self_intersections_counted);
  EXPECT_EQ(r.self_intersecting_pairs, 1u);
  p = points;
  std::vector<Triangle> crossing2 = {{0, 1, 2}, {3, 4, 5}};
  r = ST::reconstruct_topology(p, crossing2);
  EXPECT_FALSE(r.self_intersections_counted);
  EXPECT_EQ(r.self_intersecting_pairs, 0u);

  std::vector<Point> fold_points = {Point(0, 0, 0), Point(2, 0, 0), Point(0, 2, 0), Point(1, 0.5, 0), Point(0, -2, 0)};
  std::vector<Triangle> folded = {{0, 1, 2}, {1, 0, 3}};
  auto fp = fold_points;
  EXPECT_EQ(ST::reconstruct_topology(fp, folded, ST::parameters::count_self_intersections(true)).self_intersecting_pairs, 1u);
  std::vector<Triangle> flat = {{0, 1, 2}, {1, 0, 4}};
  fp = fold_points;
  EXPECT_EQ(ST::reconstruct_topology(fp, flat, ST::parameters::count_self_intersections(true)).self_intersecting_pairs, 0u);
  std::vector<Point> fan_points = {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(-1, 0, 0.5), Point(0, -1, 0.5)};
  std::vector<Triangle> fan = {{0, 1, 2}, {0, 3, 4}};
  EXPECT_EQ(ST::reconstruct_topology(fan_points, fan, ST::parameters::count_self_intersections(true)).self_intersecting_pairs, 0u);

  // Pig closed at 0.3 still self-intersects: the count agrees with CGAL's on the mesh.
  auto [pig_points, pig_triangles] = load<Point>("cgal_repair/pig.stl.xz");
  Mesh mesh;
  r = ST::reconstruct_topology(pig_points, pig_triangles, mesh,
                               ST::parameters::count_self_intersections(true, CGAL::parameters::snapping_tolerance(0.3)));
  ASSERT_EQ(r.duplicated_points, 0u);
  std::vector<std::pair<Mesh::Face_index, Mesh::Face_index>> pairs;
  PMP::self_intersections(mesh, std::back_inserter(pairs));
  EXPECT_TRUE(r.closed());
  EXPECT_EQ(r.self_intersecting_pairs, pairs.size());
  EXPECT_GT(r.self_intersecting_pairs, 0u);
}

TEST(ReconstructTopology, Issue21RelativeToleranceOnHugeCoordinates)
{
  // The bounding-box diagonal of points spanning 1e300 is finite (1.7e300) though its square is not.
  std::vector<Point> points = {Point(0, 0, 0), Point(1e300, 0, 0), Point(0, 1e300, 0), Point(0, 0, 1e300)};
  EXPECT_DOUBLE_EQ(ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>()), std::sqrt(3.0) * 1e300);
  std::vector<Triangle> triangles = {{0, 1, 2}, {0, 3, 1}, {1, 3, 2}, {2, 3, 0}};
  ST::Reconstruction_report r;
  EXPECT_NO_THROW(r = ST::reconstruct_topology(points, triangles, ST::parameters::relative_tolerance(1e-200)));
  EXPECT_DOUBLE_EQ(r.tolerance, std::sqrt(3.0) * 1e100);
  EXPECT_EQ(r.output_triangles, 4u);
  EXPECT_TRUE(r.closed());
  // The pipeline runs on these points scaled by 2^-997: a relative tolerance of 1e-6, 1.7e294, is
  // 1.7e-6 of the scaled diagonal and is accepted (tolerance.h refused it before, its square
  // overflowing).
  std::vector<Point> p2 = points;
  std::vector<Triangle> t2 = triangles;
  EXPECT_NO_THROW(r = ST::reconstruct_topology(p2, t2, ST::parameters::relative_tolerance(1e-6)));
  EXPECT_EQ(r.tolerance, 1e-6 * (std::sqrt(3.0) * 1e300));
  EXPECT_TRUE(r.closed());
  EXPECT_EQ(p2, points);
  // So is an absolute tolerance of 1e299 there. One whose square overflows at the scale of the
  // points (1e160 for points within the unit cube) is refused for that reason.
  p2 = points;
  t2 = triangles;
  EXPECT_NO_THROW(r = ST::reconstruct_topology(p2, t2, CGAL::parameters::snapping_tolerance(1e299)));
  EXPECT_EQ(r.tolerance, 1e299);
  std::vector<Point> unit = {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(0, 0, 1)};
  for(const double tolerance : {1e160, 1e300}) {
    try {
      ST::reconstruct_topology(unit, triangles, CGAL::parameters::snapping_tolerance(tolerance));
      ADD_FAILURE() << "not refused";
    } catch(const ST::Invalid_input& e) {
      EXPECT_NE(std::string(e.what()).find("is too large"), std::string::npos) << e.what();
    }
  }
}

} // namespace issue20

namespace split_filters {

namespace ST = Soup_topology;
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;
using Point = Epick::Point_3;
using Triangle = std::array<std::size_t, 3>;

// A triangle (0, 1, 2) whose edge [0, 1] has `n` vertices of a strip of triangles near it, moved
// off the edge by up to `offset` (some within the tolerance, some not).
void noisy_t_junction_strip(std::size_t n, double offset, std::vector<Point>& points, std::vector<Triangle>& triangles)
{
  std::mt19937 gen(2026);
  std::uniform_real_distribution<double> off(-offset, offset);
  points = {Point(0, 0, 0), Point(1, 0, 0), Point(0.5, 1, 0)};
  triangles = {{0, 1, 2}};
  std::vector<std::size_t> chain = {0};
  for(std::size_t k = 1; k <= n; ++k) {
    chain.push_back(points.size());
    points.push_back(Point(double(k) / double(n + 1), off(gen), off(gen)));
  }
  chain.push_back(1);
  const std::size_t below = points.size();
  for(std::size_t k = 0; k <= n + 1; ++k) points.push_back(Point(double(k) / double(n + 1), -0.01, 0));
  for(std::size_t k = 0; k + 1 < chain.size(); ++k) {
    triangles.push_back({chain[k + 1], chain[k], below + k});
    triangles.push_back({chain[k + 1], below + k, below + k + 1});
  }
}

// The double-precision acceptance of "near the segment" (Octree queries and the T-junction
// decisions) accepts only what the exact predicate accepts: with Epick (filtered) and Epeck
// (no double filter), the same triangles are split.
TEST(SplitTJunctions, DoubleFilterKeepsTheExactDecisions)
{
  const double eps = 1e-6;
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  noisy_t_junction_strip(1000, 1.5 * eps, points, triangles);
  std::vector<Epeck::Point_3> exact_points;
  for(const Point& p : points) exact_points.emplace_back(p.x(), p.y(), p.z());
  std::vector<Triangle> inexact_result = triangles, exact_result = triangles;
  const ST::Split_report r1 = ST::split_t_junctions(points, inexact_result, CGAL::parameters::snapping_tolerance(eps));
  const ST::Split_report r2 =
    ST::split_t_junctions(exact_points, exact_result, CGAL::parameters::snapping_tolerance(Epeck::FT(eps)));
  EXPECT_GT(r1.t_junctions, 0u);
  EXPECT_LT(r1.t_junctions, 1000u);
  EXPECT_EQ(r1.t_junctions, r2.t_junctions);
  EXPECT_EQ(r1.refused_flip + r1.refused_degenerate, r2.refused_flip + r2.refused_degenerate);
  EXPECT_EQ(inexact_result, exact_result);
}

TEST(SplitTJunctions, SegmentFilterNeverAcceptsAFarPoint)
{
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::size_t accepted = 0;
  for(int i = 0; i < 20000; ++i) {
    const double scale = std::pow(10.0, double(i % 13) - 6);
    const std::array<double, 3> a{{unit(gen) * scale, unit(gen) * scale, unit(gen) * scale}};
    const std::array<double, 3> b = (i % 5 == 0) ? a : std::array<double, 3>{{unit(gen) * scale, unit(gen) * scale, unit(gen) * scale}};
    const double t = (i % 3 == 0) ? 0.5 * (unit(gen) + 1) : 1.5 * unit(gen);
    const double eps = scale * 1e-3 * (1 + unit(gen));
    std::array<double, 3> p;
    for(std::size_t k = 0; k < 3; ++k) p[k] = a[k] + t * (b[k] - a[k]) + eps * 0.6 * unit(gen);
    const double eps2 = eps * eps;
    if(!ST::internal::surely_within_segment(p, a, b, eps2)) continue;
    ++accepted;
    const Epeck::Point_3 ep(p[0], p[1], p[2]), ea(a[0], a[1], a[2]), eb(b[0], b[1], b[2]);
    const Epeck::FT d2 = (i % 5 == 0) ? CGAL::squared_distance(ep, ea) : CGAL::squared_distance(ep, Epeck::Segment_3(ea, eb));
    ASSERT_LT(d2, Epeck::FT(eps2)) << i;
  }
  EXPECT_GT(accepted, 1000u);
}

} // namespace split_filters

namespace issue13 {

using ST::Reconstruction_report;

// Every count of two reports, field by field.
void expect_same_report(const Reconstruction_report& a, const Reconstruction_report& b)
{
  issue20::expect_same_report(a, b);
  EXPECT_EQ(a.collapsed_triangles, b.collapsed_triangles);
  EXPECT_EQ(a.rounds, b.rounds);
  EXPECT_EQ(a.clusters, b.clusters);
  EXPECT_EQ(a.ambiguous_sites, b.ambiguous_sites);
  EXPECT_EQ(a.short_edges, b.short_edges);
  EXPECT_EQ(a.t_junctions, b.t_junctions);
  EXPECT_EQ(a.refused_splits, b.refused_splits);
  EXPECT_EQ(a.ambiguous_t_junctions, b.ambiguous_t_junctions);
  EXPECT_EQ(a.non_manifold_edges_before, b.non_manifold_edges_before);
  EXPECT_EQ(a.non_manifold_vertices_after, b.non_manifold_vertices_after);
  EXPECT_EQ(a.components_before, b.components_before);
  EXPECT_EQ(a.removed_points, b.removed_points);
}

// The triangles as corner coordinates, each rotated to start at its smallest corner.
std::multiset<std::array<std::array<double, 3>, 3>> triangles_by_coordinates(const std::vector<Point>& pts,
                                                                           const std::vector<Triangle>& tris)
{
  std::multiset<std::array<std::array<double, 3>, 3>> out;
  for(const Triangle& q : tris) {
    std::array<std::array<double, 3>, 3> c;
    for(std::size_t k = 0; k < 3; ++k) c[k] = {pts[q[k]].x(), pts[q[k]].y(), pts[q[k]].z()};
    const std::size_t s = static_cast<std::size_t>(std::min_element(c.begin(), c.end()) - c.begin());
    out.insert({c[s], c[(s + 1) % 3], c[(s + 2) % 3]});
  }
  return out;
}

// The entry point that trusts a soup read welded (the command line's) gives the points,
// triangles and report of the public function, which welds again, on real meshes.
TEST(ReconstructTopology, Issue13WeldedSoupEntryEqualsThePublicFunction)
{
  const std::vector<std::pair<std::string, double>> inputs = {
    {"cgal_repair/pig.stl.xz", 0.3},       {"cgal_repair/pig.stl.xz", 0.0},
    {"cad/ALSTOM_TEST4.off", 1e-3},        {"clean/fandisk.off.xz", 1e-4},
    {"real_defects/openscad/bad-stl-tardis.stl", 1e-4}, {"cgal_repair/data_stitching/pinched.off", 1e-2}};
  for(const auto& [file, tolerance] : inputs) {
    SCOPED_TRACE(file + " tolerance " + std::to_string(tolerance));
    auto [points, triangles] = load<Point>(file);
    auto p2 = points;
    auto t2 = triangles;
    const auto np = CGAL::parameters::snapping_tolerance(tolerance);
    const Reconstruction_report welded_twice = ST::reconstruct_topology(points, triangles, np);
    const Reconstruction_report welded_once = ST::internal::reconstruct_exactly_welded_soup(p2, t2, np);
    EXPECT_EQ(points, p2);
    EXPECT_EQ(triangles, t2);
    expect_same_report(welded_twice, welded_once);
  }
}

// Everything a visitor of the pipeline is told, in order, as (what, index, index, index).
struct Recording_visitor
{
  std::vector<std::array<std::size_t, 4>> told;
  void on_merge(std::size_t d, std::size_t r) { told.push_back({0, d, r, 0}); }
  void on_refusal(std::size_t v, std::size_t r, ST::Refusal_reason) { told.push_back({1, v, r, 0}); }
  void on_split(std::size_t v, std::size_t a, std::size_t b) { told.push_back({2, v, a, b}); }
  void on_split_refusal(std::size_t v, std::size_t a, std::size_t b, ST::Split_refusal_reason)
  { told.push_back({3, v, a, b}); }
  void on_ambiguous_t_junction(std::size_t v, std::size_t a, std::size_t b) { told.push_back({4, v, a, b}); }
  void on_ambiguous_site(std::size_t v) { told.push_back({5, v, 0, 0}); }
};

// A soup to repair, its name for the trace and the tolerance it is repaired with.
struct Named_soup
{
  std::string name;
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  double tolerance;
};

// On a soup read exactly welded, the entry point that trusts the weld tells a visitor the same
// welds, refusals, splits and sites, with the same indices of the input, as the public function
// (which carries the index of every point from its own weld); the output is the same. Real
// meshes, and bunny00 cut into patches with T-junctions and jittered copies of their borders.
TEST(ReconstructTopology, Issue13WeldedSoupEntryTellsTheVisitorTheSameIndices)
{
  std::vector<Named_soup> inputs;
  for(const auto& [file, tolerance] : std::vector<std::pair<std::string, double>>{{"cgal_repair/pig.stl.xz", 0.3},
                                                                                   {"cad/ALSTOM_TEST4.off", 1e-3}}) {
    auto [points, triangles] = load<Point>(file);
    inputs.push_back({file, points, triangles, tolerance});
  }
  {
    auto [points, triangles] = load<Point>("clean/bunny00.off.xz");
    const double diag = ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>());
    auto soup = soup_test::t_junction_soup(points, triangles, 5, 1e-7 * diag / std::sqrt(3.0), 17);
    inputs.push_back({"bunny00 with T-junctions", soup.points, soup.triangles, 1e-6 * diag});
  }
  for(Named_soup& in : inputs) {
    SCOPED_TRACE(in.name);
    auto p2 = in.points;
    auto t2 = in.triangles;
    Recording_visitor v1, v2;
    const Reconstruction_report r1 = ST::reconstruct_topology(
      in.points, in.triangles, CGAL::parameters::snapping_tolerance(in.tolerance).visitor(std::ref(v1)));
    const Reconstruction_report r2 = ST::internal::reconstruct_exactly_welded_soup(
      p2, t2, CGAL::parameters::snapping_tolerance(in.tolerance).visitor(std::ref(v2)));
    EXPECT_EQ(r1.exact_duplicates, 0u);
    EXPECT_FALSE(v1.told.empty());
    if(r1.split_triangles > 0) {
      EXPECT_TRUE(std::any_of(v1.told.begin(), v1.told.end(), [](const auto& x) { return x[0] == 2; }));
    }
    EXPECT_EQ(v1.told, v2.told);
    EXPECT_EQ(in.points, p2);
    EXPECT_EQ(in.triangles, t2);
    expect_same_report(r1, r2);
  }
}

// An exploded, jittered soup and the same soup with its triangles shuffled and their corners
// rotated: read (index_triangles) and repaired, the same surface and the same counts.
TEST(ReconstructTopology, Issue13ShuffledExplodedSoupGivesTheSameSurface)
{
  auto [points, triangles] = load<Point>("clean/bunny00.off.xz");
  const double diag = ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>());
  std::vector<std::array<Point, 3>> exploded = soup_test::explode(points, triangles);
  std::mt19937_64 rng(13);
  const double j = 1e-7 * diag;
  std::uniform_real_distribution<double> d(-j, j);
  for(auto& t : exploded)
    for(Point& q : t) q = Point(q.x() + d(rng), q.y() + d(rng), q.z() + d(rng));
  std::vector<std::array<Point, 3>> shuffled = exploded;
  std::shuffle(shuffled.begin(), shuffled.end(), rng);
  for(auto& t : shuffled) std::rotate(t.begin(), t.begin() + static_cast<std::ptrdiff_t>(rng() % 3), t.end());

  const auto np = CGAL::parameters::snapping_tolerance(1e-5 * diag);
  std::vector<Point> p1, p2;
  std::vector<Triangle> t1, t2;
  ST::index_triangles(exploded, p1, t1);
  ST::index_triangles(shuffled, p2, t2);
  const Reconstruction_report r1 = ST::internal::reconstruct_exactly_welded_soup(p1, t1, np);
  const Reconstruction_report r2 = ST::internal::reconstruct_exactly_welded_soup(p2, t2, np);
  EXPECT_TRUE(r1.closed());
  EXPECT_EQ(r1.output_triangles, triangles.size());
  EXPECT_EQ(r1.snapped_vertices, r2.snapped_vertices);
  EXPECT_EQ(r1.border_edges_after, r2.border_edges_after);
  EXPECT_EQ(r1.output_points, r2.output_points);
  EXPECT_EQ(r1.output_triangles, r2.output_triangles);
  EXPECT_EQ(triangles_by_coordinates(p1, t1), triangles_by_coordinates(p2, t2));
}

} // namespace issue13

// Per-vertex tolerances (`vertex_tolerance_map`) in the T-junction split and the pipeline.
namespace tolerance_map {

using issue13::Named_soup;

using ST::Reconstruction_report;
using issue13::Recording_visitor;

// Three vertices of a strip (3, 4, 5) on the edge (0, 1) of a big triangle; vertex 5 is moved
// 1e-3 below the edge. A vertex c is on the border edge [a, b] when its distance to it is at most
// min(t_c, t_a, t_b): vertex 5 is split only when its own tolerance and those of 0 and 1 reach
// 1e-3; vertices 3 and 4, on the edge, are split even with tolerances of 0.
TEST(VertexToleranceMap, TJunctionNeedsTheSmallestToleranceOfTheVertexAndTheEdge)
{
  const std::vector<Point> points = {Point(0, 0, 0), Point(4, 0, 0), Point(2, 3, 0), Point(3, 0, 0), Point(1, 0, 0),
                                     Point(2, -1e-3, 0), Point(2, -2, 0)};
  const std::vector<Triangle> base = {{0, 1, 2}, {4, 0, 6}, {5, 4, 6}, {3, 5, 6}, {1, 3, 6}};
  struct Case
  {
    std::vector<double> t;
    std::size_t t_junctions;
  };
  const std::vector<Case> cases = {
    {{1e-2, 1e-2, 1e-2, 1e-2, 1e-2, 1e-2, 1e-2}, 3}, {{1e-2, 1e-2, 1e-2, 1e-2, 1e-2, 1e-4, 1e-2}, 2},
    {{1e-4, 1e-2, 1e-2, 1e-2, 1e-2, 1e-2, 1e-2}, 2}, {{1e-2, 1e-4, 1e-2, 1e-2, 1e-2, 1e-2, 1e-2}, 2},
    {{0, 0, 0, 0, 0, 1e-2, 0}, 2},                   {{2e-3, 2e-3, 0, 0, 0, 1.5e-3, 0}, 3}};
  for(const Case& c : cases) {
    SCOPED_TRACE(::testing::PrintToString(c.t));
    std::vector<Triangle> triangles = base;
    Tables tables(triangles, points.size());
    const ST::Split_report r =
      ST::split_t_junctions(points, triangles, tables, ST::parameters::vertex_tolerance_map(CGAL::make_property_map(c.t)));
    EXPECT_EQ(r.t_junctions, c.t_junctions);
    EXPECT_EQ(r.split_triangles, c.t_junctions);
    EXPECT_EQ(r.tolerance, *std::max_element(c.t.begin(), c.t.end()));
    // Three splits close the edge; two leave [4,3] open against [4,5] and [5,3].
    EXPECT_EQ(count_border(triangles), c.t_junctions == 3 ? 4u : 7u);
    // The same with one tolerance when the map is constant.
    if(c.t_junctions == 3 && c.t[2] != 0) {
      std::vector<Triangle> t2 = base;
      EXPECT_EQ(ST::split_t_junctions(points, t2, CGAL::parameters::snapping_tolerance(1e-2)).t_junctions, 3u);
      EXPECT_EQ(t2, triangles);
    }
  }
}

// The pipeline with the map of constant value t and with `snapping_tolerance(t)`: the same points,
// triangles, visitor calls (welds, refusals, splits, ambiguous sites, in order) and report, on real
// meshes and on the generated soups.
TEST(VertexToleranceMap, ConstantMapRepairsAsOneToleranceOnRealAndGeneratedSoups)
{
  std::vector<Named_soup> inputs;
  {
    auto [points, triangles] = load<Point>("cgal_repair/pig.stl.xz");
    inputs.push_back({"pig", points, triangles, 0.3});
  }
  {
    auto [points, triangles] = load<Point>("cad/ALSTOM_TEST4.off");
    const double diag = ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>());
    inputs.push_back({"ALSTOM_TEST4", points, triangles, 1e-3 * diag});
  }
  {
    auto [points, triangles] = load<Point>("clean/elephant.off");
    const double diag = ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>());
    auto t_soup = soup_test::t_junction_soup(points, triangles, 5, 1e-7 * diag, 17);
    inputs.push_back({"elephant with T-junctions", t_soup.points, t_soup.triangles, 1e-6 * diag});
    const double jitter = 1e-5 * diag;
    auto f_soup = soup_test::small_feature_soup(points, triangles, 10, jitter, 0.5, 8 * jitter, 3);
    inputs.push_back({"elephant with small features", f_soup.points, f_soup.triangles, 8 * jitter});
  }
  for(const Named_soup& in : inputs) {
    SCOPED_TRACE(in.name);
    const std::vector<double> constant(in.points.size(), in.tolerance);
    auto p1 = in.points, p2 = in.points;
    auto t1 = in.triangles, t2 = in.triangles;
    Recording_visitor v1, v2;
    const Reconstruction_report r1 = ST::reconstruct_topology(
      p1, t1, CGAL::parameters::snapping_tolerance(in.tolerance).visitor(std::ref(v1)));
    const Reconstruction_report r2 = ST::reconstruct_topology(
      p2, t2, ST::parameters::vertex_tolerance_map(CGAL::make_property_map(constant)).visitor(std::ref(v2)));
    EXPECT_GT(r1.snapped_vertices + r1.split_triangles, 0u);
    EXPECT_EQ(p1, p2);
    EXPECT_EQ(t1, t2);
    EXPECT_EQ(v1.told, v2.told);
    issue13::expect_same_report(r1, r2);
    EXPECT_EQ(r1.tolerance, r2.tolerance);
    EXPECT_EQ(r1.max_displacement, r2.max_displacement);
    EXPECT_EQ(r1.snapped_vertices, r2.snapped_vertices);
    EXPECT_EQ(r1.split_triangles, r2.split_triangles);
    EXPECT_EQ(r1.border_edges_after, r2.border_edges_after);
    EXPECT_EQ(r1.small_features_resolved, r2.small_features_resolved);
    EXPECT_EQ(r1.refused_welds(), r2.refused_welds());
  }
  // Into a FaceGraph (the second overload): the same mesh.
  const Named_soup& pig = inputs[0];
  const std::vector<double> constant(pig.points.size(), pig.tolerance);
  Mesh m1, m2;
  const Reconstruction_report r1 =
    ST::reconstruct_topology(pig.points, pig.triangles, m1, CGAL::parameters::snapping_tolerance(pig.tolerance));
  const Reconstruction_report r2 = ST::reconstruct_topology(
    pig.points, pig.triangles, m2, ST::parameters::vertex_tolerance_map(CGAL::make_property_map(constant)));
  EXPECT_EQ(num_faces(m1), num_faces(m2));
  EXPECT_EQ(num_vertices(m1), num_vertices(m2));
  EXPECT_EQ(border_edges(m1), border_edges(m2));
  EXPECT_EQ(r1.orientation_flips, r2.orientation_flips);
  EXPECT_EQ(r1.tolerance, r2.tolerance);
}

// Exactly equal points with different tolerances: the point they become takes the smaller one,
// whatever their order. The patent's cube with V0 copied exactly (8, for T10) and 1e-3 away
// (9, for T11): 9 is welded to V0 only when the tolerances of 0, 8 and 9 all reach 1e-3.
TEST(VertexToleranceMap, ExactDuplicatesKeepTheSmallestTolerance)
{
  std::vector<Point> base_points = {Point(-1, -1, 1), Point(1, -1, 1), Point(1, 1, 1), Point(-1, 1, 1),
                                    Point(-1, -1, -1), Point(1, -1, -1), Point(1, 1, -1), Point(-1, 1, -1),
                                    Point(-1, -1, 1), Point(-1 + 1e-3, -1 + 1e-3, 1)};
  std::vector<Triangle> base = {{0, 1, 3}, {2, 3, 1}, {2, 6, 3}, {7, 3, 6}, {2, 1, 6}, {5, 6, 1},
                                {4, 7, 5}, {6, 5, 7}, {1, 0, 5}, {4, 5, 0}, {3, 7, 8}, {4, 9, 7}};
  struct Case
  {
    double t0, t8;
    bool welded;
  };
  for(const Case& c : {Case{1e-2, 1e-4, false}, Case{1e-4, 1e-2, false}, Case{1e-2, 1e-2, true}}) {
    SCOPED_TRACE(std::to_string(c.t0) + " " + std::to_string(c.t8));
    std::vector<double> t(base_points.size(), 0.5);
    t[0] = c.t0;
    t[8] = c.t8;
    t[9] = 1e-2;
    auto points = base_points;
    auto triangles = base;
    const Reconstruction_report r =
      ST::reconstruct_topology(points, triangles, ST::parameters::vertex_tolerance_map(CGAL::make_property_map(t)));
    EXPECT_EQ(r.exact_duplicates, 1u);
    EXPECT_EQ(r.snapped_vertices, c.welded ? 1u : 0u);
    EXPECT_EQ(r.border_edges_after, c.welded ? 0u : 4u);
    EXPECT_EQ(r.tolerance, 0.5);
  }
}

// A soup repaired with a tolerance per point: the tolerances of one patch of the elephant cut into
// patches are larger than the others. No point moves farther than its own tolerance; the same
// surface from the shuffled input (points renumbered with their tolerances, triangles shuffled and
// rotated); a second run on the result (its points keep their tolerances) changes nothing.
TEST(VertexToleranceMap, PipelineMovesNoPointBeyondItsToleranceWhateverTheOrder)
{
  auto [mesh_points, mesh_triangles] = load<Point>("clean/elephant.off");
  const double diag = ST::internal::bounding_box_diagonal(mesh_points, CGAL::Identity_property_map<Point>());
  const auto soup = soup_test::t_junction_soup(mesh_points, mesh_triangles, 5, 3e-7 * diag, 23);
  std::mt19937_64 rng(41);
  std::uniform_real_distribution<double> draw(0, 2e-6 * diag);
  std::vector<double> t(soup.points.size());
  for(std::size_t i = 0; i < t.size(); ++i) t[i] = soup.points[i].x() < 0 ? 2e-6 * diag : draw(rng);

  struct Welds
  {
    std::vector<std::pair<std::size_t, std::size_t>> merged;
    void on_merge(std::size_t d, std::size_t r) { merged.emplace_back(d, r); }
    void on_refusal(std::size_t, std::size_t, ST::Refusal_reason) {}
  } welds;
  auto p1 = soup.points;
  auto t1 = soup.triangles;
  const Reconstruction_report r1 = ST::reconstruct_topology(
    p1, t1, ST::parameters::vertex_tolerance_map(CGAL::make_property_map(t)).visitor(std::ref(welds)));
  EXPECT_GT(r1.snapped_vertices, 100u);
  EXPECT_GT(r1.split_triangles, 0u);
  EXPECT_GT(r1.border_edges_after, 0u);  // where the tolerances are too small, seams stay open
  EXPECT_LT(r1.border_edges_after, r1.border_edges_before);
  EXPECT_EQ(welds.merged.size(), r1.snapped_vertices);
  for(const auto& [d, rep] : welds.merged) {
    const double e = std::min(t[d], t[rep]);
    EXPECT_NE(CGAL::compare(CGAL::squared_distance(soup.points[d], soup.points[rep]), e * e), CGAL::LARGER) << d;
  }
  EXPECT_LE(r1.max_displacement, 2e-6 * diag);

  // On TBB's threads: the same points, triangles and report.
  {
    auto pp = soup.points;
    auto tp = soup.triangles;
    const Reconstruction_report rp = ST::reconstruct_topology<CGAL::Parallel_if_available_tag>(
      pp, tp, ST::parameters::vertex_tolerance_map(CGAL::make_property_map(t)));
    EXPECT_EQ(pp, p1);
    EXPECT_EQ(tp, t1);
    issue13::expect_same_report(rp, r1);
  }

  // Shuffled.
  std::vector<std::size_t> relabel(soup.points.size());
  std::iota(relabel.begin(), relabel.end(), 0);
  std::shuffle(relabel.begin(), relabel.end(), rng);
  std::vector<Point> p2(soup.points.size());
  std::vector<double> tol2(soup.points.size());
  for(std::size_t i = 0; i < relabel.size(); ++i) {
    p2[relabel[i]] = soup.points[i];
    tol2[relabel[i]] = t[i];
  }
  std::vector<Triangle> t2 = soup.triangles;
  std::shuffle(t2.begin(), t2.end(), rng);
  for(Triangle& f : t2) {
    std::rotate(f.begin(), f.begin() + static_cast<std::ptrdiff_t>(rng() % 3), f.end());
    for(std::size_t& v : f) v = relabel[v];
  }
  const Reconstruction_report r2 =
    ST::reconstruct_topology(p2, t2, ST::parameters::vertex_tolerance_map(CGAL::make_property_map(tol2)));
  EXPECT_EQ(r2.snapped_vertices, r1.snapped_vertices);
  EXPECT_EQ(r2.split_triangles, r1.split_triangles);
  EXPECT_EQ(r2.border_edges_after, r1.border_edges_after);
  EXPECT_EQ(r2.max_displacement, r1.max_displacement);
  EXPECT_EQ(issue13::triangles_by_coordinates(p1, t1), issue13::triangles_by_coordinates(p2, t2));

  // Again on the result: every output point is an input point and keeps its tolerance.
  std::map<std::array<double, 3>, double> tolerance_at;
  for(std::size_t i = 0; i < soup.points.size(); ++i) {
    const std::array<double, 3> key = {soup.points[i].x(), soup.points[i].y(), soup.points[i].z()};
    auto [it, added] = tolerance_at.emplace(key, t[i]);
    if(!added) it->second = std::min(it->second, t[i]);
  }
  std::vector<double> t_out;
  for(const Point& q : p1) t_out.push_back(tolerance_at.at({q.x(), q.y(), q.z()}));
  auto p3 = p1;
  auto t3 = t1;
  const Reconstruction_report r3 =
    ST::reconstruct_topology(p3, t3, ST::parameters::vertex_tolerance_map(CGAL::make_property_map(t_out)));
  EXPECT_EQ(r3.snapped_vertices, 0u);
  EXPECT_EQ(r3.split_triangles, 0u);
  EXPECT_EQ(p3, p1);
  EXPECT_EQ(t3, t1);
}

TEST(VertexToleranceMap, PipelineRefusesBadValuesAndLeavesTheSoupUnchanged)
{
  auto [points, triangles] = load<Point>("cgal_repair/pig.stl.xz");
  const auto p0 = points;
  const auto t0 = triangles;
  for(const double bad : {-1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    std::vector<double> t(points.size(), 0.3);
    t[points.size() / 2] = bad;
    EXPECT_THROW(ST::reconstruct_topology(points, triangles, ST::parameters::vertex_tolerance_map(CGAL::make_property_map(t))),
                 ST::Invalid_input);
    EXPECT_EQ(points, p0);
    EXPECT_EQ(triangles, t0);
  }
  const std::vector<double> t(points.size(), 0.3);
  EXPECT_THROW(ST::reconstruct_topology(points, triangles,
                                        ST::parameters::vertex_tolerance_map(CGAL::make_property_map(t),
                                                                             CGAL::parameters::snapping_tolerance(0.3))),
               ST::Invalid_input);
  EXPECT_THROW(ST::reconstruct_topology(points, triangles,
                                        ST::parameters::relative_tolerance(1e-3, ST::parameters::vertex_tolerance_map(
                                                                                   CGAL::make_property_map(t)))),
               ST::Invalid_input);
  EXPECT_EQ(points, p0);
  EXPECT_EQ(triangles, t0);
}

// A file in another unit: its coordinates near 1e-270 or 1e300, where squared distances and
// squared tolerances leave the range of doubles (near 1e-270 nothing was welded; near 1e300 the
// tolerance was refused as too large). The pipeline on a soup scaled by 2^k, with its tolerances
// scaled by 2^k, takes the decisions it takes on the soup: the same welds, refusals and splits
// (the visitor), the same triangles, the points scaled, the report's lengths scaled.
TEST(Pipeline, RepairDoesNotDependOnTheScale)
{
  std::vector<Named_soup> inputs;
  {
    auto [points, triangles] = load<Point>("cad/ALSTOM_TEST4.off");
    const double diag = ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>());
    inputs.push_back({"ALSTOM_TEST4", points, triangles, 1e-3 * diag});
  }
  {
    auto [points, triangles] = load<Point>("clean/elephant.off");
    const double diag = ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>());
    const double jitter = 1e-5 * diag;
    auto f_soup = soup_test::small_feature_soup(points, triangles, 10, jitter, 0.5, 8 * jitter, 3);
    inputs.push_back({"elephant with small features", f_soup.points, f_soup.triangles, 8 * jitter});
  }
  const auto scaled = [](std::vector<Point> points, int k) {
    for(Point& p : points) p = Point(std::ldexp(p.x(), k), std::ldexp(p.y(), k), std::ldexp(p.z(), k));
    return points;
  };
  for(const Named_soup& in : inputs) {
    SCOPED_TRACE(in.name);
    auto p1 = in.points;
    auto t1 = in.triangles;
    Recording_visitor v1;
    const Reconstruction_report r1 =
      ST::reconstruct_topology(p1, t1, CGAL::parameters::snapping_tolerance(in.tolerance).visitor(std::ref(v1)));
    ASSERT_GT(r1.snapped_vertices + r1.split_triangles, 0u);
    // (-120 and 120: run as they are; the others on the points scaled back to the unit)
    for(int k : {-900, -600, -140, -120, 120, 600, 1000}) {
      SCOPED_TRACE("2^" + std::to_string(k));
      const std::vector<Point> input = scaled(in.points, k);
      const std::vector<double> tolerances(input.size(), std::ldexp(in.tolerance, k));
      for(int with_map = 0; with_map < 2; ++with_map) {
        auto p2 = input;
        auto t2 = in.triangles;
        Recording_visitor v2;
        const Reconstruction_report r2 =
          with_map ? ST::reconstruct_topology(p2, t2, ST::parameters::vertex_tolerance_map(
                                                        CGAL::make_property_map(tolerances)).visitor(std::ref(v2)))
                   : ST::reconstruct_topology(p2, t2, CGAL::parameters::snapping_tolerance(std::ldexp(in.tolerance, k))
                                                        .visitor(std::ref(v2)));
        EXPECT_EQ(t2, t1);
        EXPECT_EQ(p2, scaled(p1, k));
        EXPECT_EQ(v2.told, v1.told);
        EXPECT_EQ(r2.tolerance, std::ldexp(r1.tolerance, k));
        EXPECT_EQ(r2.max_displacement, std::ldexp(r1.max_displacement, k));
        EXPECT_EQ(r2.snapped_vertices, r1.snapped_vertices);
        EXPECT_EQ(r2.split_triangles, r1.split_triangles);
        EXPECT_EQ(r2.border_edges_after, r1.border_edges_after);
        EXPECT_EQ(r2.small_features_resolved, r1.small_features_resolved);
        EXPECT_EQ(r2.refused_welds(), r1.refused_welds());
      }
    }
  }
  // A refusal leaves the soup as it was, not scaled.
  std::vector<Point> far = scaled(inputs[0].points, 1000);
  const std::vector<Point> far0 = far;
  std::vector<Triangle> t = inputs[0].triangles;
  EXPECT_THROW(ST::reconstruct_topology(far, t, CGAL::parameters::snapping_tolerance(-1.0)), ST::Invalid_input);
  EXPECT_EQ(far, far0);
}

// A soup whose coordinates are subnormal (a file in a unit near 1e-320): brought into range by
// 2^1023, the largest power of two a double holds, it is repaired as at scale 1. Before, the
// exponent was 1074, whose power of two is infinite, and the soup was refused.
TEST(Pipeline, SoupOfSubnormalCoordinatesIsRepairedAsAtScaleOne)
{
  // Two unit squares side by side, the right one 1/16 away along x, one of its seam corners 1/32
  // higher: every coordinate a multiple of 1/32 up to 2, so a multiple of 2^-1074 (the smallest
  // subnormal) once scaled by 2^-1069, exactly.
  const std::vector<Point> points = {Point(0, 0, 0),      Point(1, 0, 0), Point(1, 1, 0), Point(0, 1, 0),
                                     Point(1.0625, 0, 0), Point(2, 0, 0), Point(2, 1, 0), Point(1.0625, 1.03125, 0)};
  const std::vector<Triangle> triangles = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}};
  const double tolerance = 0.125;
  auto p1 = points;
  auto t1 = triangles;
  const Reconstruction_report r1 = ST::reconstruct_topology(p1, t1, CGAL::parameters::snapping_tolerance(tolerance));
  ASSERT_EQ(r1.snapped_vertices, 2u);
  ASSERT_EQ(r1.border_edges_after, 6u);
  for(int k : {-1069, -1060, -1030}) {
    SCOPED_TRACE("2^" + std::to_string(k));
    std::vector<Point> p2;
    for(const Point& p : points) p2.emplace_back(std::ldexp(p.x(), k), std::ldexp(p.y(), k), std::ldexp(p.z(), k));
    ASSERT_LT(std::ldexp(2.0, k), std::numeric_limits<double>::min()); // (subnormal)
    auto t2 = triangles;
    const Reconstruction_report r2 =
      ST::reconstruct_topology(p2, t2, CGAL::parameters::snapping_tolerance(std::ldexp(tolerance, k)));
    EXPECT_EQ(t2, t1);
    ASSERT_EQ(p2.size(), p1.size());
    for(std::size_t i = 0; i < p1.size(); ++i)
      EXPECT_EQ(p2[i], Point(std::ldexp(p1[i].x(), k), std::ldexp(p1[i].y(), k), std::ldexp(p1[i].z(), k))) << i;
    EXPECT_EQ(r2.snapped_vertices, r1.snapped_vertices);
    EXPECT_EQ(r2.border_edges_after, r1.border_edges_after);
    EXPECT_EQ(r2.tolerance, std::ldexp(r1.tolerance, k));
    EXPECT_EQ(r2.max_displacement, std::ldexp(r1.max_displacement, k));
  }
}

// The steps on their own, at the same scales: `snap_vertices()` and `split_t_junctions()` decide
// on a scaled copy of points beyond 2^128 or below 2^-128 (the caller's points are not changed).
TEST(Pipeline, SnapAndSplitDoNotDependOnTheScale)
{
  const auto [points, triangles] = load<Point>("cad/ALSTOM_TEST4.off");
  const double tolerance = 2e-4 * ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>());
  const auto scaled = [](std::vector<Point> p, int k) {
    for(Point& q : p) q = Point(std::ldexp(q.x(), k), std::ldexp(q.y(), k), std::ldexp(q.z(), k));
    return p;
  };
  auto welded = triangles;
  Recording_visitor welds;
  const ST::Snap_report s1 =
    ST::snap_vertices(points, welded, CGAL::parameters::snapping_tolerance(tolerance).visitor(std::ref(welds)));
  auto split = triangles;
  Recording_visitor splits;
  const ST::Split_report x1 =
    ST::split_t_junctions(points, split, CGAL::parameters::snapping_tolerance(tolerance).visitor(std::ref(splits)));
  ASSERT_GT(s1.merged_vertices, 0u);
  ASSERT_GT(x1.split_triangles, 0u);
  for(int k : {-900, -140, 120, 1000}) {
    SCOPED_TRACE("2^" + std::to_string(k));
    const std::vector<Point> input = scaled(points, k);
    const double t = std::ldexp(tolerance, k);
    auto welded2 = triangles;
    Recording_visitor welds2;
    const ST::Snap_report s2 =
      ST::snap_vertices(input, welded2, CGAL::parameters::snapping_tolerance(t).visitor(std::ref(welds2)));
    EXPECT_EQ(welded2, welded);
    EXPECT_EQ(welds2.told, welds.told);
    EXPECT_EQ(s2.merged_vertices, s1.merged_vertices);
    EXPECT_EQ(s2.tolerance, std::ldexp(s1.tolerance, k));
    EXPECT_EQ(s2.max_displacement, std::ldexp(s1.max_displacement, k));
    const std::vector<double> tolerances(input.size(), t);
    auto split2 = triangles;
    Recording_visitor splits2;
    const ST::Split_report x2 = ST::split_t_junctions(
      input, split2,
      ST::parameters::vertex_tolerance_map(CGAL::make_property_map(tolerances)).visitor(std::ref(splits2)));
    EXPECT_EQ(split2, split);
    EXPECT_EQ(splits2.told, splits.told);
    EXPECT_EQ(x2.split_triangles, x1.split_triangles);
    EXPECT_EQ(x2.tolerance, std::ldexp(x1.tolerance, k));
  }
}

} // namespace tolerance_map

} // namespace reconstruct_topology_test
