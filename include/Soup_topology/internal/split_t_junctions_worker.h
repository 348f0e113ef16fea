// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The worker behind `Soup_topology::split_t_junctions()`: one named step per stage of the
// T-junction repair. Included by `Soup_topology/split_t_junctions.h` after `Split_report` and
// `Default_split_visitor`.

#ifndef SOUP_TOPOLOGY_INTERNAL_SPLIT_T_JUNCTIONS_WORKER_H
#define SOUP_TOPOLOGY_INTERNAL_SPLIT_T_JUNCTIONS_WORKER_H

#include <Soup_topology/split_t_junctions.h>

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/Octree.h>
#include <Soup_topology/internal/exact_signs.h>
#include <Soup_topology/internal/split_predicates.h>
#include <Soup_topology/internal/tolerance_graph.h>

#include <CGAL/property_map.h>
#include <CGAL/tags.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <optional>
#include <type_traits>
#include <utility>
#include <vector>

namespace Soup_topology {
namespace internal {

// A border edge found at the start, identified by its end vertices (triangle ids change while
// splitting), with the vertices assigned to it.
struct Pending_edge
{
  Adjacency_tables::size_type a, b;
  std::vector<Adjacency_tables::size_type> on_edge;
};

/// Splits the T-junctions of a soup given by its points and its tables; `Report` is
/// `Split_report`, `Visitor` a model of the split visitor told of each event (with
/// `Default_split_visitor` nothing is recorded for it). The steps, in the order `run()` takes them:
/// 1. `index_border_vertices()`: the border vertices, an octree over them and, for dense
///    clusters, a tolerance grid;
/// 2. `collect_claims()`: per border edge, the vertices near it (`find_vertices_near_edge()`),
///    each decided by `decide_candidate()`;
/// 3. `give_each_vertex_to_its_nearest_edge()`;
/// 4. `split_edges()`: per edge in a geometric order, the vertices ordered along it
///    (`order_along_edge()`), the edge located (`locate_border_edge()`), the fan checked
///    (`drop_vertices_breaking_the_fan()`) and the triangle split (`split_along_edge()`).
template <class Kernel, class Report, class Visitor>
class T_junction_splitter
{
public:
  using Point = typename Kernel::Point_3;
  using FT = typename Kernel::FT;
  using size_type = Adjacency_tables::size_type;

  /// `points` all points of the soup, `eps` the (checked) absolute tolerance, `visitor` told of
  /// each split, refusal and ambiguous vertex. `tolerances`, if not null, holds the (checked)
  /// tolerance of every point, and `eps` is their largest: each decision then takes the smallest
  /// tolerance of the points it involves (`pair_eps2()`, `triple_eps2()`), and `eps` only bounds
  /// the searches of the octree, whose answers are filtered by that rule.
  T_junction_splitter(const std::vector<Point>& points, Adjacency_tables& tables, const Kernel& kernel, const FT& eps,
                      Visitor& visitor, const std::vector<FT>* tolerances = nullptr)
    : points_(points), tables_(tables), visitor_(visitor), kernel_(kernel), tolerances_(tolerances), eps_(eps), eps2_(eps * eps),
      four_eps2_(4 * eps2_), eps2d_(CGAL::to_double(eps2_)),
      compare_sq_(kernel.compare_squared_distance_3_object()),
      compare_distance_(kernel.compare_distance_3_object()), less_xyz_(kernel.less_xyz_3_object()),
      orientation_(kernel.orientation_3_object()), coplanar_orientation_(kernel.coplanar_orientation_3_object()),
      collinear_(kernel.collinear_3_object()), segment_(kernel.construct_segment_3_object())
  {}

  T_junction_splitter(const T_junction_splitter&) = delete;
  T_junction_splitter& operator=(const T_junction_splitter&) = delete;

  /// runs every step; the tables are updated, `changed_triangles()` lists what to write back.
  template <class ConcurrencyTag = CGAL::Sequential_tag>
  Report run()
  {
    report_.tolerance = CGAL::to_double(eps_);
    report_.border_edges_before = tables_.number_of_border_edges();
    border_ = tables_.border_edges();
    if(border_.empty()) return report_;
    index_border_vertices();
    collect_claims<ConcurrencyTag>();
    give_each_vertex_to_its_nearest_edge();
    split_edges();
    report_.border_edges_after = tables_.number_of_border_edges();
    return report_;
  }

