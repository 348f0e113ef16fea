// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The connected components of the tolerance graph of a point set (two points linked when their
// distance is at most the tolerance), computed without listing the pairs of dense clusters.

#ifndef SOUP_TOPOLOGY_INTERNAL_TOLERANCE_GRAPH_H
#define SOUP_TOPOLOGY_INTERNAL_TOLERANCE_GRAPH_H

#include <Soup_topology/Octree.h>
#include <Soup_topology/internal/parallel.h>
#include <Soup_topology/internal/uninitialized_vector.h>
#include <Soup_topology/internal/union_find.h>

#include <CGAL/number_utils.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

namespace Soup_topology {
namespace internal {

/// a grid cell (of diagonal the tolerance) holding more candidates than this makes
/// `snap_vertices()` build the tolerance graph's components on the grid (same result, no pair
/// list), and `split_t_junctions()` skip the cells within the tolerance of an edge's end point.
constexpr std::size_t dense_cell_size = 64;

/// the placement of the cells of a `Tolerance_grid`: the cell of a point of approximate
/// coordinates c is floor((c - origin) / side) on each axis.
struct Tolerance_grid_frame
{
  bool usable = false;          ///< `false` when the tolerance is zero or too small for integer cells
  double side = 0, slack = 0;
  std::array<double, 3> origin{{0, 0, 0}};
  std::array<std::int64_t, 3> largest_key{{0, 0, 0}}; ///< the largest cell index on each axis

  /// the frame for the points of approximate coordinates `coordinates(i)`, i < n, and the tolerance `e`.
  template <class Coordinates>
  Tolerance_grid_frame(std::size_t n, const Coordinates& coordinates, double e)
    : Tolerance_grid_frame(n, coordinates, e, CGAL::Sequential_tag())
  {}

  /// the same, the box of the points taken by blocks on TBB's threads with a parallel
  /// `ConcurrencyTag`: each block's box, then the boxes in block order, by the same comparisons
  /// (of equal extreme coordinates the first is kept, even the sign of a zero): the same frame.
  template <class Coordinates, class ConcurrencyTag>
  Tolerance_grid_frame(std::size_t n, const Coordinates& coordinates, double e, ConcurrencyTag)
  {
    if(n == 0) return;
    if(!(e > 0) || !std::isfinite(e)) return;
    constexpr double infinity = std::numeric_limits<double>::infinity();
    using Box = std::array<std::array<double, 3>, 2>; // lowest, highest
    const auto add = [](Box& box, const std::array<double, 3>& c) {
      for(std::size_t k = 0; k < 3; ++k) {
        box[0][k] = std::min(box[0][k], c[k]);
        box[1][k] = std::max(box[1][k], c[k]);
      }
    };
    const Box empty{{{{infinity, infinity, infinity}}, {{-infinity, -infinity, -infinity}}}};
    std::vector<Box> boxes(number_of_blocks(n), empty);
    for_each_block<ConcurrencyTag>(n, default_block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
      for(std::size_t i = begin; i != end; ++i) add(boxes[b], coordinates(i));
    });
    Box box = empty;
    for(const Box& b : boxes)
      for(std::size_t k = 0; k < 3; ++k) {
        box[0][k] = std::min(box[0][k], b[0][k]);
        box[1][k] = std::max(box[1][k], b[1][k]);
      }
    const std::array<double, 3>& lo = box[0];
    const std::array<double, 3>& hi = box[1];
    double magnitude = 0, extent = 0;
    for(std::size_t k = 0; k < 3; ++k) {
      magnitude = std::max({magnitude, std::abs(lo[k]), std::abs(hi[k])});
      extent = std::max(extent, hi[k] - lo[k]);
    }
    side = e / std::sqrt(3.0) * (1 - 1e-6);
    // Integer cells far below the coordinates' resolution say nothing: leave it to the caller.
    if(!(side > 1e6 * std::numeric_limits<double>::epsilon() * magnitude) || !(extent / side < 1e12)) return;
    // Rounding of the approximate coordinates and of their differences, for the box filter.
    slack = 1e-6 * e + 16 * std::numeric_limits<double>::epsilon() * magnitude;
    origin = lo;
    largest_key = key(hi);
    usable = true;
  }

