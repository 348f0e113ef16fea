// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Tests of <Soup_topology/IO/write_html_report.h>: the structure of the page, the embedded
// report JSON, the absence of addresses outside the license text, the holes, the display
// simplification of large soups and the marker positions recorded during a repair.

#include <Soup_topology/IO/write_html_report.h>

#include "test_utilities.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <functional>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <vector>

// The names of this file live in a namespace of its own: test/CMakeLists.txt compiles several
// test files as one translation unit.
namespace html_report_test {

namespace ST = Soup_topology;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = std::array<std::size_t, 3>;

// An n x n grid of unit squares in the plane z = 0, two triangles each, without the squares
// whose both coordinates lie in [hole_begin, hole_end).
void grid(std::size_t n, std::size_t hole_begin, std::size_t hole_end, std::vector<Point>& points,
          std::vector<Triangle>& triangles)
{
  for(std::size_t j = 0; j <= n; ++j)
    for(std::size_t i = 0; i <= n; ++i) points.emplace_back(double(i), double(j), 0.0);
  for(std::size_t j = 0; j < n; ++j)
    for(std::size_t i = 0; i < n; ++i) {
      if(i >= hole_begin && i < hole_end && j >= hole_begin && j < hole_end) continue;
      const std::size_t a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      triangles.push_back({a, b, d});
      triangles.push_back({a, d, c});
    }
}

std::string page_of(const std::vector<Point>& points, const std::vector<Triangle>& triangles,
                    const ST::IO::Html_report_content& content)
{
  std::ostringstream out;
  ST::IO::write_html_report(out, points, triangles, content);
  return out.str();
}

// The text of the element that starts with `opening`, up to its `</script>`.
std::string element_text(const std::string& page, const std::string& opening)
{
  const std::size_t begin = page.find(opening);
  if(begin == std::string::npos) return "<missing>";
  const std::size_t text = begin + opening.size();
  return page.substr(text, page.find("</script>", text) - text);
}

std::size_t occurrences(const std::string& text, const std::string& what)
{
  std::size_t n = 0;
  for(std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST(HtmlReport, WritesOneCompletePage)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  grid(4, 1, 2, points, triangles);
  ST::IO::Html_report_content content;
  content.title = "a <grid> & its hole";
  const std::string page = page_of(points, triangles, content);
  EXPECT_EQ(page.rfind("<!DOCTYPE html>\n<html", 0), 0u);
  EXPECT_NE(page.find("<meta charset=\"utf-8\">"), std::string::npos);
  EXPECT_NE(page.find("<title>a &lt;grid&gt; &amp; its hole</title>"), std::string::npos);
  EXPECT_NE(page.find("<body data-ready=\"false\">"), std::string::npos);
  EXPECT_NE(page.find("<canvas id=\"view\"></canvas>"), std::string::npos);
  EXPECT_EQ(occurrences(page, "<script"), 4u);
  EXPECT_EQ(occurrences(page, "</script>"), 4u);
  EXPECT_NE(page.find("<script type=\"module\">"), std::string::npos);
  EXPECT_EQ(page.substr(page.size() - 16), "</body>\n</html>\n");
  const std::string data = element_text(page, "<script type=\"application/json\" id=\"viewer-data\">");
  EXPECT_NE(data.find("\"holes_total\": 2,"), std::string::npos);  // the outer border and the hole
  EXPECT_NE(data.find("\"decimated\": false"), std::string::npos);
}

TEST(HtmlReport, EmbedsTheReportJsonAsGiven)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  grid(2, 0, 0, points, triangles);
  ST::IO::Html_report_content content;
  content.report_json = "{\"input\": \"a b.stl\", \"tolerance\": 0.1, \"closed\": false, \"border_edges\": 8}";
  const std::string opening = "<script type=\"application/json\" id=\"report-json\">";
  EXPECT_EQ(element_text(page_of(points, triangles, content), opening), content.report_json);
  // An end tag inside a string is written `<\/`: the same JSON value, the element is not closed.
  content.report_json = "{\"input\": \"</script>.stl\"}";
  EXPECT_EQ(element_text(page_of(points, triangles, content), opening), "{\"input\": \"<\\/script>.stl\"}");
}

TEST(HtmlReport, HasNoAddressOutsideTheLicense)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  grid(3, 0, 0, points, triangles);
  std::string page = page_of(points, triangles, ST::IO::Html_report_content());
  const std::string opening = "<script type=\"text/plain\" id=\"viewer-license\">";
  const std::size_t license = page.find(opening);
  ASSERT_NE(license, std::string::npos);
  page.erase(license, page.find("</script>", license) - license);
  EXPECT_EQ(page.find("http://"), std::string::npos);
  EXPECT_EQ(page.find("https://"), std::string::npos);
}

