// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Counting the intersecting pairs of triangles of an indexed soup (CGAL 5.5 tests meshes only:
// the soup may be non-manifold). Two triangles that share a vertex or an edge by index intersect
// only where they meet beyond it, the rule of CGAL's self_intersections() on meshes.

#ifndef SOUP_TOPOLOGY_INTERNAL_SOUP_SELF_INTERSECTIONS_H
#define SOUP_TOPOLOGY_INTERNAL_SOUP_SELF_INTERSECTIONS_H

#include <Soup_topology/internal/soup_checks.h>

#include <CGAL/box_intersection_d.h>

#include <array>
#include <cstddef>
#include <vector>

namespace Soup_topology {
namespace internal {

/// the number of pairs of non-degenerate triangles of the soup that intersect more than in the
/// vertices and the edge they share by index. Degenerate triangles are not tested.
template <class GeomTraits, class PointRange, class TriangleRange>
std::size_t count_soup_self_intersections(const PointRange& points, const TriangleRange& triangles,
                                          const GeomTraits& gt)
{
  using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t>;
  using Point = typename GeomTraits::Point_3;
  const auto collinear = gt.collinear_3_object();
  const auto coplanar = gt.coplanar_3_object();
  const auto coplanar_orientation = gt.coplanar_orientation_3_object();
  const auto triangle_of = gt.construct_triangle_3_object();
  const auto segment_of = gt.construct_segment_3_object();
  const auto do_intersect = gt.do_intersect_3_object();

  std::vector<std::array<std::size_t, 3>> corners;
  corners.reserve(triangles.size());
  for(const auto& f : triangles) corners.push_back(triangle_indices(f));
  auto point = [&](std::size_t v) -> const Point& { return points[v]; };
  std::vector<Box> boxes;
  boxes.reserve(corners.size());
  for(std::size_t t = 0; t < corners.size(); ++t) {
    const Point &p = point(corners[t][0]), &q = point(corners[t][1]), &r = point(corners[t][2]);
    if(collinear(p, q, r)) continue;
    boxes.emplace_back(p.bbox() + q.bbox() + r.bbox(), t);
  }

  auto intersect = [&](const std::array<std::size_t, 3>& t, const std::array<std::size_t, 3>& u) {
    // position in u of each corner of t, or 3
    int in_u[3] = {3, 3, 3};
    int shared = 0;
    for(int i = 0; i < 3; ++i)
      for(int j = 0; j < 3; ++j)
        if(t[static_cast<std::size_t>(i)] == u[static_cast<std::size_t>(j)]) { in_u[i] = j; ++shared; }
    if(shared == 3) return true; // the same triangle twice
    if(shared == 2) {
      // they overlap if the opposite corners lie in one plane on the same side of the edge
      int i = 0;
      while(in_u[i] != 3) ++i;
      const std::size_t c = t[static_cast<std::size_t>(i)];
      const std::size_t a = t[static_cast<std::size_t>((i + 1) % 3)], b = t[static_cast<std::size_t>((i + 2) % 3)];
      std::size_t d = u[0];
      for(std::size_t v : u) if(v != a && v != b) d = v;
      return coplanar(point(a), point(b), point(c), point(d)) &&
             coplanar_orientation(point(a), point(b), point(c), point(d)) == CGAL::POSITIVE;
    }
    const auto tt = triangle_of(point(t[0]), point(t[1]), point(t[2]));
    const auto tu = triangle_of(point(u[0]), point(u[1]), point(u[2]));
    if(shared == 1) {
      // they meet beyond the shared corner if the edge opposite to it in one meets the other
      int i = 0;
      while(in_u[i] == 3) ++i;
      const std::size_t j = static_cast<std::size_t>(in_u[i]);
      const std::size_t ii = static_cast<std::size_t>(i);
      return do_intersect(tt, segment_of(point(u[(j + 1) % 3]), point(u[(j + 2) % 3]))) ||
             do_intersect(tu, segment_of(point(t[(ii + 1) % 3]), point(t[(ii + 2) % 3])));
    }
    return do_intersect(tt, tu);
  };

  std::size_t count = 0;
  CGAL::box_self_intersection_d<CGAL::Sequential_tag>(boxes.begin(), boxes.end(), [&](const Box& a, const Box& b) {
    if(intersect(corners[a.info()], corners[b.info()])) ++count;
  });
  return count;
}

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_SOUP_SELF_INTERSECTIONS_H
