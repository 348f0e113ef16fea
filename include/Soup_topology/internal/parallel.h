// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Deterministic parallel helpers behind CGAL's `ConcurrencyTag`. Work is cut into blocks of a
// fixed size that does not depend on the number of threads, results of blocks are put together
// in block order, so that every helper gives the same result as its sequential run, on any
// number of threads.

#ifndef SOUP_TOPOLOGY_INTERNAL_PARALLEL_H
#define SOUP_TOPOLOGY_INTERNAL_PARALLEL_H

#include <CGAL/tags.h>

#if defined(CGAL_LINKED_WITH_TBB)
#include <tbb/global_control.h>
#if defined(__SANITIZE_THREAD__)
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#else
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/partitioner.h>
#endif
#endif

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <vector>

namespace Soup_topology {
namespace internal {

/// `true` if `ConcurrencyTag` asks for the parallel code (`CGAL::Parallel_tag`, or
/// `CGAL::Parallel_if_available_tag` when TBB is linked). Asking for `CGAL::Parallel_tag`
/// without TBB is a compile-time error, as in CGAL's point-set functions.
template <class ConcurrencyTag>
constexpr bool runs_in_parallel()
{
  static_assert(std::is_convertible<ConcurrencyTag, CGAL::Sequential_tag>::value,
                "ConcurrencyTag must be CGAL::Sequential_tag, CGAL::Parallel_tag or CGAL::Parallel_if_available_tag");
#if defined(CGAL_LINKED_WITH_TBB)
  return std::is_convertible<ConcurrencyTag, CGAL::Parallel_tag>::value;
#else
  static_assert(!std::is_convertible<ConcurrencyTag, CGAL::Parallel_tag>::value,
                "Parallel_tag is enabled but TBB is unavailable.");
  return false;
#endif
}

/// the number of elements of a block of `for_each_block()` unless the caller gives one.
constexpr std::size_t default_block_size = std::size_t(1) << 14;

/// the number of blocks of `block_size` elements that cover `n` elements.
inline std::size_t number_of_blocks(std::size_t n, std::size_t block_size = default_block_size)
{
  return (n + block_size - 1) / block_size;
}

#if defined(CGAL_LINKED_WITH_TBB) && defined(__SANITIZE_THREAD__)
/// Under ThreadSanitizer, `for_each_block()` runs its blocks on threads of the standard library,
/// as many as TBB would use (its `max_allowed_parallelism`), each taking the next block not yet
/// taken. TBB hands its tasks, and the copies of a loop body it makes when it splits a range,
/// over inside its library, which Debian ships uninstrumented: the sanitizer sees no
/// synchronisation there and reports the hand-over as a race. Here every start and end of a
/// thread is seen, so a report is a race of the package's own code. The blocks are the same, and
/// any two of them may run at the same time, as under TBB. The exception of the lowest block
/// that threw is rethrown once every thread has ended.
template <class Run>
void run_blocks_on_standard_threads(std::size_t blocks, const Run& run)
{
  const std::size_t threads =
    std::min(blocks, std::max<std::size_t>(1, tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)));
  std::atomic<std::size_t> next{0};
  std::mutex failure_mutex;
  std::size_t failed_block = blocks;
  std::exception_ptr failure;
  auto work = [&] {
    for(std::size_t b = next.fetch_add(1); b < blocks; b = next.fetch_add(1)) {
      try {
        run(b);
      } catch(...) {
        const std::lock_guard<std::mutex> lock(failure_mutex);
        if(b < failed_block) { failed_block = b; failure = std::current_exception(); }
      }
    }
  };
  std::vector<std::thread> pool;
  for(std::size_t t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for(std::thread& t : pool) t.join();
  if(failure) std::rethrow_exception(failure);
}
#endif

/// `true` if `ConcurrencyTag` runs in parallel and TBB allows more than one thread (its
/// `max_allowed_parallelism`, which `--threads` and a caller's `tbb::global_control` set). Some
/// parallel algorithms do more work in all than their sequential versions, which give the same
/// result: on one thread the caller takes the sequential one.
template <class ConcurrencyTag>
bool runs_on_several_threads()
{
#if defined(CGAL_LINKED_WITH_TBB)
  if constexpr(runs_in_parallel<ConcurrencyTag>())
    return tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism) > 1;
#endif
  return false;
}

/// calls `f(block, begin, end)` for every block `[begin, end)` of `block_size` elements of
/// `[0, n)` (the last one shorter), in parallel when `ConcurrencyTag` asks for it. The blocks do
/// not depend on the number of threads.
template <class ConcurrencyTag, class F>
void for_each_block(std::size_t n, std::size_t block_size, const F& f)
{
  const std::size_t blocks = number_of_blocks(n, block_size);
  auto run = [&](std::size_t b) { f(b, b * block_size, std::min(n, (b + 1) * block_size)); };
#if defined(CGAL_LINKED_WITH_TBB)
  if constexpr(runs_in_parallel<ConcurrencyTag>()) {
    if(blocks > 1) {
#if defined(__SANITIZE_THREAD__)
      run_blocks_on_standard_threads(blocks, run);
#else
      tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, blocks, 1),
        [&](const tbb::blocked_range<std::size_t>& r) {
          for(std::size_t b = r.begin(); b != r.end(); ++b) run(b);
        },
        tbb::simple_partitioner());
#endif
      return;
    }
  }
