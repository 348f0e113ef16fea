// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The measurements of the gap analysis: for every border vertex, the distance to the nearest
// border element (vertex or edge) that shares no triangle with it; for every triangle, its
// shortest edge and its smallest height.

#ifndef SOUP_TOPOLOGY_INTERNAL_GAP_DISTANCES_H
#define SOUP_TOPOLOGY_INTERNAL_GAP_DISTANCES_H

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/Octree.h>
#include <Soup_topology/internal/parallel.h>
#include <Soup_topology/internal/uninitialized_vector.h>

#include <CGAL/number_utils.h>
#include <CGAL/property_map.h>
#include <CGAL/tags.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace Soup_topology {
namespace internal {

/// `ConcurrencyTag` for the measures that construct or compare points: `CGAL::Sequential_tag` when
/// the coordinates are not `double` (lazily exact numbers share cached state between the points
/// they come from: such steps run sequentially, `doc/Soup_topology/Parallel.md`, rule 6).
template <class ConcurrencyTag, class Geom_traits>
using Geometric_concurrency =
  std::conditional_t<std::is_same<typename Geom_traits::FT, double>::value, ConcurrencyTag, CGAL::Sequential_tag>;

/// the nearest border element of one border vertex.
struct Nearest_border_element
{
  double distance = std::numeric_limits<double>::infinity(); ///< infinite: nothing within the search radius
  std::size_t vertex = static_cast<std::size_t>(-1);         ///< the nearest vertex, or -1 if an edge is nearer
  Adjacency_tables::Edge edge{Adjacency_tables::border_edge, -1}; ///< the nearest border edge, if nearer than any vertex
};

/// the nearest border elements of the border vertices, one each (in huge pages when large: a
/// soup whose every vertex is a border vertex has 32 bytes of them a corner, which 4 KiB pages
/// would fault in one by one on every call)
using Nearest_border_elements = Uninitialized_vector<Nearest_border_element>;

/// `true` if `v` and `w` are corners of one triangle of `tables`.
inline bool share_a_triangle(const Adjacency_tables& tables, std::size_t v, std::size_t w)
{
  for(const Adjacency_tables::size_type t : tables.triangles_around_vertex(static_cast<Adjacency_tables::size_type>(v))) {
    const Adjacency_tables::Triangle& tr = tables.triangle(t);
    if(tr[0] == w || tr[1] == w || tr[2] == w) return true;
  }
  return false;
}

/// the vertices on border edges, in increasing order.
inline std::vector<std::size_t> border_vertices(const Adjacency_tables& tables)
{
  std::vector<char> on_border(tables.number_of_vertices(), 0);
  for(std::size_t t = 0; t < tables.number_of_triangles(); ++t)
    for(int i = 0; i < 3; ++i)
      if(tables.is_border_edge(static_cast<Adjacency_tables::size_type>(t), i)) {
        on_border[tables.vertex(static_cast<Adjacency_tables::size_type>(t), i)] = 1;
        on_border[tables.vertex(static_cast<Adjacency_tables::size_type>(t), (i + 1) % 3)] = 1;
      }
  std::vector<std::size_t> out;
  out.reserve(static_cast<std::size_t>(std::count(on_border.begin(), on_border.end(), char(1))));
  for(std::size_t v = 0; v < on_border.size(); ++v)
    if(on_border[v]) out.push_back(v);
  return out;
}

/// the largest number of (vertex, element) candidates `nearest_border_elements()` examines for
/// `n` border vertices: 2^24 plus 256 per vertex (real meshes need a few per vertex).
inline std::size_t gap_candidate_budget(std::size_t n) { return (std::size_t(1) << 24) + 256 * n; }

/// throws `Invalid_input` once `examined` exceeds the budget for `n` border vertices.
inline void check_gap_candidate_budget(std::size_t examined, std::size_t n)
{
  if(examined > gap_candidate_budget(n))
    throw Invalid_input("gap analysis: the " + std::to_string(n) + " border vertices are too crowded within the search "
                        "radius (more than " + std::to_string(gap_candidate_budget(n)) +
                        " candidate pairs); give the tolerance by hand");
}

/// how a search of `Nearest_border_search` counts its candidates against the budget: while it
/// examines them (one pass), or all of them first, without listing them in order or examining
/// any (a crowded soup is then refused at the cost of the count alone).
enum class Candidates { COUNT_WHILE_SEARCHING, COUNT_FIRST };

/// the search of `nearest_border_elements()`: the border vertices in an octree, the answers so
/// far, and the number of candidates examined.
///
/// The border vertices are numbered in the tree's (Morton) order, not in the order of `border`:
/// a "position" below is that number. The answers, the vertices and the points of nearby border
/// vertices are then near each other in memory too, whatever the order of the soup (the answers
/// in the order of `border` were one random access each per candidate). `nearest()` and
/// `search_subset()` speak of positions; `nearest_in_border_order()` gives the answers in the
/// order of `border`.
template <class Geom_traits>
class Nearest_border_search
{
  using Point = typename Geom_traits::Point_3;
  using FT = typename Geom_traits::FT;
  // the border vertices' points read from the soup's points through their indices: the tree
  // keeps the only copy (in its own order), no copy in the order of `border` is made
  using Border_point_map = typename CGAL::Pointer_property_map<Point>::const_type;
  using Tree = Octree<Geom_traits, Border_point_map>;
  using Subset_tree = Octree<Geom_traits>;

public:
  /// (the octree built on TBB's threads with a parallel `ConcurrencyTag`: the same tree)
  template <class ConcurrencyTag = CGAL::Sequential_tag>
  Nearest_border_search(const std::vector<Point>& points, const Adjacency_tables& tables,
                        const std::vector<std::size_t>& border, const Geom_traits& gt,
                        ConcurrencyTag tag = ConcurrencyTag())
    : tables_(tables), number_of_border_vertices_(border.size()), gt_(gt),
      squared_distance_(gt.compute_squared_distance_3_object()), nearest_(border.size())
  {
    tree_.emplace(border,
                  parameters::bucket_capacity(border_bucket_capacity,
                                              CGAL::parameters::geom_traits(gt).point_map(CGAL::make_property_map(points.data()))),
                  tag);
    border_index_at_ = tree_->number_points_in_tree_order();
    vertex_at_.resize(border.size());
    for(std::size_t p = 0; p < border.size(); ++p)
      vertex_at_[p] = static_cast<Adjacency_tables::size_type>(border[border_index_at_[p]]);
  }

