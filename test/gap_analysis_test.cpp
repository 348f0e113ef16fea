// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Tests of analyze_gaps.h (issue 17): the suggested tolerance closes the seams of real and
// generated soups as a good hand-picked tolerance does, keeps a wide crack open, does not depend
// on the order of the input, and says so when the gaps and the features overlap; the `gaps`
// command and `repair --tolerance auto`.

#include <Soup_topology/IO/read_triangle_soup.h>
#include <Soup_topology/analyze_gaps.h>
#include <Soup_topology/reconstruct_topology.h>

#include "soup_generators.h"
#include "test_utilities.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

// The names of this file live in a namespace of its own: test/CMakeLists.txt compiles several
// test files as one translation unit.
namespace gap_analysis_test {

namespace {

namespace ST = Soup_topology;
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Epick::Point_3;
using Triangle = std::array<std::size_t, 3>;

std::string cli() { return SOUP_TOPOLOGY_CLI; }

struct Soup
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
};

Soup load(const std::string& relative)
{
  Soup s;
  soup_test::read_data_mesh(relative, s.points, s.triangles);
  return s;
}

double diagonal(const std::vector<Point>& points)
{
  return ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>());
}

std::size_t border_edges_after(Soup s, double tolerance)
{
  return ST::reconstruct_topology(s.points, s.triangles, CGAL::parameters::snapping_tolerance(tolerance))
    .border_edges_after;
}

TEST(GapAnalysis, ClosedMeshNeedsNoTolerance)
{
  const Soup s = load("clean/elephant.off");
  const ST::Gap_analysis a = ST::analyze_gaps(s.points, s.triangles);
  EXPECT_EQ(a.verdict, ST::Gap_verdict::CLOSED);
  EXPECT_EQ(a.border_edges, 0u);
  EXPECT_TRUE(a.gaps.empty());
  EXPECT_EQ(a.suggested_tolerance, 0.0);
  EXPECT_GT(a.shortest_edges.count, 0u);
  EXPECT_LE(a.shortest_edges.minimum, a.shortest_edges.median);
  EXPECT_LE(a.smallest_heights.minimum, a.smallest_heights.median);
}

TEST(GapAnalysis, To220ClosesAsTheHandPickedTolerance)
{
  const Soup s = load("cad/kicad/TO-220-3_Vertical.wrl");
  const ST::Gap_analysis a = ST::analyze_gaps(s.points, s.triangles);
  ASSERT_EQ(a.verdict, ST::Gap_verdict::SUGGESTED) << a.reasoning;
  EXPECT_EQ(a.border_edges, 10u);
  // The hand-picked tolerance of the pipeline tests: 1e-6 of the diagonal closes it.
  const std::size_t by_hand = border_edges_after(s, 1e-6 * diagonal(s.points));
  EXPECT_EQ(by_hand, 0u);
  EXPECT_EQ(border_edges_after(s, a.suggested_tolerance), by_hand);
  EXPECT_LT(a.suggested_tolerance, a.feature_bound);
  EXPECT_GE(a.closing_margin, std::sqrt(2.0));
  EXPECT_GE(a.keeping_margin, std::sqrt(2.0));
  EXPECT_LE(a.largest_closed_gap, a.suggested_tolerance);
  EXPECT_GT(a.smallest_open_gap, a.suggested_tolerance);
  // The histogram counts every positive measured gap once.
  std::size_t counted = 0;
  for(const ST::Gap_histogram_bin& b : a.gap_histogram) {
    EXPECT_LT(b.lower, b.upper);
    counted += b.count;
  }
  EXPECT_EQ(counted + a.zero_gaps, a.gaps.size());
  EXPECT_EQ(a.gaps.size() + a.gaps_beyond_search_radius, a.border_vertices);
}

// The pig's seams are non-conforming: the distances from a T-junction vertex to the other side
// (0.0065 to 0.29) run into the lengths of its own border edges (from 0.26) without a break, so
// no tolerance is a factor sqrt(2) away from both. The hand-picked 0.3 closes it only because the weld
// refuses merges inside a triangle and merges that flip one; the analysis says so.
TEST(GapAnalysis, PigGapsAndFeaturesOverlap)
{
  const Soup s = load("cgal_repair/pig.stl.xz");
  const ST::Gap_analysis a = ST::analyze_gaps(s.points, s.triangles);
  EXPECT_EQ(a.border_edges, 1296u);
  EXPECT_EQ(a.verdict, ST::Gap_verdict::OVERLAP) << a.reasoning;
  EXPECT_FALSE(a.has_suggestion());
  EXPECT_TRUE(std::isnan(a.suggested_tolerance));
  EXPECT_NE(a.reasoning.find("overlap"), std::string::npos);
  ASSERT_FALSE(a.gaps.empty());
  EXPECT_LT(a.gaps.front(), a.feature_bound);
  EXPECT_GT(a.border_features.minimum, 0.2);
  EXPECT_LT(a.border_features.minimum, 0.3);
}

