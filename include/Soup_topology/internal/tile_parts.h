// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The parts of a tiled repair: the owned triangles a tile keeps, on the points they use; their
// part files (written by the process that repairs the tile, read back by rank 0); and their merge
// into one soup in the canonical order.

#ifndef SOUP_TOPOLOGY_INTERNAL_TILE_PARTS_H
#define SOUP_TOPOLOGY_INTERNAL_TILE_PARTS_H

#include <Soup_topology/IO/Read_error.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <utility>
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

/// The parts of a merge held in memory, as `merge_in_canonical_order()` reads them: the points of
/// every part, then the triangles of every part, each freed as it is read.
class Parts_in_memory
{
public:
  explicit Parts_in_memory(std::vector<Soup_part>& parts) : parts_(parts) {}
  std::size_t size() const { return parts_.size(); }
  std::size_t number_of_points(std::size_t k) const { return parts_[k].points.size(); }
  std::size_t number_of_triangles(std::size_t k) const { return parts_[k].triangles.size(); }
  void append_points(std::size_t k, std::vector<std::array<double, 3>>& all)
  {
    all.insert(all.end(), parts_[k].points.begin(), parts_[k].points.end());
    std::vector<std::array<double, 3>>().swap(parts_[k].points);
  }
  std::vector<std::array<std::uint32_t, 3>> take_triangles(std::size_t k)
  {
    std::vector<std::array<std::uint32_t, 3>> out;
    out.swap(parts_[k].triangles);
    return out;
  }

private:
  std::vector<Soup_part>& parts_;
};

constexpr char part_file_magic[8] = {'S', 'T', 'P', 'A', 'R', 'T', '1', '\0'};

/// The part files of a merge (`write_part_file()`), as `merge_in_canonical_order()` reads them:
/// their headers are read and checked when it is made, then the points of every file, then the
/// triangles of every file; only what is being read is in memory. The files are removed with it.
class Part_files
{
public:
  explicit Part_files(std::vector<std::string> files) : files_(std::move(files))
  {
    for(const std::string& file : files_) {
      std::ifstream in(file, std::ios::binary);
      char magic[8];
      std::uint64_t sizes[2];
      if(!in.read(magic, 8) || std::memcmp(magic, part_file_magic, 8) != 0 ||
         !in.read(reinterpret_cast<char*>(sizes), sizeof sizes))
        throw IO::Read_error(file + ": not a part file of a tiled repair");
      in.seekg(0, std::ios::end);
      const std::uint64_t size = static_cast<std::uint64_t>(in.tellg());
      if(sizes[0] > size / 24 || sizes[1] > size / 12 || size != header_size + 24 * sizes[0] + 12 * sizes[1])
        throw IO::Read_error(file + ": truncated part file");
      sizes_.push_back({{sizes[0], sizes[1]}});
    }
  }
  Part_files(const Part_files&) = delete;
  Part_files& operator=(const Part_files&) = delete;
  ~Part_files()
  {
    for(const std::string& file : files_) std::remove(file.c_str());
  }

  std::size_t size() const { return files_.size(); }
  std::size_t number_of_points(std::size_t k) const { return std::size_t(sizes_[k][0]); }
  std::size_t number_of_triangles(std::size_t k) const { return std::size_t(sizes_[k][1]); }
  void append_points(std::size_t k, std::vector<std::array<double, 3>>& all) const
  {
    const std::size_t n = number_of_points(k), old = all.size();
    all.resize(old + n);
    read_at(k, header_size, reinterpret_cast<char*>(all.data() + old), 24 * n);
  }
  std::vector<std::array<std::uint32_t, 3>> take_triangles(std::size_t k) const
  {
    std::vector<std::array<std::uint32_t, 3>> out(number_of_triangles(k));
    read_at(k, header_size + 24 * sizes_[k][0], reinterpret_cast<char*>(out.data()), 12 * out.size());
    for(const auto& t : out)
      for(std::uint32_t v : t)
        if(v >= sizes_[k][0]) throw IO::Read_error(files_[k] + ": a triangle refers to a missing point");
    return out;
  }

private:
  static constexpr std::uint64_t header_size = 24; // the magic and the two sizes

  void read_at(std::size_t k, std::uint64_t offset, char* data, std::size_t bytes) const
  {
    std::ifstream in(files_[k], std::ios::binary);
    in.seekg(static_cast<std::streamoff>(offset));
    if(!in.read(data, static_cast<std::streamsize>(bytes))) throw IO::Read_error(files_[k] + ": read failed");
  }

  std::vector<std::string> files_;
  std::vector<std::array<std::uint64_t, 2>> sizes_; // points, triangles
};

/// the parts put together in the canonical order (`canonical_triangle_soup()`), the points of
/// different parts with equal coordinates merged. `Parts` is `Parts_in_memory` or `Part_files`:
/// the points of all parts are read first, then the triangles part by part. Memory: the points
/// of all parts and their order, 32 bytes each, then the output points (24 bytes each) and
/// triangles (12 bytes each) and one part's triangles.
template <class Parts>
void merge_in_canonical_order(Parts& parts, std::vector<CGAL::Epick::Point_3>& points,
                              std::vector<std::array<std::uint32_t, 3>>& triangles)
{
  std::vector<std::size_t> offset;
  std::size_t total = 0, total_triangles = 0;
  for(std::size_t part = 0; part < parts.size(); ++part) {
    offset.push_back(total);
    total += parts.number_of_points(part);
    total_triangles += parts.number_of_triangles(part);
  }
  std::vector<std::array<double, 3>> all;
  all.reserve(total);
  for(std::size_t part = 0; part < parts.size(); ++part) parts.append_points(part, all);
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
  for(std::size_t part = 0; part < parts.size(); ++part)
    for(const auto& t : parts.take_triangles(part)) {
      std::array<std::uint32_t, 3> g{{global[offset[part] + t[0]], global[offset[part] + t[1]], global[offset[part] + t[2]]}};
      std::rotate(g.begin(), std::min_element(g.begin(), g.end()), g.end());
      triangles.push_back(g);
    }
  std::sort(triangles.begin(), triangles.end());
}

/// the same for parts held in memory; the parts are emptied on the way.
inline void merge_in_canonical_order(std::vector<Soup_part>& parts, std::vector<CGAL::Epick::Point_3>& points,
                                     std::vector<std::array<std::uint32_t, 3>>& triangles)
{
  Parts_in_memory in_memory(parts);
  merge_in_canonical_order(in_memory, points, triangles);
}

/// the part file of tile `tile` in `folder`: `part_00042.bin`.
inline std::string part_file_name(const std::string& folder, std::size_t tile)
{
  std::string number = std::to_string(tile);
  if(number.size() < 5) number.insert(0, 5 - number.size(), '0');
  return folder + "/part_" + number + ".bin";
}

/// writes the kept triangles of a tile for the merge (`Part_files`): a header (magic, the numbers
/// of points and triangles), the points (three doubles each), the triangles (three 32-bit indices
/// each).
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

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_TILE_PARTS_H
