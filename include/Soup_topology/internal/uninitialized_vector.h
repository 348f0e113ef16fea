// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// A `std::vector` whose `resize(n)` leaves the new elements of a trivial type uninitialized: for
// the large tables that a pass writes whole right after (on TBB's threads), so that no thread
// zeroes the memory before the pass that fills it.
//
// Its blocks of at least 4 MiB are asked for in transparent huge pages on Linux: aligned to 2 MiB
// and marked `madvise(MADV_HUGEPAGE)` (advice, which the kernel honours in its default "madvise"
// mode). glibc serves such blocks by fresh mappings and gives them back when they are freed, so
// every call of a function of the package faults its large tables in again, one 4 KiB page at a
// time; a huge page is one fault for 512 of them. Measured on a 2-core virtual machine, where a
// fault costs about 10 microseconds: `index_triangles()` of a 4.8M-triangle exploded soup 1.07 s
// -> 0.44 s on 1 thread and 0.95 s -> 0.25 s on 2 (the faults did not run in parallel). The cost
// is at most one partly used huge page a block (these tables are written whole). Define
// `SOUP_TOPOLOGY_NO_HUGE_PAGES` to allocate them as `std::allocator` does (and to leave the
// caller's vectors below unadvised).
//
// The caller's vectors that a function grows keep `std::allocator`: `reserve_in_huge_pages()`
// gives one its room in a new block whose huge pages are advised before anything touches them.
//
// Left to the threads of a parallel pass, the faults of a fresh block do not run in parallel on
// the virtual machines measured, and slow the pass by more than they cost on one thread:
// `fault_in_pages()` has the kernel fault such a block in by one call before the pass.

#ifndef SOUP_TOPOLOGY_INTERNAL_UNINITIALIZED_VECTOR_H
#define SOUP_TOPOLOGY_INTERNAL_UNINITIALIZED_VECTOR_H

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <iterator>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

#if defined(__linux__) && !defined(SOUP_TOPOLOGY_NO_HUGE_PAGES)
#include <sys/mman.h>
#include <unistd.h>
#if defined(MADV_HUGEPAGE)
#define SOUP_TOPOLOGY_HUGE_PAGES 1
#endif
#endif

namespace Soup_topology {
namespace internal {

/// the smallest block of `Default_init_allocator` asked for in huge pages (two of them).
constexpr std::size_t huge_page_block_bytes = std::size_t(4) << 20;

/// whether `Default_init_allocator` allocates a block of `bytes` bytes by
/// `allocate_in_huge_pages()` (and frees it by `std::free()`).
constexpr bool is_huge_page_block(std::size_t bytes)
{
#if defined(SOUP_TOPOLOGY_HUGE_PAGES)
  return bytes >= huge_page_block_bytes;
#else
  (void)bytes;
  return false;
#endif
}

/// the size of a transparent huge page.
constexpr std::size_t huge_page_bytes = std::size_t(2) << 20;

#if defined(SOUP_TOPOLOGY_HUGE_PAGES)
/// the size of the system's pages, the unit of `madvise()`'s ranges (4 KiB on x86-64; 16 or
/// 64 KiB on some other kernels).
inline std::uintptr_t system_page_bytes()
{
  static const std::uintptr_t bytes = [] {
    const long size = sysconf(_SC_PAGESIZE);
    return size > 0 ? static_cast<std::uintptr_t>(size) : std::uintptr_t(4096);
  }();
  return bytes;
}

/// gives `advice` (`madvise()`) to the whole pages of `page` bytes (a power of two) inside the
/// `bytes` bytes at `block`, if there is one.
inline void advise_whole_pages(void* block, std::size_t bytes, std::uintptr_t page, int advice)
{
  const std::uintptr_t first = (reinterpret_cast<std::uintptr_t>(block) + page - 1) & ~(page - 1);
  const std::uintptr_t last = (reinterpret_cast<std::uintptr_t>(block) + bytes) & ~(page - 1);
  if(first < last) madvise(reinterpret_cast<void*>(first), last - first, advice);
}
#endif

/// advises the whole huge pages inside the `bytes` bytes at `block` for transparent huge pages,
/// if they are at least `huge_page_block_bytes`; for a block not yet touched (advice given after
/// a page is faulted in does not change that page).
inline void advise_huge_pages(void* block, std::size_t bytes)
{
#if defined(SOUP_TOPOLOGY_HUGE_PAGES)
  if(is_huge_page_block(bytes)) advise_whole_pages(block, bytes, huge_page_bytes, MADV_HUGEPAGE);
#else
  (void)block;
  (void)bytes;
#endif
}

#if defined(SOUP_TOPOLOGY_HUGE_PAGES)
/// a block of `bytes` bytes aligned to 2 MiB, its whole huge pages marked for transparent huge
/// pages (the advice may be refused: the block is then made of small pages); throws
/// `std::bad_alloc` if there is no memory. Freed by `std::free()`.
inline void* allocate_in_huge_pages(std::size_t bytes)
{
  void* block = nullptr;
  if(posix_memalign(&block, huge_page_bytes, bytes) != 0 || block == nullptr) throw std::bad_alloc();
  advise_huge_pages(block, bytes);
  return block;
}
#endif

/// `std::allocator<T>` whose construction without arguments default-initializes (for a trivial
/// `T`: leaves the value indeterminate) instead of value-initializing (zeroing). Every other
/// construction, `resize(n, value)` and `assign(n, value)` included, is that of `std::allocator`.
template <class T>
class Default_init_allocator : public std::allocator<T>
{
public:
  using value_type = T;
  template <class U>
  struct rebind
  {
    using other = Default_init_allocator<U>;
  };

