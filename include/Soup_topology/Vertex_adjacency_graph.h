// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// A zero-copy Boost.Graph view of the vertices and edges (1-skeleton) of the adjacency tables.

#ifndef SOUP_TOPOLOGY_VERTEX_ADJACENCY_GRAPH_H
#define SOUP_TOPOLOGY_VERTEX_ADJACENCY_GRAPH_H

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/internal/graph_edge_descriptor.h>

#include <boost/graph/graph_traits.hpp>
#include <boost/graph/properties.hpp>
#include <boost/iterator/counting_iterator.hpp>
#include <boost/iterator/iterator_facade.hpp>
#include <boost/property_map/property_map.hpp>

#include <cstddef>
#include <utility>

namespace Soup_topology {

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
/// `num_edges()` takes linear time. After a local update of the tables, descriptors and
/// iterators obtained before it are invalid.
class Vertex_adjacency_graph
{
public:
  using size_type = Adjacency_tables::size_type;
  struct Edge_tag {};
  using Edge = internal::Graph_edge<Edge_tag>;

  explicit Vertex_adjacency_graph(const Adjacency_tables& tables) : tables_(&tables) {}

  /// the tables the view looks at.
  const Adjacency_tables& tables() const { return *tables_; }

  /// \cond SKIP_IN_MANUAL
  // `true` if edge i of t is the occurrence of its edge in the smallest triangle containing it.
  static bool is_canonical(const Adjacency_tables& a, size_type t, int i)
  {
    const size_type u = a.neighbor(t, i);
    if(u == Adjacency_tables::border_edge) return true;
    if(u != Adjacency_tables::non_manifold_edge) return t < u;
    const size_type b = a.vertex(t, (i + 1) % 3);
    for(size_type w : a.triangles_around_vertex(a.vertex(t, i))) {
      if(w >= t) break;
      if(a.local_index(w, b) >= 0) return false;
    }
    return true;
  }

  // Walks the edges around vertex v: for each triangle around v, its two edges incident to v,
  // keeping the canonical ones.
  class Edge_walker
  {
  public:
    Edge_walker() = default;
    Edge_walker(const Adjacency_tables* tables, size_type v, bool at_end) : tables_(tables), v_(v)
    {
      const Adjacency_tables::Id_range around = tables->triangles_around_vertex(v);
      p_ = at_end ? around.end() : around.begin();
      pe_ = around.end();
      settle();
    }

    size_type other() const
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
    friend bool operator==(const Edge_walker& a, const Edge_walker& b) { return a.p_ == b.p_ && a.k_ == b.k_; }

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
        if(is_canonical(*tables_, *p_, k_ == 0 ? iv : (iv + 2) % 3)) return;
        advance();
      }
    }

    const Adjacency_tables* tables_ = nullptr;
    size_type v_ = 0;
    const size_type* p_ = nullptr;
    const size_type* pe_ = nullptr;
    int k_ = 0;   // 0: edge (v, next vertex); 1: edge (previous vertex, v)
  };

  template <bool Reversed>
  class Incident_edge_iterator
    : public boost::iterator_facade<Incident_edge_iterator<Reversed>, Edge, boost::forward_traversal_tag, Edge>
  {
  public:
    Incident_edge_iterator() = default;
    explicit Incident_edge_iterator(const Edge_walker& w) : w_(w) {}
  private:
    friend class boost::iterator_core_access;
    Edge dereference() const
    {
      Edge e = w_.edge();
      if(Reversed) std::swap(e.source, e.target);
      return e;
    }
    void increment() { w_.increment(); }
    bool equal(const Incident_edge_iterator& o) const { return w_ == o.w_; }
    Edge_walker w_;
  };

  class Adjacency_iterator
    : public boost::iterator_facade<Adjacency_iterator, size_type, boost::forward_traversal_tag, size_type>
  {
  public:
    Adjacency_iterator() = default;
    explicit Adjacency_iterator(const Edge_walker& w) : w_(w) {}
  private:
    friend class boost::iterator_core_access;
    size_type dereference() const { return w_.other(); }
    void increment() { w_.increment(); }
    bool equal(const Adjacency_iterator& o) const { return w_ == o.w_; }
    Edge_walker w_;
  };

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
      while(h_ < end && !is_canonical(*tables_, static_cast<size_type>(h_ / 3), int(h_ % 3))) ++h_;
    }
    const Adjacency_tables* tables_ = nullptr;
    std::size_t h_ = 0;
  };
  /// \endcond

private:
  const Adjacency_tables* tables_;
};

