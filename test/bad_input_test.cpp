// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The bad-input matrix (doc/Soup_topology/Bad_input.md), for the library and for the
// command-line tool: every broken file, index, coordinate or tolerance gets a clear error that
// names what is wrong and where; the caller's containers and an existing output file are left as
// they were; the tool exits with code 2. Headers that claim billions of elements fail at once,
// without allocating.

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/IO/OFF.h>
#include <Soup_topology/IO/STL.h>
#include <Soup_topology/IO/read_triangle_soup.h>
#include <Soup_topology/IO/write_triangle_soup.h>
#include <Soup_topology/orient_triangle_soup.h>
#include <Soup_topology/reconstruct_topology.h>
#include <Soup_topology/triangle_soup_to_face_graph.h>

#include "../tools/memory_reuse.h"
#include "bounded_run.h"
#include "test_utilities.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/OFF.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <csignal>
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

// The names of this file live in a namespace of its own: test/CMakeLists.txt compiles several
// test files as one translation unit.
namespace bad_input_test {

namespace {

namespace ST = Soup_topology;
namespace fs = std::filesystem;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = std::array<std::size_t, 3>;

#if defined(__SANITIZE_ADDRESS__)
constexpr bool address_sanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool address_sanitizer = true;
#else
constexpr bool address_sanitizer = false;
#endif
#else
constexpr bool address_sanitizer = false;
#endif

std::string cli() { return SOUP_TOPOLOGY_CLI; }

std::string write_file(const std::string& folder, const std::string& name, const std::string& content)
{
  const std::string path = folder + "/" + name;
  std::ofstream out(path, std::ios::binary);
  out << content;
  return path;
}

std::string read_whole(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string binary_stl(std::uint32_t announced, std::size_t facets, float x = 0.f)
{
  std::string data(80, ' ');
  data.append(reinterpret_cast<const char*>(&announced), 4);
  for(std::size_t f = 0; f < facets; ++f) {
    const float c[12] = {0, 0, 1, x, 0, 0, 1, 0, 0, 0, 1, float(f)};
    data.append(reinterpret_cast<const char*>(c), sizeof c);
    data.append(2, '\0');
  }
  return data;
}

std::string ascii_facet(const std::string& third_vertex = "0 1 0", bool endloop = true, bool endfacet = true)
{
  return std::string("facet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex ") + third_vertex + "\n" +
         (endloop ? "endloop\n" : "") + (endfacet ? "endfacet\n" : "");
}

const std::string good_off = "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";

// Data the reader must not touch when it throws.
struct Sentinel
{
  std::vector<Point> points{Point(7, 7, 7), Point(8, 8, 8), Point(9, 9, 9)};
  std::vector<Triangle> triangles{{0, 1, 2}};
  bool untouched() const
  {
    return points == std::vector<Point>{Point(7, 7, 7), Point(8, 8, 8), Point(9, 9, 9)} &&
           triangles == std::vector<Triangle>{{0, 1, 2}};
  }
};

// The message of the exception `read_triangle_soup` throws on `content` written to `name`
// ("" if none); checks that the caller's containers are unchanged.
template <class Exception = std::exception>
std::string read_error(const std::string& name, const std::string& content)
{
  const std::string folder = soup_test::temporary_folder("bad_input_read");
  const std::string path = write_file(folder, name, content);
  Sentinel s;
  std::string message;
  try {
    ST::IO::read_triangle_soup(path, s.points, s.triangles);
  } catch(const Exception& e) {
    message = e.what();
  }
  EXPECT_TRUE(s.untouched()) << name;
  fs::remove_all(folder);
  return message;
}

#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE(std::string(text).find(part), std::string::npos) << "'" << (text) << "' does not contain '" << (part) << "'"

// ---------------------------------------------------------------------------------------------
// Readers

TEST(BadInputSTL, EmptyFile)
{
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("empty.stl", ""), "empty.stl: binary STL shorter than its 84-byte header (0 bytes)");
}

TEST(BadInputSTL, ZeroTrianglesIsNotAnError)
{
  const std::string folder = soup_test::temporary_folder("bad_input_zero");
  for(const std::string& content : {std::string("solid empty\nendsolid empty\n"), binary_stl(0, 0)}) {
    const std::string path = write_file(folder, "zero.stl", content);
    std::vector<Point> points;
    std::vector<Triangle> triangles;
    const ST::IO::Soup_read_report r = ST::IO::read_triangle_soup(path, points, triangles);
    EXPECT_EQ(r.input_triangles, 0u);
    EXPECT_TRUE(points.empty());
    EXPECT_TRUE(triangles.empty());
  }
  fs::remove_all(folder);
}

TEST(BadInputSTL, HeaderOnly)
{
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("header.stl", std::string(80, ' ')),
                  "binary STL shorter than its 84-byte header (80 bytes)");
}

TEST(BadInputSTL, CountLargerThanTheData)
{
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("more.stl", binary_stl(3, 2)),
                  "more.stl: binary STL header announces 3 facets, the file holds 2 complete facets (truncated at facet 2)");
}

TEST(BadInputSTL, CountSmallerThanTheData)
{
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("less.stl", binary_stl(1, 2)),
                  "less.stl: binary STL header announces 1 facets, the file holds 50 bytes more than that");
}

TEST(BadInputSTL, MissingEndloopAndEndfacet)
{
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("a.stl", "solid a\n" + ascii_facet("0 1 0", false) + "endsolid a\n"),
                  "a.stl:7: expected 'endloop', found 'endfacet'");
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("a.stl", "solid a\n" + ascii_facet("0 1 0", true, false) + "endsolid a\n"),
                  "a.stl:8: expected 'endfacet', found 'endsolid'");
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("a.stl", "solid a\n" + ascii_facet()),
                  "a.stl:9: unexpected end of file, expected 'endsolid'");
}

TEST(BadInputSTL, GarbageNumbers)
{
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("g.stl", "solid g\n" + ascii_facet("0 1.2.3 0") + "endsolid g\n"),
                  "g.stl:6: '1.2.3' is not a number");
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("g.stl", "solid g\n" + ascii_facet("0 1") + "endsolid g\n"),
                  "g.stl:7: 'endloop' is not a number");
}

TEST(BadInputSTL, NonFiniteCoordinates)
{
  EXPECT_CONTAINS(read_error<ST::Invalid_input>("n.stl", "solid n\n" + ascii_facet("0 nan 0") + "endsolid n\n"),
                  "n.stl: facet 0 has a non-finite coordinate");
  EXPECT_CONTAINS(read_error<ST::Invalid_input>("i.stl", "solid i\n" + ascii_facet() + ascii_facet("-inf 1 0") + "endsolid i\n"),
                  "i.stl: facet 1 has a non-finite coordinate");
  EXPECT_CONTAINS(read_error<ST::Invalid_input>("b.stl", binary_stl(2, 2, std::numeric_limits<float>::quiet_NaN())),
                  "b.stl: facet 0 has a non-finite coordinate");
}

