// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The steps of `orient_triangle_soup()`: repeated triangles, orientation of the patches, fans of
// the vertices, orientation of each patch as a whole, writing back. Every choice that the input
// order could change is made on a canonical order of the triangles instead.

#ifndef SOUP_TOPOLOGY_INTERNAL_ORIENT_SOUP_H
#define SOUP_TOPOLOGY_INTERNAL_ORIENT_SOUP_H

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/internal/boxes_inside_boxes.h>
#include <Soup_topology/internal/Point_hash_map.h>
#include <Soup_topology/internal/parallel.h>
#include <Soup_topology/internal/separate_non_manifold.h>
#include <Soup_topology/internal/soup_checks.h>
#include <Soup_topology/internal/uninitialized_vector.h>
#include <Soup_topology/internal/union_find.h>

#include <CGAL/number_utils.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

namespace Soup_topology {
namespace internal {

/// Whether `sum`, the sum in double of `count` terms in some order, has the sign of the terms'
/// exact sum, and so of their sum in double in any other order (which is then not 0 either):
/// true if it lies farther from 0 than 3 `count` u `magnitude`, `magnitude` the sum in double of
/// the terms' magnitudes, u = 2^-53. (Any order of summation errs by at most (count - 1) u /
/// (1 - (count - 1) u) times the exact sum of the magnitudes; two such errors, and the rounding of
/// `magnitude`, stay below the bound. Additions whose results are below the normal range are
/// exact; an overflow gives no certainty.)
inline bool sum_has_certain_sign(double sum, double magnitude, std::size_t count)
{
  const double bound = 3 * double(count) * (std::numeric_limits<double>::epsilon() / 2) * magnitude;
  return std::isfinite(sum) && std::isfinite(bound) && std::abs(sum) > bound;
}

/// How `Soup_orienter` turns a patch whose triangles form a closed surface.
struct Patch_orientation_rules
{
  /// a patch already consistently oriented as read keeps its orientation, closed or not.
  bool keep_consistent_input = false;
  /// closed patches: orientation by nesting depth (outermost outward, the next inward, ...)
  /// when true, outward (positive signed volume) when false.
  bool nest_closed_patches = true;
};

/// twice the signed solid angle of the triangle `c[0]`, `c[1]`, `c[2]` (its corners relative to
/// the point it is seen from): the term of a generalised winding number.
inline double twice_solid_angle(const std::array<double, 3> (&c)[3])
{
  const auto dot = [](const std::array<double, 3>& x, const std::array<double, 3>& y) {
    return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
  };
  const double la = std::sqrt(dot(c[0], c[0])), lb = std::sqrt(dot(c[1], c[1])), lc = std::sqrt(dot(c[2], c[2]));
  const double det = c[0][0] * (c[1][1] * c[2][2] - c[1][2] * c[2][1]) -
                     c[0][1] * (c[1][0] * c[2][2] - c[1][2] * c[2][0]) +
                     c[0][2] * (c[1][0] * c[2][1] - c[1][1] * c[2][0]);
  const double den = la * lb * lc + dot(c[0], c[1]) * lc + dot(c[0], c[2]) * lb + dot(c[1], c[2]) * la;
  return 2 * std::atan2(det, den);
}

/// What `Soup_orienter` tells of its decisions when asked (`orient_triangle_soup_in_parts()`
/// orients a soup one part at a time with it and puts the parts together).
struct Orientation_decisions
{
  /// a closed patch: its box and its sample as the nesting test takes them, how its orientation
  /// was chosen, and its triangles (indices after the repeated ones are left out) in the order of
  /// its traversal, the order in which the nesting test sums its winding number
  struct Closed_patch
  {
    Box_bounds box;
    std::array<double, 3> sample;
    bool by_volume = false;  ///< turned by its signed volume and nesting depth (not kept as read)
    bool turned = false;     ///< turned as a whole (after its consistent orientation)
    std::size_t flipped = 0; ///< its triangles written reversed
    std::vector<Adjacency_tables::size_type> triangles;
  };
  bool with_triangles = true;           ///< whether the closed patches are told with their triangles
  std::vector<char> dropped;            ///< for every triangle given: left out as a repeat (empty: none was)
  std::vector<std::size_t> copied_from; ///< for every point appended: the point it copies
  std::vector<Closed_patch> closed;     ///< the closed patches, in increasing order
};

/// Orients an indexed triangle soup in place (see `orient_triangle_soup()`).
///
/// A *patch* is a set of triangles connected through edges shared by exactly two triangles.
/// Edges shared by three or more triangles separate patches, and so does an edge that a
/// non-orientable patch has to give up (cut). The orientation of a patch is decided as a whole;
/// its vertices are then duplicated once per fan.
///
/// The canonical order of triangles, used wherever the input order could decide: the sorted
/// triple of the ranks of their points, points ranked by lexicographic coordinates (then by
/// index). It is computed only when a decision needs it (repeated triangles of both orientations
/// in equal numbers, a non-orientable patch, a tie between the two orientations of a patch, a
/// non-manifold vertex), so a clean mesh does not pay for the sort.
template <class PointRange, class TriangleRange, class Kernel>
class Soup_orienter
{
public:
  using size_type = Adjacency_tables::size_type;
  using Point = typename PointRange::value_type;

  struct Counts
  {
    std::size_t duplicate_triangles = 0;
    std::size_t orientation_flips = 0;
    std::size_t duplicated_points = 0;
  };

  /// orients `triangles` over `points`. `tables`, when not null, are the adjacency tables of
  /// exactly these triangles over these points (the same triangles in the same order, as a
  /// pipeline keeps them up to date): they are used instead of tables of its own, and not
  /// changed. Tables of its own are built only when none are given, or when repeated triangles
  /// have to be left out.
  Soup_orienter(PointRange& points, TriangleRange& triangles, const Patch_orientation_rules& rules, const Kernel& kernel,
                const Adjacency_tables* tables = nullptr, Orientation_decisions* decisions = nullptr)
    : points_(points), triangles_(triangles), rules_(rules), kernel_(kernel), input_points_(points.size()),
      tables_(tables), decisions_(decisions)
  {
    if(tables_ && (tables_->number_of_triangles() != triangles_.size() || tables_->number_of_vertices() != points_.size()))
      throw Invalid_input("orientation: the adjacency tables given are not those of the soup");
  }

