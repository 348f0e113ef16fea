// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// This file is part of Soup_topology, a header-only C++17 library that rebuilds the topology
// of triangle soups.

// Ear clipping of one polygon in the plane of its Newell normal, shared by the readers that
// meet polygons of more than three corners.

#ifndef SOUP_TOPOLOGY_INTERNAL_TRIANGULATE_POLYGON_H
#define SOUP_TOPOLOGY_INTERNAL_TRIANGULATE_POLYGON_H

#include <CGAL/number_type_basic.h>
#include <CGAL/number_utils.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace Soup_topology {
namespace internal {

/// the projection of a polygon onto the coordinate plane most parallel to its Newell normal,
/// oriented so that the polygon turns counterclockwise in (u, v).
struct Polygon_projection
{
  double normal[3] = {0, 0, 0}; ///< the Newell normal (twice the vector area)
  int axis = 0;                 ///< the dropped coordinate
  int u = 1, v = 2;             ///< the kept coordinates, in counterclockwise order
  bool degenerate() const { return normal[axis] == 0; }
};

/// computes the projection of the polygon of `k` corners whose i-th corner has the coordinates
/// `xyz(i)` (something indexable by 0, 1, 2 giving doubles), and writes the 2D corners to `uv`
/// (2k doubles).
template <class Corner_coordinates>
Polygon_projection project_polygon(std::size_t k, const Corner_coordinates& xyz, std::vector<double>& uv)
{
  Polygon_projection r;
  double* n = r.normal;
  for(std::size_t i = 0; i < k; ++i)
  {
    const auto p = xyz(i);
    const auto q = xyz(i + 1 == k ? 0 : i + 1);
    n[0] += (p[1] - q[1]) * (p[2] + q[2]);
    n[1] += (p[2] - q[2]) * (p[0] + q[0]);
    n[2] += (p[0] - q[0]) * (p[1] + q[1]);
  }
  int axis = 0;
  if(std::abs(n[1]) > std::abs(n[axis]))
    axis = 1;
  if(std::abs(n[2]) > std::abs(n[axis]))
    axis = 2;
  int u = (axis + 1) % 3, v = (axis + 2) % 3;
  if(n[axis] < 0)
    std::swap(u, v);
  r.axis = axis;
  r.u = u;
  r.v = v;
  uv.resize(2 * k);
  for(std::size_t i = 0; i < k; ++i)
  {
    const auto p = xyz(i);
    uv[2 * i] = p[static_cast<std::size_t>(u)];
    uv[2 * i + 1] = p[static_cast<std::size_t>(v)];
  }
  return r;
}

/// A set of integers in [0, n) with a successor query, as a 64-ary tree of bit words: every
/// operation costs a few word operations per level (3 levels for a quarter million corners).
class Successor_set
{
public:
  static constexpr std::size_t npos = std::size_t(-1);

  /// the set {0, ..., n-1}
  void fill(std::size_t n)
  {
    std::size_t depth = 0, size = n;
    do
    {
      const std::size_t words = (size + 63) / 64;
      if(levels_.size() <= depth)
        levels_.emplace_back();
      std::vector<std::uint64_t>& level = levels_[depth++]; // reused: no allocation per polygon
      level.assign(words, ~std::uint64_t(0));
      if(size % 64 != 0)
        level.back() = (std::uint64_t(1) << (size % 64)) - 1;
      size = words;
    } while(size > 1);
    levels_.resize(depth);
  }

  void insert(std::size_t i)
  {
    for(auto& level : levels_)
    {
      const std::uint64_t bit = std::uint64_t(1) << (i % 64);
      const bool was_empty = level[i / 64] == 0;
      level[i / 64] |= bit;
      if(!was_empty)
        return;
      i /= 64;
    }
  }

  void erase(std::size_t i)
  {
    for(auto& level : levels_)
    {
      level[i / 64] &= ~(std::uint64_t(1) << (i % 64));
      if(level[i / 64] != 0)
        return;
      i /= 64;
    }
  }

