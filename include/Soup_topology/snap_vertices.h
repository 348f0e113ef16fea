// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Pipeline step 2: welding of duplicate vertices within a tolerance (the patent's claim 4), with
// order-independent decisions taken by exact predicates.

#ifndef SOUP_TOPOLOGY_SNAP_VERTICES_H
#define SOUP_TOPOLOGY_SNAP_VERTICES_H

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/Octree.h>
#include <Soup_topology/parameters.h>
#include <Soup_topology/internal/exact_signs.h>
#include <Soup_topology/internal/soup_checks.h>
#include <Soup_topology/internal/tolerance.h>
#include <Soup_topology/internal/tolerance_graph.h>

#include <CGAL/Kernel_traits.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace Soup_topology {

/// \ingroup PkgSoupTopologyWelding
/// \brief why a merge was refused.
enum class Refusal_reason
{
  SAME_TRIANGLE,  ///< the two vertices belong to one triangle (merging would collapse it)
  DEGENERATE,     ///< a triangle around the moved vertex would become degenerate (collinear)
  FLIP,           ///< a triangle around the moved vertex would reverse its normal
  HOLDS_WELDS     ///< the vertex received welds earlier: moving it would carry them farther than the tolerance
};

/// \ingroup PkgSoupTopologyWelding
/// \brief a visitor that is told nothing; the default of the `visitor` parameter of
/// `snap_vertices()`. A user visitor provides the same two member functions.
struct Default_snap_visitor
{
  /// `duplicate` is merged into `representative`.
  void on_merge(std::size_t /*duplicate*/, std::size_t /*representative*/) {}
  /// the merge of `vertex` into `representative` is refused for `reason`.
  void on_refusal(std::size_t /*vertex*/, std::size_t /*representative*/, Refusal_reason /*reason*/) {}
};

/// \ingroup PkgSoupTopologyWelding
/// \brief what `snap_vertices()` did.
struct Snap_report
{
  double tolerance = 0;                       ///< the absolute tolerance used
  std::size_t candidate_vertices = 0;         ///< vertices on border edges before the weld
  std::size_t merged_vertices = 0;            ///< vertices merged into a representative
  std::size_t clusters = 0;                   ///< representatives that received at least one vertex
  std::size_t refused_same_triangle = 0;      ///< refusals: the two vertices share a triangle
  std::size_t refused_degenerate = 0;         ///< refusals: a triangle would become degenerate
  std::size_t refused_flip = 0;               ///< refusals: a triangle would flip
  std::size_t refused_holds_welds = 0;        ///< refusals: the vertex holds earlier welds (see `Refusal_reason`)
  /// ambiguous sites: the connected components of the tolerance graph (all pairs of candidates
  /// within the tolerance, vertices of one triangle included) that hold two vertices of one
  /// triangle, or whose vertices did not all go to one representative (a chain longer than the
  /// tolerance). Each site is listed by the index of its lexicographically smallest point, in
  /// increasing order: the sites do not depend on the order of the triangles, and follow a
  /// renumbering of the vertices.
  std::vector<std::size_t> ambiguous_sites;
  /// edges shorter than the tolerance (two vertices of one triangle closer than it): the minimum
  /// feature separation is not met there, and such pairs are never merged.
  std::size_t short_edges = 0;
  std::size_t border_edges_before = 0;        ///< border edges before the weld
  std::size_t border_edges_after = 0;         ///< border edges after the weld
  double max_displacement = 0;                ///< largest distance a merged vertex moved
  /// total number of refusals.
  std::size_t refused() const { return refused_same_triangle + refused_degenerate + refused_flip + refused_holds_welds; }
};

namespace internal_np {
/// internal: a `const std::vector<char>*`, nonzero for the vertices `snap_vertices()` may not move
enum fixed_vertices_t { fixed_vertices };
} // namespace internal_np

