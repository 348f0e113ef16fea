// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The cut of a triangle soup into tiles, the first step of the tiled repair
// (doc/Soup_topology/Tiled_repair_design.md, doc/Soup_topology/Tiling.md): the soup is streamed to
// find its bounding cube and a histogram of the Morton cells of its triangles, the cells are cut
// into contiguous ranges of balanced triangle counts (the tiles), and the soup is streamed again
// into one spill file per tile holding the triangles the tile owns and those of its halo.

#ifndef SOUP_TOPOLOGY_SOUP_TILING_H
#define SOUP_TOPOLOGY_SOUP_TILING_H

#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/IO/Read_error.h>
#include <Soup_topology/IO/STL.h>

#include <CGAL/number_utils.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace Soup_topology {

/// \ingroup PkgSoupTopologyTiling
/// the corners of one input triangle, in double.
using Tile_corners = std::array<std::array<double, 3>, 3>;

namespace internal {

// the bits of `v` (at most 21) spread to every third bit
inline std::uint64_t spread_by_three(std::uint64_t v)
{
  std::uint64_t x = v & 0x1fffff;
  x = (x | x << 32) & 0x1f00000000ffffULL;
  x = (x | x << 16) & 0x1f0000ff0000ffULL;
  x = (x | x << 8) & 0x100f00f00f00f00fULL;
  x = (x | x << 4) & 0x10c30c30c30c30c3ULL;
  x = (x | x << 2) & 0x1249249249249249ULL;
  return x;
}

inline std::uint64_t gather_every_third(std::uint64_t x)
{
  x &= 0x1249249249249249ULL;
  x = (x | x >> 2) & 0x10c30c30c30c30c3ULL;
  x = (x | x >> 4) & 0x100f00f00f00f00fULL;
  x = (x | x >> 8) & 0x1f0000ff0000ffULL;
  x = (x | x >> 16) & 0x1f00000000ffffULL;
  x = (x | x >> 32) & 0x1fffff;
  return x;
}

} // namespace internal

class Tile_plan;
template <class TriangleSource>
Tile_plan plan_tiles(const TriangleSource& source, std::size_t number_of_tiles, double halo, unsigned level = 7);

/// \ingroup PkgSoupTopologyTiling
/// \brief the cut of space into tiles: the bounding cube of a soup, divided into `8^level`
/// Morton cells, and the tiles as contiguous ranges of cells.
///
/// Every point of the cube lies in exactly one cell (cells are half-open, the last ones closed on
/// the far faces of the cube), so in exactly one tile. A triangle is **owned** by the tile of its
/// *anchor*, the lexicographically smallest of its corners (no arithmetic: the same corner on any
/// machine). A tile's **region** is its cells grown by the halo; the tiles whose region a triangle
/// may meet are `tiles_meeting()`: a superset, decided on the triangle's bounding box grown by the
/// halo and by a margin that covers the rounding of the cell computation, so that no triangle
/// meeting a region is ever left out of it.
///
/// Made by `plan_tiles()`; the cut depends only on the multiset of the triangles, not on their
/// order.
class Tile_plan
{
public:
  using Point = std::array<double, 3>;

  /// the number of tiles (some may own no triangle: a cell is never split)
  std::size_t number_of_tiles() const { return first_cell_.empty() ? 0 : first_cell_.size() - 1; }
  /// the cells of tile `t` are `first_cell(t)`, ..., `first_cell(t + 1) - 1` in Morton order
  std::uint64_t first_cell(std::size_t t) const { return first_cell_[t]; }
  /// the number of cells per side is `2^level()`
  unsigned level() const { return level_; }
  /// the halo: a tile's region is its cells grown by it
  double halo() const { return halo_; }
  /// the same cut with another halo (finite, non-negative).
  /// \throws Invalid_input for a bad halo
  Tile_plan with_halo(double halo) const
  {
    if(!(halo >= 0 && halo <= std::numeric_limits<double>::max()))
      throw Invalid_input("Tile_plan::with_halo: the halo must be finite and non-negative");
    Tile_plan plan = *this;
    plan.halo_ = halo;
    return plan;
  }
  /// the corner of the cube with the smallest coordinates
  const Point& origin() const { return origin_; }
  /// the side of the cube
  double side() const { return side_; }
  /// the number of triangles the tile `t` owns, counted when the plan was made
  std::size_t owned_triangles(std::size_t t) const { return owned_[t]; }
  /// the number of triangles of the soup the plan was made from
  std::size_t number_of_triangles() const { return triangles_; }
  /// the mean length of the edges of the soup's triangles (0 without triangles)
  double mean_edge_length() const { return mean_edge_length_; }
  /// `true` if tile `t` holds every cell: its region is the whole cube, which holds the soup
  bool holds_every_cell(std::size_t t) const
  {
    return first_cell_[t] == 0 && first_cell_[t + 1] == (std::uint64_t(1) << (3 * level_));
  }

