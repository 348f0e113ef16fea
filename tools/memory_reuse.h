// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// How the command-line tools ask the C library and the kernel to manage their memory.
//
// The pipeline allocates and frees large arrays one phase after another (the soup, the tables,
// the octree, the weld's graph, the orientation). By default glibc serves every block above its
// mmap threshold (128 KiB, raised up to 32 MiB as blocks are freed) with a fresh mapping and
// gives it back to the system when it is freed, so that every phase touches new pages. A first
// touch costs a page fault (measured on a 2-core virtual machine: 2.6 s to touch 1 GiB of fresh
// memory the first time, 0.035 s the second time). On the 1M-triangle jittered torus, half the
// faults of `soup_topology repair` were on memory that an earlier phase had just freed.
//
// The tools therefore keep freed memory in the process for the next phase: no block is served by
// its own mapping, and the heap is never trimmed. The faults left are those of the first touch of
// the peak, 4 KiB each. The tools also mark the part of the heap that they will use for
// transparent huge pages (`madvise(MADV_HUGEPAGE)`, which the kernel honours in its default
// "madvise" mode): the pages then come 2 MiB at a time, 512 times fewer faults (on the same
// machine: 1 GiB touched in 0.09 s instead of 2.6 s).
//
// This is the program's choice, not the library's: the headers do not call it, and an
// application that links the library keeps its own policy. Results do not depend on it. The cost
// is a peak resident memory a few percent higher (freed blocks that are not reused exactly, and
// huge pages touched in part); `Performance.md` has the measurements. That is why
// `repair --max-memory` keeps glibc's default: its limit is modelled and measured with freed
// memory given back; only its large blocks are asked for in huge pages
// (`restart_with_huge_page_mappings()`). A user who sets `GLIBC_TUNABLES` keeps the policy given
// there. The package's own huge-page blocks (`internal/uninitialized_vector.h`) are off in the tools
// (`SOUP_TOPOLOGY_NO_HUGE_PAGES`, tools/CMakeLists.txt): this heap is advised already.

#ifndef SOUP_TOPOLOGY_TOOLS_MEMORY_REUSE_H
#define SOUP_TOPOLOGY_TOOLS_MEMORY_REUSE_H

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#if defined(__GLIBC__)
#include <malloc.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>
#endif

namespace soup_topology_tool {

// The sanitizers' allocators ignore the policy (clang defines no __SANITIZE_ADDRESS__).
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || __has_feature(memory_sanitizer)
#define SOUP_TOPOLOGY_TOOL_SANITIZED_ALLOCATOR 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define SOUP_TOPOLOGY_TOOL_SANITIZED_ALLOCATOR 1
#endif
/// whether the policy can be set here: glibc, and no sanitizer.
#if defined(__GLIBC__) && !defined(SOUP_TOPOLOGY_TOOL_SANITIZED_ALLOCATOR)
inline constexpr bool memory_reuse_can_be_set = true;
#else
inline constexpr bool memory_reuse_can_be_set = false;
#endif

/// the size of the part of the heap that `ask_for_huge_pages_on_the_heap()` marks: half the
/// physical memory, at most 64 GiB, and at most a quarter of the address-space and data-segment
/// limits where they are set (`RLIMIT_AS`, `RLIMIT_DATA`: the rest stays for the other mappings);
/// 0 (nothing marked) where that is below 64 MiB or not known.
inline std::size_t huge_page_heap_size()
{
#if defined(__GLIBC__)
  const long pages = sysconf(_SC_PHYS_PAGES), page_size = sysconf(_SC_PAGESIZE);
  if(pages <= 0 || page_size <= 0) return 0;
  std::uint64_t size = std::min<std::uint64_t>(std::uint64_t(pages) * std::uint64_t(page_size) / 2,
                                               std::uint64_t(64) << 30);
  for(const int resource : {RLIMIT_AS, RLIMIT_DATA}) {
    rlimit limit;
    if(getrlimit(resource, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
      size = std::min<std::uint64_t>(size, std::uint64_t(limit.rlim_cur) / 4);
  }
  if(size < (std::uint64_t(64) << 20) || size > std::uint64_t(SIZE_MAX)) return 0;
  return static_cast<std::size_t>(size);
#else
  return 0;
#endif
}

/// Marks the next `huge_page_heap_size()` bytes of the heap for transparent huge pages without
/// touching them: the heap grows by that much (address space only), the range is marked and
/// handed back to the allocator, which serves the next blocks from it (the heap is not trimmed
/// under the policy). Returns the bytes marked. Where the kernel has no transparent huge pages,
/// or the heap cannot grow that far, nothing changes; memory beyond the range keeps 4 KiB pages.
inline std::size_t ask_for_huge_pages_on_the_heap()
{
#if defined(__GLIBC__) && defined(MADV_HUGEPAGE)
  const std::size_t size = huge_page_heap_size();
  if(size == 0) return 0;
  void* block = std::malloc(size);
  if(block == nullptr) return 0;
  constexpr std::uintptr_t huge_page = std::uintptr_t(1) << 21;
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(block) + huge_page - 1) & ~(huge_page - 1);
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(block) + size) & ~(huge_page - 1);
  const bool marked = begin < end && madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE) == 0;
  std::free(block);
  return marked ? std::size_t(end - begin) : 0;
#else
  return 0;
#endif
}

