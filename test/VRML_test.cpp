// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The VRML reader under hostile input (bounded DEF/USE instantiation, shared Coordinates, long
// polygons, binary files, overflows) and the polygon triangulator it shares with the other
// readers (Soup_topology/internal/triangulate_polygon.h), checked against a brute-force
// coverage test and against the textbook quadratic ear clipper. The ordinary VRML tests are in
// IO_test.cpp.

#include <Soup_topology/IO/VRML.h>
#include <Soup_topology/internal/triangulate_polygon.h>

#include "bounded_run.h"
#include "test_utilities.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

// The names of this file live in a namespace of its own: test/CMakeLists.txt compiles several
// test files as one translation unit.
namespace VRML_test {

namespace {

namespace ST = Soup_topology;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = std::array<std::size_t, 3>;

std::string cli() { return SOUP_TOPOLOGY_CLI; }

const char* const header = "#VRML V2.0 utf8\n";
const char* const one_triangle =
  "Shape { geometry IndexedFaceSet { coord Coordinate { point [0 0 0, 1 0 0, 0 1 0] } "
  "coordIndex [0 1 2 -1] } }";

std::string write_file(const std::string& folder, const std::string& name, const std::string& text)
{
  const std::string path = folder + "/" + name;
  std::ofstream out(path, std::ios::binary);
  out << text;
  return path;
}

struct Read
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  ST::IO::VRML_read_result result;
};

Read read_string(const std::string& text, const ST::IO::VRML_read_options& options = ST::IO::VRML_read_options())
{
  Read r;
  std::istringstream in(text);
  r.result = ST::IO::read_VRML(in, r.points, r.triangles, options);
  return r;
}

std::string error_of(const std::string& text, const ST::IO::VRML_read_options& options = ST::IO::VRML_read_options())
{
  try
  {
    read_string(text, options);
  }
  catch(const ST::IO::Read_error& e)
  {
    return e.what();
  }
  return "";
}

// ------------------------------------------------------------------ hostile files

// forty levels of groups, each using the previous one twice: 2^40 instances of the bottom
std::string dag_file(std::size_t levels, bool with_geometry)
{
  std::string s = header;
  s += std::string("DEF L0 Group { children [ ") + (with_geometry ? one_triangle : "") + " ] }\n";
  for(std::size_t i = 1; i <= levels; ++i)
    s += "DEF L" + std::to_string(i) + " Group { children [ USE L" + std::to_string(i - 1) + " USE L"
       + std::to_string(i - 1) + " ] }\n";
  return s;
}

// `links` groups, each the parent of the previous one: instantiating the last one walks them all
std::string chain_file(std::size_t links, bool with_geometry)
{
  std::string s = header;
  s += with_geometry ? std::string("DEF x ") + one_triangle + "\n" : std::string("DEF x Group { }\n");
  for(std::size_t i = 0; i < links; ++i)
    s += "DEF x Group { children USE x }\n";
  return s;
}

// `shapes` one-triangle shapes that use one Coordinate of `points` points
std::string shared_coordinate_file(std::size_t shapes, std::size_t points)
{
  std::ostringstream s;
  s << header << "Shape { geometry IndexedFaceSet { coord DEF C Coordinate { point [";
  for(std::size_t i = 0; i < points; ++i)
    s << (i % 200) << ' ' << (i / 200) << " 0,";
  s << "] } coordIndex [0 1 200 -1] } }\n";
  for(std::size_t i = 0; i < shapes; ++i)
    s << "Shape { geometry IndexedFaceSet { coord USE C coordIndex [0 1 200 -1] } }\n";
  return s.str();
}

// a band wound `turns` times around the origin: `corners` corners, half on each side
std::vector<std::array<double, 2>> spiral(std::size_t corners, double turns)
{
  const std::size_t half = corners / 2;
  std::vector<std::array<double, 2>> outer, inner;
  for(std::size_t i = 0; i < half; ++i)
  {
    const double t = 0.05 + double(i) * turns * 2 * M_PI / double(half);
    const double r = 1 + t;
    outer.push_back({r * std::cos(t), r * std::sin(t)});
    inner.push_back({(r - 0.5) * std::cos(t), (r - 0.5) * std::sin(t)});
  }
  outer.insert(outer.end(), inner.rbegin(), inner.rend());
  return outer;
}

// a comb of corners/4 teeth of height 10 on a base, clockwise
std::vector<std::array<double, 2>> comb(std::size_t corners)
{
  const std::size_t teeth = corners / 4;
  std::vector<std::array<double, 2>> p;
  for(std::size_t i = 0; i < teeth; ++i)
  {
    const double x = 2 * double(i);
    p.push_back({x, 0});
    p.push_back({x, 10});
    p.push_back({x + 1, 10});
    p.push_back({x + 1, 1});
  }
  p.back() = {2 * double(teeth) - 1, 0};
  p.push_back({2 * double(teeth) - 1, -1});
  p.push_back({0, -1});
  return p;
}

std::string polygon_file(const std::vector<std::array<double, 2>>& polygon)
{
  std::ostringstream s;
  s.precision(17);
  s << header << "Shape { geometry IndexedFaceSet { coord Coordinate { point [";
  for(const auto& p : polygon)
    s << p[0] << ' ' << p[1] << " 0,";
  s << "] } coordIndex [";
  for(std::size_t i = 0; i < polygon.size(); ++i)
    s << i << ' ';
  s << "-1] } }\n";
  return s.str();
}

// runs the command-line tool's `stats` on `path` within bounds far above the target (2 s and
// 500 MB), so that a regression shows as a failed expectation, not as a hung test
soup_test::Bounded_run run_stats(const std::string& path)
{
  return soup_test::run_bounded({cli(), "stats", path}, 20, 1500);
}

void expect_bounded(const soup_test::Bounded_run& r, const std::string& what)
{
  SCOPED_TRACE(what);
  EXPECT_EQ(r.signal, 0) << r.err;
  EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 2) << r.exit_code << " " << r.err;
  if(!soup_test::sanitized_build)
  {
    EXPECT_LT(r.cpu_seconds, 2.0) << r.err;
    EXPECT_LT(r.peak_rss_mb, 500u) << r.err;
  }
  EXPECT_EQ(r.err.find("out of memory"), std::string::npos) << r.err;
}