  /// the integer address of the cell holding coordinate `x` along `axis` (clamped to the cube)
  std::uint64_t cell_address(double x, std::size_t axis) const
  {
    const double cells = std::ldexp(1.0, int(level_));
    const double c = std::floor((x - origin_[axis]) / side_ * cells);
    if(!(c > 0)) return 0;
    if(c >= cells) return std::uint64_t(cells) - 1;
    return std::uint64_t(c);
  }
  /// the Morton code of the cell holding `p`
  std::uint64_t cell_of(const Point& p) const
  {
    return internal::spread_by_three(cell_address(p[0], 0)) << 2 | internal::spread_by_three(cell_address(p[1], 1)) << 1 |
           internal::spread_by_three(cell_address(p[2], 2));
  }
  /// the tile whose range holds the cell `code`
  std::size_t tile_of_cell(std::uint64_t code) const
  {
    return static_cast<std::size_t>(std::upper_bound(first_cell_.begin() + 1, first_cell_.end() - 1, code) -
                                    (first_cell_.begin() + 1));
  }
  /// the corner of a triangle that decides its owner: the lexicographically smallest
  static Point anchor(const Tile_corners& c) { return std::min({c[0], c[1], c[2]}); }
  /// the tile that owns the triangle with corners `c`
  std::size_t owner(const Tile_corners& c) const { return tile_of_cell(cell_of(anchor(c))); }

  /// writes to `out`, in increasing order, every tile whose region the triangle with corners `c`
  /// may meet (its owner among them). A bounding box over at most `cell_limit` cells is
  /// answered cell by cell, a larger one against the aligned blocks of every tile.
  template <typename OutputIterator>
  OutputIterator tiles_meeting(const Tile_corners& c, OutputIterator out, std::size_t cell_limit = 512) const
  {
    std::vector<std::size_t> tiles;
    collect_tiles_meeting(c, tiles, cell_limit);
    return std::copy(tiles.begin(), tiles.end(), out);
  }

  /// `tiles_meeting()` into `tiles` (cleared first), whose storage a caller reuses.
  void collect_tiles_meeting(const Tile_corners& c, std::vector<std::size_t>& tiles, std::size_t cell_limit = 512) const
  {
    std::array<std::uint64_t, 3> lo, hi;
    for(std::size_t i = 0; i < 3; ++i) {
      const double a = std::min({c[0][i], c[1][i], c[2][i]}), b = std::max({c[0][i], c[1][i], c[2][i]});
      const double grow = halo_ + margin_;
      lo[i] = cell_address(a - grow, i);
      hi[i] = cell_address(b + grow, i);
    }
    const std::uint64_t cells = (hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1);
    tiles.clear();
    if(cells <= cell_limit) {
      for(std::uint64_t x = lo[0]; x <= hi[0]; ++x)
        for(std::uint64_t y = lo[1]; y <= hi[1]; ++y)
          for(std::uint64_t z = lo[2]; z <= hi[2]; ++z)
            tiles.push_back(tile_of_cell(internal::spread_by_three(x) << 2 | internal::spread_by_three(y) << 1 |
                                         internal::spread_by_three(z)));
      std::sort(tiles.begin(), tiles.end());
      tiles.erase(std::unique(tiles.begin(), tiles.end()), tiles.end());
    }
    else
      for(std::size_t t = 0; t < number_of_tiles(); ++t)
        for(std::size_t b = block_begin_[t]; b != block_begin_[t + 1]; ++b)
          if(block_meets(blocks_[b], lo, hi)) {
            tiles.push_back(t);
            break;
          }
  }

