// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The steps of `snap_vertices()`: a worker that holds the state shared by the steps (candidates,
// tolerance graph, clusters, moves) and whose entry point names them.

#ifndef SOUP_TOPOLOGY_INTERNAL_SNAP_VERTICES_WORKER_H
#define SOUP_TOPOLOGY_INTERNAL_SNAP_VERTICES_WORKER_H

#include <Soup_topology/snap_vertices.h>

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/Octree.h>
#include <Soup_topology/internal/exact_signs.h>
#include <Soup_topology/internal/parallel.h>
#include <Soup_topology/internal/soup_checks.h>
#include <Soup_topology/internal/tolerance_graph.h>
#include <Soup_topology/internal/uninitialized_vector.h>

#include <CGAL/Kernel_traits.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <iterator>
#include <limits>
#include <memory>
#include <mutex>
#include <type_traits>
#include <utility>
#include <vector>

namespace Soup_topology {
namespace internal {

/// `true` if moving the corners of triangle (a, b, c) to (na, nb, nc) keeps it: it does not
/// become degenerate (unless it was) and its normal is not reversed. Otherwise `why` says which.
template <class Kernel, class Point>
bool moves_keep_triangle(const Point& a, const Point& b, const Point& c,
                         const Point& na, const Point& nb, const Point& nc, const Kernel& kernel,
                         Refusal_reason& why)
{
  const typename Kernel::Collinear_3 collinear = kernel.collinear_3_object();
  const bool was_degenerate = collinear(a, b, c);
  if(collinear(na, nb, nc)) {
    if(was_degenerate) return true; // nothing lost
    why = Refusal_reason::DEGENERATE;
    return false;
  }
  if(was_degenerate) return true;
  if(sign_of_normal_dot(a, b, c, na, nb, nc) != CGAL::POSITIVE) { why = Refusal_reason::FLIP; return false; }
  return true;
}

/// `true` if no moves of the corners of triangle (a, b, c) by at most `delta` each can make it
/// degenerate or reverse its normal: with n = (b - a) x (c - a), the moves change n by at most
/// 2 delta (|b - a| + |c - a|) + 4 delta^2, and a change smaller than |n| keeps n' . n > 0. Evaluated
/// in double with a 1% margin, for `double` coordinates only (otherwise `false`: ask the exact test).
template <class Point>
bool fat_enough_for_moves(const Point& a, const Point& b, const Point& c, double delta)
{
  using FT = typename CGAL::Kernel_traits<Point>::Kernel::FT;
  if constexpr(std::is_same<FT, double>::value) {
    const double u[3] = {b.x() - a.x(), b.y() - a.y(), b.z() - a.z()};
    const double v[3] = {c.x() - a.x(), c.y() - a.y(), c.z() - a.z()};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double norm_n = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const double lu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    const double lv = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    const double change = 2 * delta * (lu + lv) + 4 * delta * delta;
    return std::isfinite(norm_n) && norm_n > 1.01 * change + 1e-280;
  } else {
    (void)a; (void)b; (void)c; (void)delta;
    return false;
  }
}

/// compares the distances from `p` to `q` and to `r`: in double when they are far from equal
/// (double coordinates only: the squared distances are then within a few ulps of the exact
/// ones), else with the kernel's exact `Compare_distance_3`.
template <class Point, class CompareDistance>
CGAL::Comparison_result compare_distances(const Point& p, const Point& q, const Point& r,
                                          const CompareDistance& compare_distance)
{
  using FT = typename CGAL::Kernel_traits<Point>::Kernel::FT;
  if constexpr(std::is_same<FT, double>::value) {
    const double dq = (q.x() - p.x()) * (q.x() - p.x()) + (q.y() - p.y()) * (q.y() - p.y()) + (q.z() - p.z()) * (q.z() - p.z());
    const double dr = (r.x() - p.x()) * (r.x() - p.x()) + (r.y() - p.y()) * (r.y() - p.y()) + (r.z() - p.z()) * (r.z() - p.z());
    if(dq > 1e-250 && dr > 1e-250) {
      if(dq < dr * (1 - 1e-12)) return CGAL::SMALLER;
      if(dq > dr * (1 + 1e-12)) return CGAL::LARGER;
    }
  }
  return compare_distance(p, q, r);
}

/// whether `Visitor` may be told of the merges of one weld from several threads at once and in
/// any order: its `on_merge(duplicate, representative)` writes what belongs to `duplicate` alone,
/// and what it keeps does not depend on the order of the calls. True of `Default_snap_visitor`;
/// a visitor type says so with a member `static constexpr bool tells_merges_concurrently = true`.
/// (A caller's visitor is otherwise told of the merges on one thread, in increasing order of the
/// duplicates.)
template <class Visitor, class = void>
struct tells_merges_concurrently : std::is_same<Visitor, Default_snap_visitor> {};
template <class Visitor>
struct tells_merges_concurrently<Visitor, std::void_t<decltype(Visitor::tells_merges_concurrently)>>
  : std::integral_constant<bool, Visitor::tells_merges_concurrently> {};

/// the `visitor` parameter of `snap_vertices()`, held safely: a copy of the visitor given (or a
/// `Default_snap_visitor`), or a reference to it when it is given as `std::ref(v)`.
template <class NamedParameters>
class Snap_visitor_holder
{
  using Given = typename CGAL::internal_np::Lookup_named_param_def<CGAL::internal_np::visitor_t, NamedParameters,
                                                                   Default_snap_visitor>::type;

public:
  /// the type of the visitor told of the decisions.
  using Visitor = typename Given_visitor<Given>::type;

  /// \param np the parameters of `snap_vertices()`
  explicit Snap_visitor_holder(const NamedParameters& np)
    : held_(CGAL::parameters::choose_parameter<Given>(CGAL::parameters::get_parameter(np, CGAL::internal_np::visitor)))
  {}

  /// the visitor: the copy held, or the visitor referred to.
  Visitor& get() { return Given_visitor<Given>::get(held_); }

private:
  Given held_;
};

/// the most entries of one buffer of the rows of the weld's tolerance graph, so that a row's
/// start fits in 4 bytes (rows go on in a new buffer beyond it). A variable only so that a test
/// can make it small and check that rows spread over many buffers give the same weld.
inline std::size_t row_buffer_limit = std::numeric_limits<std::uint32_t>::max();

/// the room reserved for the entries of a buffer of rows when it is started (16 MiB): the rows
/// fill it and go on in a new buffer, instead of growing one buffer by doubling it (which copies
/// the rows and holds the old and the new buffer at once, the peak of the weld). The room of the
/// last buffer that no row reaches is never written, so its pages are never faulted in.
constexpr std::size_t row_buffer_room = std::size_t(1) << 22;

/// Welds the vertices of an indexed soup within a tolerance, as documented at `snap_vertices()`.
/// `run()` names the steps; each step reads and fills the members below, in this order: short
/// edges, candidates, tolerance graph (components and rows of neighbours), refusals of
/// same-triangle pairs, clusters, ambiguous sites, geometric guard, application.
///
/// With `Small_features::COLLAPSE`, two vertices of one triangle within the tolerance of each
/// other are not refused: the rows of neighbours keep them, a member may share a triangle with
/// the cluster when it is within the tolerance of every vertex of the cluster it shares one
/// with, and the triangles whose corners merge are removed (`collapsed_` lists them) where the
/// edge or point they collapse onto stays on a kept triangle (`cancel_uncovered_collapses()`). Every
/// vertex still moves to a representative within the tolerance of it, so every point of a
/// removed triangle moves by at most the tolerance. Without such a pair in the soup the
/// decisions are those of `Small_features::REFUSE`.
///
/// With per-vertex tolerances (`vertex_tolerance_map`), every "within the tolerance" above is
/// decided for the pair at hand, u and v, by the exact comparison of |uv|^2 with min(t_u, t_v)^2:
/// the short edges, the same-triangle pairs, the rows of neighbours (and so the components and the
/// members of a cluster), and the collapsible pairs. `eps_` is then the largest tolerance, the
/// radius within which the octree lists the candidates before the pair rule filters them. Without
/// a map `tolerances_` is null and each of these places takes the one-tolerance branch it took
/// before (one pointer test per pair, outside the predicates).
template <class Kernel, class Visitor>
class Snap_vertices_worker
{
  using Point = typename Kernel::Point_3;
  using FT = typename Kernel::FT;
  using size_type = Adjacency_tables::size_type;
  using Pair = std::pair<std::uint32_t, std::uint32_t>;
  // a buffer of rows of the tolerance graph (its room reserved in huge pages, see `row_buffer_room`)
  using Row_buffer = Uninitialized_vector<std::uint32_t>;
  // A buffer of rows in a cache line of its own: the threads of the concurrent join each append
  // to their own buffer, and two buffers side by side in `rows_` would share the line that holds
  // their ends (every append of one thread then took the line from the other: the join cost
  // twice the CPU time on two threads that it cost on one).
  struct alignas(64) Row_buffer_slot
  {
    Row_buffer row;
  };
  // the octree of the candidates: candidate `c` is the vertex `candidates_[c]`, its point read
  // from the soup's points through that index
  using Candidate_point_map = typename CGAL::Pointer_property_map<Point>::const_type;
  using Candidate_tree = Octree<Kernel, Candidate_point_map>;