  /// the smallest element >= i, or npos
  std::size_t next(std::size_t i) const
  {
    std::size_t depth = 0;
    // go up until a word holds an element at or after the position
    for(;; ++depth)
    {
      if(depth == levels_.size())
        return npos;
      const std::vector<std::uint64_t>& level = levels_[depth];
      if(i / 64 >= level.size())
        return npos;
      const unsigned shift = static_cast<unsigned>(i % 64);
      const std::uint64_t word = level[i / 64] & (~std::uint64_t(0) << shift);
      if(word != 0)
      {
        i = (i / 64) * 64 + lowest_bit(word);
        break;
      }
      i = i / 64 + 1;
    }
    // then down to the smallest element below
    while(depth > 0)
    {
      --depth;
      i = i * 64 + lowest_bit(levels_[depth][i]);
    }
    return i;
  }

private:
  static std::size_t lowest_bit(std::uint64_t w)
  {
    std::size_t n = 0;
    while((w & 0xFFFF) == 0)
    {
      w >>= 16;
      n += 16;
    }
    while((w & 1) == 0)
    {
      w >>= 1;
      ++n;
    }
    return n;
  }

  std::vector<std::vector<std::uint64_t>> levels_;
};

/// Ear clipping of a counterclockwise polygon given by its 2D corners `uv` (2k doubles).
///
/// The rule: a corner is an ear if it turns left (strictly) and no other remaining corner, but
/// those at the position of one of its three corners, lies in the closed triangle it forms with
/// its two neighbours. The candidate starts at corner 0; after a clip the next candidate is the
/// corner after the clipped one, after a miss the next corner; if no remaining corner is an ear
/// (a self-intersecting or degenerate rest), the remaining corners are fanned from the first of
/// them in polygon order, and their number is returned (0 when every corner was clipped).
///
/// That is the textbook quadratic walk; the same decisions (but for needle triangles, sharper
/// than about 1e-7 radians, where rounding errors decide either way) are reached in near-linear
/// time in practice by two means. The search for a corner in a triangle goes down a k-d tree of the
/// corners that skips the subtrees whose corners are all clipped and those whose box lies
/// outside the triangle (beyond a margin far above rounding errors, so that every corner the
/// rule would find is visited). And a corner found not to be an ear keeps that status until one
/// of its neighbours is clipped or the corner found in its triangle is clipped; meanwhile the
/// walk skips it through a successor set instead of testing it again on every lap.
///
/// The work is capped: after `work_limit(k)` node and corner visits the rest is fanned as if no
/// ear were left (and counted the same way), so that a polygon built to defeat the tree costs at
/// most 32 (log2(k/8) + 2) visits per corner: spirals and combs take 50 to 100.
class Ear_clipper
{
public:
  static constexpr std::size_t npos = std::size_t(-1);

  /// the number of corner visits after which the rest of a polygon of `k` corners is fanned
  static std::size_t work_limit(std::size_t k)
  {
    std::size_t depth = 2; // about the depth of the k-d tree, plus 2
    for(std::size_t n = k; n > leaf_size; n /= 2)
      ++depth;
    return 32 * k * depth + 4096;
  }

  /// the node and corner visits of the last clip(): a measure of its time that does not depend
  /// on the machine
  std::size_t work() const { return work_; }