namespace internal {

/// a grid cell (of diagonal the tolerance) holding more candidates than this makes
/// `snap_vertices()` build the tolerance graph's components on the grid (same result, no pair list).
constexpr std::size_t dense_cell_size = 64;

template <class Kernel, class Point>
bool moves_keep_triangle(const Point& a, const Point& b, const Point& c,
                         const Point& na, const Point& nb, const Point& nc, Refusal_reason& why)
{
  typename Kernel::Collinear_3 collinear = Kernel().collinear_3_object();
  const bool was_degenerate = collinear(a, b, c);
  if(collinear(na, nb, nc)) {
    if(was_degenerate) return true; // nothing lost
    why = Refusal_reason::DEGENERATE;
    return false;
  }
  if(was_degenerate) return true;
  if(sign_of_normal_dot(a, b, c, na, nb, nc) != CGAL::POSITIVE) { why = Refusal_reason::FLIP; return false; }
  return true;
}

/// `true` if no moves of the corners of triangle (a, b, c) by at most `delta` each can make it
/// degenerate or reverse its normal: with n = (b - a) x (c - a), the moves change n by at most
/// 2 delta (|b - a| + |c - a|) + 4 delta^2, and a change smaller than |n| keeps n' . n > 0. Evaluated
/// in double with a 1% margin, for `double` coordinates only (otherwise `false`: ask the exact test).
template <class Point>
bool fat_enough_for_moves(const Point& a, const Point& b, const Point& c, double delta)
{
  using FT = typename CGAL::Kernel_traits<Point>::Kernel::FT;
  if constexpr(std::is_same<FT, double>::value) {
    const double u[3] = {b.x() - a.x(), b.y() - a.y(), b.z() - a.z()};
    const double v[3] = {c.x() - a.x(), c.y() - a.y(), c.z() - a.z()};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double norm_n = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const double lu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    const double lv = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    const double change = 2 * delta * (lu + lv) + 4 * delta * delta;
    return std::isfinite(norm_n) && norm_n > 1.01 * change + 1e-280;
  } else {
    (void)a; (void)b; (void)c; (void)delta;
    return false;
  }
}

/// compares the distances from `p` to `q` and to `r`: in double when they are far from equal
/// (double coordinates only: the squared distances are then within a few ulps of the exact
/// ones), else with the kernel's exact `Compare_distance_3`.
template <class Point, class CompareDistance>
CGAL::Comparison_result compare_distances(const Point& p, const Point& q, const Point& r,
                                          const CompareDistance& compare_distance)
{
  using FT = typename CGAL::Kernel_traits<Point>::Kernel::FT;
  if constexpr(std::is_same<FT, double>::value) {
    const double dq = (q.x() - p.x()) * (q.x() - p.x()) + (q.y() - p.y()) * (q.y() - p.y()) + (q.z() - p.z()) * (q.z() - p.z());
    const double dr = (r.x() - p.x()) * (r.x() - p.x()) + (r.y() - p.y()) * (r.y() - p.y()) + (r.z() - p.z()) * (r.z() - p.z());
    if(dq > 1e-250 && dr > 1e-250) {
      if(dq < dr * (1 - 1e-12)) return CGAL::SMALLER;
      if(dq > dr * (1 + 1e-12)) return CGAL::LARGER;
    }
  }
  return compare_distance(p, q, r);
}

} // namespace internal

