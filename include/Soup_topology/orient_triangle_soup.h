// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Orienting an indexed triangle soup in place: repeated triangles left out, every patch oriented
// consistently and then as a whole by a policy, non-manifold vertices and edges separated by
// duplicating their points, every choice independent of the order of the triangles. What
// `triangle_soup_to_face_graph()` and the command-line writers build on.

#ifndef SOUP_TOPOLOGY_ORIENT_TRIANGLE_SOUP_H
#define SOUP_TOPOLOGY_ORIENT_TRIANGLE_SOUP_H

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/internal/orient_soup.h>
#include <Soup_topology/internal/soup_checks.h>
#include <Soup_topology/parameters.h>

#include <CGAL/Kernel_traits.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/property_map.h>

#include <cstddef>

namespace Soup_topology {

/// \ingroup PkgSoupTopologyPipeline
/// \brief how `orient_triangle_soup()` (and `triangle_soup_to_face_graph()`) choose the
/// orientation of each patch of the soup (a set of triangles connected through edges that
/// exactly two triangles share).
///
/// In every policy a patch is first oriented consistently, keeping the input orientation of as
/// many triangles as one orientation allows, so a patch already consistent as read keeps every
/// triangle unless the policy turns it as a whole. Open patches always keep the orientation most
/// of their triangles have as read. The policies differ on closed patches:
enum class Orientation_policy
{
  /// closed patches are oriented as `CGAL::Polygon_mesh_processing::orient_to_bound_a_volume()`
  /// does: by nesting depth, outermost shells outward, shells inside them inward, and so on. The
  /// default: a soup that bounds a volume as read is left as it is (a shell with a cavity keeps
  /// its inward inner shell), and one that does not is turned so that it does wherever the
  /// shells do not intersect, which is what a repaired mesh is for.
  BOUND_VOLUME,
  /// every patch already consistently oriented as read keeps its orientation, even a closed
  /// shell that faces inward alone; only the other closed patches are oriented by nesting depth.
  /// For data whose orientation carries meaning of its own.
  KEEP_INPUT,
  /// every closed patch gets a positive signed volume, nested or not: cavities face outward too,
  /// so a shell with a cavity no longer bounds a volume. For callers that want every closed
  /// piece to be a solid of its own.
  OUTWARD
};

/// \ingroup PkgSoupTopologyPipeline
/// \brief what `orient_triangle_soup()` changed to make the soup the triangles of a valid
/// polygon mesh.
struct Orientation_report
{
  std::size_t duplicate_triangles = 0;   ///< triangles with the same three vertices as another, left out
  std::size_t orientation_flips = 0;     ///< triangles reversed to orient their component
  std::size_t duplicated_points = 0;     ///< points duplicated to separate non-manifold vertices and edges
};

/// \ingroup PkgSoupTopologyPipeline
/// \brief what `triangle_soup_to_face_graph()` changed: the same as `orient_triangle_soup()`.
using Face_graph_output_report = Orientation_report;

/// \ingroup PkgSoupTopologyPipeline
/// \brief orients an indexed triangle soup in place so that it is the face set of a valid
/// polygon mesh (it passes `CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh()`,
/// every vertex being one fan).
///
/// 1. Triangles on the same three vertices are one: the orientation most of them have is kept
///    (on a tie, a canonical one), from its first occurrence; the others are left out.
/// 2. The triangles are grouped into patches: connected through edges shared by exactly two
///    triangles. Each patch is oriented by a breadth-first traversal; a patch that cannot be
///    oriented (a Moebius strip) gives up the edges where the traversal meets itself, starting
///    from its canonically smallest triangle.
/// 3. Every vertex gets one point per fan of its triangles: edges shared by three or more
///    triangles and given-up edges do not join fans. The extra points are appended to `pts`.
/// 4. Each patch is turned as a whole by the `orientation_policy`.
///
/// The result does not depend on the order of the triangles: every choice the order could decide
/// is made on the canonical order of the triangles (by the sorted ranks of their points, points
/// ranked by lexicographic coordinates). For any permutation of the triangles the set of
/// oriented triangles and the points are the same; for a permutation of the points too, the
/// result is the same up to relabelling wherever distinct points have distinct coordinates.
/// A soup that is already a consistently oriented closed manifold keeps its triangles, or has
/// each closed component reversed as a whole by the policy.
///
/// With `CGAL::Parallel_tag` the adjacency tables, the search for repeated triangles, the
/// patches and the orientation of their triangles, the fans of the vertices, the closed patches,
/// their volumes and the writing back run on TBB's threads; the result is the same, bit for bit,
/// on any number of threads. On several threads the patches are joined by a union-find that
/// keeps, for every two triangles of a set, whether they must be oriented alike, by blocks of
/// triangles, instead of being traversed: it gives the orientations of the traversal from each
/// patch's smallest triangle. A traversal is still made, patch by patch, where a decision depends
/// on its order: the cuts of a non-orientable patch, the nesting test between closed patches (its
/// samples and winding numbers), and the volume of a closed patch whose sign the sum in another
/// order does not decide (a volume that is 0 up to rounding).
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` (the default), `CGAL::Parallel_tag` (needs TBB)
///         or `CGAL::Parallel_if_available_tag`
/// \tparam PointRange a `std::vector` of `Point_3` (of a CGAL kernel)
/// \tparam TriangleRange a `std::vector` of triangles of three indices (`std::array<std::size_t, 3>`, ...)
/// \tparam NamedParameters a sequence of named parameters
/// \param pts the points; duplicated points are appended, nothing else changes
/// \param tris the triangles, changed in place (repeated ones removed, the others keep their order)
/// \param np optional named parameters among the following ones:
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{orientation_policy}
///     \cgalParamDescription{how closed patches are oriented}
///     \cgalParamType{`Soup_topology::Orientation_policy`}
///     \cgalParamDefault{`Orientation_policy::BOUND_VOLUME`}
///   \cgalParamNEnd
///   \cgalParamNBegin{geom_traits}
///     \cgalParamDescription{the kernel, for the lexicographic order of points}
///     \cgalParamType{a model of `Kernel`}
///     \cgalParamDefault{the kernel of the point type}
///   \cgalParamNEnd
/// \cgalNamedParamsEnd
/// \returns what was changed
/// \throws Invalid_input if a face is not a triangle of in-range, distinct indices, or a point has
///         a non-finite coordinate; nothing is changed then.
template <class ConcurrencyTag = CGAL::Sequential_tag, class PointRange, class TriangleRange,
          class NamedParameters = CGAL::parameters::Default_named_parameters>
Orientation_report orient_triangle_soup(PointRange& pts, TriangleRange& tris,
                                        const NamedParameters& np = CGAL::parameters::default_values());

namespace internal {

/// the rules of `Soup_orienter` for the `orientation_policy` of `np`.
template <class NamedParameters>
Patch_orientation_rules patch_orientation_rules(const NamedParameters& np)
{
  const Orientation_policy policy = CGAL::parameters::choose_parameter(
    CGAL::parameters::get_parameter(np, internal_np::orientation_policy), Orientation_policy::BOUND_VOLUME);
  Patch_orientation_rules rules;
  rules.keep_consistent_input = (policy == Orientation_policy::KEEP_INPUT);
  rules.nest_closed_patches = (policy != Orientation_policy::OUTWARD);
  return rules;
}

/// `orient_triangle_soup()` with the adjacency tables of the soup, when the caller has them
/// (`tables` not null: the tables of exactly `tris` over `pts`, same triangles in the same order,
/// as a pipeline keeps them up to date; they are read, not changed). The result (points,
/// triangles, report) is the same as without them: only the construction of the tables is saved
/// (they are built again, once, only if repeated triangles are left out).
/// \throws Invalid_input as `orient_triangle_soup()`, or if the tables do not have as many
///         triangles and vertices as the soup
template <class ConcurrencyTag = CGAL::Sequential_tag, class PointRange, class TriangleRange,
          class NamedParameters = CGAL::parameters::Default_named_parameters>
Orientation_report orient_triangle_soup_with_tables(PointRange& pts, TriangleRange& tris, const Adjacency_tables* tables,
                                                    const NamedParameters& np = CGAL::parameters::default_values())
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  using Point = typename PointRange::value_type;
  using Default_kernel = typename CGAL::Kernel_traits<Point>::Kernel;
  using Kernel = typename CGAL::internal_np::Lookup_named_param_def<CGAL::internal_np::geom_traits_t, NamedParameters,
                                                                     Default_kernel>::type;
  check_triangle_soup<ConcurrencyTag>(tris, pts.size());
  check_finite_points<ConcurrencyTag>(pts, CGAL::Identity_property_map<Point>());
  const Kernel kernel = choose_parameter<Kernel>(get_parameter(np, CGAL::internal_np::geom_traits));
  Soup_orienter<PointRange, TriangleRange, Kernel> orienter(pts, tris, patch_orientation_rules(np), kernel, tables);
  Orientation_report report;
  copy_orientation_counts(orienter.template run<ConcurrencyTag>(), report);
  return report;
}

} // namespace internal

template <class ConcurrencyTag, class PointRange, class TriangleRange, class NamedParameters>
Orientation_report orient_triangle_soup(PointRange& pts, TriangleRange& tris, const NamedParameters& np)
{
  return internal::orient_triangle_soup_with_tables<ConcurrencyTag>(pts, tris, nullptr, np);
}

} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_ORIENT_TRIANGLE_SOUP_H