  /// the boxes of the aligned blocks of tile `t`'s cells, `{xmin, ymin, zmin, xmax, ymax, zmax}`
  /// each (their union is the tile's cells, up to the rounding of the cells' bounds).
  std::vector<std::array<double, 6>> block_boxes(std::size_t t) const
  {
    const double cell_side = side_ / std::ldexp(1.0, int(level_));
    std::vector<std::array<double, 6>> boxes;
    for(std::size_t b = block_begin_[t]; b != block_begin_[t + 1]; ++b) {
      const std::uint64_t corner[3] = {internal::gather_every_third(blocks_[b].first >> 2),
                                       internal::gather_every_third(blocks_[b].first >> 1),
                                       internal::gather_every_third(blocks_[b].first)};
      const double width = double(std::uint64_t(1) << blocks_[b].size_level) * cell_side;
      std::array<double, 6> box;
      for(std::size_t i = 0; i < 3; ++i) {
        box[i] = origin_[i] + double(corner[i]) * cell_side;
        box[i + 3] = box[i] + width;
      }
      boxes.push_back(box);
    }
    return boxes;
  }

  /// an upper bound on the distance from `p` to the cells of tile `t`: 0 if `p` lies in one of
  /// them, otherwise the distance to the nearest of the tile's `block_boxes()` (given as `boxes`,
  /// computed once per tile), plus a margin that covers the rounding of the cells' bounds. A
  /// point within `halo - distance_to_tile(p, t, boxes)` of `p` is within `halo` of the tile's
  /// cells: that is the depth of `p` in the tile's region, as the tiled repair reads it.
  double distance_to_tile(const Point& p, std::size_t t, const std::vector<std::array<double, 6>>& boxes) const
  {
    if(tile_of_cell(cell_of(p)) == t) return 0;
    double best = std::numeric_limits<double>::infinity();
    for(const std::array<double, 6>& box : boxes) {
      double d2 = 0;
      for(std::size_t i = 0; i < 3; ++i) {
        const double d = p[i] < box[i] ? box[i] - p[i] : (p[i] > box[i + 3] ? p[i] - box[i + 3] : 0.0);
        d2 += d * d;
      }
      best = std::min(best, d2);
    }
    return std::sqrt(best) * (1 + 1e-12) + 4 * margin_;
  }
  /// `distance_to_tile(p, t, block_boxes(t))`.
  double distance_to_tile(const Point& p, std::size_t t) const { return distance_to_tile(p, t, block_boxes(t)); }

  /// the plan as bytes (host byte order), for the processes of a team that share the tiles
  /// (`tiled_reconstruct_topology()` with a team): `from_bytes(to_bytes())` is the same plan.
  std::vector<char> to_bytes() const
  {
    std::vector<char> out;
    const auto put = [&out](const void* data, std::size_t size) {
      const char* c = static_cast<const char*>(data);
      out.insert(out.end(), c, c + size);
    };
    const std::uint64_t header[4] = {level_, triangles_, first_cell_.size(), owned_.size()};
    const double reals[7] = {origin_[0], origin_[1], origin_[2], side_, halo_, margin_, mean_edge_length_};
    put(header, sizeof header);
    put(reals, sizeof reals);
    put(first_cell_.data(), 8 * first_cell_.size());
    for(std::size_t o : owned_) {
      const std::uint64_t v = o;
      put(&v, 8);
    }
    return out;
  }
  /// the plan of `to_bytes()`.
  /// \throws Invalid_input if `bytes` is not such a plan
  static Tile_plan from_bytes(const std::vector<char>& bytes)
  {
    std::size_t at = 0;
    const auto get = [&](void* data, std::size_t size) {
      if(bytes.size() - at < size) throw Invalid_input("Tile_plan::from_bytes: truncated plan");
      std::memcpy(data, bytes.data() + at, size);
      at += size;
    };
    std::uint64_t header[4];
    double reals[7];
    get(header, sizeof header);
    get(reals, sizeof reals);
    if(header[0] < 1 || header[0] > 8 || header[2] < 2 || header[3] + 1 != header[2] ||
       bytes.size() - at != 8 * (header[2] + header[3]))
      throw Invalid_input("Tile_plan::from_bytes: not a plan");
    Tile_plan plan;
    plan.level_ = static_cast<unsigned>(header[0]);
    plan.triangles_ = static_cast<std::size_t>(header[1]);
    plan.origin_ = {{reals[0], reals[1], reals[2]}};
    plan.side_ = reals[3];
    plan.halo_ = reals[4];
    plan.margin_ = reals[5];
    plan.mean_edge_length_ = reals[6];
    plan.first_cell_.resize(header[2]);
    get(plan.first_cell_.data(), 8 * plan.first_cell_.size());
    plan.owned_.resize(header[3]);
    for(std::size_t& o : plan.owned_) {
      std::uint64_t v;
      get(&v, 8);
      o = static_cast<std::size_t>(v);
    }
    plan.make_blocks();
    return plan;
  }

private:
  template <class TriangleSource>
  friend Tile_plan plan_tiles(const TriangleSource& source, std::size_t number_of_tiles, double halo, unsigned level);

