// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The counts a user looks at first: what `soup_topology stats` prints.

#ifndef SOUP_TOPOLOGY_SOUP_STATISTICS_H
#define SOUP_TOPOLOGY_SOUP_STATISTICS_H

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/internal/tolerance.h>

#include <CGAL/Named_function_parameters.h>

#include <cstddef>
#include <type_traits>
#include <vector>

namespace Soup_topology {

/// \ingroup PkgSoupTopologyRef
/// \brief topological and geometric counts of an indexed triangle soup.
struct Soup_statistics
{
  std::size_t vertices = 0;                  ///< points of the soup
  std::size_t triangles = 0;                 ///< triangles of the soup
  std::size_t border_edges = 0;              ///< edges of one triangle only
  std::size_t non_manifold_edges = 0;        ///< edges of three or more triangles
  std::size_t non_manifold_vertices = 0;     ///< see `Adjacency_tables::non_manifold_vertices()`
  std::size_t inconsistent_edges = 0;        ///< manifold edges traversed twice in the same direction
  std::size_t components = 0;                ///< edge-connected components of the triangles
  std::size_t zero_area_triangles = 0;       ///< triangles whose corners are collinear (exact predicate)
  bool closed = false;                       ///< no border edge
};

/// \ingroup PkgSoupTopologyRef
/// \brief computes `Soup_statistics` of the soup whose tables are `tables` and points `points`.
///
/// Linear time in the size of the soup, however many triangles share an edge or a vertex: every
/// count is one pass over the tables (see `Adjacency_tables`).
/// \tparam ConcurrencyTag with `CGAL::Parallel_tag`, the vertex, orientation and component
///         counts and the zero-area test run by blocks on TBB's threads (the test sequentially for
///         coordinates that are not `double`); the statistics are the same
/// \tparam PointRange a random-access container whose points are read through `point_map`
/// \param points the points of the soup
/// \param tables the adjacency tables of the triangles of the soup, over `points`
/// \param np an optional sequence of named parameters among the ones listed below
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{point_map}
///     \cgalParamDescription{a property map through which the points of `points` are read}
///     \cgalParamType{a model of `ReadablePropertyMap` from the value type of `PointRange` to `Point_3`}
///     \cgalParamDefault{`CGAL::Identity_property_map`} \cgalParamNEnd
///   \cgalParamNBegin{geom_traits}
///     \cgalParamDescription{its `Collinear_3` decides which triangles have zero area (exact with
///     Epick and Epeck)}
///     \cgalParamType{a model of `SoupTopologyTraits`} \cgalParamDefault{the kernel of the point type} \cgalParamNEnd
/// \cgalNamedParamsEnd
template <class ConcurrencyTag = CGAL::Sequential_tag, class PointRange,
          class NamedParameters = CGAL::parameters::Default_named_parameters>
Soup_statistics compute_statistics(const PointRange& points, const Adjacency_tables& tables,
                                   const NamedParameters& np = CGAL::parameters::default_values())
{
  using NP_helper = internal::Soup_np_helper<PointRange, NamedParameters>;
  using Geom_traits = typename NP_helper::Geom_traits;
  // The predicates of points whose coordinates are not `double` (lazily exact numbers) run on
  // one thread (`Parallel.md`, rule 6).
  using Geometric_tag =
    std::conditional_t<std::is_same<typename Geom_traits::FT, double>::value, ConcurrencyTag, CGAL::Sequential_tag>;
  const Geom_traits gt = NP_helper::get_geom_traits(np);
  const typename NP_helper::Point_map pm = NP_helper::get_point_map(np);
  Soup_statistics s;
  s.vertices = points.size();
  s.triangles = tables.number_of_triangles();
  s.border_edges = tables.number_of_border_edges();
  s.non_manifold_edges = tables.non_manifold_edges().size();
  s.non_manifold_vertices = tables.template non_manifold_vertices<ConcurrencyTag>().size();
  s.inconsistent_edges = tables.template inconsistently_oriented_edges<ConcurrencyTag>().size();
  s.components = tables.template number_of_connected_components<ConcurrencyTag>();
  s.closed = s.border_edges == 0;
  const std::size_t n = tables.number_of_triangles();
  std::vector<std::size_t> zero_area(internal::number_of_blocks(n), 0);
  internal::for_each_block<Geometric_tag>(n, internal::default_block_size,
                                          [&](std::size_t g, std::size_t begin, std::size_t end) {
    typename Geom_traits::Collinear_3 collinear = gt.collinear_3_object();
    for(std::size_t i = begin; i < end; ++i) {
      const Adjacency_tables::Triangle& t = tables.triangle(static_cast<Adjacency_tables::size_type>(i));
      if(collinear(get(pm, points[t[0]]), get(pm, points[t[1]]), get(pm, points[t[2]]))) ++zero_area[g];
    }
  });
  for(std::size_t z : zero_area) s.zero_area_triangles += z;
  return s;
}

} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_SOUP_STATISTICS_H
