// Copyright (c) 2024 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Morton (Z-order) codes of 3D integer addresses, used by `Soup_topology::Octree`.

#ifndef SOUP_TOPOLOGY_INTERNAL_OCTREE_MORTON_H
#define SOUP_TOPOLOGY_INTERNAL_OCTREE_MORTON_H

#include <cstdint>

namespace Soup_topology {
namespace internal {

/// spreads the 21 low bits of `v` so that bit `i` moves to bit `3i`.
inline std::uint64_t morton_spread_3(std::uint32_t v)
{
  std::uint64_t x = v & 0x1fffffu;
  x = (x | (x << 32)) & 0x001f00000000ffffull;
  x = (x | (x << 16)) & 0x001f0000ff0000ffull;
  x = (x | (x << 8))  & 0x100f00f00f00f00full;
  x = (x | (x << 4))  & 0x10c30c30c30c30c3ull;
  x = (x | (x << 2))  & 0x1249249249249249ull;
  return x;
}

/// inverse of `morton_spread_3()`.
inline std::uint32_t morton_compact_3(std::uint64_t x)
{
  x &= 0x1249249249249249ull;
  x = (x | (x >> 2))  & 0x10c30c30c30c30c3ull;
  x = (x | (x >> 4))  & 0x100f00f00f00f00full;
  x = (x | (x >> 8))  & 0x001f0000ff0000ffull;
  x = (x | (x >> 16)) & 0x001f00000000ffffull;
  x = (x | (x >> 32)) & 0x1fffffull;
  return static_cast<std::uint32_t>(x);
}

/// interleaves three addresses of at most 21 bits; the bits of `x` are the most significant of
/// each triple, so that the three bits of one level form the octant `4*bx + 2*by + bz`.
inline std::uint64_t morton_encode_3(std::uint32_t x, std::uint32_t y, std::uint32_t z)
{
  return (morton_spread_3(x) << 2) | (morton_spread_3(y) << 1) | morton_spread_3(z);
}

inline void morton_decode_3(std::uint64_t code, std::uint32_t& x, std::uint32_t& y, std::uint32_t& z)
{
  x = morton_compact_3(code >> 2);
  y = morton_compact_3(code >> 1);
  z = morton_compact_3(code);
}

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_OCTREE_MORTON_H
