// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Union-find over 32-bit ids whose sets keep their smallest element as root, so that the sets
// and their roots do not depend on the order of the unions: sequential, and for several threads
// at once; and with a parity between the ids of a set. The weld's tolerance graph, the components
// of the adjacency tables and the patches of the orientation use them.

#ifndef SOUP_TOPOLOGY_INTERNAL_UNION_FIND_H
#define SOUP_TOPOLOGY_INTERNAL_UNION_FIND_H

#include <Soup_topology/internal/uninitialized_vector.h>

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

namespace Soup_topology {
namespace internal {

/// union-find over 32-bit ids; the root of a set is its smallest id, so the sets (and their
/// roots) do not depend on the order of the unions. Its parents are an `Uninitialized_vector`:
/// written once each by `reset()` (or handed over whole by `assign()`), not zeroed before.
class Union_find
{
public:
  /// the parents, the roots of `take_roots()`
  using Parents = Uninitialized_vector<std::uint32_t>;

  explicit Union_find(std::size_t n = 0) { reset(n); }
  void reset(std::size_t n)
  {
    parent_.resize(n);
    for(std::size_t i = 0; i < n; ++i) parent_[i] = static_cast<std::uint32_t>(i);
  }
  std::uint32_t find(std::uint32_t x)
  {
    while(parent_[x] != x) x = parent_[x] = parent_[parent_[x]];
    return x;
  }
  /// `true` if `x` and `y` were in different sets.
  bool unite(std::uint32_t x, std::uint32_t y)
  {
    const std::uint32_t a = find(x), b = find(y);
    if(a == b) return false;
    parent_[std::max(a, b)] = std::min(a, b);
    return true;
  }
  /// takes the sets of `parents`, a forest whose every parent is at most its child (so that the
  /// root of a set is its smallest element, as `unite()` leaves it).
  void assign(Parents&& parents) { parent_ = std::move(parents); }
  /// the root of every element, `roots[x] == find(x)`, in the storage of the sets (left empty).
  /// One pass in increasing order: a parent is smaller than its child, so it holds its root already.
  Parents take_roots()
  {
    for(std::size_t x = 0; x < parent_.size(); ++x) parent_[x] = parent_[parent_[x]];
    return std::move(parent_);
  }

private:
  Parents parent_;
};

/// The sets of `Union_find`, united by several threads at once. A root is linked under the
/// smaller root by a compare-and-swap that fails if it stopped being a root (then the union is
/// tried again), and `find()` halves the path it walks: every parent stays at most its child, so
/// whatever the order of the unions each set ends with its smallest element as root, as with
/// `Union_find`, and `into()` gives the same sets with the same roots.
class Concurrent_union_find
{
public:
  /// `n` singletons.
  explicit Concurrent_union_find(std::size_t n) : Concurrent_union_find(n, Unset{})
  {
    make_singletons(0, n);
  }
  /// Tag of the constructor that leaves the sets unset: the caller makes every id a singleton
  /// (`make_singletons()`) before any other call, e.g. by blocks on the threads that use them,
  /// which then take the first touch of that memory.
  struct Unset {};
  Concurrent_union_find(std::size_t n, Unset) : parent_(new std::atomic<std::uint32_t>[n]), size_(n) {}
  /// makes every id of `[begin, end)` a singleton.
  void make_singletons(std::size_t begin, std::size_t end)
  {
    for(std::size_t i = begin; i < end; ++i) parent_[i].store(static_cast<std::uint32_t>(i), std::memory_order_relaxed);
  }
  std::uint32_t find(std::uint32_t x)
  {
    for(;;) {
      std::uint32_t p = parent_[x].load(std::memory_order_acquire);
      if(p == x) return x;
      const std::uint32_t g = parent_[p].load(std::memory_order_acquire);
      if(g != p) parent_[x].compare_exchange_weak(p, g, std::memory_order_acq_rel, std::memory_order_acquire);
      x = g;
    }
  }
  /// unites the sets of `x` and `y`; any number of threads may unite at once.
  void unite(std::uint32_t x, std::uint32_t y)
  {
    for(;;) {
      std::uint32_t a = find(x), b = find(y);
      if(a == b) return;
      if(a < b) std::swap(a, b);
      std::uint32_t expected = a;
      if(parent_[a].compare_exchange_strong(expected, b, std::memory_order_acq_rel, std::memory_order_acquire)) return;
    }
  }
  /// `unite(x, y)` for a thread that alone touches the sets of `x` and `y` meanwhile (the sets
  /// of a block of ids united within the block, each block by one thread): plain loads and
  /// stores, no compare-and-swap. The parents keep the same rule.
  void unite_alone(std::uint32_t x, std::uint32_t y)
  {
    const std::uint32_t a = find_alone(x), b = find_alone(y);
    if(a != b) parent_[std::max(a, b)].store(std::min(a, b), std::memory_order_relaxed);
  }
  /// the parent of `x` (at most `x`; `x` itself for a root), once every union has returned.
  std::uint32_t parent(std::uint32_t x) const { return parent_[x].load(std::memory_order_relaxed); }
  /// the sets, once every union has returned, into `uf`: the same forest (every parent at most
  /// its child, so the same roots), its parents copied by `for_each_block(n, f)`, which calls
  /// `f(block, begin, end)` for blocks covering `[0, n)` (on several threads, say).
  /// (The copy is not zeroed first: its every entry is written by the blocks, which also take
  /// the first touch of its pages.)
  template <class ForEachBlock>
  void into(Union_find& uf, const ForEachBlock& for_each_block)
  {
    Union_find::Parents parents(size_);
    for_each_block(size_, [&](std::size_t, std::size_t begin, std::size_t end) {
      for(std::size_t i = begin; i < end; ++i) parents[i] = parent_[i].load(std::memory_order_relaxed);
    });
    uf.assign(std::move(parents));
  }
  /// the same, on this thread
  void into(Union_find& uf)
  {
    into(uf, [](std::size_t n, const auto& f) { f(0, 0, n); });
  }

private:
  // `find()` for `unite_alone()`: the path is halved by plain stores.
  std::uint32_t find_alone(std::uint32_t x)
  {
    for(;;) {
      const std::uint32_t p = parent_[x].load(std::memory_order_relaxed);
      if(p == x) return x;
      const std::uint32_t g = parent_[p].load(std::memory_order_relaxed);
      parent_[x].store(g, std::memory_order_relaxed);
      x = g;
    }
  }