  /// the cell of the point of approximate coordinates `c`.
  std::array<std::int64_t, 3> key(const std::array<double, 3>& c) const
  {
    std::array<std::int64_t, 3> k;
    for(std::size_t a = 0; a < 3; ++a) k[a] = static_cast<std::int64_t>(std::floor((c[a] - origin[a]) / side));
    return k;
  }
};

/// the approximate coordinates of a point.
template <class Point>
std::array<double, 3> approximate_coordinates(const Point& p)
{
  return {{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}};
}

/// the number of points of the most populated cell of the `Tolerance_grid` of `points` for the
/// tolerance `eps` (0 when that grid is not usable): its `largest_cell()`, found from the cell
/// indices alone, without the cells; computed and sorted on TBB's threads when `ConcurrencyTag`
/// asks for it (the same count).
///
/// The points are `point_of(0)`, ..., `point_of(n - 1)` (e.g. read from a soup through indices).
template <class ConcurrencyTag = CGAL::Sequential_tag, class PointOf, class FT>
std::size_t largest_tolerance_cell(std::size_t n, const PointOf& point_of, const FT& eps)
{
  const Tolerance_grid_frame frame(n, [&](std::size_t i) { return approximate_coordinates(point_of(i)); },
                                   CGAL::to_double(eps), ConcurrencyTag());
  if(!frame.usable) return 0;
  std::size_t largest = 1;
  constexpr std::int64_t packed_limit = std::int64_t(1) << 21;
  if(frame.largest_key[0] < packed_limit && frame.largest_key[1] < packed_limit && frame.largest_key[2] < packed_limit) {
    // Three indices of 21 bits in one integer, sorted by radix.
    struct Item { std::uint64_t key; };
    Uninitialized_vector<Item> keys(n), buffer; // written whole on TBB's threads before they are read
    for_each_index<ConcurrencyTag>(n, [&](std::size_t i) {
      const std::array<std::int64_t, 3> k = frame.key(approximate_coordinates(point_of(i)));
      keys[i].key = (std::uint64_t(k[0]) << 42) | (std::uint64_t(k[1]) << 21) | std::uint64_t(k[2]);
    });
    sort_by_key<ConcurrencyTag>(keys, buffer, 63);
    for(std::size_t i = 0; i < n;) {
      std::size_t j = i + 1;
      while(j < n && keys[j].key == keys[i].key) ++j;
      largest = std::max(largest, j - i);
      i = j;
    }
    return largest;
  }
  std::vector<std::array<std::int64_t, 3>> keys(n);
  for(std::size_t i = 0; i < n; ++i) keys[i] = frame.key(approximate_coordinates(point_of(i)));
  std::sort(keys.begin(), keys.end());
  for(std::size_t i = 0; i < n;) {
    std::size_t j = i + 1;
    while(j < n && keys[j] == keys[i]) ++j;
    largest = std::max(largest, j - i);
    i = j;
  }
  return largest;
}

/// the same for the points of a vector.
template <class ConcurrencyTag = CGAL::Sequential_tag, class Point, class FT>
std::size_t largest_tolerance_cell(const std::vector<Point>& points, const FT& eps)
{
  return largest_tolerance_cell<ConcurrencyTag>(points.size(), [&points](std::size_t i) -> const Point& { return points[i]; },
                                                eps);
}

/// A grid over points whose cells have a diagonal just below the tolerance `eps`, so that every
/// point of a cell is within `eps` of the cell's first point (checked exactly all the same; a
/// point that fails, through rounding of the cell index, is handled pair by pair). The connected
/// components of the tolerance graph are then the cells, joined when some pair of points of two
/// cells is within `eps`: one exact nearest-point query per point of the smaller cell, stopped
/// at the first link. A cluster of n points within `eps` of each other costs O(n log n), not the
/// n^2 / 2 pairs. The grid is a pruning device only: every link is decided by
/// `Compare_squared_distance_3`, so the components are those of the tolerance graph.
template <class Kernel>
class Tolerance_grid
{
  using Point = typename Kernel::Point_3;
  using FT = typename Kernel::FT;
  using Key = std::array<std::int64_t, 3>;

