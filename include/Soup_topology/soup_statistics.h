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
template <class PointRange, class NamedParameters = CGAL::parameters::Default_named_parameters>
Soup_statistics compute_statistics(const PointRange& points, const Adjacency_tables& tables,
                                   const NamedParameters& np = CGAL::parameters::default_values())
{
  using NP_helper = internal::Soup_np_helper<PointRange, NamedParameters>;
  using Geom_traits = typename NP_helper::Geom_traits;
  const Geom_traits gt = NP_helper::get_geom_traits(np);
  const typename NP_helper::Point_map pm = NP_helper::get_point_map(np);
  typename Geom_traits::Collinear_3 collinear = gt.collinear_3_object();
  Soup_statistics s;
  s.vertices = points.size();
  s.triangles = tables.number_of_triangles();
  s.border_edges = tables.number_of_border_edges();
  s.non_manifold_edges = tables.non_manifold_edges().size();
  s.non_manifold_vertices = tables.non_manifold_vertices().size();
  s.inconsistent_edges = tables.inconsistently_oriented_edges().size();
  s.components = tables.number_of_connected_components();
  s.closed = s.border_edges == 0;
  for(const Adjacency_tables::Triangle& t : tables.triangles())
    if(collinear(get(pm, points[t[0]]), get(pm, points[t[1]]), get(pm, points[t[2]]))) ++s.zero_area_triangles;
  return s;
}

} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_SOUP_STATISTICS_H