TEST(HtmlReport, ContentOfAReconstructionReport)
{
  ST::Reconstruction_report r;
  r.tolerance = 0.25;
  r.border_edges_before = 12;
  r.border_edges_after = 3;
  r.snapped_vertices = 5;
  r.ambiguous_sites = 2;
  const ST::IO::Html_report_content c = ST::IO::html_report_content(r);
  EXPECT_EQ(c.tolerance, 0.25);
  EXPECT_EQ(c.welded_vertices.count, 5u);
  EXPECT_EQ(c.ambiguous_sites.count, 2u);
  ASSERT_EQ(c.table_header.size(), 3u);
  for(const auto& row : c.table) EXPECT_EQ(row.size(), 3u);
  EXPECT_NE(c.report_json.find("\"border_edges_after\": 3"), std::string::npos);
  EXPECT_NE(c.report_json.find("\"tolerance\": 0.25"), std::string::npos);
  EXPECT_NE(c.report_json.find("\"closed\": false"), std::string::npos);
}

TEST(HtmlReportHoles, LoopsWithTheirLengthAndSize)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  grid(6, 2, 4, points, triangles);  // a 6 x 6 square with a 2 x 2 hole
  std::vector<ST::internal::Html_point> pts;
  for(const Point& p : points) pts.push_back({p.x(), p.y(), p.z()});
  const ST::Adjacency_tables tables(triangles, points.size());
  const auto border = ST::internal::html_edge_vertices(tables, tables.border_edges());
  const auto holes = ST::internal::html_holes(pts, border);
  ASSERT_EQ(holes.size(), 2u);
  EXPECT_EQ(holes[0].edges, 24u);
  EXPECT_DOUBLE_EQ(holes[0].length, 24.0);
  EXPECT_DOUBLE_EQ(holes[0].size, std::sqrt(72.0));
  EXPECT_EQ(holes[1].edges, 8u);
  EXPECT_DOUBLE_EQ(holes[1].length, 8.0);
  EXPECT_DOUBLE_EQ(holes[1].center[0], 3.0);
  EXPECT_DOUBLE_EQ(holes[1].center[1], 3.0);
}

TEST(HtmlReportDecimation, StaysWithinTheLimitAndKeepsTheBorders)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  grid(150, 70, 80, points, triangles);  // 44,800 triangles, a hole of 10 x 10 squares
  std::vector<ST::internal::Html_point> pts;
  for(const Point& p : points) pts.push_back({p.x(), p.y(), p.z()});
  std::vector<ST::internal::Html_triangle> tris;
  for(const Triangle& t : triangles)
    tris.push_back({std::uint32_t(t[0]), std::uint32_t(t[1]), std::uint32_t(t[2])});
  const ST::Adjacency_tables tables(triangles, points.size());
  const auto border = ST::internal::html_edge_vertices(tables, tables.border_edges());
  for(const std::size_t limit : {5000u, 20000u}) {
    const auto display = ST::internal::html_display_mesh(pts, tris, border, {}, limit);
    EXPECT_TRUE(display.decimated);
    EXPECT_LE(display.triangles.size(), limit);
    EXPECT_GE(display.triangles.size(), limit / 10);
    // The border and the triangles along it are kept: every border edge is still drawn, at its place.
    ASSERT_EQ(display.border_edges.size(), border.size());
    for(std::size_t i = 0; i < border.size(); ++i)
      for(int c = 0; c < 3; ++c) EXPECT_EQ(display.points[display.border_edges[i]][c], pts[border[i]][c]);
    for(const auto& t : display.triangles)
      for(std::uint32_t v : t) EXPECT_LT(v, display.points.size());
  }
  const auto whole = ST::internal::html_display_mesh(pts, tris, border, {}, tris.size());
  EXPECT_FALSE(whole.decimated);
  EXPECT_EQ(whole.triangles.size(), tris.size());
}

