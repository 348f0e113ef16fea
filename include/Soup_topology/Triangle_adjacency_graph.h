// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// A zero-copy Boost.Graph view of the triangle adjacency (dual graph) of the adjacency tables.

#ifndef SOUP_TOPOLOGY_TRIANGLE_ADJACENCY_GRAPH_H
#define SOUP_TOPOLOGY_TRIANGLE_ADJACENCY_GRAPH_H

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/internal/graph_edge_descriptor.h>
#include <Soup_topology/internal/graph_view_base.h>

#include <boost/iterator/iterator_facade.hpp>

#include <algorithm>
#include <cstddef>
#include <iterator>
#include <utility>
#include <vector>

namespace Soup_topology {

namespace internal {

struct Triangle_adjacency_edge_tag {};

// Walks the graph edges of one triangle `t` of the triangle adjacency graph: the partners of its
// three edges, in the order (local edge, partner triangle). With `only_larger` only partners
// larger than `t` are listed (each undirected edge once, from its smaller triangle).
class Triangle_edge_walker
{
public:
  using size_type = Adjacency_tables::size_type;
  using Edge = Graph_edge<Triangle_adjacency_edge_tag>;

  Triangle_edge_walker() = default;
  // The end position, for any triangle.
  explicit Triangle_edge_walker(size_type t) : t_(t), i_(3) {}
  Triangle_edge_walker(const Adjacency_tables* tables, size_type t, bool only_larger)
    : tables_(tables), t_(t), i_(0), only_larger_(only_larger)
  { settle(); }

  // The first and the past-the-end positions of the out-edges of `t`.
  static Triangle_edge_walker first(const Adjacency_tables& tables, size_type t)
  { return Triangle_edge_walker(&tables, t, false); }
  static Triangle_edge_walker past_the_end(const Adjacency_tables&, size_type t)
  { return Triangle_edge_walker(t); }

  bool at_end() const { return i_ == 3; }
  size_type triangle() const { return t_; }
  size_type adjacent_vertex() const { return p_ != nullptr ? *p_ : tables_->neighbor(t_, i_); }

  Edge edge() const
  {
    const size_type u = adjacent_vertex();
    const std::size_t n = tables_->number_of_triangles();
    if(p_ == nullptr) {   // manifold
      if(t_ < u) return Edge(t_, u, 3 * std::size_t(t_) + std::size_t(i_));
      const int j = tables_->edge_index(u, tables_->vertex(t_, i_), tables_->vertex(t_, (i_ + 1) % 3));
      return Edge(t_, u, 3 * std::size_t(u) + std::size_t(j));
    }
    if(t_ < u)
      return Edge(t_, u, 3 * std::size_t(t_) + std::size_t(i_) + 3 * n * std::size_t(rank_ - rank_t_ - 1));
    const int j = tables_->edge_index(u, tables_->vertex(t_, i_), tables_->vertex(t_, (i_ + 1) % 3));
    return Edge(t_, u, 3 * std::size_t(u) + std::size_t(j) + 3 * n * std::size_t(rank_t_ - rank_ - 1));
  }

  void increment()
  {
    if(p_ != nullptr) { ++rank_; ++p_; }
    else ++i_;
    settle();
  }

  friend bool operator==(const Triangle_edge_walker& a, const Triangle_edge_walker& b)
  { return a.t_ == b.t_ && a.i_ == b.i_ && a.p_ == b.p_; }

private:
  // Moves to the first valid position at or after the current one.
  void settle()
  {
    while(i_ < 3) {
      if(p_ == nullptr) {
        const size_type u = tables_->neighbor(t_, i_);
        if(u == Adjacency_tables::border_edge) { ++i_; continue; }
        if(u != Adjacency_tables::non_manifold_edge) {
          if(!only_larger_ || u > t_) return;
          ++i_;
          continue;
        }
        // A non-manifold edge: walk the triangles of one end that contain the other end.
        const auto ends = edge_ends_fewer_triangles_first(*tables_, t_, i_);
        const Adjacency_tables::Id_range around = tables_->triangles_around_vertex(ends.first);
        p_ = around.begin();
        pe_ = around.end();
        b_ = ends.second;
        rank_ = 0;
        rank_t_ = 0;
        for(const size_type* q = p_; *q != t_; ++q)
          if(tables_->local_index(*q, b_) >= 0) ++rank_t_;
      }
      for(; p_ != pe_; ++p_) {
        const size_type u = *p_;
        if(tables_->local_index(u, b_) < 0) continue;
        if(u != t_ && (!only_larger_ || u > t_)) return;
        ++rank_;
      }
      p_ = pe_ = nullptr;
      ++i_;
    }
  }