/// Under `repair --max-memory` (and `soup_topology_mpi --max-memory`, on every rank, before
/// `MPI_Init`), glibc's default stays (a large block is a mapping of its own,
/// given back when it is freed: the peak is what the model counts), but those mappings are asked
/// for in transparent huge pages, as glibc does with its tunable `glibc.malloc.hugetlb=1`
/// (glibc 2.35 and later; older ones ignore it). Each tile's region is new memory: with 4 KiB
/// pages its faults took a third of `repair --max-memory 400M` on the 4M jittered torus in 8 tiles
/// (17.8 s against 10.7 s with the tunable, 2 threads; peak RSS 377 MiB against 385 MiB), and
/// `mpirun -np 2 soup_topology_mpi --max-memory 400M` on that soup took 16.0-20.0 s against
/// 9.9-12.0 s with it (16 tiles, 1 thread a rank). A tunable is read when the
/// program starts, so this sets it and executes the program again with the same arguments
/// (`/proc/self/exe`), once: the environment then holds `GLIBC_TUNABLES`, which also leaves alone
/// a policy that the user set there. Where the program cannot be executed again, it goes on as
/// it is; returns only then. (A tool run under valgrind is followed into the second process only
/// with `--trace-children=yes`.) `arguments` are those after the program's name, `program` that name.
inline void restart_with_huge_page_mappings(const std::vector<std::string>& arguments,
                                            const std::string& program = "soup_topology")
{
#if defined(__GLIBC__) && !defined(SOUP_TOPOLOGY_TOOL_SANITIZED_ALLOCATOR)
  if(std::getenv("GLIBC_TUNABLES") != nullptr) return;
  if(setenv("GLIBC_TUNABLES", "glibc.malloc.hugetlb=1", 0) != 0) return;
  std::vector<std::string> words{program};
  words.insert(words.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for(std::string& word : words) argv.push_back(word.data());
  argv.push_back(nullptr);
  execv("/proc/self/exe", argv.data());
  unsetenv("GLIBC_TUNABLES"); // (not executed again: as it was)
#else
  (void)arguments;
  (void)program;
#endif
}

/// asks glibc to serve large blocks from the heap and to keep freed memory for reuse, and marks
/// the heap for huge pages (nothing where `memory_reuse_can_be_set` is false, or when the
/// environment sets `GLIBC_TUNABLES`); returns whether the policy was set.
inline bool keep_freed_memory_for_reuse()
{
#if defined(__GLIBC__) && !defined(SOUP_TOPOLOGY_TOOL_SANITIZED_ALLOCATOR)
  if(std::getenv("GLIBC_TUNABLES") != nullptr) return false;
  // mallopt returns 1 on success: both must take. A trim threshold of -1 disables trimming.
  if(!(mallopt(M_MMAP_MAX, 0) == 1 && mallopt(M_TRIM_THRESHOLD, -1) == 1)) return false;
  ask_for_huge_pages_on_the_heap();
  return true;
#else
  return false;
#endif
}

} // namespace soup_topology_tool

#endif // SOUP_TOPOLOGY_TOOLS_MEMORY_REUSE_H