  /// orients the soup; with the tag the tables, the repeated triangles, the patches and their
  /// orientations (`join_patches()`), the fans of the vertices, the closed patches, the volumes
  /// and the writing back run on TBB's threads, by blocks put together in block order (the
  /// traversals of the patches that a decision needs and the decisions that follow an order stay
  /// sequential): the result is the same on any number of threads.
  template <class ConcurrencyTag = CGAL::Sequential_tag>
  Counts run()
  {
    if(!tables_) build_own_tables<ConcurrencyTag>();
    if(remove_repeated_triangles<ConcurrencyTag>()) build_own_tables<ConcurrencyTag>();
    orient_patches<ConcurrencyTag>();
    separate_fans<ConcurrencyTag>();
    find_closed_patches<ConcurrencyTag>();
    traverse_where_decisions_need_it<ConcurrencyTag>();
    // The steps left read the triangles, not their neighbours: tables of its own go first (the
    // peak of the orientation is then the tables, not the tables and what comes after).
    release_own_tables();
    choose_patch_orientations<ConcurrencyTag>();
    if(decisions_ != nullptr) tell_closed_patches();
    write_back<ConcurrencyTag>();
    return counts_;
  }

private:
  static constexpr size_type unset = static_cast<size_type>(-1);

  // Triangles per block of the parallel passes over the triangles, vertices per block of those
  // over the vertices (fixed: the blocks do not depend on the number of threads).
  static constexpr std::size_t block_size = std::size_t(1) << 14;

  template <class ConcurrencyTag>
  void build_own_tables()
  {
    own_tables_ = Adjacency_tables(); // the old tables go before the new ones are built
    own_tables_ = Adjacency_tables(triangles_, points_.size(), ConcurrencyTag());
    tables_ = &own_tables_;
  }

  void release_own_tables()
  {
    if(tables_ != &own_tables_) return;
    own_tables_ = Adjacency_tables();
    tables_ = nullptr;
  }

  // Vertex i of triangle t: from the tables while they are held, else from the triangles, which
  // are the same until `write_back()`.
  size_type vertex(size_type t, int i) const
  {
    if(tables_) return tables_->vertex(t, i);
    return static_cast<size_type>(corner(triangles_[t], std::size_t(i), t));
  }

  // Vertex i of triangle t in the output: the vertex of its fan (`separate_fans()`).
  std::size_t corner_vertex(size_type t, int i) const
  {
    if(corner_vertex_.empty()) return vertex(t, i);
    return corner_vertex_[3 * std::size_t(t) + std::size_t(i)];
  }

  // --- Canonical order -------------------------------------------------------------------------

  const std::vector<size_type>& point_ranks()
  {
    if(rank_.size() != input_points_) {
      std::vector<size_type> order(input_points_);
      std::iota(order.begin(), order.end(), size_type(0));
      const auto less_xyz = kernel_.less_xyz_3_object();
      std::stable_sort(order.begin(), order.end(),
                       [&](size_type a, size_type b) { return less_xyz(points_[a], points_[b]); });
      rank_.assign(input_points_, 0);
      for(std::size_t r = 0; r < order.size(); ++r) rank_[order[r]] = static_cast<size_type>(r);
    }
    return rank_;
  }

  std::array<size_type, 3> canonical_key(size_type t)
  {
    const std::vector<size_type>& rank = point_ranks();
    std::array<size_type, 3> k = {rank[vertex(t, 0)], rank[vertex(t, 1)], rank[vertex(t, 2)]};
    std::sort(k.begin(), k.end());
    return k;
  }

  // The canonically smallest of a list of triangles.
  template <class Range>
  size_type canonical_min(const Range& list)
  {
    size_type best = unset;
    std::array<size_type, 3> best_key{};
    for(size_type t : list) {
      const std::array<size_type, 3> k = canonical_key(t);
      if(best == unset || k < best_key) { best = t; best_key = k; }
    }
    return best;
  }

  // Whether (a, b, c) is a rotation of the triple sorted by `key` (rather than of its reverse).
  template <class Key>
  static bool is_increasing_rotation(std::size_t a, std::size_t b, std::size_t c, const Key& key)
  {
    const int ascents = int(key(a) < key(b)) + int(key(b) < key(c)) + int(key(c) < key(a));
    return ascents == 2;
  }

  // --- Step 1: repeated triangles --------------------------------------------------------------

  // The three vertices of triangle t in the tables, sorted.
  std::array<size_type, 3> sorted_corners(size_type t) const
  {
    std::array<size_type, 3> k = tables_->triangle(t);
    std::sort(k.begin(), k.end());
    return k;
  }

  // The pairs (first, t) of the triangles t that have the same three vertices as an earlier
  // triangle, `first` being the first such triangle; in increasing order of t. Read from the
  // tables: triangles on the same three vertices share their three edges, so a triangle with a
  // border edge repeats none, and one with an edge that exactly two triangles share can only
  // repeat the other one (a look at its three vertices). The triangles left, whose three edges
  // are each shared by three or more triangles (among them every copy of a triangle repeated
  // three times or more), are matched by `find_repeated_by_hashing()`: linear, whatever the soup.
  // By blocks of triangles, put together in block order.
  template <class ConcurrencyTag>
  std::vector<std::pair<std::size_t, std::size_t>> find_repeated_triangles() const
  {
    const std::size_t n = tables_->number_of_triangles();
    const std::size_t blocks = number_of_blocks(n, block_size);
    std::vector<std::vector<std::pair<std::size_t, std::size_t>>> found(blocks);
    std::vector<std::vector<size_type>> crowded(blocks);
    for_each_block<ConcurrencyTag>(n, block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
      for(std::size_t t = begin; t != end; ++t) {
        const size_type tt = static_cast<size_type>(t);
        int i = 0;
        while(i < 3 && tables_->neighbor(tt, i) == Adjacency_tables::non_manifold_edge) ++i;
        if(i == 3) {
          crowded[b].push_back(tt);
          continue;
        }
        const size_type u = tables_->neighbor(tt, i);
        if(u != Adjacency_tables::border_edge && u < tt && tables_->local_index(u, tables_->vertex(tt, (i + 2) % 3)) >= 0)
          found[b].emplace_back(u, t);
      }
    });
    std::vector<std::pair<std::size_t, std::size_t>> repeats;
    concatenate_in_block_order(found, repeats);
    std::vector<size_type> candidates;
    concatenate_in_block_order(crowded, candidates);
    const std::vector<std::pair<std::size_t, std::size_t>> hashed = find_repeated_by_hashing(candidates);
    if(!hashed.empty()) {
      std::vector<std::pair<std::size_t, std::size_t>> all(repeats.size() + hashed.size());
      std::merge(repeats.begin(), repeats.end(), hashed.begin(), hashed.end(), all.begin(),
                 [](const auto& x, const auto& y) { return x.second < y.second; });
      repeats.swap(all);
    }
    return repeats;
  }