  std::unique_ptr<std::atomic<std::uint32_t>[]> parent_;
  std::size_t size_;
};

/// Sets of 32-bit ids that also know, for every two ids of a set, whether they *agree* or *differ*
/// (a bit: the parity of a path between them), as the orientations of the triangles of a patch
/// do: two triangles across a shared edge must be turned alike or one of them must be turned.
/// Every id holds its parent and its parity relative to the parent in one word; the parity of an
/// id relative to its root is the sum (exclusive or) of the parities along its path. The root of
/// a set is its smallest id, whatever the order of the unions, as in `Union_find`.
///
/// Unions are made by one thread per group of ids (`unite_alone()`): a thread may unite ids of a
/// block that no other thread touches meanwhile, or any ids when it runs alone. Once the unions
/// have returned, `find()` may be called by any number of threads at once: it halves the paths
/// it walks by compare-and-swap, each write replacing a parent by an ancestor and the parity by
/// the parity relative to that ancestor, which stays true whatever the other threads write.
class Parity_union_find
{
public:
  /// `n` ids whose words are unset: the caller makes every id a singleton (`make_singletons()`)
  /// before any other call, e.g. by blocks on the threads that use them.
  explicit Parity_union_find(std::size_t n) : word_(new std::atomic<std::uint64_t>[n]) {}
  /// makes every id of `[begin, end)` a singleton.
  void make_singletons(std::size_t begin, std::size_t end)
  {
    for(std::size_t i = begin; i < end; ++i) word_[i].store(std::uint64_t(i) << 1, std::memory_order_relaxed);
  }
  /// the root of the set of `x` and the parity of `x` relative to it; safe on several threads
  /// at once once the unions have returned.
  std::pair<std::uint32_t, bool> find(std::uint32_t x)
  {
    bool parity = false;
    for(;;) {
      std::uint64_t w = word_[x].load(std::memory_order_acquire);
      const std::uint32_t p = static_cast<std::uint32_t>(w >> 1);
      if(p == x) return {x, parity};
      const std::uint64_t wp = word_[p].load(std::memory_order_acquire);
      const std::uint32_t g = static_cast<std::uint32_t>(wp >> 1);
      if(g == p) return {p, parity != ((w & 1) != 0)};
      const std::uint64_t step = (w ^ wp) & 1; // the parity of x relative to g
      word_[x].compare_exchange_weak(w, (std::uint64_t(g) << 1) | step, std::memory_order_acq_rel,
                                     std::memory_order_acquire);
      parity = parity != (step != 0);
      x = g;
    }
  }
  /// records that `x` and `y` differ if `differ`, agree otherwise, for a thread alone with their
  /// sets (see above). Returns `false`, changing nothing, if the sets say the opposite already.
  bool unite_alone(std::uint32_t x, std::uint32_t y, bool differ)
  {
    const auto [a, pa] = find_alone(x);
    const auto [b, pb] = find_alone(y);
    const bool root_parity = (pa != pb) != differ;
    if(a == b) return !root_parity;
    word_[std::max(a, b)].store((std::uint64_t(std::min(a, b)) << 1) | std::uint64_t(root_parity),
                                std::memory_order_relaxed);
    return true;
  }
  /// the parent of `x` (at most `x`; `x` itself for a root) and the parity relative to it, once
  /// every union has returned.
  std::pair<std::uint32_t, bool> parent(std::uint32_t x) const
  {
    const std::uint64_t w = word_[x].load(std::memory_order_relaxed);
    return {static_cast<std::uint32_t>(w >> 1), (w & 1) != 0};
  }

private:
  // `find()` for `unite_alone()`: the path is halved by plain stores.
  std::pair<std::uint32_t, bool> find_alone(std::uint32_t x)
  {
    bool parity = false;
    for(;;) {
      const std::uint64_t w = word_[x].load(std::memory_order_relaxed);
      const std::uint32_t p = static_cast<std::uint32_t>(w >> 1);
      if(p == x) return {x, parity};
      const std::uint64_t wp = word_[p].load(std::memory_order_relaxed);
      const std::uint32_t g = static_cast<std::uint32_t>(wp >> 1);
      if(g == p) return {p, parity != ((w & 1) != 0)};
      word_[x].store((std::uint64_t(g) << 1) | ((w ^ wp) & 1), std::memory_order_relaxed);
      parity = parity != (((w ^ wp) & 1) != 0);
      x = g;
    }
  }

  std::unique_ptr<std::atomic<std::uint64_t>[]> word_;
};

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_UNION_FIND_H