  static constexpr size_type none = static_cast<size_type>(-1);
  static constexpr std::uint32_t not_candidate = static_cast<std::uint32_t>(-1);
  struct Cluster_block;   // what a block of components gives back (below)
  struct Cluster_scratch; // what forming one cluster after another reuses (below)

public:
  /// \param points the points of the soup, read once through the point map
  /// \param tables the tables of the soup over `points`, updated by `run()`
  /// \param eps the absolute tolerance (checked)
  /// \param fixed nonzero for the vertices that may receive welds but not move, or `nullptr`
  /// \param kernel the traits object that takes every geometric decision
  /// \param visitor told of every merge and refusal
  /// \param policy what becomes of two vertices of one triangle within the tolerance
  /// \param tolerances the tolerance of every point (checked), or `nullptr` for `eps` everywhere;
  ///        `eps` is then their largest
  Snap_vertices_worker(const std::vector<Point>& points, Adjacency_tables& tables, const FT& eps,
                       const std::vector<char>* fixed, const Kernel& kernel, Visitor& visitor,
                       Small_features policy = Small_features::REFUSE, const std::vector<FT>* tolerances = nullptr)
    : points_(points), tables_(tables), eps_(eps), fixed_(fixed), kernel_(kernel), visitor_(visitor),
      collapse_(policy == Small_features::COLLAPSE), tolerances_(tolerances)
  {
    report_.tolerance = CGAL::to_double(eps);
    report_.border_edges_before = tables.number_of_border_edges();
  }

  /// runs the weld and writes the triangles it changed back into `triangles`.
  template <class ConcurrencyTag = CGAL::Sequential_tag, class TriangleRange>
  Snap_report run(TriangleRange& triangles)
  {
    count_short_edges<ConcurrencyTag>();
    parallel_ = runs_in_parallel<ConcurrencyTag>();
    collect_candidates<ConcurrencyTag>();
    if(candidates_.size() < 2) {
      report_.border_edges_after = report_.border_edges_before;
      return report_;
    }
    build_tolerance_graph();
    refuse_same_triangle_pairs();
    form_clusters();
    list_ambiguous_sites();
    number_candidates_by_vertex();
    guard_against_degenerate_and_flipped_triangles();
    apply();
    write_back(triangles);
    return report_;
  }

private:
  const Point& point(size_type v) const { return points_[v]; }
  // The point of candidate `c`: the soup's until the tolerance graph's octree is built, then the
  // tree's copy (in the order of the tree, near the points of its neighbours), or the copy of the
  // candidates' points kept for the grid of a dense cluster.
  const Point& candidate_point(std::uint32_t c) const
  {
    if(!candidate_points_.empty()) return candidate_points_[c];
    return tree_ ? tree_->point(c) : point(candidates_[c]);
  }
  size_type final_vertex(size_type v) const { return target_[v] == none ? v : target_[v]; }

  // With per-vertex tolerances: the squared tolerance of the pair (u, v), min(t_u, t_v)^2.
  FT pair_eps2(size_type u, size_type v) const
  {
    const FT& e = smaller_tolerance((*tolerances_)[u], (*tolerances_)[v]);
    return e * e;
  }
  // `true` if the squared distance of p and q is at most e2. With double coordinates a squared
  // distance far from e2 (computed in double, within a few ulps of the exact value) is decided
  // without the exact predicate; otherwise `Compare_squared_distance_3` decides. The same
  // decision either way.
  bool within_squared(const Point& p, const Point& q, const FT& e2) const
  {
    if constexpr(std::is_same<FT, double>::value) {
      const double dx = p.x() - q.x(), dy = p.y() - q.y(), dz = p.z() - q.z();
      const double d2 = dx * dx + dy * dy + dz * dz;
      if(d2 > 1e-250 && e2 > 1e-250) {
        if(d2 < e2 * (1 - 1e-12)) return true;
        if(d2 > e2 * (1 + 1e-12)) return false;
      }
    }
    return kernel_.compare_squared_distance_3_object()(p, q, e2) != CGAL::LARGER;
  }
  // With per-vertex tolerances: `true` if u and v are within the tolerance of the pair.
  bool within_pair_tolerance(size_type u, size_type v) const { return within_squared(point(u), point(v), pair_eps2(u, v)); }
  // The largest distance a corner of the triangle `tr` can move (in double): the tolerance, or
  // with per-vertex tolerances the largest of its corners' (a vertex moves by at most its own).
  double largest_move(const Adjacency_tables::Triangle& tr) const
  {
    if(tolerances_ == nullptr) return report_.tolerance;
    return std::max({CGAL::to_double((*tolerances_)[tr[0]]), CGAL::to_double((*tolerances_)[tr[1]]),
                     CGAL::to_double((*tolerances_)[tr[2]])});
  }

  // Short edges: where the minimum feature separation is not met. Counted by blocks of
  // triangles, on TBB's threads with the tag and double coordinates (whose predicates share no
  // lazily computed state).
  template <class ConcurrencyTag>
  void count_short_edges()
  {
    using Tag = std::conditional_t<std::is_same<FT, double>::value, ConcurrencyTag, CGAL::Sequential_tag>;
    const FT eps2 = eps_ * eps_;
    const std::size_t n = tables_.number_of_triangles();
    std::vector<std::size_t> counts(number_of_blocks(n), 0);
    for_each_block<Tag>(n, default_block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
      std::size_t count = 0;
      for(std::size_t k = begin; k < end; ++k) {
        const size_type t = static_cast<size_type>(k);
        for(int i = 0; i < 3; ++i) {
          const size_type u = tables_.neighbor(t, i);
          if(u != Adjacency_tables::border_edge && u != Adjacency_tables::non_manifold_edge && u < t) continue; // once per edge
          const size_type pv = tables_.vertex(t, i), qv = tables_.vertex(t, (i + 1) % 3);
          if(tolerances_ != nullptr ? within_pair_tolerance(pv, qv) : within_squared(point(pv), point(qv), eps2)) ++count;
        }
      }
      counts[b] = count;
    });
    for(const std::size_t c : counts) report_.short_edges += c;
  }

  // Candidates: the end points of border edges, in increasing index order (a vertex is a
  // candidate when one of its triangles has a border edge at it: each vertex is decided on its
  // own, so the vertices are decided in parallel with the tag).
  template <class ConcurrencyTag>
  void collect_candidates()
  {
    if constexpr(runs_in_parallel<ConcurrencyTag>()) {
      auto on_border = [&](std::size_t v) {
        for(size_type t : tables_.triangles_around_vertex(static_cast<size_type>(v))) {
          const int i = tables_.local_index(t, static_cast<size_type>(v));
          if(tables_.is_border_edge(t, i) || tables_.is_border_edge(t, (i + 2) % 3)) return true;
        }
        return false;
      };
      const std::size_t n = points_.size();
      // (written by the blocks up to `count`, and kept: the pages past it are never touched)
      Uninitialized_vector<size_type> found(n);
      const std::size_t count = compact_in_order<ConcurrencyTag>(
        n, on_border, [&](std::size_t v, std::size_t position) { found[position] = static_cast<size_type>(v); });
      found.resize(count);
      candidates_.swap(found);
    } else {
      std::vector<char> on_border(points_.size(), 0);
      for(size_type t = 0; t < tables_.number_of_triangles(); ++t)
        for(int i = 0; i < 3; ++i)
          if(tables_.is_border_edge(t, i))
            on_border[tables_.vertex(t, i)] = on_border[tables_.vertex(t, (i + 1) % 3)] = 1;
      for(size_type v = 0; v < points_.size(); ++v)
        if(on_border[v]) candidates_.push_back(v);
    }
    report_.candidate_vertices = candidates_.size();
  }

  // The tolerance graph over the candidates (local ids): its connected components (same-triangle
  // pairs included: the sites reported as ambiguous are components) and, unless a cluster is
  // dense, the rows of neighbours of every candidate. With a dense cluster (many candidates in a
  // cell of the grid whose diagonal is the tolerance), a grid joins whole cells without listing
  // their pairs, and the neighbours of a representative are asked of the octree when it is
  // chosen. Otherwise one self-join over the octree gives every neighbourhood at once. Both
  // decide every pair by the same exact predicate: the components and the clusters are the same.
  void build_tolerance_graph()
  {
    const std::size_t n = candidates_.size();
    // The steps below read the candidates' points from the soup (the candidates are in increasing
    // order of their vertices): no copy of them is made before the octree's own.
    // The grid's cells are counted first and the grid built only for a dense cluster. The grid
    // joins whole cells and two cells by their nearest pair, which is right for one tolerance
    // only: with per-vertex tolerances it is not used (every pair is listed by the self-join and
    // decided by the pair rule).
    const auto candidate_in_soup = [this](std::size_t c) -> const Point& { return point(candidates_[c]); };
    dense_ = tolerances_ == nullptr &&
             (parallel_ ? largest_tolerance_cell<CGAL::Parallel_if_available_tag>(n, candidate_in_soup, eps_)
                        : largest_tolerance_cell(n, candidate_in_soup, eps_)) > dense_cell_size;
    const Candidate_point_map in_soup = CGAL::make_property_map(points_.data());
    tree_ = parallel_ ? std::make_unique<Candidate_tree>(candidates_, in_soup, kernel_, CGAL::Parallel_if_available_tag())
                      : std::make_unique<Candidate_tree>(candidates_, in_soup, kernel_, CGAL::Sequential_tag());
    number_candidates_in_tree_order();
    // The grid of a dense cluster reads the candidates' points from a vector of their own.
    if(dense_) {
      candidate_points_.reserve(n);
      for(size_type v : candidates_) candidate_points_.push_back(point(v));
    }
    find_same_triangle_pairs();
    if(dense_) {
      components_.reset(n);
      Tolerance_grid<Kernel>(candidate_points_, eps_, kernel_).unite_components(components_);
    } else {
      join_neighborhoods();
      // Without a dense cluster the clusters read the rows and the points only: the octree (a
      // copy of the candidates' points, its indices and nodes) goes before they allocate, and
      // the points are read from the soup.
      tree_.reset();
    }
  }