/// \ingroup PkgSoupTopologyWelding
/// \brief merges the vertices of an indexed triangle soup that are duplicates within a tolerance,
/// following the patent's claim 4, and updates `tables` locally.
///
/// **Candidates.** Only the end points of border (unconnected) edges are candidates: a
/// well-connected region is never welded to itself.
///
/// **Decisions** (all by the kernel's predicates, exact with Epick and Epeck):
/// 1. the tolerance graph links two candidates within the tolerance of each other
///    (`Compare_squared_distance_3`); two vertices of one triangle are never merged (the pair is
///    refused);
/// 2. the candidates are cut into clusters by a canonical rule: the lexicographically smallest
///    candidate (`Less_xyz_3`, ties by index) is a representative; the candidates within the
///    tolerance of it that share no triangle with it join it, nearest first (ties by
///    `Less_xyz_3`), unless one shares a triangle with a vertex already in the cluster; the
///    smallest candidate left is the next representative, and so on. So no point moves farther
///    than the tolerance and merges never chain. A connected component of the tolerance graph
///    that holds two vertices of one triangle, or that needs more than one cluster, is an
///    ambiguous site (the minimum feature separation of Hoffmann, Hopcroft and Karasick is not
///    met there), listed by its lexicographically smallest point;
/// 3. a merge that would make a triangle degenerate or reverse its normal is refused (and the
///    other moves of that triangle with it), until every triangle is kept.
/// The representative keeps its coordinates: no point is constructed. The decisions depend on
/// the points only, not on the order of the triangles, the rotation of their corners or the
/// numbering of the vertices (for points that are pairwise distinct, which the exact weld ensures).
///
/// **Dense clusters.** The tolerance graph is never listed pair by pair where candidates crowd:
/// when a cell of a grid whose cells have a diagonal just below the tolerance holds more than 64
/// candidates, the components are found on the grid (the points of a cell are each linked to the
/// cell's first point, and two cells are joined by the first pair found within the tolerance,
/// one exact nearest-point query per point of the smaller cell), and the neighbours of each
/// representative are asked of an octree when it is chosen. Every link is still decided by
/// `Compare_squared_distance_3`, so the clusters and the sites are exactly those defined above;
/// only the cost changes: n candidates within the tolerance of each other cost O(n log n) plus
/// O(n) per representative among them, not the n^2 / 2 pairs. The grid is not used when the
/// tolerance is below about 1e-10 of the coordinates (or 1e-12 of the extent of the candidates),
/// where a cell index would be lost in rounding.
///
/// **Result.** Every reference to a merged vertex is replaced by its representative, in
/// `triangles` and in `tables` (`Adjacency_tables::replace_vertex()`). Merged vertices stay in
/// `points`, unreferenced (`reconstruct_topology()` removes them).
///
/// \tparam PointRange a random-access range of points (read through `point_map`)
/// \tparam TriangleRange a random-access range of triangles, each a random-access range of 3 indices
/// \param tables the tables of `triangles` over `points`, updated in place
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{snapping_tolerance} \cgalParamType{`geom_traits::FT`} \cgalParamDefault{0: only
///     border vertices with equal coordinates are merged} \cgalParamNEnd
///   \cgalParamNBegin{relative_tolerance} \cgalParamType{`double`} \cgalParamDescription{the tolerance as a
///     fraction of the bounding-box diagonal; exclusive with `snapping_tolerance`} \cgalParamNEnd
///   \cgalParamNBegin{point_map} \cgalParamType{a readable property map to `Point_3`}
///     \cgalParamDefault{`CGAL::Identity_property_map`} \cgalParamNEnd
///   \cgalParamNBegin{geom_traits} \cgalParamType{a CGAL Kernel} \cgalParamDefault{the kernel of the point type}
///     \cgalParamNEnd
///   \cgalParamNBegin{visitor} \cgalParamType{a class with `on_merge(std::size_t, std::size_t)` and
///     `on_refusal(std::size_t, std::size_t, Refusal_reason)`} \cgalParamDefault{`Default_snap_visitor`}
///     \cgalParamNEnd
/// \cgalNamedParamsEnd
/// \returns a `Snap_report`.
/// \throws Invalid_input for a negative, NaN or infinite tolerance, a non-finite coordinate, or
///         tables that do not match the soup. Nothing is changed then.
template <class PointRange, class TriangleRange, class NamedParameters = CGAL::parameters::Default_named_parameters>
Snap_report snap_vertices(const PointRange& points, TriangleRange& triangles, Adjacency_tables& tables,
                          const NamedParameters& np = CGAL::parameters::default_values())
{
  using NP_helper = internal::Soup_np_helper<PointRange, NamedParameters>;
  using Point = typename NP_helper::Point;
  using Kernel = typename NP_helper::Geom_traits;
  using FT = typename NP_helper::FT;
  using size_type = Adjacency_tables::size_type;

  const Kernel kernel = NP_helper::get_geom_traits(np);
  // The visitor: a reference when given as `std::ref(v)`, otherwise a copy.
  Default_snap_visitor default_visitor;
  auto&& visitor_given = CGAL::parameters::choose_parameter(
    CGAL::parameters::get_parameter_reference(np, CGAL::internal_np::visitor), default_visitor);
  using Visitor_given = decltype(visitor_given);
  std::conditional_t<std::is_const<std::remove_reference_t<Visitor_given>>::value, std::decay_t<Visitor_given>,
                     Visitor_given>
    visitor = visitor_given;
  const FT eps = NP_helper::checked_tolerance("snap_vertices", points, triangles, tables, np);
  // Vertices that may receive welds but not move (`reconstruct_topology()` fixes the
  // representatives of earlier rounds, so that no point moves farther than the tolerance in all).
  const std::vector<char>* fixed = CGAL::parameters::choose_parameter(
    CGAL::parameters::get_parameter(np, internal_np::fixed_vertices), static_cast<const std::vector<char>*>(nullptr));
  if(fixed != nullptr && fixed->size() != points.size()) fixed = nullptr;

  // The points, read once: a readable map may return them by value.
  const std::vector<Point> point_copy = NP_helper::read_points(points, np);
  auto point = [&](std::size_t v) -> const Point& { return point_copy[v]; };
  typename Kernel::Less_xyz_3 less_xyz = kernel.less_xyz_3_object();
  typename Kernel::Compare_distance_3 compare_distance = kernel.compare_distance_3_object();
  typename Kernel::Compute_squared_distance_3 squared_distance = kernel.compute_squared_distance_3_object();

  Snap_report report;
  report.tolerance = CGAL::to_double(eps);
  report.border_edges_before = tables.number_of_border_edges();

  // Short edges: where the minimum feature separation is not met.
  {
    typename Kernel::Compare_squared_distance_3 compare_sq = kernel.compare_squared_distance_3_object();
    const FT eps2 = eps * eps;
    // With double coordinates, a squared length far above eps2 (computed in double, within a
    // few ulps of the exact value) is decided without the exact predicate.
    const double eps2d = CGAL::to_double(eps2);
    constexpr bool double_coordinates = std::is_same<FT, double>::value;
    for(size_type t = 0; t < tables.number_of_triangles(); ++t)
      for(int i = 0; i < 3; ++i) {
        const size_type u = tables.neighbor(t, i);
        if(u != Adjacency_tables::border_edge && u != Adjacency_tables::non_manifold_edge && u < t) continue; // once per edge
        const Point& p = point(tables.vertex(t, i));
        const Point& q = point(tables.vertex(t, (i + 1) % 3));
        if constexpr(double_coordinates) {
          const double dx = p.x() - q.x(), dy = p.y() - q.y(), dz = p.z() - q.z();
          const double d2 = dx * dx + dy * dy + dz * dz;
          if(d2 > eps2d * (1 + 1e-12) && d2 > 1e-250) continue;
        }
        if(compare_sq(p, q, eps2) != CGAL::LARGER) ++report.short_edges;
      }
  }

  // 1. Candidates: the end points of border edges, in increasing index order.
  std::vector<size_type> candidates;
  {
    std::vector<char> on_border(points.size(), 0);
    for(size_type t = 0; t < tables.number_of_triangles(); ++t)
      for(int i = 0; i < 3; ++i)
        if(tables.is_border_edge(t, i)) on_border[tables.vertex(t, i)] = on_border[tables.vertex(t, (i + 1) % 3)] = 1;
    for(size_type v = 0; v < points.size(); ++v) if(on_border[v]) candidates.push_back(v);
  }
  report.candidate_vertices = candidates.size();
  if(candidates.size() < 2) { report.border_edges_after = report.border_edges_before; return report; }

  // 2. The tolerance graph over the candidates (local ids). Pairs of one triangle within the
  // tolerance are never merged: they are found from the triangles, and refused.
  const std::size_t n = candidates.size();
  std::vector<Point> candidate_points;
  candidate_points.reserve(n);
  for(size_type v : candidates) candidate_points.push_back(point(v));
  const Octree<Kernel> tree(candidate_points, CGAL::Identity_property_map<Point>(), kernel);
  const std::uint32_t not_candidate = static_cast<std::uint32_t>(-1);
  std::vector<std::uint32_t> local(points.size(), not_candidate);
  for(std::size_t c = 0; c < n; ++c) local[candidates[c]] = static_cast<std::uint32_t>(c);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> same_triangle_pairs;
  {
    typename Kernel::Compare_squared_distance_3 compare_sq = kernel.compare_squared_distance_3_object();
    const FT eps2 = eps * eps;
    for(size_type t = 0; t < tables.number_of_triangles(); ++t)
      for(int i = 0; i < 3; ++i) {
        const std::uint32_t a = local[tables.vertex(t, i)], b = local[tables.vertex(t, (i + 1) % 3)];
        if(a == not_candidate || b == not_candidate) continue;
        if(compare_sq(candidate_points[a], candidate_points[b], eps2) != CGAL::LARGER)
          same_triangle_pairs.emplace_back(std::min(a, b), std::max(a, b));
      }
    // In the order of the octree's self-join (Morton order of the first vertex), once each.
    std::sort(same_triangle_pairs.begin(), same_triangle_pairs.end(), [&](const auto& x, const auto& y) {
      const std::uint64_t cx = tree.morton_code(x.first), cy = tree.morton_code(y.first);
      return cx < cy || (cx == cy && x < y);
    });
    same_triangle_pairs.erase(std::unique(same_triangle_pairs.begin(), same_triangle_pairs.end()),
                              same_triangle_pairs.end());
  }

  // The connected components of the tolerance graph (same-triangle pairs included): the sites
  // reported as ambiguous are components. With a dense cluster (many candidates in a cell of the
  // grid whose diagonal is the tolerance), a grid joins whole cells without listing their pairs,
  // and the neighbours of a representative are asked of the octree when it is chosen. Otherwise
  // one self-join over the octree gives every neighbourhood at once. Both decide every pair by
  // the same exact predicate: the components and the clusters are the same.
  internal::Union_find components(n);
  internal::Tolerance_grid<Kernel> grid(candidate_points, eps, kernel);
  const bool dense = grid.usable() && grid.largest_cell() > internal::dense_cell_size;
  std::vector<std::uint32_t> row;
  std::vector<std::size_t> row_start, row_end;
  if(dense) {
    grid.unite_components(components);
  } else {
    // Rows filled in Morton order, then indexed by candidate; same-triangle pairs are left out.
    row_start.resize(n);
    row_end.resize(n);
    std::vector<char> mate(points.size(), 0);
    tree.for_each_neighborhood(eps, [&](std::size_t c, const std::vector<std::size_t>& found) {
      for(size_type t : tables.triangles_around_vertex(candidates[c]))
        for(size_type v : tables.triangle(t)) mate[v] = 1;
      row_start[c] = row.size();
      for(std::size_t d : found) {
        if(d == c) continue;
        components.unite(static_cast<std::uint32_t>(c), static_cast<std::uint32_t>(d));
        if(!mate[candidates[d]]) row.push_back(static_cast<std::uint32_t>(d));
      }
      row_end[c] = row.size();
      for(size_type t : tables.triangles_around_vertex(candidates[c]))
        for(size_type v : tables.triangle(t)) mate[v] = 0;
    });
  }

  for(const auto& pr : same_triangle_pairs) {
    ++report.refused_same_triangle;
    visitor.on_refusal(candidates[pr.second], candidates[pr.first], Refusal_reason::SAME_TRIANGLE);
  }

  // 3. Clusters: canonical representatives, no chaining, no two vertices of one triangle. The
  // candidates are visited in lexicographic order (ties: index); an unassigned one is the
  // smallest unassigned candidate of its component, and becomes a representative.
  std::vector<std::uint32_t> lex_order(n);
  std::iota(lex_order.begin(), lex_order.end(), 0u);
  std::stable_sort(lex_order.begin(), lex_order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return less_xyz(candidate_points[a], candidate_points[b]);
  });
  const size_type none = static_cast<size_type>(-1);
  std::vector<size_type> target(points.size(), none);      // representative of a merged vertex
  std::vector<std::uint32_t> in_cluster_mark(tables.number_of_triangles(), static_cast<std::uint32_t>(-1));
  std::vector<std::uint32_t> mate_of(points.size(), not_candidate); // marks the vertices sharing a triangle with the representative
  std::vector<bool> assigned(n, false);
  std::vector<std::uint32_t> members;
  std::vector<std::size_t> found;
  std::vector<std::uint32_t> component_size(n, 0), largest_cluster(n, 0);
  for(std::uint32_t c = 0; c < n; ++c) ++component_size[components.find(c)];
  std::uint32_t cluster_id = 0;
  for(const std::uint32_t rep : lex_order) {
    if(assigned[rep]) continue;
    assigned[rep] = true;
    const std::uint32_t root = components.find(rep);
    if(component_size[root] < 2) continue;
    const size_type rep_v = candidates[rep];
    members.clear();
    if(dense) {
      for(size_type t : tables.triangles_around_vertex(rep_v))
        for(size_type v : tables.triangle(t)) mate_of[v] = rep;
      found.clear();
      tree.vertices_near_point(candidate_points[rep], eps, std::back_inserter(found));
      for(std::size_t d : found)
        if(d != rep && !assigned[d] && mate_of[candidates[d]] != rep) members.push_back(static_cast<std::uint32_t>(d));
    } else {
      for(std::size_t k = row_start[rep]; k < row_end[rep]; ++k)
        if(!assigned[row[k]]) members.push_back(row[k]);
    }
    std::sort(members.begin(), members.end(), [&](std::uint32_t a, std::uint32_t b) {
      const CGAL::Comparison_result r = internal::compare_distances(candidate_points[rep], candidate_points[a],
                                                                    candidate_points[b], compare_distance);
      if(r != CGAL::EQUAL) return r == CGAL::SMALLER;
      return less_xyz(candidate_points[a], candidate_points[b]);
    });
    members.erase(std::unique(members.begin(), members.end()), members.end());
    ++cluster_id;
    for(size_type t : tables.triangles_around_vertex(rep_v)) in_cluster_mark[t] = cluster_id;
    std::uint32_t cluster_size = 1;
    for(std::uint32_t m : members) {
      const size_type mv = candidates[m];
      if(fixed != nullptr && (*fixed)[mv]) {
        // mv received welds in an earlier call: it may be a representative, never move.
        ++report.refused_holds_welds;
        visitor.on_refusal(mv, rep_v, Refusal_reason::HOLDS_WELDS);
        continue;
      }
      bool conflict = false;
      for(size_type t : tables.triangles_around_vertex(mv)) if(in_cluster_mark[t] == cluster_id) { conflict = true; break; }
      if(conflict) {
        ++report.refused_same_triangle;
        visitor.on_refusal(mv, rep_v, Refusal_reason::SAME_TRIANGLE);
        continue;
      }
      for(size_type t : tables.triangles_around_vertex(mv)) in_cluster_mark[t] = cluster_id;
      assigned[m] = true;
      target[mv] = rep_v;
      ++cluster_size;
    }
    largest_cluster[root] = std::max(largest_cluster[root], cluster_size);
  }

  // Ambiguous sites: the components that hold two vertices of one triangle, or that did not all
  // go to one representative. Each is listed by its lexicographically smallest point, so that
  // the sites do not depend on the numbering of the vertices.
  {
    std::vector<char> ambiguous(n, 0);
    for(const auto& pr : same_triangle_pairs) ambiguous[components.find(pr.first)] = 1;
    for(std::uint32_t c = 0; c < n; ++c)
      if(components.find(c) == c && component_size[c] >= 2 && largest_cluster[c] != component_size[c]) ambiguous[c] = 1;
    for(const std::uint32_t c : lex_order) {
      const std::uint32_t root = components.find(c);
      if(ambiguous[root]) {
        report.ambiguous_sites.push_back(candidates[c]);
        ambiguous[root] = 0;
      }
    }
    std::sort(report.ambiguous_sites.begin(), report.ambiguous_sites.end());
  }

  // 4. Geometric validity: no triangle may become degenerate or flip; refuse until stable.
  auto final_vertex = [&](size_type v) { return target[v] == none ? v : target[v]; };
  std::vector<size_type> touched;
  {
    std::vector<char> is_touched(tables.number_of_triangles(), 0);
    for(size_type v : candidates)
      if(target[v] != none) for(size_type t : tables.triangles_around_vertex(v)) is_touched[t] = 1;
    for(size_type t = 0; t < tables.number_of_triangles(); ++t) if(is_touched[t]) touched.push_back(t);
  }
  // Each pass checks every touched triangle against the moves of the previous pass and cancels
  // the moves of all failing triangles at once, so the result does not depend on the order in
  // which the triangles are stored.
  std::vector<std::pair<size_type, Refusal_reason>> cancelled;
  for(bool changed = true; changed;) {
    changed = false;
    cancelled.clear();
    for(size_type t : touched) {
      const Adjacency_tables::Triangle& tr = tables.triangle(t);
      const size_type n0 = final_vertex(tr[0]), n1 = final_vertex(tr[1]), n2 = final_vertex(tr[2]);
      if(n0 == tr[0] && n1 == tr[1] && n2 == tr[2]) continue;
      Refusal_reason why = Refusal_reason::FLIP;
      if(internal::fat_enough_for_moves(point(tr[0]), point(tr[1]), point(tr[2]), report.tolerance))
        continue;
      if(internal::moves_keep_triangle<Kernel>(point(tr[0]), point(tr[1]), point(tr[2]), point(n0), point(n1), point(n2), why))
        continue;
      for(size_type v : tr)
        if(target[v] != none) cancelled.emplace_back(v, why);
    }
    // A vertex cancelled by several triangles is counted once, with the first reason in vertex order.
    std::sort(cancelled.begin(), cancelled.end(),
              [](const auto& x, const auto& y) { return x.first < y.first || (x.first == y.first && x.second < y.second); });
    for(const auto& [v, why] : cancelled) {
      if(target[v] == none) continue;
      visitor.on_refusal(v, target[v], why);
      if(why == Refusal_reason::DEGENERATE) ++report.refused_degenerate; else ++report.refused_flip;
      target[v] = none;
      changed = true;
    }
  }

  // 5. Apply the merges, in increasing index order. Few merges: local updates of the tables
  // (`replace_vertex`, the patent's rules (a)-(c)). Many merges (an exploded soup): the
  // triangles are rewritten once and the tables rebuilt, which is linear, where thousands of
  // local updates around the same representatives are not. Both give the same tables.
  std::size_t number_of_merges = 0;
  for(size_type v : candidates) if(target[v] != none) ++number_of_merges;
  const bool rebuild = number_of_merges > tables.number_of_triangles() / 16 + 64;
  if(rebuild) {
    std::vector<Adjacency_tables::Triangle> rewritten(tables.triangles());
    for(Adjacency_tables::Triangle& tr : rewritten)
      for(size_type& v : tr) v = final_vertex(v);
    tables = Adjacency_tables(rewritten, points.size());
  }
  std::vector<char> is_representative(points.size(), 0);
  for(size_type v : candidates) {
    if(target[v] == none) continue;
    const size_type r = target[v];
    if(!rebuild) tables.replace_vertex(v, r);
    visitor.on_merge(v, r);
    ++report.merged_vertices;
    if(!is_representative[r]) { is_representative[r] = 1; ++report.clusters; }
    report.max_displacement = std::max(report.max_displacement, std::sqrt(CGAL::to_double(squared_distance(point(v), point(r)))));
  }
  // Write the triangles back.
  for(size_type t : touched) {
    const Adjacency_tables::Triangle& tr = tables.triangle(t);
    internal::assign_triangle(*(triangles.begin() + static_cast<std::ptrdiff_t>(t)), tr[0], tr[1], tr[2]);
  }
  report.border_edges_after = tables.number_of_border_edges();
  return report;
}

/// \ingroup PkgSoupTopologyWelding
/// \brief the same, building the adjacency tables of the soup first.
template <class PointRange, class TriangleRange, class NamedParameters = CGAL::parameters::Default_named_parameters>
Snap_report snap_vertices(const PointRange& points, TriangleRange& triangles,
                          const NamedParameters& np = CGAL::parameters::default_values())
{
  Adjacency_tables tables(triangles, points.size());
  return snap_vertices(points, triangles, tables, np);
}

} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_SNAP_VERTICES_H