  template <class Emit>
  std::size_t clip(const std::vector<double>& uv, std::size_t k, const Emit& emit)
  {
    if(k < 3)
      return k;
    if(k == 3)
    {
      emit(0, 1, 2);
      return 0;
    }
    uv_ = uv.data();
    make_ring(k);
    make_tree(k);
    work_ = 0;
    const std::size_t limit = work_limit(k);
    std::size_t size = k, cursor = 0;
    while(size > 3)
    {
      std::size_t x = unknown_.next(cursor);
      if(x == npos)
        x = unknown_.next(0);
      if(x == npos || work_ > limit)
        break; // no ear left, or the work cap reached
      unknown_.erase(x);
      const std::size_t a = prev_[x], c = next_[x];
      const std::size_t blocker = find_blocker(a, x, c);
      if(blocker == npos)
      {
        emit(a, x, c);
        remove(x);
        --size;
        cursor = c;
      }
      else
      {
        if(blocker != x) // x is blocked by a corner: it is tested again when that one goes
        {
          watch_.push_back({x, watch_head_[blocker]});
          watch_head_[blocker] = watch_.size() - 1;
        }
        blocked_by_[x] = blocker;
        cursor = x + 1;
      }
    }
    // the rest: one triangle, or a fan from the first remaining corner
    const std::size_t first = first_;
    std::size_t b = next_[first];
    for(std::size_t i = 2; i < size; ++i)
    {
      emit(first, b, next_[b]);
      b = next_[b];
    }
    return size > 3 ? size : 0;
  }

private:
  double turn(std::size_t a, std::size_t b, std::size_t c) const
  {
    const double* u = uv_;
    return (u[2 * b] - u[2 * a]) * (u[2 * c + 1] - u[2 * a + 1])
         - (u[2 * b + 1] - u[2 * a + 1]) * (u[2 * c] - u[2 * a]);
  }

  bool same(std::size_t a, std::size_t b) const
  {
    return uv_[2 * a] == uv_[2 * b] && uv_[2 * a + 1] == uv_[2 * b + 1];
  }

  void make_ring(std::size_t k)
  {
    next_.resize(k);
    prev_.resize(k);
    alive_.assign(k, 1);
    blocked_by_.assign(k, npos);
    watch_head_.assign(k, npos);
    watch_.clear();
    for(std::size_t i = 0; i < k; ++i)
    {
      next_[i] = i + 1 == k ? 0 : i + 1;
      prev_[i] = i == 0 ? k - 1 : i - 1;
    }
    first_ = 0;
    unknown_.fill(k);
  }

  // removes the clipped corner x: its neighbours and the corners it blocked are tested again
  void remove(std::size_t x)
  {
    alive_[x] = 0;
    kill_in_tree(x);
    const std::size_t a = prev_[x], c = next_[x];
    next_[a] = c;
    prev_[c] = a;
    if(first_ == x)
      first_ = c;
    for(std::size_t y : {a, c})
      retest(y);
    for(std::size_t e = watch_head_[x]; e != npos; e = watch_[e].second)
    {
      const std::size_t y = watch_[e].first;
      if(alive_[y] && blocked_by_[y] == x)
        retest(y);
    }
  }

  void retest(std::size_t y)
  {
    blocked_by_[y] = npos;
    unknown_.insert(y);
  }

  // ------------------------------------------------------------------ the k-d tree

  // a static k-d tree over the corners: node i covers order_[lo, hi) (its children 2i+1, 2i+2
  // split it at the middle along the wider side of its box); leaves hold at most 8 corners.
  // Every node keeps its box and the number of remaining corners below it, so that dead
  // subtrees and subtrees away from the triangle are skipped.
  struct Tree_node
  {
    double box[4]; // min u, min v, max u, max v
    std::size_t lo, hi, alive;
  };

  static constexpr std::size_t leaf_size = 8;

