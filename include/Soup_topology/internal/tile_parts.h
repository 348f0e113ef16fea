// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The parts of a tiled repair: the owned triangles a tile keeps, on the points they use; their
// part files (written by each process of a team, read by rank 0); and their merge into one soup
// in the canonical order.

#ifndef SOUP_TOPOLOGY_INTERNAL_TILE_PARTS_H
#define SOUP_TOPOLOGY_INTERNAL_TILE_PARTS_H

#include <Soup_topology/IO/Read_error.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace Soup_topology {
namespace internal {

/// a part of a soup: its points (each used by a triangle, none repeated within the part) and its
/// triangles.
struct Soup_part
{
  std::vector<std::array<double, 3>> points;
  std::vector<std::array<std::uint32_t, 3>> triangles;
};

/// the parts put together in the canonical order (`canonical_triangle_soup()`), the points of
/// different parts with equal coordinates merged; the parts are emptied on the way. Memory: the
/// points of all parts, 32 bytes each, and the triangles, 12 bytes each (a part's are freed as
/// they are copied).
inline void merge_in_canonical_order(std::vector<Soup_part>& parts, std::vector<CGAL::Epick::Point_3>& points,
                                     std::vector<std::array<std::uint32_t, 3>>& triangles)
{
  std::vector<std::array<double, 3>> all;
  std::vector<std::size_t> offset;
  std::size_t total = 0, total_triangles = 0;
  for(const Soup_part& p : parts) {
    offset.push_back(total);
    total += p.points.size();
    total_triangles += p.triangles.size();
  }
  all.reserve(total);
  for(Soup_part& p : parts) {
    all.insert(all.end(), p.points.begin(), p.points.end());
    std::vector<std::array<double, 3>>().swap(p.points);
  }
  std::vector<std::uint32_t> order(total);
  for(std::size_t i = 0; i < total; ++i) order[i] = static_cast<std::uint32_t>(i);
  std::sort(order.begin(), order.end(), [&](std::uint32_t x, std::uint32_t y) { return all[x] < all[y]; });
  std::vector<std::uint32_t> global(total);
  // The output points at their exact number: growing them by doubling would hold up to twice as
  // many through the steps after the merge (a third of the orientation's peak at 40M triangles).
  std::size_t distinct = 0;
  for(std::size_t k = 0; k < total; ++k) distinct += std::size_t(k == 0 || all[order[k - 1]] != all[order[k]]);
  points.clear();
  points.shrink_to_fit();
  points.reserve(distinct);
  for(std::size_t k = 0; k < total; ++k) {
    const std::array<double, 3>& q = all[order[k]];
    if(k == 0 || all[order[k - 1]] != q) points.emplace_back(q[0], q[1], q[2]);
    global[order[k]] = static_cast<std::uint32_t>(points.size() - 1);
  }
  std::vector<std::uint32_t>().swap(order);
  std::vector<std::array<double, 3>>().swap(all);
  triangles.clear();
  triangles.reserve(total_triangles);
  for(std::size_t part = 0; part < parts.size(); ++part) {
    for(const auto& t : parts[part].triangles) {
      std::array<std::uint32_t, 3> g{{global[offset[part] + t[0]], global[offset[part] + t[1]], global[offset[part] + t[2]]}};
      std::rotate(g.begin(), std::min_element(g.begin(), g.end()), g.end());
      triangles.push_back(g);
    }
    std::vector<std::array<std::uint32_t, 3>>().swap(parts[part].triangles);
  }
  std::sort(triangles.begin(), triangles.end());
}

/// the part file of tile `tile` in `folder`: `part_00042.bin`.
inline std::string part_file_name(const std::string& folder, std::size_t tile)
{
  std::string number = std::to_string(tile);
  if(number.size() < 5) number.insert(0, 5 - number.size(), '0');
  return folder + "/part_" + number + ".bin";
}

constexpr char part_file_magic[8] = {'S', 'T', 'P', 'A', 'R', 'T', '1', '\0'};

/// writes the kept triangles of a tile for rank 0's merge: a header (magic, the numbers of points
/// and triangles), the points (three doubles each), the triangles (three 32-bit indices each).
inline void write_part_file(const std::string& file, const Soup_part& part)
{
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  const std::uint64_t sizes[2] = {part.points.size(), part.triangles.size()};
  out.write(part_file_magic, 8);
  out.write(reinterpret_cast<const char*>(sizes), sizeof sizes);
  out.write(reinterpret_cast<const char*>(part.points.data()), std::streamsize(24 * part.points.size()));
  out.write(reinterpret_cast<const char*>(part.triangles.data()), std::streamsize(12 * part.triangles.size()));
  if(!out.flush()) throw IO::Write_error(file + ": write failed");
}

inline Soup_part read_part_file(const std::string& file)
{
  std::ifstream in(file, std::ios::binary);
  char magic[8];
  std::uint64_t sizes[2];
  if(!in.read(magic, 8) || std::memcmp(magic, part_file_magic, 8) != 0 || !in.read(reinterpret_cast<char*>(sizes), sizeof sizes))
    throw IO::Read_error(file + ": not a part file of a tiled repair");
  in.seekg(0, std::ios::end);
  const std::uint64_t size = static_cast<std::uint64_t>(in.tellg());
  if(sizes[0] > size / 24 || sizes[1] > size / 12 || size != 24 + 24 * sizes[0] + 12 * sizes[1])
    throw IO::Read_error(file + ": truncated part file");
  in.seekg(24);
  Soup_part part;
  part.points.resize(sizes[0]);
  part.triangles.resize(sizes[1]);
  in.read(reinterpret_cast<char*>(part.points.data()), std::streamsize(24 * sizes[0]));
  in.read(reinterpret_cast<char*>(part.triangles.data()), std::streamsize(12 * sizes[1]));
  if(!in) throw IO::Read_error(file + ": read failed");
  for(const auto& t : part.triangles)
    for(std::uint32_t v : t)
      if(v >= part.points.size()) throw IO::Read_error(file + ": a triangle refers to a missing point");
  return part;
}

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_TILE_PARTS_H
