// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Pipeline step 3: T-junction repair (the patent's synchronisation of strips, Figures 7-9) by
// splitting triangles at existing vertices, with rule tables (15) and (17).

#ifndef SOUP_TOPOLOGY_SPLIT_T_JUNCTIONS_H
#define SOUP_TOPOLOGY_SPLIT_T_JUNCTIONS_H

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/parameters.h>
#include <Soup_topology/internal/soup_checks.h>
#include <Soup_topology/internal/coordinate_scale.h>
#include <Soup_topology/internal/tolerance.h>
#include <Soup_topology/internal/uninitialized_vector.h>

#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/tags.h>

#include <cmath>
#include <cstddef>
#include <functional>
#include <type_traits>
#include <utility>

namespace Soup_topology {

/// \ingroup PkgSoupTopologyTJunctions
/// \brief what `split_t_junctions()` did.
struct Split_report
{
  double tolerance = 0;                   ///< the absolute tolerance used (with `vertex_tolerance_map`: the largest of the map)
  std::size_t t_junctions = 0;            ///< (border edge, vertex) pairs accepted as T-junctions
  std::size_t split_triangles = 0;        ///< splits done (each adds one triangle)
  std::size_t refused_overlap = 0;        ///< vertices whose border edge would overlap the split triangle
  std::size_t refused_degenerate = 0;     ///< splits refused: a new triangle would be degenerate
  std::size_t refused_flip = 0;           ///< splits refused: a new triangle would reverse its normal
  std::size_t ambiguous = 0;              ///< vertices near several border edges, or within twice the tolerance of an end point
  std::size_t border_edges_before = 0;    ///< border edges before
  std::size_t border_edges_after = 0;     ///< border edges after
};

/// \ingroup PkgSoupTopologyTJunctions
/// \brief why a split at a T-junction was refused.
enum class Split_refusal_reason
{
  OVERLAP,     ///< the border edge of the vertex would overlap the split triangle
  DEGENERATE,  ///< a new triangle would be degenerate (collinear corners)
  FLIP         ///< a new triangle would reverse its normal
};

/// \ingroup PkgSoupTopologyTJunctions
/// \brief a visitor that is told nothing; the default of the `visitor` parameter of
/// `split_t_junctions()`. A user visitor provides the same three member functions (deriving from
/// this class gives the ones it does not need). Every call names a vertex and the border edge
/// `[a,b]` it was found near, by their indices in `points`; the vertex lies within the tolerance
/// of that edge, so its point locates the event. The calls come in the same order on any number of
/// threads; each adds one to the `Split_report` count named below.
struct Default_split_visitor
{
  /// the triangle along the border edge `[a,b]` is split at `vertex` (`Split_report::split_triangles`).
  void on_split(std::size_t /*vertex*/, std::size_t /*a*/, std::size_t /*b*/) {}
  /// the split of the border edge `[a,b]` at `vertex` is refused for `reason`
  /// (`Split_report::refused_overlap`, `refused_degenerate`, `refused_flip`).
  void on_split_refusal(std::size_t /*vertex*/, std::size_t /*a*/, std::size_t /*b*/, Split_refusal_reason /*reason*/) {}
  /// `vertex` is ambiguous near the border edge `[a,b]`: near several border edges (`[a,b]` is the
  /// nearest), or within twice the tolerance of an end point (`Split_report::ambiguous`).
  void on_ambiguous_t_junction(std::size_t /*vertex*/, std::size_t /*a*/, std::size_t /*b*/) {}
};

namespace internal {

/// whether `Visitor` has the member functions of `Default_split_visitor`.
template <class Visitor, class = void>
struct is_split_visitor : std::false_type {};
template <class Visitor>
struct is_split_visitor<Visitor, std::void_t<
  decltype(std::declval<Visitor&>().on_split(std::size_t(), std::size_t(), std::size_t())),
  decltype(std::declval<Visitor&>().on_split_refusal(std::size_t(), std::size_t(), std::size_t(), Split_refusal_reason())),
  decltype(std::declval<Visitor&>().on_ambiguous_t_junction(std::size_t(), std::size_t(), std::size_t()))>>
  : std::true_type {};

template <class Kernel, class Report, class Visitor>
class T_junction_splitter;

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
/// the border edges, then along each edge. A `std::vector` without room for them is given room
/// for twice its size first, in a block whose huge pages are advised before it is written.
///
/// With `CGAL::Parallel_tag` the search for the vertices near each border edge runs on TBB's
/// threads, its results put together in the order of the border edges: the result is the same
/// on any number of threads (`doc/Soup_topology/Parallel.md`).
///
/// **Scale.** Points whose largest coordinate lies beyond 2^128 or below 2^-128 (a file in
/// another unit) are decided on a copy scaled by the power of two that brings it into [1, 2),
/// with the tolerances scaled alike; the report's lengths are given at the input's scale. A
/// power of two changes only exponents: the decisions are those taken on the soup at a moderate
/// scale, where squared tolerances and distances neither overflow nor underflow
/// (`internal/coordinate_scale.h`).
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` (the default), `CGAL::Parallel_tag` (needs TBB)
///         or `CGAL::Parallel_if_available_tag`
/// \tparam PointRange a random-access range of points (read through `point_map`)
/// \tparam TriangleRange a random-access range of triangles, each a random-access range of 3
///         indices, with `push_back()`
/// \param points the points of the soup
/// \param triangles the triangles of the soup: split triangles are rewritten, new ones appended
/// \param tables the tables of `triangles` over `points`, updated in place
/// \param np an optional sequence of named parameters among the ones listed below
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{snapping_tolerance} \cgalParamDescription{the absolute tolerance within
///     which a vertex lies on a border edge} \cgalParamType{`geom_traits::FT`} \cgalParamDefault{0}
///     \cgalParamNEnd
///   \cgalParamNBegin{relative_tolerance} \cgalParamDescription{the tolerance as a fraction of the
///     bounding-box diagonal; exclusive with `snapping_tolerance`} \cgalParamType{`double`} \cgalParamNEnd
///   \cgalParamNBegin{vertex_tolerance_map} \cgalParamDescription{a tolerance per point instead of
///     one: a vertex c is within tolerance of the segment [a,b] when its distance to it is
///     <= min(t_c, t_a, t_b), and of the point a when |ca| <= min(t_c, t_a) (twice that for "twice
///     the tolerance"); each decision above uses the tolerance of the points it involves, compared
///     exactly, so the result stays independent of the order. The dense-cluster grid is not used with
///     a map. Exclusive with `snapping_tolerance` and `relative_tolerance`.} \cgalParamType{a
///     `ReadablePropertyMap` from the index of a point in `points` (`std::size_t`) to a finite number
///     >= 0 convertible to `geom_traits::FT`} \cgalParamDefault{none: one tolerance} \cgalParamNEnd
///   \cgalParamNBegin{point_map} \cgalParamDescription{a property map associating points to the
///     elements of `points`} \cgalParamType{a readable property map to `Point_3`}
///     \cgalParamDefault{`CGAL::Identity_property_map`} \cgalParamNEnd
///   \cgalParamNBegin{geom_traits} \cgalParamDescription{an instance of a geometric traits class, which
///     takes every decision} \cgalParamType{a CGAL Kernel} \cgalParamDefault{the kernel of the point type}
///     \cgalParamNEnd
///   \cgalParamNBegin{visitor} \cgalParamDescription{told of every split, refused split and ambiguous
///     vertex; copied, unless given as `std::ref(v)`} \cgalParamType{a class with the member functions
///     of `Default_split_visitor`} \cgalParamDefault{`Default_split_visitor` (nothing is recorded)}
///     \cgalParamNEnd
/// \cgalNamedParamsEnd
/// \returns a `Split_report`.
/// \throws Invalid_input for an invalid tolerance, non-finite coordinates or mismatched tables.
template <class ConcurrencyTag = CGAL::Sequential_tag, class PointRange, class TriangleRange,
          class NamedParameters = CGAL::parameters::Default_named_parameters>
Split_report split_t_junctions(const PointRange& points, TriangleRange& triangles, Adjacency_tables& tables,
                               const NamedParameters& np = CGAL::parameters::default_values())
{
  using NP_helper = internal::Soup_np_helper<PointRange, NamedParameters>;
  using Kernel = typename NP_helper::Geom_traits;
  using FT = typename NP_helper::FT;
  using Face = typename TriangleRange::value_type;
  using Visitor_given = typename CGAL::internal_np::Lookup_named_param_def<CGAL::internal_np::visitor_t, NamedParameters,
                                                                           Default_split_visitor>::type;
  using Visitor_type = internal::Given_visitor<Visitor_given>;
  static_assert(internal::is_split_visitor<typename Visitor_type::type>::value,
                "split_t_junctions: the visitor needs the member functions of Default_split_visitor");

  const Kernel kernel = NP_helper::get_geom_traits(np);
  // The points, read once (a readable map may return them by value); a vector of points under
  // the identity map is used as it is. Beyond 2^128 or below 2^-128 the decisions are taken on a
  // copy scaled by a power of two, with the tolerances scaled alike, as in
  // `reconstruct_topology()` (internal/coordinate_scale.h).
  std::vector<typename NP_helper::Point> point_storage;
  const auto& given_points = NP_helper::points_as_vector(points, np, point_storage);
  const int exponent = internal::moderate_scale_exponent_of<ConcurrencyTag>(given_points);
  FT eps =
    NP_helper::template checked_tolerance<ConcurrencyTag>("split_t_junctions", points, triangles, tables, np, exponent);
  // Per-vertex tolerances: a vertex and a segment are decided with the smallest tolerance of the
  // three points; `eps`, the largest, bounds the searches.
  std::vector<FT> tolerance_storage;
  const std::vector<FT>* tolerances =
    internal::read_vertex_tolerances<FT>(np, points.size(), tolerance_storage, "split_t_junctions", exponent);
  if(tolerances != nullptr) eps = internal::largest_tolerance(*tolerances);
  Visitor_given visitor = CGAL::parameters::choose_parameter<Visitor_given>(
    CGAL::parameters::get_parameter(np, CGAL::internal_np::visitor));
  const auto& point_vector =
    exponent == 0 ? given_points : internal::scaled_points(given_points, exponent, point_storage);
  internal::T_junction_splitter<Kernel, Split_report, typename Visitor_type::type> splitter(
    point_vector, tables, kernel, eps, Visitor_type::get(visitor), tolerances);
  Split_report report = splitter.template run<ConcurrencyTag>();
  report.tolerance = std::ldexp(report.tolerance, -exponent);
  // Write the triangles back: the split ones and the new ones. The room for the new ones is
  // made first, as `push_back()` would make it (twice the size: later rounds may add more), in
  // huge pages for a `std::vector`.
  if(tables.number_of_triangles() > triangles.size())
    internal::reserve_in_huge_pages(triangles, tables.number_of_triangles(), 2 * triangles.size());
  for(Adjacency_tables::size_type t : splitter.changed_triangles()) {
    const Adjacency_tables::Triangle& tr = tables.triangle(t);
    while(triangles.size() <= t) triangles.push_back(internal::make_triangle<Face>(0, 0, 0));
    triangles[t] = internal::make_triangle<Face>(tr[0], tr[1], tr[2]);
  }
  return report;
}

/// \ingroup PkgSoupTopologyTJunctions
/// \brief the same, building the adjacency tables first.
/// \param points the points of the soup
/// \param triangles the triangles of the soup: split triangles are rewritten, new ones appended
/// \param np the named parameters of the function above
template <class ConcurrencyTag = CGAL::Sequential_tag, class PointRange, class TriangleRange,
          class NamedParameters = CGAL::parameters::Default_named_parameters>
Split_report split_t_junctions(const PointRange& points, TriangleRange& triangles,
                               const NamedParameters& np = CGAL::parameters::default_values())
{
  Adjacency_tables tables(triangles, points.size(), ConcurrencyTag());
  return split_t_junctions<ConcurrencyTag>(points, triangles, tables, np);
}

} // namespace Soup_topology

// The steps, after the types they report with.
#include <Soup_topology/internal/split_t_junctions_worker.h>

#endif // SOUP_TOPOLOGY_SPLIT_T_JUNCTIONS_H
