// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// libFuzzer target: the pipeline. The bytes become a small indexed soup (up to 12 points, 12
// triangles) whose coordinates are either on a coarse grid with tiny offsets (so that welds and
// T-junctions happen) or arbitrary doubles (NaN, infinities, denormals, huge values), whose
// indices may be out of range or repeated, and a tolerance (absolute or relative) that may be
// negative, NaN, infinite, tiny or huge. Then:
//  - reconstruct_topology() either throws Invalid_input, only for input that is invalid, leaving
//    the caller's containers as they were, or returns a soup whose indices are in range and
//    distinct, whose points are input points, with no collinear triangle unless the input had
//    one, with no point moved farther than the tolerance, and with symmetric adjacency tables;
//  - snap_vertices() and split_t_junctions() run by hand on the exactly welded soup leave
//    tables, updated locally, equal to tables rebuilt from the resulting triangles.

#include "fuzz_common.h"

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/index_triangles.h>
#include <Soup_topology/reconstruct_topology.h>
#include <Soup_topology/snap_vertices.h>
#include <Soup_topology/split_t_junctions.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <set>
#include <tuple>

namespace {

using soup_fuzz::Point;
using soup_fuzz::Triangle;
namespace ST = Soup_topology;

class Bytes
{
public:
  Bytes(const std::uint8_t* d, std::size_t n) : d_(d), n_(n) {}
  std::uint8_t byte() { return i_ < n_ ? d_[i_++] : 0; }
  double raw_double()
  {
    std::uint8_t b[8] = {0, 0, 0, 0, 0, 0, 0, 0};
    for(auto& x : b) x = byte();
    double v;
    std::memcpy(&v, b, sizeof v);
    return v;
  }
private:
  const std::uint8_t* d_;
  std::size_t n_;
  std::size_t i_ = 0;
};

double coordinate(Bytes& in)
{
  static const double special[] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                                   -std::numeric_limits<double>::infinity(), std::numeric_limits<double>::denorm_min(),
                                   std::numeric_limits<double>::max(), -std::numeric_limits<double>::max(), 1e200,
                                   -1e-200, 1e154, 1e-310};
  static const double jitter[] = {0, 1e-3, -1e-3, 1e-9, 0.5e-1, -2.5e-17, 1e-300, 0.3};
  const std::uint8_t mode = in.byte();
  if(mode < 216) return 0.25 * static_cast<int>(mode % 9) - 1.0 + jitter[(mode / 9) % 8];
  if(mode < 246) return special[mode % 10];
  return in.raw_double();
}

double tolerance(Bytes& in)
{
  static const double table[] = {0, 1e-310, 1e-9, 1e-3, 0.01, 0.1, 0.25, 0.5, 1, 3, 1e6, 1e154, 1e300,
                                 -1, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity()};
  const std::uint8_t k = in.byte();
  if(k < 240) return table[k % 16];
  return in.raw_double();
}

bool finite(const Point& p) { return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()); }

// The tables updated in place equal the tables rebuilt from the triangles, and are symmetric.
void check_tables(const ST::Adjacency_tables& a, const std::vector<Triangle>& triangles, std::size_t n,
                  const char* when)
{
  using size_type = ST::Adjacency_tables::size_type;
  const ST::Adjacency_tables fresh(triangles, n);
  SOUP_FUZZ_CHECK(a.number_of_triangles() == triangles.size() && a.number_of_vertices() == n, when);
  for(size_type t = 0; t < a.number_of_triangles(); ++t)
    for(int i = 0; i < 3; ++i) {
      SOUP_FUZZ_CHECK(a.vertex(t, i) == triangles[t][std::size_t(i)], when);
      SOUP_FUZZ_CHECK(a.neighbor(t, i) == fresh.neighbor(t, i), std::string(when) + ": edge neighbour");
      const size_type u = fresh.neighbor(t, i);
      std::vector<size_type> around;
      fresh.triangles_around_edge(t, i, std::back_inserter(around));
      if(u == ST::Adjacency_tables::border_edge) {
        SOUP_FUZZ_CHECK(around.empty(), std::string(when) + ": border edge with a neighbour");
      } else if(u == ST::Adjacency_tables::non_manifold_edge) {
        SOUP_FUZZ_CHECK(around.size() >= 2, std::string(when) + ": non-manifold edge with one neighbour");
      } else {
        SOUP_FUZZ_CHECK(around.size() == 1 && around[0] == u, std::string(when) + ": neighbour list");
        const int j = fresh.edge_index(u, fresh.vertex(t, i), fresh.vertex(t, (i + 1) % 3));
        SOUP_FUZZ_CHECK(j >= 0 && fresh.neighbor(u, j) == t, std::string(when) + ": asymmetric neighbours");
      }
    }
  for(size_type v = 0; v < n; ++v) {
    const auto x = a.triangles_around_vertex(v), y = fresh.triangles_around_vertex(v);
    SOUP_FUZZ_CHECK(std::equal(x.begin(), x.end(), y.begin(), y.end()), std::string(when) + ": vertex table");
  }
}