  /// the triangles split and created, in the order of the splits (with repetitions).
  const std::vector<size_type>& changed_triangles() const { return changed_; }

private:
  using Tree_traits = Kernel_with_near_end_shortcut<Kernel>;
  using Tree = Octree<Tree_traits>;
  static constexpr std::uint32_t not_border = static_cast<std::uint32_t>(-1);
  // Whether the decisions of step 2 keep the vertices they refuse or find ambiguous, for the visitor.
  static constexpr bool tells_visitor = !std::is_same<Visitor, Default_split_visitor>::value;

  const Point& point(size_type v) const { return points_[v]; }

  // A vertex clearly within the tolerance of an end point or of the segment (in double, for double
  // coordinates) is within it of the segment: the exact predicate is asked only when that does not
  // decide (it is slow on the tiny segments of a dense cluster and on collinear points).
  bool near_segment(size_type v, size_type a, size_type b) const
  {
    if(tolerances_ != nullptr) {
      const FT e2 = triple_eps2(v, a, b);
      const double e2d = CGAL::to_double(e2);
      if(surely_within(point(v), point(a), e2d) || surely_within(point(v), point(b), e2d) ||
         surely_within_segment(point(v), point(a), point(b), e2d))
        return true;
      return compare_sq_(point(v), segment_(point(a), point(b)), e2) != CGAL::LARGER;
    }
    if(surely_within(point(v), point(a), eps2d_) || surely_within(point(v), point(b), eps2d_) ||
       surely_within_segment(point(v), point(a), point(b), eps2d_))
      return true;
    return compare_sq_(point(v), segment_(point(a), point(b)), eps2_) != CGAL::LARGER;
  }
  bool near_vertex(size_type v, size_type a) const
  {
    if(tolerances_ != nullptr) {
      const FT e2 = pair_eps2(v, a);
      return surely_within(point(v), point(a), CGAL::to_double(e2)) || compare_sq_(point(v), point(a), e2) != CGAL::LARGER;
    }
    return surely_within(point(v), point(a), eps2d_) || compare_sq_(point(v), point(a), eps2_) != CGAL::LARGER;
  }
  bool within_twice_the_tolerance(size_type v, size_type a) const
  {
    if(tolerances_ != nullptr) {
      const FT e2 = 4 * pair_eps2(v, a);
      return surely_within(point(v), point(a), CGAL::to_double(e2)) || compare_sq_(point(v), point(a), e2) != CGAL::LARGER;
    }
    return surely_within(point(v), point(a), 4 * eps2d_) || compare_sq_(point(v), point(a), four_eps2_) != CGAL::LARGER;
  }
  // With per-vertex tolerances: the squared tolerance of the pair (u, v), min(t_u, t_v)^2, and
  // of a vertex and a segment (v; a, b), min(t_v, t_a, t_b)^2.
  FT pair_eps2(size_type u, size_type v) const
  {
    const FT& e = smaller_tolerance((*tolerances_)[u], (*tolerances_)[v]);
    return e * e;
  }
  FT triple_eps2(size_type v, size_type a, size_type b) const
  {
    const FT& e = smaller_tolerance((*tolerances_)[v], smaller_tolerance((*tolerances_)[a], (*tolerances_)[b]));
    return e * e;
  }
  bool share_triangle(size_type u, size_type v) const
  {
    for(size_type t : tables_.triangles_around_vertex(u)) if(tables_.local_index(t, v) >= 0) return true;
    return false;
  }

  // Step 1. The border vertices and a spatial index over them. With a dense cluster of border
  // vertices, a short edge inside it would list the whole cluster, whose vertices are all within
  // the tolerance of an end point (welds, not T-junctions): the grid skips the cells that lie
  // within the tolerance of an end point, and the vertices that share a triangle with an end
  // point (which may still be T-junctions) are added from the triangles. The vertices examined
  // are the same; the cluster is not listed per edge.
  void index_border_vertices()
  {
    for(const Adjacency_tables::Edge& e : border_) {
      border_vertices_.push_back(tables_.vertex(e.triangle, e.index));
      border_vertices_.push_back(tables_.vertex(e.triangle, (e.index + 1) % 3));
    }
    std::sort(border_vertices_.begin(), border_vertices_.end());
    border_vertices_.erase(std::unique(border_vertices_.begin(), border_vertices_.end()), border_vertices_.end());
    border_points_.reserve(border_vertices_.size());
    for(size_type v : border_vertices_) border_points_.push_back(point(v));
    tree_.emplace(border_points_, CGAL::Identity_property_map<Point>(), Tree_traits(kernel_));
    // The cells are counted first; the grid itself is built only for a dense cluster. The grid
    // skips the cells within the tolerance of an end point, which is right for one tolerance only:
    // with per-vertex tolerances it is not used (the octree lists the vertices, the rule decides).
    dense_ = tolerances_ == nullptr && largest_tolerance_cell(border_points_, eps_) > dense_cell_size;
    if(dense_) {
      grid_.emplace(border_points_, eps_, kernel_);
      border_index_.assign(points_.size(), not_border);
      for(std::size_t f = 0; f < border_vertices_.size(); ++f)
        border_index_[border_vertices_[f]] = static_cast<std::uint32_t>(f);
    }
  }