  /// the bucket capacity of the octree of the border vertices: larger than the default, as the
  /// copies of a seam vertex come in tight clusters (fewer, fuller leaves answer more queries
  /// from one leaf).
  static constexpr std::size_t border_bucket_capacity = 32;

  /// the answers so far, by position
  Nearest_border_elements& nearest() { return nearest_; }

  /// the answers in the order of `border`; the search is over (its tree and its lists are freed
  /// first, so that the copy does not raise the peak)
  Nearest_border_elements nearest_in_border_order()
  {
    tree_.reset();
    Uninitialized_vector<Adjacency_tables::Edge>().swap(border_edges_);
    Uninitialized_vector<std::array<Adjacency_tables::size_type, 2>>().swap(border_edge_ends_);
    Uninitialized_vector<Adjacency_tables::size_type>().swap(border_edge_apex_);
    Uninitialized_vector<Adjacency_tables::size_type>().swap(vertex_at_);
    Nearest_border_elements out(nearest_.size());
    for(std::size_t p = 0; p < nearest_.size(); ++p) out[border_index_at_[p]] = nearest_[p];
    Nearest_border_elements().swap(nearest_);
    return out;
  }

  /// every border vertex's nearest element within `radius`: the self-join of the border
  /// vertices, then the segment queries of all the border edges at once (their ends are
  /// border vertices, points of the tree: each query starts next to its edge). With
  /// `Candidates::COUNT_FIRST` the candidates are counted (and the budget checked) before any is
  /// listed or examined. The neighbourhoods come unsorted (`Neighborhood_order::TREE`): the
  /// answer is the least candidate in an order of its own, whatever the order of the offers.
  ///
  /// With `CGAL::Parallel_tag` and more than one thread allowed, both searches run on TBB's
  /// threads (on one thread, the sequential searches run) and the candidates are offered
  /// as they are found, in no particular order. The answer does not depend on that order: it is
  /// the least candidate in the order (distance, vertex before edge, index of the vertex or
  /// order of the edge), which is what the sequential offers keep. A vertex's answer is written
  /// by the thread of its self-join query alone; an edge's offers, which reach many vertices, are
  /// kept only when nearer than the vertex's answer of the self-join (no edge as near replaces a
  /// vertex) and written under one of a set of locks chosen by the vertex. The candidates
  /// examined are counted by an atomic counter: the budget is exceeded for the same total.
  template <class ConcurrencyTag = CGAL::Sequential_tag>
  void search_all(double radius, Candidates candidates)
  {
    const FT r(radius);
    if(border_edges_.empty()) list_border_edges();
    const bool count_while_searching = candidates == Candidates::COUNT_WHILE_SEARCHING;
    if(!count_while_searching) {
      // Counted by blocks (in parallel with `Parallel_tag`), then checked: the budget is
      // exceeded for the same total as when counted one by one.
      const std::size_t n = number_of_border_vertices_, m = border_edge_ends_.size();
      std::vector<std::size_t> counts(number_of_blocks(n + m), 0);
      for_each_block<ConcurrencyTag>(n + m, default_block_size, [&](std::size_t g, std::size_t begin, std::size_t end) {
        for(std::size_t i = begin; i < end; ++i)
          counts[g] += i < n ? tree_->number_of_vertices_near_point(border_point(i), r)
                             : tree_->number_of_vertices_near_segment(border_point(border_edge_ends_[i - n][0]),
                                                                      border_point(border_edge_ends_[i - n][1]), r);
      });
      std::size_t total = 0;
      for(std::size_t c : counts) total += c;
      count_examined(total);
    }
    // (on one thread, the sequential searches: the same answer without the locks and the atomic
    // counter of the concurrent ones)
    if(runs_on_several_threads<ConcurrencyTag>()) {
      std::atomic<std::size_t> examined(examined_);
      const auto count = [&](std::size_t n) {
        if(count_while_searching)
          check_gap_candidate_budget(examined.fetch_add(n, std::memory_order_relaxed) + n, number_of_border_vertices_);
      };
      tree_->template for_each_neighborhood_concurrently<ConcurrencyTag>(
        r, [&](std::size_t k, const std::vector<std::size_t>& near) {
          count(near.size());
          for(std::size_t j : near) offer_vertex(k, j);
        }, Neighborhood_order::TREE);
      Uninitialized_vector<double> vertex_distance(nearest_.size()); // written whole below
      for(std::size_t k = 0; k < nearest_.size(); ++k) vertex_distance[k] = nearest_[k].distance;
      std::array<std::mutex, 256> locks;
      tree_->template for_each_segment_neighborhood_concurrently<ConcurrencyTag>(
        border_edge_ends_, r,
        [&](std::size_t e, const std::vector<std::size_t>& near, const std::vector<double>& near_d2) {
          count(near.size());
          for_each_edge_distance(e, near, &near_d2, [](std::size_t m) { return m; },
                                 [&](std::size_t k) { return vertex_distance[k]; },
                                 [&](std::size_t k, double d) {
                                   if(!(d < vertex_distance[k])) return;
                                   const std::lock_guard<std::mutex> hold(locks[k % locks.size()]);
                                   offer_edge_at(k, d, border_edges_[e]);
                                 });
        }, Neighborhood_order::TREE);
      examined_ = examined.load();
    } else {
      tree_->for_each_neighborhood(r, [&](std::size_t k, const std::vector<std::size_t>& near) {
        if(count_while_searching) count_examined(near.size());
        for(std::size_t j : near) offer_vertex(k, j);
      }, Neighborhood_order::TREE);
      tree_->for_each_segment_neighborhood(
        border_edge_ends_, r,
        [&](std::size_t e, const std::vector<std::size_t>& near, const std::vector<double>& near_d2) {
          if(count_while_searching) count_examined(near.size());
          offer_edge(e, near, &near_d2, [](std::size_t m) { return m; });
        }, Neighborhood_order::TREE);
    }
  }

