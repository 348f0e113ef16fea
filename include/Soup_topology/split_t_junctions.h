// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Pipeline step 3: T-junction repair (the patent's synchronisation of strips, Figures 7-9) by
// splitting triangles at existing vertices, with rule tables (15) and (17).

#ifndef SOUP_TOPOLOGY_SPLIT_T_JUNCTIONS_H
#define SOUP_TOPOLOGY_SPLIT_T_JUNCTIONS_H

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/Octree.h>
#include <Soup_topology/parameters.h>
#include <Soup_topology/internal/exact_signs.h>
#include <Soup_topology/internal/soup_checks.h>
#include <Soup_topology/internal/tolerance.h>
#include <Soup_topology/internal/tolerance_graph.h>

#include <CGAL/Cartesian_converter.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Kernel_traits.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace Soup_topology {

/// \ingroup PkgSoupTopologyTJunctions
/// \brief what `split_t_junctions()` did.
struct Split_report
{
  double tolerance = 0;                   ///< the absolute tolerance used
  std::size_t t_junctions = 0;            ///< (border edge, vertex) pairs accepted as T-junctions
  std::size_t split_triangles = 0;        ///< splits done (each adds one triangle)
  std::size_t refused_overlap = 0;        ///< vertices whose border edge would overlap the split triangle
  std::size_t refused_degenerate = 0;     ///< splits refused: a new triangle would be degenerate
  std::size_t refused_flip = 0;           ///< splits refused: a new triangle would reverse its normal
  std::size_t ambiguous = 0;              ///< vertices near several border edges, or within twice the tolerance of an end point
  std::size_t border_edges_before = 0;    ///< border edges before
  std::size_t border_edges_after = 0;     ///< border edges after
};

