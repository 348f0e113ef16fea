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

#include <Soup_topology/internal/uninitialized_vector.h>

#include <CGAL/Kernel_traits.h>
#include <CGAL/number_utils.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
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

/// `true` if the three coordinates of `p` are finite (always for exact number types, which hold
/// neither NaN nor infinity).
template <class Point>
bool is_finite_point(const Point& p)
{
  using FT = typename CGAL::Kernel_traits<Point>::Kernel::FT;
  if constexpr(std::is_floating_point<FT>::value)
    return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z());
  else
    return true;
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

/// the hash of the exact weld: equal coordinates (-0.0 and 0.0 included) give equal hashes.
inline std::uint64_t hash_of_coordinates(double x, double y, double z)
{
  return mix_bits(double_bits(x) ^ mix_bits(double_bits(y) + 0x9e3779b97f4a7c15ULL) ^ (mix_bits(double_bits(z)) << 1));
}

/// An open-addressing table of positions of points, keyed by 32 bits of their hash, for
/// `first_equal_points()` and the passes of `first_equal_points_by_blocks()`: each slot holds a
/// position and its fingerprint, so that most probes that meet another point are rejected
/// without reading that point's coordinates (a cache miss each). `find_or_insert(position,
/// fingerprint, equal)` returns the position of the first point inserted with an equal
/// fingerprint for which `equal(that position)` holds, or inserts `position` and returns it. It
/// grows 4 times at half load, from the fingerprints alone.
class Fingerprint_table
{
public:
  explicit Fingerprint_table(std::size_t expected)
  {
    while(capacity_ < expected) capacity_ *= 2;
    slots_.assign(capacity_, Slot{empty, 0});
  }

  template <class Equal>
  std::uint32_t find_or_insert(std::uint32_t position, std::uint32_t fingerprint, const Equal& equal)
  {
    std::size_t s = fingerprint & (capacity_ - 1);
    for(;;) {
      const Slot slot = slots_[s];
      if(slot.position == empty) {
        slots_[s] = Slot{position, fingerprint};
        if(2 * ++size_ > capacity_) grow();
        return position;
      }
      if(slot.fingerprint == fingerprint && equal(slot.position)) return slot.position;
      s = (s + 1) & (capacity_ - 1);
    }
  }

private:
  static constexpr std::uint32_t empty = static_cast<std::uint32_t>(-1);
  struct Slot { std::uint32_t position, fingerprint; };

  void grow()
  {
    std::vector<Slot> old(capacity_ * 4, Slot{empty, 0});
    old.swap(slots_);
    capacity_ *= 4;
    for(const Slot& o : old) {
      if(o.position == empty) continue;
      std::size_t s = o.fingerprint & (capacity_ - 1);
      while(slots_[s].position != empty) s = (s + 1) & (capacity_ - 1);
      slots_[s] = o;
    }
  }

  std::size_t capacity_ = 16, size_ = 0;
  std::vector<Slot> slots_;
};

/// `first_of[i]` = the smallest index j with `point(j) == point(i)`, where `point(k)` returns
/// the k-th point (a kernel `Point_3`). `n` points.
template <class PointAccess>
Uninitialized_vector<std::uint32_t> first_equal_points(std::size_t n, const PointAccess& point)
{
  using Point = std::decay_t<decltype(point(std::size_t(0)))>;
  using Kernel = typename CGAL::Kernel_traits<Point>::Kernel;
  using FT = typename Kernel::FT;
  Uninitialized_vector<std::uint32_t> first_of(n); // every entry written below
  if(n == 0) return first_of;

  if constexpr(std::is_same<FT, double>::value) {
    // The table is sized for the distinct points, which soups have far fewer of than corners (an
    // STL soup has about one distinct point in six corners), and grows at half load: a small
    // table stays in cache (benchmark/index_triangles_benchmark.cpp measures it).
    Fingerprint_table table(n / 2);
    for(std::size_t i = 0; i < n; ++i) {
      const Point& p = point(i);
      const double x = p.x(), y = p.y(), z = p.z();
      first_of[i] = table.find_or_insert(static_cast<std::uint32_t>(i),
                                         static_cast<std::uint32_t>(hash_of_coordinates(x, y, z) >> 32),
                                         [&](std::uint32_t j) {
                                           const Point& q = point(j);
                                           return q.x() == x && q.y() == y && q.z() == z;
                                         });
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