  // The pairs (first, t) among `candidates` (increasing triangles, every copy of a set of
  // vertices with the others) of the triangles t on the same three vertices as an earlier one,
  // `first` the first of them; in increasing order of t. An open-addressing hash table of the
  // first triangle of every set of vertices, the candidates read once in order.
  std::vector<std::pair<std::size_t, std::size_t>> find_repeated_by_hashing(const std::vector<size_type>& candidates) const
  {
    std::vector<std::pair<std::size_t, std::size_t>> repeats;
    const std::size_t m = candidates.size();
    if(m < 2) return repeats;
    std::size_t capacity = 16;
    while(capacity < 2 * m) capacity *= 2;
    const std::size_t mask = capacity - 1;
    // the triangles are below 2^32 - 2 (`Adjacency_tables`): 32-bit slots
    std::vector<size_type> slots(capacity, unset);
    for(size_type t : candidates) {
      const std::array<size_type, 3> k = sorted_corners(t);
      std::size_t h = static_cast<std::size_t>(
        mix_bits(std::uint64_t(k[0]) * 0x9e3779b97f4a7c15ULL ^ mix_bits(std::uint64_t(k[1]) + 0x632be59bd9b4e019ULL) ^
                 (mix_bits(std::uint64_t(k[2])) << 1)));
      for(;; h = (h + 1) & mask) {
        const std::size_t slot = h & mask;
        if(slots[slot] == unset) {
          slots[slot] = t;
          break;
        }
        if(sorted_corners(slots[slot]) == k) {
          repeats.emplace_back(slots[slot], t);
          break;
        }
      }
    }
    return repeats;
  }