  // an aligned block of cells: the `8^size_level` cells from `first`
  struct Block
  {
    std::uint64_t first;
    unsigned size_level;
  };

  bool block_meets(const Block& b, const std::array<std::uint64_t, 3>& lo, const std::array<std::uint64_t, 3>& hi) const
  {
    const std::uint64_t width = std::uint64_t(1) << b.size_level;
    const std::uint64_t corner[3] = {internal::gather_every_third(b.first >> 2), internal::gather_every_third(b.first >> 1),
                                     internal::gather_every_third(b.first)};
    for(std::size_t i = 0; i < 3; ++i)
      if(corner[i] + width - 1 < lo[i] || corner[i] > hi[i]) return false;
    return true;
  }

  // the tiles' ranges as aligned blocks (at most 14 per level each)
  void make_blocks()
  {
    blocks_.clear();
    block_begin_.assign(1, 0);
    for(std::size_t t = 0; t < number_of_tiles(); ++t) {
      std::uint64_t a = first_cell_[t];
      const std::uint64_t e = first_cell_[t + 1];
      while(a < e) {
        unsigned k = 0;
        while(k < level_ && a % (std::uint64_t(8) << (3 * k)) == 0 && a + (std::uint64_t(8) << (3 * k)) <= e) ++k;
        blocks_.push_back(Block{a, k});
        a += std::uint64_t(1) << (3 * k);
      }
      block_begin_.push_back(blocks_.size());
    }
  }

  Point origin_{{0, 0, 0}};
  double side_ = 1, halo_ = 0, margin_ = 0, mean_edge_length_ = 0;
  unsigned level_ = 1;
  std::size_t triangles_ = 0;
  std::vector<std::uint64_t> first_cell_;
  std::vector<std::size_t> owned_;
  std::vector<Block> blocks_;
  std::vector<std::size_t> block_begin_;
};

/// \ingroup PkgSoupTopologyTiling
/// the triangles of an indexed soup in memory, as a source for `plan_tiles()` and
/// `write_tile_files()`: `for_each(f)` calls `f(corners, index)` for every triangle in order.
template <class PointRange, class TriangleRange>
class Soup_triangle_source
{
public:
  Soup_triangle_source(const PointRange& points, const TriangleRange& triangles) : points_(points), triangles_(triangles) {}

  template <typename F>
  void for_each(F f) const
  {
    std::uint64_t index = 0;
    for(const auto& t : triangles_) {
      Tile_corners c;
      for(std::size_t k = 0; k < 3; ++k) {
        const auto& p = points_[static_cast<std::size_t>(t[k])];
        c[k] = {{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}};
      }
      f(static_cast<const Tile_corners&>(c), index++);
    }
  }

private:
  const PointRange& points_;
  const TriangleRange& triangles_;
};

/// \ingroup PkgSoupTopologyTiling
/// the triangles of binary STL files, read in blocks (the files are never held in memory), as a
/// source for `plan_tiles()` and `write_tile_files()`: the triangles of the files in the order
/// given, numbered on from one file to the next. An assembly of many files is one soup.
/// \throws IO::Read_error from `for_each()` if a file cannot be read, is not a binary STL, or is
/// shorter or longer than its header says
class Binary_STL_source
{
public:
  explicit Binary_STL_source(std::vector<std::string> files) : files_(std::move(files)) {}