  const Adjacency_tables* tables_ = nullptr;
  size_type t_ = 0;
  int i_ = 3;
  bool only_larger_ = false;
  const size_type* p_ = nullptr;   // non-null while walking the triangles of a non-manifold edge
  const size_type* pe_ = nullptr;
  size_type b_ = 0;                // the end of that edge not walked around
  size_type rank_ = 0;             // rank of *p_ among the triangles of that edge
  size_type rank_t_ = 0;           // rank of t_ among them
};

} // namespace internal

/// \ingroup PkgSoupTopologyGraphs
/// \brief the triangle adjacency (dual) graph of an `Adjacency_tables`, as a Boost.Graph view
/// that copies nothing: it holds a reference to the tables, which must outlive it.
///
/// - **Vertices** are the triangles, described by their index `t` in `[0, number_of_triangles)`
///   (`vertex_index` is the identity).
/// - **Edges**: two triangles are adjacent when they share an edge. A manifold edge (exactly two
///   triangles) is one graph edge. A **non-manifold edge** shared by `k >= 3` triangles is a
///   clique: one graph edge between every pair of its triangles (`k (k-1) / 2` graph edges), so
///   that adjacency means "shares an edge" and the components are those of
///   `Adjacency_tables::number_of_connected_components()`. A border edge is not a graph edge.
///   Use `is_manifold_edge()` (e.g. with `boost::filtered_graph`) to walk manifold edges only.
/// - The graph is undirected. Two triangles with the same three vertices share three edges and
///   are joined by three parallel graph edges.
/// - **Edge index.** An edge between triangles `a < b` across edge `i` of `a` (local numbering of
///   `Adjacency_tables`) has index `3 a + i` when the edge is manifold. For a non-manifold edge
///   whose triangles, in increasing order, have ranks `r_a < r_b`, the index is
///   `3 a + i + 3 n (r_b - r_a - 1)` with `n` the number of triangles. Indices are distinct and
///   lie in `[0, edge_index_upper_bound(g))`, which is `3 n` when no edge is shared by more than
///   two triangles: size edge property arrays by `edge_index_upper_bound(g)`, not `num_edges(g)`.
///
/// Models `VertexListGraph`, `IncidenceGraph`, `BidirectionalGraph` (in-edges are the out-edges
/// reversed), `AdjacencyGraph` and `EdgeListGraph`, with readable `vertex_index` and
/// `edge_index` property maps. `out_edges()`, `out_degree()` and `adjacent_vertices()` take
/// constant time per triangle on manifold edges; `num_edges()` and `edge_index_upper_bound()`
/// take linear time. On an edge shared by `k >= 3` triangles they scan the triangles around the
/// end of the edge that is in fewer triangles. The view reflects the current state of the
/// tables: after a local update (`Adjacency_tables::replace_vertex()`, `split_triangle()`)
/// descriptors and iterators obtained before it are invalid.
///
/// `tables()` returns the tables the view looks at. Besides the functions listed below,
/// `vertices()`, `num_vertices()`, `out_edges()`, `in_edges()` (the out-edges reversed),
/// `adjacent_vertices()`, `in_degree()`, `degree()` (both equal to `out_degree()`), `source()`,
/// `target()` and `get()` of the `vertex_index` and `edge_index` maps are found by
/// argument-dependent lookup.
class Triangle_adjacency_graph
  : public internal::Graph_view_base<Triangle_adjacency_graph, internal::Triangle_edge_walker,
                                     &Adjacency_tables::number_of_triangles>
{
  using Base = internal::Graph_view_base<Triangle_adjacency_graph, internal::Triangle_edge_walker,
                                         &Adjacency_tables::number_of_triangles>;
public:
  /// \param tables the adjacency tables seen as a graph; they must outlive the view.
  explicit Triangle_adjacency_graph(const Adjacency_tables& tables) : Base(tables) {}

  /// \cond SKIP_IN_MANUAL
  using edge_parallel_category = boost::allow_parallel_edge_tag;

  // Every undirected edge once, from its smaller triangle, by increasing triangle.
  class Edge_iterator
    : public boost::iterator_facade<Edge_iterator, Edge, boost::forward_traversal_tag, Edge>
  {
  public:
    Edge_iterator() = default;
    Edge_iterator(const Adjacency_tables* tables, size_type t) : tables_(tables), w_(t)
    {
      if(t < tables_->number_of_triangles()) {
        w_ = Edge_walker(tables_, t, true);
        skip_empty();
      }
    }
  private:
    friend class boost::iterator_core_access;
    Edge dereference() const { return w_.edge(); }
    void increment() { w_.increment(); skip_empty(); }
    bool equal(const Edge_iterator& o) const { return w_ == o.w_; }
    void skip_empty()
    {
      const std::size_t n = tables_->number_of_triangles();
      while(w_.at_end() && std::size_t(w_.triangle()) + 1 < n)
        w_ = Edge_walker(tables_, w_.triangle() + 1, true);
      if(w_.at_end()) w_ = Edge_walker(static_cast<size_type>(n));
    }
    const Adjacency_tables* tables_ = nullptr;
    Edge_walker w_;
  };
  /// \endcond
};

/// \relates Triangle_adjacency_graph
/// returns the triangle adjacency graph of `tables` (a view; `tables` must outlive it).
/// \param tables the adjacency tables seen as a graph
inline Triangle_adjacency_graph triangle_adjacency_graph(const Adjacency_tables& tables)
{ return Triangle_adjacency_graph(tables); }

} // namespace Soup_topology