  // `for_each_block()` of default-size blocks: on TBB's threads when the weld runs in parallel
  // with double coordinates (whose predicates share no lazily computed state), else on this one.
  template <class F>
  void for_each_block_of_the_weld(std::size_t n, const F& f) const
  {
    if(parallel_ && std::is_same<FT, double>::value)
      for_each_block<CGAL::Parallel_if_available_tag>(n, default_block_size, f);
    else
      for_each_block<CGAL::Sequential_tag>(n, default_block_size, f);
  }

  // `v.assign(n, value)` written by blocks of the weld: in a parallel weld the threads share the
  // writes, and the first touch of fresh pages, of these large arrays.
  template <class Vector, class T>
  void assign_by_blocks(Vector& v, std::size_t n, const T& value) const
  {
    v.clear();
    v.resize(n); // (an `Uninitialized_vector`: not written here)
    for_each_block_of_the_weld(n, [&](std::size_t, std::size_t begin, std::size_t end) {
      std::fill(v.begin() + static_cast<std::ptrdiff_t>(begin), v.begin() + static_cast<std::ptrdiff_t>(end), value);
    });
  }

  // From the octree on, until the ambiguous sites are listed, candidate `c` is the `c`-th in the
  // octree's (Morton) order: the copies of a point, and the neighbours of a candidate in the
  // tolerance graph, are then close in every array of the graph and the clusters (the rows, the
  // union-find, the marks), whatever the order of the soup's triangles. No decision depends on
  // the numbering (the components and the clusters are sets; the members are ordered by
  // distance, then `Less_xyz_3`; the order of the visits is the lexicographic one); what is told
  // in an order (the same-triangle refusals, the merges) keeps the order of the vertices.
  void number_candidates_in_tree_order()
  {
    const Uninitialized_vector<std::uint32_t> order = tree_->number_points_in_tree_order();
    const std::size_t n = order.size();
    Uninitialized_vector<size_type> by_position(n); // (written whole below)
    for_each_block_of_the_weld(n, [&](std::size_t, std::size_t begin, std::size_t end) {
      for(std::size_t j = begin; j < end; ++j) by_position[j] = candidates_[order[j]];
    });
    candidates_.swap(by_position);
  }

  // After the ambiguous sites, the candidates in increasing vertex order again, as the guard and
  // the application go through them; the same-triangle pairs are renumbered with them.
  void number_candidates_by_vertex()
  {
    for(Pair& pr : same_triangle_pairs_) pr = Pair(candidates_[pr.first], candidates_[pr.second]);
    std::size_t k = 0;
    for(std::size_t v = 0; v < candidate_of_.size(); ++v)
      if(candidate_of_[v] != not_candidate) {
        candidate_of_[v] = static_cast<std::uint32_t>(k);
        candidates_[k++] = static_cast<size_type>(v);
      }
    for(Pair& pr : same_triangle_pairs_) pr = Pair(candidate_of_[pr.first], candidate_of_[pr.second]);
    Uninitialized_vector<std::uint32_t>().swap(candidate_of_);
  }

  // Pairs of vertices of one triangle within the tolerance: never merged, found from the
  // triangles, each as (the candidate of its smaller vertex, that of its larger one), listed in
  // the Morton order of the first, then by vertex, once each.
  void find_same_triangle_pairs()
  {
    // By blocks of vertices, then of triangles: the pairs are sorted below, so the order in
    // which the blocks list them does not matter.
    Uninitialized_vector<std::uint32_t>& local = candidate_of_;
    local.resize(points_.size());
    for_each_block_of_the_weld(points_.size(), [&](std::size_t, std::size_t begin, std::size_t end) {
      std::fill(local.begin() + static_cast<std::ptrdiff_t>(begin), local.begin() + static_cast<std::ptrdiff_t>(end), not_candidate);
    });
    for(std::size_t c = 0; c < candidates_.size(); ++c) local[candidates_[c]] = static_cast<std::uint32_t>(c);
    const FT eps2 = eps_ * eps_;
    std::vector<std::vector<Pair>> found(number_of_blocks(tables_.number_of_triangles()));
    for_each_block_of_the_weld(tables_.number_of_triangles(), [&](std::size_t g, std::size_t begin, std::size_t end) {
      for(std::size_t k = begin; k < end; ++k)
        for(int i = 0; i < 3; ++i) {
          const size_type t = static_cast<size_type>(k);
          const size_type u = tables_.vertex(t, i), v = tables_.vertex(t, (i + 1) % 3);
          const std::uint32_t a = local[u], b = local[v];
          if(a == not_candidate || b == not_candidate) continue;
          // (the points of the soup, read in the order of its triangles: the octree's copies are
          // the same points, in another order)
          if(tolerances_ != nullptr ? within_pair_tolerance(u, v) : within_squared(point(u), point(v), eps2))
            found[g].emplace_back(u < v ? Pair(a, b) : Pair(b, a)); // the smaller vertex first
        }
    });
    concatenate_in_block_order(found, same_triangle_pairs_);
    const Candidate_tree& tree = *tree_;
    std::sort(same_triangle_pairs_.begin(), same_triangle_pairs_.end(), [&](const Pair& x, const Pair& y) {
      const std::uint64_t cx = tree.morton_code(x.first), cy = tree.morton_code(y.first);
      if(cx != cy) return cx < cy;
      return std::make_pair(candidates_[x.first], candidates_[x.second]) <
             std::make_pair(candidates_[y.first], candidates_[y.second]);
    });
    same_triangle_pairs_.erase(std::unique(same_triangle_pairs_.begin(), same_triangle_pairs_.end()),
                               same_triangle_pairs_.end());
  }

  // The octree's self-join: unites every pair within the tolerance and fills the rows of
  // neighbours, leaving out same-triangle pairs. A row is in the order of the octree's leaves
  // (`Neighborhood_order::TREE`: no sort of each neighbourhood): its only reader,
  // `gather_members()`, sorts the members it keeps by an order of its own.
  // A row depends on its candidate's neighbourhood only, and the union-find links every root
  // under the smaller one, so that a component's root is its smallest candidate whatever the
  // order of the unions: with the tag and double coordinates the neighbourhoods are handed over
  // on the threads that find them, each thread writes the rows it is given into a buffer of its
  // own and unites concurrently, and the rows and the components are those of one thread.
  void join_neighborhoods()
  {
    const std::size_t n = candidates_.size();
    row_start_.resize(n);
    row_size_.resize(n);
    rows_.clear();
    row_buffer_.clear();
    if constexpr(std::is_same<FT, double>::value) {
      if(parallel_) {
        join_neighborhoods_concurrently(); // (its sets replace `components_` whole)
        return;
      }
    }
    components_.reset(n);
    Row_buffer* row = start_row_buffer(0);
    std::vector<char> mate(points_.size(), 0);
    auto mark_mates = [&](std::size_t c, char value) {
      for(size_type t : tables_.triangles_around_vertex(candidates_[c]))
        for(size_type v : tables_.triangle(t)) mate[v] = value;
    };
    tree_->for_each_neighborhood(eps_, [&](std::size_t c, const std::vector<std::size_t>& found) {
      if(!collapse_) {
#if defined(__GNUC__) || defined(__clang__)
        // The candidates come in their order (the octree's): the mates of the candidates a few
        // steps ahead, read in the tables at vertices that are far apart when the triangles come
        // in no spatial order, are asked for in stages, each reading what an earlier one brought
        // in (hints; in the callback itself, where GCC keeps them). At most `most` triangles of
        // a candidate are prefetched, so a vertex of high degree costs no more here.
        constexpr std::size_t vertex_ahead = 16, list_ahead = 8, triangle_ahead = 4, mate_ahead = 2, most = 8;
        if(c + vertex_ahead < n) tables_.prefetch_vertex(candidates_[c + vertex_ahead]);
        if(c + list_ahead < n) tables_.prefetch_triangles_around_vertex(candidates_[c + list_ahead]);
        if(c + triangle_ahead < n) {
          const Adjacency_tables::Id_range around = tables_.triangles_around_vertex(candidates_[c + triangle_ahead]);
          for(std::size_t k = 0, e = std::min<std::size_t>(around.size(), most); k < e; ++k)
            __builtin_prefetch(&tables_.triangle(around[k]));
        }
        if(c + mate_ahead < n) {
          const Adjacency_tables::Id_range around = tables_.triangles_around_vertex(candidates_[c + mate_ahead]);
          for(std::size_t k = 0, e = std::min<std::size_t>(around.size(), most); k < e; ++k)
            for(size_type v : tables_.triangle(around[k])) __builtin_prefetch(&mate[v]);
        }
#endif
        mark_mates(c, 1);
      }
      if(!row_fits(*row, found.size())) {
        // The first full buffer: the rows so far are in buffer 0, and each row says where it is.
        if(row_buffer_.empty()) row_buffer_.assign(n, 0);
        row = start_row_buffer(found.size());
      }
      if(!row_buffer_.empty()) row_buffer_[c] = static_cast<std::uint32_t>(rows_.size() - 1);
      row_start_[c] = static_cast<std::uint32_t>(row->size());
      for(std::size_t d : found) {
        if(d == c) continue;
        // The octree lists the candidates within the largest tolerance; the pair rule decides.
        if(tolerances_ != nullptr && !within_pair_tolerance(candidates_[c], candidates_[d])) continue;
        components_.unite(static_cast<std::uint32_t>(c), static_cast<std::uint32_t>(d));
        if(collapse_ || !mate[candidates_[d]]) row->push_back(static_cast<std::uint32_t>(d));
      }
      row_size_[c] = static_cast<std::uint32_t>(row->size() - row_start_[c]);
      if(!collapse_) mark_mates(c, 0);
    }, Neighborhood_order::TREE);
  }