  void make_tree(std::size_t k)
  {
    order_.resize(k);
    for(std::size_t i = 0; i < k; ++i)
      order_[i] = i;
    leaf_of_.resize(k);
    tree_.clear();
    double magnitude = 0;
    for(std::size_t i = 0; i < 2 * k; ++i)
      magnitude = std::max(magnitude, std::abs(uv_[i]));
    // far above the rounding errors of the turns (about 1e-16 of the magnitude)
    margin_ = 1e-9 * magnitude;
    if(!std::isfinite(margin_))
      margin_ = std::numeric_limits<double>::infinity(); // no pruning: the work cap bounds the search
    // nodes are numbered as in a binary heap; a node's range is split at its middle
    std::vector<std::size_t> stack{0};
    tree_.resize(1);
    tree_[0].lo = 0;
    tree_[0].hi = k;
    while(!stack.empty())
    {
      const std::size_t i = stack.back();
      stack.pop_back();
      const std::size_t lo = tree_[i].lo, hi = tree_[i].hi;
      double* box = tree_[i].box;
      box[0] = box[2] = uv_[2 * order_[lo]];
      box[1] = box[3] = uv_[2 * order_[lo] + 1];
      for(std::size_t j = lo; j < hi; ++j)
      {
        const double u = uv_[2 * order_[j]], v = uv_[2 * order_[j] + 1];
        box[0] = std::min(box[0], u);
        box[1] = std::min(box[1], v);
        box[2] = std::max(box[2], u);
        box[3] = std::max(box[3], v);
      }
      tree_[i].alive = hi - lo;
      if(hi - lo <= leaf_size)
      {
        // leaf: its corners in polygon order, so that the search does not depend on how
        // nth_element orders equal keys
        std::sort(order_.begin() + static_cast<std::ptrdiff_t>(lo), order_.begin() + static_cast<std::ptrdiff_t>(hi));
        for(std::size_t j = lo; j < hi; ++j)
          leaf_of_[order_[j]] = i;
        continue;
      }
      const std::size_t axis = (box[2] - box[0] >= box[3] - box[1]) ? 0 : 1;
      const std::size_t mid = lo + (hi - lo) / 2;
      const double* u = uv_;
      std::nth_element(order_.begin() + static_cast<std::ptrdiff_t>(lo),
                       order_.begin() + static_cast<std::ptrdiff_t>(mid),
                       order_.begin() + static_cast<std::ptrdiff_t>(hi),
                       [u, axis](std::size_t x, std::size_t y) {
                         const double cx = u[2 * x + axis], cy = u[2 * y + axis];
                         return cx < cy || (cx == cy && x < y);
                       });
      const std::size_t left = 2 * i + 1, right = 2 * i + 2;
      if(tree_.size() <= right)
        tree_.resize(right + 1);
      tree_[left].lo = lo;
      tree_[left].hi = mid;
      tree_[right].lo = mid;
      tree_[right].hi = hi;
      stack.push_back(right);
      stack.push_back(left);
    }
  }

  void kill_in_tree(std::size_t x)
  {
    std::size_t i = leaf_of_[x];
    for(;;)
    {
      --tree_[i].alive;
      if(i == 0)
        break;
      i = (i - 1) / 2;
    }
  }

  // true if the box lies beyond the margin on the outer side of the line through p and q
  bool box_outside(const double* box, const double* p, const double* q, double margin_turn) const
  {
    const double du = q[0] - p[0], dv = q[1] - p[1];
    for(int corner = 0; corner < 4; ++corner)
    {
      const double x = box[(corner & 1) ? 2 : 0], y = box[(corner & 2) ? 3 : 1];
      if(du * (y - p[1]) - dv * (x - p[0]) >= -margin_turn)
        return false;
    }
    return true;
  }

  // x if the corner b turns right or straight; else a remaining corner in the closed triangle
  // (a, b, c) not at the position of a, b or c; else npos (b is an ear)
  std::size_t find_blocker(std::size_t a, std::size_t b, std::size_t c)
  {
    ++work_;
    if(!(turn(a, b, c) > 0))
      return b;
    const double* u = uv_;
    const std::size_t t[3] = {a, b, c};
    double tbox[4] = {u[2 * a], u[2 * a + 1], u[2 * a], u[2 * a + 1]};
    double margin_turn[3];
    for(int e = 0; e < 3; ++e)
    {
      const double* p = u + 2 * t[e];
      const double* q = u + 2 * t[(e + 1) % 3];
      tbox[0] = std::min(tbox[0], p[0]);
      tbox[1] = std::min(tbox[1], p[1]);
      tbox[2] = std::max(tbox[2], p[0]);
      tbox[3] = std::max(tbox[3], p[1]);
      // a distance of `margin_` from the line, as a turn
      margin_turn[e] = margin_ * (std::abs(q[0] - p[0]) + std::abs(q[1] - p[1]));
    }
    stack_.clear();
    stack_.push_back(0);
    while(!stack_.empty())
    {
      const std::size_t i = stack_.back();
      stack_.pop_back();
      const Tree_node& node = tree_[i];
      ++work_;
      if(node.alive == 0 || node.box[0] > tbox[2] + margin_ || node.box[2] < tbox[0] - margin_
         || node.box[1] > tbox[3] + margin_ || node.box[3] < tbox[1] - margin_)
        continue;
      if(box_outside(node.box, u + 2 * a, u + 2 * b, margin_turn[0])
         || box_outside(node.box, u + 2 * b, u + 2 * c, margin_turn[1])
         || box_outside(node.box, u + 2 * c, u + 2 * a, margin_turn[2]))
        continue;
      if(node.hi - node.lo <= leaf_size)
      {
        for(std::size_t j = node.lo; j < node.hi; ++j)
        {
          const std::size_t q = order_[j];
          ++work_;
          if(!alive_[q] || q == a || q == b || q == c || same(q, a) || same(q, b) || same(q, c))
            continue;
          if(turn(a, b, q) >= 0 && turn(b, c, q) >= 0 && turn(c, a, q) >= 0)
            return q;
        }
        continue;
      }
      stack_.push_back(2 * i + 2);
      stack_.push_back(2 * i + 1);
    }
    return npos;
  }