TEST(HostileInput, Issue21VrmlDefUseDag)
{
  const std::string folder = soup_test::temporary_folder("vrml_dag");
  const std::string path = write_file(folder, "dag.wrl", dag_file(40, true));
  const soup_test::Bounded_run r = run_stats(path);
  expect_bounded(r, "dag.wrl");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(path + ":"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("instance_budget"), std::string::npos) << r.err;

  // in the library: Read_error, with the line
  const std::string message = error_of(dag_file(40, true));
  EXPECT_EQ(message.rfind("VRML:", 0), 0u) << message;
  EXPECT_NE(message.find("DEF/USE instances"), std::string::npos) << message;
}

TEST(HostileInput, Issue21VrmlDefUseDagWithoutGeometry)
{
  // 2^60 instances of groups that hold nothing: nothing to instantiate
  const std::string folder = soup_test::temporary_folder("vrml_dag_empty");
  const std::string path = write_file(folder, "dag_empty.wrl", dag_file(60, false));
  const soup_test::Bounded_run r = run_stats(path);
  expect_bounded(r, "dag_empty.wrl");
  EXPECT_EQ(r.exit_code, 0) << r.err;

  const Read read = read_string(dag_file(60, false));
  EXPECT_TRUE(read.points.empty());
  EXPECT_TRUE(read.triangles.empty());
}

TEST(HostileInput, Issue21VrmlUseChain)
{
  const std::string folder = soup_test::temporary_folder("vrml_chain");
  const std::string path = write_file(folder, "chain.wrl", chain_file(34000, false));
  const soup_test::Bounded_run r = run_stats(path);
  expect_bounded(r, "chain.wrl");
  EXPECT_EQ(r.exit_code, 0) << r.err;

  // with a shape at the bottom: 34000 chains of up to 34000 links, refused by the budget
  const std::string with_shape = write_file(folder, "chain_shape.wrl", chain_file(34000, true));
  const soup_test::Bounded_run s = run_stats(with_shape);
  expect_bounded(s, "chain_shape.wrl");
  EXPECT_EQ(s.exit_code, 2);
  EXPECT_NE(s.err.find("instance_budget"), std::string::npos) << s.err;
}

TEST(VrmlInstantiation, ChainsOfTransformsAreComposedWithoutRecursion)
{
  // 500 links, every other one a translation by (1, 0, 0); every link is a root, so the shape
  // is instantiated 1 + 500 times, then once more under a last transform
  std::string text = std::string(header) + "DEF y " + one_triangle + "\n";
  for(int i = 0; i < 500; ++i)
    text += i % 2 == 0 ? "DEF y Transform { translation 1 0 0 children USE y }\n" : "DEF y Group { children USE y }\n";
  text += "Transform { translation 0 0 5 children USE y }\n";
  const Read read = read_string(text);
  ASSERT_EQ(read.triangles.size(), 502u);
  ASSERT_EQ(read.points.size(), 3u * 502);
  EXPECT_EQ(read.result.number_of_shapes, 502u);
  EXPECT_EQ(read.points[3 * 1], Point(1, 0, 0));     // under the first link
  EXPECT_EQ(read.points[3 * 2], Point(1, 0, 0));     // the second link is a Group
  EXPECT_EQ(read.points[3 * 500], Point(250, 0, 0)); // under the 500th
  EXPECT_EQ(read.points[3 * 501], Point(250, 0, 5));
  EXPECT_EQ(read.points[3 * 501 + 1], Point(251, 0, 5));
}