  // `true` if a row of up to `length` neighbours can start in `row`: its end stays within the room
  // reserved (no copy of the buffer) and within `row_buffer_limit`, so that its start and its end
  // fit in 4 bytes (a new buffer is started otherwise).
  static bool row_fits(const Row_buffer& row, std::size_t length)
  {
    return row.size() + length <= std::min(row.capacity(), row_buffer_limit);
  }

  // A new buffer of rows at the end of `rows_`, its room reserved for a row of `length` at least:
  // `row_buffer_room`, or 4 entries a candidate when that is less (a small weld, one of many in
  // rounds or tiles, does not reserve, nor touch a huge page of, a room it cannot fill).
  Row_buffer* start_row_buffer(std::size_t length)
  {
    const std::size_t room = std::min(row_buffer_room, 4 * candidates_.size());
    Row_buffer& row = rows_.emplace_back().row;
    row.reserve(std::min(std::max(room, length), std::max(row_buffer_limit, length)));
    return &row;
  }

  // `join_neighborhoods()` on TBB's threads. The vertices that share a triangle with a candidate
  // are listed and sorted per candidate (no array over all the points per thread).
  void join_neighborhoods_concurrently()
  {
    const std::size_t n = candidates_.size();
    // (the sets made and handed over by blocks: their first touch and their copy are shared)
    Concurrent_union_find components(n, Concurrent_union_find::Unset{});
    for_each_block_of_the_weld(n, [&](std::size_t, std::size_t begin, std::size_t end) {
      components.make_singletons(begin, end);
    });
    row_buffer_.resize(n);
    std::mutex buffers_mutex;
    // A new id per call: the buffer a thread remembers belongs to this call only if it holds it.
    static std::atomic<std::uint64_t> calls{0};
    const std::uint64_t call = ++calls;
    struct Thread_rows
    {
      std::uint64_t call = 0;
      std::uint32_t buffer = 0;
      Row_buffer* row = nullptr; // rows_[buffer] (a deque: it stays where it is)
      std::vector<size_type> mates;
    };
    tree_->template for_each_neighborhood_concurrently<CGAL::Parallel_if_available_tag>(
      eps_, [&](std::size_t c, const std::vector<std::size_t>& found) {
        static thread_local Thread_rows mine;
        if(mine.call != call || !row_fits(*mine.row, found.size())) {
          const std::lock_guard<std::mutex> hold(buffers_mutex);
          mine.call = call;
          mine.buffer = static_cast<std::uint32_t>(rows_.size());
          mine.row = start_row_buffer(found.size());
        }
        Row_buffer* const row = mine.row;
        if(!collapse_) {
          mine.mates.clear();
          for(size_type t : tables_.triangles_around_vertex(candidates_[c]))
            for(size_type v : tables_.triangle(t)) mine.mates.push_back(v);
          std::sort(mine.mates.begin(), mine.mates.end());
        }
        row_buffer_[c] = mine.buffer;
        row_start_[c] = static_cast<std::uint32_t>(row->size());
        for(std::size_t d : found) {
          if(d == c) continue;
          if(tolerances_ != nullptr && !within_pair_tolerance(candidates_[c], candidates_[d])) continue;
          components.unite(static_cast<std::uint32_t>(c), static_cast<std::uint32_t>(d));
          if(collapse_ || !std::binary_search(mine.mates.begin(), mine.mates.end(), candidates_[d]))
            row->push_back(static_cast<std::uint32_t>(d));
        }
        row_size_[c] = static_cast<std::uint32_t>(row->size() - row_start_[c]);
      }, Neighborhood_order::TREE);
    components.into(components_, [&](std::size_t size, const auto& f) { for_each_block_of_the_weld(size, f); });
  }

  void refuse_same_triangle_pairs()
  {
    if(collapse_) return; // merged, or refused when the cluster is formed
    for(const Pair& pr : same_triangle_pairs_) {
      ++report_.refused_same_triangle;
      visitor_.on_refusal(candidates_[pr.second], candidates_[pr.first], Refusal_reason::SAME_TRIANGLE);
    }
  }

  // Clusters: canonical representatives, no chaining, no two vertices of one triangle. The
  // candidates are visited in lexicographic order (ties: index); an unassigned one is the
  // smallest unassigned candidate of its component, and becomes a representative.
  //
  // The clusters of a component depend on that component only: its candidates, their triangles
  // and the moves among them (a member and its neighbours are in one component; a corner of a
  // triangle around the cluster that is in another component is never in the cluster, and is
  // recognised as such without reading its target). So the components are taken in the order of
  // their smallest index, which keeps the memory accesses of neighbouring candidates together,
  // each in lexicographic order, and cut into blocks of whole components that do not depend on
  // the number of threads. With the tag (and double coordinates, outside the dense case whose
  // marks of the representative's mates are shared) the blocks run in parallel, each writing
  // only what belongs to its components; the refusals told on the way are kept by block and
  // told, in block order, in the lexicographic order of their representatives, as if the
  // candidates were all taken in that order: the result is that of one thread.
  //
  // No order of all the candidates is needed: each component is sorted on its own, by its block,
  // before its visits (`Less_xyz_3`, ties by vertex; a total order, so a component has one order
  // whatever the order its candidates come in).
  void form_clusters()
  {
    const std::size_t n = candidates_.size();
    assign_by_blocks(target_, points_.size(), none);
    if(dense_) assign_by_blocks(mate_of_, points_.size(), not_candidate);
    assign_by_blocks(assigned_, n, char(0));
    assign_by_blocks(component_size_, n, std::uint32_t(0));
    assign_by_blocks(largest_cluster_, n, std::uint32_t(0));
    // The components are read as roots from here on: their storage becomes `root_`.
    root_ = components_.take_roots();
    for(std::uint32_t c = 0; c < n; ++c) ++component_size_[root_[c]];
    // The candidates of the components of two or more, component after component in the order of
    // their roots; each component is put in lexicographic order by its block below.
    Uninitialized_vector<std::uint32_t>& visits = visits_;
    Uninitialized_vector<std::uint32_t> next_visit(n); // (written before it is read)
    visits.resize(n);
    std::uint32_t number_of_visits = 0;
    for(std::uint32_t c = 0; c < n; ++c)
      if(root_[c] == c && component_size_[c] >= 2) { next_visit[c] = number_of_visits; number_of_visits += component_size_[c]; }
    for(std::uint32_t c = 0; c < n; ++c)
      if(component_size_[root_[c]] >= 2) visits[next_visit[root_[c]]++] = c;
    visits.resize(number_of_visits);
    Uninitialized_vector<std::uint32_t>().swap(next_visit);
    // Blocks of whole components, of at least `visits_per_block` visits each (the last one may
    // be smaller): the visits of a component are consecutive.
    constexpr std::size_t visits_per_block = 4096;
    std::vector<std::size_t> block_begin{0};
    for(std::size_t k = 1; k < visits.size(); ++k)
      if(k - block_begin.back() >= visits_per_block && root_[visits[k]] != root_[visits[k - 1]]) block_begin.push_back(k);
    block_begin.push_back(visits.size());
    const std::size_t blocks = block_begin.size() - 1;
    std::vector<Cluster_block> results(blocks);
    Scratch_pool pool(tables_.number_of_triangles());
    const typename Kernel::Compare_xyz_3 compare_xyz = kernel_.compare_xyz_3_object();
    auto run_block = [&](std::size_t b) {
      std::unique_ptr<Cluster_scratch> scratch = pool.acquire();
      Cluster_block& out = results[b];
      const std::size_t end = block_begin[b + 1];
      // Each component of the block in lexicographic order. The points of the candidates a few
      // components ahead are asked for first: in a soup whose triangles come in no spatial order
      // they are far apart (hints; the sort reads them, and the visits find them in cache).
      const auto at = [&](std::size_t k) { return visits.begin() + static_cast<std::ptrdiff_t>(k); };
      std::size_t asked = block_begin[b];
      for(std::size_t k = block_begin[b]; k != end;) {
        const std::size_t component_end = k + component_size_[root_[visits[k]]];
#if defined(__GNUC__) || defined(__clang__)
        constexpr std::size_t points_ahead = 48;
        for(; asked < std::min(end, component_end + points_ahead); ++asked)
          __builtin_prefetch(&candidate_point(visits[asked]));
#endif
        std::sort(at(k), at(component_end),
                  [&](std::uint32_t x, std::uint32_t y) { return less_lexicographically(x, y, compare_xyz); });
        k = component_end;
      }
      (void)asked;
      for(std::size_t k = block_begin[b]; k != end; ++k) {
        if(!dense_) prefetch_visits(visits, k, end, *scratch);
        const std::uint32_t rep = visits[k];
        if(assigned_[rep]) continue;
        assigned_[rep] = 1;
        gather_members(rep, *scratch);
        const std::uint32_t cluster_size = join_members(rep, *scratch, out);
        largest_cluster_[root_[rep]] = std::max(largest_cluster_[root_[rep]], cluster_size);
      }
      pool.release(scratch);
    };
    if(parallel_ && !dense_ && std::is_same<FT, double>::value)
      for_each_block<CGAL::Parallel_if_available_tag>(blocks, 1, [&](std::size_t b, std::size_t, std::size_t) { run_block(b); });
    else
      for(std::size_t b = 0; b < blocks; ++b) run_block(b);
    deferred_refusals_.clear();
    for(Cluster_block& block : results) {
      report_.refused_holds_welds += block.refused_holds_welds;
      report_.refused_same_triangle += block.refused_same_triangle;
      deferred_refusals_.insert(deferred_refusals_.end(), block.refusals.begin(), block.refusals.end());
      std::vector<Deferred_refusal>().swap(block.refusals);
    }
    // (the refusals of one representative are together, in the order they were met)
    std::stable_sort(deferred_refusals_.begin(), deferred_refusals_.end(),
                     [&](const Deferred_refusal& a, const Deferred_refusal& b) {
                       return a.representative != b.representative &&
                              less_lexicographically(candidate_of_[a.representative], candidate_of_[b.representative],
                                                     compare_xyz);
                     });
    for(const Deferred_refusal& r : deferred_refusals_) visitor_.on_refusal(r.vertex, r.representative, r.reason);
    release_tolerance_graph();
  }