#else
  (void)runs_in_parallel<ConcurrencyTag>();
#endif
  for(std::size_t b = 0; b < blocks; ++b) run(b);
}

/// calls `f(i)` for every `i` in `[0, n)`, in parallel when `ConcurrencyTag` asks for it; the
/// calls must be independent of each other.
template <class ConcurrencyTag, class F>
void for_each_index(std::size_t n, const F& f, std::size_t block_size = default_block_size)
{
  for_each_block<ConcurrencyTag>(n, block_size, [&](std::size_t, std::size_t begin, std::size_t end) {
    for(std::size_t i = begin; i != end; ++i) f(i);
  });
}

/// calls `f()` and `g()`, which must be independent of each other: side by side when
/// `ConcurrencyTag` asks for it and TBB allows more than one thread (`g` may run in parallel
/// itself: the thread that is done with `f` then helps it), one after the other otherwise. Neither
/// runs any more when it returns. If either threw, one of the exceptions is rethrown then, and
/// the other may not have run at all. (Under ThreadSanitizer `f` runs on a thread of the standard
/// library: see `run_blocks_on_standard_threads()`.)
template <class ConcurrencyTag, class F, class G>
void run_side_by_side(const F& f, const G& g)
{
#if defined(CGAL_LINKED_WITH_TBB)
  if constexpr(runs_in_parallel<ConcurrencyTag>()) {
    if(runs_on_several_threads<ConcurrencyTag>()) {
#if defined(__SANITIZE_THREAD__)
      std::exception_ptr failure_of_f, failure_of_g;
      std::thread side([&] {
        try {
          f();
        } catch(...) {
          failure_of_f = std::current_exception();
        }
      });
      try {
        g();
      } catch(...) {
        failure_of_g = std::current_exception();
      }
      side.join();
      if(failure_of_f) std::rethrow_exception(failure_of_f);
      if(failure_of_g) std::rethrow_exception(failure_of_g);
#else
      tbb::parallel_invoke(f, g);
#endif
      return;
    }
  }
#endif
  f();
  g();
}

/// turns `counts` into their exclusive prefix sums and returns the total (sequential: callers
/// use it on one count per block or per element of a table built once).
template <class Count>
std::size_t exclusive_prefix_sums(std::vector<Count>& counts)
{
  std::size_t total = 0;
  for(Count& c : counts) {
    const std::size_t here = static_cast<std::size_t>(c);
    c = static_cast<Count>(total);
    total += here;
  }
  return total;
}

