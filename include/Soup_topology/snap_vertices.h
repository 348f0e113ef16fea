// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Pipeline step 2: welding of duplicate vertices within a tolerance (the patent's claim 4), with
// order-independent decisions taken by exact predicates.

#ifndef SOUP_TOPOLOGY_SNAP_VERTICES_H
#define SOUP_TOPOLOGY_SNAP_VERTICES_H

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/parameters.h>
#include <Soup_topology/internal/coordinate_scale.h>
#include <Soup_topology/internal/tolerance.h>

#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/tags.h>

#include <cmath>
#include <cstddef>
#include <vector>

namespace Soup_topology {


/// \ingroup PkgSoupTopologyWelding
/// \brief why a merge was refused.
enum class Refusal_reason
{
  SAME_TRIANGLE,  ///< the two vertices belong to one triangle (merging would collapse it)
  DEGENERATE,     ///< a triangle around the moved vertex would become degenerate (collinear)
  FLIP,           ///< a triangle around the moved vertex would reverse its normal
  HOLDS_WELDS,    ///< the vertex received welds earlier: moving it would carry them farther than the tolerance
  /// `Small_features::COLLAPSE`: a triangle the merge would remove collapses onto an edge or a
  /// point that no kept triangle has, so the part would vanish instead of being closed
  UNCOVERED_COLLAPSE
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
  double tolerance = 0;                       ///< the absolute tolerance used (with `vertex_tolerance_map`: the largest of the map)
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
  /// `Small_features::COLLAPSE`: the pairs of vertices of one triangle within the tolerance of
  /// each other that were merged (features smaller than the tolerance resolved).
  std::size_t small_features_resolved = 0;
  /// `Small_features::COLLAPSE`: the triangles removed because two of their corners were merged.
  std::size_t collapsed_triangles = 0;
  /// `Small_features::COLLAPSE`: refusals because a triangle would collapse onto an edge or a
  /// point that no kept triangle has (see `Refusal_reason::UNCOVERED_COLLAPSE`).
  std::size_t refused_uncovered_collapse = 0;
  /// total number of refusals.
  std::size_t refused() const
  { return refused_same_triangle + refused_degenerate + refused_flip + refused_holds_welds + refused_uncovered_collapse; }
};

namespace internal {
template <class Kernel, class Visitor>
class Snap_vertices_worker;
template <class NamedParameters>
class Snap_visitor_holder;
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
///
/// **Features smaller than the tolerance** (`small_features`). Under `Small_features::REFUSE`,
/// two vertices of one triangle are never merged, as above. Under `Small_features::COLLAPSE`
/// (the default), two vertices of one triangle within the tolerance of each other are merged like
/// any other pair (Milenkovic's normalisation): a candidate within the tolerance of the
/// representative joins its cluster even if they share a triangle, and a member that shares a
/// triangle with a vertex already in the cluster joins it only if it is within the tolerance of
/// every such vertex (no edge longer than the tolerance is collapsed). A triangle two of whose
/// corners merge is removed (its neighbours are linked across it when the tables are rebuilt)
/// and counted in `Snap_report::collapsed_triangles`; every point of it moves by at most the
/// tolerance. A triangle is removed only where the surface stays: the edge (or the point) it
/// collapses onto must be an edge (a corner) of a triangle that is kept. Otherwise the moves of its
/// corners are refused (`Refusal_reason::UNCOVERED_COLLAPSE`, counted in
/// `Snap_report::refused_uncovered_collapse`), together with the guard of step 3, until both hold.
/// So a part smaller than the tolerance is kept as it is rather than removed, and every point of
/// the input is within the tolerance of the output and every point of the output within the
/// tolerance of the input. The clusters are still made by the canonical rule of step 2 and the guard of
/// step 3 still keeps every other triangle non-degenerate and unflipped, so the decisions stay
/// exact and independent of the order of the input. A soup without two vertices of one triangle
/// within the tolerance is welded identically under both policies.
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
/// `points`, unreferenced (`reconstruct_topology()` removes them). Collapsed triangles are removed
/// from `triangles` and `tables` (the others keep their order).
///
/// **Scale.** Points whose largest coordinate lies beyond 2^128 or below 2^-128 (a file in
/// another unit) are decided on a copy scaled by the power of two that brings it into [1, 2),
/// with the tolerances scaled alike; the report's lengths are given at the input's scale. A
/// power of two changes only exponents: the decisions are those taken on the soup at a moderate
/// scale, where squared tolerances and distances neither overflow nor underflow
/// (`internal/coordinate_scale.h`).
///
/// **Threads.** With `CGAL::Parallel_tag` the steps that are data-parallel run on TBB's threads;
/// the result (triangles, tables, report, visitor calls) is the same on any number of threads
/// (`doc/Soup_topology/Parallel.md`; the calls to a visitor that takes the merges in any order
/// are the same, not their order).
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` (the default), `CGAL::Parallel_tag` (needs TBB)
///         or `CGAL::Parallel_if_available_tag`
/// \tparam PointRange a random-access range of points (read through `point_map`)
/// \tparam TriangleRange a random-access range of triangles, each a random-access range of 3 indices
/// \param points the points of the soup, pairwise distinct (as the exact weld leaves them); not changed
/// \param triangles the triangles of the soup, as indices into `points`; the merged vertices are replaced
/// \param tables the tables of `triangles` over `points`, updated in place
/// \param np an optional sequence of named parameters among the ones listed below
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{snapping_tolerance} \cgalParamDescription{the largest distance between two merged
///     vertices} \cgalParamType{`geom_traits::FT`} \cgalParamDefault{0: only border vertices with equal
///     coordinates are merged} \cgalParamNEnd
///   \cgalParamNBegin{relative_tolerance} \cgalParamDescription{the tolerance as a fraction of the
///     bounding-box diagonal; exclusive with `snapping_tolerance`} \cgalParamType{`double`}
///     \cgalParamDefault{none: `snapping_tolerance` applies} \cgalParamNEnd
///   \cgalParamNBegin{vertex_tolerance_map} \cgalParamDescription{a tolerance per point instead of
///     one: two vertices u and v are within tolerance when |uv| <= min(t_u, t_v) (compared exactly,
///     squared), and this pair rule replaces the one tolerance in every decision above (short edges,
///     the tolerance graph, cluster members, collapsible pairs), so the decisions stay exact and
///     independent of the order; a vertex moves by at most its own tolerance. The dense-cluster
///     grid is not used with a map. Exclusive with `snapping_tolerance` and `relative_tolerance`.}
///     \cgalParamType{a `ReadablePropertyMap` from the index of a point in `points` (`std::size_t`)
///     to a finite number >= 0 convertible to `geom_traits::FT`} \cgalParamDefault{none: one
///     tolerance} \cgalParamNEnd
///   \cgalParamNBegin{point_map} \cgalParamDescription{a property map giving the point of each element of
///     `points`} \cgalParamType{a readable property map to `Point_3`}
///     \cgalParamDefault{`CGAL::Identity_property_map`} \cgalParamNEnd
///   \cgalParamNBegin{geom_traits} \cgalParamDescription{the traits object that takes every geometric
///     decision} \cgalParamType{a CGAL Kernel} \cgalParamDefault{the kernel of the point type} \cgalParamNEnd
///   \cgalParamNBegin{visitor} \cgalParamDescription{told of every merge and refusal; copied, unless given
///     as `std::ref(v)`. The merges are told on one thread in increasing order of the merged vertices,
///     unless the class has a member `static constexpr bool tells_merges_concurrently = true`: its
///     `on_merge()` may then be called on TBB's threads with `CGAL::Parallel_tag`, several at once,
///     in no particular order (each call must touch only what belongs to its merged vertex)}
///     \cgalParamType{a class with `on_merge(std::size_t, std::size_t)` and
///     `on_refusal(std::size_t, std::size_t, Refusal_reason)`} \cgalParamDefault{`Default_snap_visitor`}
///     \cgalParamNEnd
///   \cgalParamNBegin{small_features} \cgalParamDescription{whether two vertices of one triangle within
///     the tolerance are merged, the triangle removed (`COLLAPSE`), or refused (`REFUSE`); `COLLAPSE`
///     needs a `TriangleRange` with `resize()`} \cgalParamType{`Soup_topology::Small_features`}
///     \cgalParamDefault{`Small_features::COLLAPSE`} \cgalParamNEnd
/// \cgalNamedParamsEnd
/// \returns a `Snap_report`.
/// \throws Invalid_input for a negative, NaN or infinite tolerance (also in `vertex_tolerance_map`,
///         or a map given with `snapping_tolerance` or `relative_tolerance`), a non-finite coordinate,
///         tables that do not match the soup, or `Small_features::COLLAPSE` with a triangle range
///         without `resize()`. Nothing is changed then.
template <class ConcurrencyTag = CGAL::Sequential_tag, class PointRange, class TriangleRange,
          class NamedParameters = CGAL::parameters::Default_named_parameters>
Snap_report snap_vertices(const PointRange& points, TriangleRange& triangles, Adjacency_tables& tables,
                          const NamedParameters& np = CGAL::parameters::default_values())
{
  using NP_helper = internal::Soup_np_helper<PointRange, NamedParameters>;
  using Kernel = typename NP_helper::Geom_traits;
  using FT = typename NP_helper::FT;
  using Visitor_holder = internal::Snap_visitor_holder<NamedParameters>;

  const Kernel kernel = NP_helper::get_geom_traits(np);
  Visitor_holder visitor(np);
  // The points, read once (a readable map may return them by value); a vector of points under
  // the identity map is used as it is. Beyond 2^128 or below 2^-128 the decisions are taken on a
  // copy scaled by a power of two, with the tolerances scaled alike, as in
  // `reconstruct_topology()` (internal/coordinate_scale.h).
  std::vector<typename NP_helper::Point> point_storage;
  const auto& given_points = NP_helper::points_as_vector(points, np, point_storage);
  const int exponent = internal::moderate_scale_exponent_of<ConcurrencyTag>(given_points);
  FT eps =
    NP_helper::template checked_tolerance<ConcurrencyTag>("snap_vertices", points, triangles, tables, np, exponent);
  // Per-vertex tolerances: every pair is decided with the smaller of its two; `eps`, the largest,
  // bounds the searches.
  std::vector<FT> tolerance_storage;
  const std::vector<FT>* tolerances =
    internal::read_vertex_tolerances<FT>(np, points.size(), tolerance_storage, "snap_vertices", exponent);
  if(tolerances != nullptr) eps = internal::largest_tolerance(*tolerances);
  // Vertices that may receive welds but not move (`reconstruct_topology()` fixes the
  // representatives of earlier rounds, so that no point moves farther than the tolerance in all).
  const std::vector<char>* fixed = CGAL::parameters::choose_parameter(
    CGAL::parameters::get_parameter(np, internal_np::fixed_vertices), static_cast<const std::vector<char>*>(nullptr));
  if(fixed != nullptr && fixed->size() != points.size()) fixed = nullptr;
  const Small_features policy = internal::small_features_policy(np);
  if constexpr(!internal::has_resize<TriangleRange>::value)
    if(policy == Small_features::COLLAPSE)
      throw Invalid_input("snap_vertices: Small_features::COLLAPSE removes triangles: the triangle range needs resize()");

  const auto& point_vector =
    exponent == 0 ? given_points : internal::scaled_points(given_points, exponent, point_storage);
  internal::Snap_vertices_worker<Kernel, typename Visitor_holder::Visitor> worker(point_vector, tables, eps, fixed, kernel,
                                                                                  visitor.get(), policy, tolerances);
  Snap_report report = worker.template run<ConcurrencyTag>(triangles);
  report.tolerance = std::ldexp(report.tolerance, -exponent);
  report.max_displacement = std::ldexp(report.max_displacement, -exponent);
  return report;
}

/// \ingroup PkgSoupTopologyWelding
/// \brief the same, building the adjacency tables of the soup first.
/// \param points the points of the soup, pairwise distinct; not changed
/// \param triangles the triangles of the soup, as indices into `points`; the merged vertices are replaced
/// \param np the named parameters of `snap_vertices(points, triangles, tables, np)`
template <class ConcurrencyTag = CGAL::Sequential_tag, class PointRange, class TriangleRange,
          class NamedParameters = CGAL::parameters::Default_named_parameters>
Snap_report snap_vertices(const PointRange& points, TriangleRange& triangles,
                          const NamedParameters& np = CGAL::parameters::default_values())
{
  Adjacency_tables tables(triangles, points.size(), ConcurrencyTag());
  return snap_vertices<ConcurrencyTag>(points, triangles, tables, np);
}

} // namespace Soup_topology

// The steps, after the types they report with.
#include <Soup_topology/internal/snap_vertices_worker.h>

#endif // SOUP_TOPOLOGY_SNAP_VERTICES_H
