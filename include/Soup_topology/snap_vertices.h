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
  /// ambiguous sites: groups of vertices connected by the tolerance graph that could not all be
  /// merged into one representative (a chain longer than the tolerance, or vertices of one
  /// triangle closer than the tolerance). Each site is listed by its smallest vertex index.
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
///    (`Compare_squared_distance_3`), except two vertices of one triangle, which are never merged
///    (the pair is refused and reported as an ambiguous site);
/// 2. each connected component of that graph is cut into clusters by a canonical rule: its
///    lexicographically smallest point (`Less_xyz_3`) is a representative; the candidates within
///    the tolerance of it join it, nearest first (ties by `Less_xyz_3`), unless one shares a
///    triangle with a vertex already in the cluster; the rest of the component is cut the same
///    way. So no point moves farther than the tolerance, merges never chain, and a component
///    that needs more than one cluster is reported as ambiguous (the minimum feature separation
///    of Hoffmann, Hopcroft and Karasick is not met there);
/// 3. a merge that would make a triangle degenerate or reverse its normal is refused (and the
///    other moves of that triangle with it), until every triangle is kept.
/// The representative keeps its coordinates: no point is constructed. The decisions depend on
/// the points only, not on the order of the triangles, the rotation of their corners or the
/// numbering of the vertices (for points that are pairwise distinct, which the exact weld ensures).
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
  using Point_map = typename NP_helper::Point_map;
  using Point = typename NP_helper::Point;
  using Kernel = typename NP_helper::Geom_traits;
  using FT = typename NP_helper::FT;
  using size_type = Adjacency_tables::size_type;

  const Point_map pm = NP_helper::get_point_map(np);
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

  auto point = [&](std::size_t v) -> const Point& { return get(pm, *(points.begin() + static_cast<std::ptrdiff_t>(v))); };
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

  auto share_triangle = [&](size_type u, size_type v) {
    const auto ru = tables.triangles_around_vertex(u), rv = tables.triangles_around_vertex(v);
    // both lists are sorted: a merge-like scan
    const size_type *a = ru.begin(), *b = rv.begin();
    while(a != ru.end() && b != rv.end()) {
      if(*a == *b) return true;
      if(*a < *b) ++a; else ++b;
    }
    return false;
  };

  // 2. The tolerance graph over the candidates (local ids), as compressed rows.
  std::vector<Point> candidate_points;
  candidate_points.reserve(candidates.size());
  for(size_type v : candidates) candidate_points.push_back(point(v));
  const Octree<Kernel> tree(candidate_points, CGAL::Identity_property_map<Point>(), kernel);
  std::vector<std::uint32_t> row;
  std::vector<std::uint32_t> parent(candidates.size());
  std::iota(parent.begin(), parent.end(), 0u);
  auto find = [&](std::uint32_t x) { while(parent[x] != x) x = parent[x] = parent[parent[x]]; return x; };
  std::vector<std::pair<std::uint32_t, std::uint32_t>> same_triangle_pairs;
  // One self-join over the octree (points visited in Morton order); the rows are filled in that
  // order, then indexed by candidate.
  std::vector<std::size_t> row_start(candidates.size()), row_end(candidates.size());
  tree.for_each_neighbourhood(eps, [&](std::size_t c, const std::vector<std::size_t>& found) {
    row_start[c] = row.size();
    for(std::size_t d : found) {
      if(d == c) continue;
      if(share_triangle(candidates[c], candidates[d])) {
        if(c < d) same_triangle_pairs.emplace_back(static_cast<std::uint32_t>(c), static_cast<std::uint32_t>(d));
        continue;
      }
      row.push_back(static_cast<std::uint32_t>(d));
      const std::uint32_t a = find(static_cast<std::uint32_t>(c)), b = find(static_cast<std::uint32_t>(d));
      if(a != b) parent[std::max(a, b)] = std::min(a, b);
    }
    row_end[c] = row.size();
  });
  auto neighbours = [&](std::uint32_t c) {
    return std::make_pair(row.begin() + static_cast<std::ptrdiff_t>(row_start[c]),
                          row.begin() + static_cast<std::ptrdiff_t>(row_end[c]));
  };

  // Components as compressed rows: the candidates of component k are
  // component_members[component_begin[k] .. component_begin[k+1]), in increasing order.
  std::vector<std::uint32_t> component_begin, component_members(candidates.size());
  {
    std::vector<std::uint32_t> id_of_root(candidates.size(), static_cast<std::uint32_t>(-1));
    std::vector<std::uint32_t> component_of(candidates.size());
    std::uint32_t count = 0;
    for(std::uint32_t c = 0; c < candidates.size(); ++c) {
      const std::uint32_t r = find(c);
      if(id_of_root[r] == static_cast<std::uint32_t>(-1)) id_of_root[r] = count++;
      component_of[c] = id_of_root[r];
    }
    component_begin.assign(count + 1, 0);
    for(std::uint32_t c = 0; c < candidates.size(); ++c) ++component_begin[component_of[c] + 1];
    for(std::uint32_t k = 0; k < count; ++k) component_begin[k + 1] += component_begin[k];
    std::vector<std::uint32_t> fill(component_begin.begin(), component_begin.end() - 1);
    for(std::uint32_t c = 0; c < candidates.size(); ++c) component_members[fill[component_of[c]]++] = c;
  }
  const std::size_t number_of_components = component_begin.size() - 1;
  auto component = [&](std::size_t k) {
    return std::make_pair(component_members.begin() + component_begin[k], component_members.begin() + component_begin[k + 1]);
  };
  std::vector<bool> ambiguous_component(number_of_components, false);
  for(const auto& pr : same_triangle_pairs) {
    ++report.refused_same_triangle;
    visitor.on_refusal(candidates[pr.second], candidates[pr.first], Refusal_reason::SAME_TRIANGLE);
    report.ambiguous_sites.push_back(std::min(candidates[pr.first], candidates[pr.second]));
  }

  // 3. Clusters: canonical representatives, no chaining, no two vertices of one triangle.
  const size_type none = static_cast<size_type>(-1);
  std::vector<size_type> target(points.size(), none);      // representative of a merged vertex
  std::vector<std::uint32_t> in_cluster_mark(tables.number_of_triangles(), static_cast<std::uint32_t>(-1));
  std::vector<bool> assigned(candidates.size(), false);
  std::vector<std::uint32_t> remaining, members;
  std::uint32_t cluster_id = 0;
  for(std::size_t k = 0; k < number_of_components; ++k) {
    const auto comp = component(k);
    if(comp.second - comp.first < 2) continue;
    remaining.assign(comp.first, comp.second);
    std::size_t rounds = 0;
    while(remaining.size() > 1) {
      ++rounds;
      const std::uint32_t rep = *std::min_element(remaining.begin(), remaining.end(), [&](std::uint32_t a, std::uint32_t b) {
        return less_xyz(candidate_points[a], candidate_points[b]);
      });
      members.clear();
      const auto nb = neighbours(rep);
      for(auto it = nb.first; it != nb.second; ++it) if(!assigned[*it]) members.push_back(*it);
      std::sort(members.begin(), members.end(), [&](std::uint32_t a, std::uint32_t b) {
        const CGAL::Comparison_result r = internal::compare_distances(candidate_points[rep], candidate_points[a],
                                                                      candidate_points[b], compare_distance);
        if(r != CGAL::EQUAL) return r == CGAL::SMALLER;
        return less_xyz(candidate_points[a], candidate_points[b]);
      });
      members.erase(std::unique(members.begin(), members.end()), members.end());
      const size_type rep_v = candidates[rep];
      assigned[rep] = true;
      ++cluster_id;
      for(size_type t : tables.triangles_around_vertex(rep_v)) in_cluster_mark[t] = cluster_id;
      for(std::uint32_t m : members) {
        const size_type mv = candidates[m];
        if(fixed != nullptr && (*fixed)[mv]) {
          // mv received welds in an earlier call: it may be a representative, never move.
          ++report.refused_holds_welds;
          visitor.on_refusal(mv, rep_v, Refusal_reason::HOLDS_WELDS);
          ambiguous_component[k] = true;
          continue;
        }
        bool conflict = false;
        for(size_type t : tables.triangles_around_vertex(mv)) if(in_cluster_mark[t] == cluster_id) { conflict = true; break; }
        if(conflict) {
          ++report.refused_same_triangle;
          visitor.on_refusal(mv, rep_v, Refusal_reason::SAME_TRIANGLE);
          ambiguous_component[k] = true;
          continue;
        }
        for(size_type t : tables.triangles_around_vertex(mv)) in_cluster_mark[t] = cluster_id;
        assigned[m] = true;
        target[mv] = rep_v;
      }
      remaining.erase(std::remove_if(remaining.begin(), remaining.end(), [&](std::uint32_t c) { return assigned[c]; }),
                      remaining.end());
    }
    if(rounds > 1 || !remaining.empty()) ambiguous_component[k] = true;
  }
  for(std::size_t k = 0; k < number_of_components; ++k)
    if(ambiguous_component[k]) {
      const std::size_t smallest = candidates[*component(k).first]; // members are in increasing order
      report.ambiguous_sites.push_back(smallest);
    }
  std::sort(report.ambiguous_sites.begin(), report.ambiguous_sites.end());
  report.ambiguous_sites.erase(std::unique(report.ambiguous_sites.begin(), report.ambiguous_sites.end()),
                               report.ambiguous_sites.end());

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