template <class Np>
void run(const std::vector<Point>& input_points, const std::vector<Triangle>& input_triangles, const Np& np,
         bool expected_valid)
{
  std::vector<Point> points = input_points;
  std::vector<Triangle> triangles = input_triangles;
  ST::Reconstruction_report report;
  try {
    report = ST::reconstruct_topology(points, triangles, np);
  } catch(const ST::Invalid_input& e) {
    SOUP_FUZZ_CHECK(!expected_valid, std::string("valid input refused: ") + e.what());
    SOUP_FUZZ_CHECK(points.size() == input_points.size() &&
                      std::memcmp(points.data(), input_points.data(), points.size() * sizeof(Point)) == 0,
                    "points changed by a refused call");
    SOUP_FUZZ_CHECK(triangles == input_triangles, "triangles changed by a refused call");
    return;
  }
  SOUP_FUZZ_CHECK(expected_valid, "invalid input accepted");
  SOUP_FUZZ_CHECK(report.output_points == points.size() && report.output_triangles == triangles.size(), "report");
  for(const Triangle& t : triangles) {
    for(std::size_t v : t) SOUP_FUZZ_CHECK(v < points.size(), "index out of range in the output");
    SOUP_FUZZ_CHECK(t[0] != t[1] && t[1] != t[2] && t[2] != t[0], "repeated index in the output");
  }
  // No constructed point.
  std::set<std::tuple<double, double, double>> given;
  for(const Point& p : input_points) given.insert({p.x(), p.y(), p.z()});
  for(const Point& p : points) SOUP_FUZZ_CHECK(given.count({p.x(), p.y(), p.z()}) == 1, "a point was constructed");
  // No degenerate triangle created by us.
  bool input_degenerate = false;
  for(const Triangle& t : input_triangles) {
    const Point &a = input_points[t[0]], &b = input_points[t[1]], &c = input_points[t[2]];
    if(a != b && b != c && c != a && CGAL::collinear(a, b, c)) input_degenerate = true;
  }
  if(!input_degenerate)
    for(const Triangle& t : triangles)
      SOUP_FUZZ_CHECK(!CGAL::collinear(points[t[0]], points[t[1]], points[t[2]]), "a degenerate triangle was created");
  // No point moved farther than the tolerance (the displacement is measured in double), over all
  // rounds (corpus/pipeline/chained_welds.bin once broke this: a representative of one round was
  // welded in a later one).
  const double bound = report.tolerance;
  SOUP_FUZZ_CHECK(report.max_displacement <= bound * (1 + 1e-12),
                  "moved " + std::to_string(report.max_displacement) + " > " + std::to_string(bound) + " (tolerance " +
                    std::to_string(report.tolerance) + ", " + std::to_string(report.rounds) + " rounds)");
  // Symmetric tables of the result.
  const ST::Adjacency_tables final_tables(triangles, points.size());
  check_tables(final_tables, triangles, points.size(), "output");

  // The local updates of the tables, step by step on the exactly welded soup.
  std::vector<Point> pts = input_points;
  std::vector<Triangle> tris = input_triangles;
  ST::merge_duplicate_points(pts, tris);
  ST::remove_collapsed_triangles(tris);
  ST::Adjacency_tables tables(tris, pts.size());
  const auto weld_np = CGAL::parameters::snapping_tolerance(report.tolerance);
  ST::snap_vertices(pts, tris, tables, weld_np);
  check_tables(tables, tris, pts.size(), "after snap_vertices");
  ST::split_t_junctions(pts, tris, tables, weld_np);
  check_tables(tables, tris, pts.size(), "after split_t_junctions");
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  Bytes in(data, size);
  const std::uint8_t flags = in.byte();
  const bool relative = (flags & 1) != 0;
  const bool split = (flags & 2) != 0;
  const std::size_t number_of_points = 1 + in.byte() % 12;
  const std::size_t number_of_triangles = in.byte() % 13;
  const double tol = tolerance(in);
  std::vector<Point> points;
  for(std::size_t i = 0; i < number_of_points; ++i) {
    const double x = coordinate(in), y = coordinate(in), z = coordinate(in);
    points.push_back(Point(x, y, z));
  }
  std::vector<Triangle> triangles;
  for(std::size_t t = 0; t < number_of_triangles; ++t) {
    Triangle tr;
    for(std::size_t& v : tr) {
      const std::uint8_t b = in.byte();
      v = b == 255 ? std::numeric_limits<std::size_t>::max() : b % (number_of_points + ((flags & 4) ? 1 : 0));
    }
    triangles.push_back(tr);
  }

  // What the documentation says is valid.
  bool valid = true;
  for(const Triangle& t : triangles) {
    for(std::size_t v : t) valid = valid && v < points.size();
    valid = valid && t[0] != t[1] && t[1] != t[2] && t[2] != t[0];
  }
  for(const Point& p : points) valid = valid && finite(p);
  // The tolerance is checked at the scale the pipeline decides at: points whose largest coordinate
  // lies beyond 2^128 or below 2^-128 are scaled by a power of two first, the tolerance with them.
  const int exponent = valid ? ST::internal::moderate_scale_exponent_of(points) : 0;
  double absolute = std::ldexp(tol, exponent);
  if(relative && tol > 0 && valid)
    absolute =
      tol * std::ldexp(ST::internal::bounding_box_diagonal(points, CGAL::Identity_property_map<Point>()), exponent);
  valid = valid && tol >= 0 && std::isfinite(tol) && std::isfinite(absolute) && std::isfinite(4 * absolute * absolute);

  if(relative)
    run(points, triangles, ST::parameters::do_split_t_junctions(split, ST::parameters::relative_tolerance(tol)), valid);
  else
    run(points, triangles, ST::parameters::do_split_t_junctions(split, CGAL::parameters::snapping_tolerance(tol)), valid);
  return 0;
}