  // The visits of the clusters read, for each representative, its row, and for each of its
  // neighbours whether it is assigned, its vertex, its point and its list of triangles in the
  // tables (whose marks then tell whether it shares a triangle with the cluster): in an exploded
  // soup the copies of one point are far apart in the candidates' order, and in the tables' when
  // the triangles come in no spatial order, and each of these reads missed the cache. The reads
  // of the visits a few steps ahead are prefetched in stages, each stage reading what an earlier
  // one brought in (a hint only: nothing is decided on what it reads). At most `most` neighbours
  // of a visit are prefetched, so a long row costs no more here.
#if defined(__GNUC__) || defined(__clang__)
  // (always inlined: GCC finds a function that only prefetches free of side effects and drops
  // the calls to it)
  __attribute__((always_inline))
#endif
  void prefetch_visits(const Uninitialized_vector<std::uint32_t>& visits, std::size_t k, std::size_t end,
                       const Cluster_scratch& scratch) const
  {
#if defined(__GNUC__) || defined(__clang__)
    constexpr std::uint32_t most = 8;
    constexpr std::size_t row_ahead = 36, start_ahead = 24, neighbour_ahead = 16, point_ahead = 12, list_ahead = 8,
                          mark_ahead = 4;
    const auto row_of = [&](std::uint32_t v) -> const std::uint32_t* {
      return rows_[row_buffer_.empty() ? 0 : row_buffer_[v]].row.data() + row_start_[v];
    };
    // the first neighbours of visit `v` (at most `most`; none once `v` is assigned): a row and
    // its length, read here, prefetched by the plain loops below
    const auto neighbours_of = [&](std::uint32_t v) -> std::pair<const std::uint32_t*, std::uint32_t> {
      if(assigned_[v]) return {nullptr, 0u};
      return {row_of(v), std::min<std::uint32_t>(row_size_[v], most)};
    };
    // (plain loops: a lambda that only prefetches is dropped like such a function)
    if(k + row_ahead < end) {
      const std::uint32_t v = visits[k + row_ahead];
      __builtin_prefetch(&assigned_[v]);
      __builtin_prefetch(&row_start_[v]);
      __builtin_prefetch(&row_size_[v]);
      __builtin_prefetch(&candidates_[v]);
      if(!row_buffer_.empty()) __builtin_prefetch(&row_buffer_[v]);
    }
    if(k + start_ahead < end) {
      const std::uint32_t v = visits[k + start_ahead];
      __builtin_prefetch(row_of(v));
      __builtin_prefetch(&points_[candidates_[v]]);
      tables_.prefetch_vertex(candidates_[v]);
    }
    if(k + neighbour_ahead < end) {
      const std::uint32_t v = visits[k + neighbour_ahead];
      tables_.prefetch_triangles_around_vertex(candidates_[v]);
      const auto [row, e] = neighbours_of(v);
      for(std::uint32_t q = 0; q < e; ++q) {
        __builtin_prefetch(&assigned_[row[q]]);
        __builtin_prefetch(&candidates_[row[q]]);
      }
    }
    if(k + point_ahead < end) {
      const auto [row, e] = neighbours_of(visits[k + point_ahead]);
      for(std::uint32_t q = 0; q < e; ++q) {
        __builtin_prefetch(&points_[candidates_[row[q]]]);
        tables_.prefetch_vertex(candidates_[row[q]]);
      }
    }
    if(k + list_ahead < end) {
      const auto [row, e] = neighbours_of(visits[k + list_ahead]);
      for(std::uint32_t q = 0; q < e; ++q) tables_.prefetch_triangles_around_vertex(candidates_[row[q]]);
    }
    if(k + mark_ahead < end) {
      const auto [row, e] = neighbours_of(visits[k + mark_ahead]);
      for(std::uint32_t q = 0; q < e; ++q) {
        const Adjacency_tables::Id_range around = tables_.triangles_around_vertex(candidates_[row[q]]);
        if(around.begin() != around.end()) __builtin_prefetch(&scratch.in_cluster_mark[*around.begin()]);
      }
    }
#else
    (void)visits; (void)k; (void)end; (void)scratch;
#endif
  }

  // The octree, the candidates' points and the rows of the tolerance graph are read by no step
  // after the clusters: they go before the guard and the application allocate (the peak memory
  // of a weld that rebuilds its tables).
  void release_tolerance_graph()
  {
    tree_.reset();
    std::vector<Point>().swap(candidate_points_);
    std::deque<Row_buffer_slot>().swap(rows_);
    Uninitialized_vector<std::uint32_t>().swap(row_buffer_);
    Uninitialized_vector<std::uint32_t>().swap(row_start_);
    Uninitialized_vector<std::uint32_t>().swap(row_size_);
  }

  // The unassigned neighbours of the representative `rep` that share no triangle with it,
  // nearest first (ties by `Less_xyz_3`, then by vertex: a total order, so that the members
  // come in the same order whatever the order of the row), into `scratch.members`.
  void gather_members(std::uint32_t rep, Cluster_scratch& scratch)
  {
    std::vector<std::uint32_t>& members = scratch.members;
    std::vector<std::size_t>& found = scratch.found;
    std::vector<std::pair<double, std::uint32_t>>& member_distances = scratch.member_distances;
    members.clear();
    if(dense_) {
      for(size_type t : tables_.triangles_around_vertex(candidates_[rep]))
        for(size_type v : tables_.triangle(t)) mate_of_[v] = rep;
      found.clear();
      tree_->vertices_near_point(candidate_point(rep), eps_, std::back_inserter(found));
      for(std::size_t d : found)
        if(d != rep && !assigned_[d] && (collapse_ || mate_of_[candidates_[d]] != rep))
          members.push_back(static_cast<std::uint32_t>(d));
    } else {
      const Row_buffer& row = rows_[row_buffer_.empty() ? 0 : row_buffer_[rep]].row;
      for(std::size_t k = row_start_[rep], end = k + row_size_[rep]; k < end; ++k)
        if(!assigned_[row[k]]) members.push_back(row[k]);
    }
    const typename Kernel::Compare_xyz_3 compare_xyz = kernel_.compare_xyz_3_object();
    const typename Kernel::Compare_distance_3 compare_distance = kernel_.compare_distance_3_object();
    const Point& center = candidate_point(rep);
    if constexpr(std::is_same<FT, double>::value) {
      // The order of `compare_distances()`, with the squared distances in double computed once.
      auto squared_distance = [&](const Point& q) {
        return (q.x() - center.x()) * (q.x() - center.x()) + (q.y() - center.y()) * (q.y() - center.y()) +
               (q.z() - center.z()) * (q.z() - center.z());
      };
      member_distances.clear();
      for(std::uint32_t m : members) member_distances.emplace_back(squared_distance(candidate_point(m)), m);
      std::sort(member_distances.begin(), member_distances.end(), [&](const auto& a, const auto& b) {
        const double dq = a.first, dr = b.first;
        if(dq > 1e-250 && dr > 1e-250) {
          if(dq < dr * (1 - 1e-12)) return true;
          if(dq > dr * (1 + 1e-12)) return false;
        }
        const CGAL::Comparison_result r = compare_distance(center, candidate_point(a.second), candidate_point(b.second));
        if(r != CGAL::EQUAL) return r == CGAL::SMALLER;
        return less_lexicographically(a.second, b.second, compare_xyz);
      });
      for(std::size_t k = 0; k < members.size(); ++k) members[k] = member_distances[k].second;
    } else {
      std::sort(members.begin(), members.end(), [&](std::uint32_t a, std::uint32_t b) {
        const CGAL::Comparison_result r = compare_distances(center, candidate_point(a), candidate_point(b),
                                                            compare_distance);
        if(r != CGAL::EQUAL) return r == CGAL::SMALLER;
        return less_lexicographically(a, b, compare_xyz);
      });
    }
    members.erase(std::unique(members.begin(), members.end()), members.end());
  }

