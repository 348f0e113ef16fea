// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// `orient_triangle_soup()` one part of the soup at a time, with the same result: what the output
// of a tiled repair needs when the tables of the whole soup would not fit in memory.

#ifndef SOUP_TOPOLOGY_INTERNAL_ORIENT_SOUP_IN_PARTS_H
#define SOUP_TOPOLOGY_INTERNAL_ORIENT_SOUP_IN_PARTS_H

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/orient_triangle_soup.h>
#include <Soup_topology/soup_statistics.h>
#include <Soup_topology/internal/boxes_inside_boxes.h>
#include <Soup_topology/internal/orient_soup.h>
#include <Soup_topology/internal/soup_checks.h>
#include <Soup_topology/internal/union_find.h>

#include <CGAL/Kernel_traits.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/number_utils.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace Soup_topology {
namespace internal {

/// what `orient_triangle_soup_in_parts()` gives: what `orient_triangle_soup()` gives, the
/// statistics of the oriented soup (`compute_statistics()`), and the number of parts.
struct Oriented_in_parts
{
  Orientation_report report;
  Soup_statistics statistics;
  std::size_t parts = 0;
  std::size_t largest_part_triangles = 0; ///< triangles of the largest part
  std::size_t turned_across_parts = 0;    ///< closed patches turned by the nesting across parts
};

/// Orients the soup as `orient_triangle_soup()` does (the same points, triangles and report), one
/// part at a time, and measures the oriented soup as `compute_statistics()` does over tables of the
/// whole soup. A *part* is a set of whole components of the soup (triangles connected through
/// shared points), components taken in the order of their smallest point and put together while
/// the part holds at most `part_triangles` triangles (a larger component is a part alone; a soup
/// of one part is oriented in place, as `orient_triangle_soup()` does, without a copy). Only one
/// part's copy, its tables and its orientation are held at a time (about 85 bytes a triangle of the
/// part, measured on closed meshes), beside the soup, 4 bytes a point and 1 a triangle, and 4 bytes
/// a triangle of the closed patches of the parts whose boxes meet another part's box.
///
/// Why the result is the same: every decision of the orientation is made within a component (the
/// repeated triangles, the traversal of the patches, the fans of the vertices, the orientation of
/// an open patch), on the relative order of its triangles and of the lexicographic ranks of its
/// points, which a part keeps (its points and its triangles in the order of the soup). The two
/// choices that reach across components are made again over the whole soup: the nesting depth of
/// a closed patch counts the closed patches of the other parts that enclose it (their winding
/// numbers summed in the same order on the same corners), and a patch whose count is odd is
/// turned; the copies that separate non-manifold vertices are numbered vertex after vertex in the
/// order of the soup. Repeated triangles are left out at the end, the order of the others kept.
///
/// Work: each part scans the soup twice (to cut it out and to write it back) and the boxes of the
/// parts are compared pairwise, so `k` parts cost `k` passes over the soup and `k^2` box tests:
/// meant for a few large parts (the tool gives a part room for 65,536 triangles at least; two
/// consecutive parts hold more than that together, so there are at most `2 t / 65,536 + 1`).
///
/// \throws Invalid_input as `orient_triangle_soup()`, or for 2^31 points or more; nothing is
///         changed then.
template <class ConcurrencyTag = CGAL::Sequential_tag, class PointRange, class TriangleRange,
          class NamedParameters = CGAL::parameters::Default_named_parameters>
Oriented_in_parts orient_triangle_soup_in_parts(PointRange& pts, TriangleRange& tris, std::size_t part_triangles,
                                                const NamedParameters& np = CGAL::parameters::default_values())
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  using Point = typename PointRange::value_type;
  using Triangle = typename TriangleRange::value_type;
  using Default_kernel = typename CGAL::Kernel_traits<Point>::Kernel;
  using Kernel = typename CGAL::internal_np::Lookup_named_param_def<CGAL::internal_np::geom_traits_t, NamedParameters,
                                                                     Default_kernel>::type;
  using size_type = Adjacency_tables::size_type;
  check_triangle_soup<ConcurrencyTag>(tris, pts.size());
  check_finite_points<ConcurrencyTag>(pts, CGAL::Identity_property_map<Point>());
  const Patch_orientation_rules rules = patch_orientation_rules(np);
  const Kernel kernel = choose_parameter<Kernel>(get_parameter(np, CGAL::internal_np::geom_traits));

