// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Writing an indexed triangle soup into any CGAL MutableFaceGraph: the soup is oriented, then the
// halfedge structure is built directly, in linear time.

#ifndef SOUP_TOPOLOGY_TRIANGLE_SOUP_TO_FACE_GRAPH_H
#define SOUP_TOPOLOGY_TRIANGLE_SOUP_TO_FACE_GRAPH_H

#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/internal/build_face_graph.h>
#include <Soup_topology/internal/soup_checks.h>
#include <Soup_topology/orient_triangle_soup.h>
#include <Soup_topology/parameters.h>

#include <CGAL/Kernel_traits.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>
// CGAL's soup-to-mesh functions, which callers of this header compare its meshes with and reach
// through it; this header itself does not use them.
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>

#include <array>
#include <cstddef>
#include <vector>

namespace Soup_topology {

/// \ingroup PkgSoupTopologyPipeline
/// \brief writes an indexed triangle soup (typically the result of `reconstruct_topology()`) into
/// `mesh`, any model of `MutableFaceGraph` (`CGAL::Surface_mesh`, `CGAL::Polyhedron_3`, ...).
/// What `mesh` held before stays.
///
/// A copy of the soup is oriented by `orient_triangle_soup()` (repeated triangles left out, every
/// patch oriented by the `orientation_policy`, non-manifold vertices and edges separated by
/// duplicating points), then the halfedge structure is built directly through the BGL
/// `MutableFaceGraph` functions (`add_vertex`, `add_edge`, `add_face`, `set_target`, `set_next`,
/// ...), in time linear in the size of the soup whatever the vertex degrees. The mesh gets one
/// vertex per point (in order, isolated points included) and one face per kept triangle (in
/// order), as `CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh()` would build from
/// the oriented soup, and passes `CGAL::is_valid_polygon_mesh()`. Like the orientation, the mesh
/// does not depend on the order of the triangles beyond the order of its faces.
///
/// When the point type of the mesh differs from the soup's (Epick points into a
/// `Polyhedron_3<Epeck>`), the points are converted with `CGAL::Cartesian_converter`.
///
/// \tparam PointRange a range of `Point_3` (of a CGAL kernel)
/// \tparam TriangleRange a range of triangles of three indices
/// \tparam PolygonMesh a model of `MutableFaceGraph`
/// \param points the points (not changed)
/// \param triangles the triangles (not changed)
/// \param mesh the mesh the soup is added to
/// \param np_mesh optional named parameters among the following ones:
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{vertex_point_map}
///     \cgalParamDescription{the points of the mesh's vertices}
///     \cgalParamType{a model of `WritablePropertyMap` with `vertex_descriptor` as key}
///     \cgalParamDefault{`boost::get(CGAL::vertex_point, mesh)`}
///   \cgalParamNEnd
///   \cgalParamNBegin{orientation_policy}
///     \cgalParamDescription{how closed patches are oriented, see `orient_triangle_soup()`}
///     \cgalParamType{`Soup_topology::Orientation_policy`}
///     \cgalParamDefault{`Orientation_policy::BOUND_VOLUME`}
///   \cgalParamNEnd
/// \cgalNamedParamsEnd
/// \returns what the orientation changed
/// \throws Invalid_input if a face is not a triangle of in-range, distinct indices or a point has
///         a non-finite coordinate; `mesh` is not changed then.
template <class PointRange, class TriangleRange, class PolygonMesh,
          class NamedParametersMesh = CGAL::parameters::Default_named_parameters>
Face_graph_output_report triangle_soup_to_face_graph(const PointRange& points, const TriangleRange& triangles,
                                                     PolygonMesh& mesh,
                                                     const NamedParametersMesh& np_mesh = CGAL::parameters::default_values())
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  using Point = typename PointRange::value_type;
  internal::check_triangle_soup(triangles, points.size());
  std::vector<Point> pts(points.begin(), points.end());
  std::vector<std::array<std::size_t, 3>> tris;
  tris.reserve(triangles.size());
  std::size_t face_id = 0;
  for(const auto& f : triangles) {
    tris.push_back({internal::corner(f, 0, face_id), internal::corner(f, 1, face_id), internal::corner(f, 2, face_id)});
    ++face_id;
  }
  const Orientation_policy policy =
    choose_parameter(get_parameter(np_mesh, internal_np::orientation_policy), Orientation_policy::BOUND_VOLUME);
  const Face_graph_output_report report =
    orient_triangle_soup(pts, tris, parameters::orientation_policy(policy));
  auto vpm = choose_parameter(get_parameter(np_mesh, CGAL::internal_np::vertex_point),
                              get_property_map(CGAL::vertex_point, mesh));
  internal::build_face_graph(pts, tris, mesh, vpm);
  return report;
}

} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_TRIANGLE_SOUP_TO_FACE_GRAPH_H