  // What the decisions of step 2 found: the claims and the counts they add to the report, and,
  // for a visitor, the (vertex, edge) pairs refused for an overlap or found ambiguous.
  struct Decisions
  {
    std::vector<std::pair<size_type, std::uint32_t>> claims;
    std::size_t refused_overlap = 0;
    std::size_t ambiguous = 0;
    std::vector<std::pair<size_type, std::uint32_t>> overlaps;
    std::vector<std::pair<size_type, std::uint32_t>> ambiguous_pairs;
  };

  // Step 2. Candidate (edge, vertex) pairs: every vertex near a border edge is decided. The edges
  // are independent: with the tag (and double coordinates, whose predicates share no lazily
  // computed state) blocks of edges are decided in parallel and their decisions put together in
  // the order of the edges.
  template <class ConcurrencyTag>
  void collect_claims()
  {
    pending_.resize(border_.size());
    auto decide_edges = [&](std::size_t begin, std::size_t end, Decisions& out) {
      std::vector<std::size_t> found;
      for(std::size_t k = begin; k < end; ++k) {
        const Adjacency_tables::Edge& e = border_[k];
        const size_type a = tables_.vertex(e.triangle, e.index), b = tables_.vertex(e.triangle, (e.index + 1) % 3);
        pending_[k] = Pending_edge{a, b, {}};
        found.clear();
        find_vertices_near_edge(a, b, found);
        for(std::size_t f : found) decide_candidate(k, border_vertices_[f], out);
      }
    };
    Decisions all;
    if constexpr(runs_in_parallel<ConcurrencyTag>() && std::is_same<FT, double>::value) {
      const std::size_t block_size = 1024;
      std::vector<Decisions> per_block(number_of_blocks(border_.size(), block_size));
      for_each_block<ConcurrencyTag>(border_.size(), block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
        decide_edges(begin, end, per_block[b]);
      });
      for(Decisions& d : per_block) {
        all.claims.insert(all.claims.end(), d.claims.begin(), d.claims.end());
        all.refused_overlap += d.refused_overlap;
        all.ambiguous += d.ambiguous;
        all.overlaps.insert(all.overlaps.end(), d.overlaps.begin(), d.overlaps.end());
        all.ambiguous_pairs.insert(all.ambiguous_pairs.end(), d.ambiguous_pairs.begin(), d.ambiguous_pairs.end());
      }
    } else {
      decide_edges(0, border_.size(), all);
    }
    claims_.insert(claims_.end(), all.claims.begin(), all.claims.end());
    report_.refused_overlap += all.refused_overlap;
    report_.ambiguous += all.ambiguous;
    for(const auto& [c, k] : all.overlaps)
      visitor_.on_split_refusal(c, pending_[k].a, pending_[k].b, Split_refusal_reason::OVERLAP);
    for(const auto& [c, k] : all.ambiguous_pairs) visitor_.on_ambiguous_t_junction(c, pending_[k].a, pending_[k].b);
  }

