// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// What the libFuzzer targets share: a per-process temporary file for the readers that take a
// file name, and the checks of a soup that a reader returned. A check that fails prints what it
// found and calls abort(), which libFuzzer reports as a crash with the input that caused it.

#ifndef SOUP_TOPOLOGY_FUZZ_COMMON_H
#define SOUP_TOPOLOGY_FUZZ_COMMON_H

#include <Soup_topology/IO/Read_error.h>
#include <Soup_topology/IO/read_triangle_soup.h>
#include <Soup_topology/Invalid_input.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>
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

/// a file name for this process, with the extension `ext`, removed at exit.
inline const std::string& temporary_file(const std::string& ext)
{
  static const std::string path = [&] {
    const std::string p = (std::filesystem::temp_directory_path() /
                           ("soup_topology_fuzz_" + std::to_string(::getpid()) + "." + ext)).string();
    static std::string for_exit;
    for_exit = p;
    std::atexit([] { std::remove(for_exit.c_str()); });
    return p;
  }();
  return path;
}

inline void write_file(const std::string& path, const std::uint8_t* data, std::size_t size)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  SOUP_FUZZ_CHECK(static_cast<bool>(out), "cannot write the temporary file " + path);
}

/// what read_triangle_soup() promises about its result.
inline void check_read_soup(const std::vector<Point>& points, const std::vector<Triangle>& triangles,
                            const Soup_topology::IO::Soup_read_report& report)
{
  for(const Point& p : points)
    SOUP_FUZZ_CHECK(std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()), "non-finite point read");
  for(std::size_t i = 1; i < points.size(); ++i)
    SOUP_FUZZ_CHECK(points[i] != points[i - 1] || points.size() < 2, "consecutive equal points after the exact weld");
  for(const Triangle& t : triangles) {
    for(std::size_t v : t) SOUP_FUZZ_CHECK(v < points.size(), "index out of range");
    SOUP_FUZZ_CHECK(t[0] != t[1] && t[1] != t[2] && t[2] != t[0], "repeated index");
  }
  SOUP_FUZZ_CHECK(report.input_triangles == triangles.size() + report.collapsed_triangles, "triangle count");
}

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

/// reads `data` as a file with extension `ext` through read_triangle_soup(): either a
/// documented exception with the caller's containers unchanged, or a valid soup.
inline void read_through_file(const std::uint8_t* data, std::size_t size, const std::string& ext)
{
  const std::string& path = temporary_file(ext);
  write_file(path, data, size);
  std::vector<Point> points{Point(1, 2, 3)};
  std::vector<Triangle> triangles{{0, 0, 0}};
  try {
    const Soup_topology::IO::Soup_read_report report =
      Soup_topology::IO::read_triangle_soup(path, points, triangles);
    check_read_soup(points, triangles, report);
  } catch(const Soup_topology::IO::Read_error&) {
    SOUP_FUZZ_CHECK(points.size() == 1 && triangles.size() == 1, "containers changed by a failed read");
  } catch(const Soup_topology::Invalid_input&) {
    SOUP_FUZZ_CHECK(points.size() == 1 && triangles.size() == 1, "containers changed by a failed read");
  }
}

} // namespace soup_fuzz

#endif // SOUP_TOPOLOGY_FUZZ_COMMON_H