  template <typename F>
  void for_each(F f) const
  {
    constexpr std::size_t facets_per_block = 1 << 14;
    std::vector<char> block(50 * facets_per_block);
    std::uint64_t index = 0;
    for(const std::string& file : files_) {
      std::ifstream in(file, std::ios::binary);
      if(!in) throw IO::Read_error(file + ": cannot open");
      char header[84];
      in.read(header, 84);
      if(in.gcount() != 84) throw IO::Read_error(file + ": binary STL shorter than its 84-byte header");
      if(IO::internal::starts_with_solid(header, header + 84) && !IO::internal::has_binary_byte(header, header + 84))
        throw IO::Read_error(file + ": an ASCII STL; the tiling streams binary STL only");
      std::uint32_t n;
      std::memcpy(&n, header + 80, 4);
      in.seekg(0, std::ios::end);
      const std::uint64_t size = static_cast<std::uint64_t>(in.tellg());
      if(size != 84 + 50 * std::uint64_t(n))
        throw IO::Read_error(file + ": binary STL header announces " + std::to_string(n) + " facets, the file has " +
                             std::to_string(size) + " bytes");
      in.seekg(84);
      for(std::uint64_t done = 0; done < n;) {
        const std::size_t count = static_cast<std::size_t>(std::min<std::uint64_t>(facets_per_block, n - done));
        in.read(block.data(), static_cast<std::streamsize>(50 * count));
        if(static_cast<std::size_t>(in.gcount()) != 50 * count) throw IO::Read_error(file + ": read failed");
        for(std::size_t facet = 0; facet < count; ++facet) {
          Tile_corners c;
          for(std::size_t k = 0; k < 3; ++k) {
            float v[3];
            std::memcpy(v, block.data() + 50 * facet + 12 * (1 + k), sizeof v);
            c[k] = {{double(v[0]), double(v[1]), double(v[2])}};
          }
          f(static_cast<const Tile_corners&>(c), index++);
        }
        done += count;
      }
    }
  }

private:
  std::vector<std::string> files_;
};

/// \ingroup PkgSoupTopologyTiling
/// \brief plans the tiles of the soup of `source` (a class with `for_each(f)`, calling
/// `f(const Tile_corners&, std::uint64_t index)` for every triangle, as `Soup_triangle_source`
/// and `Binary_STL_source`).
///
/// Two streams of the source: the bounding box (made a cube), then the histogram of the cells of
/// the triangles' anchors. Tile `k` starts at the first cell before which at least
/// `k * n / number_of_tiles` of the `n` triangles are owned, so the tiles own balanced counts,
/// up to one cell's triangles. Memory: the histogram, `8^level` counts of 8 bytes (16 MiB at the
/// default level 7).
/// \param source the triangles
/// \param number_of_tiles at least 1
/// \param halo how far a tile's region reaches beyond its cells (finite, non-negative)
/// \param level the cells per side are `2^level`, from 1 to 8
/// \throws Invalid_input for a bad argument or a corner that is not finite (naming the triangle)
template <class TriangleSource>
Tile_plan plan_tiles(const TriangleSource& source, std::size_t number_of_tiles, double halo, unsigned level)
{
  if(number_of_tiles == 0) throw Invalid_input("plan_tiles: at least one tile is needed");
  if(!(halo >= 0 && halo <= std::numeric_limits<double>::max()))
    throw Invalid_input("plan_tiles: the halo must be finite and non-negative");
  if(level < 1 || level > 8) throw Invalid_input("plan_tiles: the level must be from 1 to 8");
  Tile_plan plan;
  plan.level_ = level;
  plan.halo_ = halo;
  const double infinity = std::numeric_limits<double>::infinity();
  Tile_plan::Point lo{{infinity, infinity, infinity}}, hi{{-infinity, -infinity, -infinity}};
  std::size_t n = 0;
  double edge_lengths = 0;
  source.for_each([&](const Tile_corners& c, std::uint64_t index) {
    for(std::size_t k = 0; k < 3; ++k) {
      const auto& p = c[k];
      const auto& q = c[(k + 1) % 3];
      edge_lengths += std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) + (p[2] - q[2]) * (p[2] - q[2]));
    }
    for(const auto& p : c)
      for(std::size_t i = 0; i < 3; ++i) {
        if(!std::isfinite(p[i]))
          throw Invalid_input("plan_tiles: triangle " + std::to_string(index) + " has a corner that is not finite");
        lo[i] = std::min(lo[i], p[i]);
        hi[i] = std::max(hi[i], p[i]);
      }
    ++n;
  });
  plan.triangles_ = n;
  plan.mean_edge_length_ = n > 0 && std::isfinite(edge_lengths) ? edge_lengths / double(3 * n) : 0;
  double extent = 0, largest = 0;
  for(std::size_t i = 0; i < 3 && n > 0; ++i) {
    extent = std::max(extent, hi[i] - lo[i]);
    largest = std::max({largest, std::abs(lo[i]), std::abs(hi[i])});
  }
  if(n > 0) plan.origin_ = lo;
  // The far faces of the cube lie beyond every point (they are closed by the clamping anyway).
  plan.side_ = extent > 0 ? extent * (1 + 1e-9) : 1.0;
  // Covers the rounding of the cell computation: a few units in the last place of the
  // coordinates and of the side, far more than enough.
  plan.margin_ = 1e-12 * (largest + plan.side_);
  const std::uint64_t cells = std::uint64_t(1) << (3 * level);
  std::vector<std::uint64_t> histogram(cells, 0);
  source.for_each([&](const Tile_corners& c, std::uint64_t) { ++histogram[plan.cell_of(Tile_plan::anchor(c))]; });
  plan.first_cell_.assign(number_of_tiles + 1, cells);
  plan.first_cell_[0] = 0;
  std::size_t k = 1;
  std::uint64_t before = 0; // the triangles owned by the cells before `cell`
  for(std::uint64_t cell = 0; cell < cells && k < number_of_tiles; ++cell) {
    // tile k starts at the first cell with at least k * n / tiles triangles before it
    while(k < number_of_tiles && before * number_of_tiles >= k * std::uint64_t(n)) plan.first_cell_[k++] = cell;
    before += histogram[cell];
  }
  plan.owned_.assign(number_of_tiles, 0);
  for(std::size_t t = 0; t < number_of_tiles; ++t)
    for(std::uint64_t cell = plan.first_cell_[t]; cell < plan.first_cell_[t + 1]; ++cell) plan.owned_[t] += histogram[cell];
  plan.make_blocks();
  return plan;
}