  // The positions in `border_vertices_` of the border vertices within the tolerance of [a,b].
  void find_vertices_near_edge(size_type a, size_type b, std::vector<std::size_t>& found) const
  {
    if(dense_ && grid_->is_short(point(a), point(b))) {
      grid_->for_each_point_near_box(point(a), point(b), [&](std::uint32_t f) {
        if(near_segment(border_vertices_[f], a, b)) found.push_back(f);
      });
      for(size_type end : {a, b})
        for(size_type t : tables_.triangles_around_vertex(end))
          for(size_type w : tables_.triangle(t))
            if(border_index_[w] != not_border && near_segment(w, a, b)) found.push_back(border_index_[w]);
      std::sort(found.begin(), found.end());
      found.erase(std::unique(found.begin(), found.end()), found.end());
      return;
    }
    // The same answer by either strategy; the index-space box of a long segment is most of the
    // workspace, so long segments cull the boxes along the segment instead.
    const double length2 = CGAL::to_double(kernel_.compute_squared_distance_3_object()(point(a), point(b)));
    const Segment_query_strategy strategy = length2 > 64 * eps2d_ ? Segment_query_strategy::NEIGHBORHOOD_CULLING
                                                                 : tree_->segment_query_strategy();
    tree_->vertices_near_segment(point(a), point(b), eps_, std::back_inserter(found), strategy);
    // Per-vertex tolerances: the octree lists the vertices within the largest tolerance; the
    // rule of the vertex and the segment keeps those within their own.
    if(tolerances_ != nullptr)
      found.erase(std::remove_if(found.begin(), found.end(),
                                 [&](std::size_t f) { return !near_segment(border_vertices_[f], a, b); }),
                  found.end());
  }

  // Decides whether vertex `c`, near border edge `k`, is a T-junction of it (a claim), a vertex
  // whose split would overlap the other side, or an ambiguous one.
  void decide_candidate(std::size_t k, size_type c, Decisions& out) const
  {
    const Adjacency_tables::Edge& e = border_[k];
    const size_type a = pending_[k].a, b = pending_[k].b;
    const size_type apex = tables_.vertex(e.triangle, (e.index + 2) % 3);
    if(c == a || c == b || c == apex) return;
    // Within the tolerance of an end point: that is a weld, not a T-junction, unless the two
    // vertices share a triangle (no weld can merge them). Within twice the tolerance, the vertex
    // may be an unwelded copy of the end point, and a split there would make a sliver: it is
    // accepted only if its own border edge ends at that end point (below), else counted as
    // ambiguous (the minimum feature separation is not met).
    if((near_vertex(c, a) && !share_triangle(c, a)) || (near_vertex(c, b) && !share_triangle(c, b))) return;
    const bool close_to_a = within_twice_the_tolerance(c, a) && !share_triangle(c, a);
    const bool close_to_b = within_twice_the_tolerance(c, b) && !share_triangle(c, b);
    bool along = false, overlap_only = false;
    classify_border_edges_of(c, e.triangle, a, b, apex, close_to_a, close_to_b, along, overlap_only);
    if(along) {
      out.claims.emplace_back(c, static_cast<std::uint32_t>(k));
    } else if(overlap_only) {
      ++out.refused_overlap;
      if constexpr(tells_visitor) out.overlaps.emplace_back(c, static_cast<std::uint32_t>(k));
    } else if(close_to_a || close_to_b) {
      ++out.ambiguous;
      if constexpr(tells_visitor) out.ambiguous_pairs.emplace_back(c, static_cast<std::uint32_t>(k));
    }
  }

  // Looks for a border edge of c, in another triangle than `t`, running along [a,b]: `along` if
  // one does without overlapping the triangle (a, b, apex), `overlap_only` if one does but
  // overlaps it. Near an end point, only the border edge from c to that very end point counts:
  // the split then mirrors the short edge the other side already has.
  void classify_border_edges_of(size_type c, size_type t, size_type a, size_type b, size_type apex,
                                bool close_to_a, bool close_to_b, bool& along, bool& overlap_only) const
  {
    for(size_type t2 : tables_.triangles_around_vertex(c)) {
      if(t2 == t) continue;
      const int ic = tables_.local_index(t2, c);
      for(int j : {ic, (ic + 2) % 3}) {
        if(!tables_.is_border_edge(t2, j)) continue;
        const size_type d = (j == ic) ? tables_.vertex(t2, (ic + 1) % 3) : tables_.vertex(t2, (ic + 2) % 3);
        // The two border edges run along each other: one end of either lies within the
        // tolerance of the other segment (vertex-segment tests only, never the infinite line).
        if(!(d == a || d == b || near_segment(d, a, b) || near_segment(a, c, d) || near_segment(b, c, d))) continue;
        if((close_to_a && d != a) || (close_to_b && d != b)) continue;
        const size_type x = tables_.vertex(t2, (j + 2) % 3); // apex of t2 across [c,d]
        const bool overlaps = orientation_(point(a), point(b), point(apex), point(x)) == CGAL::COPLANAR &&
                              !collinear_(point(a), point(b), point(x)) &&
                              coplanar_orientation_(point(a), point(b), point(apex), point(x)) == CGAL::POSITIVE;
        if(overlaps) overlap_only = true;
        else along = true;
      }
    }
  }