  struct Cell
  {
    Key key;
    std::uint32_t begin, end;       // into ids_
    std::array<double, 3> lo, hi;   // bounding box of its points (approximate coordinates)
    bool has_loose = false;         // a point of the cell is not within eps of the first one
  };

public:
  /// the grid over `points` (kept by reference) for the tolerance `eps`. `usable()` is false when
  /// the tolerance is zero or too small against the extent of the points for integer cells.
  Tolerance_grid(const std::vector<Point>& points, const FT& eps, const Kernel& kernel)
    : points_(points), eps_(eps), eps2_(eps * eps), kernel_(kernel)
  {
    const std::size_t n = points.size();
    if(n == 0) return;
    approx_.resize(n);
    for(std::size_t i = 0; i < n; ++i) approx_[i] = approximate_coordinates(points[i]);
    const Tolerance_grid_frame frame(n, [&](std::size_t i) { return approx_[i]; }, CGAL::to_double(eps));
    if(!frame.usable) return;
    side_ = frame.side;
    slack_ = frame.slack;
    origin_ = frame.origin;
    std::vector<std::pair<Key, std::uint32_t>> keyed(n);
    for(std::size_t i = 0; i < n; ++i) {
      keyed[i] = {frame.key(approx_[i]), static_cast<std::uint32_t>(i)};
    }
    std::sort(keyed.begin(), keyed.end());
    ids_.resize(n);
    for(std::size_t i = 0; i < n; ++i) ids_[i] = keyed[i].second;
    for(std::size_t i = 0; i < n;) {
      std::size_t j = i;
      Cell c;
      c.key = keyed[i].first;
      c.lo = c.hi = approx_[keyed[i].second];
      while(j < n && keyed[j].first == c.key) {
        for(std::size_t k = 0; k < 3; ++k) {
          c.lo[k] = std::min(c.lo[k], approx_[keyed[j].second][k]);
          c.hi[k] = std::max(c.hi[k], approx_[keyed[j].second][k]);
        }
        ++j;
      }
      c.begin = static_cast<std::uint32_t>(i);
      c.end = static_cast<std::uint32_t>(j);
      largest_cell_ = std::max(largest_cell_, j - i);
      cells_.push_back(c);
      i = j;
    }
    usable_ = true;
  }

  bool usable() const { return usable_; }
  /// the number of points of the most populated cell.
  std::size_t largest_cell() const { return largest_cell_; }

