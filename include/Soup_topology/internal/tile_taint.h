// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The taint of a tile (doc/Soup_topology/Tiled_repair_design.md): while a tile's region is
// repaired, which of its points may have another state than in the repair of the whole soup. An
// observer of the phases of `Soup_reconstruction::weld_and_split_in_rounds()`.

#ifndef SOUP_TOPOLOGY_INTERNAL_TILE_TAINT_H
#define SOUP_TOPOLOGY_INTERNAL_TILE_TAINT_H

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/Octree.h>
#include <Soup_topology/internal/snap_vertices_worker.h>

#include <CGAL/number_utils.h>
#include <CGAL/property_map.h>
#include <CGAL/squared_distance_3.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <utility>
#include <vector>

namespace Soup_topology {
namespace internal {

/// Follows the taint of the points of one tile, phase by phase, by the rules of the design page,
/// each applied so as to taint at least what the page's rules taint (more is allowed: a tainted
/// owned triangle only makes the tile run again on a larger region).
///
/// A point is *tainted* when its own state (position, the vertex it is merged into, whether it
/// holds welds) may differ from the whole soup's. A triangle with a tainted corner may differ; a
/// triangle without one is the whole soup's (triangles change only through decisions about their
/// corners, or through a split, whose corners are then tainted). So the star of a point may differ
/// only when the point is a corner of a triangle with a tainted corner (the point is then in the
/// *star band*), and the border status of an edge only when it is an edge of such a triangle.
/// The band is computed afresh before each phase, and taint spreads only through decisions:
///
/// - **before a weld**: a *decision unit* joins the candidates (end points of border edges)
///   within the tolerance of each other and the candidate corners of every triangle that is not
///   *rigid*. A unit is uncertified when one of its members is in the band or shallow (depth at
///   most the tolerance), has a point of the band within the tolerance (it may be a candidate of
///   the whole soup), or has a triangle with a shallow corner; its members are tainted. Under
///   `Small_features::COLLAPSE` a unit also joins the corners of the triangles around the members
///   of a component that holds a corner of a triangle with an edge at most twice the tolerance
///   (the coverage test of a collapse reads them).
/// - **before a split**: a vertex is uncertain when it is shallow, in the band, or within twice
///   the tolerance of an edge of a triangle with a tainted corner (the whole soup's edge may lie a
///   tolerance away). The split of a triangle without a tainted corner is uncertified when one of
///   its border edges may have a vertex within the tolerance that the region misses (the edge's
///   depth bound is at most twice the tolerance) or has an uncertain vertex other than the
///   triangle's corners within the tolerance; the split of a triangle with a tainted corner, or
///   along an edge it shares with one (whose border status may differ), when a vertex other than
///   its corners lies within twice the tolerance of that edge. An uncertified split taints those
///   vertices (every triangle a split makes holds one) and the triangle's corners unless one is
///   tainted already. Points merged away are left out unless tainted (untainted, they are merged
///   away in the whole soup too).
///
/// `depth[v]` is a lower bound on the distance from point `v` to the outside of the region (it
/// may be negative). Every test compares distances with the tolerance grown by a relative 1e-9:
/// a superset of the pairs the weld and the split decide exactly.
template <class Kernel>
class Tile_taint
{
public:
  using Point = typename Kernel::Point_3;
  using FT = typename Kernel::FT;
  using size_type = Adjacency_tables::size_type;

  /// \param collapse whether the weld runs under `Small_features::COLLAPSE`
  Tile_taint(const std::vector<Point>& points, std::vector<double> depth, double tolerance, bool collapse,
             const Kernel& kernel)
    : tree_(points, CGAL::Identity_property_map<Point>(), kernel), depth_(std::move(depth)), tolerance_(tolerance),
      radius_(FT(tolerance * (1 + 1e-9))), twice_radius_(FT(2 * tolerance * (1 + 1e-9))), collapse_(collapse),
      tainted_(points.size(), 0), budget_(crowd_budget * points.size() + 65536)
  {}

  /// `true` if the state of point `v` may differ from the whole soup's.
  bool tainted(size_type v) const { return tainted_[v] != 0; }
  /// marks point `v` as tainted.
  void taint(size_type v) { tainted_[v] = 1; }

