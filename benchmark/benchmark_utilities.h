// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// What the benchmark programs share: the CPU time of the calling thread, the peak resident
// memory, the bounding-box diagonal that their tolerances are relative to, and binary STL files
// of exploded soups for the command-line and file-reading cases.

#ifndef SOUP_TOPOLOGY_BENCHMARK_UTILITIES_H
#define SOUP_TOPOLOGY_BENCHMARK_UTILITIES_H

#include <CGAL/Bbox_3.h>

#include <sys/resource.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <ctime>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace soup_benchmark {

/// the CPU time of the calling thread, in milliseconds (for the per-phase counters)
inline double thread_cpu_ms()
{
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return 1e3 * static_cast<double>(ts.tv_sec) + 1e-6 * static_cast<double>(ts.tv_nsec);
}

/// the peak resident memory of the process so far, in bytes (getrusage)
inline double peak_resident_bytes()
{
  rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  return 1024.0 * static_cast<double>(usage.ru_maxrss);
}

/// the minor page faults of the process so far (getrusage): the pages of fresh memory touched,
/// a count that does not change from run to run where the times do
inline double minor_page_faults()
{
  rusage usage;
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_minflt);
}

/// the length of the diagonal of the bounding box of `points`
template <class Point>
double diagonal(const std::vector<Point>& points)
{
  CGAL::Bbox_3 box;
  for(const Point& p : points) box += p.bbox();
  const double dx = box.xmax() - box.xmin(), dy = box.ymax() - box.ymin(), dz = box.zmax() - box.zmin();
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

/// writes the triangles of `soup` (three points each, coordinates rounded to float, normals and
/// attributes zero) as a binary STL file whose 80-byte header starts with `header`
template <class Point>
void write_binary_STL(const std::string& file, const std::vector<std::array<Point, 3>>& soup,
                      const std::string& header = std::string())
{
  std::string bytes(80, '\0');
  std::memcpy(&bytes[0], header.data(), std::min<std::size_t>(header.size(), 79));
  const std::uint32_t n = static_cast<std::uint32_t>(soup.size());
  bytes.append(reinterpret_cast<const char*>(&n), 4);
  for(const std::array<Point, 3>& t : soup) {
    float f[12] = {};
    for(std::size_t k = 0; k < 3; ++k)
      for(int d = 0; d < 3; ++d) f[3 + 3 * k + static_cast<std::size_t>(d)] = static_cast<float>(t[k][d]);
    bytes.append(reinterpret_cast<const char*>(f), sizeof f);
    bytes.append(2, '\0');
  }
  std::ofstream out(file, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if(!out) throw std::runtime_error("cannot write " + file);
}

} // namespace soup_benchmark

#endif // SOUP_TOPOLOGY_BENCHMARK_UTILITIES_H