  // The lexicographic order of the clusters' visits and of a cluster's members at equal distance:
  // `Less_xyz_3` on the points of candidates `a` and `b` (one `Compare_xyz_3`), then their
  // vertices (equal points only when the caller's points are not pairwise distinct). A total
  // order, whatever the numbering of the candidates.
  bool less_lexicographically(std::uint32_t a, std::uint32_t b, const typename Kernel::Compare_xyz_3& compare_xyz) const
  {
    const CGAL::Comparison_result r = compare_xyz(candidate_point(a), candidate_point(b));
    if(r != CGAL::EQUAL) return r == CGAL::SMALLER;
    return candidates_[a] < candidates_[b];
  }

  // Joins the members to the cluster of `rep` in turn, refusing those that hold welds or share
  // a triangle with a vertex already in the cluster (the refusals are kept in `out` and told by
  // `form_clusters()`); returns the size of the cluster.
  std::uint32_t join_members(std::uint32_t rep, Cluster_scratch& scratch, Cluster_block& out)
  {
    const size_type rep_v = candidates_[rep];
    std::vector<std::uint32_t>& in_cluster_mark = scratch.in_cluster_mark;
    const std::uint32_t cluster_id = ++scratch.cluster_id;
    for(size_type t : tables_.triangles_around_vertex(rep_v)) in_cluster_mark[t] = cluster_id;
    std::uint32_t cluster_size = 1;
    for(std::uint32_t m : scratch.members) {
      const size_type mv = candidates_[m];
      if(fixed_ != nullptr && (*fixed_)[mv]) {
        // mv received welds in an earlier call: it may be a representative, never move.
        ++out.refused_holds_welds;
        out.refusals.push_back({mv, rep_v, Refusal_reason::HOLDS_WELDS});
        continue;
      }
      bool conflict = false;
      for(size_type t : tables_.triangles_around_vertex(mv))
        if(in_cluster_mark[t] == cluster_id && !(collapse_ && collapsible(t, mv, rep_v))) { conflict = true; break; }
      if(conflict) {
        ++out.refused_same_triangle;
        out.refusals.push_back({mv, rep_v, Refusal_reason::SAME_TRIANGLE});
        continue;
      }
      for(size_type t : tables_.triangles_around_vertex(mv)) in_cluster_mark[t] = cluster_id;
      assigned_[m] = 1;
      target_[mv] = rep_v;
      ++cluster_size;
    }
    return cluster_size;
  }

  // Under `Small_features::COLLAPSE`: `true` if member `mv` may join the cluster of `rep_v` although
  // it shares triangle `t` with it: `mv` is within the tolerance of every vertex of `t` in the
  // cluster (the collapsed edges are all shorter than the tolerance).
  bool collapsible(size_type t, size_type mv, size_type rep_v) const
  {
    const FT eps2 = eps_ * eps_;
    const std::uint32_t component = root_[candidate_of_[rep_v]];
    for(size_type w : tables_.triangle(t)) {
      if(w == mv) continue;
      if(w != rep_v) {
        // In the cluster only if merged into `rep_v`, which only a candidate of its component
        // can be: the target of a vertex of another component is not read (another block may
        // be writing it).
        const std::uint32_t cw = candidate_of_[w];
        if(cw == not_candidate || root_[cw] != component || target_[w] != rep_v) continue;
      }
      if(tolerances_ != nullptr) {
        if(!within_pair_tolerance(mv, w)) return false;
        continue;
      }
      if(!within_squared(point(mv), point(w), eps2)) return false;
    }
    return true;
  }

  // Ambiguous sites: the components that hold two vertices of one triangle, or that did not all
  // go to one representative. Each is listed by its lexicographically smallest point, so that
  // the sites do not depend on the numbering of the vertices.
  void list_ambiguous_sites()
  {
    const std::size_t n = candidates_.size();
    std::vector<char> ambiguous(n, 0);
    if(!collapse_)
      for(const Pair& pr : same_triangle_pairs_) ambiguous[root_[pr.first]] = 1;
    for(std::uint32_t c = 0; c < n; ++c)
      if(root_[c] == c && component_size_[c] >= 2 && largest_cluster_[c] != component_size_[c])
        ambiguous[c] = 1;
    // (an ambiguous component has two candidates or more: its first visit is its smallest point)
    for(const std::uint32_t c : visits_) {
      const std::uint32_t root = root_[c];
      if(ambiguous[root]) {
        report_.ambiguous_sites.push_back(candidates_[c]);
        ambiguous[root] = 0;
      }
    }
    Uninitialized_vector<std::uint32_t>().swap(visits_);
    std::sort(report_.ambiguous_sites.begin(), report_.ambiguous_sites.end());
  }

  // Geometric validity: no triangle may become degenerate or flip; refuse until stable. Each
  // pass checks the touched triangles against the moves of the previous pass and cancels the
  // moves of all failing triangles at once, so the result does not depend on the order in which
  // the triangles are stored.
  //
  // Only the first pass of each kind checks every touched triangle; a later pass checks what the
  // cancellations since the previous pass of its kind can change, which gives the same
  // decisions:
  // - the verdict of `cancel_failing_moves()` on a triangle depends on the final vertices of its
  //   three corners only, and a cancellation changes the final vertex of the cancelled vertex
  //   only (a representative never moves, so no other vertex ends at a moving one). A triangle
  //   with no cancelled corner since its last check has the verdict of that check: it passed
  //   (a failing triangle has all its moving corners cancelled), and passes again. So the
  //   triangles around the vertices cancelled since the previous pass are the only ones that
  //   can fail, and a pass that checks them finds the same failing triangles as a pass over all;
  // - under `cancel_uncovered_collapses()` a collapsing triangle with image (p, q) is covered
  //   exactly when some non-collapsing triangle has final vertices p and q (p alone for a point):
  //   such a triangle has a corner ending at p and one ending at q, which are ends of images or
  //   vertices merged into them, and every covering pair is made of such corners. Cancellations
  //   never make a triangle collapse (the cancelled vertex ends at itself, which no other vertex
  //   does). A collapsing triangle t without a cancelled corner keeps its image (p, q). A
  //   triangle K that covered it and no longer does lost a corner ending at p or at q (if both
  //   stay, K keeps p and q, and its cancelled corners end at themselves, distinct from them):
  //   p or q was the target of a cancelled vertex. A triangle that was uncovered had its moving
  //   corners cancelled. So the collapsing triangles around the cancelled vertices and those
  //   with an end that was the target of a cancelled vertex are the only ones whose verdict can
  //   change.
  // The cancellations of a pass are then the same, in the same vertex order, with the same
  // reasons, the same visitor calls and the same counts. Each vertex is cancelled once, so the
  // passes after the first check the triangles around the cancelled vertices (and, for the
  // collapses, around the clusters that lost a member) rather than every touched triangle.
  void guard_against_degenerate_and_flipped_triangles()
  {
    // The triangles around a moved vertex: those with a corner that moves (only candidates do),
    // found by blocks of the weld, in increasing order.
    std::vector<std::vector<size_type>> touched_by_block(number_of_blocks(tables_.number_of_triangles()));
    for_each_block_of_the_weld(tables_.number_of_triangles(), [&](std::size_t b, std::size_t begin, std::size_t end) {
      for(std::size_t t = begin; t != end; ++t) {
        const Adjacency_tables::Triangle& tr = tables_.triangle(static_cast<size_type>(t));
        if(target_[tr[0]] != none || target_[tr[1]] != none || target_[tr[2]] != none)
          touched_by_block[b].push_back(static_cast<size_type>(t));
      }
    });
    concatenate_in_block_order(touched_by_block, touched_);
    do {
      while(cancel_failing_moves()) {}
    } while(collapse_ && cancel_uncovered_collapses());
  }

  // `true` if two corners of the triangle `t` end at one vertex (only under COLLAPSE: clusters
  // hold no two vertices of one triangle otherwise).
  bool collapses(size_type t) const
  {
    const Adjacency_tables::Triangle& tr = tables_.triangle(t);
    const size_type n0 = final_vertex(tr[0]), n1 = final_vertex(tr[1]), n2 = final_vertex(tr[2]);
    return n0 == n1 || n1 == n2 || n2 == n0;
  }

  // Marks `t` as listed in the current pass; `false` if it was already.
  bool mark_for_pass(size_type t)
  {
    if(pass_mark_.empty()) pass_mark_.assign(tables_.number_of_triangles(), 0);
    if(pass_mark_[t] == pass_id_) return false;
    pass_mark_[t] = pass_id_;
    return true;
  }

  // Cancels the moves listed in `cancelled_` (sorted: by vertex, then reason), each vertex once
  // with its first reason; `true` if some move was cancelled.
  bool cancel_listed_moves()
  {
    std::sort(cancelled_.begin(), cancelled_.end());
    bool changed = false;
    for(const auto& [v, why] : cancelled_) {
      if(target_[v] == none) continue;
      visitor_.on_refusal(v, target_[v], why);
      if(why == Refusal_reason::DEGENERATE) ++report_.refused_degenerate;
      else if(why == Refusal_reason::UNCOVERED_COLLAPSE) ++report_.refused_uncovered_collapse;
      else ++report_.refused_flip;
      cancelled_since_moves_check_.push_back(v);
      cancelled_since_collapses_check_.emplace_back(v, target_[v]);
      target_[v] = none;
      changed = true;
    }
    return changed;
  }