/// `soup` with its points renumbered, the corners of every triangle rotated (same triangle, same
/// orientation) and the triangles in another order, all drawn from `seed`.
Soup shuffled_soup(const Soup& soup, unsigned seed)
{
  std::mt19937 rng(seed);
  std::vector<std::size_t> order(soup.points.size());
  for(std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::shuffle(order.begin(), order.end(), rng);
  Soup shuffled;
  shuffled.points.resize(soup.points.size());
  std::vector<std::size_t> new_index(soup.points.size());
  for(std::size_t i = 0; i < order.size(); ++i) {
    shuffled.points[i] = soup.points[order[i]];
    new_index[order[i]] = i;
  }
  for(const Triangle& t : soup.triangles) {
    const std::size_t r = rng() % 3;
    shuffled.triangles.push_back({new_index[t[r]], new_index[t[(r + 1) % 3]], new_index[t[(r + 2) % 3]]});
  }
  std::shuffle(shuffled.triangles.begin(), shuffled.triangles.end(), rng);
  return shuffled;
}

ST::Gap_analysis analyze_jittered(const Soup& mesh, double relative_jitter, unsigned seed, Soup& soup)
{
  const auto generated =
    soup_test::t_junction_soup(mesh.points, mesh.triangles, 4, relative_jitter * diagonal(mesh.points), seed);
  soup.points = generated.points;
  soup.triangles = generated.triangles;
  return ST::analyze_gaps(soup.points, soup.triangles);
}

TEST(GapAnalysis, JitteredSeamsOfRealMeshesAreClosed)
{
  for(const char* file : {"clean/elephant.off", "clean/fandisk.off.xz"}) {
    const Soup mesh = load(file);
    for(double jitter : {1e-7, 1e-6, 1e-5, 1e-4}) {
      SCOPED_TRACE(std::string(file) + " jitter " + std::to_string(jitter));
      Soup soup;
      const ST::Gap_analysis a = analyze_jittered(mesh, jitter, 17, soup);
      EXPECT_EQ(a.verdict, ST::Gap_verdict::SUGGESTED) << a.reasoning;
      if(!a.has_suggestion()) continue;
      // The copies of a point are at most 2 sqrt(3) jitter apart: the tolerance is above that.
      EXPECT_EQ(border_edges_after(soup, a.suggested_tolerance), 0u) << a.reasoning;
    }
  }
}

TEST(GapAnalysis, ShuffledInputGivesTheSameSuggestion)
{
  const Soup mesh = load("clean/elephant.off");
  Soup soup;
  const ST::Gap_analysis a = analyze_jittered(mesh, 1e-6, 5, soup);
  const Soup shuffled = shuffled_soup(soup, 3);
  const ST::Gap_analysis b = ST::analyze_gaps(shuffled.points, shuffled.triangles);
  EXPECT_EQ(a.verdict, b.verdict);
  EXPECT_EQ(a.suggested_tolerance, b.suggested_tolerance);
  EXPECT_EQ(a.gaps, b.gaps);
  EXPECT_EQ(a.feature_bound, b.feature_bound);
  EXPECT_EQ(a.search_radius, b.search_radius);
}

TEST(GapAnalysis, CrackWiderThanTheSmallestFeatureStaysOpen)
{
  const Soup mesh = load("clean/elephant.off");
  Soup soup;
  analyze_jittered(mesh, 1e-7, 9, soup);
  // Move the patch of triangle 0 (its own copies of its points) by the median shortest edge of
  // the mesh, far wider than its smallest feature: a crack along that patch's border.
  const ST::Gap_analysis clean = ST::analyze_gaps(mesh.points, mesh.triangles);
  const double width = clean.shortest_edges.median;
  ASSERT_GT(width, clean.shortest_edges.minimum);
  std::vector<ST::Adjacency_tables::size_type> component;
  ST::Adjacency_tables(soup.triangles, soup.points.size()).number_of_connected_components(&component);
  std::vector<char> moved(soup.points.size(), 0);
  for(std::size_t t = 0; t < soup.triangles.size(); ++t)
    if(component[t] == component[0])
      for(std::size_t v : soup.triangles[t]) moved[v] = 1;
  for(std::size_t v = 0; v < soup.points.size(); ++v)
    if(moved[v]) soup.points[v] = Point(soup.points[v].x() + width, soup.points[v].y(), soup.points[v].z());
  const ST::Gap_analysis a = ST::analyze_gaps(soup.points, soup.triangles);
  ASSERT_TRUE(a.has_suggestion()) << a.reasoning;
  EXPECT_LT(a.suggested_tolerance, a.border_features.minimum / 3);
  Soup repaired = soup;
  const ST::Reconstruction_report r = ST::reconstruct_topology(
    repaired.points, repaired.triangles, CGAL::parameters::snapping_tolerance(a.suggested_tolerance));
  EXPECT_GT(r.border_edges_after, 0u) << a.reasoning;
  // The jittered seams away from the moved patch are closed: fewer border edges than before.
  EXPECT_LT(r.border_edges_after, r.border_edges_before);
}

TEST(GapAnalysis, ExactKernelGivesTheSameSuggestion)
{
  const Soup s = load("cad/kicad/TO-220-3_Vertical.wrl");
  using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;
  const ST::Gap_analysis a = ST::analyze_gaps(s.points, s.triangles);
  const ST::Gap_analysis b = ST::analyze_gaps(s.points, s.triangles, CGAL::parameters::geom_traits(Epeck()));
  EXPECT_EQ(a.verdict, b.verdict);
  EXPECT_DOUBLE_EQ(a.suggested_tolerance, b.suggested_tolerance);
  EXPECT_EQ(a.gaps.size(), b.gaps.size());
}

TEST(GapAnalysis, RuleClosesTheLargestSeparatedClusterBelowTheBound)
{
  using ST::internal::closed_gap_count;
  EXPECT_EQ(closed_gap_count({1e-6, 2e-6, 1e-3, 1.5e-3}, 0.1), 4u);   // both clusters below the bound
  EXPECT_EQ(closed_gap_count({1e-6, 2e-6, 1e-3, 1.5e-3}, 2e-3), 2u);  // the second one too near the bound
  EXPECT_EQ(closed_gap_count({1e-6, 1.5e-6, 2e-6}, 3e-6), 0u);       // no separation anywhere
  EXPECT_EQ(closed_gap_count({0, 0, 1e-2}, 1e-3), 2u);              // exact T-junctions only
  EXPECT_EQ(closed_gap_count({1.0, 2.0}, 0.1), 0u);                 // nothing below the bound
  EXPECT_DOUBLE_EQ(ST::internal::tolerance_between(1e-6, 1e-4), 1e-5);
  EXPECT_DOUBLE_EQ(ST::internal::tolerance_between(0, 1e-4), 5e-5);
}

TEST(GapAnalysis, TwoSquaresWithANarrowSeam)
{
  // Two unit squares (two triangles each) side by side, 1e-4 apart: four gaps of 1e-4.
  const double g = 1e-4;
  std::vector<Point> points = {Point(0, 0, 0), Point(1, 0, 0), Point(1, 1, 0), Point(0, 1, 0),
                               Point(1 + g, 0, 0), Point(2, 0, 0), Point(2, 1, 0), Point(1 + g, 1, 0)};
  std::vector<Triangle> triangles = {{0, 1, 2}, {0, 2, 3}, {4, 5, 6}, {4, 6, 7}};
  const ST::Gap_analysis a = ST::analyze_gaps(points, triangles);
  ASSERT_EQ(a.verdict, ST::Gap_verdict::SUGGESTED) << a.reasoning;
  EXPECT_EQ(a.border_vertices, 8u);
  EXPECT_EQ(a.closed_gaps, 4u);
  EXPECT_NEAR(a.feature_bound, (1 - g) / 3, 1e-12);  // the shortest border edge, on the right square
  EXPECT_GT(a.suggested_tolerance, g);
  EXPECT_LT(a.suggested_tolerance, a.feature_bound);
  Soup s{points, triangles};
  EXPECT_EQ(border_edges_after(s, a.suggested_tolerance), 6u);  // the seam closed, the outline left
}

// Two squares of side `side` (two triangles each) side by side, `gap` apart, moved by `offset`
// along x: one part of an assembly with a seam at its own scale.
void add_two_squares(Soup& s, double side, double gap, double offset)
{
  const std::size_t first = s.points.size();
  const double x[4] = {offset, offset + side, offset + side + gap, offset + 2 * side + gap};
  for(int k = 0; k < 2; ++k) {
    s.points.emplace_back(x[2 * k], 0, 0);
    s.points.emplace_back(x[2 * k + 1], 0, 0);
    s.points.emplace_back(x[2 * k + 1], side, 0);
    s.points.emplace_back(x[2 * k], side, 0);
  }
  for(std::size_t k = 0; k < 2; ++k) {
    const std::size_t b = first + 4 * k;
    s.triangles.push_back({b, b + 1, b + 2});
    s.triangles.push_back({b, b + 2, b + 3});
  }
}

// A small part (squares of 0.01, seam 1e-6) and a large one (squares of 10, seam 0.05), far
// apart: one tolerance closes the small seam only (0.05 is above a third of the small part's
// edges); per part, each seam gets its own tolerance, below its own features. The same parts in
// any order of the input.
TEST(GapAnalysis, PartsOfDifferentScalesGetTheirOwnTolerances)
{
  Soup s;
  add_two_squares(s, 0.01, 1e-6, 0);
  add_two_squares(s, 10, 0.05, 100);
  const ST::Gap_analysis whole = ST::analyze_gaps(s.points, s.triangles);
  ASSERT_EQ(whole.verdict, ST::Gap_verdict::SUGGESTED) << whole.reasoning;
  EXPECT_LT(whole.suggested_tolerance, 0.05);
  const std::vector<ST::Part_gap_analysis> parts = ST::analyze_gaps_per_part(s.points, s.triangles);
  ASSERT_EQ(parts.size(), 2u);
  const ST::Part_gap_analysis& large = parts[0];
  const ST::Part_gap_analysis& small = parts[1];
  EXPECT_EQ(large.triangles, 4u);
  EXPECT_EQ(large.border_vertices, 8u);
  EXPECT_NEAR(large.feature_bound, 10.0 / 3, 1e-9);
  ASSERT_EQ(large.verdict, ST::Gap_verdict::SUGGESTED) << large.reasoning;
  EXPECT_GT(large.suggested_tolerance, 0.05);
  EXPECT_LT(large.suggested_tolerance, large.feature_bound);
  EXPECT_NEAR(small.feature_bound, 0.01 / 3, 1e-9);
  ASSERT_EQ(small.verdict, ST::Gap_verdict::SUGGESTED) << small.reasoning;
  EXPECT_GT(small.suggested_tolerance, 1e-6);
  EXPECT_LT(small.suggested_tolerance, small.feature_bound);
  EXPECT_EQ(small.suggested_tolerance, whole.suggested_tolerance);
  // Each tolerance closes its own part's seam: the large part alone at its tolerance.
  Soup large_part;
  add_two_squares(large_part, 10, 0.05, 100);
  EXPECT_EQ(border_edges_after(large_part, large.suggested_tolerance), 6u);

  // Reversed points and triangles: the same parts.
  Soup reversed;
  const std::size_t n = s.points.size();
  reversed.points.assign(s.points.rbegin(), s.points.rend());
  for(auto it = s.triangles.rbegin(); it != s.triangles.rend(); ++it)
    reversed.triangles.push_back({n - 1 - (*it)[1], n - 1 - (*it)[2], n - 1 - (*it)[0]});
  const std::vector<ST::Part_gap_analysis> again = ST::analyze_gaps_per_part(reversed.points, reversed.triangles);
  ASSERT_EQ(again.size(), 2u);
  for(std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(again[i].triangles, parts[i].triangles);
    EXPECT_EQ(again[i].suggested_tolerance, parts[i].suggested_tolerance);
    EXPECT_EQ(again[i].reasoning, parts[i].reasoning);
  }
}

// The analysis per part turned into a tolerance per point (`per_part_vertex_tolerances()`) for
// the pipeline's `vertex_tolerance_map`: on the two parts above, the one tolerance of
// `analyze_gaps()` closes the small seam only, the map closes both, and no point moves farther
// than its own tolerance (a weld of u and v needs |uv| <= min(t_u, t_v)).
TEST(GapAnalysis, PerPartTolerancesThroughTheVertexMapCloseEverySeam)
{
  Soup s;
  add_two_squares(s, 0.01, 1e-6, 0);
  add_two_squares(s, 10, 0.05, 100);
  const std::vector<ST::Part_gap_analysis> parts = ST::analyze_gaps_per_part(s.points, s.triangles);
  ASSERT_EQ(parts.size(), 2u);
  ASSERT_EQ(parts[0].verdict, ST::Gap_verdict::SUGGESTED);
  ASSERT_EQ(parts[1].verdict, ST::Gap_verdict::SUGGESTED);
  EXPECT_EQ(parts[0].points, (std::vector<std::size_t>{8, 9, 10, 11, 12, 13, 14, 15}));  // the large squares
  EXPECT_EQ(parts[1].points, (std::vector<std::size_t>{0, 1, 2, 3, 4, 5, 6, 7}));
  const std::vector<double> tolerances = ST::per_part_vertex_tolerances(parts, s.points.size());
  ASSERT_EQ(tolerances.size(), s.points.size());
  for(std::size_t i = 0; i < s.points.size(); ++i)
    EXPECT_EQ(tolerances[i], i < 8 ? parts[1].suggested_tolerance : parts[0].suggested_tolerance) << i;

  // One tolerance: the small seam closes (the small outline: 6 edges), the large one stays open (8).
  const ST::Gap_analysis whole = ST::analyze_gaps(s.points, s.triangles);
  EXPECT_EQ(border_edges_after(s, whole.suggested_tolerance), 14u);

  // The map: both seams close, every weld within the tolerances of both of its points.
  struct Welds
  {
    std::vector<std::pair<std::size_t, std::size_t>> merged;
    void on_merge(std::size_t d, std::size_t r) { merged.emplace_back(d, r); }
    void on_refusal(std::size_t, std::size_t, ST::Refusal_reason) {}
  } welds;
  Soup repaired = s;
  const ST::Reconstruction_report r = ST::reconstruct_topology(
    repaired.points, repaired.triangles,
    ST::parameters::vertex_tolerance_map(CGAL::make_property_map(tolerances)).visitor(std::ref(welds)));
  EXPECT_EQ(r.border_edges_after, 12u);
  EXPECT_EQ(r.snapped_vertices, 4u);
  EXPECT_EQ(r.output_points, 12u);
  EXPECT_EQ(r.tolerance, parts[0].suggested_tolerance);  // the largest of the map
  ASSERT_EQ(welds.merged.size(), 4u);
  for(const auto& [d, rep] : welds.merged) {
    const double moved = std::sqrt(CGAL::squared_distance(s.points[d], s.points[rep]));
    EXPECT_LE(moved, tolerances[d]);
    EXPECT_LE(moved, tolerances[rep]);
  }
  EXPECT_LE(r.max_displacement, parts[0].suggested_tolerance);

  // A point of no part (unused) gets 0; a part without suggestion gives 0 to its points.
  std::vector<ST::Part_gap_analysis> no_suggestion = parts;
  no_suggestion[0].verdict = ST::Gap_verdict::OVERLAP;
  const std::vector<double> partly = ST::per_part_vertex_tolerances(no_suggestion, s.points.size() + 1);
  EXPECT_EQ(partly[8], 0.0);
  EXPECT_EQ(partly[0], parts[1].suggested_tolerance);
  EXPECT_EQ(partly[16], 0.0);
  EXPECT_THROW(ST::per_part_vertex_tolerances(parts, 10), ST::Invalid_input);
  // The map gives every tolerance: the automatic tolerance is refused with it.
  Soup refused = s;
  EXPECT_THROW(ST::reconstruct_topology(refused.points, refused.triangles,
                                        ST::parameters::automatic_tolerance(
                                          true, ST::parameters::vertex_tolerance_map(CGAL::make_property_map(tolerances)))),
               ST::Invalid_input);
  EXPECT_EQ(refused.points, s.points);
  EXPECT_EQ(refused.triangles, s.triangles);
}

TEST(GapAnalysis, RejectsInvalidSoups)
{
  std::vector<Point> points = {Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0)};
  std::vector<Triangle> out_of_range = {{0, 1, 3}};
  EXPECT_THROW(ST::analyze_gaps(points, out_of_range), ST::Invalid_input);
  std::vector<Triangle> repeated = {{0, 1, 1}};
  EXPECT_THROW(ST::analyze_gaps(points, repeated), ST::Invalid_input);
  points[2] = Point(std::nan(""), 0, 0);
  std::vector<Triangle> one = {{0, 1, 2}};
  EXPECT_THROW(ST::analyze_gaps(points, one), ST::Invalid_input);
}

