// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// libFuzzer target: triangulate_polygon() on a polygon read from the bytes, two signed bytes
// (x, y) per corner, in the plane z = x - y. Whatever the polygon (self-intersecting,
// repeated corners, collinear), it must give k - 2 triangles of its corners, the same twice,
// within the work cap.

#include <Soup_topology/internal/triangulate_polygon.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#define SOUP_FUZZ_CHECK(condition, what)                                                          \
  do {                                                                                            \
    if(!(condition)) {                                                                            \
      std::fprintf(stderr, "invariant violated: %s (%s) at %s:%d\n", #condition, what, __FILE__,   \
                   __LINE__);                                                                     \
      std::abort();                                                                               \
    }                                                                                             \
  } while(false)

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;
  std::vector<Point> points;
  for(std::size_t i = 0; i + 1 < size; i += 2)
  {
    const double x = static_cast<std::int8_t>(data[i]), y = static_cast<std::int8_t>(data[i + 1]);
    points.emplace_back(x, y, x - y);
  }
  std::vector<std::size_t> polygon(points.size());
  for(std::size_t i = 0; i < polygon.size(); ++i)
    polygon[i] = polygon.size() - 1 - i;
  std::vector<std::array<std::size_t, 3>> first, second;
  const std::size_t left = Soup_topology::internal::triangulate_polygon(points, polygon, first);
  Soup_topology::internal::triangulate_polygon(points, polygon, second);
  SOUP_FUZZ_CHECK(first == second, "not deterministic");
  const std::size_t k = polygon.size();
  if(k < 3)
  {
    SOUP_FUZZ_CHECK(first.empty() && left == k, "a short polygon gave triangles");
    return 0;
  }
  SOUP_FUZZ_CHECK(first.size() == k - 2, "not k - 2 triangles");
  SOUP_FUZZ_CHECK(left == 0 || (left >= 4 && left <= k), "corners left");
  for(const auto& t : first)
  {
    for(std::size_t v : t)
      SOUP_FUZZ_CHECK(v < k, "index out of range");
    SOUP_FUZZ_CHECK(t[0] != t[1] && t[1] != t[2] && t[2] != t[0], "repeated corner");
  }
  // every corner is used (a fan or an ear covers each one)
  std::vector<char> used(k, 0);
  for(const auto& t : first)
    for(std::size_t v : t)
      used[v] = 1;
  for(std::size_t i = 0; i < k; ++i)
    SOUP_FUZZ_CHECK(used[i], "a corner in no triangle");
  return 0;
}