  /// unites in `uf` every two points within the tolerance of each other (their components).
  void unite_components(Union_find& uf)
  {
    typename Kernel::Compare_squared_distance_3 compare_sq = kernel_.compare_squared_distance_3_object();
    std::vector<std::uint32_t> loose;
    // 1. Each point with the first point of its cell.
    for(Cell& c : cells_) {
      const std::uint32_t first = ids_[c.begin];
      for(std::uint32_t k = c.begin + 1; k < c.end; ++k) {
        const std::uint32_t p = ids_[k];
        if(compare_sq(points_[p], points_[first], eps2_) != CGAL::LARGER) uf.unite(p, first);
        else c.has_loose = true;
      }
    }
    // A loose point is compared with every other point of its cell.
    for(const Cell& c : cells_) {
      if(!c.has_loose) continue;
      for(std::uint32_t k = c.begin; k < c.end; ++k)
        for(std::uint32_t l = k + 1; l < c.end; ++l) link_if_near(ids_[k], ids_[l], uf);
    }
    // 2. Pairs of cells whose keys differ by at most 2 on every axis (points within eps are in
    // such cells: eps is below 1.74 sides), each unordered pair once.
    for(std::size_t x = 0; x < cells_.size(); ++x) {
      for(std::int64_t dx = -2; dx <= 2; ++dx)
        for(std::int64_t dy = -2; dy <= 2; ++dy)
          for(std::int64_t dz = -2; dz <= 2; ++dz) {
            const Key offset{{dx, dy, dz}};
            if(!(Key{{0, 0, 0}} < offset)) continue;
            const Key key{{cells_[x].key[0] + dx, cells_[x].key[1] + dy, cells_[x].key[2] + dz}};
            const auto it = std::lower_bound(cells_.begin(), cells_.end(), key,
                                             [](const Cell& c, const Key& k) { return c.key < k; });
            if(it == cells_.end() || it->key != key) continue;
            link_cells(x, static_cast<std::size_t>(it - cells_.begin()), uf);
          }
    }
  }

  /// `true` if the segment [a,b] is shorter than twice the tolerance (in double, a choice of
  /// strategy only).
  bool is_short(const Point& a, const Point& b) const
  {
    const double dx = CGAL::to_double(a.x()) - CGAL::to_double(b.x());
    const double dy = CGAL::to_double(a.y()) - CGAL::to_double(b.y());
    const double dz = CGAL::to_double(a.z()) - CGAL::to_double(b.z());
    const double d2 = dx * dx + dy * dy + dz * dz;
    const double e = 2 * CGAL::to_double(eps_);
    return d2 <= e * e;
  }

  /// calls `visit(i)` for every point `i` of the cells that may hold a point within the tolerance
  /// of the box [lo, hi] (approximate coordinates), except the points of the cells that lie
  /// entirely within the tolerance of `a` or of `b` (certainly, despite rounding: every point
  /// of such a cell is decided within the tolerance by the exact predicate too).
  template <class Visit>
  void for_each_point_near_box(const Point& a, const Point& b, Visit visit) const
  {
    const std::array<double, 3> ac{{CGAL::to_double(a.x()), CGAL::to_double(a.y()), CGAL::to_double(a.z())}};
    const std::array<double, 3> bc{{CGAL::to_double(b.x()), CGAL::to_double(b.y()), CGAL::to_double(b.z())}};
    const double e = CGAL::to_double(eps_);
    Key low, high;
    for(std::size_t k = 0; k < 3; ++k) {
      low[k] = static_cast<std::int64_t>(std::floor((std::min(ac[k], bc[k]) - e - origin_[k]) / side_)) - 1;
      high[k] = static_cast<std::int64_t>(std::floor((std::max(ac[k], bc[k]) + e - origin_[k]) / side_)) + 1;
    }
    for(std::int64_t x = low[0]; x <= high[0]; ++x)
      for(std::int64_t y = low[1]; y <= high[1]; ++y) {
        const Key first{{x, y, low[2]}};
        auto it = std::lower_bound(cells_.begin(), cells_.end(), first,
                                   [](const Cell& c, const Key& k) { return c.key < k; });
        for(; it != cells_.end() && it->key[0] == x && it->key[1] == y && it->key[2] <= high[2]; ++it) {
          if(box_within(*it, ac) || box_within(*it, bc)) continue;
          for(std::uint32_t k = it->begin; k < it->end; ++k) visit(ids_[k]);
        }
      }
  }

private:
  // every point of the cell is within the tolerance of `p`, with a margin above rounding
  bool box_within(const Cell& c, const std::array<double, 3>& p) const
  {
    double d2 = 0;
    for(std::size_t k = 0; k < 3; ++k) {
      const double d = std::max(std::abs(c.lo[k] - p[k]), std::abs(c.hi[k] - p[k]));
      d2 += d * d;
    }
    return std::sqrt(d2) + slack_ < CGAL::to_double(eps_) * (1 - 1e-6);
  }

