// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Exact-duplicate detection for points: the representative of every point is the first point
// with exactly the same coordinates. Two implementations behind one function:
// - coordinates stored as `double` (Simple_cartesian<double>, Epick): an open-addressing hash
//   table keyed on the bit patterns (with -0.0 folded onto 0.0), expected linear time;
// - any other number type (Epeck, Gmpq): a sort by `Less_xyz_3`, then equal runs, in O(n log n),
//   because such numbers have no canonical bit pattern to hash.

#ifndef SOUP_TOPOLOGY_INTERNAL_POINT_HASH_MAP_H
#define SOUP_TOPOLOGY_INTERNAL_POINT_HASH_MAP_H

#include <CGAL/Kernel_traits.h>
#include <CGAL/number_utils.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <numeric>
#include <type_traits>
#include <vector>

namespace Soup_topology {
namespace internal {

inline std::uint64_t double_bits(double x)
{
  if(x == 0.0) x = 0.0; // fold -0.0 onto +0.0: they compare equal
  std::uint64_t u;
  std::memcpy(&u, &x, sizeof u);
  return u;
}

inline std::uint64_t mix_bits(std::uint64_t h)
{
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdULL;
  h ^= h >> 33;
  h *= 0xc4ceb9fe1a85ec53ULL;
  h ^= h >> 33;
  return h;
}

/// `first_of[i]` = the smallest index j with `point(j) == point(i)`, where `point(k)` returns
/// the k-th point (a kernel `Point_3`). `n` points.
template <class PointAccess>
std::vector<std::uint32_t> first_equal_points(std::size_t n, const PointAccess& point)
{
  using Point = std::decay_t<decltype(point(std::size_t(0)))>;
  using Kernel = typename CGAL::Kernel_traits<Point>::Kernel;
  using FT = typename Kernel::FT;
  std::vector<std::uint32_t> first_of(n);
  if(n == 0) return first_of;

  if constexpr(std::is_same<FT, double>::value) {
    std::size_t capacity = 16;
    while(capacity < 2 * n) capacity *= 2;
    const std::size_t mask = capacity - 1;
    constexpr std::uint32_t empty = static_cast<std::uint32_t>(-1);
    std::vector<std::uint32_t> slots(capacity, empty);
    for(std::size_t i = 0; i < n; ++i) {
      const Point& p = point(i);
      const double x = p.x(), y = p.y(), z = p.z();
      std::uint64_t h = mix_bits(double_bits(x) ^ mix_bits(double_bits(y) + 0x9e3779b97f4a7c15ULL) ^
                                 (mix_bits(double_bits(z)) << 1));
      std::size_t s = static_cast<std::size_t>(h) & mask;
      for(;;) {
        const std::uint32_t j = slots[s];
        if(j == empty) { slots[s] = static_cast<std::uint32_t>(i); first_of[i] = static_cast<std::uint32_t>(i); break; }
        const Point& q = point(j);
        if(q.x() == x && q.y() == y && q.z() == z) { first_of[i] = j; break; }
        s = (s + 1) & mask;
      }
    }
  } else {
    typename Kernel::Less_xyz_3 less;
    typename Kernel::Equal_3 equal;
    std::vector<std::uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return less(point(a), point(b)); });
    std::size_t run = 0;
    for(std::size_t k = 0; k < n; ++k) {
      if(k > 0 && !equal(point(order[k]), point(order[run]))) run = k;
      first_of[order[k]] = order[run]; // stable sort: order[run] is the smallest index of the run
    }
  }
  return first_of;
}

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_POINT_HASH_MAP_H
