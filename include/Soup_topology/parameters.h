// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The package's named parameters, all declared here by one macro. They chain with CGAL's: CGAL
// already has `geom_traits`, `point_map`, `vertex_point_map`, `snapping_tolerance`, `visitor`,
// `number_of_iterations` and `stream_precision`, which the package reuses; new tags exist only
// for what CGAL lacks. Each builder has a one-argument form that starts a chain and a two-argument form
// that appends to an existing chain:
//   Soup_topology::parameters::relative_tolerance(1e-6, CGAL::parameters::geom_traits(K()))
// CGAL's own parameters chain as members (`.geom_traits(k).visitor(v)`), but CGAL 5.5 fixes the
// list of members (no `combine` either): a package parameter therefore wraps a CGAL chain, as
// above, and a CGAL member may follow it: `relative_tolerance(1e-6).geom_traits(K())`.

#ifndef SOUP_TOPOLOGY_PARAMETERS_H
#define SOUP_TOPOLOGY_PARAMETERS_H

#include <CGAL/Named_function_parameters.h>

/// \cond SKIP_IN_MANUAL
// Declares the tag `Soup_topology::internal_np::NAME` of type `TAG` and the two builders
// `Soup_topology::parameters::NAME(value)` and `Soup_topology::parameters::NAME(value, np)`. As
// in CGAL, the builders store the value with the type it is given; the function that reads the
// parameter converts it to the type it documents.
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
/// \endcond

namespace Soup_topology {

// The list of the package's named parameters. The manual (`Soup_topology.txt`, section "Named
// parameters") lists them with the functions that read them.

// Welding and T-junctions (`snap_vertices()`, `split_t_junctions()`, `reconstruct_topology()`).

/// the tolerance given as a fraction of the diagonal of the bounding box of the points
/// (instead of CGAL's absolute `snapping_tolerance`); a `double`.
SOUP_TOPOLOGY_ADD_NAMED_PARAMETER(relative_tolerance_t, relative_tolerance)
/// one tolerance per point instead of one for the whole soup: a `ReadablePropertyMap` whose key
/// is the index of a point in the range given (`std::size_t`) and whose value is a finite number
/// >= 0 convertible to `double` (for instance `CGAL::make_property_map(std::vector<double>&)`).
/// Two vertices u and v are within tolerance of each other when |uv| <= min(t_u, t_v); a vertex c
/// is within tolerance of the segment [a,b] when its distance to it is <= min(t_c, t_a, t_b).
/// Not with `snapping_tolerance`, `relative_tolerance` or `automatic_tolerance`.
SOUP_TOPOLOGY_ADD_NAMED_PARAMETER(vertex_tolerance_map_t, vertex_tolerance_map)
/// the vertices that `snap_vertices()` may not move (they may still receive welds): a
/// `const std::vector<char>*`, nonzero for a fixed vertex, ignored unless it has one entry per
/// point. `reconstruct_topology()` fixes with it the vertices that received welds in earlier
/// rounds; it is not meant for users and not listed in the manual.
SOUP_TOPOLOGY_ADD_NAMED_PARAMETER(fixed_vertices_t, fixed_vertices)

/// \ingroup PkgSoupTopologyWelding
/// \brief what the weld does with a feature smaller than the tolerance: two vertices of one
/// triangle within the tolerance of each other (a short edge, a sliver), which the minimum
/// feature separation of Hoffmann, Hopcroft and Karasick excludes. The named parameter
/// `small_features` chooses; `Small_features::COLLAPSE` is the default (the manual, section
/// "Features smaller than the tolerance", says why).
enum class Small_features
{
  REFUSE,   ///< two vertices of one triangle are never merged; the site is reported as ambiguous
  COLLAPSE  ///< they are merged like any two vertices within the tolerance (Milenkovic's
            ///< normalisation), and the triangles whose corners merge are removed
};

/// what `snap_vertices()` and `reconstruct_topology()` do with features smaller than the
/// tolerance, a `Soup_topology::Small_features` (default `Small_features::COLLAPSE`).
SOUP_TOPOLOGY_ADD_NAMED_PARAMETER(small_features_t, small_features)

namespace internal {
/// the `small_features` parameter of `np`, or its default.
template <class NamedParameters>
Small_features small_features_policy(const NamedParameters& np)
{
  return CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, internal_np::small_features),
                                            Small_features::COLLAPSE);
}
} // namespace internal