// A 12 x 12 grid of squares over the unit square in four patches, each with its own copies of
// its points, every copy jittered by 10^u with u uniform in [-7, -1.5]: gaps from 1e-7 to beyond
// the grid step.
Soup jittered_patches()
{
  const std::size_t n = 12;
  std::mt19937_64 random(11);
  std::uniform_real_distribution<double> exponent(-7, -1.5), direction(-1, 1);
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  for(std::size_t patch = 0; patch < 4; ++patch) {
    const std::size_t i0 = (patch % 2) * n / 2, j0 = (patch / 2) * n / 2;
    const std::size_t first = points.size();
    for(std::size_t i = 0; i <= n / 2; ++i)
      for(std::size_t j = 0; j <= n / 2; ++j) {
        const double size = std::pow(10.0, exponent(random));
        const double x = double(i0 + i) / double(n), y = double(j0 + j) / double(n);
        points.emplace_back(x + size * direction(random), y + size * direction(random),
                            0.1 * std::sin(3 * x + 2 * y) + size * direction(random));
      }
    auto at = [&](std::size_t i, std::size_t j) { return first + i * (n / 2 + 1) + j; };
    for(std::size_t i = 0; i < n / 2; ++i)
      for(std::size_t j = 0; j < n / 2; ++j) {
        triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
        triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      }
  }
  return Soup{points, triangles};
}

