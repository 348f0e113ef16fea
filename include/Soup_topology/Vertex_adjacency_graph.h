// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// A zero-copy Boost.Graph view of the vertices and edges (1-skeleton) of the adjacency tables.

#ifndef SOUP_TOPOLOGY_VERTEX_ADJACENCY_GRAPH_H
#define SOUP_TOPOLOGY_VERTEX_ADJACENCY_GRAPH_H

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/internal/graph_edge_descriptor.h>
#include <Soup_topology/internal/graph_view_base.h>

#include <boost/iterator/iterator_facade.hpp>

#include <cstddef>
#include <utility>

namespace Soup_topology {

namespace internal {

struct Vertex_adjacency_edge_tag {};

// `true` if edge i of t is the occurrence of its edge in the smallest triangle containing it.
inline bool is_canonical_edge(const Adjacency_tables& a, Adjacency_tables::size_type t, int i)
{
  const Adjacency_tables::size_type u = a.neighbor(t, i);
  if(u == Adjacency_tables::border_edge) return true;
  if(u != Adjacency_tables::non_manifold_edge) return t < u;
  const auto ends = edge_ends_fewer_triangles_first(a, t, i);
  for(Adjacency_tables::size_type w : a.triangles_around_vertex(ends.first)) {
    if(w >= t) break;
    if(a.local_index(w, ends.second) >= 0) return false;
  }
  return true;
}

// Walks the edges around vertex v of the vertex adjacency graph: for each triangle around v,
// its two edges incident to v, keeping the canonical ones.
class Vertex_edge_walker
{
public:
  using size_type = Adjacency_tables::size_type;
  using Edge = Graph_edge<Vertex_adjacency_edge_tag>;

  Vertex_edge_walker() = default;
  Vertex_edge_walker(const Adjacency_tables* tables, size_type v, bool at_end) : tables_(tables), v_(v)
  {
    const Adjacency_tables::Id_range around = tables->triangles_around_vertex(v);
    p_ = at_end ? around.end() : around.begin();
    pe_ = around.end();
    settle();
  }

  // The first and the past-the-end positions of the out-edges of `v`.
  static Vertex_edge_walker first(const Adjacency_tables& tables, size_type v)
  { return Vertex_edge_walker(&tables, v, false); }
  static Vertex_edge_walker past_the_end(const Adjacency_tables& tables, size_type v)
  { return Vertex_edge_walker(&tables, v, true); }

  size_type adjacent_vertex() const
  {
    const int iv = tables_->local_index(*p_, v_);
    return tables_->vertex(*p_, (iv + (k_ == 0 ? 1 : 2)) % 3);
  }
  Edge edge() const
  {
    const int iv = tables_->local_index(*p_, v_);
    const int h = k_ == 0 ? iv : (iv + 2) % 3;
    return Edge(v_, tables_->vertex(*p_, (iv + (k_ == 0 ? 1 : 2)) % 3), 3 * std::size_t(*p_) + std::size_t(h));
  }
  void increment() { advance(); settle(); }
  friend bool operator==(const Vertex_edge_walker& a, const Vertex_edge_walker& b)
  { return a.p_ == b.p_ && a.k_ == b.k_; }

private:
  void advance()
  {
    if(k_ == 0) k_ = 1;
    else { k_ = 0; ++p_; }
  }
  void settle()
  {
    while(p_ != pe_) {
      const int iv = tables_->local_index(*p_, v_);
      if(is_canonical_edge(*tables_, *p_, k_ == 0 ? iv : (iv + 2) % 3)) return;
      advance();
    }
  }

