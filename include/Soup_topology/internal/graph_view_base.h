// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// What the Boost.Graph views of the adjacency tables have in common, written once: the
// incidence and adjacency iterators over an edge walker, a base class whose friends are the
// free functions that do not depend on the view, and the `boost::graph_traits` and
// `boost::property_map` specialisations (`SOUP_TOPOLOGY_GRAPH_VIEW_TRAITS`).

#ifndef SOUP_TOPOLOGY_INTERNAL_GRAPH_VIEW_BASE_H
#define SOUP_TOPOLOGY_INTERNAL_GRAPH_VIEW_BASE_H

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/internal/graph_edge_descriptor.h>

#include <boost/graph/graph_traits.hpp>
#include <boost/graph/properties.hpp>
#include <boost/iterator/counting_iterator.hpp>
#include <boost/iterator/iterator_facade.hpp>
#include <boost/property_map/property_map.hpp>

#include <cstddef>
#include <utility>

// Called with the length of every list of triangles that the views scan to find the triangles
// of an edge shared by three or more triangles; the tests define it to bound that work.
#ifndef SOUP_TOPOLOGY_GRAPH_VIEW_SCAN
#define SOUP_TOPOLOGY_GRAPH_VIEW_SCAN(number_of_triangles)
#endif

namespace Soup_topology {
namespace internal {

// The two end vertices of edge `i` of triangle `t`, the one in fewer triangles first. The
// triangles of the edge are the triangles around the first that contain the second: scanning
// the shorter of the two lists finds them, in increasing order, whichever end is first.
inline std::pair<Adjacency_tables::size_type, Adjacency_tables::size_type>
edge_ends_fewer_triangles_first(const Adjacency_tables& tables, Adjacency_tables::size_type t, int i)
{
  const Adjacency_tables::size_type a = tables.vertex(t, i), b = tables.vertex(t, (i + 1) % 3);
  const bool b_first = tables.degree(b) < tables.degree(a);
  SOUP_TOPOLOGY_GRAPH_VIEW_SCAN(tables.degree(b_first ? b : a));
  if(b_first) return {b, a};
  return {a, b};
}

// The out-edges (in-edges when `Reversed`) of one graph vertex, read from a `Walker`: a class
// with a nested `Edge`, `edge()`, `increment()` and `operator==`.
template <class Walker, bool Reversed>
class Graph_incident_edge_iterator
  : public boost::iterator_facade<Graph_incident_edge_iterator<Walker, Reversed>, typename Walker::Edge,
                                  boost::forward_traversal_tag, typename Walker::Edge>
{
public:
  using Edge = typename Walker::Edge;
  Graph_incident_edge_iterator() = default;
  explicit Graph_incident_edge_iterator(const Walker& w) : w_(w) {}
private:
  friend class boost::iterator_core_access;
  Edge dereference() const
  {
    Edge e = w_.edge();
    if(Reversed) std::swap(e.source, e.target);
    return e;
  }
  void increment() { w_.increment(); }
  bool equal(const Graph_incident_edge_iterator& o) const { return w_ == o.w_; }
  Walker w_;
};

// The vertices adjacent to one graph vertex, read from a `Walker` (`adjacent_vertex()`).
template <class Walker>
class Graph_adjacency_iterator
  : public boost::iterator_facade<Graph_adjacency_iterator<Walker>, Adjacency_tables::size_type,
                                  boost::forward_traversal_tag, Adjacency_tables::size_type>
{
public:
  Graph_adjacency_iterator() = default;
  explicit Graph_adjacency_iterator(const Walker& w) : w_(w) {}
private:
  friend class boost::iterator_core_access;
  Adjacency_tables::size_type dereference() const { return w_.adjacent_vertex(); }
  void increment() { w_.increment(); }
  bool equal(const Graph_adjacency_iterator& o) const { return w_ == o.w_; }
  Walker w_;
};

// The base of a view `View` of `Adjacency_tables` whose graph vertices are the indices
// `[0, (tables.*number_of_graph_vertices)())` and whose incident edges are listed by `Walker`
// (`Walker::first(tables, v)` and `Walker::past_the_end(tables, v)` delimit those of `v`).
// Its friends, found by argument-dependent lookup on `View`, are the free functions of the
// Boost.Graph concepts that are the same for every view; `View` adds `out_degree()`, `edges()`,
// `num_edges()` and its `Edge_iterator`.
template <class View, class Walker, std::size_t (Adjacency_tables::*number_of_graph_vertices)() const>
class Graph_view_base
{
public:
  using size_type = Adjacency_tables::size_type;
  using Edge = typename Walker::Edge;
  using Edge_walker = Walker;
  using vertex_iterator = boost::counting_iterator<size_type>;
  template <bool Reversed>
  using Incident_edge_iterator = Graph_incident_edge_iterator<Walker, Reversed>;
  using Adjacency_iterator = Graph_adjacency_iterator<Walker>;

  explicit Graph_view_base(const Adjacency_tables& tables) : tables_(&tables) {}

  // the tables the view looks at.
  const Adjacency_tables& tables() const { return *tables_; }

  friend std::pair<vertex_iterator, vertex_iterator> vertices(const View& g)
  {
    const std::size_t n = (g.tables().*number_of_graph_vertices)();
    return {vertex_iterator(0), vertex_iterator(static_cast<size_type>(n))};
  }