// The nearest border element of every border vertex, from the two passes of
// nearest_border_elements(), equals a brute-force search over all border vertices and edges with
// the same exact radius test and the same preference rules, at radii where most vertices are
// decided by the first pass and where few are. Also with the soup scaled by 1e150, where squared
// distances to edges overflow: an infinite distance is no answer, for the search as for the brute
// force (analyze_gaps() scales such a soup by a power of two first, and never searches it so).
TEST(GapAnalysis, NearestBorderElementsMatchBruteForce)
{
  const Soup s = jittered_patches();
  const std::vector<Triangle>& triangles = s.triangles;
  const ST::Adjacency_tables tables(triangles, s.points.size());
  const std::vector<std::size_t> border = ST::internal::border_vertices(tables);
  ASSERT_GT(border.size(), 40u);
  const Epick gt;
  auto squared_distance = gt.compute_squared_distance_3_object();
  auto compare = gt.compare_squared_distance_3_object();
  for(double scale : {1.0, 1e150}) {
    std::vector<Point> points;
    for(const Point& p : s.points) points.emplace_back(p.x() * scale, p.y() * scale, p.z() * scale);
    for(double unit_radius : {1e-4, 0.01, 0.05, 0.2, 2.0}) {
      const double radius = unit_radius * scale;
      const auto found = ST::internal::nearest_border_elements(points, tables, border, radius, gt);
      ASSERT_EQ(found.size(), border.size());
      const double r2 = radius * radius;
      std::size_t decided = 0;
      for(std::size_t k = 0; k < border.size(); ++k) {
        const std::size_t v = border[k];
        ST::internal::Nearest_border_element best;
        for(std::size_t w : border) {
          if(w == v || ST::internal::share_a_triangle(tables, v, w) ||
             compare(points[v], points[w], r2) == CGAL::LARGER)
            continue;
          const double d = std::sqrt(CGAL::to_double(squared_distance(points[v], points[w])));
          if(d < best.distance || (d == best.distance && w < best.vertex)) { best.distance = d; best.vertex = w; }
        }
        for(std::size_t t = 0; t < triangles.size(); ++t)
          for(int i = 0; i < 3; ++i) {
            const auto tt = static_cast<ST::Adjacency_tables::size_type>(t);
            const Triangle& tr = triangles[t];
            if(!tables.is_border_edge(tt, i) || tr[0] == v || tr[1] == v || tr[2] == v) continue;
            const Epick::Segment_3 e(points[tr[std::size_t(i)]], points[tr[std::size_t((i + 1) % 3)]]);
            if(compare(points[v], e, r2) == CGAL::LARGER) continue;
            const double d = std::sqrt(CGAL::to_double(squared_distance(points[v], e)));
            if(d < best.distance) { best.distance = d; best.vertex = std::size_t(-1); best.edge = {tt, i}; }
          }
        const std::string where = "scale " + std::to_string(scale) + ", radius " + std::to_string(unit_radius) +
                                  ", vertex " + std::to_string(v);
        EXPECT_EQ(found[k].distance, best.distance) << where;
        EXPECT_EQ(found[k].vertex, best.vertex) << where;
        EXPECT_EQ(found[k].edge, best.edge) << where;
        if(best.distance < radius * ST::internal::first_gap_pass_fraction) ++decided;
      }
      // Both passes are exercised: some answers lie within the first radius, some beyond.
      if(unit_radius == 0.2) {
        EXPECT_GT(decided, 0u);
        EXPECT_LT(decided, border.size());
      }
    }
  }
}