  // The lexicographic order of the edges by their end points (smaller end point first).
  bool edge_less(std::uint32_t x, std::uint32_t y) const
  {
    const Point& ax = point(pending_[x].a); const Point& bx = point(pending_[x].b);
    const Point& ay = point(pending_[y].a); const Point& by = point(pending_[y].b);
    const Point& lx = less_xyz_(ax, bx) ? ax : bx; const Point& hx = less_xyz_(ax, bx) ? bx : ax;
    const Point& ly = less_xyz_(ay, by) ? ay : by; const Point& hy = less_xyz_(ay, by) ? by : ay;
    if(less_xyz_(lx, ly)) return true;
    if(less_xyz_(ly, lx)) return false;
    return less_xyz_(hx, hy);
  }

  // Step 3. A vertex claimed by several edges goes to the nearest one (distances compared
  // exactly; ties: the smaller edge by `edge_less()`) and is counted as ambiguous.
  void give_each_vertex_to_its_nearest_edge()
  {
    std::sort(claims_.begin(), claims_.end());
    for(std::size_t i = 0; i < claims_.size();) {
      std::size_t j = i;
      while(j < claims_.size() && claims_[j].first == claims_[i].first) ++j;
      const size_type c = claims_[i].first;
      std::uint32_t best = claims_[i].second;
      for(std::size_t k = i + 1; k < j; ++k) {
        const std::uint32_t e = claims_[k].second;
        const CGAL::Comparison_result r = compare_point_segment_distances(
          point(c), point(pending_[e].a), point(pending_[e].b), point(pending_[best].a), point(pending_[best].b));
        if(r == CGAL::SMALLER || (r == CGAL::EQUAL && edge_less(e, best))) best = e;
      }
      if(j - i > 1) {
        ++report_.ambiguous;
        visitor_.on_ambiguous_t_junction(c, pending_[best].a, pending_[best].b);
      }
      pending_[best].on_edge.push_back(c);
      i = j;
    }
  }

  // Step 4. Split, edge by edge, along each edge from a to b. Two edges of one triangle may both
  // be split: the edges are processed in a geometric order (lexicographic end points) so that the
  // result does not depend on the order of the triangles.
  void split_edges()
  {
    std::vector<std::uint32_t> order;
    for(std::uint32_t k = 0; k < pending_.size(); ++k) if(!pending_[k].on_edge.empty()) order.push_back(k);
    std::sort(order.begin(), order.end(), [this](std::uint32_t x, std::uint32_t y) { return edge_less(x, y); });
    for(std::uint32_t k : order) {
      Pending_edge& pe = pending_[k];
      order_along_edge(pe);
      size_type t = Adjacency_tables::border_edge;
      int i = -1;
      if(!locate_border_edge(pe, t, i)) continue;
      const size_type apex = tables_.vertex(t, (i + 2) % 3);
      if(!pe.on_edge.empty()) drop_vertices_breaking_the_fan(pe, apex);
      if(pe.on_edge.empty()) continue;
      split_along_edge(pe, t, i);
    }
  }

  // Sorts the vertices of an edge by their distance from a (ties by `Less_xyz_3`).
  void order_along_edge(Pending_edge& pe) const
  {
    std::sort(pe.on_edge.begin(), pe.on_edge.end(), [&](size_type x, size_type y) {
      const CGAL::Comparison_result r = compare_distance_(point(pe.a), point(x), point(y));
      if(r != CGAL::EQUAL) return r == CGAL::SMALLER;
      return less_xyz_(point(x), point(y));
    });
  }

  // The triangle `t` and local edge `i` that hold the border edge [a,b] now (an earlier split on
  // another edge of the same triangle may have moved it to a new triangle with another apex);
  // `false` if it is no border edge any more.
  bool locate_border_edge(const Pending_edge& pe, size_type& t, int& i) const
  {
    for(size_type u : tables_.triangles_around_vertex(pe.a)) {
      const int j = tables_.edge_index(u, pe.a, pe.b);
      if(j >= 0 && tables_.vertex(u, j) == pe.a && tables_.is_border_edge(u, j)) { t = u; i = j; return true; }
    }
    return false;
  }