  // Triangles on the same three vertices are one: the orientation kept is the one most of them
  // have (on a tie, the increasing rotation of the point ranks), from its first occurrence.
  // Returns whether a triangle was left out (the tables are then those of the soup before).
  template <class ConcurrencyTag>
  bool remove_repeated_triangles()
  {
    std::vector<std::pair<std::size_t, std::size_t>> repeats = find_repeated_triangles<ConcurrencyTag>();
    if(repeats.empty()) return false;
    // the repeats of one set of vertices together, each set's in increasing index order
    std::stable_sort(repeats.begin(), repeats.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    const std::size_t n = triangles_.size();
    std::vector<char> drop(n, 0);
    auto by_index = [](std::size_t v) { return v; };
    auto increasing = [&](std::size_t t) {
      return is_increasing_rotation(corner(triangles_[t], 0, t), corner(triangles_[t], 1, t), corner(triangles_[t], 2, t),
                                    by_index);
    };
    std::vector<std::size_t> group;
    for(std::size_t g = 0; g < repeats.size();) {
      std::size_t e = g + 1;
      while(e < repeats.size() && repeats[e].first == repeats[g].first) ++e;
      group.assign(1, repeats[g].first);
      for(std::size_t k = g; k < e; ++k) group.push_back(repeats[k].second);
      counts_.duplicate_triangles += group.size() - 1;
      std::size_t up = 0;
      for(std::size_t t : group) up += increasing(t) ? 1u : 0u;
      bool keep_increasing = 2 * up > group.size();
      if(2 * up == group.size()) {
        const std::vector<size_type>& rank = point_ranks();
        const std::size_t t = group.front();
        const bool rank_increasing =
          is_increasing_rotation(corner(triangles_[t], 0, t), corner(triangles_[t], 1, t), corner(triangles_[t], 2, t),
                                 [&](std::size_t v) { return rank[v]; });
        keep_increasing = (increasing(t) == rank_increasing);
      }
      bool kept = false;
      for(std::size_t t : group) { // in increasing index order
        if(!kept && increasing(t) == keep_increasing) kept = true;
        else drop[t] = 1;
      }
      g = e;
    }
    if(decisions_ != nullptr) decisions_->dropped = drop;
    std::size_t kept = 0;
    for(std::size_t t = 0; t < n; ++t)
      if(!drop[t]) {
        if(kept != t) triangles_[kept] = triangles_[t];
        ++kept;
      }
    triangles_.resize(kept);
    return true;
  }

  // --- Step 2: orientation of the patches ------------------------------------------------------

  // Breadth-first from `root` across the manifold edges not cut: each triangle reached is
  // reversed or not so that it runs the shared edge opposite to the triangle it is reached
  // from; an edge between two triangles already placed that run it the same way is cut. Appends
  // the triangles of the patch to `patch_order_`; returns whether an edge was cut. With
  // `canonical_edges` the three edges of a triangle are crossed in the order of the ranks of
  // their points rather than in their order in the triangle, which the input can rotate.
  bool orient_patch_from(size_type root, size_type p, bool canonical_edges)
  {
    std::size_t head = patch_order_.size();
    patch_[root] = p;
    reversed_[root] = 0;
    patch_order_.push_back(root);
    bool cut_an_edge = false;
    while(head < patch_order_.size()) {
      const size_type t = patch_order_[head++];
      std::array<int, 3> edges = {0, 1, 2};
      if(canonical_edges) {
        const std::vector<size_type>& rank = point_ranks();
        std::array<std::pair<size_type, size_type>, 3> key;
        for(int i = 0; i < 3; ++i) {
          const size_type ra = rank[tables_->vertex(t, i)], rb = rank[tables_->vertex(t, (i + 1) % 3)];
          key[std::size_t(i)] = {std::min(ra, rb), std::max(ra, rb)};
        }
        std::sort(edges.begin(), edges.end(), [&](int x, int y) { return key[std::size_t(x)] < key[std::size_t(y)]; });
      }
      for(int i : edges) {
        const std::size_t ti = 3 * std::size_t(t) + std::size_t(i);
        const size_type u = tables_->neighbor(t, i);
        if(u >= Adjacency_tables::non_manifold_edge || cut_[ti]) continue;
        const size_type a = tables_->vertex(t, i);
        const int j = tables_->edge_index(u, a, tables_->vertex(t, (i + 1) % 3));
        const bool u_reads_a_to_b = tables_->vertex(u, j) == a;
        if(patch_[u] == unset) {
          patch_[u] = p;
          reversed_[u] = (u_reads_a_to_b != (reversed_[t] != 0)) ? 1 : 0;
          patch_order_.push_back(u);
        } else {
          const bool t_runs_a_to_b = reversed_[t] == 0;
          const bool u_runs_a_to_b = u_reads_a_to_b != (reversed_[u] != 0);
          if(t_runs_a_to_b == u_runs_a_to_b) {
            cut_[ti] = 1;
            cut_[3 * std::size_t(u) + std::size_t(j)] = 1;
            cut_an_edge = true;
          }
        }
      }
    }
    return cut_an_edge;
  }

  // The patches (their triangles in `patch_order_`, patch after patch, and `patch_`), the
  // orientation of every triangle relative to the first triangle of its patch (`reversed_`),
  // and the edges cut in the non-orientable patches. On several threads with the tag the
  // patches are joined by `join_patches()`, their triangles then in increasing order in
  // `patch_order_` (a traversal's order is written there only for the patches whose decisions
  // depend on it: `write_traversal_orders()`); otherwise each patch is traversed from its first
  // triangle. Both give the same patches, numbers, orientations and cuts.
  template <class ConcurrencyTag>
  void orient_patches()
  {
    const std::size_t n = tables_->number_of_triangles();
    std::vector<size_type> non_orientable;
    // (the edges between blocks of `join_patches()` are listed as corners of 32 bits)
    if(runs_on_several_threads<ConcurrencyTag>() && n < (std::size_t(1) << 32) / 3) {
      join_patches<ConcurrencyTag>(non_orientable);
      traversed_.assign(patch_begin_.size() - 1, 0);
    } else {
      reversed_.assign(n, 0);
      patch_.assign(n, unset);
      cut_.assign(3 * n, 0);
      patch_order_.clear();
      patch_order_.reserve(n);
      patch_begin_.clear();
      for(size_type seed = 0; seed < n; ++seed) {
        if(patch_[seed] != unset) continue;
        const size_type p = static_cast<size_type>(patch_begin_.size());
        patch_begin_.push_back(patch_order_.size());
        if(orient_patch_from(seed, p, false)) non_orientable.push_back(p);
      }
      patch_begin_.push_back(n);
      traversed_.assign(patch_begin_.size() - 1, 1);
    }
    non_orientable_.assign(patch_begin_.size() - 1, 0);
    // Where a cut is needed, which edges are cut depends on the traversal: start again from the
    // canonically smallest triangle, edges in canonical order, so that the input does not decide.
    std::vector<size_type> members;
    for(size_type p : non_orientable) {
      non_orientable_[p] = 1;
      traversed_[p] = 1;
      members.assign(patch_order_.begin() + std::ptrdiff_t(patch_begin_[p]),
                     patch_order_.begin() + std::ptrdiff_t(patch_begin_[p + 1]));
      for(size_type t : members) {
        patch_[t] = unset;
        reversed_[t] = 0;
        for(int i = 0; i < 3; ++i) cut_[3 * std::size_t(t) + std::size_t(i)] = 0;
      }
      const size_type root = canonical_min(members);
      const std::size_t end = patch_order_.size();
      orient_patch_from(root, p, true);
      std::copy(patch_order_.begin() + std::ptrdiff_t(end), patch_order_.end(),
                patch_order_.begin() + std::ptrdiff_t(patch_begin_[p]));
      patch_order_.resize(end);
    }
  }

  // Whether triangle u, across the manifold edge i of t, runs that edge in the same direction
  // as t: the two must then be oriented differently (one of them reversed).
  bool runs_shared_edge_alike(size_type t, int i, size_type u) const
  {
    const size_type a = tables_->vertex(t, i);
    const int j = tables_->edge_index(u, a, tables_->vertex(t, (i + 1) % 3));
    return tables_->vertex(u, j) == a;
  }

  // The patches without traversing them: the triangles joined across their manifold edges in
  // sets that know, for every two triangles, whether they must be oriented alike
  // (`Parity_union_find`, whose root is a set's smallest triangle); by blocks of triangles on
  // TBB's threads, each block alone with the edges inside it, then one thread with the edges
  // between blocks. A triangle's orientation relative to its root is what the traversal from
  // that triangle gives, when the patch is orientable (every edge agrees with the others); a
  // patch where an edge disagrees is listed in `non_orientable` (increasing), its orientations
  // and cuts left to the canonical traversal. The patches are numbered by their smallest
  // triangles, as the traversals number them; `patch_order_` lists their triangles in increasing
  // order.
  template <class ConcurrencyTag>
  void join_patches(std::vector<size_type>& non_orientable)
  {
    const std::size_t n = tables_->number_of_triangles();
    const std::size_t blocks = number_of_blocks(n, block_size);
    std::vector<std::vector<size_type>> disagreeing(blocks);
    reversed_.resize(n);
    patch_.resize(n);
    std::vector<std::size_t> roots_before(blocks + 1, 0);
    {
      Parity_union_find sets(n);
      // (the edges between blocks as corners 3 t + i: 4 bytes each, `orient_patches()` checks 3 n < 2^32)
      std::vector<std::vector<std::uint32_t>> between(blocks);
      for_each_block<ConcurrencyTag>(n, block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
        sets.make_singletons(begin, end);
        for(std::size_t t = begin; t < end; ++t)
          for(int i = 0; i < 3; ++i) {
            const size_type u = tables_->neighbor(size_type(t), i);
            if(u >= Adjacency_tables::non_manifold_edge || u <= t) continue;
            if(u >= end) between[b].push_back(static_cast<std::uint32_t>(3 * t + std::size_t(i)));
            else if(!sets.unite_alone(size_type(t), u, runs_shared_edge_alike(size_type(t), i, u)))
              disagreeing[b].push_back(size_type(t));
          }
      });
      for(std::size_t b = 0; b < blocks; ++b) {
        for(const std::uint32_t corner : between[b]) {
          const size_type t = corner / 3, u = tables_->neighbor(t, int(corner % 3));
          if(!sets.unite_alone(t, u, runs_shared_edge_alike(t, int(corner % 3), u))) disagreeing[b].push_back(t);
        }
        std::vector<std::uint32_t>().swap(between[b]);
      }
      // Every triangle's root (in `patch_` for now) and orientation relative to it, by blocks in
      // increasing order (a parent in the block has them already); the roots of every block counted.
      for_each_block<ConcurrencyTag>(n, block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
        std::size_t roots = 0;
        for(std::size_t t = begin; t < end; ++t) {
          const auto [p, differs] = sets.parent(size_type(t));
          if(p == t) {
            patch_[t] = p;
            reversed_[t] = 0;
            ++roots;
          } else if(p >= begin) {
            patch_[t] = patch_[p];
            reversed_[t] = static_cast<char>(reversed_[p] != (differs ? 1 : 0));
          } else {
            const auto [r, parity] = sets.find(size_type(t));
            patch_[t] = r;
            reversed_[t] = parity ? 1 : 0;
          }
        }
        roots_before[b + 1] = roots;
      });
    }
    for(std::size_t b = 0; b < blocks; ++b) roots_before[b + 1] += roots_before[b];
    const std::size_t patches = roots_before[blocks];
    // The number of every patch: its root's rank among the roots, written over the root's entry
    // (a root is its own root: `patch_[t] == t`), then read by the other triangles.
    Uninitialized_vector<char> is_root(n); // every entry written below
    for_each_block<ConcurrencyTag>(n, block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
      std::size_t next = roots_before[b];
      for(std::size_t t = begin; t < end; ++t) {
        is_root[t] = patch_[t] == t;
        if(is_root[t]) patch_[t] = static_cast<size_type>(next++);
      }
    });
    for_each_block<ConcurrencyTag>(n, block_size, [&](std::size_t, std::size_t begin, std::size_t end) {
      for(std::size_t t = begin; t < end; ++t)
        if(!is_root[t]) patch_[t] = patch_[patch_[t]];
    });
    Uninitialized_vector<char>().swap(is_root);
    cut_.assign(3 * n, 0);
    // The triangles of every patch, in increasing order: the patches' sizes, their ends, then
    // the triangles placed from the last (`patch_begin_[p]` ends at the start of patch p).
    patch_begin_.assign(patches + 1, 0);
    for(std::size_t t = 0; t < n; ++t) ++patch_begin_[patch_[t]];
    for(std::size_t p = 1; p < patches; ++p) patch_begin_[p] += patch_begin_[p - 1];
    patch_begin_[patches] = n;
    patch_order_.resize(n);
    for(std::size_t t = n; t-- > 0;) patch_order_[--patch_begin_[patch_[t]]] = size_type(t);
    for(const std::vector<size_type>& list : disagreeing)
      for(size_type t : list) non_orientable.push_back(patch_[t]);
    std::sort(non_orientable.begin(), non_orientable.end());
    non_orientable.erase(std::unique(non_orientable.begin(), non_orientable.end()), non_orientable.end());
  }

  // The triangles of the patches `patches` (numbers) in the order of the traversal of
  // `orient_patch_from()` from their first triangle, written over their increasing order in
  // `patch_order_`, for those whose order is not a traversal's yet; patch by patch on TBB's
  // threads with the tag. Only orientable patches are not traversed already: no edge of theirs
  // is cut.
  template <class ConcurrencyTag>
  void write_traversal_orders(const std::vector<size_type>& patches)
  {
    std::vector<size_type> to_traverse;
    for(size_type p : patches)
      if(!traversed_[p]) to_traverse.push_back(p);
    if(to_traverse.empty()) return;
    if(reached_.empty()) reached_.assign(tables_->number_of_triangles(), 0);
    for_each_patch<ConcurrencyTag>(to_traverse, [&](std::size_t k) {
      const size_type p = to_traverse[k];
      const std::size_t begin = patch_begin_[p], size = patch_begin_[p + 1] - begin;
      std::vector<size_type> order;
      order.reserve(size);
      order.push_back(patch_order_[begin]);
      reached_[order.back()] = 1;
      for(std::size_t head = 0; head < order.size(); ++head) {
        const size_type t = order[head];
        for(int i = 0; i < 3; ++i) {
          const size_type u = tables_->neighbor(t, i);
          if(u >= Adjacency_tables::non_manifold_edge || reached_[u]) continue;
          reached_[u] = 1;
          order.push_back(u);
        }
      }
      std::copy(order.begin(), order.end(), patch_order_.begin() + std::ptrdiff_t(begin));
      traversed_[p] = 1;
    });
  }

  // --- Step 3: non-manifold vertices -----------------------------------------------------------

  // Every vertex gets one point per fan of its triangles (edges shared by three or more
  // triangles and cut edges do not join fans). The fan with the canonically smallest triangle
  // keeps the point; the others get copies appended, in the canonical order of their smallest
  // triangles, vertex after vertex in index order. Which vertices have more than one fan is found
  // by blocks of vertices (`Adjacency_tables::is_one_fan()` across the edges not cut); only those
  // are searched and separated, in order.
  template <class ConcurrencyTag>
  void separate_fans()
  {
    corner_vertex_.clear();
    std::vector<std::pair<std::size_t, std::size_t>> moved; // (3 t + i, the copy)
    const std::size_t vertices = tables_->number_of_vertices();
    std::vector<std::vector<size_type>> split_in_block(number_of_blocks(vertices, block_size));
    for_each_block<ConcurrencyTag>(vertices, block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
      tables_->for_each_vertex_of_several_fans(
        begin, end, [&](size_type t, int i) { return !cut_[3 * std::size_t(t) + std::size_t(i)]; },
        [&](size_type v) { split_in_block[b].push_back(v); });
    });
    std::vector<size_type> several_fans;
    concatenate_in_block_order(split_in_block, several_fans);
    std::vector<std::size_t> fan, stack, rank_of_fan, new_index;
    std::vector<size_type> smallest;
    for(size_type v : several_fans) {
      const std::size_t k = fans_around_vertex(*tables_, cut_, v, fan, stack);
      if(k == 1) continue;
      const Adjacency_tables::Id_range around = tables_->triangles_around_vertex(v);
      smallest.assign(k, unset);
      std::vector<std::array<size_type, 3>> smallest_key(k);
      for(std::size_t j = 0; j < around.size(); ++j) {
        const std::array<size_type, 3> key = canonical_key(around[j]);
        if(smallest[fan[j]] == unset || key < smallest_key[fan[j]]) { smallest[fan[j]] = around[j]; smallest_key[fan[j]] = key; }
      }
      rank_of_fan.resize(k);
      std::iota(rank_of_fan.begin(), rank_of_fan.end(), std::size_t(0));
      std::sort(rank_of_fan.begin(), rank_of_fan.end(),
                [&](std::size_t a, std::size_t b) { return smallest_key[a] < smallest_key[b]; });
      new_index.assign(k, v);
      for(std::size_t r = 1; r < k; ++r) {
        const Point copy = points_[v];
        new_index[rank_of_fan[r]] = points_.size();
        points_.push_back(copy);
        if(decisions_ != nullptr) decisions_->copied_from.push_back(v);
        ++counts_.duplicated_points;
      }
      for(std::size_t j = 0; j < around.size(); ++j)
        if(new_index[fan[j]] != v)
          moved.emplace_back(3 * std::size_t(around[j]) + std::size_t(tables_->local_index(around[j], v)), new_index[fan[j]]);
    }
    if(moved.empty()) return; // every corner keeps its vertex: no array (24 bytes a triangle)
    // Corners are read by `list_shared_non_manifold_corners()` and by `write_back()`: an array of
    // them all, read in constant time, once a vertex is separated.
    const std::size_t n = tables_->number_of_triangles();
    corner_vertex_.resize(3 * n);
    for_each_index<ConcurrencyTag>(n, [&](std::size_t t) {
      for(int i = 0; i < 3; ++i) corner_vertex_[3 * t + std::size_t(i)] = tables_->vertex(size_type(t), i);
    });
    for(const auto& [c, copy] : moved) corner_vertex_[c] = copy;
  }

  // Whether edge i of t is shared by another triangle once the fans are separated. Only a
  // triangle of the same patch can share it (both ends are in the same fans), and then it runs
  // the edge in the opposite direction: the fans are consistently oriented. A non-manifold edge
  // is looked up in `shared_non_manifold_corners_` (`list_shared_non_manifold_corners()`).
  bool is_shared_in_output(size_type t, int i) const
  {
    const size_type u = tables_->neighbor(t, i);
    const std::size_t ti = 3 * std::size_t(t) + std::size_t(i);
    if(u == Adjacency_tables::border_edge || cut_[ti]) return false;
    if(u != Adjacency_tables::non_manifold_edge) return true;
    return std::binary_search(shared_non_manifold_corners_.begin(), shared_non_manifold_corners_.end(), ti);
  }

  // The corners 3t + i whose edge i is non-manifold and shared in the output: another triangle w
  // on the same edge has, at the two ends, the same output vertices as t. (A corner of w other
  // than those of the edge's ends is a third vertex or a copy of it, never an output vertex of
  // the ends.) The triangles on a non-manifold edge are grouped by the edge and their two output
  // vertices in one sort, instead of each of the k triangles of an edge reading the other k - 1:
  // k log k, not k^2, on a fan of k triangles around one edge. Sorted, for `is_shared_in_output()`.
  void list_shared_non_manifold_corners()
  {
    struct Corner_on_edge
    {
      std::array<std::size_t, 4> key; // the edge's ends (smaller first), their output vertices
      std::size_t corner;
    };
    std::vector<Corner_on_edge> on_edges;
    const std::size_t n = tables_->number_of_triangles();
    for(std::size_t t = 0; t < n; ++t)
      for(int i = 0; i < 3; ++i) {
        if(tables_->neighbor(size_type(t), i) != Adjacency_tables::non_manifold_edge) continue;
        const int j = (i + 1) % 3;
        std::size_t a = tables_->vertex(size_type(t), i), b = tables_->vertex(size_type(t), j);
        std::size_t out_a = corner_vertex(size_type(t), i), out_b = corner_vertex(size_type(t), j);
        if(b < a) { std::swap(a, b); std::swap(out_a, out_b); }
        on_edges.push_back(Corner_on_edge{{{a, b, out_a, out_b}}, 3 * t + std::size_t(i)});
      }
    std::sort(on_edges.begin(), on_edges.end(),
              [](const Corner_on_edge& x, const Corner_on_edge& y) { return x.key < y.key; });
    shared_non_manifold_corners_.clear();
    for(std::size_t r = 0; r < on_edges.size();) {
      std::size_t e = r + 1;
      while(e < on_edges.size() && on_edges[e].key == on_edges[r].key) ++e;
      if(e - r >= 2)
        for(std::size_t k = r; k < e; ++k) shared_non_manifold_corners_.push_back(on_edges[k].corner);
      r = e;
    }
    std::sort(shared_non_manifold_corners_.begin(), shared_non_manifold_corners_.end());
  }

  // A patch is closed when every edge of its triangles is shared in the output. The triangles
  // with an edge that is not are found by blocks; a patch known to be open is not looked at
  // again within a block.
  template <class ConcurrencyTag>
  void find_closed_patches()
  {
    closed_.assign(patch_begin_.size() - 1, 1);
    list_shared_non_manifold_corners();
    const std::size_t n = tables_->number_of_triangles();
    std::vector<std::vector<size_type>> open_in_block(number_of_blocks(n, block_size));
    for_each_block<ConcurrencyTag>(n, block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
      size_type last_open = unset;
      for(std::size_t t = begin; t != end; ++t) {
        const size_type p = patch_[t];
        if(p == last_open) continue;
        for(int i = 0; i < 3; ++i)
          if(!is_shared_in_output(size_type(t), i)) {
            open_in_block[b].push_back(p);
            last_open = p;
            break;
          }
      }
    });
    for(const std::vector<size_type>& open : open_in_block)
      for(size_type p : open) closed_[p] = 0;
    std::vector<std::size_t>().swap(shared_non_manifold_corners_);
  }

  // Calls f(k) for every k in [0, patches.size()), in parallel with the tag: the patches are cut
  // into groups of consecutive patches of about `block_size` triangles (a group per big patch),
  // a group per task, so that many small patches make few tasks. The groups depend on the
  // patches only.
  template <class ConcurrencyTag, class F>
  void for_each_patch(const std::vector<size_type>& patches, const F& f) const
  {
    std::vector<std::size_t> group_begin(1, 0);
    std::size_t triangles = 0;
    for(std::size_t k = 0; k < patches.size(); ++k) {
      triangles += patch_begin_[patches[k] + 1] - patch_begin_[patches[k]];
      if(triangles >= block_size || k + 1 == patches.size()) {
        group_begin.push_back(k + 1);
        triangles = 0;
      }
    }
    for_each_index<ConcurrencyTag>(group_begin.size() - 1, [&](std::size_t g) {
      for(std::size_t k = group_begin[g]; k < group_begin[g + 1]; ++k) f(k);
    }, 1);
  }

  // --- Step 4: orientation of each patch as a whole ----------------------------------------------

  const std::array<double, 3>& xyz(std::size_t v) const { return xyz_[v]; }

  // Six times the signed volume of the tetrahedron (origin, a, b, d): the term of a triangle
  // (a, b, d) in the volume of its patch.
  static double volume_term(const std::array<double, 3>& a, const std::array<double, 3>& b,
                            const std::array<double, 3>& d)
  {
    return a[0] * (b[1] * d[2] - b[2] * d[1]) - a[1] * (b[0] * d[2] - b[2] * d[0]) + a[2] * (b[0] * d[1] - b[1] * d[0]);
  }

  // Six times the signed volume of the patch as oriented by step 2, summed in the order of its
  // traversal (`traversed_[p]`).
  double patch_volume(size_type p) const
  {
    double volume = 0;
    for(std::size_t k = patch_begin_[p]; k < patch_begin_[p + 1]; ++k) {
      const size_type t = patch_order_[k];
      volume +=
        volume_term(xyz(vertex(t, 0)), xyz(vertex(t, reversed_[t] ? 2 : 1)), xyz(vertex(t, reversed_[t] ? 1 : 2)));
    }
    return volume;
  }

  // The coordinates of point v in double, as `xyz_` holds them (computed here before `xyz_`
  // exists: the tables and `xyz_` are not held together).
  std::array<double, 3> point_in_double(std::size_t v) const
  {
    return {CGAL::to_double(points_[v].x()), CGAL::to_double(points_[v].y()), CGAL::to_double(points_[v].z())};
  }

  // The sign of the volume of patch p in double, summed in increasing order of its triangles, if
  // that sum decides the sign of the sum in any order (`sum_has_certain_sign()`), so of
  // `patch_volume()`: -1 (negative) or 1 (positive); 0 if it does not. By blocks of its triangles
  // on TBB's threads with the tag (with coordinates stored as double), the blocks' sums added in
  // block order.
  template <class ConcurrencyTag>
  signed char certain_volume_sign(size_type p) const
  {
    using Tag =
      std::conditional_t<std::is_same<typename Kernel::FT, double>::value, ConcurrencyTag, CGAL::Sequential_tag>;
    const std::size_t begin = patch_begin_[p], size = patch_begin_[p + 1] - begin;
    struct Sums { double sum = 0, magnitude = 0; };
    std::vector<Sums> by_block(number_of_blocks(size, block_size));
    for_each_block<Tag>(size, block_size, [&](std::size_t g, std::size_t first, std::size_t last) {
      for(std::size_t k = begin + first; k < begin + last; ++k) {
        const size_type t = patch_order_[k];
        const double term = volume_term(point_in_double(vertex(t, 0)), point_in_double(vertex(t, reversed_[t] ? 2 : 1)),
                                        point_in_double(vertex(t, reversed_[t] ? 1 : 2)));
        by_block[g].sum += term;
        by_block[g].magnitude += std::abs(term);
      }
    });
    Sums total;
    for(const Sums& g : by_block) {
      total.sum += g.sum;
      total.magnitude += g.magnitude;
    }
    if(!sum_has_certain_sign(total.sum, total.magnitude, size)) return 0;
    return total.sum < 0 ? -1 : 1;
  }

  // Before the tables go (`release_own_tables()`): the patches whose decisions follow the order
  // of a traversal, and that `join_patches()` did not traverse, are traversed
  // (`write_traversal_orders()`). Those are the closed patches when they are tested for nesting
  // (their samples and winding numbers) or told to `decisions_`, and the patches decided by
  // their volume whose sign the sum in increasing order does not decide (`certain_volume_sign()`,
  // kept in `volume_sign_` for `choose_patch_orientations()`). Large patches are summed one after
  // the other by blocks, the others one per task.
  template <class ConcurrencyTag>
  void traverse_where_decisions_need_it()
  {
    const std::size_t number_of_patches = patch_begin_.size() - 1;
    volume_sign_.assign(number_of_patches, 0);
    if(std::all_of(traversed_.begin(), traversed_.end(), [](char c) { return c != 0; })) return;
    std::vector<size_type> by_volume, closed_patches;
    for(size_type p = 0; p < number_of_patches; ++p) {
      if(!closed_[p]) continue;
      closed_patches.push_back(p);
      if(!(rules_.keep_consistent_input && is_consistent_as_read(p))) by_volume.push_back(p);
    }
    if((rules_.nest_closed_patches && closed_patches.size() > 1 && !by_volume.empty()) || decisions_ != nullptr) {
      write_traversal_orders<ConcurrencyTag>(closed_patches);
      std::vector<char>().swap(reached_);
      return;
    }
    std::vector<size_type> small, undecided;
    for(size_type p : by_volume) {
      if(traversed_[p]) continue;
      if(patch_begin_[p + 1] - patch_begin_[p] <= block_size) small.push_back(p);
      else volume_sign_[p] = certain_volume_sign<ConcurrencyTag>(p);
    }
    for_each_patch<ConcurrencyTag>(small, [&](std::size_t k) {
      volume_sign_[small[k]] = certain_volume_sign<CGAL::Sequential_tag>(small[k]);
    });
    for(size_type p : by_volume)
      if(!traversed_[p] && volume_sign_[p] == 0) undecided.push_back(p);
    write_traversal_orders<ConcurrencyTag>(undecided);
    std::vector<char>().swap(reached_); // (no traversal follows)
  }

  // The generalised winding number of the (closed) patch p around point q: the sum of the solid
  // angles of its triangles seen from q over 4 pi; close to +-1 inside, 0 outside.
  double winding_number(size_type p, const std::array<double, 3>& q) const
  {
    double sum = 0;
    for(std::size_t k = patch_begin_[p]; k < patch_begin_[p + 1]; ++k) {
      const size_type t = patch_order_[k];
      std::array<double, 3> c[3];
      for(int i = 0; i < 3; ++i) {
        const std::array<double, 3>& x = xyz(vertex(t, i));
        c[i] = {x[0] - q[0], x[1] - q[1], x[2] - q[2]};
      }
      if(reversed_[t]) std::swap(c[1], c[2]);
      sum += twice_solid_angle(c);
    }
    return sum / (4 * 3.14159265358979323846);
  }

  // The box of patch p and its sample: the centroid of its largest triangle (the first in the
  // order of its traversal), corners as given.
  void box_and_sample(size_type p, Box_bounds& box, std::array<double, 3>& sample) const
  {
    box = {HUGE_VAL, HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    double largest = -1;
    for(std::size_t k = patch_begin_[p]; k < patch_begin_[p + 1]; ++k) {
      const size_type t = patch_order_[k];
      const std::array<double, 3>& a = xyz(vertex(t, 0));
      const std::array<double, 3>& b = xyz(vertex(t, 1));
      const std::array<double, 3>& d = xyz(vertex(t, 2));
      for(const std::array<double, 3>* x : {&a, &b, &d})
        for(std::size_t i = 0; i < 3; ++i) {
          box[i] = std::min(box[i], (*x)[i]);
          box[i + 3] = std::max(box[i + 3], (*x)[i]);
        }
      const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
      const double n[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
      const double area = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
      if(area > largest) {
        largest = area;
        sample = {(a[0] + b[0] + d[0]) / 3, (a[1] + b[1] + d[1]) / 3, (a[2] + b[2] + d[2]) / 3};
      }
    }
  }

  // For every closed patch, the number of other closed patches that enclose it, tested at the
  // centroid of its largest triangle (a geometric choice: the input order does not change it).
  // The boxes and samples are computed one patch per index, on TBB's threads with the tag.
  template <class ConcurrencyTag>
  std::vector<std::size_t> nesting_depths(const std::vector<size_type>& closed_patches) const
  {
    const std::size_t m = closed_patches.size();
    std::vector<std::array<double, 6>> box(m);
    std::vector<std::array<double, 3>> sample(m);
    for_each_patch<ConcurrencyTag>(closed_patches,
                                   [&](std::size_t c) { box_and_sample(closed_patches[c], box[c], sample[c]); });
    // Only a closed patch whose box holds the other's box can enclose it: those pairs alone are
    // listed (`for_each_box_inside_another()`), not every pair (a soup can hold many thousands of
    // closed pieces) nor every pair of overlapping boxes (k closed pieces around one edge all
    // overlap: k^2 pairs, none of them nested).
    std::vector<std::size_t> depth(m, 0);
    for_each_box_inside_another(box, [&](std::size_t outer, std::size_t inner) {
      if(std::abs(winding_number(closed_patches[outer], sample[inner])) > 0.5) ++depth[inner];
    });
    return depth;
  }

  // An open patch (or one whose orientation the rules leave to the input): the orientation most
  // of its triangles have as read; on a tie, the one its canonically smallest triangle has.
  bool majority_turns(size_type p)
  {
    std::size_t reversals = 0;
    const std::size_t size = patch_begin_[p + 1] - patch_begin_[p];
    for(std::size_t k = patch_begin_[p]; k < patch_begin_[p + 1]; ++k) reversals += reversed_[patch_order_[k]] ? 1u : 0u;
    if(2 * reversals != size) return 2 * reversals > size;
    std::vector<size_type> members(patch_order_.begin() + std::ptrdiff_t(patch_begin_[p]),
                                   patch_order_.begin() + std::ptrdiff_t(patch_begin_[p + 1]));
    return reversed_[canonical_min(members)] != 0;
  }

  bool is_consistent_as_read(size_type p) const
  {
    if(non_orientable_[p]) return false;
    for(std::size_t k = patch_begin_[p]; k < patch_begin_[p + 1]; ++k)
      if(reversed_[patch_order_[k]]) return false;
    return true;
  }

  template <class ConcurrencyTag>
  void choose_patch_orientations()
  {
    const std::size_t number_of_patches = patch_begin_.size() - 1;
    turn_.assign(number_of_patches, 0);
    xyz_.resize(input_points_); // unwritten: every entry is written below, on the thread of its block
    for_each_index<ConcurrencyTag>(input_points_, [&](std::size_t v) {
      xyz_[v] = {CGAL::to_double(points_[v].x()), CGAL::to_double(points_[v].y()), CGAL::to_double(points_[v].z())};
    });
    std::vector<size_type> by_volume, closed_patches;
    for(size_type p = 0; p < number_of_patches; ++p) {
      if(!closed_[p]) turn_[p] = majority_turns(p) ? 1 : 0;
      else if(rules_.keep_consistent_input && is_consistent_as_read(p)) turn_[p] = 0;
      else by_volume.push_back(p);
      if(closed_[p]) closed_patches.push_back(p);
    }
    if(by_volume.empty()) return;
    std::vector<std::size_t> depth(number_of_patches, 0);
    if(rules_.nest_closed_patches && closed_patches.size() > 1) { // one closed patch alone is at depth 0
      // (traversed: the samples and the winding numbers follow the order of the traversals)
      const std::vector<std::size_t> d = nesting_depths<ConcurrencyTag>(closed_patches);
      for(std::size_t c = 0; c < closed_patches.size(); ++c) depth[closed_patches[c]] = d[c];
    }
    // one volume per patch, each summed in the order of its traversal by one thread, or its
    // sign known (`traverse_where_decisions_need_it()`)
    for_each_patch<ConcurrencyTag>(by_volume, [&](std::size_t k) {
      const size_type p = by_volume[k];
      const bool negative = traversed_[p] ? patch_volume(p) < 0 : volume_sign_[p] < 0;
      turn_[p] = (negative != (depth[p] % 2 == 1)) ? 1 : 0;
    });
  }

  // The closed patches and how they were turned, for `decisions_` (before `write_back()`: the
  // corners are still those given).
  // (the closed patches are traversed: `traverse_where_decisions_need_it()`)
  void tell_closed_patches()
  {
    for(size_type p = 0; p + 1 < patch_begin_.size(); ++p) {
      if(!closed_[p]) continue;
      Orientation_decisions::Closed_patch c;
      box_and_sample(p, c.box, c.sample);
      c.by_volume = !(rules_.keep_consistent_input && is_consistent_as_read(p));
      c.turned = turn_[p] != 0;
      for(std::size_t k = patch_begin_[p]; k < patch_begin_[p + 1]; ++k)
        c.flipped += ((reversed_[patch_order_[k]] != 0) != c.turned) ? 1u : 0u;
      if(decisions_->with_triangles)
        c.triangles.assign(patch_order_.begin() + std::ptrdiff_t(patch_begin_[p]),
                           patch_order_.begin() + std::ptrdiff_t(patch_begin_[p + 1]));
      decisions_->closed.push_back(std::move(c));
    }
  }

  // --- Step 5: writing back --------------------------------------------------------------------

  template <class ConcurrencyTag>
  void write_back()
  {
    const std::size_t n = triangles_.size();
    std::vector<std::size_t> flips(number_of_blocks(n, block_size), 0);
    for_each_block<ConcurrencyTag>(n, block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
      for(std::size_t t = begin; t != end; ++t) {
        const std::size_t c[3] = {corner_vertex(size_type(t), 0), corner_vertex(size_type(t), 1), corner_vertex(size_type(t), 2)};
        const bool reverse = (reversed_[t] != 0) != (turn_[patch_[t]] != 0);
        if(reverse) ++flips[b];
        if(reverse) assign_triangle(triangles_[t], c[0], c[2], c[1]);
        else assign_triangle(triangles_[t], c[0], c[1], c[2]);
      }
    });
    for(std::size_t f : flips) counts_.orientation_flips += f;
  }

  PointRange& points_;
  TriangleRange& triangles_;
  Patch_orientation_rules rules_;
  Kernel kernel_;
  std::size_t input_points_;
  Counts counts_;
  const Adjacency_tables* tables_; // the tables given, or own_tables_
  Orientation_decisions* decisions_; // where the decisions are told, if asked
  Adjacency_tables own_tables_;
  std::vector<size_type> rank_;
  std::vector<char> reversed_, cut_, non_orientable_, closed_, turn_;
  std::vector<char> traversed_; // per patch: whether `patch_order_` lists it in the order of a traversal
  std::vector<char> reached_;   // per triangle, while `write_traversal_orders()` runs (each patch marks its own)
  std::vector<signed char> volume_sign_; // per patch: the sign of its volume where a sum in any order decides it
  std::vector<size_type> patch_;
  std::vector<size_type> patch_order_;   // the triangles, patch after patch (increasing, or traversed)
  std::vector<std::size_t> patch_begin_; // patch p is patch_order_[patch_begin_[p], patch_begin_[p + 1])
  // the vertex of every corner in the output (`separate_fans()`); empty when no corner moves to a
  // copy of its vertex (a soup without non-manifold vertices), every corner then keeping its own
  std::vector<std::size_t> corner_vertex_;
  std::vector<std::size_t> shared_non_manifold_corners_; // `list_shared_non_manifold_corners()`
  Uninitialized_vector<std::array<double, 3>> xyz_; // written whole by blocks before it is read
};

// Copies what an orientation changed (`duplicate_triangles`, `orientation_flips` and
// `duplicated_points`, the members of `Soup_orienter::Counts`) from `counts` into `report`,
// whose other members are left as they are.
template <class Report, class Counts>
void copy_orientation_counts(const Counts& counts, Report& report)
{
  report.duplicate_triangles = counts.duplicate_triangles;
  report.orientation_flips = counts.orientation_flips;
  report.duplicated_points = counts.duplicated_points;
}

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_ORIENT_SOUP_H
