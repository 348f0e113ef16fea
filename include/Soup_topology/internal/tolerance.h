// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The named parameters every algorithm on a soup reads, deduced in one place: the point map, the
// geometric traits, and the tolerance, absolute (`snapping_tolerance`) or relative to the
// bounding-box diagonal (`relative_tolerance`), validated once for every algorithm.

#ifndef SOUP_TOPOLOGY_INTERNAL_TOLERANCE_H
#define SOUP_TOPOLOGY_INTERNAL_TOLERANCE_H

#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/parameters.h>

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/internal/coordinate_scale.h>
#include <Soup_topology/internal/soup_checks.h>

#include <CGAL/Kernel_traits.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/number_utils.h>

#include <boost/property_map/property_map.hpp>

#include <algorithm>
#include <functional>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>
#include <type_traits>

namespace Soup_topology {
namespace internal {

/// the diagonal of the bounding box of the points, in double.
template <class PointRange, class PointMap>
double bounding_box_diagonal(const PointRange& points, const PointMap& pm)
{
  double lo[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                  std::numeric_limits<double>::infinity()};
  double hi[3] = {-lo[0], -lo[1], -lo[2]};
  bool any = false;
  for(const auto& e : points) {
    const auto& p = get(pm, e);
    const double c[3] = {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
    for(int k = 0; k < 3; ++k) { lo[k] = std::min(lo[k], c[k]); hi[k] = std::max(hi[k], c[k]); }
    any = true;
  }
  if(!any) return 0;
  // The sides are scaled by the longest one before squaring: squaring sides near 1e300 would
  // overflow although the diagonal, at most sqrt(3) times the longest side, is finite. A side
  // itself overflows only when the box spans more than the largest double (then infinity).
  const double side[3] = {hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]};
  const double longest = std::max(side[0], std::max(side[1], side[2]));
  if(longest == 0 || !std::isfinite(longest)) return longest;
  const double u[3] = {side[0] / longest, side[1] / longest, side[2] / longest};
  return longest * std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
}

/// the absolute tolerance given by `np`: `snapping_tolerance` if present, else
/// `relative_tolerance` times the bounding-box diagonal, else 0; times 2^exponent, for points
/// that the caller scales by 2^exponent (`moderate_scale_exponent()`), and checked at that scale.
/// \throws Invalid_input if it is negative, NaN or infinite, or if both are given.
template <class FT, class PointRange, class PointMap, class NamedParameters>
FT resolve_tolerance(const PointRange& points, const PointMap& pm, const NamedParameters& np, int exponent = 0)
{
  using CGAL::parameters::get_parameter;
  using CGAL::parameters::is_default_parameter;
  constexpr bool has_absolute = !is_default_parameter<NamedParameters, CGAL::internal_np::snapping_tolerance_t>::value;
  constexpr bool has_relative = !is_default_parameter<NamedParameters, internal_np::relative_tolerance_t>::value;
  static_assert(!(has_absolute && has_relative), "give either snapping_tolerance or relative_tolerance, not both");
  // The predicates compare squared distances with the squared tolerance and with the square of
  // twice the tolerance (split_t_junctions): neither may overflow (an infinite bound reaches
  // GMP's exact conversion, which raises SIGFPE on infinity). The largest accepted is ~6.7e153.
  const auto text = [](double x) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", x);
    return std::string(buffer);
  };
  const auto check_square = [&](double e, const char* what) {
    if(!std::isfinite(4 * e * e))
      throw Invalid_input(std::string(what) + " is too large (" + text(e) +
                          "): the square of twice its value overflows a double");
  };
  if constexpr(has_absolute) {
    const FT given = FT(get_parameter(np, CGAL::internal_np::snapping_tolerance));
    const double e = CGAL::to_double(given);
    if(!(e >= 0) || !std::isfinite(e))
      throw Invalid_input("the tolerance must be a finite number >= 0 (got " + std::to_string(e) + ")");
    if(exponent == 0) {
      check_square(e, "the tolerance");
      return given;
    }
    const FT eps = given * FT(std::ldexp(1.0, exponent));
    check_square(CGAL::to_double(eps), "the tolerance, at the scale of the points,");
    return eps;
  } else if constexpr(has_relative) {
    const double r = static_cast<double>(get_parameter(np, internal_np::relative_tolerance));
    if(!(r >= 0) || !std::isfinite(r))
      throw Invalid_input("the relative tolerance must be a finite number >= 0 (got " + std::to_string(r) + ")");
    if(r == 0) return FT(0);
    const double e = r * std::ldexp(bounding_box_diagonal(points, pm), exponent);
    if(!std::isfinite(e))
      throw Invalid_input("the relative tolerance " + text(r) + " gives a non-finite absolute tolerance "
                          "(the bounding-box diagonal overflows a double)");
    check_square(e, "the absolute tolerance given by the relative tolerance");
    return FT(e);
  } else {
    return FT(0);
  }
}

/// whether `np` holds a `vertex_tolerance_map`.
template <class NamedParameters>
constexpr bool has_vertex_tolerance_map()
{
  return !CGAL::parameters::is_default_parameter<NamedParameters, internal_np::vertex_tolerance_map_t>::value;
}

/// The per-vertex tolerances that `reconstruct_topology()` hands to `snap_vertices()` and
/// `split_t_junctions()` in every round: a readable property map over a vector that was read and
/// checked once, which those functions then use as it is (no copy, no second check).
template <class FT>
struct Vertex_tolerance_vector
{
  using key_type = std::size_t;
  using value_type = FT;
  using reference = const FT&;
  using category = boost::readable_property_map_tag;
  const std::vector<FT>* values = nullptr;
  friend reference get(const Vertex_tolerance_vector& map, std::size_t i) { return (*map.values)[i]; }
};

/// \throws Invalid_input if `np` gives a `vertex_tolerance_map` together with `snapping_tolerance`,
/// `relative_tolerance` or `automatic_tolerance(true)`: the map gives every tolerance.
template <class NamedParameters>
void check_vertex_tolerance_map_alone(const NamedParameters& np, const char* function)
{
  using CGAL::parameters::is_default_parameter;
  if constexpr(has_vertex_tolerance_map<NamedParameters>()) {
    constexpr bool has_absolute = !is_default_parameter<NamedParameters, CGAL::internal_np::snapping_tolerance_t>::value;
    constexpr bool has_relative = !is_default_parameter<NamedParameters, internal_np::relative_tolerance_t>::value;
    if(has_absolute || has_relative)
      throw Invalid_input(std::string(function) + ": vertex_tolerance_map gives the tolerance of every point: give no "
                          "snapping_tolerance or relative_tolerance with it");
    if constexpr(!is_default_parameter<NamedParameters, internal_np::automatic_tolerance_t>::value)
      if(CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, internal_np::automatic_tolerance), false))
        throw Invalid_input(std::string(function) + ": vertex_tolerance_map gives the tolerance of every point: "
                            "automatic_tolerance(true) cannot be given with it");
  } else {
    (void)np; (void)function;
  }
}