/// the elements `i` of `[0, n)` kept by `keep(i)`, with `out(i, position)` called for each at its
/// position among the kept ones, in the order of `i` (count by blocks, prefix sums over the
/// blocks, then place): the result does not depend on the number of threads. Returns the number
/// kept.
template <class ConcurrencyTag, class Keep, class Out>
std::size_t compact_in_order(std::size_t n, const Keep& keep, const Out& out, std::size_t block_size = default_block_size)
{
  std::vector<std::size_t> kept(number_of_blocks(n, block_size), 0);
  for_each_block<ConcurrencyTag>(n, block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
    std::size_t c = 0;
    for(std::size_t i = begin; i != end; ++i) c += keep(i) ? 1 : 0;
    kept[b] = c;
  });
  const std::size_t total = exclusive_prefix_sums(kept);
  for_each_block<ConcurrencyTag>(n, block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
    std::size_t position = kept[b];
    for(std::size_t i = begin; i != end; ++i)
      if(keep(i)) out(i, position++);
  });
  return total;
}

/// appends the per-block buffers `buffers[0], buffers[1], ...` to `out`, in block order.
template <class T>
void concatenate_in_block_order(std::vector<std::vector<T>>& buffers, std::vector<T>& out)
{
  std::size_t total = out.size();
  for(const std::vector<T>& b : buffers) total += b.size();
  out.reserve(total);
  for(std::vector<T>& b : buffers) {
    out.insert(out.end(), b.begin(), b.end());
    std::vector<T>().swap(b);
  }
}

/// appends to `out` the elements `i` of `[0, n)` for which `keep(i)` holds, in increasing order
/// (blocks scanned in parallel when `ConcurrencyTag` asks for it, their finds put together in
/// block order). `keep` is called once per element: for a costly test that few pass.
template <class ConcurrencyTag, class Index, class Keep>
void append_indices_where(std::size_t n, const Keep& keep, std::vector<Index>& out)
{
  if constexpr(!runs_in_parallel<ConcurrencyTag>()) {
    for(std::size_t i = 0; i < n; ++i)
      if(keep(i)) out.push_back(static_cast<Index>(i));
  } else {
    std::vector<std::vector<Index>> found(number_of_blocks(n));
    for_each_block<ConcurrencyTag>(n, default_block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
      for(std::size_t i = begin; i != end; ++i)
        if(keep(i)) found[b].push_back(static_cast<Index>(i));
    });
    concatenate_in_block_order(found, out);
  }
}

/// the first `i` in `[0, n)` for which `bad(i)` holds, or `n` (blocks checked in parallel when
/// `ConcurrencyTag` asks for it; the smallest index wins whatever the threads).
template <class ConcurrencyTag, class Predicate>
std::size_t first_index_where(std::size_t n, const Predicate& bad)
{
  if constexpr(!runs_in_parallel<ConcurrencyTag>()) {
    for(std::size_t i = 0; i < n; ++i)
      if(bad(i)) return i;
    return n;
  } else {
    std::vector<std::size_t> first(number_of_blocks(n), n);
    for_each_block<ConcurrencyTag>(n, default_block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
      for(std::size_t i = begin; i != end; ++i)
        if(bad(i)) { first[b] = i; return; }
    });
    for(const std::size_t i : first)
      if(i != n) return i;
    return n;
  }
}

/// the largest of `value_of(i)` over `[0, n)` and `smallest` (blocks taken in parallel when
/// `ConcurrencyTag` asks for it, then the largest of the blocks). A maximum is the same in any
/// order, so the result does not depend on the threads, provided `value_of` gives no NaN.
template <class ConcurrencyTag, class ValueOf>
double largest_by_blocks(std::size_t n, const ValueOf& value_of, double smallest = 0.)
{
  std::vector<double> largest_of_block(number_of_blocks(n), smallest);
  for_each_block<ConcurrencyTag>(n, default_block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
    double largest = smallest;
    for(std::size_t i = begin; i != end; ++i) largest = std::max(largest, static_cast<double>(value_of(i)));
    largest_of_block[b] = largest;
  });
  double largest = smallest;
  for(const double x : largest_of_block) largest = std::max(largest, x);
  return largest;
}