TEST(HostileInput, Issue21VrmlSharedCoordinate)
{
  const std::string folder = soup_test::temporary_folder("vrml_coordinate");
  const std::string path = write_file(folder, "shared.wrl", shared_coordinate_file(5000, 20000));
  const soup_test::Bounded_run r = run_stats(path);
  expect_bounded(r, "shared.wrl");
  EXPECT_EQ(r.exit_code, 0) << r.err;

  // each shape appends the three points it names, at the right places
  const Read read = read_string(shared_coordinate_file(50, 20000));
  ASSERT_EQ(read.points.size(), 3u * 51);
  ASSERT_EQ(read.triangles.size(), 51u);
  EXPECT_EQ(read.result.number_of_points, 3u * 51);
  for(std::size_t t = 0; t < read.triangles.size(); ++t)
  {
    EXPECT_EQ(read.points[read.triangles[t][0]], Point(0, 0, 0));
    EXPECT_EQ(read.points[read.triangles[t][1]], Point(1, 0, 0));
    EXPECT_EQ(read.points[read.triangles[t][2]], Point(0, 1, 0));
  }
}

TEST(HostileInput, Issue21VrmlSharedCoordinateKeepsTheOrderOfItsPoints)
{
  // the faces name the points out of order and skip some: they come in the Coordinate's order
  const Read read = read_string(std::string(header) + R"(
Shape { geometry IndexedFaceSet { coord DEF C Coordinate { point [ 0 0 0, 9 9 9, 1 0 0, 0 1 0, 1 1 0 ] }
                                  coordIndex [ 4 3 2 -1 ] } }
Shape { geometry IndexedFaceSet { coord USE C coordIndex [ 3 0 2 -1 ] } })");
  ASSERT_EQ(read.points.size(), 6u);
  EXPECT_EQ(read.points[0], Point(1, 0, 0));
  EXPECT_EQ(read.points[1], Point(0, 1, 0));
  EXPECT_EQ(read.points[2], Point(1, 1, 0));
  EXPECT_EQ(read.triangles[0], (Triangle{2, 1, 0}));
  EXPECT_EQ(read.points[3], Point(0, 0, 0));
  EXPECT_EQ(read.triangles[1], (Triangle{5, 3, 4}));
}

TEST(HostileInput, Issue21VrmlBudgetsAreOptions)
{
  const std::string text = std::string(header) + "DEF A Group { children [ " + one_triangle
                         + " ] }\nGroup { children [ USE A USE A USE A ] }\n";
  EXPECT_EQ(read_string(text).triangles.size(), 4u);
  ST::IO::VRML_read_options few_instances;
  few_instances.instance_budget = 5;
  const std::string instances = error_of(text, few_instances);
  EXPECT_NE(instances.find("more than 5 node instances"), std::string::npos) << instances;
  ST::IO::VRML_read_options little_output;
  little_output.output_budget = 10;
  const std::string output = error_of(text, little_output);
  EXPECT_NE(output.find("more than 10 points and triangles"), std::string::npos) << output;
  little_output.output_budget = 16;
  EXPECT_EQ(read_string(text, little_output).triangles.size(), 4u);
}

TEST(HostileInput, Issue21VrmlSpiralAndComb)
{
  const std::string folder = soup_test::temporary_folder("vrml_polygons");
  const std::pair<const char*, std::vector<std::array<double, 2>>> files[] = {
    {"spiral10k.wrl", spiral(10000, 20)},
    {"spiral20k.wrl", spiral(20000, 20)},
    {"comb60k.wrl", comb(60000)},
  };
  for(const auto& f : files)
  {
    const std::string path = write_file(folder, f.first, polygon_file(f.second));
    const soup_test::Bounded_run r = run_stats(path);
    expect_bounded(r, f.first);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find(" " + std::to_string(f.second.size() - 2) + "\n"), std::string::npos) << r.out;
  }
}

TEST(HostileInput, Issue21VrmlGzipIsNamed)
{
  // the gzip magic, then deflated bytes
  const char gzip[] = "\x1f\x8b\x08\x00\x00\x00\x00\x00\x00\x03\xcb\x48\xcd\xc9\xc9\x07\x00";
  const std::string bytes(gzip, sizeof gzip - 1);
  const std::string message = error_of(bytes);
  EXPECT_EQ(message.rfind("VRML:1: ", 0), 0u) << message;
  EXPECT_NE(message.find("gzip-compressed"), std::string::npos) << message;
  EXPECT_NE(message.find("decompress"), std::string::npos) << message;
  for(char c : message)
    EXPECT_TRUE(static_cast<unsigned char>(c) >= 0x20 && static_cast<unsigned char>(c) < 0x7F) << message;
}

