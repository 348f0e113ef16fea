// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The pairs of axis-aligned boxes of which one holds the other, found in time that grows with
// the pairs found rather than with the pairs of overlapping boxes.

#ifndef SOUP_TOPOLOGY_INTERNAL_BOXES_INSIDE_BOXES_H
#define SOUP_TOPOLOGY_INTERNAL_BOXES_INSIDE_BOXES_H

#include <algorithm>
#include <array>
#include <cstddef>
#include <numeric>
#include <vector>

namespace Soup_topology {
namespace internal {

/// a closed axis-aligned box: {lo x, lo y, lo z, hi x, hi y, hi z}.
using Box_bounds = std::array<double, 6>;

/// Calls `f(outer, inner)` for every ordered pair of distinct indices into `boxes` such that
/// `boxes[inner]` lies inside `boxes[outer]` (closed boxes: equal bounds count, so two equal boxes
/// give both pairs). The pairs come in no particular order.
///
/// Box b holds box c exactly when the point (c.lo, -c.hi) is at least (b.lo, -b.hi) on each of
/// the six coordinates (the negations are exact). The points of all the boxes go into a k-d tree
/// whose nodes know the least and the greatest coordinates below them; each box then asks for the
/// points in its orthant, and a node is left as soon as one of its greatest coordinates is below
/// the orthant's corner. Many boxes that overlap without holding each other (k closed parts
/// around one edge) cost no pair, where a search of overlapping boxes lists k^2 pairs; boxes
/// nested k deep give their k(k - 1)/2 pairs, which are the answer.
template <class F>
void for_each_box_inside_another(const std::vector<Box_bounds>& boxes, const F& f)
{
  using Key = std::array<double, 6>;
  const std::size_t m = boxes.size();
  std::vector<Key> key(m);
  for(std::size_t c = 0; c < m; ++c)
    for(std::size_t i = 0; i < 3; ++i) {
      key[c][i] = boxes[c][i];
      key[c][i + 3] = -boxes[c][i + 3];
    }
  struct Node
  {
    Key least, greatest;
    std::size_t begin, end;  // the points order[begin, end)
    std::size_t first_child; // the children are first_child and first_child + 1; 0 for a leaf
  };
  constexpr std::size_t leaf_size = 8;
  std::vector<std::size_t> order(m);
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::vector<Node> nodes;
  if(m == 0) return;
  nodes.push_back(Node{Key{}, Key{}, 0, m, 0});
  // Nodes are split at the median of one coordinate after the other, parents before children.
  for(std::size_t n = 0; n < nodes.size(); ++n) {
    const std::size_t begin = nodes[n].begin, end = nodes[n].end;
    Key least = key[order[begin]], greatest = least;
    for(std::size_t j = begin + 1; j < end; ++j)
      for(std::size_t i = 0; i < 6; ++i) {
        least[i] = std::min(least[i], key[order[j]][i]);
        greatest[i] = std::max(greatest[i], key[order[j]][i]);
      }
    nodes[n].least = least;
    nodes[n].greatest = greatest;
    if(end - begin <= leaf_size) continue;
    // the coordinate of widest spread: equal coordinates (boxes sharing a side) are not split on
    std::size_t axis = 0;
    for(std::size_t i = 1; i < 6; ++i)
      if(greatest[i] - least[i] > greatest[axis] - least[axis]) axis = i;
    if(!(greatest[axis] > least[axis])) continue; // all points equal: a leaf
    const std::size_t middle = begin + (end - begin) / 2;
    std::nth_element(order.begin() + std::ptrdiff_t(begin), order.begin() + std::ptrdiff_t(middle),
                     order.begin() + std::ptrdiff_t(end),
                     [&](std::size_t a, std::size_t b) { return key[a][axis] < key[b][axis]; });
    nodes[n].first_child = nodes.size();
    nodes.push_back(Node{Key{}, Key{}, begin, middle, 0});
    nodes.push_back(Node{Key{}, Key{}, middle, end, 0});
  }
  std::vector<std::size_t> pending;
  for(std::size_t outer = 0; outer < m; ++outer) {
    const Key& corner = key[outer];
    const auto at_least_corner = [&](const Key& x) {
      for(std::size_t i = 0; i < 6; ++i)
        if(x[i] < corner[i]) return false;
      return true;
    };
    pending.assign(1, 0);
    while(!pending.empty()) {
      const Node& nd = nodes[pending.back()];
      pending.pop_back();
      if(!at_least_corner(nd.greatest)) continue;         // no point of the node in the orthant
      const bool all_inside = at_least_corner(nd.least); // every point of the node in it
      if(all_inside || nd.first_child == 0) {
        for(std::size_t j = nd.begin; j < nd.end; ++j) {
          const std::size_t inner = order[j];
          if(inner != outer && (all_inside || at_least_corner(key[inner]))) f(outer, inner);
        }
        continue;
      }
      pending.push_back(nd.first_child);
      pending.push_back(nd.first_child + 1);
    }
  }
}

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_BOXES_INSIDE_BOXES_H