/// the tolerance `value` of point `i` of a `vertex_tolerance_map` times 2^exponent (see
/// `resolve_tolerance()`), checked as `resolve_tolerance()` checks one tolerance.
/// \throws Invalid_input if it is negative, NaN, infinite or too large.
template <class FT, class Value>
FT checked_vertex_tolerance(const Value& value, std::size_t i, const char* function, int exponent = 0)
{
  // (checked as given; the square, at the scale of the points)
  const FT scaled = exponent == 0 ? FT(value) : FT(value) * FT(std::ldexp(1.0, exponent));
  const double e = CGAL::to_double(value);
  const auto text = [](double x) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%g", x);
    return std::string(buffer);
  };
  if(!(e >= 0) || !std::isfinite(e))
    throw Invalid_input(std::string(function) + ": the tolerance of point " + std::to_string(i) +
                        " (vertex_tolerance_map) must be a finite number >= 0 (got " + text(e) + ")");
  const double at_scale = CGAL::to_double(scaled);
  if(!std::isfinite(4 * at_scale * at_scale))
    throw Invalid_input(std::string(function) + ": the tolerance of point " + std::to_string(i) +
                        " (vertex_tolerance_map) is too large (" + text(e) +
                        "): the square of twice its value overflows a double");
  return scaled;
}

/// the tolerances of the points 0, ..., n - 1 given by the `vertex_tolerance_map` of `np`, or
/// `nullptr` when `np` has none (one tolerance for all). They are read once, times 2^exponent
/// (see `resolve_tolerance()`), and checked into `storage`, unless the map is a
/// `Vertex_tolerance_vector` of `n` values (the pipeline's, already checked and at the scale of
/// its points), which is used as it is.
/// \throws Invalid_input for a bad value, or for a map given with another tolerance parameter.
template <class FT, class NamedParameters>
const std::vector<FT>* read_vertex_tolerances(const NamedParameters& np, std::size_t n, std::vector<FT>& storage,
                                              const char* function, int exponent = 0)
{
  if constexpr(has_vertex_tolerance_map<NamedParameters>()) {
    check_vertex_tolerance_map_alone(np, function);
    const auto map = CGAL::parameters::get_parameter(np, internal_np::vertex_tolerance_map);
    if constexpr(std::is_same<std::decay_t<decltype(map)>, Vertex_tolerance_vector<FT>>::value) {
      if(map.values->size() != n)
        throw Invalid_input(std::string(function) + ": the vertex tolerances do not match the points");
      return map.values;
    } else {
      storage.clear();
      storage.reserve(n);
      for(std::size_t i = 0; i < n; ++i)
        storage.push_back(checked_vertex_tolerance<FT>(get(map, i), i, function, exponent));
      return &storage;
    }
  } else {
    (void)np; (void)n; (void)storage; (void)function;
    return nullptr;
  }
}