  /// the nearest element within `radius` of the border vertices `subset` (positions,
  /// increasing) only, their earlier answers forgotten: one radius query per vertex of
  /// the subset, and one segment query per border edge over an octree of the subset. The
  /// candidates are counted (and the budget checked) before any is listed in order or examined.
  void search_subset(const std::vector<std::size_t>& subset, double radius)
  {
    const FT r(radius);
    if(border_edges_.empty()) list_border_edges();
    for(std::size_t k : subset) count_examined(tree_->number_of_vertices_near_point(border_point(k), r));
    std::vector<Point> subset_points;
    subset_points.reserve(subset.size());
    for(std::size_t k : subset) subset_points.push_back(border_point(k));
    const Subset_tree subset_tree(subset_points, CGAL::Identity_property_map<Point>(), gt_);
    for(const std::array<Adjacency_tables::size_type, 2>& ends : border_edge_ends_)
      count_examined(subset_tree.number_of_vertices_near_segment(border_point(ends[0]), border_point(ends[1]), r));
    std::vector<std::size_t> near;
    for(std::size_t k : subset) {
      nearest_[k] = Nearest_border_element();
      near.clear();
      tree_->vertices_near_point(border_point(k), r, std::back_inserter(near));
      for(std::size_t j : near) offer_vertex(k, j);
    }
    search_edges(subset_tree, subset, r);
  }

private:
  // the point of the border vertex at position k, as the tree holds it
  const Point& border_point(std::size_t k) const { return tree_->point(k); }