// `s` with every coordinate times 2^k (exactly: no coordinate of the soups below leaves the
// normal numbers).
Soup scaled_soup(const Soup& s, int k)
{
  Soup out{{}, s.triangles};
  for(const Point& p : s.points)
    out.points.emplace_back(std::ldexp(p.x(), k), std::ldexp(p.y(), k), std::ldexp(p.z(), k));
  return out;
}

void expect_scaled(const ST::Size_distribution& a, const ST::Size_distribution& b, int k, const std::string& what)
{
  EXPECT_EQ(b.count, a.count) << what;
  EXPECT_EQ(b.minimum, std::ldexp(a.minimum, k)) << what;
  EXPECT_EQ(b.median, std::ldexp(a.median, k)) << what;
  EXPECT_EQ(b.maximum, std::ldexp(a.maximum, k)) << what;
}

// A file in the wrong unit, or generated at an odd scale, has coordinates near 1e-270 or 1e300:
// squared lengths leave the range of doubles there (distances to edges came out infinite, gaps
// and heights 0, and the suggestion changed with the unit). The analysis of the soup scaled by
// 2^k is that of the soup, scaled by 2^k, to the bit: gaps, features, bound and suggestion, the
// parts and their tolerances, and the automatic repair closes the same seams. (k even: the
// suggestion, a geometric mean, is then scaled exactly too.)
TEST(GapAnalysis, AnalysisDoesNotDependOnTheScale)
{
  for(const auto& [name, soup] : {std::make_pair(std::string("TO-220"), load("cad/kicad/TO-220-3_Vertical.wrl")),
                                  std::make_pair(std::string("jittered patches"), jittered_patches())}) {
    const ST::Gap_analysis a = ST::analyze_gaps(soup.points, soup.triangles);
    const std::vector<ST::Part_gap_analysis> parts = ST::analyze_gaps_per_part(soup.points, soup.triangles);
    Soup repaired = soup;
    const ST::Reconstruction_report r =
      ST::reconstruct_topology(repaired.points, repaired.triangles, ST::parameters::automatic_tolerance(true));
    ASSERT_EQ(a.verdict, ST::Gap_verdict::SUGGESTED) << name << ": " << a.reasoning;
    ASSERT_GT(a.gaps.size(), 4u) << name;
    // (-120 and 120: measured as they are; the others on a copy scaled back to the unit)
    for(int k : {-900, -500, -140, -120, 120, 500, 1000}) {
      const std::string what = name + ", 2^" + std::to_string(k);
      const Soup scaled = scaled_soup(soup, k);
      const ST::Gap_analysis b = ST::analyze_gaps(scaled.points, scaled.triangles);
      EXPECT_EQ(b.verdict, a.verdict) << what << ": " << b.reasoning;
      EXPECT_EQ(b.vertices, a.vertices) << what;
      EXPECT_EQ(b.border_vertices, a.border_vertices) << what;
      EXPECT_EQ(b.degenerate_triangles, a.degenerate_triangles) << what;
      EXPECT_EQ(b.bounding_box_diagonal, std::ldexp(a.bounding_box_diagonal, k)) << what;
      EXPECT_EQ(b.search_radius, std::ldexp(a.search_radius, k)) << what;
      ASSERT_EQ(b.gaps.size(), a.gaps.size()) << what;
      for(std::size_t i = 0; i < a.gaps.size(); ++i)
        EXPECT_EQ(b.gaps[i], std::ldexp(a.gaps[i], k)) << what << ", gap " << i;
      EXPECT_EQ(b.gaps_beyond_search_radius, a.gaps_beyond_search_radius) << what;
      EXPECT_EQ(b.zero_gaps, a.zero_gaps) << what;
      expect_scaled(a.shortest_edges, b.shortest_edges, k, what + ", shortest edges");
      expect_scaled(a.smallest_heights, b.smallest_heights, k, what + ", smallest heights");
      expect_scaled(a.border_features, b.border_features, k, what + ", border features");
      EXPECT_EQ(b.feature_bound, std::ldexp(a.feature_bound, k)) << what;
      EXPECT_EQ(b.suggested_tolerance, std::ldexp(a.suggested_tolerance, k)) << what;
      EXPECT_EQ(b.closed_gaps, a.closed_gaps) << what;
      EXPECT_EQ(b.closing_margin, a.closing_margin) << what;
      EXPECT_EQ(b.keeping_margin, a.keeping_margin) << what;

      const std::vector<ST::Part_gap_analysis> scaled_parts =
        ST::analyze_gaps_per_part(scaled.points, scaled.triangles);
      ASSERT_EQ(scaled_parts.size(), parts.size()) << what;
      for(std::size_t i = 0; i < parts.size(); ++i) {
        EXPECT_EQ(scaled_parts[i].verdict, parts[i].verdict) << what << ", part " << i;
        EXPECT_EQ(scaled_parts[i].feature_bound, std::ldexp(parts[i].feature_bound, k)) << what << ", part " << i;
        EXPECT_EQ(scaled_parts[i].suggested_tolerance, std::ldexp(parts[i].suggested_tolerance, k)) << what;
        EXPECT_EQ(scaled_parts[i].points, parts[i].points) << what << ", part " << i;
      }

      Soup scaled_repaired = scaled;
      const ST::Reconstruction_report rb = ST::reconstruct_topology(
        scaled_repaired.points, scaled_repaired.triangles, ST::parameters::automatic_tolerance(true));
      EXPECT_EQ(rb.tolerance, std::ldexp(r.tolerance, k)) << what;
      EXPECT_EQ(rb.border_edges_after, r.border_edges_after) << what;
      EXPECT_EQ(scaled_repaired.triangles, repaired.triangles) << what;
      EXPECT_EQ(scaled_repaired.points, scaled_soup(repaired, k).points) << what;
    }
  }
}