  const std::size_t n = pts.size(), m = tris.size();
  if(n > std::size_t(std::numeric_limits<size_type>::max()) || m > std::size_t(std::numeric_limits<size_type>::max()))
    throw Invalid_input("orientation in parts: more than 2^32 - 1 points or triangles");
  const auto corner_of = [&](std::size_t t, std::size_t i) { return corner(tris[t], i, t); };

  // The components (their roots, then their numbers in the order of their smallest point), and
  // the part of every point, kept in one array.
  Union_find::Parents part_of;
  std::size_t parts = 0;
  {
    Union_find sets(n);
    for(std::size_t t = 0; t < m; ++t) {
      sets.unite(static_cast<std::uint32_t>(corner_of(t, 0)), static_cast<std::uint32_t>(corner_of(t, 1)));
      sets.unite(static_cast<std::uint32_t>(corner_of(t, 0)), static_cast<std::uint32_t>(corner_of(t, 2)));
    }
    part_of = sets.take_roots();
  }
  {
    constexpr std::uint32_t none = std::numeric_limits<std::uint32_t>::max();
    std::vector<std::uint32_t> component_of_root(n, none); // (a root is its component's smallest point)
    std::vector<std::size_t> size;                         // triangles of each component
    for(std::size_t v = 0; v < n; ++v)
      if(part_of[v] == v) {
        component_of_root[v] = static_cast<std::uint32_t>(size.size());
        size.push_back(0);
      }
    for(std::size_t t = 0; t < m; ++t) ++size[component_of_root[part_of[corner_of(t, 0)]]];
    std::vector<std::uint32_t> part_of_component(size.size());
    std::size_t held = 0;
    for(std::size_t c = 0; c < size.size(); ++c) {
      if(size[c] == 0) { part_of_component[c] = none; continue; } // a point of no triangle
      if(parts == 0 || held + size[c] > part_triangles) { ++parts; held = 0; }
      part_of_component[c] = static_cast<std::uint32_t>(parts - 1);
      held += size[c];
    }
    for(std::size_t v = 0; v < n; ++v) part_of[v] = part_of_component[component_of_root[part_of[v]]];
  }