  /// The work of a phase is counted in points read from the answers of the queries (and in
  /// triangles read around non-manifold edges). Past `crowd_budget` a point of the region, the
  /// region is crowded (e.g. thousands of points within the tolerance of each other): the taint
  /// stops following the phases, which would cost the square of the crowd, and reports it here.
  /// The caller must then repair the soup without tiles.
  static constexpr std::size_t crowd_budget = 64;
  /// `true` if a phase exceeded the budget of work: the taint is then incomplete.
  bool crowded() const { return crowded_; }

  template <class Points>
  void before_weld(const Points& points, const Adjacency_tables& tables)
  {
    if(!start_phase()) return;
    const std::vector<char> band = star_band(tables);
    std::vector<char> candidate(points.size(), 0);
    for(size_type t = 0; t < tables.number_of_triangles(); ++t)
      for(int i = 0; i < 3; ++i)
        if(tables.is_border_edge(t, i)) candidate[tables.vertex(t, i)] = candidate[tables.vertex(t, (i + 1) % 3)] = 1;
    std::vector<char> reached(points.size(), 0);
    std::vector<size_type> stack;
    const auto reach = [&](size_type v) {
      if(candidate[v] && !reached[v]) {
        reached[v] = 1;
        stack.push_back(v);
      }
    };
    // The seeds: members whose unit cannot be certified.
    for(size_type v = 0; v < points.size(); ++v) {
      if(!candidate[v]) continue;
      bool seed = band[v] || shallow(v);
      for(size_type t : tables.triangles_around_vertex(v))
        for(size_type u : tables.triangle(t)) seed = seed || shallow(u);
      if(seed) reach(v);
    }
    std::vector<std::size_t> near;
    // A tainted point of the whole soup may lie a tolerance away from its place here.
    for(size_type x = 0; x < points.size(); ++x) {
      if(!band[x]) continue;
      near.clear();
      tree_.vertices_near_point(points[x], tainted_[x] ? twice_radius_ : radius_, std::back_inserter(near));
      if(!spend(near.size())) return;
      for(std::size_t y : near) reach(static_cast<size_type>(y));
    }
    const std::vector<char> collapsing = collapse_ ? members_near_collapses(points, tables, candidate) : std::vector<char>();
    if(crowded_) return;
    // Their units: the tolerance graph, the triangles that are not rigid and, under COLLAPSE,
    // the stars of the members of a component with a corner of a triangle that may collapse.
    while(!stack.empty()) {
      const size_type v = stack.back();
      stack.pop_back();
      near.clear();
      tree_.vertices_near_point(points[v], radius_, std::back_inserter(near));
      if(!spend(near.size())) return;
      for(std::size_t y : near) reach(static_cast<size_type>(y));
      for(size_type t : tables.triangles_around_vertex(v)) {
        const Adjacency_tables::Triangle& tr = tables.triangle(t);
        const bool whole = !rigid(points[tr[0]], points[tr[1]], points[tr[2]]) || (collapse_ && collapsing[v]);
        for(size_type u : tr)
          if(whole || (collapse_ && collapsing[u])) reach(u);
      }
    }
    for(size_type v = 0; v < points.size(); ++v)
      if(reached[v]) tainted_[v] = 1;
  }

  template <class Points>
  void after_weld(const Points&, const Adjacency_tables&)
  {}