// A 1 MB-class hostile soup: 20,000 separate triangles of edge ~0.5 scattered in the unit cube.
// Every border vertex lies within the search radius (the median border edge) of a large part of
// the others: listing them all is quadratic (minutes), so the analysis stops at its candidate
// budget with a clear error instead.
TEST(GapAnalysis, CrowdedBordersStopAtTheCandidateBudget)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  soup_test::crowded_scattered_soup(20000, points, triangles);
  try {
    ST::analyze_gaps(points, triangles);
    ADD_FAILURE() << "not refused";
  } catch(const ST::Invalid_input& e) {
    EXPECT_NE(std::string(e.what()).find("too crowded"), std::string::npos) << e.what();
  }
}

// The soup `s` as an OFF file whose coordinates read back as the same doubles.
void write_off(const std::string& file, const Soup& s)
{
  std::ofstream out(file);
  out.precision(17);
  out << "OFF\n" << s.points.size() << " " << s.triangles.size() << " 0\n";
  for(const Point& p : s.points) out << p.x() << " " << p.y() << " " << p.z() << "\n";
  for(const Triangle& t : s.triangles) out << "3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
}

// The value of `"key": x` in a one-line JSON object, as the double it reads back as.
double json_double(const std::string& json, const std::string& key)
{
  const std::string pattern = "\"" + key + "\": ";
  const std::size_t at = json.find(pattern);
  return at == std::string::npos ? std::nan("") : std::strtod(json.c_str() + at + pattern.size(), nullptr);
}

ST::Reconstruction_report automatic_repair(Soup& s)
{
  return ST::reconstruct_topology(s.points, s.triangles, ST::parameters::automatic_tolerance(true));
}

// The named parameter automatic_tolerance(true) runs the analysis and repairs at the tolerance it
// suggests, with the verdict and the reasoning in the report: the same tolerance and the same
// result as `soup_topology repair --tolerance auto` on the same soup.
TEST(GapAnalysis, AutomaticToleranceOfThePipelineEqualsTheTool)
{
  const Soup mesh = load("clean/elephant.off");
  Soup soup;
  const ST::Gap_analysis a = analyze_jittered(mesh, 1e-6, 23, soup);
  ASSERT_EQ(a.verdict, ST::Gap_verdict::SUGGESTED) << a.reasoning;
  Soup repaired = soup;
  const ST::Reconstruction_report r = automatic_repair(repaired);
  EXPECT_TRUE(r.automatic_tolerance);
  EXPECT_EQ(r.tolerance, a.suggested_tolerance);
  EXPECT_EQ(r.tolerance_verdict, ST::Gap_verdict::SUGGESTED);
  EXPECT_EQ(r.tolerance_reasoning, a.reasoning);
  EXPECT_EQ(r.border_edges_after, 0u);
  // The same as the hand-given tolerance.
  Soup by_hand = soup;
  const ST::Reconstruction_report h =
    ST::reconstruct_topology(by_hand.points, by_hand.triangles, CGAL::parameters::snapping_tolerance(a.suggested_tolerance));
  EXPECT_FALSE(h.automatic_tolerance);
  EXPECT_EQ(repaired.points, by_hand.points);
  EXPECT_EQ(repaired.triangles, by_hand.triangles);

  if(cli().empty()) GTEST_SKIP() << "the tool is not built";
  const std::string dir = soup_test::temporary_folder("automatic_tolerance");
  write_off(dir + "/jittered.off", soup);
  const auto [json, code] = soup_test::run_command(cli() + " repair '" + dir + "/jittered.off' -o '" + dir +
                                                   "/repaired.off' --tolerance auto --json");
  ASSERT_EQ(code, 0) << json;
  EXPECT_EQ(json_double(json, "tolerance"), r.tolerance) << json;
  EXPECT_NE(json.find("\"tolerance_choice\": \"suggested: " + r.tolerance_reasoning + "\""), std::string::npos) << json;
  EXPECT_EQ(soup_test::json_integer(json, "border_edges_after"), static_cast<long long>(r.border_edges_after));
  EXPECT_EQ(soup_test::json_integer(json, "soup_triangles"), static_cast<long long>(r.output_triangles));
  EXPECT_EQ(soup_test::json_integer(json, "soup_vertices"), static_cast<long long>(r.output_points));
  EXPECT_EQ(soup_test::json_integer(json, "snapped_vertices"), static_cast<long long>(r.snapped_vertices));
}