// Pipeline (`reconstruct_topology()`).

/// whether `reconstruct_topology()` counts the pairs of triangles of its result that intersect
/// (more than in a shared vertex or edge), in `Reconstruction_report::self_intersecting_pairs`
/// (default `false`: the count costs a box intersection over all triangles).
SOUP_TOPOLOGY_ADD_NAMED_PARAMETER(count_self_intersections_t, count_self_intersections)
/// the largest number of weld/split rounds of `reconstruct_topology()` (default 8).
SOUP_TOPOLOGY_ADD_NAMED_PARAMETER(maximum_number_of_rounds_t, maximum_number_of_rounds)
/// whether `reconstruct_topology()` splits T-junctions (default `true`).
SOUP_TOPOLOGY_ADD_NAMED_PARAMETER(split_t_junctions_t, do_split_t_junctions)
/// whether `reconstruct_topology()` chooses its tolerance by the gap analysis (`analyze_gaps()`)
/// of the soup, instead of `snapping_tolerance` or `relative_tolerance`; a `bool` (default `false`).
SOUP_TOPOLOGY_ADD_NAMED_PARAMETER(automatic_tolerance_t, automatic_tolerance)

// Tiled repair (`tiled_reconstruct_topology()`).

/// the halo of the first repair of every tile, a `double` (default four times the tolerance plus
/// four times the mean edge length of the soup): a tile whose owned triangles are tainted is
/// repaired again with the halo doubled, so the halo changes the time, never the result.
SOUP_TOPOLOGY_ADD_NAMED_PARAMETER(tile_halo_t, tile_halo)
/// a callable taking a `const Tile_progress&`, called after each repair of a tile by the process
/// that made it (default: none); for progress displays.
SOUP_TOPOLOGY_ADD_NAMED_PARAMETER(tile_progress_t, tile_progress)

// Orientation (`orient_triangle_soup()`, `triangle_soup_to_face_graph()`).

/// how closed patches are oriented, a `Soup_topology::Orientation_policy` (default
/// `Orientation_policy::BOUND_VOLUME`).
SOUP_TOPOLOGY_ADD_NAMED_PARAMETER(orientation_policy_t, orientation_policy)

// Octree (`Octree`).

/// the largest number of points of a leaf (a box holding more is split into 8), unless the
/// maximum depth is reached; a `std::size_t`.
SOUP_TOPOLOGY_ADD_NAMED_PARAMETER(bucket_capacity_t, bucket_capacity)
/// the largest depth `n` of the octree: the integer addresses have `n` bits per axis
/// (1 <= n <= 21); a `std::size_t`.
SOUP_TOPOLOGY_ADD_NAMED_PARAMETER(maximum_depth_t, maximum_depth)
/// the default strategy of `Octree::vertices_near_segment()`, a `Soup_topology::Segment_query_strategy`.
SOUP_TOPOLOGY_ADD_NAMED_PARAMETER(segment_query_strategy_t, segment_query_strategy)

// Loop subdivision (`loop_subdivision()`, `loop_limit_points()`, `loop_limit_tangents()`).

/// the choice of `beta` of Loop's vertex rule, a `Soup_topology::Loop_beta` (default `Loop_beta::LOOP`).
SOUP_TOPOLOGY_ADD_NAMED_PARAMETER(loop_beta_t, loop_beta)
/// an `Adjacency_tables*` that, if not null, receives the tables of the subdivided soup.
SOUP_TOPOLOGY_ADD_NAMED_PARAMETER(output_adjacency_tables_t, output_adjacency_tables)

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