  template <class Points>
  void before_split(const Points& points, const Adjacency_tables& tables)
  {
    if(!start_phase()) return;
    const std::vector<char> band = star_band(tables);
    const auto differs = [&](size_type t) {
      const Adjacency_tables::Triangle& tr = tables.triangle(t);
      return tainted_[tr[0]] || tainted_[tr[1]] || tainted_[tr[2]];
    };
    // A point merged away here is merged away in the whole soup unless it is tainted: otherwise
    // it is no vertex there either, and no split reads it.
    const auto is_vertex = [&](std::size_t y) { return tables.degree(static_cast<size_type>(y)) > 0 || tainted_[y]; };
    // Uncertain vertices: in the band, or near an edge whose border status may differ (the
    // whole soup's edge may lie a tolerance away, where a tainted end moved). The vertices within
    // twice the tolerance of the edges of the triangles with a tainted corner are kept for the
    // second pass (`cached`, three ranges per such triangle).
    std::vector<char> dirty(band);
    constexpr std::uint32_t no_slot = static_cast<std::uint32_t>(-1);
    std::vector<std::uint32_t> slot(tables.number_of_triangles(), no_slot);
    std::vector<std::size_t> cached, cached_begin;
    for(size_type t = 0; t < tables.number_of_triangles(); ++t) {
      if(!differs(t)) continue;
      slot[t] = static_cast<std::uint32_t>(cached_begin.size() / 3);
      for(int i = 0; i < 3; ++i) {
        cached_begin.push_back(cached.size());
        const std::size_t before = cached.size();
        tree_.vertices_near_segment(points[tables.vertex(t, i)], points[tables.vertex(t, (i + 1) % 3)], twice_radius_,
                                    std::back_inserter(cached));
        cached.erase(std::remove_if(cached.begin() + std::ptrdiff_t(before), cached.end(),
                                    [&](std::size_t y) { return !is_vertex(y); }),
                     cached.end());
        if(!spend(cached.size() - before)) return;
        for(std::size_t k = before; k < cached.size(); ++k) dirty[cached[k]] = 1;
      }
    }
    cached_begin.push_back(cached.size());
    // Appends to `out` the vertices within `radius` (the tolerance, or twice it) of edge `i` of
    // `t`, from the cache when the edge is one of a triangle with a tainted corner.
    const auto near_edge = [&](size_type t, int i, bool twice, std::vector<std::size_t>& out) {
      size_type holder = t;
      int local = i;
      if(twice && slot[t] == no_slot) {
        const size_type n = tables.neighbor(t, i);
        if(n != Adjacency_tables::border_edge && n != Adjacency_tables::non_manifold_edge && slot[n] != no_slot) {
          holder = n;
          local = tables.edge_index(n, tables.vertex(t, i), tables.vertex(t, (i + 1) % 3));
        }
      }
      if(twice && slot[holder] != no_slot) {
        const std::size_t k = 3 * std::size_t(slot[holder]) + std::size_t(local);
        out.insert(out.end(), cached.begin() + std::ptrdiff_t(cached_begin[k]), cached.begin() + std::ptrdiff_t(cached_begin[k + 1]));
        return;
      }
      const std::size_t before = out.size();
      tree_.vertices_near_segment(points[tables.vertex(t, i)], points[tables.vertex(t, (i + 1) % 3)],
                                  twice ? twice_radius_ : radius_, std::back_inserter(out));
      out.erase(std::remove_if(out.begin() + std::ptrdiff_t(before), out.end(), [&](std::size_t y) { return !is_vertex(y); }),
                out.end());
    };
    // Whether the edge `i` of `t` is an edge of a triangle with a tainted corner.
    std::vector<size_type> around;
    const auto edge_may_differ = [&](size_type t, int i) {
      const size_type n = tables.neighbor(t, i);
      if(n == Adjacency_tables::border_edge) return false;
      if(n != Adjacency_tables::non_manifold_edge) return differs(n);
      around.clear();
      tables.triangles_around_edge(t, i, std::back_inserter(around));
      spend(around.size());
      return std::any_of(around.begin(), around.end(), differs);
    };
    std::vector<size_type> to_taint;
    std::vector<std::size_t> found;
    for(size_type t = 0; t < tables.number_of_triangles(); ++t) {
      const Adjacency_tables::Triangle& tr = tables.triangle(t);
      const bool tainted_corner = differs(t);
      bool uncertain = false;
      found.clear();
      for(int i = 0; i < 3; ++i) {
        const size_type a = tr[std::size_t(i)], b = tr[std::size_t(i + 1) % 3];
        const bool border = tables.is_border_edge(t, i);
        if(!border && !tainted_corner && !(band[a] && band[b] && edge_may_differ(t, i))) continue;
        const std::size_t before = found.size();
        near_edge(t, i, tainted_corner || !border, found);
        if(!spend(found.size() - before)) return;
        if(border) {
          const double length = std::sqrt(CGAL::to_double(CGAL::squared_distance(points[a], points[b])));
          if((depth_[a] + depth_[b] - length) / 2 <= 2 * tolerance_ * (1 + 1e-9)) uncertain = true;
          // The decisions about the edge read the states of the vertices near it and of its
          // triangle, not the stars of its ends (the edge's depth bound covers the ends).
          for(std::size_t k = before; k < found.size(); ++k)
            if(found[k] != tr[0] && found[k] != tr[1] && found[k] != tr[2] &&
               (dirty[found[k]] || shallow(static_cast<size_type>(found[k]))))
              uncertain = true;
        }
        // An edge that may differ from the whole soup's: a split needs a vertex near it.
        if(border && !tainted_corner) continue;
        for(std::size_t k = before; k < found.size() && !uncertain; ++k)
          if(found[k] != tr[0] && found[k] != tr[1] && found[k] != tr[2]) uncertain = true;
      }
      if(!uncertain) continue;
      // The triangles a split makes hold the split vertex; the triangle left whole holds a tainted
      // corner already, or gets three.
      if(!tainted_corner) to_taint.insert(to_taint.end(), tr.begin(), tr.end());
      for(std::size_t y : found)
        if(y != tr[0] && y != tr[1] && y != tr[2]) to_taint.push_back(static_cast<size_type>(y));
    }
    for(size_type v : to_taint) tainted_[v] = 1;
  }