// No suggestion (the pig's gaps and features overlap): the pipeline throws, the soup unchanged,
// as the tool refuses; a tolerance given with it is refused too.
TEST(GapAnalysis, AutomaticToleranceRefusesWithoutSuggestion)
{
  const Soup pig = load("cgal_repair/pig.stl.xz");
  Soup s = pig;
  try {
    automatic_repair(s);
    ADD_FAILURE() << "not refused";
  } catch(const ST::Invalid_input& e) {
    EXPECT_NE(std::string(e.what()).find("overlap"), std::string::npos) << e.what();
  }
  EXPECT_EQ(s.points, pig.points);
  EXPECT_EQ(s.triangles, pig.triangles);
  EXPECT_THROW(ST::reconstruct_topology(s.points, s.triangles,
                                        ST::parameters::automatic_tolerance(true, CGAL::parameters::snapping_tolerance(0.1))),
               ST::Invalid_input);
  EXPECT_EQ(s.points, pig.points);
  // automatic_tolerance(false) is the tolerance given.
  const ST::Reconstruction_report r = ST::reconstruct_topology(
    s.points, s.triangles, ST::parameters::automatic_tolerance(false, CGAL::parameters::snapping_tolerance(0.3)));
  EXPECT_FALSE(r.automatic_tolerance);
  EXPECT_EQ(r.tolerance, 0.3);

  if(cli().empty()) GTEST_SKIP() << "the tool is not built";
  const std::string dir = soup_test::temporary_folder("automatic_tolerance_pig");
  const auto [refused, code] = soup_test::run_command(cli() + " repair '" + soup_test::data_file("cgal_repair/pig.stl.xz") +
                                                      "' -o '" + dir + "/pig.off' --tolerance auto 2>&1");
  EXPECT_EQ(code, 2) << refused;
  EXPECT_NE(refused.find("overlap"), std::string::npos) << refused;
}

// The same soup in another order (points, triangles, corners): the same tolerance, reasoning and
// result counts.
TEST(GapAnalysis, AutomaticToleranceDoesNotDependOnTheOrder)
{
  const Soup mesh = load("clean/fandisk.off.xz");
  Soup soup;
  analyze_jittered(mesh, 1e-5, 29, soup);
  Soup shuffled = shuffled_soup(soup, 31);
  const ST::Reconstruction_report a = automatic_repair(soup);
  const ST::Reconstruction_report b = automatic_repair(shuffled);
  EXPECT_TRUE(a.automatic_tolerance);
  EXPECT_EQ(a.tolerance, b.tolerance);
  EXPECT_EQ(a.tolerance_verdict, b.tolerance_verdict);
  EXPECT_EQ(a.tolerance_reasoning, b.tolerance_reasoning);
  EXPECT_EQ(a.border_edges_after, b.border_edges_after);
  EXPECT_EQ(a.output_triangles, b.output_triangles);
  EXPECT_EQ(a.output_points, b.output_points);
  EXPECT_EQ(a.border_edges_after, 0u);
}

// The analysis of a soup exactly welded already (as the tool reads it) equals that of the
// public function, which welds its own copy.
TEST(GapAnalysis, ExactlyWeldedSoupIsNotWeldedAgain)
{
  for(const char* file : {"cgal_repair/pig.stl.xz", "cad/kicad/TO-220-3_Vertical.wrl", "cad/ALSTOM_TEST4.off"}) {
    SCOPED_TRACE(file);
    const Soup s = load(file);
    const ST::Gap_analysis a = ST::analyze_gaps(s.points, s.triangles);
    std::vector<Point> points;
    std::vector<Triangle> triangles;
    ST::IO::read_triangle_soup(soup_test::data_file(file), points, triangles);
    points.push_back(Point(1e3, 1e3, 1e3)); // a point no triangle uses is ignored
    const ST::Gap_analysis b = ST::internal::analyze_exactly_welded_gaps(points, triangles, Epick());
    EXPECT_EQ(a.vertices, b.vertices);
    EXPECT_EQ(a.triangles, b.triangles);
    EXPECT_EQ(a.border_vertices, b.border_vertices);
    EXPECT_EQ(a.bounding_box_diagonal, b.bounding_box_diagonal);
    EXPECT_EQ(a.gaps, b.gaps);
    EXPECT_EQ(a.border_features.minimum, b.border_features.minimum);
    EXPECT_EQ(a.verdict, b.verdict);
    EXPECT_TRUE(a.suggested_tolerance == b.suggested_tolerance ||
                (std::isnan(a.suggested_tolerance) && std::isnan(b.suggested_tolerance)));
    EXPECT_EQ(a.reasoning, b.reasoning);
  }
}

TEST(GapsCommand, PrintsTheAnalysisAndRepairsWithAutomaticTolerance)
{
  if(cli().empty()) GTEST_SKIP() << "the tool is not built";
  const std::string to220 = soup_test::data_file("cad/kicad/TO-220-3_Vertical.wrl");
  const auto [json, code] = soup_test::run_command(cli() + " gaps '" + to220 + "' --json");
  ASSERT_EQ(code, 0) << json;
  EXPECT_NE(json.find("\"verdict\": \"suggested\""), std::string::npos) << json;
  EXPECT_EQ(soup_test::json_integer(json, "border_edges"), 10);
  const auto [text, code_text] = soup_test::run_command(cli() + " gaps '" + to220 + "'");
  EXPECT_EQ(code_text, 0);
  EXPECT_NE(text.find("suggested_tolerance"), std::string::npos) << text;

  const std::string dir = soup_test::temporary_folder("gaps_auto");
  const auto [repair, code_repair] =
    soup_test::run_command(cli() + " repair '" + to220 + "' -o '" + dir + "/to220.off' --tolerance auto --json --check");
  EXPECT_EQ(code_repair, 0) << repair;
  EXPECT_EQ(soup_test::json_integer(repair, "border_edges_after"), 0);
  EXPECT_NE(repair.find("\"tolerance_choice\": \"suggested: closes"), std::string::npos) << repair;

  // No suggestion: exit code 2, the reason on stderr, nothing written.
  const std::string pig = soup_test::data_file("cgal_repair/pig.stl.xz");
  const auto [refused, code_refused] = soup_test::run_command(cli() + " repair '" + pig + "' -o '" + dir +
                                                              "/pig.off' --tolerance auto 2>&1");
  EXPECT_EQ(code_refused, 2) << refused;
  EXPECT_NE(refused.find("overlap"), std::string::npos) << refused;
  EXPECT_FALSE(std::filesystem::exists(dir + "/pig.off"));

  const auto [usage, code_usage] = soup_test::run_command(cli() + " gaps 2>&1");
  EXPECT_EQ(code_usage, 2) << usage;
  const auto [both, code_both] = soup_test::run_command(cli() + " repair '" + to220 + "' -o '" + dir +
                                                        "/x.off' --tolerance auto --relative-tolerance 1e-6 2>&1");
  EXPECT_EQ(code_both, 2) << both;
}

