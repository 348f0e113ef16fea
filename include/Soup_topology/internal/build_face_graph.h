// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Building the halfedge structure of a MutableFaceGraph directly from an oriented, manifold
// indexed triangle soup, in time linear in its size.

#ifndef SOUP_TOPOLOGY_INTERNAL_BUILD_FACE_GRAPH_H
#define SOUP_TOPOLOGY_INTERNAL_BUILD_FACE_GRAPH_H

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/Invalid_input.h>

#include <CGAL/Cartesian_converter.h>
#include <CGAL/Kernel_traits.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>

#include <boost/graph/graph_traits.hpp>
#include <boost/property_map/property_map.hpp>

#include <array>
#include <cstddef>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace Soup_topology {
namespace internal {

// Converts a soup point to the mesh's point type: a plain copy when the types match or convert,
// `CGAL::Cartesian_converter` between the two kernels otherwise (e.g. Epick into Epeck).
template <class Target, class Source>
Target convert_point(const Source& p)
{
  if constexpr(std::is_convertible<Source, Target>::value) {
    return Target(p);
  } else {
    using Source_kernel = typename CGAL::Kernel_traits<Source>::Kernel;
    using Target_kernel = typename CGAL::Kernel_traits<Target>::Kernel;
    static const CGAL::Cartesian_converter<Source_kernel, Target_kernel> converter;
    return converter(p);
  }
}

/// Adds the points and triangles of an indexed soup to `g` (what `g` held stays): one vertex per
/// point (isolated points included, in order), one face per triangle (in order), the edges and
/// their border halfedges, without `CGAL::Euler::add_face()`: each edge is paired with its
/// opposite through the soup's adjacency tables and each border halfedge with the border halfedge
/// leaving its target, so the cost does not depend on vertex degrees. Same vertices, faces and
/// face cycles as `CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh()`.
///
/// Precondition, checked: every edge belongs to at most two triangles, traversed in opposite
/// directions (the soup is oriented). The caller also guarantees that every vertex is manifold
/// (one fan), as `orient_triangle_soup()` leaves it; a vertex with two border fans would make
/// the border cycles wrong.
template <class PointRange, class TriangleRange, class PolygonMesh, class VertexPointMap>
void build_face_graph(const PointRange& points, const TriangleRange& triangles, PolygonMesh& g, VertexPointMap vpm)
{
  using Graph_traits = boost::graph_traits<PolygonMesh>;
  using vertex_descriptor = typename Graph_traits::vertex_descriptor;
  using halfedge_descriptor = typename Graph_traits::halfedge_descriptor;
  using face_descriptor = typename Graph_traits::face_descriptor;
  using Mesh_point = typename boost::property_traits<VertexPointMap>::value_type;
  using size_type = Adjacency_tables::size_type;

  const Adjacency_tables tables(triangles, points.size());
  const std::size_t nv = points.size(), nf = tables.number_of_triangles();
  const std::size_t number_of_borders = tables.number_of_border_edges();
  // Checked before the mesh is touched: a shared edge must be manifold and consistently oriented.
  for(size_type t = 0; t < nf; ++t)
    for(int i = 0; i < 3; ++i) {
      const size_type u = tables.neighbor(t, i);
      if(u == Adjacency_tables::border_edge) continue;
      const size_type a = tables.vertex(t, i), b = tables.vertex(t, (i + 1) % 3);
      if(u == Adjacency_tables::non_manifold_edge || tables.vertex(u, tables.edge_index(u, a, b)) == a)
        throw Invalid_input("triangle " + std::to_string(t) + ": edge (" + std::to_string(a) + ", " +
                            std::to_string(b) + ") is not shared by exactly two oppositely oriented triangles");
    }

  reserve(g, static_cast<typename Graph_traits::vertices_size_type>(num_vertices(g) + nv),
          static_cast<typename Graph_traits::edges_size_type>(num_edges(g) + (3 * nf + number_of_borders) / 2),
          static_cast<typename Graph_traits::faces_size_type>(num_faces(g) + nf));

  std::vector<vertex_descriptor> vertex(nv);
  for(std::size_t v = 0; v < nv; ++v) {
    vertex[v] = add_vertex(g);
    put(vpm, vertex[v], convert_point<Mesh_point>(points[v]));
  }

  // halfedge[3 t + i] runs along edge i of triangle t, from its corner i to its corner i + 1.
  std::vector<halfedge_descriptor> halfedge_of(3 * nf);
  // For every border halfedge (which runs opposite to a triangle edge), its target's soup index;
  // border_out[v] is the border halfedge that leaves v (at most one: v is manifold).
  std::vector<std::pair<halfedge_descriptor, size_type>> borders;
  borders.reserve(number_of_borders);
  std::vector<halfedge_descriptor> border_out(nv, Graph_traits::null_halfedge());
  for(size_type t = 0; t < nf; ++t)
    for(int i = 0; i < 3; ++i) {
      const size_type u = tables.neighbor(t, i);
      const size_type a = tables.vertex(t, i), b = tables.vertex(t, (i + 1) % 3);
      if(u != Adjacency_tables::border_edge && u < t) {
        halfedge_of[3 * std::size_t(t) + std::size_t(i)] =
          opposite(halfedge_of[3 * std::size_t(u) + std::size_t(tables.edge_index(u, a, b))], g);
        continue;
      }
      const halfedge_descriptor h = halfedge(add_edge(g), g);
      halfedge_of[3 * std::size_t(t) + std::size_t(i)] = h;
      if(u == Adjacency_tables::border_edge) {
        const halfedge_descriptor hb = opposite(h, g);
        set_face(hb, Graph_traits::null_face(), g);
        set_target(hb, vertex[a], g);
        border_out[b] = hb;
        borders.emplace_back(hb, a);
      }
    }

  for(size_type t = 0; t < nf; ++t) {
    const face_descriptor f = add_face(g);
    const std::size_t base = 3 * std::size_t(t);
    for(int i = 0; i < 3; ++i) {
      const halfedge_descriptor h = halfedge_of[base + std::size_t(i)];
      const vertex_descriptor w = vertex[tables.vertex(t, (i + 1) % 3)];
      set_target(h, w, g);
      set_face(h, f, g);
      set_next(h, halfedge_of[base + std::size_t((i + 1) % 3)], g);
      set_halfedge(w, h, g);
    }
    // The halfedge that Euler::add_face() gives a face: the one ending at corner 0.
    set_halfedge(f, halfedge_of[base + 2], g);
  }
  // A border vertex points to its incoming border halfedge (the convention of CGAL's BGL, which
  // `is_border(v, g)` relies on).
  for(const auto& [hb, a] : borders) {
    set_next(hb, border_out[a], g);
    set_halfedge(vertex[a], hb, g);
  }
}

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_BUILD_FACE_GRAPH_H
