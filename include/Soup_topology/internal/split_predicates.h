// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Distance predicates of the T-junction repair: an exact comparison of point-segment distances,
// and a kernel whose `Compare_squared_distance_3` accepts clearly near end points in double.

#ifndef SOUP_TOPOLOGY_INTERNAL_SPLIT_PREDICATES_H
#define SOUP_TOPOLOGY_INTERNAL_SPLIT_PREDICATES_H

#include <Soup_topology/internal/octree_distance_filters.h>

#include <CGAL/Cartesian_converter.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Kernel_traits.h>
#include <CGAL/number_utils.h>

#include <array>
#include <type_traits>

namespace Soup_topology {
namespace internal {

/// compares the distances from `p` to the segments [a,b] and [c,d], exactly: the squared
/// distances are constructed in `Exact_predicates_exact_constructions_kernel` (a rare question:
/// only a vertex near several border edges asks it).
template <class Point>
CGAL::Comparison_result compare_point_segment_distances(const Point& p, const Point& a, const Point& b,
                                                        const Point& c, const Point& d)
{
  using Kernel = typename CGAL::Kernel_traits<Point>::Kernel;
  using Exact = CGAL::Exact_predicates_exact_constructions_kernel;
  const CGAL::Cartesian_converter<Kernel, Exact> to_exact;
  const Exact::Point_3 ep = to_exact(p);
  const Exact::FT d1 = CGAL::squared_distance(ep, Exact::Segment_3(to_exact(a), to_exact(b)));
  const Exact::FT d2 = CGAL::squared_distance(ep, Exact::Segment_3(to_exact(c), to_exact(d)));
  return CGAL::compare(d1, d2);
}

/// `true` if the squared distance of `p` and `q`, computed in double, is clearly below `bound2`
/// (a squared distance in double, far above underflow): the exact comparison then says so too.
/// For double coordinates only (otherwise `false`: ask the exact predicate).
template <class Point>
bool surely_within(const Point& p, const Point& q, double bound2)
{
  using FT = typename CGAL::Kernel_traits<Point>::Kernel::FT;
  if constexpr(std::is_same<FT, double>::value) {
    const double dx = p.x() - q.x(), dy = p.y() - q.y(), dz = p.z() - q.z();
    return bound2 > 1e-250 && dx * dx + dy * dy + dz * dz < bound2 * (1 - 1e-12);
  } else {
    (void)p; (void)q; (void)bound2;
    return false;
  }
}

/// `true` if the squared distance of `p` and the closed segment `[a,b]`, computed in double with
/// an error bound, is clearly below `bound2` (a squared distance in double): the exact comparison
/// then says so too. For double coordinates only (otherwise `false`: ask the exact predicate).
template <class Point>
bool surely_within_segment(const Point& p, const Point& a, const Point& b, double bound2)
{
  using FT = typename CGAL::Kernel_traits<Point>::Kernel::FT;
  if constexpr(std::is_same<FT, double>::value) {
    return surely_within_segment(std::array<double, 3>{{p.x(), p.y(), p.z()}},
                                 std::array<double, 3>{{a.x(), a.y(), a.z()}},
                                 std::array<double, 3>{{b.x(), b.y(), b.z()}}, bound2);
  } else {
    (void)p; (void)a; (void)b; (void)bound2;
    return false;
  }
}

/// The kernel, with a `Compare_squared_distance_3` that first accepts, in double, a point clearly
/// within the bound of a segment's end point (or of the other point), then asks the kernel. The
/// answers are the kernel's; the shortcut spares the exact fallback that the filtered
/// point-segment predicate takes for a point equal to the segment's target, as every border
/// vertex is for the border edges that end at it.
template <class Kernel>
struct Kernel_with_near_end_shortcut : public Kernel
{
  using Point_3 = typename Kernel::Point_3;
  using Segment_3 = typename Kernel::Segment_3;
  using FT = typename Kernel::FT;

  struct Compare_squared_distance_3
  {
    typename Kernel::Compare_squared_distance_3 base;
    using result_type = CGAL::Comparison_result;
    CGAL::Comparison_result operator()(const Point_3& p, const Point_3& q, const FT& bound2) const
    {
      if(surely_within(p, q, CGAL::to_double(bound2))) return CGAL::SMALLER;
      return base(p, q, bound2);
    }
    CGAL::Comparison_result operator()(const Point_3& p, const Segment_3& s, const FT& bound2) const
    {
      const double b = CGAL::to_double(bound2);
      if(surely_within(p, s.source(), b) || surely_within(p, s.target(), b)) return CGAL::SMALLER;
      return base(p, s, bound2);
    }
  };

  Kernel_with_near_end_shortcut() = default;
  explicit Kernel_with_near_end_shortcut(const Kernel& kernel) : Kernel(kernel) {}
  Compare_squared_distance_3 compare_squared_distance_3_object() const
  {
    return Compare_squared_distance_3{Kernel::compare_squared_distance_3_object()};
  }
};

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_SPLIT_PREDICATES_H