// `soup_topology repair --tolerance per-part`: the analysis per part and the pipeline's
// vertex_tolerance_map through the tool. On the two parts of different scales both seams close
// (the outline of each part is left: 6 + 6 border edges), where `--tolerance auto` closes the
// small seam only (14); the report gives the largest tolerance of the map and the choice per part.
TEST(GapAnalysis, ToolRepairsEachPartWithItsOwnTolerance)
{
  if(cli().empty()) GTEST_SKIP() << "the tool is not built";
  Soup s;
  add_two_squares(s, 0.01, 1e-6, 0);
  add_two_squares(s, 10, 0.05, 100);
  const std::vector<ST::Part_gap_analysis> parts = ST::analyze_gaps_per_part(s.points, s.triangles);
  ASSERT_EQ(parts.size(), 2u);
  const std::string dir = soup_test::temporary_folder("per_part_tolerance");
  write_off(dir + "/parts.off", s);
  const std::string repair = cli() + " repair '" + dir + "/parts.off' -o '" + dir + "/repaired.off' ";
  const auto [json, code] = soup_test::run_command(repair + "--tolerance per-part --json");
  ASSERT_EQ(code, 0) << json;
  EXPECT_EQ(soup_test::json_integer(json, "soup_border_edges"), 12) << json;
  EXPECT_EQ(soup_test::json_integer(json, "snapped_vertices"), 4) << json;
  EXPECT_EQ(json_double(json, "tolerance"), parts[0].suggested_tolerance) << json;
  EXPECT_NE(json.find("\"tolerance_choice\": \"per part: 2 parts: 4 triangles, tolerance "), std::string::npos) << json;
  const auto [automatic, automatic_code] = soup_test::run_command(repair + "--tolerance auto --json");
  ASSERT_EQ(automatic_code, 0) << automatic;
  EXPECT_EQ(soup_test::json_integer(automatic, "soup_border_edges"), 14) << automatic;
  const auto [both, both_code] = soup_test::run_command(repair + "--tolerance per-part --relative-tolerance 1e-3 2>&1");
  EXPECT_EQ(both_code, 2) << both;
  EXPECT_NE(both.find("give --tolerance or --relative-tolerance, not both"), std::string::npos) << both;
  std::filesystem::remove_all(dir);
}

// An assembly of many parts: the report lists the ten largest parts and sums up the others,
// and every seam is still closed with its own part's tolerance.
TEST(GapAnalysis, ToolListsTenPartsAndSumsUpTheOthers)
{
  if(cli().empty()) GTEST_SKIP() << "the tool is not built";
  Soup s;
  for(int k = 0; k < 13; ++k) add_two_squares(s, 0.01 * (k + 1), 1e-6 * (k + 1), 100.0 * k);
  const std::string dir = soup_test::temporary_folder("many_parts_tolerance");
  write_off(dir + "/parts.off", s);
  const auto [json, code] = soup_test::run_command(cli() + " repair '" + dir + "/parts.off' -o '" + dir +
                                                   "/repaired.off' --tolerance per-part --json");
  ASSERT_EQ(code, 0) << json;
  EXPECT_EQ(soup_test::json_integer(json, "snapped_vertices"), 2 * 13) << json;
  EXPECT_NE(json.find("\"tolerance_choice\": \"per part: 13 parts: 4 triangles, tolerance "), std::string::npos) << json;
  EXPECT_NE(json.find("; 3 more parts, 3 with a suggestion, tolerances "), std::string::npos) << json;
  std::size_t listed = 0;
  for(std::size_t at = json.find("triangles, tolerance "); at != std::string::npos; at = json.find("triangles, tolerance ", at + 1))
    ++listed;
  EXPECT_EQ(listed, 10u) << json;
  std::filesystem::remove_all(dir);
}

// A soup too crowded to analyse is refused by both automatic choices of the tool with the same
// advice (give the tolerance by hand), and nothing is written.
TEST(GapAnalysis, ToolRefusesACrowdedSoupUnderAutoAndPerPartWithTheSameAdvice)
{
  if(cli().empty()) GTEST_SKIP() << "the tool is not built";
  Soup s;
  soup_test::crowded_scattered_soup(20000, s.points, s.triangles);
  const std::string dir = soup_test::temporary_folder("crowded_automatic_tolerance");
  write_off(dir + "/crowded.off", s);
  for(const std::string choice : {"auto", "per-part"}) {
    SCOPED_TRACE(choice);
    const auto [message, code] = soup_test::run_command(cli() + " repair '" + dir + "/crowded.off' -o '" + dir +
                                                        "/repaired.off' --tolerance " + choice + " 2>&1");
    EXPECT_EQ(code, 2) << message;
    EXPECT_NE(message.find("--tolerance " + choice + ": gap analysis:"), std::string::npos) << message;
    EXPECT_NE(message.find("too crowded"), std::string::npos) << message;
    EXPECT_NE(message.find("with --tolerance T (see 'soup_topology gaps')"), std::string::npos) << message;
    EXPECT_FALSE(std::filesystem::exists(dir + "/repaired.off"));
  }
  std::filesystem::remove_all(dir);
}

} // namespace

} // namespace gap_analysis_test
