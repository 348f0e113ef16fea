// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// What the libFuzzer targets share: the checks of a soup that a reader returned, and the read of
// the bytes through a per-process temporary file by read_triangle_soup() (fuzz_common.cpp). A
// check that fails prints what it found and calls abort(), which libFuzzer reports as a crash with
// the input that caused it.

#ifndef SOUP_TOPOLOGY_FUZZ_COMMON_H
#define SOUP_TOPOLOGY_FUZZ_COMMON_H

#include <Soup_topology/IO/Read_error.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace soup_fuzz {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = std::array<std::size_t, 3>;

#define SOUP_FUZZ_CHECK(condition, what)                                                          \
  do {                                                                                            \
    if(!(condition)) {                                                                            \
      std::fprintf(stderr, "invariant violated: %s (%s) at %s:%d\n", #condition, std::string(what).c_str(), \
                   __FILE__, __LINE__);                                                           \
      std::abort();                                                                               \
    }                                                                                             \
  } while(false)

/// reads `data` as a file with extension `ext` through read_triangle_soup(): either a
/// documented exception with the caller's containers unchanged, or a valid soup (the checks of
/// fuzz_common.cpp, compiled once for the targets that call it).
void read_through_file(const std::uint8_t* data, std::size_t size, const std::string& ext);

/// calls `read(points, polygons)`, a reader of polygons that appends to its containers and
/// returns a report of `vertices` and `faces`, on containers that already hold 2 points and 1
/// polygon: either it appends what its report counts, with finite coordinates and indices into
/// the appended points, or it throws `Read_error` with the containers unchanged and a message
/// that starts with `message_start` (`missing` names what the message lacks otherwise).
template <class Read>
void check_polygon_reader(const Read& read, const std::string& message_start, const std::string& missing)
{
  std::vector<Point> points(2);
  std::vector<std::vector<std::size_t>> polygons(1);
  try {
    const auto r = read(points, polygons);
    SOUP_FUZZ_CHECK(points.size() == 2 + r.vertices && polygons.size() == 1 + r.faces, "counts");
    for(std::size_t f = 1; f < polygons.size(); ++f)
      for(std::size_t v : polygons[f]) SOUP_FUZZ_CHECK(v >= 2 && v < points.size(), "index out of range");
    for(const auto& p : points)
      SOUP_FUZZ_CHECK(std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()), "non-finite point");
  } catch(const Soup_topology::IO::Read_error& e) {
    SOUP_FUZZ_CHECK(points.size() == 2 && polygons.size() == 1, "containers changed by a failed read");
    SOUP_FUZZ_CHECK(std::string(e.what()).rfind(message_start, 0) == 0, missing + " in " + e.what());
  }
}

} // namespace soup_fuzz

#endif // SOUP_TOPOLOGY_FUZZ_COMMON_H