  void count_examined(std::size_t n)
  {
    examined_ += n;
    check_gap_candidate_budget(examined_, number_of_border_vertices_);
  }

  // The vertices first, the nearest one and among equally near ones the smallest index. Whether
  // the two share a triangle (random accesses to the tables) is asked only of a candidate that
  // would replace the answer: the least candidate that shares none is kept all the same.
  void offer_vertex(std::size_t k, std::size_t j)
  {
    if(j == k) return;
    const double d = std::sqrt(CGAL::to_double(squared_distance_(border_point(k), border_point(j))));
    const std::size_t w = vertex_at_[j];
    Nearest_border_element& best = nearest_[k];
    if(!(d < best.distance || (d == best.distance && w < best.vertex))) return;
    if(share_a_triangle(tables_, vertex_at_[k], w)) return;
    best.distance = d;
    best.vertex = w;
  }

  // The border edges in the order of the positions of their first ends (then of their
  // triangles): the order in which the segment queries visit them, so that what a query reads
  // of its edge lies next to what the one before read. For each, its ends as positions and the
  // vertex of its triangle opposite to it: what the searches need, without the tables.
  void list_border_edges()
  {
    // (read only at the ends of border edges, which are border vertices: all written)
    Uninitialized_vector<Adjacency_tables::size_type> border_index(tables_.number_of_vertices());
    for(std::size_t p = 0; p < vertex_at_.size(); ++p)
      border_index[vertex_at_[p]] = static_cast<Adjacency_tables::size_type>(p);
    // a counting sort by first end: the edges of each position, then their places (`std::size_t`:
    // a soup may have more than 2^32 border edges, three per triangle)
    std::vector<std::size_t> first(vertex_at_.size() + 1, 0);
    const auto for_each_border_edge = [&](const auto& f) {
      for(std::size_t t = 0; t < tables_.number_of_triangles(); ++t) {
        const auto tt = static_cast<Adjacency_tables::size_type>(t);
        for(int i = 0; i < 3; ++i)
          if(tables_.is_border_edge(tt, i)) f(tt, i, tables_.triangle(tt));
      }
    };
    for_each_border_edge([&](Adjacency_tables::size_type, int i, const Adjacency_tables::Triangle& tr) {
      ++first[border_index[tr[static_cast<std::size_t>(i)]] + 1];
    });
    for(std::size_t p = 1; p < first.size(); ++p) first[p] += first[p - 1];
    const std::size_t m = first.back();
    border_edges_.resize(m);
    border_edge_ends_.resize(m);
    border_edge_apex_.resize(m);
    for_each_border_edge([&](Adjacency_tables::size_type t, int i, const Adjacency_tables::Triangle& tr) {
      const Adjacency_tables::size_type a = border_index[tr[static_cast<std::size_t>(i)]];
      const std::size_t e = first[a]++;
      border_edges_[e] = Adjacency_tables::Edge{t, i};
      border_edge_ends_[e] = {a, border_index[tr[static_cast<std::size_t>((i + 1) % 3)]]};
      border_edge_apex_[e] = tr[static_cast<std::size_t>((i + 2) % 3)];
    });
  }

