// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Exact signs that CGAL kernels do not offer as one predicate: whether a triangle keeps the
// direction of its normal when its corners move.

#ifndef SOUP_TOPOLOGY_INTERNAL_EXACT_SIGNS_H
#define SOUP_TOPOLOGY_INTERNAL_EXACT_SIGNS_H

#include <CGAL/Exact_rational.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Kernel_traits.h>
#include <CGAL/enum.h>
#include <CGAL/number_utils.h>

#include <type_traits>

namespace Soup_topology {
namespace internal {

template <class NT>
NT normal_dot(const NT a[3], const NT b[3], const NT c[3], const NT d[3], const NT e[3], const NT f[3])
{
  // n1 = (b - a) x (c - a), n2 = (e - d) x (f - d), returns n1 . n2
  const NT u1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, v1[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const NT u2[3] = {e[0] - d[0], e[1] - d[1], e[2] - d[2]}, v2[3] = {f[0] - d[0], f[1] - d[1], f[2] - d[2]};
  const NT n1[3] = {u1[1] * v1[2] - u1[2] * v1[1], u1[2] * v1[0] - u1[0] * v1[2], u1[0] * v1[1] - u1[1] * v1[0]};
  const NT n2[3] = {u2[1] * v2[2] - u2[2] * v2[1], u2[2] * v2[0] - u2[0] * v2[2], u2[0] * v2[1] - u2[1] * v2[0]};
  return n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2];
}

/// the exact sign of the dot product of the normals of triangles (a, b, c) and (d, e, f).
/// Coordinates stored as `double` are evaluated with interval arithmetic first and, when the
/// interval contains 0, with exact rationals; other number types are used as they are (exact for
/// Epeck and rational kernels).
template <class Point>
CGAL::Sign sign_of_normal_dot(const Point& a, const Point& b, const Point& c,
                              const Point& d, const Point& e, const Point& f)
{
  using FT = typename CGAL::Kernel_traits<Point>::Kernel::FT;
  if constexpr(std::is_same<FT, double>::value) {
    {
      CGAL::Protect_FPU_rounding<true> protect;
      using I = CGAL::Interval_nt<false>;
      const I pa[3] = {a.x(), a.y(), a.z()}, pb[3] = {b.x(), b.y(), b.z()}, pc[3] = {c.x(), c.y(), c.z()};
      const I pd[3] = {d.x(), d.y(), d.z()}, pe[3] = {e.x(), e.y(), e.z()}, pf[3] = {f.x(), f.y(), f.z()};
      const I s = normal_dot(pa, pb, pc, pd, pe, pf);
      if(s.inf() > 0) return CGAL::POSITIVE;
      if(s.sup() < 0) return CGAL::NEGATIVE;
    }
    using Q = CGAL::Exact_rational;
    const Q pa[3] = {a.x(), a.y(), a.z()}, pb[3] = {b.x(), b.y(), b.z()}, pc[3] = {c.x(), c.y(), c.z()};
    const Q pd[3] = {d.x(), d.y(), d.z()}, pe[3] = {e.x(), e.y(), e.z()}, pf[3] = {f.x(), f.y(), f.z()};
    return CGAL::sign(normal_dot(pa, pb, pc, pd, pe, pf));
  } else {
    const FT pa[3] = {a.x(), a.y(), a.z()}, pb[3] = {b.x(), b.y(), b.z()}, pc[3] = {c.x(), c.y(), c.z()};
    const FT pd[3] = {d.x(), d.y(), d.z()}, pe[3] = {e.x(), e.y(), e.z()}, pf[3] = {f.x(), f.y(), f.z()};
    return CGAL::sign(normal_dot(pa, pb, pc, pd, pe, pf));
  }
}

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_EXACT_SIGNS_H
