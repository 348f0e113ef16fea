// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The read of a fuzz input through a file by read_triangle_soup() (fuzz_common.h): every format's
// reader, the weld and the triangulation of polygons, compiled once for all the targets.

#include "fuzz_common.h"

#include <Soup_topology/IO/read_triangle_soup.h>
#include <Soup_topology/Invalid_input.h>

#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace soup_fuzz {
namespace {

/// a file name for this process, with the extension `ext`, removed at exit.
const std::string& temporary_file(const std::string& ext)
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

void write_file(const std::string& path, const std::uint8_t* data, std::size_t size)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  SOUP_FUZZ_CHECK(static_cast<bool>(out), "cannot write the temporary file " + path);
}

/// what read_triangle_soup() promises about its result.
void check_read_soup(const std::vector<Point>& points, const std::vector<Triangle>& triangles,
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

} // namespace

void read_through_file(const std::uint8_t* data, std::size_t size, const std::string& ext)
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