/// \ingroup PkgSoupTopologyTiling
/// one triangle of a tile's spill file.
struct Tile_triangle
{
  Tile_corners corners;     ///< its corners
  std::uint64_t index = 0;  ///< its index in the source
  bool owned = false;       ///< `true` in the file of the tile that owns it, `false` in the halos
};

/// \ingroup PkgSoupTopologyTiling
/// what `write_tile_files()` wrote: per tile, its file (empty if not written) and its triangles
/// owned and in the halo.
struct Tile_files
{
  std::vector<std::string> files;
  std::vector<std::size_t> owned, halo;
};

namespace internal {

constexpr char tile_file_magic[8] = {'S', 'T', 'T', 'I', 'L', 'E', '1', '\0'};
constexpr std::size_t tile_record_size = 9 * 8 + 8 + 8;

inline std::string tile_file_name(const std::string& folder, std::size_t t)
{
  std::string number = std::to_string(t);
  if(number.size() < 5) number.insert(0, 5 - number.size(), '0');
  return folder + "/tile_" + number + ".bin";
}

} // namespace internal

/// \ingroup PkgSoupTopologyTiling
/// \brief streams the soup of `source` into one spill file per tile of `plan`, in `folder`
/// (`tile_00000.bin`, ...): a tile's file holds every triangle of `tiles_meeting()`, marked owned
/// in its owner's file, in the order of the source.
///
/// The file: 8 bytes `STTILE1\0`, the tile and the number of tiles (8 bytes each), then one record
/// of 88 bytes per triangle (9 coordinates, the index, the owned flag and padding), in the byte
/// order of the machine: spill files are for the machines of one run. All the files are open at
/// once: the number of tiles is bounded by the process's open files.
///
/// With `wanted` (one flag per tile), only the files of the tiles flagged are written; the others
/// have an empty name and no count in the result (the tiled repair spills the tiles it repairs
/// again this way, with a larger halo).
/// \throws IO::Write_error if a file cannot be written; Invalid_input if the source does not give
/// the triangles the plan was made from (another count), or `wanted` has another size than the
/// number of tiles
template <class TriangleSource>
Tile_files write_tile_files(const TriangleSource& source, const Tile_plan& plan, const std::string& folder,
                            const std::vector<char>* wanted = nullptr)
{
  const std::size_t tiles = plan.number_of_tiles();
  if(wanted != nullptr && wanted->size() != tiles)
    throw Invalid_input("write_tile_files: the tiles wanted do not match the plan");
  const auto is_wanted = [&](std::size_t t) { return wanted == nullptr || (*wanted)[t] != 0; };
  Tile_files out;
  out.owned.assign(tiles, 0);
  out.halo.assign(tiles, 0);
  std::vector<std::unique_ptr<std::ofstream>> streams(tiles);
  std::vector<std::string> buffers(tiles);
  out.files.resize(tiles);
  for(std::size_t t = 0; t < tiles; ++t) {
    if(!is_wanted(t)) continue;
    out.files[t] = internal::tile_file_name(folder, t);
    streams[t] = std::make_unique<std::ofstream>(out.files[t], std::ios::binary | std::ios::trunc);
    if(!*streams[t]) throw IO::Write_error(out.files[t] + ": cannot open for writing");
    buffers[t].append(internal::tile_file_magic, 8);
    const std::uint64_t head[2] = {std::uint64_t(t), std::uint64_t(tiles)};
    buffers[t].append(reinterpret_cast<const char*>(head), sizeof head);
  }
  const auto flush = [&](std::size_t t, bool always) {
    if(!always && buffers[t].size() < (1u << 16)) return;
    streams[t]->write(buffers[t].data(), static_cast<std::streamsize>(buffers[t].size()));
    buffers[t].clear();
    if(!*streams[t]) throw IO::Write_error(out.files[t] + ": write failed");
  };
  std::vector<std::size_t> meeting;
  std::size_t n = 0;
  source.for_each([&](const Tile_corners& c, std::uint64_t index) {
    ++n;
    const std::size_t owner = plan.owner(c);
    plan.collect_tiles_meeting(c, meeting);
    for(std::size_t t : meeting) {
      if(!is_wanted(t)) continue;
      const std::uint64_t owned = t == owner ? 1 : 0;
      (owned ? out.owned : out.halo)[t] += 1;
      buffers[t].append(reinterpret_cast<const char*>(c.data()), 9 * 8);
      buffers[t].append(reinterpret_cast<const char*>(&index), 8);
      buffers[t].append(reinterpret_cast<const char*>(&owned), 8);
      flush(t, false);
    }
  });
  if(n != plan.number_of_triangles())
    throw Invalid_input("write_tile_files: the source gives " + std::to_string(n) + " triangles, the plan was made from " +
                        std::to_string(plan.number_of_triangles()));
  for(std::size_t t = 0; t < tiles; ++t) {
    if(!is_wanted(t)) continue;
    flush(t, true);
    streams[t]->close();
    if(!*streams[t]) throw IO::Write_error(out.files[t] + ": write failed");
  }
  return out;
}