TEST(HtmlReportDecimation, PageOfALargeSoupIsSimplified)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  grid(100, 0, 0, points, triangles);
  ST::IO::Html_report_content content;
  content.display_triangle_limit = 4000;
  const std::string page = page_of(points, triangles, content);
  const std::string data = element_text(page, "<script type=\"application/json\" id=\"viewer-data\">");
  EXPECT_NE(data.find("\"soup_triangles\": 20000,"), std::string::npos);
  EXPECT_NE(data.find("\"decimated\": true"), std::string::npos);
}

// The value of `"key": ` in `data`, up to the next `,` or `}` (the first occurrence).
std::string json_value(const std::string& data, const std::string& key)
{
  const std::string opening = "\"" + key + "\": ";
  const std::size_t begin = data.find(opening);
  if(begin == std::string::npos) return "<missing>";
  const std::size_t text = begin + opening.size();
  return data.substr(text, data.find_first_of(",}", text) - text);
}

// The floats of the base64 text of `"key": "..."` in `data`.
std::vector<float> base64_floats(const std::string& data, const std::string& key)
{
  std::string text = json_value(data, key);
  text = text.substr(1, text.size() - 2);
  static const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> bytes;
  std::uint32_t bits = 0;
  int count = 0;
  for(char c : text) {
    if(c == '=') break;
    bits = (bits << 6) | static_cast<std::uint32_t>(alphabet.find(c));
    if((count += 6) >= 8) {
      count -= 8;
      bytes.push_back(static_cast<unsigned char>((bits >> count) & 0xFF));
    }
  }
  std::vector<float> values(bytes.size() / sizeof(float));
  std::copy(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(values.size() * sizeof(float)),
            reinterpret_cast<unsigned char*>(values.data()));
  return values;
}