TEST(BadInputSTL, FourBillionFacetsFailAtOnce)
{
  // The reader compares the count with the size before allocating anything.
  const std::string data = binary_stl(4000000000u, 1);
  std::vector<std::array<Point, 3>> triangles;
  const auto start = std::chrono::steady_clock::now();
  try {
    ST::IO::read_STL_triangles(data, triangles, "big.stl");
    ADD_FAILURE() << "no error";
  } catch(const ST::IO::Read_error& e) {
    EXPECT_CONTAINS(e.what(), "big.stl: binary STL header announces 4000000000 facets, the file holds 1 complete facets");
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
  EXPECT_TRUE(triangles.empty());
}

// The facets are decoded into the caller's vector, after what it held. A malformed file leaves
// the vector as it was, also when facets before the error were read (ASCII), and a good file
// appends its facets after the old ones, binary and ASCII alike.
TEST(BadInputSTL, FacetsAppendAndAMalformedFileLeavesTheVectorAsItWas)
{
  const std::array<Point, 3> held{{Point(7, 7, 7), Point(8, 8, 8), Point(9, 9, 9)}};
  const std::vector<std::array<Point, 3>> before{held, held};
  const std::string three_then_garbage =
    "solid g\n" + ascii_facet() + ascii_facet("1 0 0") + ascii_facet("0 0 1") + ascii_facet("0 1.2.3 0") + "endsolid g\n";
  for(const std::string& bad : {three_then_garbage, binary_stl(3, 2)}) {
    std::vector<std::array<Point, 3>> triangles = before;
    EXPECT_THROW(ST::IO::read_STL_triangles(bad, triangles, "bad.stl"), ST::IO::Read_error);
    EXPECT_EQ(triangles, before);
  }
  for(const std::string& good : {"solid g\n" + ascii_facet() + ascii_facet("1 0 0") + "endsolid g\n", binary_stl(2, 2)}) {
    std::vector<std::array<Point, 3>> alone, appended = before;
    const ST::IO::STL_read_result a = ST::IO::read_STL_triangles(good, alone, "good.stl");
    const ST::IO::STL_read_result b = ST::IO::read_STL_triangles(good, appended, "good.stl");
    ASSERT_EQ(alone.size(), 2u);
    EXPECT_EQ(a.triangles, 2u);
    EXPECT_EQ(b.triangles, 2u);
    EXPECT_EQ(a.binary, b.binary);
    ASSERT_EQ(appended.size(), 4u);
    EXPECT_EQ(appended[0], held);
    EXPECT_EQ(appended[1], held);
    EXPECT_EQ(appended[2], alone[0]);
    EXPECT_EQ(appended[3], alone[1]);
  }
}

TEST(BadInputOFF, EmptyFileAndMissingHeader)
{
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("e.off", ""), "e.off:1: empty file, expected the OFF header");
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("e.off", "# only a comment\n\n"), "e.off:1: empty file");
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("h.off", "PLY\n3 1 0\n"), "h.off:1: expected the keyword OFF");
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("b.off", "OFF BINARY\n"), "b.off:1: binary OFF is not supported");
}

TEST(BadInputOFF, ZeroFacesIsNotAnError)
{
  const std::string folder = soup_test::temporary_folder("bad_input_zero_off");
  const std::string path = write_file(folder, "zero.off", "OFF\n0 0 0\n");
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  EXPECT_EQ(ST::IO::read_triangle_soup(path, points, triangles).input_polygons, 0u);
  EXPECT_TRUE(triangles.empty());
  fs::remove_all(folder);
}

TEST(BadInputOFF, NegativeAndOutOfRangeIndices)
{
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("n.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n"),
                  "n.off:6: face 0 of 1 has a negative vertex index (-1)");
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("o.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 1 7\n"),
                  "o.off:7: face 1 of 2 has vertex index 7, out of range (3 vertices)");
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("o.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 99999999999999999999\n"),
                  "o.off:6: '99999999999999999999' is too large");
}

TEST(BadInputOFF, WrongCountLine)
{
  // More vertices announced than given: the face line is read as a vertex, then the faces are missing.
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("v.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
                  "v.off:6: unexpected end of file, expected number of corners of face 0 of 1");
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("f.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
                  "f.off:6: unexpected end of file, expected number of corners of face 1 of 2");
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("s.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 2 1 0\n"),
                  "s.off:7: data after the 1 faces the header announces ('3'): is the count line wrong?");
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("x.off", "OFF\n3 x 0\n"),
                  "x.off:2: 'x' is not an integer (number of faces in the count line)");
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("m.off", "OFF\n-3 1 0\n"),
                  "m.off:2: negative number of vertices (-3) in the count line");
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("c.off", "OFF\n"), "c.off:1: unexpected end of file, expected the count line");
}

TEST(BadInputOFF, GarbageAndNonFiniteNumbers)
{
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("g.off", "OFF\n3 1 0\n0 0 0\n1 x 0\n0 1 0\n3 0 1 2\n"),
                  "g.off:4: 'x' is not a number (vertex 1 of 3)");
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("n.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 nan 0\n3 0 1 2\n"),
                  "n.off:5: non-finite coordinate 'nan' (vertex 2 of 3)");
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("i.off", "OFF\n3 1 0\n0 0 0\n1e999 0 0\n0 1 0\n3 0 1 2\n"),
                  "i.off:4: non-finite coordinate '1e999' (vertex 1 of 3)");
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("w.off", "4OFF\n3 1 0\n0 0 0 1\n1 0 0 0\n0 1 0 1\n3 0 1 2\n"),
                  "w.off:4: homogeneous coordinate 0 (vertex 1 of 3)");
}

TEST(BadInputOFF, ShortFacesAndRepeatedIndicesAreCountedNotRead)
{
  // A face of fewer than 3 corners is skipped; a repeated index makes a collapsed triangle,
  // removed; both are counted in the report.
  const std::string folder = soup_test::temporary_folder("bad_input_faces");
  const std::string path = write_file(folder, "f.off", "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"
                                                       "2 0 1\n3 0 0 1\n3 0 1 2\n1 3\n");
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  const ST::IO::Soup_read_report r = ST::IO::read_triangle_soup(path, points, triangles);
  EXPECT_EQ(r.input_polygons, 4u);
  EXPECT_EQ(r.skipped_polygons, 2u);
  EXPECT_EQ(r.collapsed_triangles, 1u);
  EXPECT_EQ(triangles, (std::vector<Triangle>{{0, 1, 2}}));
  fs::remove_all(folder);
}

TEST(BadInputOFF, FourBillionVerticesFailAtOnce)
{
  // CGAL's reader resizes its vectors to the header's counts; ours checks them against the size.
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  const auto start = std::chrono::steady_clock::now();
  for(const std::string& text : {std::string("OFF\n4000000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
                                 std::string("OFF\n3 4000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
                                 std::string("OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n4000000000 0 1 2\n")}) {
    try {
      ST::IO::read_OFF_polygons(text, points, polygons, "big.off");
      ADD_FAILURE() << "no error";
    } catch(const ST::IO::Read_error& e) {
      EXPECT_TRUE(std::strstr(e.what(), "announces") != nullptr) << e.what();
    }
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
  EXPECT_TRUE(points.empty());
  EXPECT_TRUE(polygons.empty());
}

TEST(BadInputOFF, ReadsTheSharedFilesLikeCGAL)
{
  // Our OFF reader against CGAL's on every OFF file of the shared data (plain, NOFF, quads, comments).
  for(const char* file : {"cgal_repair/data_repair/nm_edges_triple.off", "cgal_repair/data_stitching/pinched.off",
                                 "cgal_repair/quads_to_stitch.off", "cgal_repair/data_stitching/deg_border.off",
                                 "cad/ALSTOM_TEST4.off", "clean/elephant.off"}) {
    const std::string path = soup_test::data_file(file);
    std::vector<Point> ours, theirs;
    std::vector<std::vector<std::size_t>> our_polygons, their_polygons;
    ST::IO::read_OFF_polygons(ST::IO::read_file_contents(path), ours, our_polygons, path);
    ASSERT_TRUE(CGAL::IO::read_OFF(path, theirs, their_polygons)) << file;
    EXPECT_EQ(ours, theirs) << file;
    EXPECT_EQ(our_polygons, their_polygons) << file;
  }
}

TEST(BadInputPLY, HeadersThatCGALsReaderMishandles)
{
  // Found by fuzz/fuzz_ply: undefined behaviour or unbounded allocation in CGAL 5.5's reader,
  // now refused by the header check of read_triangle_soup (internal/PLY_header.h).
  const std::string format = "ply\nformat ascii 1.0\n";
  const std::string data = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("p.ply", format + "property float x\nelement vertex 3\nend_header\n" + data),
                  "p.ply:3: PLY 'property' before any 'element'");
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("t.ply", format + "element vertex 3\nproperty float x\nproperty uchar y\n"
                                                          "property float z\nend_header\n" + data),
                  "t.ply:5: PLY vertex coordinate 'y' of type 'uchar' (expected float or double)");
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("d.ply", format + "element vertex 3\nproperty float x\nproperty float x\n"
                                                          "end_header\n" + data),
                  "d.ply:5: PLY element 'vertex' has two properties named 'x'");
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("n.ply", format + "element vertex 988888888888888\nend_header\n"),
                  "n.ply:3: PLY element 'vertex' announces 988888888888888 items with no property");
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("b.ply", format + "element vertex 4000000000\nproperty float x\n"
                                                          "property float y\nproperty float z\nend_header\n" + data),
                  "b.ply:3: PLY element 'vertex' announces 4000000000 items, more than the file of");
  EXPECT_CONTAINS(read_error<ST::IO::Read_error>("l.ply", format + "element vertex 3\nproperty float x\nproperty float y\n"
                                                          "property float z\nelement face 1\nproperty list int int vertex_indices\n"
                                                          "end_header\n" + data),
                  "l.ply:8: PLY list 'vertex_indices' with a count of type 'int' is not supported");
}