/// \ingroup PkgSoupTopologyTiling
/// \brief the triangles of a spill file written by `write_tile_files()`, in the order written.
/// \throws IO::Read_error if the file cannot be read, is not a spill file or is truncated
inline std::vector<Tile_triangle> read_tile_file(const std::string& file)
{
  std::ifstream in(file, std::ios::binary);
  if(!in) throw IO::Read_error(file + ": cannot open");
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if(data.size() < 24 || std::memcmp(data.data(), internal::tile_file_magic, 8) != 0)
    throw IO::Read_error(file + ": not a tile spill file");
  if((data.size() - 24) % internal::tile_record_size != 0)
    throw IO::Read_error(file + ": truncated tile spill file (" + std::to_string(data.size()) + " bytes)");
  std::vector<Tile_triangle> out((data.size() - 24) / internal::tile_record_size);
  for(std::size_t r = 0; r < out.size(); ++r) {
    const char* p = data.data() + 24 + r * internal::tile_record_size;
    std::memcpy(out[r].corners.data(), p, 9 * 8);
    std::memcpy(&out[r].index, p + 72, 8);
    std::uint64_t owned;
    std::memcpy(&owned, p + 80, 8);
    if(owned > 1) throw IO::Read_error(file + ": record " + std::to_string(r) + " is corrupt");
    out[r].owned = owned == 1;
  }
  return out;
}

} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_SOUP_TILING_H