namespace internal {

// A border edge found at the start, identified by its end vertices (triangle ids change while
// splitting) and the triangle's third vertex.
struct Pending_edge
{
  Adjacency_tables::size_type a, b;
  std::vector<Adjacency_tables::size_type> on_edge;
};

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

/// \ingroup PkgSoupTopologyTJunctions
/// \brief repairs T-junctions: a vertex lying within the tolerance of the interior of a border
/// edge of another triangle, with its own border edge running along that edge from the other side.
///
/// For every border edge `[a,b]` of a triangle `t`, the vertices within the tolerance of the
/// closed segment (`Octree::vertices_near_segment()`, decided by `Compare_squared_distance_3`)
/// that are farther than the tolerance from `a` and from `b` are candidates; so is a vertex
/// within the tolerance of an end point it shares a triangle with (a weld can never merge those
/// two, so the vertex is not claimed twice). A vertex between one and two tolerances of an end
/// point it does not share a triangle with may be an unwelded copy of that end point (a split
/// there would make a sliver): it is accepted only if its border edge along `[a,b]` ends at that
/// very end point, and is otherwise counted as ambiguous. A candidate `c` is
/// accepted if one of its border edges `[c,d]` belongs to another triangle and runs along `[a,b]`
/// (`d` is within the tolerance of `[a,b]`, or `a` or `b` is within the tolerance of `[c,d]`: the
/// two borders may be sampled independently), and that triangle does not overlap
/// `t` (their apexes are not on the same side of the line `ab` in a common plane).
/// A vertex near several border edges goes to the nearest one (distances compared exactly;
/// ties: the lexicographically smallest edge) and is counted as ambiguous. The accepted vertices of an edge are sorted along it
/// and `t` is split at each in turn by rule table (15), with the vertex table updated by rule
/// table (17) (`Adjacency_tables::split_triangle()`). A vertex whose split would create a
/// degenerate triangle or reverse a normal (exact predicates) is refused.
/// No point is constructed: splits reuse existing vertices.
///
/// **Dense clusters.** Where a cell of a grid whose cells have a diagonal just below the tolerance
/// holds more than 64 border vertices, a border edge shorter than twice the tolerance does not
/// list the cells that lie entirely within the tolerance of one of its end points: their
/// vertices are welds of that end point, not T-junctions, except those that share a triangle with
/// it, which are taken from the triangles. The vertices examined, and so every decision, are the
/// same; a cluster of n border vertices within the tolerance of each other is not listed once per
/// edge (n^2 work). The fan check along an edge is linear in the number of vertices on it.
///
/// New triangles are appended to `triangles` (which must support `push_back`), in the order of
/// the border edges, then along each edge.
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{snapping_tolerance} \cgalParamType{`geom_traits::FT`} \cgalParamDefault{0} \cgalParamNEnd
///   \cgalParamNBegin{relative_tolerance} \cgalParamType{`double`} \cgalParamDescription{fraction of the
///     bounding-box diagonal; exclusive with `snapping_tolerance`} \cgalParamNEnd
///   \cgalParamNBegin{point_map} \cgalParamType{a readable property map to `Point_3`} \cgalParamNEnd
///   \cgalParamNBegin{geom_traits} \cgalParamType{a CGAL Kernel} \cgalParamNEnd
/// \cgalNamedParamsEnd
/// \throws Invalid_input for an invalid tolerance, non-finite coordinates or mismatched tables.
template <class PointRange, class TriangleRange, class NamedParameters = CGAL::parameters::Default_named_parameters>
Split_report split_t_junctions(const PointRange& points, TriangleRange& triangles, Adjacency_tables& tables,
                               const NamedParameters& np = CGAL::parameters::default_values())
{
  using NP_helper = internal::Soup_np_helper<PointRange, NamedParameters>;
  using Point = typename NP_helper::Point;
  using Kernel = typename NP_helper::Geom_traits;
  using FT = typename NP_helper::FT;
  using size_type = Adjacency_tables::size_type;

  const Kernel kernel = NP_helper::get_geom_traits(np);
  const FT eps = NP_helper::checked_tolerance("split_t_junctions", points, triangles, tables, np);
  const FT eps2 = eps * eps;

  // The points, read once: a readable map may return them by value.
  const std::vector<Point> point_copy = NP_helper::read_points(points, np);
  auto point = [&](std::size_t v) -> const Point& { return point_copy[v]; };
  typename Kernel::Compare_squared_distance_3 compare_sq = kernel.compare_squared_distance_3_object();
  typename Kernel::Compare_distance_3 compare_distance = kernel.compare_distance_3_object();
  typename Kernel::Less_xyz_3 less_xyz = kernel.less_xyz_3_object();
  typename Kernel::Orientation_3 orientation = kernel.orientation_3_object();
  typename Kernel::Coplanar_orientation_3 coplanar_orientation = kernel.coplanar_orientation_3_object();
  typename Kernel::Collinear_3 collinear = kernel.collinear_3_object();
  typename Kernel::Construct_segment_3 segment = kernel.construct_segment_3_object();

  Split_report report;
  report.tolerance = CGAL::to_double(eps);
  report.border_edges_before = tables.number_of_border_edges();
  const std::vector<Adjacency_tables::Edge> border = tables.border_edges();
  if(border.empty()) return report;

  // The border vertices and a spatial index over them.
  std::vector<size_type> border_vertices;
  for(const Adjacency_tables::Edge& e : border) {
    border_vertices.push_back(tables.vertex(e.triangle, e.index));
    border_vertices.push_back(tables.vertex(e.triangle, (e.index + 1) % 3));
  }
  std::sort(border_vertices.begin(), border_vertices.end());
  border_vertices.erase(std::unique(border_vertices.begin(), border_vertices.end()), border_vertices.end());
  std::vector<Point> border_points;
  border_points.reserve(border_vertices.size());
  for(size_type v : border_vertices) border_points.push_back(point(v));
  using Tree_traits = internal::Kernel_with_near_end_shortcut<Kernel>;
  const Octree<Tree_traits> tree(border_points, CGAL::Identity_property_map<Point>(), Tree_traits(kernel));
  // With a dense cluster of border vertices, a short edge inside it would list the whole cluster,
  // whose vertices are all within the tolerance of an end point (welds, not T-junctions): the
  // grid skips the cells that lie within the tolerance of an end point, and the vertices that
  // share a triangle with an end point (which may still be T-junctions) are added from the
  // triangles. The vertices examined below are the same; the cluster is not listed per edge.
  internal::Tolerance_grid<Kernel> grid(border_points, eps, kernel);
  const bool dense = grid.usable() && grid.largest_cell() > internal::dense_cell_size;
  const std::uint32_t not_border = static_cast<std::uint32_t>(-1);
  std::vector<std::uint32_t> border_index;
  if(dense) {
    border_index.assign(points.size(), not_border);
    for(std::size_t f = 0; f < border_vertices.size(); ++f) border_index[border_vertices[f]] = static_cast<std::uint32_t>(f);
  }

  // A vertex clearly within the tolerance of an end point (in double, for double coordinates) is
  // within it of the segment: the exact predicate is asked only when that does not decide (it
  // is slow on the tiny segments of a dense cluster).
  const double eps2d = CGAL::to_double(eps2);
  auto near_segment = [&](size_type v, size_type a, size_type b) {
    if(internal::surely_within(point(v), point(a), eps2d) || internal::surely_within(point(v), point(b), eps2d)) return true;
    return compare_sq(point(v), segment(point(a), point(b)), eps2) != CGAL::LARGER;
  };
  auto near_vertex = [&](size_type v, size_type a) {
    return internal::surely_within(point(v), point(a), eps2d) || compare_sq(point(v), point(a), eps2) != CGAL::LARGER;
  };
  const FT four_eps2 = 4 * eps2;
  auto near_vertex2 = [&](size_type v, size_type a) {
    return internal::surely_within(point(v), point(a), 4 * eps2d) || compare_sq(point(v), point(a), four_eps2) != CGAL::LARGER;
  };
  auto share_triangle = [&](size_type u, size_type v) {
    for(size_type t : tables.triangles_around_vertex(u)) if(tables.local_index(t, v) >= 0) return true;
    return false;
  };

  // 1. Candidate (edge, vertex) pairs.
  std::vector<internal::Pending_edge> pending(border.size());
  std::vector<std::pair<size_type, std::uint32_t>> claims; // (vertex, pending edge)
  std::vector<std::size_t> found;
  for(std::size_t k = 0; k < border.size(); ++k) {
    const Adjacency_tables::Edge& e = border[k];
    const size_type a = tables.vertex(e.triangle, e.index), b = tables.vertex(e.triangle, (e.index + 1) % 3);
    const size_type apex = tables.vertex(e.triangle, (e.index + 2) % 3);
    pending[k] = internal::Pending_edge{a, b, {}};
    found.clear();
    if(dense && grid.is_short(point(a), point(b))) {
      grid.for_each_point_near_box(point(a), point(b), [&](std::uint32_t f) {
        if(near_segment(border_vertices[f], a, b)) found.push_back(f);
      });
      for(size_type end : {a, b})
        for(size_type t : tables.triangles_around_vertex(end))
          for(size_type w : tables.triangle(t))
            if(border_index[w] != not_border && near_segment(w, a, b)) found.push_back(border_index[w]);
      std::sort(found.begin(), found.end());
      found.erase(std::unique(found.begin(), found.end()), found.end());
    } else {
      // The same answer by either strategy; the index-space box of a long segment is most of the
      // workspace, so long segments cull the boxes along the segment instead.
      const double length2 = CGAL::to_double(kernel.compute_squared_distance_3_object()(point(a), point(b)));
      const Segment_query_strategy strategy = length2 > 64 * eps2d ? Segment_query_strategy::NEIGHBORHOOD_CULLING
                                                                   : tree.segment_query_strategy();
      tree.vertices_near_segment(point(a), point(b), eps, std::back_inserter(found), strategy);
    }
    for(std::size_t f : found) {
      const size_type c = border_vertices[f];
      if(c == a || c == b || c == apex) continue;
      // Within the tolerance of an end point: that is a weld, not a T-junction, unless the two
      // vertices share a triangle (no weld can merge them). Within twice the tolerance, the vertex
      // may be an unwelded copy of the end point, and a split there would make a sliver: it is
      // accepted only if its own border edge ends at that end point (below), else counted as
      // ambiguous (the minimum feature separation is not met).
      if((near_vertex(c, a) && !share_triangle(c, a)) || (near_vertex(c, b) && !share_triangle(c, b))) continue;
      const bool close_to_a = near_vertex2(c, a) && !share_triangle(c, a);
      const bool close_to_b = near_vertex2(c, b) && !share_triangle(c, b);
      // A border edge of c, in another triangle, running along [a,b]. Near an end point, only
      // the border edge from c to that very end point counts: the split then mirrors the short
      // edge the other side already has.
      bool along = false, overlap_only = false;
      for(size_type t2 : tables.triangles_around_vertex(c)) {
        if(t2 == e.triangle) continue;
        const int ic = tables.local_index(t2, c);
        for(int j : {ic, (ic + 2) % 3}) {
          if(!tables.is_border_edge(t2, j)) continue;
          const size_type d = (j == ic) ? tables.vertex(t2, (ic + 1) % 3) : tables.vertex(t2, (ic + 2) % 3);
          // The two border edges run along each other: one end of either lies within the
          // tolerance of the other segment (vertex-segment tests only, never the infinite line).
          if(!(d == a || d == b || near_segment(d, a, b) || near_segment(a, c, d) || near_segment(b, c, d))) continue;
          if((close_to_a && d != a) || (close_to_b && d != b)) continue;
          const size_type x = tables.vertex(t2, (j + 2) % 3); // apex of t2 across [c,d]
          const bool overlaps = orientation(point(a), point(b), point(apex), point(x)) == CGAL::COPLANAR &&
                                !collinear(point(a), point(b), point(x)) &&
                                coplanar_orientation(point(a), point(b), point(apex), point(x)) == CGAL::POSITIVE;
          if(overlaps) overlap_only = true;
          else along = true;
        }
      }
      if(along) claims.emplace_back(c, static_cast<std::uint32_t>(k));
      else if(overlap_only) ++report.refused_overlap;
      else if(close_to_a || close_to_b) ++report.ambiguous;
    }
  }

  // 2. A vertex claimed by several edges goes to the nearest one.
  std::sort(claims.begin(), claims.end());
  auto edge_less = [&](std::uint32_t x, std::uint32_t y) {
    const Point& ax = point(pending[x].a); const Point& bx = point(pending[x].b);
    const Point& ay = point(pending[y].a); const Point& by = point(pending[y].b);
    const Point& lx = less_xyz(ax, bx) ? ax : bx; const Point& hx = less_xyz(ax, bx) ? bx : ax;
    const Point& ly = less_xyz(ay, by) ? ay : by; const Point& hy = less_xyz(ay, by) ? by : ay;
    if(less_xyz(lx, ly)) return true;
    if(less_xyz(ly, lx)) return false;
    return less_xyz(hx, hy);
  };
  for(std::size_t i = 0; i < claims.size();) {
    std::size_t j = i;
    while(j < claims.size() && claims[j].first == claims[i].first) ++j;
    const size_type c = claims[i].first;
    std::uint32_t best = claims[i].second;
    for(std::size_t k = i + 1; k < j; ++k) {
      const std::uint32_t e = claims[k].second;
      const CGAL::Comparison_result r = internal::compare_point_segment_distances(
        point(c), point(pending[e].a), point(pending[e].b), point(pending[best].a), point(pending[best].b));
      if(r == CGAL::SMALLER || (r == CGAL::EQUAL && edge_less(e, best))) best = e;
    }
    if(j - i > 1) ++report.ambiguous;
    pending[best].on_edge.push_back(c);
    i = j;
  }

  // 3. Split, edge by edge, along each edge from a to b. Two edges of one triangle may both be
  // split: the edges are processed in a geometric order (lexicographic end points) so that the
  // result does not depend on the order of the triangles.
  std::vector<std::uint32_t> order;
  for(std::uint32_t k = 0; k < pending.size(); ++k) if(!pending[k].on_edge.empty()) order.push_back(k);
  std::sort(order.begin(), order.end(), edge_less);
  std::vector<size_type> changed;
  for(std::uint32_t k : order) {
    internal::Pending_edge& pe = pending[k];
    std::sort(pe.on_edge.begin(), pe.on_edge.end(), [&](size_type x, size_type y) {
      const CGAL::Comparison_result r = compare_distance(point(pe.a), point(x), point(y));
      if(r != CGAL::EQUAL) return r == CGAL::SMALLER;
      return less_xyz(point(x), point(y));
    });
    // Locate the triangle that holds the border edge [a,b] now (an earlier split on another edge
    // of the same triangle may have moved it to a new triangle with another apex).
    size_type t = Adjacency_tables::border_edge;
    int i = -1;
    for(size_type u : tables.triangles_around_vertex(pe.a)) {
      const int j = tables.edge_index(u, pe.a, pe.b);
      if(j >= 0 && tables.vertex(u, j) == pe.a && tables.is_border_edge(u, j)) { t = u; i = j; break; }
    }
    if(t == Adjacency_tables::border_edge) continue;
    const size_type apex = tables.vertex(t, (i + 2) % 3);
    // Refuse the vertices whose fan triangle (previous, c, apex) or (c, next, apex) would be
    // degenerate or flipped relative to (a, b, apex): the first failing fan triangle along the
    // edge loses its on-edge vertex (the one nearer b when both are), until the whole fan is
    // valid. The fan before a failure is unchanged by the drop, so the scan resumes there: one
    // pass over a doubly linked chain, linear in the number of vertices on the edge.
    if(!pe.on_edge.empty()) {
      const std::size_t m = pe.on_edge.size();
      std::vector<size_type> chain;
      chain.reserve(m + 2);
      chain.push_back(pe.a);
      chain.insert(chain.end(), pe.on_edge.begin(), pe.on_edge.end());
      chain.push_back(pe.b);
      const std::size_t last = m + 1;
      std::vector<std::size_t> next(m + 2), previous(m + 2);
      for(std::size_t j = 0; j <= last; ++j) { next[j] = j + 1; previous[j] = j == 0 ? 0 : j - 1; }
      std::vector<char> dropped(m + 2, 0);
      std::size_t left = 0;
      while(left != last && next[0] != last) {
        const std::size_t right = next[left];
        const Point& p = point(chain[left]);
        const Point& q = point(chain[right]);
        const bool degenerate = collinear(p, q, point(apex));
        const bool flipped = !degenerate &&
          internal::sign_of_normal_dot(point(pe.a), point(pe.b), point(apex), p, q, point(apex)) != CGAL::POSITIVE;
        if(!degenerate && !flipped) { left = right; continue; }
        if(degenerate) ++report.refused_degenerate; else ++report.refused_flip;
        if(right != last) {
          dropped[right] = 1;
          next[left] = next[right];
          previous[next[right]] = left;
        } else {
          // left is an on-edge vertex: the loop stops when none is left.
          dropped[left] = 1;
          const std::size_t before = previous[left];
          next[before] = last;
          previous[last] = before;
          left = before;
        }
      }
      std::size_t kept = 0;
      for(std::size_t j = 1; j <= m; ++j)
        if(!dropped[j]) pe.on_edge[kept++] = chain[j];
      pe.on_edge.resize(kept);
    }
    if(pe.on_edge.empty()) continue;
    report.t_junctions += pe.on_edge.size();
    for(size_type c : pe.on_edge) {
      const size_type t_new = tables.split_triangle(t, i, c);
      changed.push_back(t);
      changed.push_back(t_new);
      ++report.split_triangles;
      t = t_new; // the rest of the edge, (c, b), is edge i of the new triangle
    }
  }

  // 4. Write the triangles back: the split ones and the new ones.
  using Face = typename TriangleRange::value_type;
  for(size_type t : changed) {
    const Adjacency_tables::Triangle& tr = tables.triangle(t);
    while(triangles.size() <= t) triangles.push_back(internal::make_triangle<Face>(0, 0, 0));
    triangles[t] = internal::make_triangle<Face>(tr[0], tr[1], tr[2]);
  }
  report.border_edges_after = tables.number_of_border_edges();
  return report;
}

/// \ingroup PkgSoupTopologyTJunctions
/// \brief the same, building the adjacency tables first.
template <class PointRange, class TriangleRange, class NamedParameters = CGAL::parameters::Default_named_parameters>
Split_report split_t_junctions(const PointRange& points, TriangleRange& triangles,
                               const NamedParameters& np = CGAL::parameters::default_values())
{
  Adjacency_tables tables(triangles, points.size());
  return split_t_junctions(points, triangles, tables, np);
}

} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_SPLIT_T_JUNCTIONS_H