  const Adjacency_tables* tables_ = nullptr;
  size_type v_ = 0;
  const size_type* p_ = nullptr;
  const size_type* pe_ = nullptr;
  int k_ = 0;   // 0: edge (v, next vertex); 1: edge (previous vertex, v)
};

} // namespace internal

/// \ingroup PkgSoupTopologyGraphs
/// \brief the 1-skeleton of an `Adjacency_tables` (vertices and triangle edges), as a Boost.Graph
/// view that copies nothing: it holds a reference to the tables, which must outlive it.
///
/// - **Vertices** are the soup vertices, described by their index in `[0, number_of_vertices)`
///   (`vertex_index` is the identity). Isolated vertices (in no triangle) are vertices of degree 0.
/// - **Edges**: one undirected edge per distinct pair `{v, w}` of vertices of a common triangle,
///   however many triangles (one, two, or more for a non-manifold edge) contain it. No parallel
///   edges, no loops.
/// - **Edge index**: `3 t + i`, where `t` is the smallest triangle containing the edge and `i`
///   its local index there (numbering of `Adjacency_tables`). Indices are distinct and lie in
///   `[0, edge_index_upper_bound(g))` = `[0, 3 number_of_triangles)`: size edge property arrays
///   by that, not by `num_edges(g)`.
///
/// Models `VertexListGraph`, `IncidenceGraph`, `BidirectionalGraph` (in-edges are the out-edges
/// reversed), `AdjacencyGraph` and `EdgeListGraph`, with readable `vertex_index` and
/// `edge_index` property maps. The out-edges of `v` are found by walking the triangles around
/// `v` and keeping each edge only in the smallest triangle that contains it, so `out_edges()` and
/// `out_degree()` take time linear in the number of triangles around `v` (on manifold edges).
/// Deciding whether an edge shared by `k >= 3` triangles is kept scans the triangles around the
/// end of the edge that is in fewer triangles. `num_edges()` takes linear time. After a local
/// update of the tables, descriptors and iterators obtained before it are invalid.
///
/// `tables()` returns the tables the view looks at. Besides the functions listed below,
/// `vertices()`, `num_vertices()`, `out_edges()`, `in_edges()` (the out-edges reversed),
/// `adjacent_vertices()`, `in_degree()`, `degree()` (both equal to `out_degree()`), `source()`,
/// `target()` and `get()` of the `vertex_index` and `edge_index` maps are found by
/// argument-dependent lookup.
class Vertex_adjacency_graph
  : public internal::Graph_view_base<Vertex_adjacency_graph, internal::Vertex_edge_walker,
                                     &Adjacency_tables::number_of_vertices>
{
  using Base = internal::Graph_view_base<Vertex_adjacency_graph, internal::Vertex_edge_walker,
                                         &Adjacency_tables::number_of_vertices>;
public:
  /// \param tables the adjacency tables seen as a graph; they must outlive the view.
  explicit Vertex_adjacency_graph(const Adjacency_tables& tables) : Base(tables) {}

  /// \cond SKIP_IN_MANUAL
  using edge_parallel_category = boost::disallow_parallel_edge_tag;

  // Every edge once, at its canonical occurrence, by increasing 3 t + i.
  class Edge_iterator
    : public boost::iterator_facade<Edge_iterator, Edge, boost::forward_traversal_tag, Edge>
  {
  public:
    Edge_iterator() = default;
    Edge_iterator(const Adjacency_tables* tables, std::size_t h) : tables_(tables), h_(h) { settle(); }
  private:
    friend class boost::iterator_core_access;
    Edge dereference() const
    {
      const size_type t = static_cast<size_type>(h_ / 3);
      const int i = int(h_ % 3);
      return Edge(tables_->vertex(t, i), tables_->vertex(t, (i + 1) % 3), h_);
    }
    void increment() { ++h_; settle(); }
    bool equal(const Edge_iterator& o) const { return h_ == o.h_; }
    void settle()
    {
      const std::size_t end = 3 * tables_->number_of_triangles();
      while(h_ < end && !internal::is_canonical_edge(*tables_, static_cast<size_type>(h_ / 3), int(h_ % 3))) ++h_;
    }
    const Adjacency_tables* tables_ = nullptr;
    std::size_t h_ = 0;
  };
  /// \endcond
};

/// \relates Vertex_adjacency_graph
/// returns the vertex adjacency graph of `tables` (a view; `tables` must outlive it).
/// \param tables the adjacency tables seen as a graph
inline Vertex_adjacency_graph vertex_adjacency_graph(const Adjacency_tables& tables)
{ return Vertex_adjacency_graph(tables); }

} // namespace Soup_topology

SOUP_TOPOLOGY_GRAPH_VIEW_TRAITS(Soup_topology::Vertex_adjacency_graph)

namespace Soup_topology {

/// \name Free functions of `Vertex_adjacency_graph` (found by argument-dependent lookup)
/// @{

/// \relates Vertex_adjacency_graph
/// the number of distinct vertices sharing a triangle with `v`.
/// \param v a vertex (a vertex of the graph)
/// \param g the graph
inline std::size_t out_degree(Vertex_adjacency_graph::size_type v, const Vertex_adjacency_graph& g)
{
  const Adjacency_tables& a = g.tables();
  std::size_t d = 0;
  for(Adjacency_tables::size_type t : a.triangles_around_vertex(v)) {
    const int iv = a.local_index(t, v);
    if(internal::is_canonical_edge(a, t, iv)) ++d;
    if(internal::is_canonical_edge(a, t, (iv + 2) % 3)) ++d;
  }
  return d;
}

/// \relates Vertex_adjacency_graph
/// every edge once, oriented as in the smallest triangle that contains it.
/// \param g the graph
inline std::pair<Vertex_adjacency_graph::Edge_iterator, Vertex_adjacency_graph::Edge_iterator>
edges(const Vertex_adjacency_graph& g)
{
  using It = Vertex_adjacency_graph::Edge_iterator;
  return {It(&g.tables(), 0), It(&g.tables(), 3 * g.tables().number_of_triangles())};
}

/// \relates Vertex_adjacency_graph
/// the number of edges (linear time).
/// \param g the graph
inline std::size_t num_edges(const Vertex_adjacency_graph& g)
{
  const Adjacency_tables& a = g.tables();
  std::size_t count = 0;
  for(Adjacency_tables::size_type t = 0; t < a.number_of_triangles(); ++t)
    for(int i = 0; i < 3; ++i)
      if(internal::is_canonical_edge(a, t, i)) ++count;
  return count;
}

/// \relates Vertex_adjacency_graph
/// one past the largest edge index: `3 number_of_triangles`.
/// \param g the graph
inline std::size_t edge_index_upper_bound(const Vertex_adjacency_graph& g) { return 3 * g.tables().number_of_triangles(); }

/// \relates Vertex_adjacency_graph
/// the triangle and local edge index of the occurrence of `e` in the smallest triangle containing it.
/// \param e an edge of `g`
/// \param g the graph
inline Adjacency_tables::Edge halfedge_in_smaller_triangle(const Vertex_adjacency_graph::Edge& e,
                                                           const Vertex_adjacency_graph&)
{ return Adjacency_tables::Edge{static_cast<Adjacency_tables::size_type>(e.id / 3), int(e.id % 3)}; }

/// @}

} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_VERTEX_ADJACENCY_GRAPH_H