  // One pass of the guard; `true` if some move was cancelled.
  bool cancel_failing_moves()
  {
    cancelled_.clear();
    // (`cancelled` receives the moves to cancel; they are sorted before they are told)
    auto check = [&](size_type t, std::vector<std::pair<size_type, Refusal_reason>>& cancelled) {
      const Adjacency_tables::Triangle& tr = tables_.triangle(t);
      const size_type n0 = final_vertex(tr[0]), n1 = final_vertex(tr[1]), n2 = final_vertex(tr[2]);
      if(n0 == tr[0] && n1 == tr[1] && n2 == tr[2]) return;
      // Two corners merged: the triangle is removed, nothing of it to keep.
      if(n0 == n1 || n1 == n2 || n2 == n0) return;
      Refusal_reason why = Refusal_reason::FLIP;
      if(fat_enough_for_moves(point(tr[0]), point(tr[1]), point(tr[2]), largest_move(tr))) return;
      if(moves_keep_triangle(point(tr[0]), point(tr[1]), point(tr[2]), point(n0), point(n1), point(n2), kernel_, why))
        return;
      for(size_type v : tr)
        if(target_[v] != none) cancelled.emplace_back(v, why);
    };
    if(!moves_checked_) {
      // every triangle touched, by blocks of the weld
      moves_checked_ = true;
      std::vector<std::vector<std::pair<size_type, Refusal_reason>>> cancelled_by_block(
        number_of_blocks(touched_.size()));
      for_each_block_of_the_weld(touched_.size(), [&](std::size_t b, std::size_t begin, std::size_t end) {
        for(std::size_t i = begin; i != end; ++i) check(touched_[i], cancelled_by_block[b]);
      });
      concatenate_in_block_order(cancelled_by_block, cancelled_);
    } else {
      ++pass_id_;
      for(size_type v : cancelled_since_moves_check_)
        for(size_type t : tables_.triangles_around_vertex(v))
          if(mark_for_pass(t)) check(t, cancelled_);
    }
    cancelled_since_moves_check_.clear();
    // A vertex cancelled by several triangles is counted once, with the first reason in vertex order.
    return cancel_listed_moves();
  }

  // Under `Small_features::COLLAPSE`: a triangle two of whose corners merge collapses onto an edge
  // (or, all three, onto a point) of the final vertices; the collapse is kept only if that edge
  // (point) belongs to a triangle that is kept, so that every point of the removed triangle,
  // moved by at most the tolerance, lands on the surface. Otherwise the moves of its corners are
  // cancelled. All uncovered collapses of a pass are cancelled at once (the result does not
  // depend on the order of the triangles); `true` if some move was cancelled.
  bool cancel_uncovered_collapses()
  {
    std::vector<size_type> collapsing;
    if(!collapses_checked_) {
      collapses_checked_ = true;
      for(size_type t : touched_)
        if(collapses(t)) collapsing.push_back(t);
      // What the later passes look up: the collapsing triangles by the ends of their images, and
      // the vertices merged into each representative.
      for(size_type t : collapsing)
        for(size_type v : tables_.triangle(t)) collapsing_by_end_.emplace_back(final_vertex(v), t);
      std::sort(collapsing_by_end_.begin(), collapsing_by_end_.end());
      collapsing_by_end_.erase(std::unique(collapsing_by_end_.begin(), collapsing_by_end_.end()),
                               collapsing_by_end_.end());
      if(!collapsing.empty())
        for(size_type v : candidates_)
          if(target_[v] != none) merged_into_.emplace_back(target_[v], v);
      std::sort(merged_into_.begin(), merged_into_.end());
    } else {
      ++pass_id_;
      std::vector<size_type> former_targets;
      for(const auto& [v, former_target] : cancelled_since_collapses_check_) {
        for(size_type t : tables_.triangles_around_vertex(v))
          if(collapses(t) && mark_for_pass(t)) collapsing.push_back(t);
        former_targets.push_back(former_target);
      }
      // Each representative once: a cluster may lose many members in one pass.
      std::sort(former_targets.begin(), former_targets.end());
      former_targets.erase(std::unique(former_targets.begin(), former_targets.end()), former_targets.end());
      for(size_type r : former_targets) {
        auto range = std::equal_range(collapsing_by_end_.begin(), collapsing_by_end_.end(), std::make_pair(r, size_type(0)),
                                      [](const auto& x, const auto& y) { return x.first < y.first; });
        for(auto it = range.first; it != range.second; ++it)
          if(collapses(it->second) && mark_for_pass(it->second)) collapsing.push_back(it->second);
      }
    }
    cancelled_since_collapses_check_.clear();
    if(collapsing.empty()) return false;
    std::vector<size_type> image_ends;
    is_image_end_.resize(points_.size(), 0);
    for(size_type t : collapsing)
      for(size_type v : tables_.triangle(t)) {
        const size_type end = final_vertex(v);
        if(!is_image_end_[end]) { is_image_end_[end] = 1; image_ends.push_back(end); }
      }
    // The vertices that end at an end of an image: the end itself and the vertices merged into it.
    std::vector<size_type> at_image_ends = image_ends;
    for(size_type end : image_ends) {
      auto range = std::equal_range(merged_into_.begin(), merged_into_.end(), std::make_pair(end, size_type(0)),
                                    [](const auto& x, const auto& y) { return x.first < y.first; });
      for(auto it = range.first; it != range.second; ++it)
        if(target_[it->second] == end) at_image_ends.push_back(it->second);
    }
    // The edges and corners of the kept triangles at the ends of the images, as pairs of final vertices.
    std::vector<std::pair<size_type, size_type>> kept;
    for(size_type v : at_image_ends) {
      const size_type x = final_vertex(v);
      for(size_type t : tables_.triangles_around_vertex(v)) {
        if(collapses(t)) continue;
        for(size_type w : tables_.triangle(t)) {
          const size_type f = final_vertex(w);
          kept.emplace_back(std::min(x, f), std::max(x, f));
        }
      }
    }
    std::sort(kept.begin(), kept.end());
    cancelled_.clear();
    for(size_type t : collapsing) {
      const Adjacency_tables::Triangle& tr = tables_.triangle(t);
      const size_type n0 = final_vertex(tr[0]), n1 = final_vertex(tr[1]), n2 = final_vertex(tr[2]);
      // The two ends of the image (equal when it is a point).
      const size_type p = std::min({n0, n1, n2}), q = std::max({n0, n1, n2});
      if(std::binary_search(kept.begin(), kept.end(), std::make_pair(p, q))) continue;
      for(size_type v : tr)
        if(target_[v] != none) cancelled_.emplace_back(v, Refusal_reason::UNCOVERED_COLLAPSE);
    }
    for(size_type end : image_ends) is_image_end_[end] = 0;
    return cancel_listed_moves();
  }

  // Applies the merges, in increasing index order. Few merges: local updates of the tables
  // (`replace_vertex`, the patent's rules (a)-(c)). Many merges (an exploded soup): the
  // triangles are rewritten once and the tables rebuilt, which is linear, where thousands of
  // local updates around the same representatives are not. Both give the same tables.
  //
  // Triangles whose corners merge (`Small_features::COLLAPSE`) are removed, the others keep their
  // order, and the tables are rebuilt: the neighbours of a removed triangle are linked across it.
  void apply()
  {
    std::vector<std::size_t> merges_by_block(number_of_blocks(candidates_.size()), 0);
    for_each_block_of_the_weld(candidates_.size(), [&](std::size_t g, std::size_t begin, std::size_t end) {
      for(std::size_t i = begin; i != end; ++i) merges_by_block[g] += target_[candidates_[i]] != none ? 1 : 0;
    });
    std::size_t number_of_merges = 0;
    for(std::size_t m : merges_by_block) number_of_merges += m;
    if(collapse_) count_collapses();
    const bool rebuild = number_of_merges > tables_.number_of_triangles() / 16 + 64 || !collapsed_.empty();
    if(rebuild) {
      // every triangle on its final vertices (by blocks, on TBB's threads in a parallel weld: every
      // entry written there), then the collapsed ones left out, the others keeping their order
      Uninitialized_vector<Adjacency_tables::Triangle> rewritten(tables_.number_of_triangles());
      for_each_block_of_the_weld(rewritten.size(), [&](std::size_t, std::size_t begin, std::size_t end) {
        for(std::size_t t = begin; t != end; ++t) {
          Adjacency_tables::Triangle tr = tables_.triangle(static_cast<size_type>(t));
          for(size_type& v : tr) v = final_vertex(v);
          rewritten[t] = tr;
        }
      });
      if(!collapsed_.empty()) {
        std::size_t kept = 0, next_collapsed = 0;
        for(std::size_t t = 0; t < rewritten.size(); ++t) {
          if(next_collapsed < collapsed_.size() && collapsed_[next_collapsed] == t) { ++next_collapsed; continue; }
          rewritten[kept++] = rewritten[t];
        }
        rewritten.resize(kept);
      }
      if(parallel_)
        tables_ = Adjacency_tables(rewritten, points_.size(), CGAL::Parallel_if_available_tag());
      else
        tables_ = Adjacency_tables(rewritten, points_.size());
    }
    const typename Kernel::Compute_squared_distance_3 squared_distance = kernel_.compute_squared_distance_3_object();
    if constexpr(tells_merges_concurrently<Visitor>::value) {
      if(rebuild) {
        tell_merges_by_blocks(number_of_merges);
        report_.border_edges_after = tables_.number_of_border_edges();
        return;
      }
    }
    std::vector<char> is_representative(points_.size(), 0);
    // (the representatives' points are read at random when the triangles come in no spatial
    // order: a few merges ahead, they are asked for)
    constexpr std::size_t ahead = 16;
    for(std::size_t i = 0, n = candidates_.size(); i < n; ++i) {
#if defined(__GNUC__) || defined(__clang__)
      if(i + ahead < n && target_[candidates_[i + ahead]] != none) {
        __builtin_prefetch(&points_[target_[candidates_[i + ahead]]]);
        __builtin_prefetch(&is_representative[target_[candidates_[i + ahead]]]);
      }
#endif
      const size_type v = candidates_[i];
      if(target_[v] == none) continue;
      const size_type r = target_[v];
      if(!rebuild) tables_.replace_vertex(v, r);
      visitor_.on_merge(v, r);
      ++report_.merged_vertices;
      if(!is_representative[r]) { is_representative[r] = 1; ++report_.clusters; }
      report_.max_displacement =
        std::max(report_.max_displacement, std::sqrt(CGAL::to_double(squared_distance(point(v), point(r)))));
    }
    report_.border_edges_after = tables_.number_of_border_edges();
  }