/// \relates Vertex_adjacency_graph
/// returns the vertex adjacency graph of `tables` (a view; `tables` must outlive it).
inline Vertex_adjacency_graph vertex_adjacency_graph(const Adjacency_tables& tables)
{ return Vertex_adjacency_graph(tables); }

} // namespace Soup_topology

namespace boost {

template <>
struct graph_traits<Soup_topology::Vertex_adjacency_graph>
{
private:
  using G = Soup_topology::Vertex_adjacency_graph;
public:
  struct traversal_category
    : public virtual boost::bidirectional_graph_tag,
      public virtual boost::adjacency_graph_tag,
      public virtual boost::vertex_list_graph_tag,
      public virtual boost::edge_list_graph_tag
  {};
  using vertex_descriptor = G::size_type;
  using edge_descriptor = G::Edge;
  using directed_category = boost::undirected_tag;
  using edge_parallel_category = boost::disallow_parallel_edge_tag;

  using vertices_size_type = std::size_t;
  using edges_size_type = std::size_t;
  using degree_size_type = std::size_t;

  using vertex_iterator = boost::counting_iterator<G::size_type>;
  using out_edge_iterator = G::Incident_edge_iterator<false>;
  using in_edge_iterator = G::Incident_edge_iterator<true>;
  using adjacency_iterator = G::Adjacency_iterator;
  using edge_iterator = G::Edge_iterator;

  static vertex_descriptor null_vertex() { return Soup_topology::Adjacency_tables::border_edge; }
};

template <>
struct graph_traits<const Soup_topology::Vertex_adjacency_graph>
  : public graph_traits<Soup_topology::Vertex_adjacency_graph>
{};

template <>
struct property_map<Soup_topology::Vertex_adjacency_graph, boost::vertex_index_t>
{
  using type = boost::typed_identity_property_map<Soup_topology::Vertex_adjacency_graph::size_type>;
  using const_type = type;
};

template <>
struct property_map<Soup_topology::Vertex_adjacency_graph, boost::edge_index_t>
{
  using type = Soup_topology::internal::Graph_edge_index_map<Soup_topology::Vertex_adjacency_graph::Edge>;
  using const_type = type;
};

template <>
struct property_map<const Soup_topology::Vertex_adjacency_graph, boost::vertex_index_t>
  : public property_map<Soup_topology::Vertex_adjacency_graph, boost::vertex_index_t>
{};

template <>
struct property_map<const Soup_topology::Vertex_adjacency_graph, boost::edge_index_t>
  : public property_map<Soup_topology::Vertex_adjacency_graph, boost::edge_index_t>
{};

} // namespace boost