TEST(BadInputPLY, CommonFilesAreRead)
{
  const std::string folder = soup_test::temporary_folder("bad_input_ply");
  const std::string path = write_file(folder, "ok.ply", "ply\nformat ascii 1.0\ncomment fine\nelement vertex 3\n"
                                                        "property double x\nproperty double y\nproperty double z\n"
                                                        "element face 1\nproperty list uchar int vertex_indices\n"
                                                        "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  ST::IO::read_triangle_soup(path, points, triangles);
  EXPECT_EQ(points.size(), 3u);
  EXPECT_EQ(triangles.size(), 1u);
  fs::remove_all(folder);
}

// ---------------------------------------------------------------------------------------------
// The library: reconstruct_topology

struct Small_soup
{
  std::vector<Point> points{Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(0, 0, 1)};
  std::vector<Triangle> triangles{{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
};

template <class Points, class Triangles, class Np>
std::string pipeline_error(Points points, Triangles triangles, const Np& np)
{
  const Points points_before = points;
  const Triangles triangles_before = triangles;
  std::string message;
  try {
    ST::reconstruct_topology(points, triangles, np);
  } catch(const ST::Invalid_input& e) {
    message = e.what();
  }
  // Bit for bit (NaN included).
  EXPECT_EQ(points.size(), points_before.size());
  EXPECT_TRUE(std::memcmp(points.data(), points_before.data(), sizeof(Point) * points.size()) == 0);
  EXPECT_EQ(triangles, triangles_before);
  return message;
}

TEST(BadInputPipeline, IndicesOutOfRangeNegativeOrRepeated)
{
  const auto np = CGAL::parameters::snapping_tolerance(0.1);
  Small_soup s;
  s.triangles[2] = {0, 2, 4};
  EXPECT_CONTAINS(pipeline_error(s.points, s.triangles, np), "face 2: vertex index 4 is out of range (4 points)");
  s = Small_soup();
  s.triangles[1] = {3, 1, 3};
  EXPECT_CONTAINS(pipeline_error(s.points, s.triangles, np), "face 1 repeats a vertex index (3, 1, 3)");
  std::vector<std::array<int, 3>> signed_triangles{{0, 1, 2}, {0, -1, 3}};
  EXPECT_CONTAINS(pipeline_error(s.points, signed_triangles, np), "face 1: negative vertex index -1");
  std::vector<std::vector<std::size_t>> polygons{{0, 1, 2}, {0, 1}};
  EXPECT_CONTAINS(pipeline_error(s.points, polygons, np), "face 1 has 2 vertices; a triangle soup needs exactly 3");
}

TEST(BadInputPipeline, NonFiniteCoordinates)
{
  for(double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                    -std::numeric_limits<double>::infinity()}) {
    Small_soup s;
    s.points[3] = Point(0, bad, 1);
    EXPECT_CONTAINS(pipeline_error(s.points, s.triangles, CGAL::parameters::default_values()),
                    "point 3 has a non-finite coordinate");
  }
}

TEST(BadInputPipeline, InvalidTolerances)
{
  Small_soup s;
  for(double bad : {-1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
    EXPECT_CONTAINS(pipeline_error(s.points, s.triangles, CGAL::parameters::snapping_tolerance(bad)),
                    "the tolerance must be a finite number >= 0");
  for(double bad : {-1.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()})
    EXPECT_CONTAINS(pipeline_error(s.points, s.triangles, ST::parameters::relative_tolerance(bad)),
                    "the relative tolerance must be a finite number >= 0");
}

TEST(BadInputPipeline, HugeToleranceIsRefusedNotACrash)
{
  // Regression: a tolerance whose square overflows reached GMP's conversion of infinity in the
  // exact fallback of Compare_squared_distance_3 and the process died of SIGFPE.
  Small_soup s;
  EXPECT_CONTAINS(pipeline_error(s.points, s.triangles, CGAL::parameters::snapping_tolerance(1e300)),
                  "the tolerance is too large (1e+300): the square of twice its value overflows a double");
  // A bounding box too large for a double diagonal, with a relative tolerance.
  s.points[0] = Point(-1e308, 0, 0);
  s.points[1] = Point(1e308, 0, 0);
  EXPECT_CONTAINS(pipeline_error(s.points, s.triangles, ST::parameters::relative_tolerance(1e-6)),
                  "gives a non-finite absolute tolerance");
  // Points near 1e154 are scaled to the unit before the pipeline decides (coordinate_scale.h):
  // twice their diagonal, 2.4e154, is then a tolerance it accepts, as it does on a unit soup.
  s.points = {Point(0, 0, 0), Point(0.7e154, 0, 0), Point(0, 0.7e154, 0), Point(0, 0, 0.7e154)};
  {
    std::vector<Point> big = s.points;
    std::vector<Triangle> big_triangles = s.triangles;
    const double diagonal = ST::internal::bounding_box_diagonal(big, CGAL::Identity_property_map<Point>());
    EXPECT_EQ(ST::reconstruct_topology(big, big_triangles, ST::parameters::relative_tolerance(2.0)).tolerance,
              2 * diagonal);
  }
  // Regression (found by fuzz_pipeline): 1e154 squares to a finite 1e308, but split_t_junctions
  // compares with (2 * 1e154)^2, which overflowed into the same SIGFPE.
  s = Small_soup();
  EXPECT_CONTAINS(pipeline_error(s.points, s.triangles, CGAL::parameters::snapping_tolerance(1e154)),
                  "the tolerance is too large (1e+154)");
  std::vector<Point> near_limit = s.points;
  std::vector<Triangle> near_limit_triangles = s.triangles;
  EXPECT_NO_THROW(ST::reconstruct_topology(near_limit, near_limit_triangles, CGAL::parameters::snapping_tolerance(6e153)));
  // A relative tolerance of 0 is the exact weld, whatever the box.
  s.points[0] = Point(-1e308, 0, 0);
  std::vector<Point> points = s.points;
  std::vector<Triangle> triangles = s.triangles;
  EXPECT_EQ(ST::reconstruct_topology(points, triangles, ST::parameters::relative_tolerance(0.0)).output_triangles, 4u);
}

TEST(BadInputPipeline, ToleranceLargerThanTheModelKeepsItValid)
{
  // Not an error: every weld that would degenerate or flip a triangle is refused (and counted),
  // under Small_features::REFUSE (the default collapses a model smaller than the tolerance).
  // Two unit squares side by side with a gap of 0.01, tolerance 10 times the model.
  std::vector<Point> points{Point(0, 0, 0), Point(1, 0, 0), Point(1, 1, 0), Point(0, 1, 0),
                            Point(1.01, 0, 0), Point(2, 0, 0), Point(2, 1, 0), Point(1.01, 1, 0)};
  std::vector<Triangle> triangles{{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}};
  const std::vector<Point> input = points;
  const ST::Reconstruction_report r =
    ST::reconstruct_topology(points, triangles, ST::parameters::small_features(ST::Small_features::REFUSE,
                                                                               CGAL::parameters::snapping_tolerance(30.0)));
  EXPECT_GT(r.refused_welds(), 0u);
  EXPECT_LE(r.max_displacement, 30.0);
  for(const Triangle& t : triangles) EXPECT_FALSE(CGAL::collinear(points[t[0]], points[t[1]], points[t[2]]));
  EXPECT_EQ(triangles.size(), 4u);
}

// Found by fuzz_pipeline (fuzz/corpus/pipeline/chained_welds.bin): a representative that
// receives points in one round must not be welded again in a later round, or its points would
// move 1.46 with a tolerance of 1.
TEST(BadInputPipeline, NoPointMovesFartherThanTheToleranceOverRounds)
{
  std::vector<Point> points{
    Point(-0.25, 0.749, 0.999), Point(0, -1, -1), Point(-1, -1, -1), Point(-1, -1, -1),
    Point(0.249, -0.99999999900000003, -0.94999999999999996), Point(0.749, 0.80000000000000004, 0.80000000000000004),
    Point(0.249, 1.05, -2.4999999999999999e-17), Point(0.050000000000000003, 0.50000000099999997, -0.45000000000000001),
    Point(-0.249999999, -0.20000000000000001, 0.001), Point(0, -1, 0.24999999999999997),
    Point(-0.75, -0.99999999900000003, -0.94999999999999996), Point(0.749, 0.80000000000000004, 0.80000000000000004)};
  std::vector<Triangle> triangles{{11, 8, 1}, {4, 9, 2}, {6, 3, 1}, {4, 0, 2}, {1, 2, 3}, {11, 10, 1}, {9, 11, 0}, {0, 7, 4}};
  const ST::Reconstruction_report r =
    ST::reconstruct_topology(points, triangles, CGAL::parameters::snapping_tolerance(1.0));
  EXPECT_LE(r.max_displacement, 1.0) << r.rounds << " rounds";
}

TEST(BadInputPipeline, EmptySoupIsANoOp)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  const ST::Reconstruction_report r =
    ST::reconstruct_topology(points, triangles, CGAL::parameters::snapping_tolerance(0.5));
  EXPECT_EQ(r.output_triangles, 0u);
  EXPECT_EQ(r.output_points, 0u);
}

TEST(BadInputTables, RepeatedAndOutOfRangeIndices)
{
  std::vector<Triangle> triangles{{0, 1, 2}, {2, 1, 2}};
  EXPECT_THROW(ST::Adjacency_tables(triangles, 3), ST::Invalid_input);
  triangles[1] = {0, 1, 3};
  EXPECT_THROW(ST::Adjacency_tables(triangles, 3), ST::Invalid_input);
}

// ---------------------------------------------------------------------------------------------
// The command-line tool

struct Cli_result
{
  std::string output;
  int code;
};

Cli_result run_cli(const std::string& arguments)
{
  const auto r = soup_test::run_command("'" + cli() + "' " + arguments + " 2>&1");
  return {r.first, r.second};
}

class BadInputCli : public ::testing::Test
{
protected:
  void SetUp() override
  {
    if(cli().empty()) GTEST_SKIP() << "the command-line tool is not built";
    folder = soup_test::temporary_folder("bad_input_cli");
    output = write_file(folder, "out.off", "previous content\n");
  }
  void TearDown() override
  {
    if(!folder.empty()) fs::remove_all(folder);
  }
  // repair on `content` written to `name` fails with exit code 2, a message containing `part`,
  // and leaves the existing output file and the folder as they were.
  void expect_refused(const std::string& name, const std::string& content, const std::string& part,
                      const std::string& options = "")
  {
    const std::string input = write_file(folder, name, content);
    const Cli_result r = run_cli("repair '" + input + "' -o '" + output + "' " + options);
    EXPECT_EQ(r.code, 2) << r.output;
    EXPECT_CONTAINS(r.output, part);
    EXPECT_EQ(read_whole(output), "previous content\n") << name;
    EXPECT_EQ(read_whole(input), content) << name;
    std::size_t files = 0;
    for(const auto& entry : fs::directory_iterator(folder)) { (void)entry; ++files; }
    EXPECT_EQ(files, 2u) << "a temporary file was left behind";
    fs::remove(input);
  }
  std::string folder, output;
};

TEST_F(BadInputCli, BrokenFiles)
{
  expect_refused("empty.stl", "", "empty.stl: binary STL shorter than its 84-byte header (0 bytes)");
  expect_refused("empty.off", "", "empty.off:1: empty file, expected the OFF header");
  expect_refused("header.stl", std::string(80, ' '), "header.stl: binary STL shorter than its 84-byte header");
  expect_refused("more.stl", binary_stl(3, 2), "more.stl: binary STL header announces 3 facets");
  expect_refused("less.stl", binary_stl(1, 2), "less.stl: binary STL header announces 1 facets, the file holds 50 bytes more");
  expect_refused("loop.stl", "solid a\n" + ascii_facet("0 1 0", false) + "endsolid a\n", "loop.stl:7: expected 'endloop'");
  expect_refused("facet.stl", "solid a\n" + ascii_facet("0 1 0", true, false) + "endsolid a\n",
                 "facet.stl:8: expected 'endfacet'");
  expect_refused("garbage.stl", "solid g\n" + ascii_facet("0 1.2.3 0") + "endsolid g\n", "garbage.stl:6: '1.2.3' is not a number");
  expect_refused("nan.stl", "solid n\n" + ascii_facet("0 nan 0") + "endsolid n\n",
                 "invalid input: " + folder + "/nan.stl: facet 0 has a non-finite coordinate");
  expect_refused("inf.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 inf 0\n3 0 1 2\n", "inf.off:5: non-finite coordinate 'inf'");
  expect_refused("neg.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", "neg.off:6: face 0 of 1 has a negative vertex index (-1)");
  expect_refused("range.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", "range.off:6: face 0 of 1 has vertex index 3, out of range");
  expect_refused("count.off", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", "count.off:6: unexpected end of file, expected number of corners of face 1 of 2");
  expect_refused("extra.off", good_off + "3 2 1 0\n", "extra.off:7: data after the 1 faces the header announces");
  expect_refused("unknown.xyz", "1 2 3\n", "unknown file extension 'xyz'");
}

TEST_F(BadInputCli, MissingInput)
{
  const Cli_result r = run_cli("repair '" + folder + "/missing.stl' -o '" + output + "'");
  EXPECT_EQ(r.code, 2);
  EXPECT_CONTAINS(r.output, "missing.stl: cannot open the file for reading");
  EXPECT_EQ(read_whole(output), "previous content\n");
}

TEST_F(BadInputCli, InvalidTolerances)
{
  for(const char* t : {"-1", "nan", "inf", "-inf"})
    expect_refused("t.off", good_off, "the tolerance must be a finite number >= 0, got '" + std::string(t) + "'",
                   "--tolerance '" + std::string(t) + "'");
  for(const char* t : {"1e999", "abc", "", "0.1x"})
    expect_refused("t.off", good_off, "--tolerance: '" + std::string(t) + "' is not a number",
                   "--tolerance '" + std::string(t) + "'");
  expect_refused("t.off", good_off, "the tolerance is too large (1e+300)", "--tolerance 1e300");
  expect_refused("t.off", good_off, "--relative-tolerance: the tolerance must be a finite number >= 0",
                 "--relative-tolerance -0.5");
  expect_refused("t.off", good_off, "give --tolerance or --relative-tolerance, not both",
                 "--tolerance 1 --relative-tolerance 0.1");
}

TEST_F(BadInputCli, ToleranceLargerThanTheModelIsRefusedWeldByWeld)
{
  const std::string input = soup_test::data_file("cgal_repair/data_stitching/pinched.off");
  const Cli_result r =
    run_cli("repair '" + input + "' -o '" + output + "' --tolerance 100 --small-features refuse --json");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_GT(soup_test::json_integer(r.output, "refused_welds"), 0);
  EXPECT_EQ(soup_test::json_integer(r.output, "output_triangles"), 102);
  EXPECT_EQ(soup_test::json_integer(r.output, "max_displacement"), 0);
}

TEST_F(BadInputCli, UnwritableOutput)
{
  const std::string input = write_file(folder, "in.off", good_off);
  // A folder that does not exist.
  Cli_result r = run_cli("repair '" + input + "' -o '" + folder + "/missing/out.off'");
  EXPECT_EQ(r.code, 2);
  EXPECT_CONTAINS(r.output, folder + "/missing/out.off: the output folder does not exist");
  // A "folder" that is a regular file (root ignores permissions, not this).
  r = run_cli("repair '" + input + "' -o '" + output + "/out.off'");
  EXPECT_EQ(r.code, 2);
  EXPECT_CONTAINS(r.output, output + "/out.off: the output folder does not exist");
  EXPECT_EQ(read_whole(output), "previous content\n");
  // A report that cannot be written: refused before anything is written.
  r = run_cli("repair '" + input + "' -o '" + folder + "/new.off' --report '" + output + "/r.json'");
  EXPECT_EQ(r.code, 2);
  EXPECT_CONTAINS(r.output, "the folder of the report file does not exist");
  EXPECT_EQ(read_whole(output), "previous content\n");
  EXPECT_FALSE(std::filesystem::exists(folder + "/new.off"));
}

TEST_F(BadInputCli, OutputIsTheInput)
{
  const std::string input = write_file(folder, "same.off", good_off);
  for(const std::string& out : {input, folder + "/./same.off"}) {
    const Cli_result r = run_cli("repair '" + input + "' -o '" + out + "'");
    EXPECT_EQ(r.code, 2);
    EXPECT_CONTAINS(r.output, "the output file is the input file");
    EXPECT_EQ(read_whole(input), good_off);
  }
}

TEST_F(BadInputCli, HugeCountsFailFastUnderAMemoryLimit)
{
  // 4 billion facets or vertices announced in a tiny file: refused before any allocation, so a
  // limit of 1 GB of address space is enough (not under AddressSanitizer, which reserves more).
  const std::string stl = write_file(folder, "big.stl", binary_stl(4000000000u, 1));
  const std::string off = write_file(folder, "big.off", "OFF\n4000000000 4000000000 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  const std::string limit = address_sanitizer ? "" : "ulimit -v 1000000; ";
  for(const std::string& file : {stl, off}) {
    const auto start = std::chrono::steady_clock::now();
    const auto r = soup_test::run_command(limit + "'" + cli() + "' stats '" + file + "' 2>&1");
    EXPECT_EQ(r.second, 2) << r.first;
    EXPECT_CONTAINS(r.first, "4000000000");
    EXPECT_CONTAINS(r.first, "announces");
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
  }
}

// ---------------------------------------------------------------------------------------------
// Issue 21: the tool never loses a file, writes what it reports, and refuses what it cannot write.

// Every regular file of a folder: name -> (content, permission bits).
std::map<std::string, std::pair<std::string, unsigned>> folder_snapshot(const std::string& folder)
{
  std::map<std::string, std::pair<std::string, unsigned>> files;
  for(const auto& entry : fs::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    if(entry.is_symlink()) files[name] = {"-> " + fs::read_symlink(entry.path()).string(), 0};
    else if(entry.is_directory()) files[name] = {"<dir>", 0};
    else if(!entry.is_regular_file()) files[name] = {"<not a regular file>", 0}; // reading a fifo blocks
    else files[name] = {read_whole(entry.path().string()), static_cast<unsigned>(fs::status(entry.path()).permissions())};
  }
  return files;
}

unsigned file_mode(const std::string& path)
{
  struct stat s;
  return ::stat(path.c_str(), &s) == 0 ? static_cast<unsigned>(s.st_mode & 07777) : 0u;
}

std::vector<std::string> temporaries_in(const std::string& folder)
{
  std::vector<std::string> names;
  for(const auto& entry : fs::directory_iterator(folder))
    if(entry.path().filename().string().rfind(".soup_topology.", 0) == 0) names.push_back(entry.path().string());
  return names;
}

// Two interpenetrating tetrahedra as OFF: closed, manifold, self-intersecting.
const std::string crossing_tetrahedra =
  "OFF\n8 8 0\n0 0 0\n2 0 0\n0 2 0\n0 0 2\n0.5 0.5 0.5\n2.5 0.5 0.5\n0.5 2.5 0.5\n0.5 0.5 2.5\n"
  "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n3 4 6 5\n3 4 5 7\n3 4 7 6\n3 5 6 7\n";
const std::string tetrahedron = "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";

class HostileInput : public ::testing::Test
{
protected:
  void SetUp() override
  {
    if(cli().empty()) GTEST_SKIP() << "the command-line tool is not built";
    folder = soup_test::temporary_folder("hostile_cli");
    input = write_file(folder, "in.off", tetrahedron);
    output = write_file(folder, "out.off", "previous content\n");
  }
  void TearDown() override
  {
    if(!folder.empty()) fs::remove_all(folder);
  }
  soup_test::Bounded_run run(std::vector<std::string> args)
  {
    args.insert(args.begin(), cli());
    return soup_test::run_bounded(args, 60, 4096);
  }
  // Runs the tool and checks that it fails with exit code 2 and `message`, and that no file of
  // the folder changed (none created, none removed).
  void expect_refused_unchanged(const std::vector<std::string>& args, const std::string& message)
  {
    const auto before = folder_snapshot(folder);
    const soup_test::Bounded_run r = run(args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_CONTAINS(r.err, message);
    EXPECT_TRUE(folder_snapshot(folder) == before) << "a file of the folder changed: " << r.err;
  }
  std::string folder, input, output;
};

TEST_F(HostileInput, Issue21ReportOntoInput)
{
  fs::create_hard_link(input, folder + "/hard.off");
  fs::create_symlink(input, folder + "/soft.json");
  for(const std::string& report : {input, folder + "/./in.off", folder + "/hard.off", folder + "/soft.json"})
    expect_refused_unchanged({"repair", input, "-o", output, "--report", report}, "the report file is the input file");
}

TEST_F(HostileInput, Issue21ReportOntoOutput)
{
  fs::create_symlink(output, folder + "/soft.json");
  for(const std::string& report : {output, folder + "/./out.off", folder + "/soft.json"})
    expect_refused_unchanged({"repair", input, "-o", output, "--report", report}, "the report file is the output file");
  // The same new file given twice: neither exists yet.
  expect_refused_unchanged({"repair", input, "-o", folder + "/new.off", "--report", folder + "/sub/../new.off"},
                           "the report file is the output file");
  fs::create_directory(folder + "/sub");
  expect_refused_unchanged({"repair", input, "-o", folder + "/new.off", "--report", folder + "/sub/../new.off"},
                           "the report file is the output file");
}

TEST_F(HostileInput, OutputOntoInputThroughLinks)
{
  fs::create_hard_link(input, folder + "/hard.off");
  fs::create_symlink(input, folder + "/soft.off");
  for(const std::string& out : {folder + "/hard.off", folder + "/soft.off"})
    expect_refused_unchanged({"repair", input, "-o", out}, "the output file is the input file");
}

TEST_F(HostileInput, Issue21UnwritableReportLeavesOutputUntouched)
{
  // The report is a directory: refused before the output is written.
  fs::create_directory(folder + "/report.json");
  expect_refused_unchanged({"repair", input, "-o", output, "--report", folder + "/report.json"},
                           "report.json: is a directory");
  // Not a regular file: a rename would replace it (a device such as /dev/null, never used here:
  // a tool without the check would replace the system's device node).
  const std::string fifo = folder + "/fifo.off";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  expect_refused_unchanged({"repair", input, "-o", output, "--report", fifo}, "fifo.off: is not a regular file");
  expect_refused_unchanged({"repair", input, "-o", fifo}, "fifo.off: is not a regular file");
  EXPECT_TRUE(fs::is_fifo(fifo));
}

TEST_F(HostileInput, Issue21OutputCheckedBeforeReading)
{
  // An input that fails only when read: the output problem must be the one reported.
  const std::string broken = write_file(folder, "broken.stl", "");
  fs::create_directory(folder + "/out_dir.off");
  expect_refused_unchanged({"repair", broken, "-o", folder + "/out_dir.off"}, "out_dir.off: is a directory");
  expect_refused_unchanged({"repair", broken, "-o", folder + "/missing/out.off"}, "the output folder does not exist");
  expect_refused_unchanged({"repair", broken, "-o", output, "--report", folder + "/missing/r.json"},
                           "the folder of the report file does not exist");
}

TEST_F(HostileInput, Issue21PermissionsKept)
{
  const std::string report = write_file(folder, "r.json", "{}\n");
  fs::permissions(output, fs::perms::owner_read | fs::perms::owner_write);
  fs::permissions(report, fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  soup_test::Bounded_run r = run({"repair", input, "-o", output, "--report", report});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(file_mode(output), 0600u);
  EXPECT_EQ(file_mode(report), 0640u);
  EXPECT_NE(read_whole(output), "previous content\n");
  // A new file gets the mode of the umask, as any program's new file.
  const mode_t mask = umask(0);
  umask(mask);
  r = run({"repair", input, "-o", folder + "/new.ply", "--report", folder + "/new.json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(file_mode(folder + "/new.ply"), 0666u & ~static_cast<unsigned>(mask));
  EXPECT_EQ(file_mode(folder + "/new.json"), 0666u & ~static_cast<unsigned>(mask));
  EXPECT_TRUE(temporaries_in(folder).empty());
}

TEST_F(HostileInput, Issue21FailedStandardOutputIsAnError)
{
  for(const std::string& options : {std::string("--json"), std::string("")}) {
    const auto r = soup_test::run_command("'" + cli() + "' repair '" + input + "' -o '" + output + "' " + options +
                                          " 2>&1 > /dev/full");
    EXPECT_EQ(r.second, 2) << r.first;
    EXPECT_CONTAINS(r.first, "cannot write to standard output");
  }
  const auto r = soup_test::run_command("'" + cli() + "' stats '" + input + "' --json 2>&1 > /dev/full");
  EXPECT_EQ(r.second, 2) << r.first;
  EXPECT_CONTAINS(r.first, "cannot write to standard output");
}

// `repair --tiles N` on the real files and on hostile ones (in the sanitizer build too): a real
// mesh gives the triangles of the repair in memory; a streamed STL with a corner that is not a
// number, an empty one and one triangle are handled; bad counts of tiles and a relative tolerance
// are refused, leaving OUT as it was.
TEST_F(HostileInput, TiledRepair)
{
  const std::string pig = soup_test::data_file("cgal_repair/pig.stl.xz");
  const soup_test::Bounded_run whole = run({"repair", pig, "-o", output, "--tolerance", "0.3", "--json"});
  ASSERT_EQ(whole.exit_code, 0) << whole.err;
  for(const std::string tiles : {"1", "3", "16"}) {
    const soup_test::Bounded_run r = run({"repair", pig, "-o", output, "--tolerance", "0.3", "--json", "--tiles", tiles});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(soup_test::json_integer(r.out, "tiles"), std::stoll(tiles));
    for(const char* key : {"output_triangles", "output_vertices", "border_edges", "components"})
      EXPECT_EQ(soup_test::json_integer(r.out, key), soup_test::json_integer(whole.out, key)) << key << ", " << tiles << " tiles";
  }
  std::string nan(80, '\0');
  const std::uint32_t one = 1;
  nan.append(reinterpret_cast<const char*>(&one), 4);
  float facet[12] = {0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0};
  facet[6] = std::numeric_limits<float>::quiet_NaN();
  nan.append(reinterpret_cast<const char*>(facet), sizeof facet);
  nan.append(2, '\0');
  expect_refused_unchanged({"repair", write_file(folder, "nan.stl", nan), "-o", output, "--tolerance", "0.1", "--tiles", "2"},
                           "triangle 0 has a corner that is not finite");
  std::string empty(80, '\0');
  empty.append(4, '\0');
  soup_test::Bounded_run r = run({"repair", write_file(folder, "empty.stl", empty), "-o", output, "--tolerance", "0.1",
                                  "--tiles", "2", "--json"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(soup_test::json_integer(r.out, "output_triangles"), 0);
  facet[6] = 1;
  std::string single = nan.substr(0, 84);
  single.append(reinterpret_cast<const char*>(facet), sizeof facet);
  single.append(2, '\0');
  r = run({"repair", write_file(folder, "one.stl", single), "-o", output, "--tolerance", "0.1", "--tiles", "4", "--json"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(soup_test::json_integer(r.out, "output_triangles"), 1);
  expect_refused_unchanged({"repair", input, "-o", output, "--tolerance", "0.1", "--tiles", "0"}, "--tiles takes a number");
  expect_refused_unchanged({"repair", input, "-o", output, "--tolerance", "0.1", "--tiles", "5000"}, "--tiles takes a number");
  expect_refused_unchanged({"repair", input, "-o", output, "--relative-tolerance", "0.1", "--tiles", "2"},
                           "--tiles needs an absolute --tolerance");
  EXPECT_TRUE(temporaries_in(folder).empty());
}

TEST_F(HostileInput, Issue21SubnormalTolerance)
{
  const soup_test::Bounded_run r = run({"repair", input, "-o", output, "--tolerance", "1e-320", "--json"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_CONTAINS(r.out, "\"tolerance\": 1e-320");
}

TEST_F(HostileInput, Issue21StlRoundingIsRefused)
{
  const std::string stl = write_file(folder, "out.stl", "previous content\n");
  const std::string huge = write_file(folder, "huge.off", "OFF\n3 1 0\n0 0 0\n1e308 0 0\n0 1 0\n3 0 1 2\n");
  expect_refused_unchanged({"repair", huge, "-o", stl}, "point 1 (1e+308, 0, 0) becomes infinite in float");
  expect_refused_unchanged({"repair", huge, "-o", stl}, "write .off, .obj or .ply");
  // 0.1 apart near 5e6: the float spacing there is 0.5.
  const std::string near = write_file(folder, "near.off", "OFF\n4 2 0\n5000000 0 0\n5000000.1 0 0\n5000000.1 1 0\n"
                                                          "5000000 0 1\n3 0 1 2\n3 0 2 3\n");
  expect_refused_unchanged({"repair", near, "-o", stl}, "points 0 and 1");
  expect_refused_unchanged({"repair", near, "-o", stl}, "become the same point in float");
  // A thin triangle whose apex rounds onto its base.
  const std::string thin = write_file(folder, "thin.off", "OFF\n3 1 0\n0 5000000 0\n1 5000000 0\n0.5 5000000.1 0\n3 0 1 2\n");
  expect_refused_unchanged({"repair", thin, "-o", stl}, "triangle 0 (points 0, 1, 2) becomes degenerate in float");
  // The same files as OFF keep their doubles.
  for(const std::string& in : {huge, near, thin}) {
    const soup_test::Bounded_run r = run({"repair", in, "-o", output});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    std::vector<Point> original, written;
    std::vector<std::vector<std::size_t>> original_faces, written_faces;
    ST::IO::read_OFF_polygons(read_whole(in), original, original_faces, in);
    ST::IO::read_OFF_polygons(read_whole(output), written, written_faces, output);
    EXPECT_EQ(original, written) << in;
  }
}

TEST_F(HostileInput, Issue21ReportDescribesTheWrittenFile)
{
  // nm_cubes: the repaired soup is closed with 2 non-manifold edges; the file written separates
  // them by duplicating points, and has border edges and two components.
  struct Expected
  {
    const char* file;
    long long border_edges, components, soup_non_manifold_edges;
  };
  for(const Expected& e : {Expected{"nm_cubes.off", 8, 2, 2}, Expected{"non_manifold.off", 4, 1, 1},
                           Expected{"non_manifold2.off", 4, 1, 1}}) {
    SCOPED_TRACE(e.file);
    const std::string in = soup_test::data_file(std::string("cgal_repair/data_stitching/") + e.file);
    const soup_test::Bounded_run r = run({"repair", in, "-o", output, "--json", "--check"});
    EXPECT_EQ(r.exit_code, 1) << r.err;
    EXPECT_FALSE(soup_test::json_bool(r.out, "closed"));
    EXPECT_EQ(soup_test::json_integer(r.out, "border_edges"), e.border_edges);
    EXPECT_EQ(soup_test::json_integer(r.out, "components"), e.components);
    EXPECT_EQ(soup_test::json_integer(r.out, "non_manifold_edges"), 0);
    EXPECT_EQ(soup_test::json_integer(r.out, "soup_non_manifold_edges"), e.soup_non_manifold_edges);
    EXPECT_TRUE(soup_test::json_bool(r.out, "soup_closed"));
    // The file as written, read without welding: the same counts.
    std::vector<Point> points;
    std::vector<std::vector<std::size_t>> faces;
    ST::IO::read_OFF_polygons(read_whole(output), points, faces, output);
    std::vector<Triangle> triangles;
    for(const auto& f : faces) triangles.push_back({f[0], f[1], f[2]});
    EXPECT_EQ(static_cast<long long>(soup_test::count_border_and_non_manifold_edges(triangles).first), e.border_edges);
    EXPECT_EQ(soup_test::json_integer(r.out, "output_vertices"), static_cast<long long>(points.size()));
    EXPECT_EQ(soup_test::json_integer(r.out, "vertices"), static_cast<long long>(points.size()));
  }
}

TEST_F(HostileInput, Issue21SelfIntersections)
{
  const std::string crossing = write_file(folder, "crossing.off", crossing_tetrahedra);
  soup_test::Bounded_run r = run({"repair", crossing, "-o", output, "--json", "--check"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(soup_test::json_integer(r.out, "self_intersecting_pairs"), -1) << "counted without the option";
  r = run({"repair", crossing, "-o", output, "--json", "--check", "--self-intersections"});
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_GT(soup_test::json_integer(r.out, "self_intersecting_pairs"), 0);
  EXPECT_TRUE(soup_test::json_bool(r.out, "closed"));
  r = run({"repair", input, "-o", output, "--json", "--check", "--self-intersections"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(soup_test::json_integer(r.out, "self_intersecting_pairs"), 0);
}

// A binary STL grid of about 1M triangles: long enough to read, repair and write that a signal
// can be sent while the output is being written.
std::string million_triangle_stl(const std::string& folder)
{
  const int n = 710;
  std::string data(80, ' ');
  const std::uint32_t count = static_cast<std::uint32_t>(2 * (n - 1) * (n - 1));
  data.append(reinterpret_cast<const char*>(&count), 4);
  data.reserve(84 + 50 * std::size_t(count));
  auto z = [](int i, int j) { return static_cast<float>((i * j) % 7) * 0.25f; };
  for(int i = 0; i + 1 < n; ++i)
    for(int j = 0; j + 1 < n; ++j) {
      const float a[3] = {float(i), float(j), z(i, j)}, b[3] = {float(i + 1), float(j), z(i + 1, j)};
      const float c[3] = {float(i + 1), float(j + 1), z(i + 1, j + 1)}, d[3] = {float(i), float(j + 1), z(i, j + 1)};
      const float* corners[2][3] = {{a, b, c}, {a, c, d}};
      for(const auto& t : corners) {
        const float normal[3] = {0, 0, 0};
        data.append(reinterpret_cast<const char*>(normal), sizeof normal);
        for(const float* p : t) data.append(reinterpret_cast<const char*>(p), 3 * sizeof(float));
        data.append(2, '\0');
      }
    }
  return write_file(folder, "grid.stl", data);
}

TEST_F(HostileInput, Issue21SignalsLeaveNoTemporaryFile)
{
  const std::string grid = million_triangle_stl(folder);
  fs::permissions(output, fs::perms::owner_read | fs::perms::owner_write);
  const std::string report = folder + "/r.json";
  for(int signal_number : {SIGTERM, SIGINT, SIGHUP}) {
    SCOPED_TRACE(signal_number);
    const auto before = folder_snapshot(folder);
    const pid_t pid = fork();
    ASSERT_GE(pid, 0);
    if(pid == 0) {
      const int null = ::open("/dev/null", O_WRONLY);
      dup2(null, 1);
      dup2(null, 2);
      const std::string program = cli();
      execl(program.c_str(), program.c_str(), "repair", grid.c_str(), "-o", output.c_str(), "--report", report.c_str(),
            static_cast<char*>(nullptr));
      _exit(127);
    }
    // Wait for the temporary output file to appear, then send the signal while it is written.
    std::vector<std::string> seen;
    const auto start = std::chrono::steady_clock::now();
    int status = 0;
    bool exited = false;
    while(seen.empty() && std::chrono::steady_clock::now() - start < std::chrono::seconds(300)) {
      seen = temporaries_in(folder);
      if(!seen.empty()) break;
      if(waitpid(pid, &status, WNOHANG) == pid) { exited = true; break; }
      std::this_thread::sleep_for(std::chrono::microseconds(500));
    }
    ASSERT_FALSE(exited) << "the tool finished before its temporary file was seen";
    ASSERT_FALSE(seen.empty()) << "no temporary file appeared";
    // Private while written.
    const unsigned mode = file_mode(seen.front());
    kill(pid, signal_number);
    waitpid(pid, &status, 0);
    EXPECT_EQ(mode & 077u, 0u) << "the temporary file is readable by others: " << std::oct << mode;
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal_number) << "status " << status;
    EXPECT_TRUE(temporaries_in(folder).empty()) << "a temporary file was left behind";
    EXPECT_TRUE(folder_snapshot(folder) == before) << "a file of the folder changed";
  }
}

// ---------------------------------------------------------------------------------------------
// Issue 21: IO::write_triangle_soup

std::vector<std::array<std::size_t, 3>> rotated_sorted(std::vector<std::array<std::size_t, 3>> triangles)
{
  for(auto& t : triangles) std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  std::sort(triangles.begin(), triangles.end());
  return triangles;
}

std::vector<Triangle> as_triangles(const std::vector<std::vector<std::size_t>>& faces)
{
  std::vector<Triangle> triangles;
  for(const auto& f : faces) {
    EXPECT_EQ(f.size(), 3u);
    if(f.size() == 3) triangles.push_back({f[0], f[1], f[2]});
  }
  return triangles;
}

TEST(WriteTriangleSoup, Issue21ReadsBackTheSamePointsAndTriangles)
{
  // Doubles with all 53 bits used, of every magnitude: the text formats must keep them all.
  std::mt19937_64 random(21);
  std::uniform_real_distribution<double> mantissa(-1, 1);
  std::uniform_int_distribution<int> exponent(-300, 300);
  std::vector<Point> points;
  for(int i = 0; i < 300; ++i)
    points.emplace_back(std::ldexp(mantissa(random), exponent(random)), mantissa(random) * 1e6, std::ldexp(mantissa(random), -1070 + i % 3));
  std::vector<Triangle> triangles;
  for(std::size_t i = 0; i + 2 < points.size(); i += 2) triangles.push_back({i, i + 2, i + 1});
  const std::string folder = soup_test::temporary_folder("write_soup");
  for(const std::string name : {"a.off", "a.OBJ", "a.ply", "ascii.ply"}) {
    SCOPED_TRACE(name);
    const std::string path = folder + "/" + name;
    if(name == "ascii.ply") ST::IO::write_triangle_soup(path, points, triangles, CGAL::parameters::use_binary_mode(false));
    else ST::IO::write_triangle_soup(path, points, triangles);
    std::vector<Point> read_points;
    std::vector<std::vector<std::size_t>> faces;
    if(name == "a.off") ST::IO::read_OFF_polygons(read_whole(path), read_points, faces, path);
    else {
      const std::string copy = folder + "/copy." + (name == "a.OBJ" ? "obj" : "ply");
      fs::copy_file(path, copy, fs::copy_options::overwrite_existing);
      ASSERT_TRUE(CGAL::IO::read_polygon_soup(copy, read_points, faces));
    }
    EXPECT_TRUE(read_points == points);
    EXPECT_TRUE(as_triangles(faces) == triangles);
  }
  // STL: float coordinates come back exactly, corner by corner.
  std::vector<Point> float_points;
  for(const Point& p : points)
    float_points.emplace_back(static_cast<float>(p.x() / 1e300), static_cast<float>(p.y()), static_cast<float>(p.z() * 1e300));
  ST::IO::write_triangle_soup(folder + "/a.stl", float_points, triangles);
  std::vector<std::array<Point, 3>> corners;
  ST::IO::read_STL_triangles(read_whole(folder + "/a.stl"), corners, "a.stl");
  ASSERT_EQ(corners.size(), triangles.size());
  for(std::size_t t = 0; t < triangles.size(); ++t)
    for(int k = 0; k < 3; ++k) EXPECT_EQ(corners[t][k], float_points[triangles[t][k]]);
  // Errors name the file.
  try {
    ST::IO::write_triangle_soup(folder + "/missing/a.off", points, triangles);
    ADD_FAILURE() << "no error";
  } catch(const ST::IO::Write_error& e) {
    EXPECT_CONTAINS(e.what(), folder + "/missing/a.off: cannot open the file for writing");
  }
  try {
    ST::IO::write_triangle_soup(folder + "/b.stl", points, triangles);
    ADD_FAILURE() << "no error";
  } catch(const ST::IO::Write_error& e) {
    EXPECT_CONTAINS(e.what(), folder + "/b.stl: point ");
    EXPECT_CONTAINS(e.what(), "becomes infinite in float");
  }
  EXPECT_FALSE(fs::exists(folder + "/b.stl"));
  fs::remove_all(folder);
}

TEST(WriteTriangleSoup, Issue21SameMeshAsTheFaceGraphWriter)
{
  // The tool used to write through a Surface_mesh and CGAL's writer; the soup written directly
  // must be the same mesh: the same points in the same order, the same oriented triangles.
  struct Case
  {
    const char* file;
    double tolerance;
  };
  for(const Case& c : {Case{"cgal_repair/pig.stl.xz", 0.3}, Case{"cad/ALSTOM_TEST4.off", 0.0},
                       Case{"cgal_repair/data_stitching/nm_cubes.off", 0.0}}) {
    SCOPED_TRACE(c.file);
    std::vector<Point> points;
    std::vector<Triangle> triangles;
    soup_test::read_data_mesh(c.file, points, triangles);
    ST::reconstruct_topology(points, triangles, CGAL::parameters::snapping_tolerance(c.tolerance));
    CGAL::Surface_mesh<Point> mesh;
    ST::triangle_soup_to_face_graph(points, triangles, mesh);
    std::ostringstream theirs;
    ASSERT_TRUE(CGAL::IO::write_OFF(theirs, mesh, CGAL::parameters::stream_precision(17)));
    ST::orient_triangle_soup(points, triangles);
    std::ostringstream ours;
    ST::IO::write_OFF_triangle_soup(ours, points, triangles);
    std::vector<Point> our_points, their_points;
    std::vector<std::vector<std::size_t>> our_faces, their_faces;
    ST::IO::read_OFF_polygons(ours.str(), our_points, our_faces, "ours");
    ST::IO::read_OFF_polygons(theirs.str(), their_points, their_faces, "theirs");
    EXPECT_EQ(our_points.size(), their_points.size());
    EXPECT_TRUE(our_points == their_points);
    EXPECT_TRUE(rotated_sorted(as_triangles(our_faces)) == rotated_sorted(as_triangles(their_faces)));
  }
}

} // namespace

// ---------------------------------------------------------------------------------------------
// The orientation policy of the tool, and a written file that does not depend on the input order.

TEST_F(HostileInput, Issue20OrientationOptionKeepsTheCavity)
{
  // CP_Radial bounds a volume as read: an outer shell and an inner one turned inward.
  const std::string in = soup_test::data_file("cad/kicad/CP_Radial_D10.0mm_P5.00mm.wrl");
  soup_test::Bounded_run r = run({"repair", in, "-o", output, "--json"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(soup_test::json_integer(r.out, "orientation_flips"), 0);
  r = run({"repair", in, "-o", output, "--json", "--orientation", "keep-input"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(soup_test::json_integer(r.out, "orientation_flips"), 0);
  r = run({"repair", in, "-o", output, "--json", "--orientation", "outward"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(soup_test::json_integer(r.out, "orientation_flips"), 138) << "the inner shell turned outward";
  expect_refused_unchanged({"repair", in, "-o", output, "--orientation", "inward"}, "--orientation takes");
}

// The triangles of a written OFF file as coordinate triples, each rotated to start at its
// smallest corner (orientation kept), sorted.
std::vector<std::array<Point, 3>> canonical_triangles(const std::string& off_file)
{
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> faces;
  ST::IO::read_OFF_polygons(read_whole(off_file), points, faces, off_file);
  std::vector<std::array<Point, 3>> triangles;
  for(const auto& f : faces) {
    std::array<Point, 3> t{points[f[0]], points[f[1]], points[f[2]]};
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    triangles.push_back(t);
  }
  std::sort(triangles.begin(), triangles.end());
  return triangles;
}

TEST_F(HostileInput, Issue21WrittenMeshDoesNotDependOnTheTriangleOrder)
{
  // ALSTOM_TEST4 at a relative tolerance of 1e-2: many non-manifold sites to separate and open
  // parts to orient, where the written mesh once depended on the order of the triangles.
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  soup_test::read_data_mesh("cad/ALSTOM_TEST4.off", points, triangles);
  std::mt19937 random(21);
  std::vector<std::vector<std::array<Point, 3>>> results;
  std::vector<std::string> reports;
  for(int trial = 0; trial < 3; ++trial) {
    if(trial > 0) std::shuffle(triangles.begin(), triangles.end(), random);
    std::ostringstream off;
    off << std::setprecision(17) << "OFF\n" << points.size() << " " << triangles.size() << " 0\n";
    for(const Point& p : points) off << p.x() << " " << p.y() << " " << p.z() << "\n";
    for(const Triangle& t : triangles) off << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
    const std::string in = write_file(folder, "alstom" + std::to_string(trial) + ".off", off.str());
    const soup_test::Bounded_run r = run({"repair", in, "-o", output, "--relative-tolerance", "1e-2", "--json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    results.push_back(canonical_triangles(output));
    // Everything but the file names must be the same.
    std::string report = r.out;
    report.erase(0, report.find("\"format\""));
    reports.push_back(report);
  }
  EXPECT_GT(results[0].size(), 1000u);
  for(int trial = 1; trial < 3; ++trial) {
    EXPECT_EQ(results[trial], results[0]) << "trial " << trial;
    EXPECT_EQ(reports[trial], reports[0]) << "trial " << trial;
  }
}

// --threads N on every command: the output is the same for any N (the pig, whose analysis and
// repair exercise the parallel searches, the weld and the orientation), and a count that is not a
// number from 1 to 4096 is refused.
TEST_F(HostileInput, ThreadCountsGiveTheSameOutputAndBadCountsAreRefused)
{
  const std::string pig = soup_test::data_file("cgal_repair/pig.stl.xz");
  std::vector<std::string> outputs;
  for(const std::string threads : {"1", "2", "3"}) {
    const soup_test::Bounded_run gaps = run({"gaps", pig, "--json", "--threads", threads});
    ASSERT_EQ(gaps.exit_code, 0) << gaps.err;
    const soup_test::Bounded_run stats = run({"stats", pig, "--json", "--threads", threads});
    ASSERT_EQ(stats.exit_code, 0) << stats.err;
    const std::string out = folder + "/pig" + threads + ".off";
    const soup_test::Bounded_run repair = run({"repair", pig, "-o", out, "--tolerance", "0.3", "--json", "--threads", threads});
    ASSERT_EQ(repair.exit_code, 0) << repair.err;
    std::string report = repair.out;
    report.erase(0, report.find("\"format\""));  // the file names differ
    outputs.push_back(gaps.out + stats.out + report + read_whole(out));
  }
  EXPECT_NE(outputs[0].find("\"verdict\""), std::string::npos);
  EXPECT_EQ(outputs[1], outputs[0]);
  EXPECT_EQ(outputs[2], outputs[0]);
  for(const std::string command : {"gaps", "stats"})
    for(const std::string bad : {"0", "x", "-1", "5000"})
      expect_refused_unchanged({command, input, "--threads", bad}, "--threads takes a number of threads from 1 to 4096");
  expect_refused_unchanged({"gaps", input, "--threads"}, "gaps: --threads needs a value");
  expect_refused_unchanged({"repair", input, "-o", output, "--threads", "0"},
                           "--threads takes a number of threads from 1 to 4096");
}

// The tools keep freed memory for reuse (tools/memory_reuse.h) unless GLIBC_TUNABLES is set:
// what they print and write must not depend on it.
TEST_F(HostileInput, MemoryReuseChangesNoOutput)
{
  const std::string pig = soup_test::data_file("cgal_repair/pig.stl.xz");
  const auto outputs = [&](const std::string& name) {
    const std::string out = folder + "/" + name + ".off";
    const soup_test::Bounded_run repair = run({"repair", pig, "-o", out, "--tolerance", "0.3", "--json", "--threads", "2"});
    EXPECT_EQ(repair.exit_code, 0) << repair.err;
    std::string report = repair.out;
    report.erase(0, report.find("\"format\""));  // the file names differ
    const soup_test::Bounded_run gaps = run({"gaps", pig, "--json", "--threads", "2"});
    EXPECT_EQ(gaps.exit_code, 0) << gaps.err;
    const soup_test::Bounded_run stats = run({"stats", pig, "--json", "--threads", "2"});
    EXPECT_EQ(stats.exit_code, 0) << stats.err;
    return report + gaps.out + stats.out + read_whole(out);
  };
  ASSERT_EQ(std::getenv("GLIBC_TUNABLES"), nullptr);
  const std::string reused = outputs("reused");
  ASSERT_EQ(setenv("GLIBC_TUNABLES", "glibc.malloc.perturb=0", 1), 0);
  const std::string by_default = outputs("default");
  // The policy stands aside for the environment's, and is taken otherwise (glibc, no sanitizer).
  EXPECT_FALSE(soup_topology_tool::keep_freed_memory_for_reuse());
  ASSERT_EQ(unsetenv("GLIBC_TUNABLES"), 0);
  EXPECT_EQ(soup_topology_tool::keep_freed_memory_for_reuse(), soup_topology_tool::memory_reuse_can_be_set);
  EXPECT_NE(reused.find("\"verdict\""), std::string::npos);
  EXPECT_EQ(reused, by_default);
  // With the policy taken, the heap is advised for huge pages wherever the kernel has them: one
  // mapping (the part of the heap grown for it) of nearly `huge_page_heap_size()` bytes flagged
  // "hg" in /proc/self/smaps.
  std::ifstream thp("/sys/kernel/mm/transparent_hugepage/enabled");
  const std::size_t marked = soup_topology_tool::huge_page_heap_size();
  if(soup_topology_tool::memory_reuse_can_be_set && thp && marked > 0) {
    const std::vector<soup_test::Memory_mapping> mappings = soup_test::memory_mappings();
    ASSERT_FALSE(mappings.empty()) << "no /proc/self/smaps";
    std::size_t largest_advised = 0;
    for(const soup_test::Memory_mapping& m : mappings)
      if(m.advised_for_huge_pages) largest_advised = std::max(largest_advised, std::size_t(m.end - m.begin));
    EXPECT_GE(largest_advised, marked - (std::size_t(4) << 20));
  }
}

} // namespace bad_input_test