  const double* uv_ = nullptr;
  std::vector<std::size_t> next_, prev_, blocked_by_, watch_head_;
  std::vector<std::pair<std::size_t, std::size_t>> watch_; // (blocked corner, next entry)
  std::vector<char> alive_;
  std::size_t first_ = 0;
  Successor_set unknown_; // corners whose ear status is not known
  std::size_t work_ = 0;
  // the k-d tree
  std::vector<Tree_node> tree_;
  std::vector<std::size_t> order_, leaf_of_, stack_;
  double margin_ = 0;
};

/// triangulates the polygon `polygon` (indices into `points`, any CGAL Point_3 type, read
/// through CGAL::to_double) by ear clipping in the plane of its Newell normal; appends the
/// triangles (indices into points) to `triangles`; returns the number of corners it could not
/// clip (0 when fully triangulated; then triangles gained polygon.size()-2 entries).
/// Deterministic; near-linear on spirals and combs.
///
/// When no ear is left (a self-intersecting or degenerate rest, e.g. all corners collinear),
/// the remaining corners are fanned from the first of them in polygon order and their number
/// is returned: `triangles` gains polygon.size()-2 entries for every polygon of 3 or more
/// corners. A polygon of fewer than 3 corners adds nothing and returns its size. The same
/// happens past the work cap of `Ear_clipper` (about 32 log2(k) visits per corner). The
/// triangles keep the orientation of the polygon. The rule and the order of the clips are
/// those of `Ear_clipper`.
///
/// \tparam Point a point type with `x()`, `y()`, `z()` (`CGAL::Point_3` of any kernel)
/// \param points the points the polygon's corners refer to
/// \param polygon the corners, in order (indices into `points`)
/// \param triangles where the triangles are appended, as indices into `points`
/// \return the number of corners left to the fan (0 if every ear was clipped)
template <class Point>
std::size_t triangulate_polygon(const std::vector<Point>& points, const std::vector<std::size_t>& polygon,
                                std::vector<std::array<std::size_t, 3>>& triangles)
{
  const std::size_t k = polygon.size();
  if(k < 3)
    return k;
  if(k == 3)
  {
    triangles.push_back({polygon[0], polygon[1], polygon[2]});
    return 0;
  }
  std::vector<double> uv;
  project_polygon(k,
                  [&](std::size_t i) {
                    const Point& p = points[polygon[i]];
                    return std::array<double, 3>{CGAL::to_double(p.x()), CGAL::to_double(p.y()),
                                                 CGAL::to_double(p.z())};
                  },
                  uv);
  Ear_clipper clipper;
  return clipper.clip(uv, k, [&](std::size_t a, std::size_t b, std::size_t c) {
    triangles.push_back({polygon[a], polygon[b], polygon[c]});
  });
}

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_TRIANGULATE_POLYGON_H