// The 3D view of a soup does not depend on its unit: a soup scaled by 2^k (exact) is drawn at the
// same float coordinates in the view's unit, near 1e-270 and near 1e300 as at 1 (where float
// coordinates relative to the center used to underflow to 0 or overflow), with the lengths of
// the holes in the soup's unit; simplified above the display limit the same way.
TEST(HtmlReportScale, TheViewOfASoupDoesNotDependOnItsUnit)
{
  for(const std::size_t limit : {std::size_t(1) << 20, std::size_t(60)}) {
    SCOPED_TRACE("display triangle limit " + std::to_string(limit));
    std::vector<Point> points;
    std::vector<Triangle> triangles;
    grid(12, 4, 7, points, triangles);  // a 12 x 12 square with a 3 x 3 hole
    // Far from the origin, so that the view's origin matters.
    for(Point& p : points) p = Point(p.x() + 1000, p.y() - 64, p.z());
    std::vector<std::string> data_at;
    std::vector<std::vector<float>> positions_at;
    const int exponents[] = {-900, -40, -20, 0, 20, 40, 1000};
    for(const int k : exponents) {
      std::vector<Point> scaled;
      for(const Point& p : points)
        scaled.emplace_back(std::ldexp(p.x(), k), std::ldexp(p.y(), k), std::ldexp(p.z(), k));
      ST::IO::Html_report_content content;
      content.display_triangle_limit = limit;
      content.welded_vertices.count = 1;
      content.welded_vertices.positions = {{scaled[5].x(), scaled[5].y(), 0}};
      data_at.push_back(element_text(page_of(scaled, triangles, content),
                                     "<script type=\"application/json\" id=\"viewer-data\">"));
      positions_at.push_back(base64_floats(data_at.back(), "positions"));
    }
    // The square is 12 wide: its half extent 6 (times 2^k) stays in the soup's unit while it
    // lies within 2^+-32; beyond, it is brought between 1 and 2: the view's unit is then 2^-2
    // times that of the soup at k = 0, and the page is the same, to the bit, for every such k.
    const int view_exponents[] = {898, 38, 0, 0, 0, -42, -1002};
    const std::size_t at_one = 3, beyond = 0;
    ASSERT_FALSE(positions_at[at_one].empty());
    for(std::size_t i = 0; i < std::size(exponents); ++i) {
      SCOPED_TRACE("soup scaled by 2^" + std::to_string(exponents[i]));
      const std::string& data = data_at[i];
      const int view_exponent = view_exponents[i];
      EXPECT_EQ(json_value(data, "view_exponent"), std::to_string(view_exponent));
      EXPECT_EQ(json_value(data, "decimated"), limit < 1000 ? "true" : "false");
      EXPECT_EQ(json_value(data, "triangles"), json_value(data_at[at_one], "triangles"));
      EXPECT_EQ(json_value(data, "border_edges"), json_value(data_at[at_one], "border_edges"));
      EXPECT_EQ(json_value(data, "displayed_triangles"), json_value(data_at[at_one], "displayed_triangles"));
      const float view_scale = static_cast<float>(std::ldexp(1.0, exponents[i] + view_exponent));
      // In the soup's unit the points are drawn as at k = 0, times 2^k; in another unit, as at
      // every other k beyond the range; and either way as at k = 0 up to float rounding.
      const std::vector<float>& same = view_exponent == 0 ? positions_at[at_one] : positions_at[beyond];
      const float same_scale = view_exponent == 0 ? 1.0f : 0.25f;
      ASSERT_EQ(positions_at[i].size(), same.size());
      ASSERT_EQ(positions_at[i].size(), positions_at[at_one].size());
      for(std::size_t c = 0; c < same.size(); ++c) {
        ASSERT_EQ(positions_at[i][c], same[c] / same_scale * view_scale) << "coordinate " << c;
        ASSERT_NEAR(positions_at[i][c], positions_at[at_one][c] * view_scale, 1e-5 * view_scale) << "coordinate " << c;
      }
      // The length of the longest hole (the outer border, 48 long) in the soup's unit; the
      // marker in the view's.
      EXPECT_EQ(json_value(data, "length"), ST::internal::html_json_number(std::ldexp(48.0, exponents[i])));
      const std::string marker = "[" + ST::internal::html_json_float(-1 * view_scale) + "," +
                                 ST::internal::html_json_float(-6 * view_scale) + ",0]";
      EXPECT_NE(data.find("\"welded_vertices\": [" + marker + "]"), std::string::npos) << data.substr(0, 600);
    }
  }
}

TEST(HtmlReport, WritesTheNonManifoldEdges)
{
  // Three triangles on the edge (0, 1): one non-manifold edge, six border edges.
  const std::vector<Point> points{Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0), Point(0, -1, 0), Point(0, 0, 1)};
  const std::vector<Triangle> triangles{{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  const std::string data =
    element_text(page_of(points, triangles, ST::IO::Html_report_content()), "<script type=\"application/json\" id=\"viewer-data\">");
  // Two 32-bit indices per edge, in base64: 8 bytes -> 12 characters.
  const std::string key = "\"non_manifold_edges\": \"";
  const std::size_t at = data.find(key);
  ASSERT_NE(at, std::string::npos);
  EXPECT_EQ(data.find('"', at + key.size()) - (at + key.size()), 12u);
  EXPECT_EQ(data.find("\"holes_total\": 0,"), std::string::npos);
}

TEST(HtmlReport, RefusesAnIndexOutOfRange)
{
  std::vector<Point> points(3, Point(0, 0, 0));
  std::vector<Triangle> triangles{{0, 1, 3}};
  std::ostringstream out;
  EXPECT_THROW(ST::IO::write_html_report(out, points, triangles, ST::IO::Html_report_content()), ST::Invalid_input);
}

// A soup with one site of each marker kind at tolerance 0.1 under Small_features::REFUSE, the
// pieces 10 apart along x:
//   - x = 0: two triangles whose shared edge is open by 0.045 at each end (two welds);
//   - x = 10: a triangle whose border edge [(10,0), (12,0)] has a vertex of two others at (11,0)
//     (one T-junction split);
//   - x = 20: a triangle with an edge of length 0.05 (a refused weld and an ambiguous site);
//   - x = 30: a triangle over [(30,0), (32,0)] and a second one folded over it, whose border edge
//     runs 0.02 above that edge (two splits refused for the overlap).
struct Site_soup
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  std::size_t add(double x, double y) { points.emplace_back(x, y, 0.0); return points.size() - 1; }
};