/// the largest of `tolerances` (0 when empty).
template <class FT>
FT largest_tolerance(const std::vector<FT>& tolerances)
{
  FT largest(0);
  for(const FT& t : tolerances)
    if(largest < t) largest = t;
  return largest;
}

/// the smaller of two tolerances (the rule of a pair under a `vertex_tolerance_map`).
template <class FT>
const FT& smaller_tolerance(const FT& a, const FT& b)
{
  return b < a ? b : a;
}

/// the visitor of a `visitor` named parameter given as `Given`: `Given` itself (held by copy), or
/// `T` for `std::reference_wrapper<T>` (held by reference, the caller's object).
template <class Given>
struct Given_visitor
{
  using type = Given;
  static type& get(Given& held) { return held; }
};
template <class T>
struct Given_visitor<std::reference_wrapper<T>>
{
  using type = T;
  static type& get(std::reference_wrapper<T>& held) { return held.get(); }
};

/// the types and values that the named parameters `np` give an algorithm on the soup `points`.
template <class PointRange, class NamedParameters>
struct Soup_np_helper
{
  using Point_map = typename CGAL::GetPointMap<PointRange, NamedParameters>::const_type;
  using Point = typename boost::property_traits<Point_map>::value_type;
  using Default_geom_traits = typename CGAL::Kernel_traits<Point>::Kernel;
  using Geom_traits = typename CGAL::internal_np::Lookup_named_param_def<CGAL::internal_np::geom_traits_t,
                                                                         NamedParameters, Default_geom_traits>::type;
  using FT = typename Geom_traits::FT;
  /// the point map of an algorithm that writes the points (`loop_subdivision()`).
  using Writable_point_map = typename CGAL::GetPointMap<PointRange, NamedParameters>::type;

  static Point_map get_point_map(const NamedParameters& np)
  {
    return CGAL::parameters::choose_parameter<Point_map>(CGAL::parameters::get_parameter(np, CGAL::internal_np::point_map));
  }
  static Writable_point_map get_writable_point_map(const NamedParameters& np)
  {
    return CGAL::parameters::choose_parameter<Writable_point_map>(
      CGAL::parameters::get_parameter(np, CGAL::internal_np::point_map));
  }
  static Geom_traits get_geom_traits(const NamedParameters& np)
  {
    return CGAL::parameters::choose_parameter<Geom_traits>(CGAL::parameters::get_parameter(np, CGAL::internal_np::geom_traits));
  }
  /// the points of `points`, read once through the point map (a readable map may return them by value).
  static std::vector<Point> read_points(const PointRange& points, const NamedParameters& np)
  {
    const Point_map pm = get_point_map(np);
    std::vector<Point> copy;
    copy.reserve(points.size());
    for(const auto& e : points) copy.push_back(get(pm, e));
    return copy;
  }
  /// the points of `points` as a vector: `points` itself when it is a vector of points read
  /// through the identity map (no copy), otherwise `read_points()` kept in `storage`.
  static const std::vector<Point>& points_as_vector(const PointRange& points, const NamedParameters& np,
                                                   std::vector<Point>& storage)
  {
    if constexpr(std::is_same<PointRange, std::vector<Point>>::value &&
                 (std::is_same<Point_map, CGAL::Identity_property_map<const Point>>::value ||
                  std::is_same<Point_map, CGAL::Identity_property_map<Point>>::value)) {
      (void)np;
      return points;
    } else {
      storage = read_points(points, np);
      return storage;
    }
  }
  /// checks the points (finite) and the tables (they describe `triangles` over `points`), then
  /// returns the tolerance, times 2^exponent (see `resolve_tolerance()`); throws `Invalid_input`
  /// naming `function` otherwise. (The points are checked by blocks on TBB's threads with a
  /// parallel `ConcurrencyTag`, as `check_finite_points()` does: the same point is named.)
  template <class ConcurrencyTag = CGAL::Sequential_tag, class TriangleRange>
  static FT checked_tolerance(const char* function, const PointRange& points, const TriangleRange& triangles,
                              const Adjacency_tables& tables, const NamedParameters& np, int exponent = 0)
  {
    if(tables.number_of_vertices() != points.size() || tables.number_of_triangles() != triangles.size())
      throw Invalid_input(std::string(function) + ": the adjacency tables do not match the soup (" +
                          std::to_string(tables.number_of_vertices()) + " vertices and " +
                          std::to_string(tables.number_of_triangles()) + " triangles in the tables, " +
                          std::to_string(points.size()) + " points and " + std::to_string(triangles.size()) +
                          " triangles in the soup)");
    const Point_map pm = get_point_map(np);
    check_finite_points<ConcurrencyTag>(points, pm);
    return resolve_tolerance<FT>(points, pm, np, exponent);
  }
};

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_TOLERANCE_H