TEST(HostileInput, Issue21VrmlControlBytesAreRefused)
{
  std::string bytes;
  for(int i = 0; i < 600; ++i)
    bytes += static_cast<char>(1 + i % 8);
  const std::string message = error_of(bytes);
  EXPECT_EQ(message.rfind("VRML:1: ", 0), 0u) << message;
  EXPECT_NE(message.find("control byte \\x01"), std::string::npos) << message;

  const std::string folder = soup_test::temporary_folder("vrml_control");
  const std::string path = write_file(folder, "control.wrl", bytes);
  const soup_test::Bounded_run r = run_stats(path);
  expect_bounded(r, "control.wrl");
  EXPECT_EQ(r.exit_code, 2);

  // the same byte in a comment or a string is not an error; an empty file is an empty scene
  EXPECT_EQ(error_of(std::string(header) + "# a \x01 comment\nWorldInfo { title \"\x02\" }\n" + one_triangle), "");
  EXPECT_EQ(error_of(""), "");
}

TEST(HostileInput, Issue21VrmlBinaryBytesArePrintable)
{
  const std::string message = error_of(std::string(header) + "\xff\xfe 12");
  EXPECT_NE(message.find("\\xff\\xfe"), std::string::npos) << message;
  for(char c : message)
    EXPECT_TRUE(static_cast<unsigned char>(c) >= 0x20 && static_cast<unsigned char>(c) < 0x7F) << message;
}

TEST(HostileInput, Issue21VrmlOverflowNamesFileAndLine)
{
  const std::string text = std::string(header) + "Transform { scale 1e200 1e200 1e200 children\n"
                           "  Transform { scale 1e200 1e200 1e200 children\n    " + one_triangle + " } }\n";
  const std::string message = error_of(text);
  EXPECT_EQ(message.rfind("VRML:4: ", 0), 0u) << message; // the IndexedFaceSet's line
  EXPECT_NE(message.find("overflows"), std::string::npos) << message;

  const std::string folder = soup_test::temporary_folder("vrml_overflow");
  const std::string path = write_file(folder, "overflow.wrl", text);
  const soup_test::Bounded_run r = run_stats(path);
  expect_bounded(r, "overflow.wrl");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(path + ":4: "), std::string::npos) << r.err;

  const std::string too_large = error_of(std::string(header) + "Shape { geometry IndexedFaceSet {\n"
                                         "coord Coordinate { point [ 0 0 1e999 ] } } }");
  EXPECT_EQ(too_large.rfind("VRML:3: ", 0), 0u) << too_large;
  EXPECT_NE(too_large.find("out of the range of a double"), std::string::npos) << too_large;
}

// ------------------------------------------------------------------ the KiCad files

std::uint64_t fnv(std::uint64_t h, std::uint64_t v)
{
  for(int i = 0; i < 8; ++i)
  {
    h ^= (v >> (8 * i)) & 0xFF;
    h *= 1099511628211ull;
  }
  return h;
}

// points, triangles and their shapes hashed: coordinates by their bits
std::uint64_t checksum(const std::vector<Point>& points, const std::vector<Triangle>& triangles,
                       const std::vector<std::size_t>& shapes)
{
  std::uint64_t h = 1469598103934665603ull;
  for(const Point& p : points)
    for(double d : {p.x(), p.y(), p.z()})
    {
      std::uint64_t bits;
      std::memcpy(&bits, &d, sizeof bits);
      h = fnv(h, bits);
    }
  for(const Triangle& t : triangles)
    for(std::size_t v : t)
      h = fnv(h, v);
  for(std::size_t s : shapes)
    h = fnv(h, s);
  return h;
}

TEST(HostileInput, Issue21VrmlKicadFilesReadAsBefore)
{
  // reference counts and checksums of the points, triangles and shapes read from each file
  struct Expected
  {
    const char* file;
    std::size_t points, triangles;
    std::uint64_t checksum;
  };
  const Expected files[] = {
    {"CP_Radial_D10.0mm_P5.00mm.wrl", 2607, 3432, 0xc21a86fb4bf4ed09ull},
    {"Infineon_EasyPIM-2B.wrl.xz", 194908, 194708, 0xf98de3f4b075ea90ull},
    {"LQFP-48_7x7mm_P0.5mm.wrl.xz", 8423, 6978, 0xc5eb06d4370c00d3ull},
    {"PinHeader_1x04_P2.54mm_Vertical.wrl", 476, 292, 0x379772e73ff4ff5bull},
    {"R_Axial_DIN0207_L6.3mm_D2.5mm_P10.16mm_Horizontal.wrl", 2574, 3600, 0xa7af343bf06242e0ull},
    {"SOT-23.wrl", 724, 696, 0xdf715e0dadac148aull},
    {"Samtec_FMC_ASP-134602-01_10x40_P1.27mm_Vertical.wrl.xz", 78682, 73312, 0xe49de4e3c84fbc6cull},
    {"TO-220-3_Vertical.wrl", 370, 280, 0x8a7b4ba35e9e020dull},
  };
  for(const Expected& e : files)
  {
    SCOPED_TRACE(e.file);
    std::vector<Point> points;
    std::vector<Triangle> triangles;
    const auto result = ST::IO::read_VRML(soup_test::data_file(std::string("cad/kicad/") + e.file), points, triangles);
    EXPECT_EQ(points.size(), e.points);
    EXPECT_EQ(triangles.size(), e.triangles);
    EXPECT_EQ(checksum(points, triangles, result.triangle_shape_ids), e.checksum);
  }
}