Site_soup soup_with_every_site_kind()
{
  Site_soup s;
  const std::size_t p0 = s.add(0, 0), p1 = s.add(1, 0), p2 = s.add(0, 1);
  const std::size_t q0 = s.add(1.04, 0.02), r = s.add(1, 1), q2 = s.add(0.02, 1.04);
  s.triangles.push_back({p0, p1, p2});
  s.triangles.push_back({q0, r, q2});
  const std::size_t a = s.add(10, 0), b = s.add(12, 0), apex = s.add(11, -1), c = s.add(11, 0);
  const std::size_t u1 = s.add(10.5, 1), u2 = s.add(11.5, 1);
  s.triangles.push_back({b, a, apex});
  s.triangles.push_back({a, c, u1});
  s.triangles.push_back({c, b, u2});
  s.triangles.push_back({c, u2, u1});
  s.triangles.push_back({s.add(20, 0), s.add(20.05, 0), s.add(20, 1)});
  s.triangles.push_back({s.add(30, 0), s.add(32, 0), s.add(31, 1)});
  s.triangles.push_back({s.add(31, 0.02), s.add(31.5, 0.02), s.add(31.3, 0.5)});
  return s;
}

// Repairs `s` at tolerance 0.1 (refusing small features) and returns the page content with the
// positions recorded.
ST::IO::Html_report_content repaired_content(Site_soup s, ST::Reconstruction_report& report)
{
  const std::vector<Point> input = s.points;
  ST::IO::Html_report_site_recorder recorder;
  report = ST::reconstruct_topology(s.points, s.triangles,
                                    ST::parameters::small_features(ST::Small_features::REFUSE,
                                                                   CGAL::parameters::snapping_tolerance(0.1)
                                                                     .visitor(std::ref(recorder))));
  ST::IO::Html_report_content content = ST::IO::html_report_content(report);
  ST::IO::add_site_positions(content, recorder, input);
  return content;
}

double distance(const std::array<double, 3>& p, const Point& q)
{
  return std::sqrt(CGAL::to_double(CGAL::squared_distance(Point(p[0], p[1], p[2]), q)));
}

// Every position lies within `tolerance` of one of `places`, and every place has a position.
void expect_at(const ST::IO::Html_report_sites& sites, const std::vector<Point>& places, double tolerance,
               const char* kind)
{
  EXPECT_EQ(sites.positions.size(), places.size()) << kind;
  for(const auto& p : sites.positions) {
    double nearest = 1e30;
    for(const Point& q : places) nearest = std::min(nearest, distance(p, q));
    EXPECT_LE(nearest, tolerance) << kind << " at " << p[0] << ' ' << p[1] << ' ' << p[2];
  }
  for(const Point& q : places) {
    double nearest = 1e30;
    for(const auto& p : sites.positions) nearest = std::min(nearest, distance(p, q));
    EXPECT_LE(nearest, tolerance) << kind << ": nothing near " << q;
  }
}

TEST(HtmlReportSites, PositionsOfEveryKindWhereTheRepairActed)
{
  ST::Reconstruction_report report;
  const ST::IO::Html_report_content c = repaired_content(soup_with_every_site_kind(), report);
  const double eps = 0.1;
  expect_at(c.welded_vertices, {Point(1, 0, 0), Point(0, 1, 0)}, eps, "welded vertices");
  expect_at(c.t_junction_splits, {Point(11, 0, 0)}, eps, "T-junction splits");
  expect_at(c.refused_welds, {Point(20.025, 0, 0)}, eps, "refused welds");
  expect_at(c.refused_splits, {Point(31, 0, 0), Point(31.5, 0, 0)}, eps, "refused splits");
  expect_at(c.ambiguous_sites, {Point(20, 0, 0)}, eps, "ambiguous sites");
  // The counts are those of the report; a place counted in several rounds is shown once.
  EXPECT_EQ(c.welded_vertices.count, 2u);
  EXPECT_EQ(c.t_junction_splits.count, 1u);
  EXPECT_GE(c.refused_welds.count, 1u);
  EXPECT_GE(c.refused_splits.count, 2u);
  EXPECT_GE(c.ambiguous_sites.count, 1u);
  // The page holds them, relative to the center of the soup.
  std::vector<Point> points = soup_with_every_site_kind().points;
  const std::string data = element_text(page_of(points, soup_with_every_site_kind().triangles, c),
                                        "<script type=\"application/json\" id=\"viewer-data\">");
  EXPECT_NE(data.find("\"t_junction_splits\": [[-5,"), std::string::npos);
  EXPECT_NE(data.find("\"ambiguous_sites\": [[4,"), std::string::npos);
}

