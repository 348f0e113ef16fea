// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Union-find over 32-bit ids whose sets keep their smallest element as root, so that the sets
// and their roots do not depend on the order of the unions: sequential, and for several threads
// at once. The weld's tolerance graph and the components of the adjacency tables use them.

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

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_UNION_FIND_H