TEST(VrmlDocumentation, RecipeGivesAValidSoup)
{
  // the recipe of doc/Soup_topology/VRML.md: read, weld, drop the collapsed triangles
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  ST::IO::read_VRML(soup_test::data_file("cad/kicad/CP_Radial_D10.0mm_P5.00mm.wrl"), points, triangles);
  ST::merge_duplicate_points(points, triangles);
  EXPECT_EQ(ST::remove_collapsed_triangles(triangles), 20u);
  for(const Triangle& t : triangles)
    ASSERT_TRUE(t[0] != t[1] && t[1] != t[2] && t[2] != t[0]);
}

// ------------------------------------------------------------------ triangulate_polygon

using I2 = std::array<std::int64_t, 2>;

std::int64_t cross(const I2& a, const I2& b, const I2& c)
{
  return (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
}

// twice the signed area
std::int64_t area2(const std::vector<I2>& polygon)
{
  std::int64_t s = 0;
  for(std::size_t i = 0; i < polygon.size(); ++i)
  {
    const I2& p = polygon[i];
    const I2& q = polygon[(i + 1) % polygon.size()];
    s += p[0] * q[1] - p[1] * q[0];
  }
  return s;
}

// whether the interiors of two triangles of positive area (counterclockwise) meet: no edge of
// either separates them
bool interiors_meet(const std::array<I2, 3>& s, const std::array<I2, 3>& t)
{
  auto separated_by_an_edge_of = [](const std::array<I2, 3>& a, const std::array<I2, 3>& b) {
    for(int e = 0; e < 3; ++e)
    {
      bool all_outside = true;
      for(const I2& p : b)
        if(cross(a[e], a[(e + 1) % 3], p) > 0)
          all_outside = false;
      if(all_outside)
        return true;
    }
    return false;
  };
  return !separated_by_an_edge_of(s, t) && !separated_by_an_edge_of(t, s);
}

// whether the point p lies strictly inside the simple polygon (crossing number), or on its
// boundary (`on_boundary`)
bool inside(const std::vector<I2>& polygon, const I2& p, bool& on_boundary)
{
  bool in = false;
  on_boundary = false;
  for(std::size_t i = 0; i < polygon.size(); ++i)
  {
    const I2& a = polygon[i];
    const I2& b = polygon[(i + 1) % polygon.size()];
    if(cross(a, b, p) == 0 && std::min(a[0], b[0]) <= p[0] && p[0] <= std::max(a[0], b[0])
       && std::min(a[1], b[1]) <= p[1] && p[1] <= std::max(a[1], b[1]))
      on_boundary = true;
    if((a[1] > p[1]) != (b[1] > p[1]))
    {
      // the crossing's x against p's, exactly: sign of (x - p.x) * (b.y - a.y)
      const std::int64_t d = (b[0] - a[0]) * (p[1] - a[1]) - (p[0] - a[0]) * (b[1] - a[1]);
      if((d > 0) == (b[1] > a[1]))
        in = !in;
    }
  }
  return in;
}

// the triangles cover the counterclockwise simple polygon exactly: n - 2 triangles of its
// corners, each of area >= 0, whose areas add up to the polygon's, with pairwise disjoint
// interiors, and every sample point of a fine lattice covered once inside and never outside
void expect_exact_cover(const std::vector<I2>& polygon, const std::vector<Triangle>& triangles)
{
  const std::size_t n = polygon.size();
  ASSERT_EQ(triangles.size(), n - 2);
  std::int64_t sum = 0;
  std::vector<std::array<I2, 3>> t;
  for(const Triangle& f : triangles)
  {
    ASSERT_TRUE(f[0] < n && f[1] < n && f[2] < n);
    ASSERT_TRUE(f[0] != f[1] && f[1] != f[2] && f[2] != f[0]);
    const std::array<I2, 3> c{polygon[f[0]], polygon[f[1]], polygon[f[2]]};
    const std::int64_t a = cross(c[0], c[1], c[2]);
    ASSERT_GE(a, 0) << "a triangle turns the other way";
    sum += a;
    if(a > 0)
      t.push_back(c);
  }
  ASSERT_EQ(sum, area2(polygon));
  for(std::size_t i = 0; i < t.size(); ++i)
    for(std::size_t j = i + 1; j < t.size(); ++j)
      ASSERT_FALSE(interiors_meet(t[i], t[j])) << "triangles " << i << " and " << j << " overlap";
  // lattice points between the integer ones (the polygon scaled by 4, samples at odd
  // coordinates): each inside point in exactly one triangle
  std::vector<I2> scaled;
  for(const I2& p : polygon)
    scaled.push_back({4 * p[0], 4 * p[1]});
  std::int64_t lo[2] = {scaled[0][0], scaled[0][1]}, hi[2] = {lo[0], lo[1]};
  for(const I2& p : scaled)
    for(int k = 0; k < 2; ++k)
    {
      lo[k] = std::min(lo[k], p[k]);
      hi[k] = std::max(hi[k], p[k]);
    }
  for(std::int64_t x = lo[0] + 1; x < hi[0]; x += 2)
    for(std::int64_t y = lo[1] + 1; y < hi[1]; y += 2)
    {
      const I2 p{x, y};
      bool on_boundary = false;
      const bool in = inside(scaled, p, on_boundary);
      if(on_boundary)
        continue;
      int covered = 0;
      bool on_an_edge = false;
      for(const auto& c : t)
      {
        const I2 a{4 * c[0][0], 4 * c[0][1]}, b{4 * c[1][0], 4 * c[1][1]}, d{4 * c[2][0], 4 * c[2][1]};
        const std::int64_t s0 = cross(a, b, p), s1 = cross(b, d, p), s2 = cross(d, a, p);
        if(s0 >= 0 && s1 >= 0 && s2 >= 0)
        {
          if(s0 == 0 || s1 == 0 || s2 == 0)
            on_an_edge = true;
          else
            ++covered;
        }
      }
      if(on_an_edge)
        continue;
      ASSERT_EQ(covered, in ? 1 : 0) << "sample (" << x << ", " << y << ")/4";
    }
}

// the textbook quadratic ear clipper, the reference for the decisions of the fast one
std::vector<Triangle> reference_ear_clipping(const std::vector<I2>& polygon, std::size_t& left)
{
  auto turn = [&](std::size_t a, std::size_t b, std::size_t c) {
    return cross(polygon[a], polygon[b], polygon[c]);
  };
  std::vector<std::size_t> ring(polygon.size());
  for(std::size_t i = 0; i < ring.size(); ++i)
    ring[i] = i;
  std::vector<Triangle> out;
  std::size_t cursor = 0, misses = 0;
  left = 0;
  while(ring.size() > 3)
  {
    const std::size_t m = ring.size();
    const std::size_t ia = (cursor + m - 1) % m, ib = cursor % m, ic = (cursor + 1) % m;
    const std::size_t a = ring[ia], b = ring[ib], c = ring[ic];
    bool ear = turn(a, b, c) > 0;
    for(std::size_t j = 0; ear && j < m; ++j)
    {
      const std::size_t q = ring[j];
      if(q == a || q == b || q == c || polygon[q] == polygon[a] || polygon[q] == polygon[b] || polygon[q] == polygon[c])
        continue;
      if(turn(a, b, q) >= 0 && turn(b, c, q) >= 0 && turn(c, a, q) >= 0)
        ear = false;
    }
    if(ear)
    {
      out.push_back({a, b, c});
      ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(ib));
      cursor = ib;
      misses = 0;
    }
    else
    {
      ++cursor;
      if(++misses <= m)
        continue;
      for(std::size_t i = 1; i + 1 < m; ++i)
        out.push_back({ring[0], ring[i], ring[i + 1]});
      left = m;
      return out;
    }
  }
  out.push_back({ring[0], ring[1], ring[2]});
  return out;
}

