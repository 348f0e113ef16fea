// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Orienting an indexed triangle soup in place: repeated triangles left out, every edge-connected
// component oriented consistently, non-manifold vertices and edges separated by duplicating
// their points. What `triangle_soup_to_face_graph()` and the command-line writers build on.

#ifndef SOUP_TOPOLOGY_ORIENT_TRIANGLE_SOUP_H
#define SOUP_TOPOLOGY_ORIENT_TRIANGLE_SOUP_H

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/Triangle_adjacency_graph.h>
#include <Soup_topology/internal/soup_checks.h>

#include <CGAL/Kernel_traits.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <boost/graph/breadth_first_search.hpp>

#include <algorithm>
#include <array>
#include <cstddef>
#include <vector>

namespace Soup_topology {

namespace internal {

// BFS over the triangle adjacency graph: each triangle reached over a manifold edge is reversed
// if it traverses the shared edge in the same direction as the triangle it was reached from.
struct Orientation_bfs_visitor : boost::default_bfs_visitor
{
  std::vector<char>* reversed;
  std::size_t* flips;
  template <class Edge, class Graph>
  void tree_edge(const Edge& e, const Graph& g) const
  {
    const Adjacency_tables& a = g.tables();
    const auto s = source(e, g), t = target(e, g);
    const Adjacency_tables::Edge h = halfedge_in_smaller_triangle(e, g);
    const auto p = a.vertex(h.triangle, h.index), q = a.vertex(h.triangle, (h.index + 1) % 3);
    auto goes_p_to_q = [&](Adjacency_tables::size_type u) {
      const int j = a.edge_index(u, p, q);
      return (a.vertex(u, j) == p) != ((*reversed)[u] != 0);
    };
    if(goes_p_to_q(s) == goes_p_to_q(t)) { (*reversed)[t] = !(*reversed)[t]; ++*flips; }
  }
};

} // namespace internal

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
/// polygon mesh.
///
/// Triangles repeating another triangle's three vertices are left out (the first is kept); each
/// edge-connected component is oriented consistently by a breadth-first search over the
/// `Triangle_adjacency_graph` (from its smallest triangle), then turned as a whole so that a
/// closed component has a positive signed volume and an open one reverses fewer triangles than
/// it keeps; vertices and edges that cannot be manifold are separated by duplicating their points
/// (appended to `points`). Each step is counted in the report.
///
/// \tparam PointRange a `std::vector` of `Point_3`
/// \tparam TriangleRange a `std::vector` of `std::array<std::size_t, 3>`
/// \param pts the points; duplicated points are appended
/// \param tris the triangles, changed in place
/// \throws Invalid_input if a face is not a triangle of in-range, distinct indices.
template <class PointRange, class TriangleRange>
Orientation_report orient_triangle_soup(PointRange& pts, TriangleRange& tris)
{
  using Point = typename PointRange::value_type;
  using Kernel = typename CGAL::Kernel_traits<Point>::Kernel;
  internal::check_triangle_soup(tris, pts.size());
  Orientation_report report;
  // Leave out repeated triangles (same three vertices in any order), keeping the first.
  {
    std::vector<std::pair<std::array<std::size_t, 3>, std::size_t>> keys(tris.size());
    for(std::size_t t = 0; t < tris.size(); ++t) {
      std::array<std::size_t, 3> k = tris[t];
      std::sort(k.begin(), k.end());
      keys[t] = {k, t};
    }
    std::sort(keys.begin(), keys.end());
    std::vector<char> drop(tris.size(), 0);
    for(std::size_t k = 1; k < keys.size(); ++k)
      if(keys[k].first == keys[k - 1].first) { drop[keys[k].second] = 1; ++report.duplicate_triangles; }
    std::size_t kept = 0;
    for(std::size_t t = 0; t < tris.size(); ++t) if(!drop[t]) tris[kept++] = tris[t];
    tris.resize(kept);
  }

  // Orient every component by a BFS over the triangle adjacency graph.
  const Adjacency_tables tables(tris, pts.size());
  const Triangle_adjacency_graph graph(tables);
  std::vector<char> reversed(tris.size(), 0);
  std::size_t flips = 0;
  std::vector<Adjacency_tables::size_type> component;
  const std::size_t number_of_components = tables.number_of_connected_components(&component);
  {
    std::vector<boost::default_color_type> colour(tris.size(), boost::white_color);
    auto colour_map = boost::make_iterator_property_map(colour.begin(), get(boost::vertex_index, graph));
    internal::Orientation_bfs_visitor visitor;
    visitor.reversed = &reversed;
    visitor.flips = &flips;
    for(Adjacency_tables::size_type t = 0; t < tris.size(); ++t)
      if(colour[t] == boost::white_color)
        boost::breadth_first_visit(graph, t, boost::visitor(visitor).color_map(colour_map));
  }
  // Canonical orientation per component: positive volume if closed, else fewer reversals.
  {
    std::vector<double> volume(number_of_components, 0.0);
    std::vector<std::size_t> size(number_of_components, 0), reversals(number_of_components, 0);
    std::vector<char> open(number_of_components, 0);
    for(Adjacency_tables::size_type t = 0; t < tris.size(); ++t) {
      const std::size_t c = component[t];
      ++size[c];
      if(reversed[t]) ++reversals[c];
      for(int i = 0; i < 3; ++i) if(tables.is_border_edge(t, i)) open[c] = 1;
      const Point& a = pts[tris[t][0]];
      const Point& b = pts[tris[t][reversed[t] ? 2 : 1]];
      const Point& d = pts[tris[t][reversed[t] ? 1 : 2]];
      const double ax = CGAL::to_double(a.x()), ay = CGAL::to_double(a.y()), az = CGAL::to_double(a.z());
      const double bx = CGAL::to_double(b.x()), by = CGAL::to_double(b.y()), bz = CGAL::to_double(b.z());
      const double dx = CGAL::to_double(d.x()), dy = CGAL::to_double(d.y()), dz = CGAL::to_double(d.z());
      volume[c] += ax * (by * dz - bz * dy) - ay * (bx * dz - bz * dx) + az * (bx * dy - by * dx);
    }
    std::vector<char> turn(number_of_components, 0);
    for(std::size_t c = 0; c < number_of_components; ++c)
      turn[c] = open[c] ? (2 * reversals[c] > size[c]) : (volume[c] < 0);
    for(Adjacency_tables::size_type t = 0; t < tris.size(); ++t)
      if(turn[component[t]]) reversed[t] = !reversed[t];
  }
  for(std::size_t t = 0; t < tris.size(); ++t)
    if(reversed[t]) {
      ++report.orientation_flips;
      std::swap(tris[t][1], tris[t][2]);
    }
  // When every edge is manifold and consistently oriented and every vertex is manifold, the
  // oriented triangles go to the mesh as they are. Otherwise CGAL's orient_polygon_soup()
  // separates what cannot be manifold by duplicating points (measured: on 1.2M manifold
  // triangles it costs three times as much as the rest of this function, hence the test).
  bool manifold = tables.non_manifold_vertices().empty();
  for(Adjacency_tables::size_type t = 0; manifold && t < tris.size(); ++t)
    for(int i = 0; i < 3 && manifold; ++i) {
      const Adjacency_tables::size_type u = tables.neighbor(t, i);
      if(u == Adjacency_tables::border_edge) continue;
      if(u == Adjacency_tables::non_manifold_edge) { manifold = false; break; }
      const std::size_t a = tables.vertex(t, i), b = tables.vertex(t, (i + 1) % 3);
      // t now runs a -> b unless reversed; u must run b -> a.
      const bool t_forward = !reversed[t];
      const int j = tables.edge_index(u, static_cast<Adjacency_tables::size_type>(a), static_cast<Adjacency_tables::size_type>(b));
      const bool u_forward = (tables.vertex(u, j) == a) != (reversed[u] != 0);
      if(t_forward == u_forward) manifold = false;
    }
  if(manifold) return report;
  std::vector<std::vector<std::size_t>> polygons(tris.size());
  for(std::size_t t = 0; t < tris.size(); ++t) polygons[t] = {tris[t][0], tris[t][1], tris[t][2]};
  const std::size_t points_before = pts.size();
  CGAL::Polygon_mesh_processing::orient_polygon_soup(pts, polygons, CGAL::parameters::geom_traits(Kernel()));
  report.duplicated_points = pts.size() - points_before;
  tris.resize(polygons.size());
  for(std::size_t t = 0; t < polygons.size(); ++t) tris[t] = {polygons[t][0], polygons[t][1], polygons[t][2]};
  return report;
}

} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_ORIENT_TRIANGLE_SOUP_H
