// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// A `std::vector` whose `resize(n)` leaves the new elements of a trivial type uninitialized: for
// the large tables that a pass writes whole right after (on TBB's threads), so that the memory is
// first touched, and its pages faulted in, by the threads that fill it rather than zeroed by one
// thread before.

#ifndef SOUP_TOPOLOGY_INTERNAL_UNINITIALIZED_VECTOR_H
#define SOUP_TOPOLOGY_INTERNAL_UNINITIALIZED_VECTOR_H

#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace Soup_topology {
namespace internal {

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

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_UNINITIALIZED_VECTOR_H
