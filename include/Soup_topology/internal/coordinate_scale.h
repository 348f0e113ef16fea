// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Soups at extreme scales: the power of two by which the gap analysis and the pipeline scale
// coordinates beyond 2^128 or below 2^-128 before they measure and decide, and back after.

#ifndef SOUP_TOPOLOGY_INTERNAL_COORDINATE_SCALE_H
#define SOUP_TOPOLOGY_INTERNAL_COORDINATE_SCALE_H

#include <Soup_topology/internal/parallel.h>

#include <CGAL/Kernel_traits.h>
#include <CGAL/number_utils.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>
#include <vector>

namespace Soup_topology {
namespace internal {

/// the exponent beyond which (in absolute value) the coordinates of a soup are scaled before
/// they are measured: with the largest coordinate within [2^-128, 2^128), every product the
/// measures and the predicates' filters form (squared lengths and tolerances, cross products,
/// their squares: up to fourth powers of coordinates and of their differences) is a normal double.
constexpr int moderate_exponent_bound = 128;

/// the largest absolute value of a coordinate of `p`, as a double.
template <class Point>
double largest_coordinate(const Point& p)
{
  return std::max(std::abs(CGAL::to_double(p.x())),
                  std::max(std::abs(CGAL::to_double(p.y())), std::abs(CGAL::to_double(p.z()))));
}

/// the exponent e such that `value` times 2^e lies in [1, 2), when `value` lies outside
/// [2^-bound, 2^bound); 0 when it lies inside, is 0 or is not finite. (Scaled by a power of two, a
/// number keeps its digits.)
inline int exponent_into_unit_range(double value, int bound)
{
  if(!(value > 0) || !std::isfinite(value)) return 0;
  const int e = std::ilogb(value);
  if(e >= -bound && e < bound) return 0;
  return -e;
}

/// the power of two 2^e by which a soup whose largest coordinate (absolute value) is `largest`
/// is scaled: e = 0 when that lies in [2^-128, 2^128) (or is 0, or not finite), else the e that
/// brings it into [1, 2).
///
/// Beyond, squared lengths overflow (coordinates near 1e200: a distance to an edge comes out
/// infinite, a tolerance is refused as too large) or underflow (near 1e-200: gaps, heights and
/// squared tolerances come out 0, and nothing is welded), and results change with the unit of the
/// file. Scaled by a power of two, the coordinates are the same numbers with another exponent:
/// every distance computed on them, scaled back, is the one computed on the soup at a moderate
/// scale, scaled, to the bit (the rounding of `+ - * / sqrt` does not depend on the exponents
/// while the results are normal numbers), and the exact predicates decide the same.
///
/// The exponent is at most 1023, so that 2^e is itself a double (the scaling multiplies by it):
/// a soup whose largest coordinate is subnormal (down to 2^-1074) is brought near 2^-51 instead
/// of [1, 2), still within the moderate range.
inline int moderate_scale_exponent(double largest)
{
  return std::min(exponent_into_unit_range(largest, moderate_exponent_bound),
                  std::numeric_limits<double>::max_exponent - 1);
}

/// `true` if the coordinates of `p` times 2^e are exact: always with an exact number type; with
/// double coordinates, unless one falls below the normal numbers and is rounded.
template <class Point>
bool scales_exactly(const Point& p, int e)
{
  using FT = typename CGAL::Kernel_traits<Point>::Kernel::FT;
  if constexpr(std::is_same<FT, double>::value) {
    const auto exact = [e](double x) { return std::ldexp(std::ldexp(x, e), -e) == x; };
    return exact(p.x()) && exact(p.y()) && exact(p.z());
  } else {
    return true;
  }
}

/// `p` times 2^e (exact when `scales_exactly(p, e)`).
template <class Point>
Point scaled_point(const Point& p, int e)
{
  using FT = typename CGAL::Kernel_traits<Point>::Kernel::FT;
  const FT factor(std::ldexp(1.0, e));
  return Point(p.x() * factor, p.y() * factor, p.z() * factor);
}

/// the exponent e of `moderate_scale_exponent()` for the points `points` (all of them), or 0
/// when some point would not scale exactly (coordinates that span more than the range of the
/// exponents): such a soup is measured as it is.
///
/// With a parallel `ConcurrencyTag` and `double` coordinates, the largest coordinate (a maximum:
/// the same in any order) and the check are computed by blocks on TBB's threads.
template <class ConcurrencyTag = CGAL::Sequential_tag, class Point>
int moderate_scale_exponent_of(const std::vector<Point>& points)
{
  using Tag = std::conditional_t<std::is_same<typename CGAL::Kernel_traits<Point>::Kernel::FT, double>::value,
                                 ConcurrencyTag, CGAL::Sequential_tag>;
  const std::size_t n = points.size();
  const double largest = largest_by_blocks<Tag>(n, [&](std::size_t i) { return largest_coordinate(points[i]); });
  const int e = moderate_scale_exponent(largest);
  if(e == 0) return 0;
  return first_index_where<Tag>(n, [&](std::size_t i) { return !scales_exactly(points[i], e); }) == n ? e : 0;
}

/// `points` times 2^exponent in `storage` (in place when `points` is `storage`); returns `storage`.
template <class Point>
const std::vector<Point>& scaled_points(const std::vector<Point>& points, int exponent, std::vector<Point>& storage)
{
  if(&points == &storage) {
    for(Point& p : storage) p = scaled_point(p, exponent);
  } else {
    storage.clear();
    storage.reserve(points.size());
    for(const Point& p : points) storage.push_back(scaled_point(p, exponent));
  }
  return storage;
}

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_COORDINATE_SCALE_H