  void link_if_near(std::uint32_t p, std::uint32_t q, Union_find& uf)
  {
    if(uf.find(p) == uf.find(q)) return;
    if(kernel_.compare_squared_distance_3_object()(points_[p], points_[q], eps2_) != CGAL::LARGER) uf.unite(p, q);
  }

  bool boxes_apart(const Cell& a, const Cell& b) const
  {
    double gap2 = 0;
    for(std::size_t k = 0; k < 3; ++k) {
      const double g = std::max({0.0, a.lo[k] - b.hi[k], b.lo[k] - a.hi[k]});
      gap2 += g * g;
    }
    const double bound = CGAL::to_double(eps_) * (1 + 1e-6) + slack_;
    return gap2 > bound * bound;
  }

  // The point of `cell` nearest to `p` among those within eps of it, if any (exact).
  std::optional<std::uint32_t> near_point_in(std::size_t cell, const Point& p)
  {
    const Cell& c = cells_[cell];
    const std::size_t size = c.end - c.begin;
    if(size <= brute_force_size) {
      typename Kernel::Compare_squared_distance_3 compare_sq = kernel_.compare_squared_distance_3_object();
      for(std::uint32_t k = c.begin; k < c.end; ++k)
        if(compare_sq(p, points_[ids_[k]], eps2_) != CGAL::LARGER) return ids_[k];
      return std::nullopt;
    }
    if(trees_.size() != cells_.size()) trees_.resize(cells_.size());
    if(!trees_[cell]) {
      std::vector<Point> cell_points;
      cell_points.reserve(size);
      for(std::uint32_t k = c.begin; k < c.end; ++k) cell_points.push_back(points_[ids_[k]]);
      trees_[cell] = std::make_unique<Octree<Kernel>>(cell_points, CGAL::Identity_property_map<Point>(), kernel_);
    }
    const std::optional<std::size_t> found = trees_[cell]->nearest_vertex(p, eps_);
    if(!found) return std::nullopt;
    return ids_[c.begin + *found];
  }

  void link_cells(std::size_t x, std::size_t y, Union_find& uf)
  {
    const Cell& a = cells_[x];
    const Cell& b = cells_[y];
    if(boxes_apart(a, b)) return;
    if(a.has_loose || b.has_loose) {
      // Rare (rounding at a cell boundary): every pair whose sets differ.
      for(std::uint32_t k = a.begin; k < a.end; ++k)
        for(std::uint32_t l = b.begin; l < b.end; ++l) link_if_near(ids_[k], ids_[l], uf);
      return;
    }
    // Both cells are one set each: one link joins them.
    const bool a_smaller = (a.end - a.begin) <= (b.end - b.begin);
    const Cell& small = a_smaller ? a : b;
    const std::size_t large = a_smaller ? y : x;
    const std::uint32_t large_first = ids_[cells_[large].begin];
    for(std::uint32_t k = small.begin; k < small.end; ++k) {
      if(uf.find(ids_[k]) == uf.find(large_first)) return;
      const std::optional<std::uint32_t> q = near_point_in(large, points_[ids_[k]]);
      if(q) { uf.unite(ids_[k], *q); return; }
    }
  }

  static constexpr std::size_t brute_force_size = 32;

  const std::vector<Point>& points_;
  FT eps_, eps2_;
  Kernel kernel_;
  bool usable_ = false;
  double side_ = 0, slack_ = 0;
  std::array<double, 3> origin_{{0, 0, 0}};
  std::vector<std::array<double, 3>> approx_;
  std::vector<std::uint32_t> ids_;   // point ids sorted by (cell key, id)
  std::vector<Cell> cells_;          // sorted by key
  std::size_t largest_cell_ = 0;
  std::vector<std::unique_ptr<Octree<Kernel>>> trees_;
};

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_TOLERANCE_GRAPH_H
