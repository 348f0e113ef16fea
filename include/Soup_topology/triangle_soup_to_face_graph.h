// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Writing an indexed triangle soup into any CGAL MutableFaceGraph: repeated triangles left out,
// every component oriented, non-manifold vertices and edges separated.

#ifndef SOUP_TOPOLOGY_TRIANGLE_SOUP_TO_FACE_GRAPH_H
#define SOUP_TOPOLOGY_TRIANGLE_SOUP_TO_FACE_GRAPH_H

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/orient_triangle_soup.h>
#include <Soup_topology/internal/soup_checks.h>

#include <CGAL/Kernel_traits.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <algorithm>
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
/// component oriented, non-manifold vertices and edges separated by duplicating points), then
/// `CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh()` builds the mesh. The result
/// passes `CGAL::is_valid_polygon_mesh()`.
///
/// \param np_mesh parameters for the mesh: `vertex_point_map`
/// \throws Invalid_input if a face is not a triangle of in-range, distinct indices.
template <class PointRange, class TriangleRange, class PolygonMesh,
          class NamedParametersMesh = CGAL::parameters::Default_named_parameters>
Face_graph_output_report triangle_soup_to_face_graph(const PointRange& points, const TriangleRange& triangles,
                                                     PolygonMesh& mesh,
                                                     const NamedParametersMesh& np_mesh = CGAL::parameters::default_values())
{
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
  const Face_graph_output_report report = orient_triangle_soup(pts, tris);
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(pts, tris, mesh, CGAL::parameters::default_values(),
                                                              np_mesh);
  return report;
}

} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_TRIANGLE_SOUP_TO_FACE_GRAPH_H