  template <class Points>
  void after_split(const Points&, const Adjacency_tables&)
  {}

private:
  // Starts the count of a phase's work; `false` once the region is crowded.
  bool start_phase()
  {
    work_ = 0;
    return !crowded_;
  }
  // Counts `n` more points read; `false` (and crowded) past the budget.
  bool spend(std::size_t n)
  {
    work_ += n;
    if(work_ > budget_) crowded_ = true;
    return !crowded_;
  }

  // The star band: the tainted points and the corners of the triangles with a tainted corner.
  std::vector<char> star_band(const Adjacency_tables& tables) const
  {
    std::vector<char> band(tainted_);
    for(const Adjacency_tables::Triangle& tr : tables.triangles())
      if(tainted_[tr[0]] || tainted_[tr[1]] || tainted_[tr[2]]) band[tr[0]] = band[tr[1]] = band[tr[2]] = 1;
    return band;
  }

  // Under COLLAPSE: the candidates of the components (of the tolerance graph) that hold a corner
  // of a triangle with an edge at most twice the tolerance (one that may collapse).
  template <class Points>
  std::vector<char> members_near_collapses(const Points& points, const Adjacency_tables& tables,
                                           const std::vector<char>& candidate)
  {
    std::vector<char> flagged(points.size(), 0);
    std::vector<size_type> stack;
    const double four_t2 = 4 * tolerance_ * tolerance_ * (1 + 1e-9);
    for(const Adjacency_tables::Triangle& tr : tables.triangles())
      for(int i = 0; i < 3; ++i)
        if(CGAL::to_double(CGAL::squared_distance(points[tr[std::size_t(i)]], points[tr[std::size_t(i + 1) % 3]])) <= four_t2)
          for(size_type u : tr)
            if(candidate[u] && !flagged[u]) {
              flagged[u] = 1;
              stack.push_back(u);
            }
    std::vector<std::size_t> near;
    while(!stack.empty()) {
      const size_type v = stack.back();
      stack.pop_back();
      near.clear();
      tree_.vertices_near_point(points[v], radius_, std::back_inserter(near));
      if(!spend(near.size())) break;
      for(std::size_t y : near)
        if(candidate[y] && !flagged[y]) {
          flagged[y] = 1;
          stack.push_back(static_cast<size_type>(y));
        }
    }
    return flagged;
  }

  bool shallow(size_type v) const { return depth_[v] <= tolerance_ * (1 + 1e-9); }

  // A triangle that no moves of its corners by the tolerance can flip or make degenerate (the
  // guard's own test) and whose edges are longer than twice the tolerance (it never collapses).
  bool rigid(const Point& a, const Point& b, const Point& c) const
  {
    const double four_t2 = 4 * tolerance_ * tolerance_ * (1 + 1e-9);
    return fat_enough_for_moves(a, b, c, tolerance_) && CGAL::to_double(CGAL::squared_distance(a, b)) > four_t2 &&
           CGAL::to_double(CGAL::squared_distance(b, c)) > four_t2 && CGAL::to_double(CGAL::squared_distance(c, a)) > four_t2;
  }

  Octree<Kernel> tree_;
  std::vector<double> depth_;
  double tolerance_;
  FT radius_, twice_radius_;
  bool collapse_;
  std::vector<char> tainted_;
  std::size_t budget_, work_ = 0;
  bool crowded_ = false;
};

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_TILE_TAINT_H
