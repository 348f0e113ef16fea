// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The whole pipeline in one call: exact weld, adjacency tables, epsilon welding and T-junction
// splitting iterated to a fixpoint, and the output into any CGAL MutableFaceGraph
// (through triangle_soup_to_face_graph.h).

#ifndef SOUP_TOPOLOGY_RECONSTRUCT_TOPOLOGY_H
#define SOUP_TOPOLOGY_RECONSTRUCT_TOPOLOGY_H

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/Triangle_adjacency_graph.h>
#include <Soup_topology/index_triangles.h>
#include <Soup_topology/parameters.h>
#include <Soup_topology/snap_vertices.h>
#include <Soup_topology/split_t_junctions.h>
#include <Soup_topology/triangle_soup_to_face_graph.h>
#include <Soup_topology/internal/soup_checks.h>

#include <CGAL/Kernel_traits.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <type_traits>
#include <vector>

namespace Soup_topology {

/// \ingroup PkgSoupTopologyPipeline
/// \brief everything `reconstruct_topology()` did: nothing is changed silently.
struct Reconstruction_report
{
  double tolerance = 0;                     ///< the absolute tolerance used
  std::size_t input_points = 0;             ///< points given
  std::size_t input_triangles = 0;          ///< triangles given
  std::size_t exact_duplicates = 0;         ///< points merged by the exact weld
  std::size_t collapsed_triangles = 0;      ///< triangles removed because the exact weld collapsed them
  std::size_t rounds = 0;                   ///< weld/split rounds run (the last one changes nothing)
  // Welding, summed over the rounds.
  std::size_t snapped_vertices = 0;         ///< vertices merged within the tolerance
  std::size_t clusters = 0;                 ///< representatives that received vertices
  std::size_t refused_same_triangle = 0;    ///< welds refused: the vertices share a triangle
  std::size_t refused_degenerate = 0;       ///< welds refused: a triangle would degenerate
  std::size_t refused_flip = 0;             ///< welds refused: a triangle would flip
  std::size_t refused_holds_welds = 0;      ///< welds refused: the vertex received welds in an earlier round
  std::size_t ambiguous_sites = 0;          ///< sites where the minimum feature separation is not met
  std::size_t short_edges = 0;              ///< edges shorter than the tolerance (first round)
  // T-junctions, summed over the rounds.
  std::size_t t_junctions = 0;              ///< vertices found on the interior of a border edge
  std::size_t split_triangles = 0;          ///< triangle splits (each adds one triangle)
  std::size_t refused_splits = 0;           ///< T-junctions refused (overlap, degenerate, flip)
  std::size_t ambiguous_t_junctions = 0;    ///< vertices near several border edges
  // Before (after the exact weld) and after.
  std::size_t border_edges_before = 0;
  std::size_t border_edges_after = 0;
  std::size_t non_manifold_edges_before = 0;
  std::size_t non_manifold_edges_after = 0;
  std::size_t non_manifold_vertices_after = 0;
  std::size_t components_before = 0;
  std::size_t components = 0;               ///< edge-connected components of the result
  std::size_t removed_points = 0;           ///< points no triangle uses any more, removed at the end
  std::size_t output_points = 0;
  std::size_t output_triangles = 0;
  double max_displacement = 0;              ///< largest distance from an input point to its output point
  // Writing into a FaceGraph.
  std::size_t duplicate_triangles = 0;      ///< triangles with the same three vertices as another, left out
  std::size_t orientation_flips = 0;        ///< triangles reversed to orient their component
  std::size_t duplicated_points = 0;        ///< points duplicated to separate non-manifold vertices and edges

