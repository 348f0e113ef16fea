// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// A floating-point filter for "the point is within the bound of the segment", used by
// `Soup_topology::Octree` and the T-junction repair before the exact predicate.

#ifndef SOUP_TOPOLOGY_INTERNAL_OCTREE_DISTANCE_FILTERS_H
#define SOUP_TOPOLOGY_INTERNAL_OCTREE_DISTANCE_FILTERS_H

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace Soup_topology {
namespace internal {

/// the decision of `surely_within_segment()` from the squared distance `d2` it computes and its
/// `scale` (the largest absolute coordinate difference, of `p - a` and of `b - a`): for callers that
/// computed both the same way already.
inline bool surely_within(double d2, double scale, double bound2)
{
  if(!(bound2 > 1e-200 && bound2 < 1e200) || !(scale < 1e100))
    return false;
  const double reach = std::sqrt(d2) + 1e-12 * scale + 1e-150;
  return reach * reach < bound2 * (1 - 1e-12);
}

/// `true` if the squared distance from `p` to the closed segment `[a,b]` (exact double
/// coordinates) is certainly below `bound2`; `false` if that is not proven (ask the exact
/// predicate then).
///
/// The distance is measured to the point `a + t (b - a)`, `t` the projection parameter computed
/// in double and clamped to [0,1]: whatever its rounding, that point lies on the segment, so its
/// distance bounds the distance to the segment from above. The only errors left are those of
/// evaluating `|p - a - t (b - a)|` at that `t`: a few ulps of the largest coordinate difference,
/// covered here by `1e-12` of it (plus an absolute term for underflow).
inline bool surely_within_segment(const std::array<double, 3>& p, const std::array<double, 3>& a,
                                  const std::array<double, 3>& b, double bound2)
{
  if(!(bound2 > 1e-200 && bound2 < 1e200))
    return false;
  double v[3], d[3];
  double scale = 0, dot = 0, len2 = 0;
  for(std::size_t i = 0; i < 3; ++i)
  {
    v[i] = p[i] - a[i];
    d[i] = b[i] - a[i];
    scale = std::max({scale, std::abs(v[i]), std::abs(d[i])});
    dot += v[i] * d[i];
    len2 += d[i] * d[i];
  }
  if(!(scale < 1e100))
    return false;
  double t = 0;
  if(len2 > 0)
  {
    t = dot / len2;
    t = t > 0 ? (t < 1 ? t : 1) : 0; // a NaN becomes 0
  }
  double d2 = 0;
  for(std::size_t i = 0; i < 3; ++i)
  {
    const double w = v[i] - t * d[i];
    d2 += w * w;
  }
  return surely_within(d2, scale, bound2);
}

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_OCTREE_DISTANCE_FILTERS_H