SOUP_TOPOLOGY_GRAPH_VIEW_TRAITS(Soup_topology::Triangle_adjacency_graph)

namespace Soup_topology {

/// \name Free functions of `Triangle_adjacency_graph` (found by argument-dependent lookup)
/// @{

/// \relates Triangle_adjacency_graph
/// the number of graph edges of `t`: one per manifold edge, `k - 1` per edge shared by `k >= 3`
/// triangles, none per border edge.
/// \param t a triangle (a vertex of the graph)
/// \param g the graph
inline std::size_t out_degree(Triangle_adjacency_graph::size_type t, const Triangle_adjacency_graph& g)
{
  const Adjacency_tables& a = g.tables();
  std::size_t d = 0;
  for(int i = 0; i < 3; ++i) {
    const Adjacency_tables::size_type u = a.neighbor(t, i);
    if(u == Adjacency_tables::border_edge) continue;
    if(u != Adjacency_tables::non_manifold_edge) { ++d; continue; }
    const auto ends = internal::edge_ends_fewer_triangles_first(a, t, i);
    for(Adjacency_tables::size_type w : a.triangles_around_vertex(ends.first))
      if(w != t && a.local_index(w, ends.second) >= 0) ++d;
  }
  return d;
}

/// \relates Triangle_adjacency_graph
/// every undirected edge once, oriented from its smaller triangle to its larger one.
/// \param g the graph
inline std::pair<Triangle_adjacency_graph::Edge_iterator, Triangle_adjacency_graph::Edge_iterator>
edges(const Triangle_adjacency_graph& g)
{
  using It = Triangle_adjacency_graph::Edge_iterator;
  const auto n = static_cast<Triangle_adjacency_graph::size_type>(g.tables().number_of_triangles());
  return {It(&g.tables(), 0), It(&g.tables(), n)};
}

/// \relates Triangle_adjacency_graph
/// the number of graph edges (linear time).
/// \param g the graph
inline std::size_t num_edges(const Triangle_adjacency_graph& g)
{
  const Adjacency_tables& a = g.tables();
  std::size_t count = 0;
  for(Adjacency_tables::size_type t = 0; t < a.number_of_triangles(); ++t)
    for(int i = 0; i < 3; ++i) {
      const Adjacency_tables::size_type u = a.neighbor(t, i);
      if(u == Adjacency_tables::border_edge) continue;
      if(u != Adjacency_tables::non_manifold_edge) { count += (u > t) ? 1 : 0; continue; }
      // Counted once, from the smallest triangle of the edge: k (k-1) / 2 graph edges.
      const auto ends = internal::edge_ends_fewer_triangles_first(a, t, i);
      std::size_t k = 0;
      bool smallest = true;
      for(Adjacency_tables::size_type w : a.triangles_around_vertex(ends.first))
        if(a.local_index(w, ends.second) >= 0) { if(w < t) { smallest = false; break; } ++k; }
      if(smallest) count += k * (k - 1) / 2;
    }
  return count;
}

/// \relates Triangle_adjacency_graph
/// one past the largest edge index: `3 n max(1, k - 1)` with `n` triangles and `k` the largest
/// number of triangles sharing one edge (`3 n` for a manifold soup). Linear time.
/// \param g the graph
inline std::size_t edge_index_upper_bound(const Triangle_adjacency_graph& g)
{
  const Adjacency_tables& a = g.tables();
  std::size_t layers = 1;
  std::vector<Adjacency_tables::size_type> fan;
  for(const Adjacency_tables::Edge& e : a.non_manifold_edges()) {
    fan.clear();
    a.triangles_around_edge(e.triangle, e.index, std::back_inserter(fan));
    layers = (std::max)(layers, fan.size());   // k - 1 with k = fan.size() + 1
  }
  return 3 * a.number_of_triangles() * layers;
}

/// \relates Triangle_adjacency_graph
/// `true` if `e` crosses an edge shared by exactly two triangles.
/// \param e an edge of `g`
/// \param g the graph
inline bool is_manifold_edge(const Triangle_adjacency_graph::Edge& e, const Triangle_adjacency_graph& g)
{
  const Adjacency_tables& a = g.tables();
  const std::size_t h = e.id % (3 * a.number_of_triangles());
  return a.neighbor(static_cast<Adjacency_tables::size_type>(h / 3), int(h % 3)) < Adjacency_tables::non_manifold_edge;
}

/// \relates Triangle_adjacency_graph
/// the triangle index and the local edge index (in the numbering of `Adjacency_tables`) of edge
/// `e` in its smaller triangle.
/// \param e an edge of `g`
/// \param g the graph
inline Adjacency_tables::Edge halfedge_in_smaller_triangle(const Triangle_adjacency_graph::Edge& e,
                                                           const Triangle_adjacency_graph& g)
{
  const std::size_t h = e.id % (3 * g.tables().number_of_triangles());
  return Adjacency_tables::Edge{static_cast<Adjacency_tables::size_type>(h / 3), int(h % 3)};
}

/// @}

} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_TRIANGLE_ADJACENCY_GRAPH_H