  Oriented_in_parts out;
  out.parts = parts;
  // One part (one component larger than `part_triangles`, or a soup that fits): oriented in
  // place, as a whole, without a copy of the soup.
  if(parts <= 1) {
    Union_find::Parents().swap(part_of);
    out.largest_part_triangles = m;
    Soup_orienter<PointRange, TriangleRange, Kernel> orienter(pts, tris, rules, kernel);
    copy_orientation_counts(orienter.template run<ConcurrencyTag>(), out.report);
    out.statistics = compute_statistics<ConcurrencyTag>(pts, Adjacency_tables(tris, pts.size(), ConcurrencyTag()));
    return out;
  }
  // The boxes of the parts: the closed patches of a part whose box meets no other part's box can
  // neither enclose nor be enclosed by a patch of another part, and their triangles are not kept
  // for the nesting across parts.
  std::vector<Box_bounds> part_box(parts, Box_bounds{HUGE_VAL, HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL});
  for(std::size_t v = 0; v < n; ++v) {
    if(part_of[v] == std::numeric_limits<std::uint32_t>::max()) continue;
    Box_bounds& b = part_box[part_of[v]];
    const double c[3] = {CGAL::to_double(pts[v].x()), CGAL::to_double(pts[v].y()), CGAL::to_double(pts[v].z())};
    for(std::size_t i = 0; i < 3; ++i) {
      b[i] = std::min(b[i], c[i]);
      b[i + 3] = std::max(b[i + 3], c[i]);
    }
  }
  std::vector<char> part_meets_another(parts, 0);
  for(std::size_t a = 0; a < parts; ++a)
    for(std::size_t b = a + 1; b < parts; ++b) {
      bool meet = true;
      for(std::size_t i = 0; i < 3; ++i)
        meet = meet && part_box[a][i] <= part_box[b][i + 3] && part_box[b][i] <= part_box[a][i + 3];
      if(meet) part_meets_another[a] = part_meets_another[b] = 1;
    }
  // a triangle's state: as given, written back (its corners may be copies, numbered later), or
  // left out as a repeat
  enum : char { GIVEN, WRITTEN, DROPPED };
  std::vector<char> state(m, GIVEN);
  std::vector<std::size_t> copied_from;          // the point each copy copies, in the order of the parts
  std::vector<Orientation_decisions::Closed_patch> closed; // triangles as indices into `tris`
  std::vector<std::uint32_t> part_of_closed;
  // While part q is cut out, `part_of[v]` of its points becomes their index in the part with the
  // top bit set (`in_part`); the triangles of earlier parts, whose points are marked too, are no
  // longer `GIVEN`.
  constexpr std::uint32_t in_part = std::uint32_t(1) << 31;
  if(n >= in_part) throw Invalid_input("orientation in parts: 2^31 points or more");
  const auto in_this_part = [&](std::size_t t) {
    return state[t] == GIVEN && (part_of[corner_of(t, 0)] & in_part) != 0;
  };
  for(std::size_t q = 0; q < parts; ++q) {
    PointRange part_points;
    TriangleRange part_triangles_of_q;
    std::vector<size_type> global_point;
    for(std::size_t v = 0; v < n; ++v)
      if(part_of[v] == q) {
        part_of[v] = in_part | static_cast<std::uint32_t>(part_points.size());
        part_points.push_back(pts[v]);
        global_point.push_back(static_cast<size_type>(v));
      }
    const auto local = [&](std::size_t v) { return std::size_t(part_of[v] & ~in_part); };
    for(std::size_t t = 0; t < m; ++t)
      if(in_this_part(t)) {
        Triangle tr = tris[t];
        assign_triangle(tr, local(corner_of(t, 0)), local(corner_of(t, 1)), local(corner_of(t, 2)));
        part_triangles_of_q.push_back(tr);
      }
    const std::size_t part_n = part_points.size();
    out.largest_part_triangles = std::max(out.largest_part_triangles, part_triangles_of_q.size());
    Orientation_decisions decisions;
    decisions.with_triangles = part_meets_another[q] != 0;
    {
      Soup_orienter<PointRange, TriangleRange, Kernel> orienter(part_points, part_triangles_of_q, rules, kernel,
                                                                nullptr, &decisions);
      const auto counts = orienter.template run<ConcurrencyTag>();
      out.report.duplicate_triangles += counts.duplicate_triangles;
      out.report.orientation_flips += counts.orientation_flips;
      out.report.duplicated_points += counts.duplicated_points;
    }
    {
      const Soup_statistics s = compute_statistics<ConcurrencyTag>(
        part_points, Adjacency_tables(part_triangles_of_q, part_points.size(), ConcurrencyTag()));
      out.statistics.triangles += s.triangles;
      out.statistics.border_edges += s.border_edges;
      out.statistics.non_manifold_edges += s.non_manifold_edges;
      out.statistics.non_manifold_vertices += s.non_manifold_vertices;
      out.statistics.inconsistent_edges += s.inconsistent_edges;
      out.statistics.components += s.components;
      out.statistics.zero_area_triangles += s.zero_area_triangles;
    }
    // The kept triangles back in their places (the part's triangles found again in the same
    // order); a copy k of the part is point n + (copies before the part) + k until the copies are
    // numbered.
    std::vector<size_type> kept; // kept triangle -> index into `tris`
    kept.reserve(part_triangles_of_q.size());
    for(std::size_t t = 0, j = 0; t < m; ++t) {
      if(!in_this_part(t)) continue;
      if(!decisions.dropped.empty() && decisions.dropped[j]) state[t] = DROPPED;
      else kept.push_back(static_cast<size_type>(t));
      ++j;
    }
    const std::size_t first_copy = n + copied_from.size();
    const auto to_soup = [&](std::size_t v) {
      return v < part_n ? std::size_t(global_point[v]) : first_copy + (v - part_n);
    };
    for(std::size_t k = 0; k < kept.size(); ++k) {
      const std::array<std::size_t, 3> c = triangle_indices(part_triangles_of_q[k]);
      assign_triangle(tris[kept[k]], to_soup(c[0]), to_soup(c[1]), to_soup(c[2]));
      state[kept[k]] = WRITTEN;
    }
    for(std::size_t v : decisions.copied_from) copied_from.push_back(global_point[v]);
    if(part_meets_another[q])
      for(Orientation_decisions::Closed_patch& c : decisions.closed) {
        for(size_type& t : c.triangles) t = kept[t];
        closed.push_back(std::move(c));
        part_of_closed.push_back(static_cast<std::uint32_t>(q));
      }
  }
  Union_find::Parents().swap(part_of);

