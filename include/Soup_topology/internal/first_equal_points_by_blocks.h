// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The exact weld of many points with `double` coordinates, by blocks: the same result as
// `first_equal_points()` (the first point of every class of equal points), computed with small
// hash tables that stay in cache, on TBB's threads when the concurrency tag asks for it.
//
// A soup keeps the copies of a point close together: an STL file, an exploded mesh or a scan
// lists a triangle's neighbours near it, so that most of the six or so copies of a corner fall in
// the same block of 16,384 points. The weld has three passes:
// 1. every block is welded alone: the first point of each class inside the block, its block
//    representative, is found with a table of the block's size; the other points of the block
//    name it. The representatives are counted by block and by partition (the top 8 bits of their
//    hash: equal points share a partition).
// 2. the representatives' coordinates and indices are copied out, partition by partition, each in
//    increasing index order (the counts' prefix sums, partition-major, give every block its
//    place); every partition is welded by a table of its own, reading the copies one after the
//    other. The first representative of a class is its smallest index over the whole range.
// 3. every point takes the class's first point from its block representative (a caller that reads
//    the entries in increasing order can follow the two links itself: `Exact_weld_extras`).
// The single table of `first_equal_points()` misses the cache on nearly every point of a large
// soup (a probe, and the coordinates of the point it finds); here only the copy of the
// representatives does, and it writes in 256 streams. The copies take 32 bytes a representative;
// when the representatives are more than a quarter of the points (a shuffled soup), they are
// copied and welded by rounds of consecutive partitions, so that the copies never take more than
// 8 bytes a point. The partition of each representative is kept from step 1 (one byte a point):
// a round reads and hashes only the points of its own partitions, and every point is read once
// in step 2, however many rounds there are.

#ifndef SOUP_TOPOLOGY_INTERNAL_FIRST_EQUAL_POINTS_BY_BLOCKS_H
#define SOUP_TOPOLOGY_INTERNAL_FIRST_EQUAL_POINTS_BY_BLOCKS_H

#include <Soup_topology/internal/Point_hash_map.h>
#include <Soup_topology/internal/parallel.h>
#include <Soup_topology/internal/uninitialized_vector.h>