  // The merges told to a visitor that takes them in any order (`tells_merges_concurrently`),
  // once the tables are rebuilt (none is updated here), by blocks of the weld: the counts and the
  // largest displacement are those of the loop of `apply()` (a count and a maximum do not depend
  // on the order). A representative is counted by the one merge that marks it first (a relaxed
  // exchange on a byte of its own).
  void tell_merges_by_blocks(std::size_t number_of_merges)
  {
    const typename Kernel::Compute_squared_distance_3 squared_distance = kernel_.compute_squared_distance_3_object();
    std::unique_ptr<std::atomic<unsigned char>[]> is_representative(new std::atomic<unsigned char>[points_.size()]);
    for_each_block_of_the_weld(points_.size(), [&](std::size_t, std::size_t begin, std::size_t end) {
      for(std::size_t v = begin; v != end; ++v) is_representative[v].store(0, std::memory_order_relaxed);
    });
    const std::size_t blocks = number_of_blocks(candidates_.size());
    std::vector<std::size_t> clusters(blocks, 0);
    std::vector<double> largest(blocks, 0.);
    for_each_block_of_the_weld(candidates_.size(), [&](std::size_t g, std::size_t begin, std::size_t end) {
      for(std::size_t i = begin; i != end; ++i) {
        const size_type v = candidates_[i];
        if(target_[v] == none) continue;
        const size_type r = target_[v];
        visitor_.on_merge(v, r);
        if(is_representative[r].load(std::memory_order_relaxed) == 0 &&
           is_representative[r].exchange(1, std::memory_order_relaxed) == 0)
          ++clusters[g];
        largest[g] = std::max(largest[g], std::sqrt(CGAL::to_double(squared_distance(point(v), point(r)))));
      }
    });
    report_.merged_vertices += number_of_merges;
    for(std::size_t g = 0; g < blocks; ++g) {
      report_.clusters += clusters[g];
      report_.max_displacement = std::max(report_.max_displacement, largest[g]);
    }
  }

  // The triangles removed (in increasing order) and the pairs of vertices of one triangle
  // within the tolerance that were merged.
  void count_collapses()
  {
    for(size_type t : touched_) {
      const Adjacency_tables::Triangle& tr = tables_.triangle(t);
      const size_type n0 = final_vertex(tr[0]), n1 = final_vertex(tr[1]), n2 = final_vertex(tr[2]);
      if(n0 == n1 || n1 == n2 || n2 == n0) collapsed_.push_back(t);
    }
    report_.collapsed_triangles = collapsed_.size();
    for(const Pair& pr : same_triangle_pairs_)
      if(final_vertex(candidates_[pr.first]) == final_vertex(candidates_[pr.second])) ++report_.small_features_resolved;
  }

  template <class TriangleRange>
  void write_back(TriangleRange& triangles) const
  {
    if(!collapsed_.empty()) {
      // Triangles were removed: every triangle is written, and the range shortened.
      if constexpr(has_resize<TriangleRange>::value) {
        triangles.resize(tables_.number_of_triangles());
        for(size_type t = 0; t < tables_.number_of_triangles(); ++t) {
          const Adjacency_tables::Triangle& tr = tables_.triangle(t);
          assign_triangle(*(triangles.begin() + static_cast<std::ptrdiff_t>(t)), tr[0], tr[1], tr[2]);
        }
      }
      return;
    }
    for(size_type t : touched_) {
      const Adjacency_tables::Triangle& tr = tables_.triangle(t);
      assign_triangle(*(triangles.begin() + static_cast<std::ptrdiff_t>(t)), tr[0], tr[1], tr[2]);
    }
  }

  // Input.
  const std::vector<Point>& points_;
  Adjacency_tables& tables_;
  const FT eps_;
  const std::vector<char>* fixed_;
  const Kernel kernel_;
  Visitor& visitor_;
  const bool collapse_;                                 // Small_features::COLLAPSE
  const std::vector<FT>* tolerances_;                   // per point, or null: eps_ for every pair
  Snap_report report_;
  // Candidates and the tolerance graph over them (local ids).
  Uninitialized_vector<size_type> candidates_;
  std::vector<Point> candidate_points_;
  std::unique_ptr<Candidate_tree> tree_; // over the candidates (local ids), their points read from the soup
  std::vector<Pair> same_triangle_pairs_;
  Union_find components_;                               // of the tolerance graph, until they become `root_`
  bool dense_ = false;
  bool parallel_ = false; // with the tag: the neighborhoods, the clusters and the rebuilt tables in parallel
  std::deque<Row_buffer_slot> rows_;    // the rows of neighbours, in one buffer per thread
  // (the arrays by candidate below are `Uninitialized_vector`s: the search writes every candidate's
  // entry, once each, on the thread that finds its neighbourhood)
  Uninitialized_vector<std::uint32_t> row_buffer_;      // by candidate: the buffer of its row (empty: the first)
  Uninitialized_vector<std::uint32_t> row_start_;       // by candidate: where its row begins in its buffer (4 bytes:
                                                        // a buffer holds at most `row_buffer_limit` entries)
  Uninitialized_vector<std::uint32_t> row_size_;        // by candidate: the length of its row (fewer than the candidates)
  // Clusters.
  Uninitialized_vector<std::uint32_t> visits_;          // the clusters' visits: by component, each sorted
  Uninitialized_vector<size_type> target_;              // representative of a merged vertex, or none
  Uninitialized_vector<std::uint32_t> candidate_of_;    // by vertex: its candidate, or not_candidate
  Union_find::Parents root_;                            // by candidate: the root of its component
  Uninitialized_vector<std::uint32_t> mate_of_;         // vertices sharing a triangle with the representative
  Uninitialized_vector<char> assigned_;                 // by candidate (one byte each: written by blocks in parallel)
  Uninitialized_vector<std::uint32_t> component_size_, largest_cluster_;
  struct Deferred_refusal
  {
    size_type vertex, representative;
    Refusal_reason reason;
  };
  std::vector<Deferred_refusal> deferred_refusals_;     // told at the end of `form_clusters()`
  // What a block of components gives back: its refusals, in the order met, and their counts.
  struct Cluster_block
  {
    std::vector<Deferred_refusal> refusals;
    std::size_t refused_holds_welds = 0, refused_same_triangle = 0;
  };
  // What forming one cluster after another reuses: the marks of the triangles around the current
  // cluster (a new id per cluster, so never cleared), the members and the neighbourhood found.
  struct Cluster_scratch
  {
    explicit Cluster_scratch(std::size_t triangles) : in_cluster_mark(triangles, 0) {}
    std::vector<std::uint32_t> in_cluster_mark;
    std::uint32_t cluster_id = 0;
    std::vector<std::uint32_t> members;
    std::vector<std::pair<double, std::uint32_t>> member_distances; // (squared distance in double, member)
    std::vector<std::size_t> found;
  };
  // The scratches of the blocks running at one time: at most one per thread is ever made.
  class Scratch_pool
  {
  public:
    explicit Scratch_pool(std::size_t triangles) : triangles_(triangles) {}
    std::unique_ptr<Cluster_scratch> acquire()
    {
      {
        const std::lock_guard<std::mutex> hold(mutex_);
        if(!free_.empty()) {
          std::unique_ptr<Cluster_scratch> s = std::move(free_.back());
          free_.pop_back();
          return s;
        }
      }
      return std::make_unique<Cluster_scratch>(triangles_);
    }
    void release(std::unique_ptr<Cluster_scratch>& s)
    {
      const std::lock_guard<std::mutex> hold(mutex_);
      free_.push_back(std::move(s));
    }
  private:
    std::size_t triangles_;
    std::mutex mutex_;
    std::vector<std::unique_ptr<Cluster_scratch>> free_;
  };
  // Geometric guard.
  std::vector<size_type> touched_;                      // triangles around a moved vertex
  std::vector<std::pair<size_type, Refusal_reason>> cancelled_;
  bool moves_checked_ = false, collapses_checked_ = false; // the first pass of each kind is done
  std::vector<size_type> cancelled_since_moves_check_;  // vertices cancelled since the last check of the moves
  std::vector<std::pair<size_type, size_type>> cancelled_since_collapses_check_; // (vertex, its former target)
  std::vector<std::pair<size_type, size_type>> collapsing_by_end_; // (end of the image, collapsing triangle)
  std::vector<std::pair<size_type, size_type>> merged_into_;       // (representative, vertex merged into it)
  std::vector<std::uint32_t> pass_mark_;                // triangles listed in the pass `pass_id_`
  std::uint32_t pass_id_ = 0;
  std::vector<char> is_image_end_;                      // final vertices of their images (all 0 between passes)
  // Application.
  std::vector<size_type> collapsed_;                    // triangles removed, in increasing order
};

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_SNAP_VERTICES_WORKER_H