// a random simple polygon: integer points sorted by angle around a point off the lattice
std::vector<I2> random_star(std::mt19937& random, std::size_t n, int size)
{
  std::uniform_int_distribution<int> coordinate(-size, size);
  std::vector<I2> p;
  std::vector<std::pair<double, I2>> by_angle;
  for(;;)
  {
    by_angle.clear();
    while(by_angle.size() < n)
    {
      const I2 q{coordinate(random), coordinate(random)};
      const double angle = std::atan2(double(q[1]) - 0.31, double(q[0]) - 0.17);
      bool taken = false;
      for(const auto& e : by_angle)
        taken = taken || e.second == q || std::abs(e.first - angle) < 1e-9;
      if(!taken)
        by_angle.push_back({angle, q});
    }
    std::sort(by_angle.begin(), by_angle.end());
    // the centre must see every gap under less than half a turn, or the polygon is not simple
    double widest = by_angle.front().first + 2 * M_PI - by_angle.back().first;
    for(std::size_t i = 1; i < n; ++i)
      widest = std::max(widest, by_angle[i].first - by_angle[i - 1].first);
    if(widest < M_PI - 1e-6)
      break;
  }
  for(const auto& e : by_angle)
    p.push_back(e.second);
  return p;
}

// a random comb: teeth of random heights and widths on a base
std::vector<I2> random_comb(std::mt19937& random, std::size_t teeth)
{
  std::uniform_int_distribution<int> height(1, 9), width(1, 3);
  std::vector<I2> p{{0, 0}};
  std::int64_t x = 0;
  for(std::size_t i = 0; i < teeth; ++i)
  {
    const std::int64_t w = width(random), gap = width(random), h = height(random);
    p.push_back({x + gap, 0});
    p.push_back({x + gap, h});
    p.push_back({x + gap + w, h});
    p.push_back({x + gap + w, 0});
    x += gap + w;
  }
  p.push_back({x + 1, 0});
  p.push_back({x + 1, -2});
  p.push_back({0, -2});
  // the teeth were listed left to right on top: clockwise; make it counterclockwise
  std::reverse(p.begin(), p.end());
  return p;
}