  /// the total number of refused welds.
  std::size_t refused_welds() const
  { return refused_same_triangle + refused_degenerate + refused_flip + refused_holds_welds; }
  /// `true` if the result has no border edge.
  bool closed() const { return border_edges_after == 0; }
};

namespace internal {

template <class T>
struct is_named_parameters : std::false_type {};
template <class T, class Tag, class Base>
struct is_named_parameters<CGAL::Named_function_parameters<T, Tag, Base>> : std::true_type {};

/// removes the points no triangle uses and renumbers the triangles; returns the new index of
/// every old point (or -1).
template <class PointRange, class TriangleRange>
std::vector<std::size_t> remove_unreferenced_points(PointRange& points, TriangleRange& triangles)
{
  std::vector<std::size_t> new_index(points.size(), static_cast<std::size_t>(-1));
  for(const auto& f : triangles)
    for(const auto& v : f) new_index[static_cast<std::size_t>(v)] = 0;
  std::size_t kept = 0;
  for(std::size_t i = 0; i < points.size(); ++i)
    if(new_index[i] == 0) {
      new_index[i] = kept;
      if(kept != i) points[kept] = points[i];
      ++kept;
    }
  points.resize(kept);
  for(auto& f : triangles)
    for(auto& v : f) v = static_cast<std::decay_t<decltype(v)>>(new_index[static_cast<std::size_t>(v)]);
  return new_index;
}

} // namespace internal

/// \ingroup PkgSoupTopologyPipeline
/// \brief repairs an indexed triangle soup in place: merges exactly equal points, builds the
/// adjacency tables, then welds duplicate vertices within the tolerance (`snap_vertices()`) and
/// splits T-junctions (`split_t_junctions()`) in rounds until a round changes nothing (a split
/// can expose a new duplicate and a weld a new T-junction: Milenkovic's normalisation). Finally
/// the points no triangle uses are removed.
///
/// Triangles that the exact weld collapses (two equal corners) are removed and counted. The
/// output points are a subset of the input points (no coordinate is constructed), in input order.
///
/// \tparam PointRange a `std::vector`-like container of `Point_3`
/// \tparam TriangleRange a `std::vector`-like container of triangles (3 indices each)
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{snapping_tolerance} \cgalParamType{`geom_traits::FT`} \cgalParamDefault{0: exact
///     duplicates only} \cgalParamNEnd
///   \cgalParamNBegin{relative_tolerance} \cgalParamType{`double`} \cgalParamDescription{the tolerance as a
///     fraction of the bounding-box diagonal} \cgalParamNEnd
///   \cgalParamNBegin{geom_traits} \cgalParamType{a CGAL Kernel} \cgalParamDefault{the kernel of the point type}
///     \cgalParamNEnd
///   \cgalParamNBegin{maximum_number_of_rounds} \cgalParamType{`std::size_t`} \cgalParamDefault{8} \cgalParamNEnd
///   \cgalParamNBegin{do_split_t_junctions} \cgalParamType{`bool`} \cgalParamDefault{`true`} \cgalParamNEnd
/// \cgalNamedParamsEnd
/// \returns a `Reconstruction_report`.
/// \throws Invalid_input on an index out of range, a face that is not a triangle, a repeated index
///         in a face, a non-finite coordinate or an invalid tolerance; `points` and `triangles`
///         are unchanged then.
template <class PointRange, class TriangleRange, class NamedParameters = CGAL::parameters::Default_named_parameters,
          std::enable_if_t<internal::is_named_parameters<NamedParameters>::value, int> = 0>
Reconstruction_report reconstruct_topology(PointRange& points, TriangleRange& triangles,
                                           const NamedParameters& np = CGAL::parameters::default_values())
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  using Point = typename PointRange::value_type;
  using Kernel = typename CGAL::Kernel_traits<Point>::Kernel;
  using FT = typename Kernel::FT;

  Reconstruction_report report;
  report.input_points = points.size();
  report.input_triangles = triangles.size();
  // Validate everything before changing anything.
  {
    std::size_t face_id = 0;
    for(const auto& f : triangles) {
      if(internal::face_size(f) != 3)
        throw Invalid_input("face " + std::to_string(face_id) + " has " + std::to_string(internal::face_size(f)) +
                            " vertices; a triangle soup needs exactly 3");
      for(std::size_t k = 0; k < 3; ++k)
        if(internal::corner(f, k, face_id) >= points.size())
          throw Invalid_input("face " + std::to_string(face_id) + ": vertex index " +
                              std::to_string(internal::corner(f, k, face_id)) + " is out of range (" +
                              std::to_string(points.size()) + " points)");
      const std::size_t a = internal::corner(f, 0, face_id), b = internal::corner(f, 1, face_id),
                        c = internal::corner(f, 2, face_id);
      if(a == b || b == c || c == a)
        throw Invalid_input("face " + std::to_string(face_id) + " repeats a vertex index (" + std::to_string(a) +
                            ", " + std::to_string(b) + ", " + std::to_string(c) + ")");
      ++face_id;
    }
  }
  internal::check_finite_points(points, CGAL::Identity_property_map<Point>());
  const FT eps = internal::resolve_tolerance<FT>(points, CGAL::Identity_property_map<Point>(), np);
  report.tolerance = CGAL::to_double(eps);
  const std::size_t max_rounds = choose_parameter(get_parameter(np, internal_np::maximum_number_of_rounds), std::size_t(8));
  const bool do_split = choose_parameter(get_parameter(np, internal_np::do_split_t_junctions), true);
  const Kernel kernel = choose_parameter<Kernel>(get_parameter(np, CGAL::internal_np::geom_traits));
  const auto weld_np = CGAL::parameters::snapping_tolerance(eps).geom_traits(kernel);

  // Step 0: exact weld.
  report.exact_duplicates = merge_duplicate_points(points, triangles);
  report.collapsed_triangles = remove_collapsed_triangles(triangles);

  // Step 1: the tables.
  Adjacency_tables tables(triangles, points.size());
  report.border_edges_before = tables.number_of_border_edges();
  report.non_manifold_edges_before = tables.non_manifold_edges().size();
  report.components_before = tables.number_of_connected_components();

  // Steps 2 and 3, to a fixpoint.
  std::vector<std::size_t> merged_into(points.size());
  for(std::size_t i = 0; i < merged_into.size(); ++i) merged_into[i] = i;
  struct Recording_visitor
  {
    std::vector<std::size_t>* merged_into;
    void on_merge(std::size_t d, std::size_t r) { (*merged_into)[d] = r; }
    void on_refusal(std::size_t, std::size_t, Refusal_reason) {}
  } recorder{&merged_into};
  std::vector<std::size_t> sites;
  // A vertex that received welds is never moved in a later round (its welded points would move
  // farther than the tolerance); it may still receive more.
  std::vector<char> holds_welds(points.size(), 0);
  for(std::size_t round = 0; round < max_rounds; ++round) {
    ++report.rounds;
    const Snap_report s = snap_vertices(
      points, triangles, tables,
      CGAL::Named_function_parameters<const std::vector<char>*, internal_np::fixed_vertices_t,
                                      std::decay_t<decltype(weld_np.visitor(std::ref(recorder)))>>(
        &holds_welds, weld_np.visitor(std::ref(recorder))));
    for(std::size_t v = 0; v < merged_into.size(); ++v)
      if(merged_into[v] != v) holds_welds[merged_into[v]] = 1;
    report.snapped_vertices += s.merged_vertices;
    report.clusters += s.clusters;
    report.refused_same_triangle += s.refused_same_triangle;
    report.refused_degenerate += s.refused_degenerate;
    report.refused_flip += s.refused_flip;
    report.refused_holds_welds += s.refused_holds_welds;
    if(round == 0) report.short_edges = s.short_edges;
    sites.insert(sites.end(), s.ambiguous_sites.begin(), s.ambiguous_sites.end());
    std::size_t splits = 0;
    if(do_split) {
      const Split_report t = split_t_junctions(points, triangles, tables, weld_np);
      report.t_junctions += t.t_junctions;
      report.split_triangles += t.split_triangles;
      report.refused_splits += t.refused_overlap + t.refused_degenerate + t.refused_flip;
      report.ambiguous_t_junctions += t.ambiguous;
      splits = t.split_triangles;
    }
    if(s.merged_vertices == 0 && splits == 0) break;
  }
  std::sort(sites.begin(), sites.end());
  report.ambiguous_sites = static_cast<std::size_t>(std::unique(sites.begin(), sites.end()) - sites.begin());

  // How far the points moved: every input point follows its exact-weld image (same coordinates)
  // and then the chain of welds; only the points of the soup that were welded can move.
  typename Kernel::Compute_squared_distance_3 squared_distance = kernel.compute_squared_distance_3_object();
  for(std::size_t v = 0; v < merged_into.size(); ++v) {
    if(merged_into[v] == v) continue;
    std::size_t w = merged_into[v];
    while(merged_into[w] != w) w = merged_into[w];
    report.max_displacement =
      std::max(report.max_displacement, std::sqrt(CGAL::to_double(squared_distance(points[v], points[w]))));
  }

  // Final counts, from the live tables (removing unused points below changes none of them).
  report.border_edges_after = tables.number_of_border_edges();
  report.non_manifold_edges_after = tables.non_manifold_edges().size();
  report.non_manifold_vertices_after = tables.non_manifold_vertices().size();
  report.components = tables.number_of_connected_components();
  const std::size_t before = points.size();
  internal::remove_unreferenced_points(points, triangles);
  report.removed_points = before - points.size();
  report.output_points = points.size();
  report.output_triangles = triangles.size();
  return report;
}

/// \ingroup PkgSoupTopologyPipeline
/// \brief repairs a copy of the soup with `reconstruct_topology(points, triangles, np_soup)` and
/// writes the result into `mesh` with `triangle_soup_to_face_graph()`; the report gathers both.
/// `points` and `triangles` are not changed.
///
/// \param np_soup the parameters of `reconstruct_topology()` for the soup
/// \param np_mesh parameters for the mesh: `vertex_point_map`
template <class PointRange, class TriangleRange, class PolygonMesh,
          class NamedParametersSoup = CGAL::parameters::Default_named_parameters,
          class NamedParametersMesh = CGAL::parameters::Default_named_parameters,
          std::enable_if_t<!internal::is_named_parameters<PolygonMesh>::value, int> = 0>
Reconstruction_report reconstruct_topology(const PointRange& points, const TriangleRange& triangles, PolygonMesh& mesh,
                                           const NamedParametersSoup& np_soup = CGAL::parameters::default_values(),
                                           const NamedParametersMesh& np_mesh = CGAL::parameters::default_values())
{
  using Point = typename PointRange::value_type;
  std::vector<Point> pts(points.begin(), points.end());
  std::vector<std::array<std::size_t, 3>> tris;
  tris.reserve(triangles.size());
  std::size_t face_id = 0;
  for(const auto& f : triangles) {
    if(internal::face_size(f) != 3)
      throw Invalid_input("face " + std::to_string(face_id) + " has " + std::to_string(internal::face_size(f)) +
                          " vertices; a triangle soup needs exactly 3");
    tris.push_back({internal::corner(f, 0, face_id), internal::corner(f, 1, face_id), internal::corner(f, 2, face_id)});
    ++face_id;
  }
  Reconstruction_report report = reconstruct_topology(pts, tris, np_soup);
  const Face_graph_output_report out = triangle_soup_to_face_graph(pts, tris, mesh, np_mesh);
  report.duplicate_triangles = out.duplicate_triangles;
  report.orientation_flips = out.orientation_flips;
  report.duplicated_points = out.duplicated_points;
  return report;
}

} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_RECONSTRUCT_TOPOLOGY_H
