// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// This file is part of Soup_topology, a header-only C++17 library that rebuilds the topology
// of triangle soups.

#ifndef SOUP_TOPOLOGY_TRIANGLE_STRIPS_H
#define SOUP_TOPOLOGY_TRIANGLE_STRIPS_H

#include <Soup_topology/index_triangles.h>

#include <cstddef>
#include <iterator>
#include <type_traits>
#include <utility>

/// \file triangle_strips.h
/// Adapters from OpenGL-style triangle strips and triangle fans to independent triangles,
/// so that a soup given as strips or fans goes straight into the pipeline.
///
/// Conventions (those of OpenGL's `GL_TRIANGLE_STRIP` and `GL_TRIANGLE_FAN`):
/// - strip `v_0 v_1 ... v_{n-1}`: triangle `k` (0 <= k < n-2) is `(v_k, v_{k+1}, v_{k+2})` for
///   even `k` and `(v_{k+1}, v_k, v_{k+2})` for odd `k`, so that every triangle of the strip
///   has the orientation of the first one;
/// - fan `v_0 v_1 ... v_{n-1}`: triangle `k` is `(v_0, v_{k+1}, v_{k+2})`;
/// - a primitive-restart index ends the current strip (fan) and starts a new one; the parity
///   of a strip is counted from its own first vertex;
/// - a triangle with two equal indices (the degenerate triangles used to join strips) is
///   dropped and counted, it is never appended;
/// - a strip (fan) of fewer than 3 vertices gives no triangle and is counted as short.
///
/// Indices are copied as they are (no range check: the point count is not known here).

namespace Soup_topology {

/// \ingroup PkgSoupTopologyIO
/// What `append_triangle_strip()` and `append_triangle_fan()` did.
struct Strip_conversion_report
{
  std::size_t number_of_primitives = 0;             ///< strips (fans) of at least one vertex, after splitting at restarts
  std::size_t number_of_short_primitives = 0;       ///< strips (fans) of 1 or 2 vertices: no triangle
  std::size_t number_of_triangles = 0;              ///< triangles appended
  std::size_t number_of_degenerate_triangles = 0;   ///< triangles with a repeated index, dropped