// triangulates `polygon` placed in three planes of 3D, in both orientations
void check_polygon(const std::vector<I2>& polygon)
{
  ASSERT_GT(area2(polygon), 0);
  const std::size_t n = polygon.size();
  for(int embedding = 0; embedding < 3; ++embedding)
  {
    std::vector<Point> points;
    for(const I2& p : polygon)
    {
      const double x = double(p[0]), y = double(p[1]);
      if(embedding == 0)
        points.emplace_back(x, y, 0);
      else if(embedding == 1)
        points.emplace_back(y, -3, x); // the plane y = -3, seen from -y
      else
        points.emplace_back(x, y, x + 2 * y); // a tilted plane
    }
    for(bool reversed : {false, true})
    {
      SCOPED_TRACE("embedding " + std::to_string(embedding) + (reversed ? ", reversed" : ""));
      std::vector<std::size_t> corners(n);
      for(std::size_t i = 0; i < n; ++i)
        corners[i] = reversed ? n - 1 - i : i;
      std::vector<Triangle> triangles{{7, 7, 7}}; // appended to
      const std::size_t left = ST::internal::triangulate_polygon(points, corners, triangles);
      ASSERT_EQ(triangles.front(), (Triangle{7, 7, 7}));
      triangles.erase(triangles.begin());
      EXPECT_EQ(left, 0u);
      if(reversed)
        for(Triangle& t : triangles)
          std::swap(t[1], t[2]); // back to the counterclockwise orientation of `polygon`
      expect_exact_cover(polygon, triangles);
      if(embedding == 0 && !reversed)
      {
        std::size_t reference_left = 0;
        EXPECT_EQ(triangles, reference_ear_clipping(polygon, reference_left)) << "other decisions than the reference";
        EXPECT_EQ(reference_left, left);
      }
    }
  }
}

TEST(TriangulatePolygon, RandomSimplePolygonsAreCoveredExactly)
{
  std::mt19937 random(21);
  for(int i = 0; i < 300; ++i)
  {
    SCOPED_TRACE("star " + std::to_string(i));
    const std::size_t n = 4 + static_cast<std::size_t>(i % 25);
    check_polygon(random_star(random, n, i % 2 == 0 ? 6 : 25));
    if(HasFatalFailure())
      return;
  }
  for(int i = 0; i < 100; ++i)
  {
    SCOPED_TRACE("comb " + std::to_string(i));
    check_polygon(random_comb(random, 1 + static_cast<std::size_t>(i % 12)));
    if(HasFatalFailure())
      return;
  }
}

TEST(TriangulatePolygon, PolygonsWithHolesJoinedByBridges)
{
  // a square with a square hole, joined by a bridge that repeats two corners (as CAD exporters
  // write faces with holes)
  const std::vector<I2> polygon{{0, 0}, {10, 0}, {10, 10}, {0, 10}, {0, 0}, {3, 3}, {3, 7}, {7, 7}, {7, 3}, {3, 3}};
  std::vector<Point> points;
  for(const I2& p : polygon)
    points.emplace_back(double(p[0]), double(p[1]), 0);
  std::vector<std::size_t> corners(polygon.size());
  for(std::size_t i = 0; i < corners.size(); ++i)
    corners[i] = i;
  std::vector<Triangle> triangles;
  EXPECT_EQ(ST::internal::triangulate_polygon(points, corners, triangles), 0u);
  ASSERT_EQ(triangles.size(), polygon.size() - 2);
  std::int64_t sum = 0;
  for(const Triangle& t : triangles)
  {
    const std::int64_t a = cross(polygon[t[0]], polygon[t[1]], polygon[t[2]]);
    EXPECT_GE(a, 0);
    sum += a;
  }
  EXPECT_EQ(sum, 2 * (100 - 16));
  std::size_t reference_left = 0;
  EXPECT_EQ(triangles, reference_ear_clipping(polygon, reference_left));
}