#include <CGAL/Kernel_traits.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace Soup_topology {
namespace internal {

/// What `first_equal_points_by_blocks()` also finds when asked, read by passes that read every
/// point and every entry anyway.
struct Exact_weld_extras
{
  /// the number of first points (`first_of[i] == i`) in every block of `default_block_size` points
  std::vector<std::size_t> firsts_by_block;
  /// `true` if every coordinate is finite (`is_finite_point()`); `false` if the weld stopped at a
  /// NaN or an infinite coordinate (a NaN equals nothing, not even itself)
  bool all_finite = true;
  /// set by the caller: `true` leaves out the weld's last pass (step 3 at the top of this file).
  /// An entry `first_of[i] != i` then names a smaller index `r`: the first point of the class, or
  /// a point of the same block of `default_block_size` points whose entry names the first point.
  /// A caller that numbers the first points, then renumbers the other entries of each block in
  /// increasing order from the entry each names, reads the class's number at either link.
  /// The first points are the same (`first_of[i] == i`), and so are their counts by block, found
  /// by the partitions' tables instead.
  bool links_to_block_representatives = false;
};

/// `first_of[i]` = the smallest index j with `point(j) == point(i)`, for the `n` points
/// `point(0)`, ..., `point(n - 1)` (kernel points, returned by reference or by value): the result
/// of `first_equal_points(n, point)`, computed by blocks (see the top of this file), on TBB's
/// threads when `ConcurrencyTag` asks for it. Other number types than `double` go to
/// `first_equal_points()` (lazily exact numbers share state between copies), as do the soups of
/// one block. `key_budget`: the most representatives copied at once (0: a quarter of `n`, at
/// least one block); the result does not depend on it. `extras`, if given, receives what
/// `Exact_weld_extras` says (the first points counted by the last pass, the coordinates tested by
/// the first), and may ask for the entries of later points as links to their block's
/// representative instead (`Exact_weld_extras::links_to_block_representatives`, one pass fewer;
/// the first points and their counts are the same). With `extras`, a NaN or infinite coordinate
/// stops the weld: `extras->all_finite` is `false` and the returned entries are not written (the
/// caller refuses the soup). NaNs of one bit pattern share a hash and equal nothing, so that a
/// table of many of them would be probed in quadratic time.
template <class ConcurrencyTag, class PointAccess>
Uninitialized_vector<std::uint32_t> first_equal_points_by_blocks(std::size_t n, const PointAccess& point,
                                                                 std::size_t key_budget = 0,
                                                                 Exact_weld_extras* extras = nullptr)
{
  using Point = std::decay_t<decltype(point(std::size_t(0)))>;
  using FT = typename CGAL::Kernel_traits<Point>::Kernel::FT;
  constexpr std::size_t block_size = default_block_size;
  const std::size_t blocks = number_of_blocks(n, block_size);
  if(extras != nullptr) {
    extras->firsts_by_block.assign(blocks, 0);
    extras->all_finite = true;
  }
  // the one-table weld, the coordinates tested first and the first points counted afterwards
  // when `extras` asks for them
  auto weld_in_one_table = [&] {
    if(extras != nullptr) {
      for(std::size_t i = 0; i < n; ++i) {
        if(!is_finite_point(point(i))) {
          extras->all_finite = false;
          return Uninitialized_vector<std::uint32_t>(n);
        }
      }
    }
    Uninitialized_vector<std::uint32_t> first_of = first_equal_points(n, point);
    if(extras != nullptr)
      for(std::size_t i = 0; i < n; ++i) extras->firsts_by_block[i / block_size] += first_of[i] == i ? 1u : 0u;
    return first_of;
  };
  if constexpr(!std::is_same<FT, double>::value) {
    return weld_in_one_table();
  } else {
    if(n <= block_size) return weld_in_one_table();
    constexpr std::size_t partitions = 256;
    auto partition = [](std::uint64_t hash) { return static_cast<std::size_t>(hash >> 56); };
    // the other bits of the hash: the slot of a point in a table
    auto fingerprint = [](std::uint64_t hash) { return static_cast<std::uint32_t>(hash >> 24); };
    // (`Uninitialized_vector`: written whole by the blocks, which fault in its pages)
    Uninitialized_vector<std::uint32_t> first_of(n);

    // 1. Each block alone; representatives[b * partitions + q]: those of block b in partition q.
    std::vector<std::uint32_t> representatives(blocks * partitions, 0);
    // the partition of every representative (only theirs are written and read): a round of step 2
    // reads the point of a representative of its own partitions only, so that every point is read
    // and hashed once more whatever the number of rounds
    Uninitialized_vector<std::uint8_t> partition_of(n);
    // the blocks that met a NaN or an infinite coordinate (with `extras` only)
    std::vector<unsigned char> non_finite_in_block(blocks, 0);
    fault_in_pages(first_of);
    fault_in_pages(partition_of);
    for_each_block<ConcurrencyTag>(n, block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
      std::uint32_t* count = representatives.data() + b * partitions;
      Fingerprint_table table(2 * (end - begin));
      for(std::size_t i = begin; i != end; ++i) {
        const Point& p = point(i);
        const double x = p.x(), y = p.y(), z = p.z();
        if(extras != nullptr && !(std::isfinite(x) && std::isfinite(y) && std::isfinite(z))) {
          non_finite_in_block[b] = 1; // the soup is refused: the block stops (see above)
          return;
        }
        const std::uint64_t hash = hash_of_coordinates(x, y, z);
        first_of[i] = table.find_or_insert(static_cast<std::uint32_t>(i), fingerprint(hash), [&](std::uint32_t j) {
          const Point& o = point(j);
          return o.x() == x && o.y() == y && o.z() == z;
        });
        if(first_of[i] == i) {
          ++count[partition(hash)];
          partition_of[i] = static_cast<std::uint8_t>(partition(hash));
        }
      }
    });
    if(extras != nullptr) {
      extras->all_finite =
        std::find(non_finite_in_block.begin(), non_finite_in_block.end(), 1) == non_finite_in_block.end();
      if(!extras->all_finite) return first_of;
    }

    // 2. The representatives, partition by partition. Partition-major prefix sums: `place[b *
    // partitions + q]` is where block b writes its first representative of partition q.
    std::vector<std::size_t> partition_begin(partitions + 1, 0);
    std::vector<std::uint32_t>& place = representatives;
    {
      std::size_t total = 0;
      for(std::size_t q = 0; q < partitions; ++q) {
        partition_begin[q] = total;
        for(std::size_t b = 0; b < blocks; ++b) {
          const std::size_t c = place[b * partitions + q];
          place[b * partitions + q] = static_cast<std::uint32_t>(total);
          total += c;
        }
      }
      partition_begin[partitions] = total;
    }
    if(key_budget == 0) key_budget = n / 4;
    key_budget = std::max({key_budget, block_size, std::size_t(1)});
    // with the last pass left out, the first points of every block are counted by the partitions'
    // tables: firsts_in[q * blocks + b], those of partition q in block b (a partition's row is
    // written by its own task)
    const bool count_in_partitions = extras != nullptr && extras->links_to_block_representatives;
    std::vector<std::uint32_t> firsts_in(count_in_partitions ? partitions * blocks : 0, 0);
    struct Key { double x, y, z; std::uint32_t index, fingerprint; };
    Uninitialized_vector<Key> keys(std::min(key_budget, partition_begin[partitions]));
    fault_in_pages(keys);
    for(std::size_t first = 0; first < partitions;) {
      // the round: partitions [first, last), whose copies fit in the budget (one at least)
      std::size_t last = first + 1;
      while(last < partitions && partition_begin[last + 1] - partition_begin[first] <= keys.size()) ++last;
      const std::size_t base = partition_begin[first], round_size = partition_begin[last] - base;
      if(round_size > keys.size()) keys.resize(round_size);
      for_each_block<ConcurrencyTag>(n, block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
        std::uint32_t* next = place.data() + b * partitions;
        for(std::size_t i = begin; i != end; ++i) {
          if(first_of[i] != i) continue;
          const std::size_t q = partition_of[i];
          if(q < first || q >= last) continue;
          const Point& p = point(i);
          const double x = p.x(), y = p.y(), z = p.z();
          const std::uint64_t hash = hash_of_coordinates(x, y, z);
          keys[next[q]++ - base] = Key{x, y, z, static_cast<std::uint32_t>(i), fingerprint(hash)};
        }
      });
      for_each_block<ConcurrencyTag>(last - first, 1, [&](std::size_t r, std::size_t, std::size_t) {
        const Key* k = keys.data() + (partition_begin[first + r] - base);
        const std::size_t m = partition_begin[first + r + 1] - partition_begin[first + r];
        Fingerprint_table table(m);
        for(std::size_t j = 0; j < m; ++j) {
          const Key& key = k[j];
          const std::uint32_t found = table.find_or_insert(static_cast<std::uint32_t>(j), key.fingerprint, [&](std::uint32_t o) {
            return k[o].x == key.x && k[o].y == key.y && k[o].z == key.z;
          });
          // (a representative not first of its class is written once, by its partition's task)
          if(found != j)
            first_of[key.index] = k[found].index;
          else if(count_in_partitions)
            ++firsts_in[(first + r) * blocks + key.index / block_size];
        }
      });
      first = last;
    }

    if(count_in_partitions) {
      std::vector<std::size_t>& firsts = extras->firsts_by_block;
      for(std::size_t q = 0; q < partitions; ++q)
        for(std::size_t b = 0; b < blocks; ++b) firsts[b] += firsts_in[q * blocks + b];
      return first_of;
    }
    // 3. A point other than its block's representative names that representative, below it in
    // the same block. A representative names the first point of its class now (itself, or a
    // point of an earlier block), which names itself: nothing read here is written by another
    // block.
    for_each_block<ConcurrencyTag>(n, block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
      std::size_t firsts = 0;
      for(std::size_t i = begin; i != end; ++i) {
        const std::uint32_t r = first_of[i];
        if(r != i)
          first_of[i] = first_of[r];
        else
          ++firsts;
      }
      if(extras != nullptr) extras->firsts_by_block[b] = firsts;
    });
    return first_of;
  }
}

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_FIRST_EQUAL_POINTS_BY_BLOCKS_H