namespace Soup_topology {

/// \name Free functions of `Vertex_adjacency_graph` (found by argument-dependent lookup)
/// @{

/// \relates Vertex_adjacency_graph
inline std::pair<boost::graph_traits<Vertex_adjacency_graph>::vertex_iterator,
                 boost::graph_traits<Vertex_adjacency_graph>::vertex_iterator>
vertices(const Vertex_adjacency_graph& g)
{
  using It = boost::graph_traits<Vertex_adjacency_graph>::vertex_iterator;
  return {It(0), It(static_cast<Vertex_adjacency_graph::size_type>(g.tables().number_of_vertices()))};
}

/// \relates Vertex_adjacency_graph
inline std::size_t num_vertices(const Vertex_adjacency_graph& g) { return g.tables().number_of_vertices(); }

/// \relates Vertex_adjacency_graph
inline std::pair<Vertex_adjacency_graph::Incident_edge_iterator<false>,
                 Vertex_adjacency_graph::Incident_edge_iterator<false>>
out_edges(Vertex_adjacency_graph::size_type v, const Vertex_adjacency_graph& g)
{
  using It = Vertex_adjacency_graph::Incident_edge_iterator<false>;
  using W = Vertex_adjacency_graph::Edge_walker;
  return {It(W(&g.tables(), v, false)), It(W(&g.tables(), v, true))};
}

/// \relates Vertex_adjacency_graph
/// the edges of `v` with `v` as their target.
inline std::pair<Vertex_adjacency_graph::Incident_edge_iterator<true>,
                 Vertex_adjacency_graph::Incident_edge_iterator<true>>
in_edges(Vertex_adjacency_graph::size_type v, const Vertex_adjacency_graph& g)
{
  using It = Vertex_adjacency_graph::Incident_edge_iterator<true>;
  using W = Vertex_adjacency_graph::Edge_walker;
  return {It(W(&g.tables(), v, false)), It(W(&g.tables(), v, true))};
}

/// \relates Vertex_adjacency_graph
inline std::pair<Vertex_adjacency_graph::Adjacency_iterator, Vertex_adjacency_graph::Adjacency_iterator>
adjacent_vertices(Vertex_adjacency_graph::size_type v, const Vertex_adjacency_graph& g)
{
  using It = Vertex_adjacency_graph::Adjacency_iterator;
  using W = Vertex_adjacency_graph::Edge_walker;
  return {It(W(&g.tables(), v, false)), It(W(&g.tables(), v, true))};
}

/// \relates Vertex_adjacency_graph
/// the number of distinct vertices sharing a triangle with `v`.
inline std::size_t out_degree(Vertex_adjacency_graph::size_type v, const Vertex_adjacency_graph& g)
{
  const Adjacency_tables& a = g.tables();
  std::size_t d = 0;
  for(Adjacency_tables::size_type t : a.triangles_around_vertex(v)) {
    const int iv = a.local_index(t, v);
    if(Vertex_adjacency_graph::is_canonical(a, t, iv)) ++d;
    if(Vertex_adjacency_graph::is_canonical(a, t, (iv + 2) % 3)) ++d;
  }
  return d;
}

/// \relates Vertex_adjacency_graph
inline std::size_t in_degree(Vertex_adjacency_graph::size_type v, const Vertex_adjacency_graph& g)
{ return out_degree(v, g); }

/// \relates Vertex_adjacency_graph
/// the number of incident edges (undirected graph: equal to `out_degree()`).
inline std::size_t degree(Vertex_adjacency_graph::size_type v, const Vertex_adjacency_graph& g)
{ return out_degree(v, g); }

/// \relates Vertex_adjacency_graph
inline Vertex_adjacency_graph::size_type source(const Vertex_adjacency_graph::Edge& e, const Vertex_adjacency_graph&)
{ return e.source; }

/// \relates Vertex_adjacency_graph
inline Vertex_adjacency_graph::size_type target(const Vertex_adjacency_graph::Edge& e, const Vertex_adjacency_graph&)
{ return e.target; }

/// \relates Vertex_adjacency_graph
/// every edge once, oriented as in the smallest triangle that contains it.
inline std::pair<Vertex_adjacency_graph::Edge_iterator, Vertex_adjacency_graph::Edge_iterator>
edges(const Vertex_adjacency_graph& g)
{
  using It = Vertex_adjacency_graph::Edge_iterator;
  return {It(&g.tables(), 0), It(&g.tables(), 3 * g.tables().number_of_triangles())};
}

/// \relates Vertex_adjacency_graph
/// the number of edges (linear time).
inline std::size_t num_edges(const Vertex_adjacency_graph& g)
{
  const Adjacency_tables& a = g.tables();
  std::size_t count = 0;
  for(Adjacency_tables::size_type t = 0; t < a.number_of_triangles(); ++t)
    for(int i = 0; i < 3; ++i)
      if(Vertex_adjacency_graph::is_canonical(a, t, i)) ++count;
  return count;
}

/// \relates Vertex_adjacency_graph
/// one past the largest edge index: `3 number_of_triangles`.
inline std::size_t edge_index_upper_bound(const Vertex_adjacency_graph& g) { return 3 * g.tables().number_of_triangles(); }

/// \relates Vertex_adjacency_graph
/// the triangle and local edge index of the occurrence of `e` in the smallest triangle containing it.
inline Adjacency_tables::Edge halfedge_in_smaller_triangle(const Vertex_adjacency_graph::Edge& e,
                                                           const Vertex_adjacency_graph&)
{ return Adjacency_tables::Edge{static_cast<Adjacency_tables::size_type>(e.id / 3), int(e.id % 3)}; }

/// \relates Vertex_adjacency_graph
inline boost::typed_identity_property_map<Vertex_adjacency_graph::size_type>
get(boost::vertex_index_t, const Vertex_adjacency_graph&)
{ return {}; }

/// \relates Vertex_adjacency_graph
inline Vertex_adjacency_graph::size_type get(boost::vertex_index_t, const Vertex_adjacency_graph&,
                                             Vertex_adjacency_graph::size_type v)
{ return v; }

/// \relates Vertex_adjacency_graph
inline internal::Graph_edge_index_map<Vertex_adjacency_graph::Edge>
get(boost::edge_index_t, const Vertex_adjacency_graph&)
{ return {}; }

/// \relates Vertex_adjacency_graph
inline std::size_t get(boost::edge_index_t, const Vertex_adjacency_graph&, const Vertex_adjacency_graph::Edge& e)
{ return e.id; }

/// @}

} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_VERTEX_ADJACENCY_GRAPH_H