  // Refuses the vertices whose fan triangle (previous, c, apex) or (c, next, apex) would be
  // degenerate or flipped relative to (a, b, apex): the first failing fan triangle along the
  // edge loses its on-edge vertex (the one nearer b when both are), until the whole fan is valid.
  // The fan before a failure is unchanged by the drop, so the scan resumes there: one pass over a
  // doubly linked chain, linear in the number of vertices on the edge.
  void drop_vertices_breaking_the_fan(Pending_edge& pe, size_type apex)
  {
    const std::size_t m = pe.on_edge.size();
    std::vector<size_type> chain;
    chain.reserve(m + 2);
    chain.push_back(pe.a);
    chain.insert(chain.end(), pe.on_edge.begin(), pe.on_edge.end());
    chain.push_back(pe.b);
    const std::size_t last = m + 1;
    std::vector<std::size_t> next(m + 2), previous(m + 2);
    for(std::size_t j = 0; j <= last; ++j) { next[j] = j + 1; previous[j] = j == 0 ? 0 : j - 1; }
    std::vector<char> dropped(m + 2, 0);
    std::size_t left = 0;
    while(left != last && next[0] != last) {
      const std::size_t right = next[left];
      const Point& p = point(chain[left]);
      const Point& q = point(chain[right]);
      const bool degenerate = collinear_(p, q, point(apex));
      const bool flipped = !degenerate &&
        sign_of_normal_dot(point(pe.a), point(pe.b), point(apex), p, q, point(apex)) != CGAL::POSITIVE;
      if(!degenerate && !flipped) { left = right; continue; }
      if(degenerate) ++report_.refused_degenerate; else ++report_.refused_flip;
      visitor_.on_split_refusal(chain[right != last ? right : left], pe.a, pe.b,
                                degenerate ? Split_refusal_reason::DEGENERATE : Split_refusal_reason::FLIP);
      if(right != last) {
        dropped[right] = 1;
        next[left] = next[right];
        previous[next[right]] = left;
      } else {
        // left is an on-edge vertex: the loop stops when none is left.
        dropped[left] = 1;
        const std::size_t before = previous[left];
        next[before] = last;
        previous[last] = before;
        left = before;
      }
    }
    std::size_t kept = 0;
    for(std::size_t j = 1; j <= m; ++j)
      if(!dropped[j]) pe.on_edge[kept++] = chain[j];
    pe.on_edge.resize(kept);
  }

  // Splits triangle `t` at each vertex of the edge in turn (rule tables (15) and (17)).
  void split_along_edge(const Pending_edge& pe, size_type t, int i)
  {
    report_.t_junctions += pe.on_edge.size();
    for(size_type c : pe.on_edge) {
      const size_type t_new = tables_.split_triangle(t, i, c);
      changed_.push_back(t);
      changed_.push_back(t_new);
      ++report_.split_triangles;
      visitor_.on_split(c, pe.a, pe.b);
      t = t_new; // the rest of the edge, (c, b), is edge i of the new triangle
    }
  }

  const std::vector<Point>& points_; // all points, read once (a readable map may return them by value); kept by reference
  Adjacency_tables& tables_;
  Visitor& visitor_;
  const Kernel kernel_;
  const std::vector<FT>* tolerances_; // per point, or null: eps_ for every decision
  const FT eps_, eps2_, four_eps2_;
  const double eps2d_;
  typename Kernel::Compare_squared_distance_3 compare_sq_;
  typename Kernel::Compare_distance_3 compare_distance_;
  typename Kernel::Less_xyz_3 less_xyz_;
  typename Kernel::Orientation_3 orientation_;
  typename Kernel::Coplanar_orientation_3 coplanar_orientation_;
  typename Kernel::Collinear_3 collinear_;
  typename Kernel::Construct_segment_3 segment_;

  Report report_;
  std::vector<Adjacency_tables::Edge> border_;
  std::vector<size_type> border_vertices_;
  std::vector<Point> border_points_; // kept: the grid refers to it
  std::optional<Tree> tree_;
  std::optional<Tolerance_grid<Kernel>> grid_;
  bool dense_ = false;
  std::vector<std::uint32_t> border_index_; // vertex -> position in border_vertices_ (dense only)
  std::vector<Pending_edge> pending_;
  std::vector<std::pair<size_type, std::uint32_t>> claims_; // (vertex, pending edge)
  std::vector<size_type> changed_;
};

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_SPLIT_T_JUNCTIONS_WORKER_H