  // Then the border edges: an edge replaces the answer only if it is strictly nearer, or as near
  // as an edge earlier in the order of the triangles (a vertex at the same distance as an edge
  // is preferred, its end point usually; among equally near edges the first one): the answer
  // does not depend on the order in which the edges are offered. An edge shares a triangle with
  // a vertex when its (only) triangle contains the vertex. `e` is the edge's place in the list,
  // `near` lists vertices found near it, `near_d2` (or null) the octree's estimates of their
  // squared distances, `to_position(m)` their positions.
  template <class To_position>
  void offer_edge(std::size_t e, const std::vector<std::size_t>& near, const std::vector<double>* near_d2,
                  const To_position& to_position)
  {
    for_each_edge_distance(e, near, near_d2, to_position, [&](std::size_t k) { return nearest_[k].distance; },
                           [&](std::size_t k, double d) { offer_edge_at(k, d, border_edges_[e]); });
  }

  // `offer(k, d)` for every vertex of `near` that is not a corner of the (only) triangle of the
  // border edge `e` (its place in the list), `k` its position, `d` its distance to the edge,
  // except the vertices whose estimate in `near_d2` (the octree's, or null: none) puts them
  // surely farther from the edge than `bound(k)`: `offer(k, d)` refuses a `d` above `bound(k)`,
  // so the kernel's distance is not computed for them. On the exploded torus of
  // `benchmark/exploded_torus.py`, 71 % of the pairs are farther than their vertex's nearest
  // vertex, and are left out that way.
  template <class To_position, class Bound, class Offer>
  void for_each_edge_distance(std::size_t e, const std::vector<std::size_t>& near, const std::vector<double>* near_d2,
                              const To_position& to_position, const Bound& bound, const Offer& offer) const
  {
    if(near.empty()) return;
    const std::array<Adjacency_tables::size_type, 2>& ends = border_edge_ends_[e];
    const std::size_t u = vertex_at_[ends[0]], w = vertex_at_[ends[1]], apex = border_edge_apex_[e];
    const Point& a = border_point(ends[0]);
    const Point& b = border_point(ends[1]);
    const auto s = gt_.construct_segment_3_object()(a, b);
    // The estimate's distance is within a few units in the last place of (length + distance)
    // of the exact one, and so is the kernel's: a margin of 1e-10 of each is far beyond both.
    constexpr bool estimates = std::is_same<FT, double>::value;
    double margin = 0;
    if constexpr(estimates) {
      if(near_d2 != nullptr) {
        const double dx = CGAL::to_double(b.x()) - CGAL::to_double(a.x());
        const double dy = CGAL::to_double(b.y()) - CGAL::to_double(a.y());
        const double dz = CGAL::to_double(b.z()) - CGAL::to_double(a.z());
        margin = estimate_margin * (std::sqrt(dx * dx + dy * dy + dz * dz) * (1 + estimate_margin));
      }
    }
    for(std::size_t i = 0; i < near.size(); ++i) {
      const std::size_t k = to_position(near[i]);
      const std::size_t v = vertex_at_[k];
      if(v == u || v == w || v == apex) continue;
      if constexpr(estimates) {
        if(near_d2 != nullptr) {
          // surely farther than the bound (infinite: never; an estimate not computed, NaN: never;
          // a bound whose square is not a normal number: never, as the relative margin is lost in
          // the rounding of numbers that small)
          const double beyond = (bound(k) + margin) * (1 + 2 * estimate_margin);
          if(beyond > smallest_estimated_bound && (*near_d2)[i] > beyond * beyond) continue;
        }
      }
      offer(k, std::sqrt(CGAL::to_double(squared_distance_(border_point(k), s))));
    }
  }