TEST(TriangulatePolygon, DegenerateAndSelfIntersectingPolygons)
{
  std::vector<Point> points{Point(0, 0, 0), Point(1, 0, 0), Point(2, 0, 0), Point(3, 0, 0), Point(4, 0, 0)};
  std::vector<Triangle> triangles;
  // fewer than 3 corners: nothing
  EXPECT_EQ(ST::internal::triangulate_polygon(points, {0, 1}, triangles), 2u);
  EXPECT_TRUE(triangles.empty());
  // collinear: no ear, fanned, every corner left
  EXPECT_EQ(ST::internal::triangulate_polygon(points, {0, 1, 2, 3, 4}, triangles), 5u);
  ASSERT_EQ(triangles.size(), 3u);
  EXPECT_EQ(triangles[0], (Triangle{0, 1, 2}));
  // a figure eight (bow tie) of 6 corners: clips what it can, fans the rest
  std::vector<Point> eight{Point(0, 0, 0), Point(2, 1, 0), Point(4, 0, 0), Point(4, 2, 0), Point(2, 1.5, 0), Point(0, 2, 0)};
  // swap two corners so that the boundary crosses itself
  std::swap(eight[1], eight[4]);
  triangles.clear();
  ST::internal::triangulate_polygon(eight, {0, 1, 2, 3, 4, 5}, triangles);
  EXPECT_EQ(triangles.size(), 4u);
  // a non-finite coordinate: no crash, n - 2 triangles
  std::vector<Point> bad{Point(0, 0, 0), Point(1, 0, 0), Point(std::nan(""), 1, 0), Point(0, 1, 0), Point(0.5, 0.5, 0)};
  triangles.clear();
  ST::internal::triangulate_polygon(bad, {0, 1, 2, 3, 4}, triangles);
  EXPECT_EQ(triangles.size(), 3u);
}

TEST(TriangulatePolygon, Issue21SpiralsAndCombsTakeNearLinearWork)
{
  // the visits of the k-d tree and of corners per corner stay under a constant (50 to 100 on
  // these; the quadratic clipper makes about k/2 per corner)
  const std::pair<const char*, std::vector<std::array<double, 2>>> polygons[] = {
    {"spiral 10k", spiral(10000, 20)},
    {"spiral 40k", spiral(40000, 20)},
    {"spiral 40k, 200 turns", spiral(40000, 200)},
    {"comb 60k", comb(60000)},
  };
  for(const auto& entry : polygons)
  {
    SCOPED_TRACE(entry.first);
    std::vector<double> uv;
    for(const auto& p : entry.second)
    {
      uv.push_back(p[0]);
      uv.push_back(p[1]);
    }
    std::size_t k = entry.second.size();
    if(std::string(entry.first).rfind("comb", 0) == 0)
    {
      // clockwise as written: the clipper wants counterclockwise
      std::vector<double> r;
      for(std::size_t i = k; i-- > 0;)
      {
        r.push_back(uv[2 * i]);
        r.push_back(uv[2 * i + 1]);
      }
      uv = r;
    }
    ST::internal::Ear_clipper clipper;
    double area = 0, twice_area = 0;
    std::size_t triangles = 0;
    const std::size_t left = clipper.clip(uv, k, [&](std::size_t a, std::size_t b, std::size_t c) {
      ++triangles;
      const double t = (uv[2 * b] - uv[2 * a]) * (uv[2 * c + 1] - uv[2 * a + 1])
                     - (uv[2 * b + 1] - uv[2 * a + 1]) * (uv[2 * c] - uv[2 * a]);
      EXPECT_GT(t, 0);
      area += t;
    });
    for(std::size_t i = 0; i < k; ++i)
    {
      const std::size_t j = (i + 1) % k;
      twice_area += uv[2 * i] * uv[2 * j + 1] - uv[2 * j] * uv[2 * i + 1];
    }
    EXPECT_EQ(left, 0u);
    EXPECT_EQ(triangles, k - 2);
    EXPECT_NEAR(area, twice_area, 1e-9 * std::abs(twice_area));
    EXPECT_LT(clipper.work(), 150 * k);
    EXPECT_LT(clipper.work(), ST::internal::Ear_clipper::work_limit(k));
  }
}

TEST(TriangulatePolygon, WorkCapFansTheRest)
{
  // the cap is deterministic: the same polygon gives the same triangles every time, and a
  // polygon past the cap is still turned into k - 2 triangles
  const auto polygon = spiral(2000, 20);
  std::vector<Point> points;
  for(const auto& p : polygon)
    points.emplace_back(p[0], p[1], 0);
  std::vector<std::size_t> corners(points.size());
  for(std::size_t i = 0; i < corners.size(); ++i)
    corners[i] = i;
  std::vector<Triangle> first, second;
  ST::internal::triangulate_polygon(points, corners, first);
  ST::internal::triangulate_polygon(points, corners, second);
  EXPECT_EQ(first, second);
  EXPECT_EQ(first.size(), points.size() - 2);
  EXPECT_GT(ST::internal::Ear_clipper::work_limit(2000), 150u * 2000);
}

} // namespace

} // namespace VRML_test