  // The point of a corner: a copy has the coordinates of the point it copies.
  const auto xyz = [&](std::size_t v) {
    const Point& p = pts[v < n ? v : copied_from[v - n]];
    return std::array<double, 3>{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
  };
  // The nesting across parts: the closed patches of other parts that enclose each closed patch.
  // Their winding numbers are summed as `Soup_orienter` sums them: in the order of the traversal,
  // each triangle as the consistent orientation ran it (as written, turned back if its patch was).
  if(rules.nest_closed_patches && parts > 1 && closed.size() > 1) {
    std::vector<Box_bounds> boxes(closed.size());
    for(std::size_t c = 0; c < closed.size(); ++c) boxes[c] = closed[c].box;
    std::vector<std::size_t> depth(closed.size(), 0);
    for_each_box_inside_another(boxes, [&](std::size_t outer, std::size_t inner) {
      if(part_of_closed[outer] == part_of_closed[inner]) return; // counted within the part
      const std::array<double, 3>& q = closed[inner].sample;
      double sum = 0;
      for(size_type t : closed[outer].triangles) {
        const std::array<std::size_t, 3> v = triangle_indices(tris[t]);
        std::array<double, 3> c[3];
        for(std::size_t i = 0; i < 3; ++i) {
          const std::array<double, 3> x = xyz(v[i]);
          c[i] = {x[0] - q[0], x[1] - q[1], x[2] - q[2]};
        }
        if(closed[outer].turned) std::swap(c[1], c[2]);
        sum += twice_solid_angle(c);
      }
      if(std::abs(sum / (4 * 3.14159265358979323846)) > 0.5) ++depth[inner];
    });
    for(std::size_t c = 0; c < closed.size(); ++c) {
      if(!closed[c].by_volume || depth[c] % 2 == 0) continue;
      for(size_type t : closed[c].triangles) {
        const std::array<std::size_t, 3> v = triangle_indices(tris[t]);
        assign_triangle(tris[t], v[0], v[2], v[1]);
      }
      out.report.orientation_flips += closed[c].triangles.size() - 2 * closed[c].flipped;
      ++out.turned_across_parts;
    }
  }
  std::vector<Orientation_decisions::Closed_patch>().swap(closed);

  // The copies numbered vertex after vertex in the order of the soup (those of one point come
  // from one part, in their order there), then the corners renamed and the points appended.
  if(!copied_from.empty()) {
    std::vector<size_type> order(copied_from.size());
    for(std::size_t k = 0; k < order.size(); ++k) order[k] = static_cast<size_type>(k);
    std::stable_sort(order.begin(), order.end(),
                     [&](size_type a, size_type b) { return copied_from[a] < copied_from[b]; });
    std::vector<size_type> final_index(order.size());
    for(std::size_t r = 0; r < order.size(); ++r) final_index[order[r]] = static_cast<size_type>(n + r);
    for(std::size_t t = 0; t < m; ++t) {
      if(state[t] == DROPPED) continue;
      const std::array<std::size_t, 3> v = triangle_indices(tris[t]);
      if(v[0] < n && v[1] < n && v[2] < n) continue;
      const auto renamed = [&](std::size_t c) { return c < n ? c : std::size_t(final_index[c - n]); };
      assign_triangle(tris[t], renamed(v[0]), renamed(v[1]), renamed(v[2]));
    }
    pts.reserve(n + order.size());
    for(size_type k : order) {
      const Point copy = pts[copied_from[k]];
      pts.push_back(copy);
    }
  }
  std::size_t kept = 0;
  for(std::size_t t = 0; t < m; ++t)
    if(state[t] != DROPPED) {
      if(kept != t) tris[kept] = tris[t];
      ++kept;
    }
  tris.resize(kept);
  out.statistics.vertices = pts.size();
  out.statistics.closed = out.statistics.border_edges == 0;
  return out;
}

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_ORIENT_SOUP_IN_PARTS_H