  // the relative margin of the octree's estimates of the distances to an edge
  static constexpr double estimate_margin = 1e-10;
  // the smallest bound below which the estimates leave nothing out (its square, 1e-280, and the
  // estimates above it are normal numbers)
  static constexpr double smallest_estimated_bound = 1e-140;

  // The edge `edge` at distance `d` of border vertex `k`, by the rule above. An infinite (or NaN)
  // distance, which only a squared distance out of the range of doubles gives, is no answer.
  void offer_edge_at(std::size_t k, double d, const Adjacency_tables::Edge& edge)
  {
    if(!(d < std::numeric_limits<double>::infinity())) return;
    Nearest_border_element& best = nearest_[k];
    if(d < best.distance || (d == best.distance && best.vertex == static_cast<std::size_t>(-1) && edge < best.edge)) {
      best.distance = d;
      best.vertex = static_cast<std::size_t>(-1);
      best.edge = edge;
    }
  }

  // The segment query of every border edge over `tree`, which holds the points of the vertices
  // at the positions `ks`, in that order (the candidates counted already).
  void search_edges(const Subset_tree& tree, const std::vector<std::size_t>& ks, const FT& r)
  {
    std::vector<std::size_t> near;
    for(std::size_t e = 0; e < border_edges_.size(); ++e) {
      near.clear();
      tree.vertices_near_segment(border_point(border_edge_ends_[e][0]), border_point(border_edge_ends_[e][1]), r,
                                 std::back_inserter(near));
      offer_edge(e, near, nullptr, [&ks](std::size_t m) { return ks[m]; });
    }
  }

