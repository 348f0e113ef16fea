// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Degenerate triangles of the input (three distinct collinear corners) removed by an edge flip,
// under `Small_features::COLLAPSE`: the corner between the two others lies on the opposite edge,
// and the triangle across that edge is split there, which is the flip of that edge in the
// quadrilateral the two triangles make.

#ifndef SOUP_TOPOLOGY_INTERNAL_SMALL_FEATURE_DEGENERATE_H
#define SOUP_TOPOLOGY_INTERNAL_SMALL_FEATURE_DEGENERATE_H

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/internal/parallel.h>
#include <Soup_topology/internal/soup_checks.h>

#include <CGAL/tags.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <type_traits>
#include <utility>
#include <vector>

namespace Soup_topology {
namespace internal {

/// what `flip_degenerate_triangles()` did.
struct Degenerate_flip_counts
{
  std::size_t flipped = 0;    ///< degenerate triangles removed by a flip
  std::size_t remaining = 0;  ///< degenerate triangles left (no neighbour to flip with)
};

/// the triangles of `triangles` whose three distinct corners are collinear (exactly, by
/// `Collinear_3`), in increasing order. With `CGAL::Parallel_tag` and double coordinates (whose
/// predicates share no lazily computed state) the triangles are tested by blocks on TBB's
/// threads; the list is the same.
template <class ConcurrencyTag = CGAL::Sequential_tag, class Kernel, class Point, class TriangleRange>
std::vector<Adjacency_tables::size_type> degenerate_triangles(const std::vector<Point>& points,
                                                              const TriangleRange& triangles, const Kernel& kernel)
{
  using Tag = std::conditional_t<std::is_same<typename Kernel::FT, double>::value, ConcurrencyTag, CGAL::Sequential_tag>;
  const typename Kernel::Collinear_3 collinear = kernel.collinear_3_object();
  std::vector<Adjacency_tables::size_type> degenerate;
  append_indices_where<Tag>(static_cast<std::size_t>(triangles.size()), [&](std::size_t t) {
    const std::array<std::size_t, 3> c = triangle_indices(*(triangles.begin() + static_cast<std::ptrdiff_t>(t)));
    return c[0] != c[1] && c[1] != c[2] && c[2] != c[0] && collinear(points[c[0]], points[c[1]], points[c[2]]);
  }, degenerate);
  return degenerate;
}

/// removes, by edge flips, the triangles of `triangles` whose three distinct corners are
/// collinear (exactly, by `Collinear_3`). For such a triangle (a, b, c) with c between a and b
/// (c is the middle one of the three in `Less_xyz_3` order: along a line that order is monotone),
/// the triangle (b, a, d) across the edge [a,b] is replaced by (b, c, d) and (c, a, d), and
/// (a, b, c) goes: the edge [a,b] is flipped to [c,d]. The two new triangles cover (b, a, d)
/// exactly and have its orientation (their normals are positive multiples of its normal), so the
/// surface does not move, and the number of triangles does not change. A flip is not done when
/// the edge [a,b] is a border or non-manifold edge, when the neighbour is oriented the other way
/// or degenerate too, or when the edge [c,d] exists already (it would become non-manifold).
///
/// The degenerate triangles are taken in a geometric order (their sorted corners); within a pass
/// a triangle takes part in one flip at most, and the tables are rebuilt between passes. Every
/// flip removes a degenerate triangle and creates none, so the passes end.
///
/// Cost: a pass scans the triangles and builds the tables, O(n), and there are at most 17 passes,
/// so the whole is linear in the soup (no re-scan after each flip). A pass flips every degenerate
/// triangle whose neighbour is free; another pass is needed only where a flip makes a degenerate
/// triangle flippable, i.e. along a chain of degenerate triangles each across the long edge of
/// the next, which one pass shortens by one. A chain longer than the passes allow is left
/// (counted in `remaining`) to `remove_covered_degenerate_triangles()`, rather than paid for with a
/// quadratic number of passes.
///
/// With `CGAL::Parallel_tag`, the scans (`degenerate_triangles()`) and the tables of each pass
/// run on TBB's threads; the flips, in their geometric order, do not.
template <class ConcurrencyTag = CGAL::Sequential_tag, class Kernel, class Point, class TriangleRange>
Degenerate_flip_counts flip_degenerate_triangles(const std::vector<Point>& points, TriangleRange& triangles,
                                                 const Kernel& kernel)
{
  using size_type = Adjacency_tables::size_type;
  const typename Kernel::Collinear_3 collinear = kernel.collinear_3_object();
  const typename Kernel::Less_xyz_3 less_xyz = kernel.less_xyz_3_object();
  auto corners = [&](std::size_t t) { return triangle_indices(*(triangles.begin() + static_cast<std::ptrdiff_t>(t))); };
  // The corners of a triangle sorted lexicographically, for the geometric order.
  auto sorted_corners = [&](std::size_t t) {
    std::array<std::size_t, 3> c = corners(t);
    std::sort(c.begin(), c.end(), [&](std::size_t x, std::size_t y) { return less_xyz(points[x], points[y]); });
    return c;
  };
  auto geometric_less = [&](std::size_t s, std::size_t t) {
    const std::array<std::size_t, 3> x = sorted_corners(s), y = sorted_corners(t);
    for(std::size_t k = 0; k < 3; ++k) {
      if(less_xyz(points[x[k]], points[y[k]])) return true;
      if(less_xyz(points[y[k]], points[x[k]])) return false;
    }
    return false;
  };

  Degenerate_flip_counts counts;
  const std::size_t n = static_cast<std::size_t>(triangles.size());
  std::vector<size_type> degenerate;
  for(std::size_t pass = 0;; ++pass) {
    degenerate = degenerate_triangles<ConcurrencyTag>(points, triangles, kernel);
    if(degenerate.empty() || pass == 16) break;
    std::stable_sort(degenerate.begin(), degenerate.end(), geometric_less);
    const Adjacency_tables tables(triangles, points.size(), ConcurrencyTag());
    std::vector<char> used(n, 0);
    bool changed = false;
    for(const size_type t : degenerate) {
      if(used[t]) continue;
      const std::array<std::size_t, 3> sorted = sorted_corners(t);
      const size_type c = static_cast<size_type>(sorted[1]);
      const int k = tables.local_index(t, c);
      const int i = (k + 1) % 3; // the edge (a, b) opposite c
      const size_type a = tables.vertex(t, i), b = tables.vertex(t, (i + 1) % 3);
      const size_type u = tables.neighbor(t, i);
      if(u == Adjacency_tables::border_edge || u == Adjacency_tables::non_manifold_edge || used[u]) continue;
      const int ib = tables.local_index(u, b);
      if(ib < 0 || tables.vertex(u, (ib + 1) % 3) != a) continue; // oriented the other way
      const size_type d = tables.vertex(u, (ib + 2) % 3);
      if(d == c || collinear(points[a], points[b], points[d])) continue;
      bool edge_exists = false;
      for(size_type w : tables.triangles_around_vertex(c))
        if(tables.local_index(w, d) >= 0) { edge_exists = true; break; }
      if(edge_exists) continue;
      assign_triangle(*(triangles.begin() + static_cast<std::ptrdiff_t>(t)), b, c, d);
      assign_triangle(*(triangles.begin() + static_cast<std::ptrdiff_t>(u)), c, a, d);
      used[t] = used[u] = 1;
      ++counts.flipped;
      changed = true;
    }
    if(!changed) break;
  }
  counts.remaining = degenerate.size();
  return counts;
}

/// removes from `triangles` the triangles whose three distinct corners are collinear (exactly,
/// by `Collinear_3`) and whose points the other triangles cover, and returns how many. Such a
/// triangle (a, b, c), c between a and b, is the segment [a,b]; it is covered when [a,b] is an
/// edge of a triangle that is not degenerate, or when [a,c] and [c,b] both are. Removing it then
/// moves no point of the surface: it only unlinks its edges, which the weld and the T-junction
/// splits of the pipeline link again (c lies on [a,b]). This resolves what the flips of
/// `flip_degenerate_triangles()` cannot, e.g. two degenerate triangles glued back to back or
/// along their long edge. The decision of each triangle depends on the non-degenerate triangles
/// only, so it does not depend on the order of the triangles; the others keep their order.
/// With `CGAL::Parallel_tag`, the scan (`degenerate_triangles()`) and the tables run on TBB's
/// threads.
template <class ConcurrencyTag = CGAL::Sequential_tag, class Kernel, class Point, class TriangleRange>
std::size_t remove_covered_degenerate_triangles(const std::vector<Point>& points, TriangleRange& triangles,
                                                const Kernel& kernel)
{
  using size_type = Adjacency_tables::size_type;
  const typename Kernel::Less_xyz_3 less_xyz = kernel.less_xyz_3_object();
  const std::size_t n = static_cast<std::size_t>(triangles.size());
  auto corners = [&](std::size_t t) { return triangle_indices(*(triangles.begin() + static_cast<std::ptrdiff_t>(t))); };
  const std::vector<size_type> degenerate = degenerate_triangles<ConcurrencyTag>(points, triangles, kernel);
  if(degenerate.empty()) return 0;
  std::vector<char> is_degenerate(n, 0);
  for(const size_type t : degenerate) is_degenerate[t] = 1;
  const Adjacency_tables tables(triangles, points.size(), ConcurrencyTag());
  // `true` if [u,w] is an edge of a triangle that is not degenerate.
  auto has_covering_edge = [&](std::size_t u, std::size_t w) {
    for(size_type t : tables.triangles_around_vertex(static_cast<size_type>(u)))
      if(!is_degenerate[t] && tables.local_index(t, static_cast<size_type>(w)) >= 0) return true;
    return false;
  };
  std::vector<char> is_removed(n, 0);
  std::size_t removed = 0;
  for(const size_type t : degenerate) {
    std::array<std::size_t, 3> c = corners(t);
    std::sort(c.begin(), c.end(), [&](std::size_t x, std::size_t y) { return less_xyz(points[x], points[y]); });
    const std::size_t a = c[0], middle = c[1], b = c[2];
    if(has_covering_edge(a, b) || (has_covering_edge(a, middle) && has_covering_edge(middle, b))) {
      is_removed[t] = 1;
      ++removed;
    }
  }
  if(removed == 0) return 0;
  std::size_t kept = 0;
  for(std::size_t t = 0; t < n; ++t) {
    if(is_removed[t]) continue;
    if(kept != t)
      *(triangles.begin() + static_cast<std::ptrdiff_t>(kept)) = std::move(*(triangles.begin() + static_cast<std::ptrdiff_t>(t)));
    ++kept;
  }
  triangles.erase(triangles.begin() + static_cast<std::ptrdiff_t>(kept), triangles.end());
  return removed;
}

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_SMALL_FEATURE_DEGENERATE_H