TEST(HtmlReportSites, TheRecorderChangesNoResult)
{
  Site_soup with = soup_with_every_site_kind(), without = soup_with_every_site_kind();
  ST::Reconstruction_report recorded;
  repaired_content(with, recorded);
  const auto np = ST::parameters::small_features(ST::Small_features::REFUSE, CGAL::parameters::snapping_tolerance(0.1));
  ST::IO::Html_report_site_recorder recorder;
  const ST::Reconstruction_report plain = ST::reconstruct_topology(without.points, without.triangles, np);
  ST::reconstruct_topology(with.points, with.triangles,
                           ST::parameters::small_features(ST::Small_features::REFUSE,
                                                          CGAL::parameters::snapping_tolerance(0.1).visitor(std::ref(recorder))));
  EXPECT_EQ(ST::IO::reconstruction_report_json(recorded), ST::IO::reconstruction_report_json(plain));
  EXPECT_EQ(with.points, without.points);
  EXPECT_EQ(with.triangles, without.triangles);
  // One entry per event the report counts.
  EXPECT_EQ(recorder.welded_vertices.size(), plain.snapped_vertices);
  EXPECT_EQ(recorder.t_junction_splits.size(), plain.split_triangles);
  EXPECT_EQ(recorder.refused_welds.size(), plain.refused_welds());
  EXPECT_EQ(recorder.refused_splits.size(), plain.refused_splits);
  EXPECT_EQ(recorder.ambiguous_sites.size(), plain.ambiguous_sites + plain.ambiguous_t_junctions);
}

TEST(HtmlReportSites, SamePositionsForAShuffledSoup)
{
  ST::Reconstruction_report report;
  const ST::IO::Html_report_content expected = repaired_content(soup_with_every_site_kind(), report);
  std::mt19937 random(16);
  for(int trial = 0; trial < 4; ++trial) {
    const Site_soup s = soup_with_every_site_kind();
    std::vector<std::size_t> order(s.points.size());
    std::iota(order.begin(), order.end(), std::size_t(0));
    std::shuffle(order.begin(), order.end(), random);
    Site_soup shuffled;
    std::vector<std::size_t> new_index(order.size());
    for(std::size_t i = 0; i < order.size(); ++i) {
      shuffled.points.push_back(s.points[order[i]]);
      new_index[order[i]] = i;
    }
    for(const Triangle& t : s.triangles) {
      const std::size_t turn = random() % 3;
      shuffled.triangles.push_back(
        {new_index[t[turn]], new_index[t[(turn + 1) % 3]], new_index[t[(turn + 2) % 3]]});
    }
    std::shuffle(shuffled.triangles.begin(), shuffled.triangles.end(), random);
    ST::Reconstruction_report shuffled_report;
    const ST::IO::Html_report_content c = repaired_content(shuffled, shuffled_report);
    EXPECT_EQ(c.welded_vertices.positions, expected.welded_vertices.positions);
    EXPECT_EQ(c.t_junction_splits.positions, expected.t_junction_splits.positions);
    EXPECT_EQ(c.refused_welds.positions, expected.refused_welds.positions);
    EXPECT_EQ(c.refused_splits.positions, expected.refused_splits.positions);
    EXPECT_EQ(c.ambiguous_sites.positions, expected.ambiguous_sites.positions);
  }
}

// A split visitor that keeps every call, in order.
struct Split_calls : ST::Default_split_visitor
{
  std::vector<std::array<std::size_t, 4>> splits, refusals, ambiguous;
  void on_split(std::size_t v, std::size_t a, std::size_t b) { splits.push_back({v, a, b, 0}); }
  void on_split_refusal(std::size_t v, std::size_t a, std::size_t b, ST::Split_refusal_reason reason)
  { refusals.push_back({v, a, b, static_cast<std::size_t>(reason)}); }
  void on_ambiguous_t_junction(std::size_t v, std::size_t a, std::size_t b) { ambiguous.push_back({v, a, b, 0}); }
};

