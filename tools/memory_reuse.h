// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// How the command-line tools ask the C library to manage their memory.
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
// its own mapping, and the top of the heap is not given back. This is the program's choice, not
// the library's: the headers do not call it, and an application that links the library keeps its
// own policy. Results do not depend on it. The cost is a peak resident memory a few percent higher
// (freed blocks that are not reused exactly); `Performance.md` has the measurements. That is why
// `repair --max-memory` keeps glibc's default: its limit is modelled and measured with freed
// memory given back. A user who sets `GLIBC_TUNABLES` keeps the policy given there.

#ifndef SOUP_TOPOLOGY_TOOLS_MEMORY_REUSE_H
#define SOUP_TOPOLOGY_TOOLS_MEMORY_REUSE_H

#include <climits>
#include <cstdlib>

#if defined(__GLIBC__)
#include <malloc.h>
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

/// asks glibc to serve large blocks from the heap and to keep freed memory for reuse (nothing
/// where `memory_reuse_can_be_set` is false, or when the environment sets `GLIBC_TUNABLES`);
/// returns whether the policy was set.
inline bool keep_freed_memory_for_reuse()
{
#if defined(__GLIBC__) && !defined(SOUP_TOPOLOGY_TOOL_SANITIZED_ALLOCATOR)
  if(std::getenv("GLIBC_TUNABLES") != nullptr) return false;
  // mallopt returns 1 on success: both must take.
  return mallopt(M_MMAP_MAX, 0) == 1 && mallopt(M_TRIM_THRESHOLD, INT_MAX) == 1;
#else
  return false;
#endif
}

} // namespace soup_topology_tool

#endif // SOUP_TOPOLOGY_TOOLS_MEMORY_REUSE_H