  const Adjacency_tables& tables_;
  const std::size_t number_of_border_vertices_;
  const Geom_traits& gt_;
  typename Geom_traits::Compute_squared_distance_3 squared_distance_;
  std::optional<Tree> tree_;
  Uninitialized_vector<std::uint32_t> border_index_at_;         // position -> index into `border`
  Uninitialized_vector<Adjacency_tables::size_type> vertex_at_; // position -> vertex
  Nearest_border_elements nearest_;                             // by position
  // (`Uninitialized_vector`s: their large blocks come in huge pages)
  // (the border edges in the order of `list_border_edges()`)
  Uninitialized_vector<Adjacency_tables::Edge> border_edges_;                          // the edges
  Uninitialized_vector<std::array<Adjacency_tables::size_type, 2>> border_edge_ends_; // their ends, positions
  Uninitialized_vector<Adjacency_tables::size_type> border_edge_apex_;                // their opposite vertices
  std::size_t examined_ = 0;
};

/// the radius of the first pass of `nearest_border_elements()`, as a fraction of the search
/// radius: seams are usually far narrower than the border edges that bound the search.
constexpr double first_gap_pass_fraction = 1.0 / 32;

/// for every vertex of `border` (indices into `points`), its nearest border element within
/// `radius` that shares no triangle with it. The candidates are found by the octree's exact
/// radius queries over the border vertices; the distances are then evaluated by the kernel's
/// `Compute_squared_distance_3` (exact squared distances with an exact kernel, correctly rounded
/// to double otherwise, up to the rounding of the construction with Epick).
///
/// Two passes give the answer of one search at `radius`. The first searches every vertex within
/// `first_gap_pass_fraction * radius` (a self-join, and one segment query per border edge). A
/// vertex whose nearest element found there lies clearly inside that smaller radius (below it by
/// more than any rounding of the distances) has its answer: every element it did not see is
/// farther, so it can neither be nearer nor tie. The other vertices are searched again at
/// `radius`, alone. Narrow seams, the common case, are answered by the first pass, which lists far
/// fewer candidates than a search at the median border edge length.
///
/// The candidates examined are counted: border vertices crowded within the radius of each other
/// (a dense cluster, or many long border edges over one small region) would make the listing
/// quadratic, so past `gap_candidate_budget(border.size())` candidates the analysis stops and
/// throws `Invalid_input` (the caller then gives a tolerance by hand). The second pass counts
/// its candidates before it sorts or examines any: where it would exceed the budget, the refusal
/// costs the count only. Whether the budget is exceeded depends on the total only, not on the
/// order of the counts.
template <class ConcurrencyTag = CGAL::Sequential_tag, class Geom_traits>
Nearest_border_elements nearest_border_elements(const std::vector<typename Geom_traits::Point_3>& points,
                                                const Adjacency_tables& tables,
                                                const std::vector<std::size_t>& border,
                                                double radius, const Geom_traits& gt)
{
  if(border.empty()) return {};
  using Tag = Geometric_concurrency<ConcurrencyTag, Geom_traits>;
  Nearest_border_search<Geom_traits> search(points, tables, border, gt, Tag());
  const double first_radius = radius * first_gap_pass_fraction;
  search.template search_all<Tag>(first_radius, Candidates::COUNT_WHILE_SEARCHING);
  // Relative rounding of a distance evaluated in double is a few units in the last place.
  const double decided_below = first_radius * (1 - 1e-9);
  std::vector<std::size_t> undecided; // positions in the search's order
  for(std::size_t k = 0; k < border.size(); ++k)
    if(!(search.nearest()[k].distance < decided_below)) undecided.push_back(k);
  if(2 * undecided.size() > border.size()) {
    search.nearest().assign(border.size(), Nearest_border_element());
    search.template search_all<Tag>(radius, Candidates::COUNT_FIRST);
  }
  else if(!undecided.empty())
    search.search_subset(undecided, radius);
  return search.nearest_in_border_order();
}

/// the shortest edge and the smallest height of a triangle, in double, and whether its corners
/// are collinear (then both sizes describe a degenerate triangle).
struct Triangle_feature_sizes
{
  double shortest_edge = 0;
  double smallest_height = 0;
};

template <class Point>
Triangle_feature_sizes triangle_feature_sizes(const Point& p, const Point& q, const Point& r)
{
  const double a[3] = {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
  const double b[3] = {CGAL::to_double(q.x()), CGAL::to_double(q.y()), CGAL::to_double(q.z())};
  const double c[3] = {CGAL::to_double(r.x()), CGAL::to_double(r.y()), CGAL::to_double(r.z())};
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double w[3] = {c[0] - b[0], c[1] - b[1], c[2] - b[2]};
  const double lu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  const double lv = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  const double lw = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  const double twice_area = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  const double longest = std::max(lu, std::max(lv, lw));
  Triangle_feature_sizes s;
  s.shortest_edge = std::min(lu, std::min(lv, lw));
  s.smallest_height = longest > 0 ? twice_area / longest : 0;
  return s;
}

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_GAP_DISTANCES_H