template <class ConcurrencyTag>
Split_calls split_calls(ST::Split_report& report)
{
  Site_soup s = soup_with_every_site_kind();
  Split_calls calls;
  report = ST::split_t_junctions<ConcurrencyTag>(s.points, s.triangles,
                                                 CGAL::parameters::snapping_tolerance(0.1).visitor(std::ref(calls)));
  return calls;
}

TEST(HtmlReportSites, SplitVisitorIsToldEveryEventInTheSameOrderOnAnyThreads)
{
  ST::Split_report report, parallel_report;
  const Split_calls calls = split_calls<CGAL::Sequential_tag>(report);
  EXPECT_EQ(calls.splits.size(), report.split_triangles);
  EXPECT_EQ(calls.refusals.size(), report.refused_overlap + report.refused_degenerate + report.refused_flip);
  EXPECT_EQ(calls.ambiguous.size(), report.ambiguous);
  ASSERT_EQ(calls.splits.size(), 1u);
  const Site_soup s = soup_with_every_site_kind();
  EXPECT_EQ(s.points[calls.splits[0][0]], Point(11, 0, 0));
  ASSERT_EQ(calls.refusals.size(), 2u);
  for(const auto& r : calls.refusals) EXPECT_EQ(r[3], static_cast<std::size_t>(ST::Split_refusal_reason::OVERLAP));
  const Split_calls parallel_calls = split_calls<CGAL::Parallel_if_available_tag>(parallel_report);
  EXPECT_EQ(parallel_calls.splits, calls.splits);
  EXPECT_EQ(parallel_calls.refusals, calls.refusals);
  EXPECT_EQ(parallel_calls.ambiguous, calls.ambiguous);
}

TEST(HtmlReportSites, RefusesAnIndexBeyondThePoints)
{
  ST::IO::Html_report_site_recorder recorder;
  recorder.refused_welds.push_back({0, 3});
  ST::IO::Html_report_content content;
  const std::vector<Point> points(3, Point(0, 0, 0));
  EXPECT_THROW(ST::IO::add_site_positions(content, recorder, points), ST::Invalid_input);
}

std::string read_file(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The page of the command-line tool embeds exactly the object that --json prints.
TEST(HtmlReportCli, PagesEmbedTheJsonOutput)
{
  const std::string cli = SOUP_TOPOLOGY_CLI;
  if(cli.empty()) GTEST_SKIP() << "the tool is not built";
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  grid(5, 1, 3, points, triangles);
  const std::string dir = soup_test::temporary_folder("html_report_cli");
  {
    std::ofstream off(dir + "/grid.off");
    off << "OFF\n" << points.size() << ' ' << triangles.size() << " 0\n";
    for(const Point& p : points) off << p << '\n';
    for(const Triangle& t : triangles) off << "3 " << t[0] << ' ' << t[1] << ' ' << t[2] << '\n';
  }
  const std::string opening = "<script type=\"application/json\" id=\"report-json\">";
  const auto [stats, stats_code] =
    soup_test::run_command(cli + " stats '" + dir + "/grid.off' --json --html '" + dir + "/stats.html'");
  ASSERT_EQ(stats_code, 0);
  EXPECT_EQ(element_text(read_file(dir + "/stats.html"), opening) + "\n", stats);
  const auto [repair, repair_code] = soup_test::run_command(
    cli + " repair '" + dir + "/grid.off' -o '" + dir + "/out.off' --tolerance 0.01 --json --html '" + dir + "/repair.html'");
  ASSERT_EQ(repair_code, 0);
  EXPECT_EQ(element_text(read_file(dir + "/repair.html"), opening) + "\n", repair);
  // The page may not replace the input.
  const auto [refused, refused_code] =
    soup_test::run_command(cli + " stats '" + dir + "/grid.off' --html '" + dir + "/grid.off' 2>/dev/null");
  EXPECT_EQ(refused_code, 2);
  EXPECT_TRUE(refused.empty());
}

} // namespace html_report_test
