// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Splitting the triangles around each vertex of an indexed soup into fans, so that a vertex whose
// triangles do not form one fan can be duplicated once per fan.

#ifndef SOUP_TOPOLOGY_INTERNAL_SEPARATE_NON_MANIFOLD_H
#define SOUP_TOPOLOGY_INTERNAL_SEPARATE_NON_MANIFOLD_H

#include <Soup_topology/Adjacency_tables.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace Soup_topology {
namespace internal {

/// The fans around vertex `v`: the triangles of `v` grouped by the edges incident to `v` that are
/// manifold and not cut (`cut[3 t + i]` non-zero cuts edge `i` of `t`). Writes to `fan[k]` the
/// fan of the `k`-th triangle of `tables.triangles_around_vertex(v)`, numbered from 0 in the
/// order of their first triangle; returns the number of fans. Linear in the degree of `v`
/// (a neighbour is found in the sorted triangle list by bisection).
inline std::size_t fans_around_vertex(const Adjacency_tables& tables, const std::vector<char>& cut,
                                      Adjacency_tables::size_type v, std::vector<std::size_t>& fan,
                                      std::vector<std::size_t>& stack)
{
  using size_type = Adjacency_tables::size_type;
  const Adjacency_tables::Id_range around = tables.triangles_around_vertex(v);
  const std::size_t unset = static_cast<std::size_t>(-1);
  fan.assign(around.size(), unset);
  std::size_t count = 0;
  for(std::size_t k = 0; k < around.size(); ++k) {
    if(fan[k] != unset) continue;
    fan[k] = count;
    stack.assign(1, k);
    while(!stack.empty()) {
      const size_type t = around[stack.back()];
      stack.pop_back();
      const int iv = tables.local_index(t, v);
      for(int e : {iv, (iv + 2) % 3}) {
        const size_type u = tables.neighbor(t, e);
        if(u >= Adjacency_tables::non_manifold_edge || cut[3 * std::size_t(t) + std::size_t(e)]) continue;
        const std::size_t ku = static_cast<std::size_t>(std::lower_bound(around.begin(), around.end(), u) - around.begin());
        if(fan[ku] == unset) { fan[ku] = count; stack.push_back(ku); }
      }
    }
    ++count;
  }
  return count;
}

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_SEPARATE_NON_MANIFOLD_H