  Strip_conversion_report& operator+=(const Strip_conversion_report& other)
  {
    number_of_primitives += other.number_of_primitives;
    number_of_short_primitives += other.number_of_short_primitives;
    number_of_triangles += other.number_of_triangles;
    number_of_degenerate_triangles += other.number_of_degenerate_triangles;
    return *this;
  }
};

namespace internal {

template <typename Index>
bool is_degenerate_triangle(const Index& a, const Index& b, const Index& c)
{
  return a == b || b == c || c == a;
}

// Shared driver of strips and fans; `is_restart(v)` tells whether the value `v` ends the
// current primitive.
template <bool is_strip, typename IndexRange, typename TriangleRange, typename IsRestart>
Strip_conversion_report append_primitives(const IndexRange& indices,
                                          TriangleRange& triangles,
                                          const IsRestart& is_restart)
{
  using Face = typename TriangleRange::value_type;
  using std::begin;
  using std::end;
  using Index = std::decay_t<decltype(*begin(indices))>;

  Strip_conversion_report report;
  std::size_t count = 0;          // vertices of the current primitive so far
  Index first{}, previous{}, last{};  // fan centre / strip window: previous, last
  auto push = [&](const Index& a, const Index& b, const Index& c) {
    if(is_degenerate_triangle(a, b, c))
    {
      ++report.number_of_degenerate_triangles;
      return;
    }
    triangles.push_back(make_triangle<Face>(static_cast<std::size_t>(a), static_cast<std::size_t>(b),
                                            static_cast<std::size_t>(c)));
    ++report.number_of_triangles;
  };
  auto close = [&]() {
    if(count == 0)
      return;
    ++report.number_of_primitives;
    if(count < 3)
      ++report.number_of_short_primitives;
    count = 0;
  };

  for(auto it = begin(indices); it != end(indices); ++it)
  {
    const Index v = *it;
    if(is_restart(v))
    {
      close();
      continue;
    }
    if(count == 0)
      first = v;
    else if(count >= 2)
    {
      if constexpr(is_strip)
      {
        // triangle k = count - 2 of this strip
        if(((count - 2) & 1) == 0)
          push(previous, last, v);
        else
          push(last, previous, v);
      }
      else
        push(first, last, v);
    }
    previous = last;
    last = v;
    ++count;
  }
  close();
  return report;
}

} // namespace internal

/// \ingroup PkgSoupTopologyIO
/// appends to `triangles` the triangles of the triangle strip(s) `indices`, with the alternating
/// orientation of OpenGL strips undone: every triangle keeps the orientation of the first one.
/// Triangles with a repeated index (strip joins) are dropped and counted.
///
/// \tparam IndexRange a range of vertex indices (`std::vector<int>`, `std::vector<std::uint32_t>`, ...)
/// \tparam TriangleRange a back-insertion sequence whose value type is a random-access range of 3
///         indices (`std::array<std::size_t,3>`, `std::vector<int>`, ...)
/// \param indices the vertex indices of the strip
/// \param triangles the triangles, to which the triangles of the strip are appended
/// \return what was appended and dropped
template <typename IndexRange, typename TriangleRange>
Strip_conversion_report append_triangle_strip(const IndexRange& indices, TriangleRange& triangles)
{
  return internal::append_primitives<true>(indices, triangles, [](const auto&) { return false; });
}

/// \ingroup PkgSoupTopologyIO
/// same as above, with every occurrence of `restart_index` (OpenGL's primitive restart, e.g.
/// `0xFFFFFFFF` or `-1`) ending the current strip and starting a new one.
/// \param indices the vertex indices of the strips, separated by `restart_index`
/// \param triangles the triangles, to which the triangles of the strips are appended
/// \param restart_index the index that ends a strip (compared after conversion to the index type)
/// \return what was appended and dropped
template <typename IndexRange, typename TriangleRange, typename Index>
Strip_conversion_report append_triangle_strip(const IndexRange& indices, TriangleRange& triangles,
                                              const Index& restart_index)
{
  return internal::append_primitives<true>(indices, triangles,
                                           [&](const auto& v) { return v == static_cast<std::decay_t<decltype(v)>>(restart_index); });
}

/// \ingroup PkgSoupTopologyIO
/// appends to `triangles` the triangles of the triangle fan(s) `indices`: triangle `k` is
/// `(v_0, v_{k+1}, v_{k+2})`. Triangles with a repeated index are dropped and counted.
/// \tparam IndexRange as for `append_triangle_strip()`
/// \tparam TriangleRange as for `append_triangle_strip()`
/// \param indices the vertex indices of the fan, its center first
/// \param triangles the triangles, to which the triangles of the fan are appended
/// \return what was appended and dropped
template <typename IndexRange, typename TriangleRange>
Strip_conversion_report append_triangle_fan(const IndexRange& indices, TriangleRange& triangles)
{
  return internal::append_primitives<false>(indices, triangles, [](const auto&) { return false; });
}

/// \ingroup PkgSoupTopologyIO
/// same as above, with every occurrence of `restart_index` ending the current fan and starting
/// another one (whose first vertex is its center).
/// \param indices the vertex indices of the fans, separated by `restart_index`
/// \param triangles the triangles, to which the triangles of the fans are appended
/// \param restart_index the index that ends a fan (compared after conversion to the index type)
/// \return what was appended and dropped
template <typename IndexRange, typename TriangleRange, typename Index>
Strip_conversion_report append_triangle_fan(const IndexRange& indices, TriangleRange& triangles,
                                            const Index& restart_index)
{
  return internal::append_primitives<false>(indices, triangles,
                                            [&](const auto& v) { return v == static_cast<std::decay_t<decltype(v)>>(restart_index); });
}

/// \ingroup PkgSoupTopologyIO
/// appends the triangles of every strip of `strips` (a range of index ranges, one strip each,
/// as `glMultiDrawElements` takes them).
/// \param strips the strips, each a range of vertex indices
/// \param triangles the triangles, to which the triangles of the strips are appended
/// \return the sum of the reports of the strips
template <typename StripRange, typename TriangleRange>
Strip_conversion_report append_triangle_strips(const StripRange& strips, TriangleRange& triangles)
{
  Strip_conversion_report report;
  for(const auto& strip : strips)
    report += append_triangle_strip(strip, triangles);
  return report;
}

/// \ingroup PkgSoupTopologyIO
/// appends the triangles of every fan of `fans` (a range of index ranges, one fan each).
/// \param fans the fans, each a range of vertex indices, its center first
/// \param triangles the triangles, to which the triangles of the fans are appended
/// \return the sum of the reports of the fans
template <typename FanRange, typename TriangleRange>
Strip_conversion_report append_triangle_fans(const FanRange& fans, TriangleRange& triangles)
{
  Strip_conversion_report report;
  for(const auto& fan : fans)
    report += append_triangle_fan(fan, triangles);
  return report;
}

} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_TRIANGLE_STRIPS_H
