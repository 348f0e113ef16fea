// Copyright (c) 2024 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Named-parameter tags and builders of `Soup_topology::Octree`.
// Included by `Soup_topology/Octree.h` (and by the package's `parameters.h`).

#ifndef SOUP_TOPOLOGY_INTERNAL_OCTREE_PARAMETERS_H
#define SOUP_TOPOLOGY_INTERNAL_OCTREE_PARAMETERS_H

#include <CGAL/Named_function_parameters.h>

#include <cstddef>

namespace Soup_topology {
namespace internal_np {

/// maximal number of points of a leaf (a box holding more is split into 8), unless the maximum depth is reached
enum bucket_capacity_t { bucket_capacity };
/// maximal depth `n` of the octree: the integer addresses have `n` bits per axis (1 <= n <= 21)
enum maximum_depth_t { maximum_depth };
/// default strategy of `Octree::vertices_near_segment()`, a value of `Soup_topology::Segment_query_strategy`
enum segment_query_strategy_t { segment_query_strategy };

} // namespace internal_np

namespace parameters {

using CGAL::parameters::default_values;

// bucket_capacity

/// starts a named-parameter chain with `bucket_capacity`
inline CGAL::Named_function_parameters<std::size_t, internal_np::bucket_capacity_t>
bucket_capacity(std::size_t c)
{
  return CGAL::Named_function_parameters<std::size_t, internal_np::bucket_capacity_t>(c);
}

/// appends `bucket_capacity` to an existing named-parameter chain
template <typename T, typename Tag, typename Base>
CGAL::Named_function_parameters<std::size_t, internal_np::bucket_capacity_t,
                                CGAL::Named_function_parameters<T, Tag, Base>>
bucket_capacity(std::size_t c, const CGAL::Named_function_parameters<T, Tag, Base>& np)
{
  return CGAL::Named_function_parameters<std::size_t, internal_np::bucket_capacity_t,
                                         CGAL::Named_function_parameters<T, Tag, Base>>(c, np);
}

// maximum_depth

/// starts a named-parameter chain with `maximum_depth`
inline CGAL::Named_function_parameters<std::size_t, internal_np::maximum_depth_t>
maximum_depth(std::size_t d)
{
  return CGAL::Named_function_parameters<std::size_t, internal_np::maximum_depth_t>(d);
}

/// appends `maximum_depth` to an existing named-parameter chain
template <typename T, typename Tag, typename Base>
CGAL::Named_function_parameters<std::size_t, internal_np::maximum_depth_t,
                                CGAL::Named_function_parameters<T, Tag, Base>>
maximum_depth(std::size_t d, const CGAL::Named_function_parameters<T, Tag, Base>& np)
{
  return CGAL::Named_function_parameters<std::size_t, internal_np::maximum_depth_t,
                                         CGAL::Named_function_parameters<T, Tag, Base>>(d, np);
}

// segment_query_strategy (the value is a `Soup_topology::Segment_query_strategy`)

/// starts a named-parameter chain with `segment_query_strategy`
template <typename Strategy>
CGAL::Named_function_parameters<Strategy, internal_np::segment_query_strategy_t>
segment_query_strategy(const Strategy& s)
{
  return CGAL::Named_function_parameters<Strategy, internal_np::segment_query_strategy_t>(s);
}

/// appends `segment_query_strategy` to an existing named-parameter chain
template <typename Strategy, typename T, typename Tag, typename Base>
CGAL::Named_function_parameters<Strategy, internal_np::segment_query_strategy_t,
                                CGAL::Named_function_parameters<T, Tag, Base>>
segment_query_strategy(const Strategy& s, const CGAL::Named_function_parameters<T, Tag, Base>& np)
{
  return CGAL::Named_function_parameters<Strategy, internal_np::segment_query_strategy_t,
                                         CGAL::Named_function_parameters<T, Tag, Base>>(s, np);
}

} // namespace parameters
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_OCTREE_PARAMETERS_H
