// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The package's named parameters. They chain with CGAL's: CGAL already has `geom_traits`,
// `point_map`, `snapping_tolerance`, `visitor`, `number_of_iterations` and `verbose`, which the
// package reuses; new tags exist only for what CGAL lacks. The octree's parameters
// (`bucket_capacity`, `maximum_depth`, `segment_query_strategy`) and the subdivision's are
// declared beside their algorithms and included here, so this header gives all of them. Each builder has a one-argument form
// that starts a chain and a two-argument form that appends to an existing chain:
//   Soup_topology::parameters::relative_tolerance(1e-6, CGAL::parameters::geom_traits(K()))
// CGAL's own parameters chain as members (`.geom_traits(k).visitor(v)`), but CGAL 5.5 fixes the
// list of members (no `combine` either): a package parameter therefore wraps a CGAL chain, as
// above, and a CGAL member may follow it: `relative_tolerance(1e-6).geom_traits(K())`.

#ifndef SOUP_TOPOLOGY_PARAMETERS_H
#define SOUP_TOPOLOGY_PARAMETERS_H

#include <Soup_topology/internal/octree_parameters.h>
#include <Soup_topology/internal/subdivision_parameters.h>

#include <CGAL/Named_function_parameters.h>

#define SOUP_TOPOLOGY_ADD_NAMED_PARAMETER(TAG, NAME)                                                   \
  namespace internal_np { enum TAG { NAME }; }                                                         \
  namespace parameters {                                                                               \
  template <class T>                                                                                   \
  CGAL::Named_function_parameters<T, internal_np::TAG> NAME(const T& value)                            \
  { return CGAL::Named_function_parameters<T, internal_np::TAG>(value); }                              \
  template <class T, class T2, class Tag2, class Base2>                                                \
  CGAL::Named_function_parameters<T, internal_np::TAG, CGAL::Named_function_parameters<T2, Tag2, Base2>> \
  NAME(const T& value, const CGAL::Named_function_parameters<T2, Tag2, Base2>& np)                     \
  { return CGAL::Named_function_parameters<T, internal_np::TAG, CGAL::Named_function_parameters<T2, Tag2, Base2>>(value, np); } \
  }

namespace Soup_topology {

/// the tolerance given as a fraction of the diagonal of the bounding box of the points
/// (instead of CGAL's absolute `snapping_tolerance`); a `double`.
SOUP_TOPOLOGY_ADD_NAMED_PARAMETER(relative_tolerance_t, relative_tolerance)
/// whether `reconstruct_topology()` counts the pairs of triangles of its result that intersect
/// (more than in a shared vertex or edge), in `Reconstruction_report::self_intersecting_pairs`
/// (default `false`: the count costs a box intersection over all triangles).
SOUP_TOPOLOGY_ADD_NAMED_PARAMETER(count_self_intersections_t, count_self_intersections)
/// the largest number of weld/split rounds of `reconstruct_topology()` (default 8).
SOUP_TOPOLOGY_ADD_NAMED_PARAMETER(maximum_number_of_rounds_t, maximum_number_of_rounds)
/// whether `reconstruct_topology()` splits T-junctions (default `true`).
SOUP_TOPOLOGY_ADD_NAMED_PARAMETER(split_t_junctions_t, do_split_t_junctions)
/// how `orient_triangle_soup()` and `triangle_soup_to_face_graph()` orient closed patches, a
/// `Soup_topology::Orientation_policy` (default `Orientation_policy::BOUND_VOLUME`).
SOUP_TOPOLOGY_ADD_NAMED_PARAMETER(orientation_policy_t, orientation_policy)

namespace parameters {
using CGAL::parameters::default_values;
using CGAL::parameters::geom_traits;
using CGAL::parameters::number_of_iterations;
using CGAL::parameters::point_map;
using CGAL::parameters::snapping_tolerance;
using CGAL::parameters::vertex_point_map;
using CGAL::parameters::visitor;
} // namespace parameters

} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_PARAMETERS_H