  friend std::size_t num_vertices(const View& g) { return (g.tables().*number_of_graph_vertices)(); }

  friend std::pair<Incident_edge_iterator<false>, Incident_edge_iterator<false>>
  out_edges(size_type v, const View& g)
  {
    using It = Incident_edge_iterator<false>;
    return {It(Walker::first(g.tables(), v)), It(Walker::past_the_end(g.tables(), v))};
  }

  // the edges of `v` with `v` as their target.
  friend std::pair<Incident_edge_iterator<true>, Incident_edge_iterator<true>>
  in_edges(size_type v, const View& g)
  {
    using It = Incident_edge_iterator<true>;
    return {It(Walker::first(g.tables(), v)), It(Walker::past_the_end(g.tables(), v))};
  }

  friend std::pair<Adjacency_iterator, Adjacency_iterator> adjacent_vertices(size_type v, const View& g)
  {
    return {Adjacency_iterator(Walker::first(g.tables(), v)), Adjacency_iterator(Walker::past_the_end(g.tables(), v))};
  }

  friend std::size_t in_degree(size_type v, const View& g) { return out_degree(v, g); }

  // the number of incident edges (undirected graph: equal to `out_degree()`).
  friend std::size_t degree(size_type v, const View& g) { return out_degree(v, g); }

  friend size_type source(const Edge& e, const View&) { return e.source; }

  friend size_type target(const Edge& e, const View&) { return e.target; }

  friend boost::typed_identity_property_map<size_type> get(boost::vertex_index_t, const View&) { return {}; }

  friend size_type get(boost::vertex_index_t, const View&, size_type v) { return v; }

  friend Graph_edge_index_map<Edge> get(boost::edge_index_t, const View&) { return {}; }

  friend std::size_t get(boost::edge_index_t, const View&, const Edge& e) { return e.id; }

private:
  const Adjacency_tables* tables_;
};

// The members of `boost::graph_traits<View>` for a view derived from `Graph_view_base`; `View`
// names its `edge_parallel_category` and its `Edge_iterator`.
template <class View>
struct Graph_view_traits
{
  struct traversal_category
    : public virtual boost::bidirectional_graph_tag,
      public virtual boost::adjacency_graph_tag,
      public virtual boost::vertex_list_graph_tag,
      public virtual boost::edge_list_graph_tag
  {};
  using vertex_descriptor = typename View::size_type;
  using edge_descriptor = typename View::Edge;
  using directed_category = boost::undirected_tag;
  using edge_parallel_category = typename View::edge_parallel_category;

  using vertices_size_type = std::size_t;
  using edges_size_type = std::size_t;
  using degree_size_type = std::size_t;

  using vertex_iterator = typename View::vertex_iterator;
  using out_edge_iterator = typename View::template Incident_edge_iterator<false>;
  using in_edge_iterator = typename View::template Incident_edge_iterator<true>;
  using adjacency_iterator = typename View::Adjacency_iterator;
  using edge_iterator = typename View::Edge_iterator;

  static vertex_descriptor null_vertex() { return Adjacency_tables::border_edge; }
};

// `boost::property_map<View, boost::vertex_index_t>`: the identity.
template <class View>
struct Graph_view_vertex_index_property
{
  using type = boost::typed_identity_property_map<typename View::size_type>;
  using const_type = type;
};

// `boost::property_map<View, boost::edge_index_t>`: the `id` of the edge descriptor.
template <class View>
struct Graph_view_edge_index_property
{
  using type = Graph_edge_index_map<typename View::Edge>;
  using const_type = type;
};

} // namespace internal
} // namespace Soup_topology

// Specialises `boost::graph_traits` and `boost::property_map` (`vertex_index_t`, `edge_index_t`)
// for the view `VIEW` and `const VIEW`. Used at global scope, after the definition of `VIEW`.
#define SOUP_TOPOLOGY_GRAPH_VIEW_TRAITS(VIEW)                                                          \
  namespace boost {                                                                                     \
  template <>                                                                                           \
  struct graph_traits<VIEW> : public Soup_topology::internal::Graph_view_traits<VIEW> {};              \
  template <>                                                                                           \
  struct graph_traits<const VIEW> : public Soup_topology::internal::Graph_view_traits<VIEW> {};        \
  template <>                                                                                           \
  struct property_map<VIEW, vertex_index_t>                                                             \
    : public Soup_topology::internal::Graph_view_vertex_index_property<VIEW> {};                       \
  template <>                                                                                           \
  struct property_map<const VIEW, vertex_index_t>                                                       \
    : public Soup_topology::internal::Graph_view_vertex_index_property<VIEW> {};                       \
  template <>                                                                                           \
  struct property_map<VIEW, edge_index_t> : public Soup_topology::internal::Graph_view_edge_index_property<VIEW> {}; \
  template <>                                                                                           \
  struct property_map<const VIEW, edge_index_t>                                                         \
    : public Soup_topology::internal::Graph_view_edge_index_property<VIEW> {};                         \
  }

#endif // SOUP_TOPOLOGY_INTERNAL_GRAPH_VIEW_BASE_H
