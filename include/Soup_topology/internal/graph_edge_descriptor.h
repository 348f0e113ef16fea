// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The edge descriptor and the edge index property map shared by the Boost.Graph views of the
// adjacency tables.

#ifndef SOUP_TOPOLOGY_INTERNAL_GRAPH_EDGE_DESCRIPTOR_H
#define SOUP_TOPOLOGY_INTERNAL_GRAPH_EDGE_DESCRIPTOR_H

#include <boost/property_map/property_map.hpp>

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>

namespace Soup_topology {
namespace internal {

// An undirected graph edge seen from one of its ends: `source` and `target` are the two graph
// vertices, `id` identifies the undirected edge (the same from both ends). Two descriptors compare
// equal when they name the same undirected edge, whatever the direction they were obtained in, as
// for the undirected `boost::adjacency_list`. `Tag` keeps the descriptors of different views apart.
template <class Tag>
struct Graph_edge
{
  using size_type = std::uint32_t;
  static constexpr std::size_t null_id = std::numeric_limits<std::size_t>::max();

  size_type source = std::numeric_limits<size_type>::max();
  size_type target = std::numeric_limits<size_type>::max();
  std::size_t id = null_id;

  Graph_edge() = default;
  Graph_edge(size_type s, size_type t, std::size_t i) : source(s), target(t), id(i) {}

  friend bool operator==(const Graph_edge& a, const Graph_edge& b) { return a.id == b.id; }
  friend bool operator!=(const Graph_edge& a, const Graph_edge& b) { return a.id != b.id; }
  friend bool operator<(const Graph_edge& a, const Graph_edge& b) { return a.id < b.id; }
  friend std::size_t hash_value(const Graph_edge& e) { return std::hash<std::size_t>()(e.id); }
};

// The readable property map edge descriptor -> edge index.
template <class Edge>
struct Graph_edge_index_map
{
  using key_type = Edge;
  using value_type = std::size_t;
  using reference = std::size_t;
  using category = boost::readable_property_map_tag;

  friend std::size_t get(const Graph_edge_index_map&, const Edge& e) { return e.id; }
};

} // namespace internal
} // namespace Soup_topology

namespace std {
template <class Tag>
struct hash<Soup_topology::internal::Graph_edge<Tag>>
{
  std::size_t operator()(const Soup_topology::internal::Graph_edge<Tag>& e) const
  { return std::hash<std::size_t>()(e.id); }
};
} // namespace std

#endif // SOUP_TOPOLOGY_INTERNAL_GRAPH_EDGE_DESCRIPTOR_H