  Default_init_allocator() noexcept = default;
  template <class U>
  Default_init_allocator(const Default_init_allocator<U>&) noexcept
  {}

  /// `n` objects' memory: in huge pages from `huge_page_block_bytes` on (`is_huge_page_block()`),
  /// else that of `std::allocator<T>`.
  T* allocate(std::size_t n)
  {
#if defined(SOUP_TOPOLOGY_HUGE_PAGES)
    if(n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    if(is_huge_page_block(n * sizeof(T))) return static_cast<T*>(allocate_in_huge_pages(n * sizeof(T)));
#endif
    return std::allocator<T>::allocate(n);
  }

  void deallocate(T* p, std::size_t n) noexcept
  {
#if defined(SOUP_TOPOLOGY_HUGE_PAGES)
    if(is_huge_page_block(n * sizeof(T))) {
      std::free(p);
      return;
    }
#endif
    std::allocator<T>::deallocate(p, n);
  }

  template <class U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible<U>::value)
  {
    ::new(static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args)
  {
    ::new(static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

template <class T, class U>
bool operator==(const Default_init_allocator<T>&, const Default_init_allocator<U>&) noexcept
{
  return true;
}
template <class T, class U>
bool operator!=(const Default_init_allocator<T>&, const Default_init_allocator<U>&) noexcept
{
  return false;
}

/// a vector of a trivial type whose `resize(n)` does not write the new elements: every one of them
/// must be written before it is read.
template <class T>
using Uninitialized_vector = std::vector<T, Default_init_allocator<T>>;

/// faults in the pages of the elements of `v` in one system call on the calling thread
/// (`madvise(MADV_POPULATE_WRITE)`, Linux 5.14 and later), for a fresh block of at least
/// `huge_page_block_bytes` that passes on TBB's threads then write whole; the elements are not
/// written (what the block holds stays). Measured on a 2-core virtual machine, the 72 MB of the
/// weld's first pass on a 4.8M-triangle soup: faulted in by the two threads of the pass that
/// writes them, the pass took 0.115-0.14 s; after this call (4 ms), 0.08-0.10 s; the same
/// population split between the two threads took 12 ms instead of 4 (the faults of one process
/// do not run in parallel there). On one thread the call costs what the pass's own faults cost.
/// Nothing is done where the kernel or the build has no such call (the pass then faults the
/// pages in itself, as before), nor for a smaller block.
template <class T, class Allocator>
void fault_in_pages(std::vector<T, Allocator>& v)
{
#if defined(SOUP_TOPOLOGY_HUGE_PAGES) && defined(MADV_POPULATE_WRITE)
  const std::size_t bytes = v.size() * sizeof(T);
  if(bytes >= huge_page_block_bytes) advise_whole_pages(v.data(), bytes, system_page_bytes(), MADV_POPULATE_WRITE);
#else
  (void)v;
#endif
}

/// gives a caller's `std::vector` room for `n` elements: if its capacity is smaller, its elements
/// move into a new block whose huge pages are advised before the move touches them. The caller's
/// vectors keep `std::allocator`, from which glibc serves a large block by a fresh mapping: the
/// growth of a 116 MB vector by `push_back()` (which doubles the capacity and copies the elements on
/// one thread) faulted it in one 4 KiB page at a time, 0.29 s on a machine where a fault costs
/// about 10 microseconds, against 0.01 s in huge pages. The new capacity is `room` (at least `n`:
/// a caller that goes on appending asks for more). The elements and the size are unchanged; if an
/// exception is thrown, `v` is left as it was (elements whose move may throw are copied, as
/// `std::vector` does when it grows).
template <class T>
void reserve_in_huge_pages(std::vector<T>& v, std::size_t n, std::size_t room = 0)
{
  if(v.capacity() >= n) return;
  room = (std::max)(room, n);
  std::vector<T> grown;
  grown.reserve(room);
  advise_huge_pages(grown.data(), room * sizeof(T));
  if constexpr(std::is_nothrow_move_constructible<T>::value || !std::is_copy_constructible<T>::value)
    grown.insert(grown.end(), std::make_move_iterator(v.begin()), std::make_move_iterator(v.end()));
  else
    grown.insert(grown.end(), v.begin(), v.end());
  v.swap(grown);
}

/// whether `Range` has `reserve(std::size_t)`.
template <class Range, class = void>
struct Has_reserve : std::false_type {};
template <class Range>
struct Has_reserve<Range, std::void_t<decltype(std::declval<Range&>().reserve(std::size_t(1)))>> : std::true_type {};

/// for a range of another type: `reserve(n)` where the range has it, nothing otherwise.
template <class Range>
void reserve_in_huge_pages(Range& r, std::size_t n, std::size_t /*room*/ = 0)
{
  if constexpr(Has_reserve<Range>::value) r.reserve(n);
}

/// `r.resize(n)`, the room made first by `reserve_in_huge_pages()`.
template <class Range>
void resize_in_huge_pages(Range& r, std::size_t n)
{
  reserve_in_huge_pages(r, n);
  r.resize(n);
}

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_UNINITIALIZED_VECTOR_H
