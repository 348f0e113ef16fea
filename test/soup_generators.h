// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Broken soups made from clean meshes, for the tests and the benchmarks:
// - `subdivide_midpoints`: 1-to-4 split of every triangle (to reach a million triangles);
// - `t_junction_soup`: the mesh cut into patches whose shared borders are tessellated
//   differently on the two sides (T-junctions), with every patch owning its own copies of its
//   vertices, each copy jittered;
// - `small_feature_soup`: the same with patches around random seeds, and split points placed
//   within a given distance of an edge's end point (features below the tolerance);
// - `crowded_scattered_soup`: separate triangles of random sizes scattered in a unit cube, whose
//   borders crowd each other (the candidate budget of the gap analysis).

#ifndef SOUP_TOPOLOGY_TEST_SOUP_GENERATORS_H
#define SOUP_TOPOLOGY_TEST_SOUP_GENERATORS_H

#include <CGAL/number_utils.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <map>
#include <random>
#include <unordered_map>
#include <utility>
#include <vector>

namespace soup_test {

using Index_triangle = std::array<std::size_t, 3>;

/// splits every triangle into 4 at its edge midpoints (shared midpoints are shared).
template <class Point>
void subdivide_midpoints(std::vector<Point>& points, std::vector<Index_triangle>& triangles)
{
  std::unordered_map<unsigned long long, std::size_t> midpoint;
  midpoint.reserve(triangles.size() * 2);
  auto mid = [&](std::size_t a, std::size_t b) {
    const unsigned long long key = (static_cast<unsigned long long>(std::min(a, b)) << 32) | std::max(a, b);
    auto it = midpoint.find(key);
    if(it != midpoint.end()) return it->second;
    const Point& p = points[a];
    const Point& q = points[b];
    points.push_back(Point((p.x() + q.x()) / 2, (p.y() + q.y()) / 2, (p.z() + q.z()) / 2));
    midpoint.emplace(key, points.size() - 1);
    return points.size() - 1;
  };
  std::vector<Index_triangle> out;
  out.reserve(4 * triangles.size());
  for(const Index_triangle& t : triangles) {
    const std::size_t m0 = mid(t[0], t[1]), m1 = mid(t[1], t[2]), m2 = mid(t[2], t[0]);
    out.push_back({t[0], m0, m2});
    out.push_back({m0, t[1], m1});
    out.push_back({m2, m1, t[2]});
    out.push_back({m0, m1, m2});
  }
  triangles.swap(out);
}

/// A soup with T-junctions and duplicated, jittered border vertices.
template <class Point>
struct T_junction_soup
{
  std::vector<Point> points;
  std::vector<Index_triangle> triangles;
  std::size_t patches = 0;
  std::size_t t_junctions = 0;   ///< midpoints inserted on one side of a patch border
};

/// cuts the closed mesh (points, triangles) into `slabs` patches along x (by triangle centroid);
/// on every other edge shared by two patches, the triangle of the first patch is split at the
/// edge midpoint while its neighbour keeps the whole edge (a T-junction); then every patch gets
/// its own copies of its vertices, each coordinate moved by a uniform random amount in
/// [-jitter, jitter].
template <class Point>
T_junction_soup<Point> t_junction_soup(const std::vector<Point>& points, const std::vector<Index_triangle>& triangles,
                                       int slabs, double jitter, unsigned seed)
{
  T_junction_soup<Point> soup;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for(const Point& p : points) { lo = std::min(lo, CGAL::to_double(p.x())); hi = std::max(hi, CGAL::to_double(p.x())); }
  std::vector<int> patch(triangles.size());
  for(std::size_t t = 0; t < triangles.size(); ++t) {
    double cx = 0;
    for(std::size_t v : triangles[t]) cx += CGAL::to_double(points[v].x());
    cx /= 3;
    patch[t] = std::min(slabs - 1, static_cast<int>((cx - lo) / (hi - lo) * slabs));
  }
  soup.patches = static_cast<std::size_t>(slabs);
  // Edges shared by two patches: (smaller patch triangle, local edge).
  std::map<std::pair<std::size_t, std::size_t>, std::vector<std::pair<std::size_t, int>>> edges;
  for(std::size_t t = 0; t < triangles.size(); ++t)
    for(int i = 0; i < 3; ++i) {
      std::size_t a = triangles[t][i], b = triangles[t][(i + 1) % 3];
      edges[{std::min(a, b), std::max(a, b)}].emplace_back(t, i);
    }
  std::vector<int> split_edge(triangles.size(), -1);
  std::size_t seam = 0;
  for(const auto& kv : edges) {
    if(kv.second.size() != 2) continue;
    const auto [t0, i0] = kv.second[0];
    const auto [t1, i1] = kv.second[1];
    if(patch[t0] == patch[t1]) continue;
    if(seam++ % 2 != 0) continue;
    const std::size_t t = patch[t0] < patch[t1] ? t0 : t1;
    const int i = patch[t0] < patch[t1] ? i0 : i1;
    if(split_edge[t] == -1) split_edge[t] = i;
  }
  // Triangles of the soup, in original vertex ids or new midpoint ids.
  std::vector<Point> all = points;
  std::vector<std::pair<Index_triangle, int>> tris; // (triangle, patch)
  for(std::size_t t = 0; t < triangles.size(); ++t) {
    const Index_triangle& tr = triangles[t];
    const int i = split_edge[t];
    if(i < 0) { tris.push_back({tr, patch[t]}); continue; }
    const std::size_t a = tr[i], b = tr[(i + 1) % 3], c = tr[(i + 2) % 3];
    const Point& p = points[a];
    const Point& q = points[b];
    all.push_back(Point((p.x() + q.x()) / 2, (p.y() + q.y()) / 2, (p.z() + q.z()) / 2));
    const std::size_t m = all.size() - 1;
    tris.push_back({{a, m, c}, patch[t]});
    tris.push_back({{m, b, c}, patch[t]});
    ++soup.t_junctions;
  }
  // Per-patch copies of the vertices, jittered.
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> d(-jitter, jitter);
  std::map<std::pair<int, std::size_t>, std::size_t> copy;
  for(const auto& [tr, pt] : tris) {
    Index_triangle out;
    for(int k = 0; k < 3; ++k) {
      auto ins = copy.emplace(std::make_pair(pt, tr[k]), soup.points.size());
      if(ins.second) {
        const Point& p = all[tr[k]];
        soup.points.push_back(jitter > 0 ? Point(p.x() + d(rng), p.y() + d(rng), p.z() + d(rng)) : p);
      }
      out[k] = ins.first->second;
    }
    soup.triangles.push_back(out);
  }
  return soup;
}

/// A soup whose seams hold features smaller than the tolerance (issue 18).
template <class Point>
struct Small_feature_soup
{
  std::vector<Point> points;
  std::vector<Index_triangle> triangles;
  std::size_t patches = 0;
  std::size_t t_junctions = 0;            ///< border edges split on one side of a seam
  std::size_t near_end_t_junctions = 0;   ///< of which the split point lies within `near_distance` of an end point
};

/// cuts the closed mesh (points, triangles) into `patches` patches (every triangle goes to the
/// nearest of `patches` seed triangles, by centroid, the seeds drawn from `seed`); on every
/// other edge shared by two patches, the triangle on the side of the smaller patch id is split
/// at a point of the edge while its neighbour keeps the whole edge (a T-junction). A fraction
/// `near_fraction` of the split points lie at a distance in [0.1, 0.5] `near_distance` from an
/// end point of the edge (drawn at random), the others at a parameter in [0.3, 0.7]. Then every
/// patch gets its own copies of its vertices, each coordinate moved by a uniform random amount
/// in [-jitter, jitter]. The split points lie on the edges of the input mesh: the unperturbed
/// surface is the input's. Deterministic for a given `seed`.
template <class Point>
Small_feature_soup<Point> small_feature_soup(const std::vector<Point>& points, const std::vector<Index_triangle>& triangles,
                                             std::size_t patches, double jitter, double near_fraction,
                                             double near_distance, unsigned seed)
{
  Small_feature_soup<Point> soup;
  soup.patches = patches;
  std::mt19937_64 rng(seed);
  auto centroid = [&](std::size_t t) {
    std::array<double, 3> c{{0, 0, 0}};
    for(std::size_t v : triangles[t]) {
      c[0] += CGAL::to_double(points[v].x()) / 3;
      c[1] += CGAL::to_double(points[v].y()) / 3;
      c[2] += CGAL::to_double(points[v].z()) / 3;
    }
    return c;
  };
  std::vector<std::array<double, 3>> seeds;
  std::uniform_int_distribution<std::size_t> pick(0, triangles.size() - 1);
  for(std::size_t k = 0; k < patches; ++k) seeds.push_back(centroid(pick(rng)));
  std::vector<std::size_t> patch(triangles.size(), 0);
  for(std::size_t t = 0; t < triangles.size(); ++t) {
    const std::array<double, 3> c = centroid(t);
    double best = std::numeric_limits<double>::infinity();
    for(std::size_t k = 0; k < seeds.size(); ++k) {
      const double d = (c[0] - seeds[k][0]) * (c[0] - seeds[k][0]) + (c[1] - seeds[k][1]) * (c[1] - seeds[k][1]) +
                       (c[2] - seeds[k][2]) * (c[2] - seeds[k][2]);
      if(d < best) { best = d; patch[t] = k; }
    }
  }
  // Seam edges, in the order of their sorted end points.
  std::map<std::pair<std::size_t, std::size_t>, std::vector<std::pair<std::size_t, int>>> edges;
  for(std::size_t t = 0; t < triangles.size(); ++t)
    for(int i = 0; i < 3; ++i) {
      const std::size_t a = triangles[t][i], b = triangles[t][(i + 1) % 3];
      edges[{std::min(a, b), std::max(a, b)}].emplace_back(t, i);
    }
  std::vector<int> split_edge(triangles.size(), -1);
  std::size_t seam = 0;
  for(const auto& kv : edges) {
    if(kv.second.size() != 2) continue;
    const auto [t0, i0] = kv.second[0];
    const auto [t1, i1] = kv.second[1];
    if(patch[t0] == patch[t1]) continue;
    if(seam++ % 2 != 0) continue;
    const std::size_t t = patch[t0] < patch[t1] ? t0 : t1;
    if(split_edge[t] == -1) split_edge[t] = patch[t0] < patch[t1] ? i0 : i1;
  }
  std::uniform_real_distribution<double> unit(0, 1);
  std::vector<Point> all = points;
  std::vector<std::pair<Index_triangle, std::size_t>> tris; // (triangle, patch)
  for(std::size_t t = 0; t < triangles.size(); ++t) {
    const Index_triangle& tr = triangles[t];
    const int i = split_edge[t];
    if(i < 0) { tris.push_back({tr, patch[t]}); continue; }
    const std::size_t a = tr[i], b = tr[(i + 1) % 3], c = tr[(i + 2) % 3];
    const Point& p = points[a];
    const Point& q = points[b];
    const double dx = CGAL::to_double(q.x() - p.x()), dy = CGAL::to_double(q.y() - p.y()),
                 dz = CGAL::to_double(q.z() - p.z());
    const double length = std::sqrt(dx * dx + dy * dy + dz * dz);
    double s = 0.3 + 0.4 * unit(rng);
    const bool near = unit(rng) < near_fraction && length > 2 * near_distance;
    if(near) {
      const double from_end = (0.1 + 0.4 * unit(rng)) * near_distance / length;
      s = unit(rng) < 0.5 ? from_end : 1 - from_end;
      ++soup.near_end_t_junctions;
    }
    all.push_back(Point(p.x() + s * (q.x() - p.x()), p.y() + s * (q.y() - p.y()), p.z() + s * (q.z() - p.z())));
    const std::size_t m = all.size() - 1;
    tris.push_back({{a, m, c}, patch[t]});
    tris.push_back({{m, b, c}, patch[t]});
    ++soup.t_junctions;
  }
  std::uniform_real_distribution<double> d(-jitter, jitter);
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> copy;
  for(const auto& [tr, pt] : tris) {
    Index_triangle out;
    for(int k = 0; k < 3; ++k) {
      auto ins = copy.emplace(std::make_pair(pt, tr[k]), soup.points.size());
      if(ins.second) {
        const Point& p = all[tr[k]];
        soup.points.push_back(jitter > 0 ? Point(p.x() + d(rng), p.y() + d(rng), p.z() + d(rng)) : p);
      }
      out[k] = ins.first->second;
    }
    soup.triangles.push_back(out);
  }
  return soup;
}

/// `n` separate triangles, each with corners within 0.3 (per coordinate) of a random centre in
/// the unit cube: every border crowds the others (20,000 exceed the gap analysis' candidate budget).
template <class Point>
void crowded_scattered_soup(std::size_t n, std::vector<Point>& points, std::vector<Index_triangle>& triangles)
{
  std::mt19937_64 random(7);
  auto coordinate = [&random] { return double(random() >> 11) * 0x1.0p-53; };
  for(std::size_t t = 0; t < n; ++t) {
    const double c[3] = {coordinate(), coordinate(), coordinate()};
    for(std::size_t k = 0; k < 3; ++k)
      points.emplace_back(c[0] + 0.6 * (coordinate() - 0.5), c[1] + 0.6 * (coordinate() - 0.5),
                          c[2] + 0.6 * (coordinate() - 0.5));
    triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
  }
}

} // namespace soup_test

#endif // SOUP_TOPOLOGY_TEST_SOUP_GENERATORS_H
