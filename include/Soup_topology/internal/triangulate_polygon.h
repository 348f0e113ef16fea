// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// This file is part of Soup_topology, a header-only C++17 library that rebuilds the topology
// of triangle soups.

// Ear clipping of one polygon in the plane of its Newell normal, shared by the readers that
// meet polygons of more than three corners.

#ifndef SOUP_TOPOLOGY_INTERNAL_TRIANGULATE_POLYGON_H
#define SOUP_TOPOLOGY_INTERNAL_TRIANGULATE_POLYGON_H

#include <CGAL/number_utils.h>

#include <array>
#include <cmath>
#include <cstddef>
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
    uv[2 * i] = p[u];
    uv[2 * i + 1] = p[v];
  }
  return r;
}

/// Ear clipping of a counterclockwise polygon given by its 2D corners `uv` (2k doubles).
/// Emits triangles of corner numbers (0 to k-1) through `emit(a, b, c)`, in the polygon's
/// orientation. A corner is an ear if it turns left and no other corner (but those at the
/// position of one of its three corners) lies in the closed triangle. The candidate corner
/// starts at corner 0; after a clip the next candidate is the corner after the clipped one,
/// after a miss the next corner. If no corner is an ear (self-intersecting or degenerate
/// rest), the remaining corners are fanned from the first remaining one (in polygon order) and
/// their number is returned; 0 otherwise.
class Ear_clipper
{
public:
  template <class Emit>
  std::size_t clip(const std::vector<double>& uv, std::size_t k, const Emit& emit)
  {
    if(k < 3)
      return k;
    auto turn = [&](std::size_t a, std::size_t b, std::size_t c) {
      return (uv[2 * b] - uv[2 * a]) * (uv[2 * c + 1] - uv[2 * a + 1])
           - (uv[2 * b + 1] - uv[2 * a + 1]) * (uv[2 * c] - uv[2 * a]);
    };
    auto same = [&](std::size_t a, std::size_t b) {
      return uv[2 * a] == uv[2 * b] && uv[2 * a + 1] == uv[2 * b + 1];
    };
    std::vector<std::size_t>& ring = ring_;
    ring.resize(k);
    for(std::size_t i = 0; i < k; ++i)
      ring[i] = i;
    std::size_t cursor = 0, misses = 0;
    while(ring.size() > 3)
    {
      const std::size_t m = ring.size();
      const std::size_t ia = (cursor + m - 1) % m, ib = cursor % m, ic = (cursor + 1) % m;
      const std::size_t a = ring[ia], b = ring[ib], c = ring[ic];
      bool ear = turn(a, b, c) > 0;
      for(std::size_t j = 0; ear && j < m; ++j)
      {
        const std::size_t q = ring[j];
        if(q == a || q == b || q == c || same(q, a) || same(q, b) || same(q, c))
          continue;
        if(turn(a, b, q) >= 0 && turn(b, c, q) >= 0 && turn(c, a, q) >= 0)
          ear = false;
      }
      if(ear)
      {
        emit(a, b, c);
        ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(ib));
        cursor = ib;
        misses = 0;
      }
      else
      {
        ++cursor;
        if(++misses > m)
        {
          for(std::size_t i = 1; i + 1 < m; ++i)
            emit(ring[0], ring[i], ring[i + 1]);
          return m;
        }
      }
    }
    emit(ring[0], ring[1], ring[2]);
    return 0;
  }

private:
  std::vector<std::size_t> ring_;
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
/// corners. A polygon of fewer than 3 corners adds nothing and returns its size.
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