/// a stable sort of `items` by the digits of `digit_bits` bits of `key_of(item)` (an unsigned
/// integer) that start at bits `low`, `low + digit_bits`, ... below `high`: one pass of counts and
/// one scatter a digit, from the lowest, the passes whose digit is the same for all skipped. On
/// TBB's threads when `ConcurrencyTag` asks for it and the items are many: each pass counts the
/// digits of 16 blocks of items in parallel, places the items of a block after those of the
/// blocks before it with the same digit, and scatters the blocks in parallel. A stable sort has
/// one result, on any number of threads. `Items` is a `std::vector`; with an
/// `Uninitialized_vector`, the scratch space `buffer` is first written by the parallel passes,
/// not zeroed by one thread before.
template <class ConcurrencyTag, class Items, class KeyOf>
void sort_by_digits(Items& items, Items& buffer, unsigned low, unsigned high, unsigned digit_bits, const KeyOf& key_of)
{
  const std::size_t n = items.size();
  if(n < 2) return;
  const std::size_t digits = std::size_t(1) << digit_bits;
  const std::uint64_t mask = digits - 1;
  const std::size_t block_size = runs_in_parallel<ConcurrencyTag>() && n >= (std::size_t(1) << 20) ? (n + 15) / 16 : n;
  const std::size_t blocks = number_of_blocks(n, block_size);
  buffer.resize(n);
  std::vector<std::size_t> offset(blocks * digits); // by block, then digit
  for(unsigned shift = low; shift < high; shift += digit_bits) {
    auto digit = [&](std::size_t i) { return static_cast<std::size_t>((static_cast<std::uint64_t>(key_of(items[i])) >> shift) & mask); };
    for_each_block<ConcurrencyTag>(n, block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
      std::size_t* const count = offset.data() + b * digits;
      std::fill(count, count + digits, 0);
      for(std::size_t i = begin; i != end; ++i) ++count[digit(i)];
    });
    const std::size_t first_digit = digit(0);
    std::size_t with_first_digit = 0;
    for(std::size_t b = 0; b < blocks; ++b) with_first_digit += offset[b * digits + first_digit];
    if(with_first_digit == n) continue; // one digit for all: already in order
    std::size_t sum = 0;
    for(std::size_t d = 0; d < digits; ++d)
      for(std::size_t b = 0; b < blocks; ++b) {
        std::size_t& c = offset[b * digits + d];
        const std::size_t here = c;
        c = sum;
        sum += here;
      }
    for_each_block<ConcurrencyTag>(n, block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
      std::size_t* const next = offset.data() + b * digits;
      for(std::size_t i = begin; i != end; ++i) buffer[next[digit(i)]++] = items[i];
    });
    items.swap(buffer);
  }
}

/// sorts `items` by their member `key` (an unsigned 64-bit integer), stably: a comparison sort
/// below 4096 items (fewer than the digits' counters), else `sort_by_digits()` of 16-bit digits
/// over the `bits` low bits of the keys (the others are zero), on TBB's threads when
/// `ConcurrencyTag` asks for it and the items are many. A stable sort has one result, whichever
/// way it is computed. `buffer` is scratch space.
template <class ConcurrencyTag, class Items>
void sort_by_key(Items& items, Items& buffer, unsigned bits = 64)
{
  using Item = typename Items::value_type;
  if(items.size() < 2) return;
  if(items.size() < 4096) {
    std::stable_sort(items.begin(), items.end(), [](const Item& a, const Item& b) { return a.key < b.key; });
    return;
  }
  sort_by_digits<ConcurrencyTag>(items, buffer, 0, bits, 16, [](const Item& item) { return item.key; });
}

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_PARALLEL_H
