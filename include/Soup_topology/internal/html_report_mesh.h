// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// What the HTML report draws, computed from the soup: the border and non-manifold edges, the
// holes (loops of border edges) and, for a soup above the display limit, a simplified mesh
// (vertex clustering) that keeps the areas around the border and non-manifold edges at full
// resolution.

#ifndef SOUP_TOPOLOGY_INTERNAL_HTML_REPORT_MESH_H
#define SOUP_TOPOLOGY_INTERNAL_HTML_REPORT_MESH_H

#include <Soup_topology/Adjacency_tables.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

namespace Soup_topology {
namespace internal {

using Html_point = std::array<double, 3>;
using Html_triangle = std::array<std::uint32_t, 3>;

/// a hole: a loop (or an open chain, where the border is not a set of loops) of border edges.
struct Html_hole
{
  std::size_t edges = 0;   ///< number of border edges
  double length = 0;       ///< sum of their lengths
  double size = 0;         ///< diagonal of their bounding box
  Html_point center{};     ///< center of their bounding box
};

/// the mesh as the page shows it.
struct Html_display_mesh
{
  std::vector<Html_point> points;
  std::vector<Html_triangle> triangles;
  std::vector<std::uint32_t> border_edges;        ///< pairs of indices into `points`
  std::vector<std::uint32_t> non_manifold_edges;  ///< pairs of indices into `points`
  bool decimated = false;
};

inline double html_distance(const Html_point& a, const Html_point& b)
{
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

/// the end vertices of the edges `edges` of `tables`, as pairs.
inline std::vector<std::uint32_t> html_edge_vertices(const Adjacency_tables& tables,
                                                     const std::vector<Adjacency_tables::Edge>& edges)
{
  std::vector<std::uint32_t> ends;
  ends.reserve(2 * edges.size());
  for(const Adjacency_tables::Edge& e : edges) {
    ends.push_back(tables.vertex(e.triangle, e.index));
    ends.push_back(tables.vertex(e.triangle, (e.index + 1) % 3));
  }
  return ends;
}

/// the holes formed by the border edges `border` (pairs of vertices), longest first. Chains are
/// followed through the vertices without regard to the edges' directions, so that a soup not yet
/// oriented still gives its loops.
inline std::vector<Html_hole> html_holes(const std::vector<Html_point>& points, const std::vector<std::uint32_t>& border)
{
  const std::size_t n = border.size() / 2;
  std::unordered_map<std::uint32_t, std::vector<std::size_t>> edges_at;
  edges_at.reserve(2 * n);
  for(std::size_t e = 0; e < n; ++e) {
    edges_at[border[2 * e]].push_back(e);
    edges_at[border[2 * e + 1]].push_back(e);
  }
  std::vector<char> used(n, 0);
  std::vector<Html_hole> holes;
  for(std::size_t first = 0; first < n; ++first) {
    if(used[first]) continue;
    Html_hole hole;
    Html_point low{}, high{};
    for(std::size_t c = 0; c < 3; ++c) {
      low[c] = std::numeric_limits<double>::infinity();
      high[c] = -std::numeric_limits<double>::infinity();
    }
    // Walks from both ends of the first edge until no unused edge continues the chain.
    used[first] = 1;
    std::vector<std::size_t> chain{first};
    for(int side = 0; side < 2; ++side) {
      std::uint32_t at = border[2 * first + static_cast<std::size_t>(side)];
      for(;;) {
        std::size_t next = n;
        for(std::size_t e : edges_at[at])
          if(!used[e]) { next = e; break; }
        if(next == n) break;
        used[next] = 1;
        chain.push_back(next);
        at = border[2 * next] == at ? border[2 * next + 1] : border[2 * next];
      }
    }
    for(std::size_t e : chain) {
      const Html_point& a = points[border[2 * e]];
      const Html_point& b = points[border[2 * e + 1]];
      hole.length += html_distance(a, b);
      for(std::size_t c = 0; c < 3; ++c) {
        low[c] = std::min({low[c], a[c], b[c]});
        high[c] = std::max({high[c], a[c], b[c]});
      }
    }
    hole.edges = chain.size();
    hole.size = html_distance(low, high);
    for(std::size_t c = 0; c < 3; ++c) hole.center[c] = (low[c] + high[c]) / 2;
    holes.push_back(hole);
  }
  std::stable_sort(holes.begin(), holes.end(),
                   [](const Html_hole& a, const Html_hole& b) { return a.length > b.length; });
  return holes;
}

/// the vertices of a soup kept as they are in the display mesh: those of every triangle with a
/// vertex on a problem edge (`border`, `non_manifold`), or none if those triangles alone are more
/// than half of `limit`.
inline std::vector<char> html_kept_vertices(std::size_t number_of_points, const std::vector<Html_triangle>& triangles,
                                            const std::vector<std::uint32_t>& border,
                                            const std::vector<std::uint32_t>& non_manifold, std::size_t limit)
{
  std::vector<char> on_problem_edge(number_of_points, 0), kept(number_of_points, 0);
  for(std::uint32_t v : border) on_problem_edge[v] = 1;
  for(std::uint32_t v : non_manifold) on_problem_edge[v] = 1;
  std::size_t kept_triangles = 0;
  for(const Html_triangle& t : triangles)
    if(on_problem_edge[t[0]] || on_problem_edge[t[1]] || on_problem_edge[t[2]]) {
      ++kept_triangles;
      for(std::uint32_t v : t) kept[v] = 1;
    }
  if(kept_triangles > limit / 2) kept.assign(number_of_points, 0);
  return kept;
}

/// the lower corner of the bounding box of `points` (in `low`) and the side of the first grid
/// cell tried: a surface of area A cut by cells of side h keeps about 2 A / h^2 triangles.
inline double html_first_cell_size(const std::vector<Html_point>& points, const std::vector<Html_triangle>& triangles,
                                   std::size_t limit, Html_point& low)
{
  Html_point high{};
  for(std::size_t c = 0; c < 3; ++c) {
    low[c] = std::numeric_limits<double>::infinity();
    high[c] = -std::numeric_limits<double>::infinity();
  }
  for(const Html_point& p : points)
    for(std::size_t c = 0; c < 3; ++c) { low[c] = std::min(low[c], p[c]); high[c] = std::max(high[c], p[c]); }
  double area = 0;
  for(const Html_triangle& t : triangles) {
    const Html_point &p = points[t[0]], &q = points[t[1]], &r = points[t[2]];
    const double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
    const double w[3] = {r[0] - p[0], r[1] - p[1], r[2] - p[2]};
    const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
    area += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  }
  const double diagonal = std::max(html_distance(low, high), std::numeric_limits<double>::min());
  return std::max(std::sqrt(2.2 * area / static_cast<double>(limit)), diagonal * 1e-6);
}

/// one vertex clustering on a grid of cells of side `cell` from `low`: every vertex not `kept`
/// goes to the cluster of its cell, a kept vertex to a cluster of its own. Fills `cluster` (the
/// cluster of each vertex), `display.triangles` (those with three distinct clusters) and
/// `display.points` (the centroid of each cluster).
inline void html_cluster_vertices(const std::vector<Html_point>& points, const std::vector<Html_triangle>& triangles,
                                  const std::vector<char>& kept, const Html_point& low, double cell,
                                  std::vector<std::uint32_t>& cluster, Html_display_mesh& display)
{
  std::unordered_map<std::uint64_t, std::uint32_t> cell_cluster;
  std::vector<Html_point> sums;
  std::vector<std::uint32_t> members;
  const auto grid = [&](double x, std::size_t c) {
    return static_cast<std::uint64_t>(std::min(std::floor((x - low[c]) / cell), 2097151.0)) & 0x1FFFFF;
  };
  cluster.resize(points.size());
  for(std::size_t v = 0; v < points.size(); ++v) {
    const Html_point& p = points[v];
    std::uint32_t id = static_cast<std::uint32_t>(sums.size());
    if(!kept[v]) {
      const std::uint64_t key = grid(p[0], 0) | (grid(p[1], 1) << 21) | (grid(p[2], 2) << 42);
      id = cell_cluster.emplace(key, id).first->second;
    }
    if(id == sums.size()) { sums.push_back({0, 0, 0}); members.push_back(0); }
    cluster[v] = id;
    for(std::size_t c = 0; c < 3; ++c) sums[id][c] += p[c];
    ++members[id];
  }
  display.triangles.clear();
  for(const Html_triangle& t : triangles) {
    const Html_triangle d{cluster[t[0]], cluster[t[1]], cluster[t[2]]};
    if(d[0] != d[1] && d[1] != d[2] && d[2] != d[0]) display.triangles.push_back(d);
  }
  display.points.resize(sums.size());
  for(std::size_t i = 0; i < sums.size(); ++i)
    for(std::size_t c = 0; c < 3; ++c) display.points[i][c] = members[i] ? sums[i][c] / members[i] : 0;
}

/// the display mesh of a soup: the soup itself when it has at most `limit` triangles; otherwise
/// a vertex clustering on a grid, coarsened until at most `limit` triangles remain. The vertices
/// of the triangles that touch a border or non-manifold edge are kept as they are (unless those
/// triangles alone are more than half the limit), so the problem areas stay at full resolution.
inline Html_display_mesh html_display_mesh(const std::vector<Html_point>& points,
                                           const std::vector<Html_triangle>& triangles,
                                           const std::vector<std::uint32_t>& border,
                                           const std::vector<std::uint32_t>& non_manifold, std::size_t limit)
{
  Html_display_mesh display;
  if(triangles.size() <= limit) {
    display.points = points;
    display.triangles = triangles;
    display.border_edges = border;
    display.non_manifold_edges = non_manifold;
    return display;
  }
  display.decimated = true;
  const std::vector<char> kept = html_kept_vertices(points.size(), triangles, border, non_manifold, limit);
  Html_point low{};
  double cell = html_first_cell_size(points, triangles, limit, low);
  std::vector<std::uint32_t> cluster;
  for(int attempt = 0; attempt < 40; ++attempt, cell *= 1.3) {
    html_cluster_vertices(points, triangles, kept, low, cell, cluster, display);
    if(display.triangles.size() <= limit) break;
  }
  const auto map_edges = [&](const std::vector<std::uint32_t>& edges, std::vector<std::uint32_t>& out) {
    for(std::size_t e = 0; e + 1 < edges.size(); e += 2)
      if(cluster[edges[e]] != cluster[edges[e + 1]]) {
        out.push_back(cluster[edges[e]]);
        out.push_back(cluster[edges[e + 1]]);
      }
  };
  map_edges(border, display.border_edges);
  map_edges(non_manifold, display.non_manifold_edges);
  return display;
}

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_HTML_REPORT_MESH_H
