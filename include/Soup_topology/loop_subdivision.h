// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Loop subdivision of an indexed triangle soup on its adjacency tables, and the limit positions
// and tangents of Loop's scheme from the eigen-decomposition of the local subdivision matrix.

#ifndef SOUP_TOPOLOGY_LOOP_SUBDIVISION_H
#define SOUP_TOPOLOGY_LOOP_SUBDIVISION_H

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/index_triangles.h>
#include <Soup_topology/parameters.h>
#include <Soup_topology/internal/parallel.h>
#include <Soup_topology/internal/soup_checks.h>
#include <Soup_topology/internal/tolerance.h>
#include <Soup_topology/internal/uninitialized_vector.h>

#include <CGAL/Named_function_parameters.h>
#include <CGAL/Origin.h>
#include <CGAL/number_utils.h>
#include <CGAL/property_map.h>
#include <CGAL/tags.h>

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace Soup_topology {

/// \ingroup PkgSoupTopologySubdivision
/// \brief the weight `beta` given to each of the `k` neighbors of a smooth vertex of valence `k`
/// by Loop's vertex rule `(1 - k beta) p + beta sum(q_i)`; the value of the named parameter `loop_beta`.
enum class Loop_beta
{
  /// Loop's original choice, `beta = (5/8 - (3/8 + 1/4 cos(2 pi / k))^2) / k` (the default; the
  /// one of `CGAL::Subdivision_method_3::Loop_subdivision`).
  LOOP,
  /// Warren's simplification, `beta = 3 / (8 k)` for `k > 3` and `3/16` for `k = 3`.
  WARREN
};

namespace internal {

/// `beta` of Loop's vertex rule for a smooth vertex of valence `k`.
inline double loop_beta_value(Loop_beta choice, std::size_t k)
{
  if(k == 0) return 0.;
  const double dk = static_cast<double>(k);
  if(choice == Loop_beta::WARREN) return k == 3 ? 3. / 16. : 3. / (8. * dk);
  if(k == 6) return 1. / 16.;   // the regular case, exactly (the formula gives it up to rounding)
  const double c = 3. / 8. + 0.25 * std::cos(2. * CGAL_PI / dk);
  return (5. / 8. - c * c) / dk;
}

/// The role of a vertex in Loop's scheme.
enum class Loop_vertex_kind : std::uint8_t
{
  SMOOTH,  ///< no crease edge and a single fan of triangles: Loop's vertex rule
  CREASE,  ///< exactly two crease (border or non-manifold) edges: the rule 1/8, 3/4, 1/8
  CORNER   ///< anything else (isolated, one or more than two crease edges, a pinch): fixed
};

/// The edges of one level of subdivision: every triangle edge `3t + i` has an edge id; an edge
/// remembers the first two triangle edges ("halves") that carry it and how many do (saturated
/// at 3). An edge carried by exactly two halves is smooth, otherwise it is a crease.
struct Loop_level
{
  using Index = std::uint32_t;
  static constexpr Index none = static_cast<Index>(-1);

  // (`Uninitialized_vector`: `refine()` writes every entry of the next level's arrays on TBB's
  // threads, and nothing zeroes them before.)
  Uninitialized_vector<std::array<Index, 3>> triangles;
  Uninitialized_vector<Index> edge_of;        // 3 per triangle
  Uninitialized_vector<Index> half1, half2;   // per edge
  Uninitialized_vector<std::uint8_t> count;   // per edge, saturated at 3
  std::vector<Loop_vertex_kind> kind;
  std::size_t number_of_edges = 0;
  // The ring rows, for the smoothing on several threads only (empty otherwise): the edges of
  // vertex `v` that its rule sums, in increasing order (every edge of a smooth vertex, the two
  // crease edges of a crease vertex, none for a corner), each with its other end, are
  // `ring[ring_first[v]] .. ring[ring_first[v + 1] - 1]`. Built from the vertex rows of the
  // adjacency tables (`build_ring_rows()`), then carried from level to level by `refine()`.
  struct Ring_entry { Index edge, other; };
  Uninitialized_vector<std::size_t> ring_first;
  Uninitialized_vector<Ring_entry> ring;
  // Or, after the last refinement of a subdivision, the level this one was refined from, with its
  // ring rows and edges, and its number of vertices: the rows of this level follow from them
  // (`for_each_ring_entry()`), and are not stored (see `refine()`).
  std::shared_ptr<const Loop_level> parent;
  std::size_t parent_vertices = 0;

  bool is_crease(Index e) const { return count[e] != 2; }
  Index first_vertex(Index e) const { return triangles[half1[e] / 3][half1[e] % 3]; }
  Index second_vertex(Index e) const { return triangles[half1[e] / 3][(half1[e] + 1) % 3]; }

  void compute_halves()
  {
    half1.assign(number_of_edges, none);
    half2.assign(number_of_edges, none);
    count.assign(number_of_edges, 0);
    for(std::size_t h = 0; h < edge_of.size(); ++h) {
      const Index e = edge_of[h];
      std::uint8_t& c = count[e];
      if(c == 0) half1[e] = static_cast<Index>(h);
      else if(c == 1) half2[e] = static_cast<Index>(h);
      if(c < 3) ++c;
    }
  }

  /// level 0: the edge ids from the edge-neighbor table, the vertex kinds from the crease
  /// edges and a walk around each vertex (the walks in parallel with the tag). An edge is
  /// numbered at its first half-edge, that of the smallest triangle that carries it, in the order
  /// of the triangles; on several threads the edges are numbered by blocks of triangles (counted,
  /// then numbered from the counts' prefix sums), which gives the same numbers.
  template <class ConcurrencyTag = CGAL::Sequential_tag>
  void initialize(const Adjacency_tables& adj)
  {
    using size_type = Adjacency_tables::size_type;
    const std::size_t m = adj.number_of_triangles(), n = adj.number_of_vertices();
    decltype(ring_first)().swap(ring_first); // (no rows yet)
    decltype(ring)().swap(ring);
    parent.reset();
    parent_vertices = 0;
    triangles.assign(adj.triangles().begin(), adj.triangles().end());
    const Non_manifold_halves non_manifold = non_manifold_halves<ConcurrencyTag>(adj);
    if(runs_on_several_threads<ConcurrencyTag>()) {
      number_edges_by_blocks<ConcurrencyTag>(adj, non_manifold);
    } else {
      edge_of.assign(3 * m, none);
      number_of_edges = 0;
      for(size_type t = 0; t < m; ++t)
        for(int i = 0; i < 3; ++i) {
          const size_type owner = owner_of_edge(adj, non_manifold, t, i);
          Index& id = edge_of[3 * std::size_t(t) + std::size_t(i)];
          if(owner == t) {
            id = static_cast<Index>(number_of_edges++);
          } else {
            const int j = adj.edge_index(owner, adj.vertex(t, i), adj.vertex(t, (i + 1) % 3));
            id = edge_of[3 * std::size_t(owner) + std::size_t(j)];
          }
        }
      compute_halves();
    }

    std::vector<std::uint8_t> creases(n, 0);
    for(Index e = 0; e < number_of_edges; ++e)
      if(is_crease(e))
        for(Index v : {first_vertex(e), second_vertex(e)})
          if(creases[v] < 3) ++creases[v];
    kind.assign(n, Loop_vertex_kind::CORNER);
    for_each_index<ConcurrencyTag>(n, [&](std::size_t i) {
      const size_type v = static_cast<size_type>(i);
      if(adj.degree(v) == 0) return;
      if(creases[v] == 2) kind[v] = Loop_vertex_kind::CREASE;
      else if(creases[v] == 0 && is_single_fan(adj, v)) kind[v] = Loop_vertex_kind::SMOOTH;
    });
  }

  /// The half-edges of the non-manifold edges, each with the first two halves of its edge (those
  /// of its two smallest triangles) and the number of halves that carry it (saturated at 3),
  /// found by one sort of all of them: a search of the triangles around each such half would take
  /// time quadratic in the number of triangles on one edge (a fan of many fins).
  struct Non_manifold_halves
  {
    struct Entry { Index half, first, second; std::uint8_t count; };
    std::vector<Entry> by_half; // in increasing order of `half`

    /// the entry of half-edge `h`, a half of a non-manifold edge
    const Entry& of(std::size_t h) const
    {
      return *std::lower_bound(by_half.begin(), by_half.end(), h,
                               [](const Entry& e, std::size_t half) { return e.half < half; });
    }
  };

  template <class ConcurrencyTag>
  static Non_manifold_halves non_manifold_halves(const Adjacency_tables& adj)
  {
    using size_type = Adjacency_tables::size_type;
    const std::size_t m = adj.number_of_triangles();
    // (smaller end, larger end, half), by blocks of triangles, then sorted
    std::vector<std::vector<std::array<Index, 3>>> found(number_of_blocks(m));
    for_each_block<ConcurrencyTag>(m, default_block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
      for(std::size_t t = begin; t != end; ++t)
        for(int i = 0; i < 3; ++i)
          if(adj.neighbor(static_cast<size_type>(t), i) == Adjacency_tables::non_manifold_edge) {
            const size_type tt = static_cast<size_type>(t);
            const Index a = adj.vertex(tt, i), c = adj.vertex(tt, (i + 1) % 3);
            found[b].push_back({std::min(a, c), std::max(a, c), static_cast<Index>(3 * t + std::size_t(i))});
          }
    });
    std::vector<std::array<Index, 3>> halves;
    concatenate_in_block_order(found, halves);
    std::sort(halves.begin(), halves.end());
    Non_manifold_halves out;
    out.by_half.reserve(halves.size());
    for(std::size_t g = 0; g < halves.size();) {
      std::size_t end = g + 1;
      while(end < halves.size() && halves[end][0] == halves[g][0] && halves[end][1] == halves[g][1]) ++end;
      // (a non-manifold edge has at least three halves)
      const Index second = end - g > 1 ? halves[g + 1][2] : none;
      const auto count = static_cast<std::uint8_t>(std::min<std::size_t>(3, end - g));
      for(std::size_t k = g; k < end; ++k) out.by_half.push_back({halves[k][2], halves[g][2], second, count});
      g = end;
    }
    std::sort(out.by_half.begin(), out.by_half.end(),
              [](const typename Non_manifold_halves::Entry& x, const typename Non_manifold_halves::Entry& y) {
                return x.half < y.half;
              });
    return out;
  }

  /// the smallest triangle that carries edge `i` of triangle `t` (`t` itself or a neighbour)
  static Adjacency_tables::size_type owner_of_edge(const Adjacency_tables& adj, const Non_manifold_halves& non_manifold,
                                                   Adjacency_tables::size_type t, int i)
  {
    const Adjacency_tables::size_type u = adj.neighbor(t, i);
    if(u == Adjacency_tables::border_edge) return t;
    if(u != Adjacency_tables::non_manifold_edge) return std::min(t, u);
    return static_cast<Adjacency_tables::size_type>(non_manifold.of(3 * std::size_t(t) + std::size_t(i)).first / 3);
  }

  /// `edge_of`, `number_of_edges` and the halves of level 0 as the sequential pass of
  /// `initialize()` and `compute_halves()` give them, by blocks of triangles on TBB's threads:
  /// the edges owned by each block counted; then numbered in the block from the counts' prefix
  /// sums, each with its first half (its owner's), its second half and its count: the owner of a
  /// manifold edge also numbers the edge's half in its neighbour (of a larger index, maybe in
  /// another block). Last, the other halves of the non-manifold edges take their owner's number.
  /// Every entry is written once.
  template <class ConcurrencyTag>
  void number_edges_by_blocks(const Adjacency_tables& adj, const Non_manifold_halves& non_manifold)
  {
    using size_type = Adjacency_tables::size_type;
    const std::size_t m = adj.number_of_triangles();
    edge_of.resize(3 * m); // every entry written below
    std::vector<std::size_t> owned(number_of_blocks(m), 0);
    for_each_block<ConcurrencyTag>(m, default_block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
      std::size_t c = 0;
      for(std::size_t t = begin; t != end; ++t)
        for(int i = 0; i < 3; ++i)
          c += owner_of_edge(adj, non_manifold, static_cast<size_type>(t), i) == t ? 1u : 0u;
      owned[b] = c;
    });
    number_of_edges = exclusive_prefix_sums(owned);
    half1.resize(number_of_edges); // every entry written below
    half2.resize(number_of_edges);
    count.resize(number_of_edges);
    for_each_block<ConcurrencyTag>(m, default_block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
      std::size_t next = owned[b];
      for(std::size_t t = begin; t != end; ++t)
        for(int i = 0; i < 3; ++i) {
          const size_type tt = static_cast<size_type>(t);
          if(owner_of_edge(adj, non_manifold, tt, i) != tt) continue;
          const Index id = static_cast<Index>(next++);
          const std::size_t h = 3 * t + std::size_t(i);
          edge_of[h] = id;
          half1[id] = static_cast<Index>(h);
          const size_type u = adj.neighbor(tt, i);
          if(u == Adjacency_tables::border_edge) {
            half2[id] = none;
            count[id] = 1;
          } else if(u == Adjacency_tables::non_manifold_edge) {
            const typename Non_manifold_halves::Entry& entry = non_manifold.of(h);
            half2[id] = entry.second;
            count[id] = entry.count;
          } else {
            // the edge's half in u (tt < u, its owner is tt): written here only
            const int j = adj.edge_index(u, adj.vertex(tt, i), adj.vertex(tt, (i + 1) % 3));
            const std::size_t other = 3 * std::size_t(u) + std::size_t(j);
            edge_of[other] = id;
            half2[id] = static_cast<Index>(other);
            count[id] = 2;
          }
        }
    });
    // (after the pass above, which numbered the first half of every edge)
    for_each_index<ConcurrencyTag>(non_manifold.by_half.size(), [&](std::size_t k) {
      const typename Non_manifold_halves::Entry& entry = non_manifold.by_half[k];
      if(entry.half != entry.first) edge_of[entry.half] = edge_of[entry.first];
    });
  }

  /// `true` if the ring rows of the `n` vertices of this level are stored (see `ring_first`).
  bool stores_ring_rows(std::size_t n) const { return ring_first.size() == n + 1; }

  /// `true` if the ring rows of the `n` vertices of this level are there: stored, or following
  /// from those of the level it was refined from (see `parent`).
  bool has_ring_rows(std::size_t n) const
  {
    return stores_ring_rows(n) || (parent != nullptr && parent_vertices + parent->number_of_edges == n);
  }

  /// calls `f(edge, other)` for the entries of the ring row of vertex `v`, in order (see `ring`);
  /// the rows are there (`has_ring_rows()`).
  template <class F>
  void for_each_ring_entry(Index v, const F& f) const
  {
    if(parent == nullptr) {
      for(std::size_t j = ring_first[v]; j != ring_first[v + 1]; ++j) f(ring[j].edge, ring[j].other);
      return;
    }
    const std::size_t n = parent_vertices;
    if(v >= n) {
      parent->ring_of_edge_point(static_cast<Index>(v - n), n, f);
      return;
    }
    for(std::size_t j = parent->ring_first[v]; j != parent->ring_first[v + 1]; ++j) {
      const Ring_entry r = parent->ring[j];
      f(2 * r.edge + (v < r.other ? 0 : 1), static_cast<Index>(n + r.edge));
    }
  }

  /// the ring rows of level 0 (after `initialize()`), vertex by vertex on TBB's threads with the
  /// tag. A smooth vertex has as many edges as triangles (it has no crease edge), a crease vertex
  /// two. The edges of `v` are those of the triangles around it that are numbered in that triangle
  /// (its first half is there: the edge is not shared with a smaller triangle), met in increasing
  /// order of the triangles (rows of the tables) and of the edges in a triangle: the order in
  /// which `initialize()` numbered them. None is sorted.
  template <class ConcurrencyTag = CGAL::Sequential_tag>
  void build_ring_rows(const Adjacency_tables& adj)
  {
    using size_type = Adjacency_tables::size_type;
    const std::size_t n = kind.size();
    parent.reset();
    parent_vertices = 0;
    ring_first.resize(n + 1); // every entry written below
    ring_first[0] = 0;
    for_each_index<ConcurrencyTag>(n, [&](std::size_t v) {
      const Loop_vertex_kind k = kind[v];
      ring_first[v + 1] = k == Loop_vertex_kind::SMOOTH ? adj.degree(static_cast<size_type>(v))
                                                      : (k == Loop_vertex_kind::CREASE ? 2 : 0);
    });
    for(std::size_t v = 0; v < n; ++v) ring_first[v + 1] += ring_first[v];
    ring.resize(ring_first[n]); // every entry written below
    for_each_index<ConcurrencyTag>(n, [&](std::size_t i) {
      const size_type v = static_cast<size_type>(i);
      if(kind[v] == Loop_vertex_kind::CORNER) return;
      const bool crease = kind[v] == Loop_vertex_kind::CREASE;
      Ring_entry* out = ring.data() + ring_first[v];
      for(const size_type t : adj.triangles_around_vertex(v)) {
        const int iv = adj.local_index(t, v), ip = (iv + 2) % 3; // the edges (v, next) and (previous, v)
        for(const int j : {std::min(iv, ip), std::max(iv, ip)}) {
          const size_type u = adj.neighbor(t, j);
          const std::size_t h = 3 * std::size_t(t) + std::size_t(j);
          const bool numbered_here = u == Adjacency_tables::border_edge ||
                                     (u == Adjacency_tables::non_manifold_edge ? half1[edge_of[h]] == h : t < u);
          if(!numbered_here || (u >= Adjacency_tables::non_manifold_edge) != crease) continue;
          *out++ = {edge_of[h], j == iv ? adj.vertex(t, (iv + 1) % 3) : adj.vertex(t, ip)};
        }
      }
      CGAL_assertion(out == ring.data() + ring_first[v + 1]);
    });
  }

  /// `true` if walking across the (manifold) edges around `v` visits all its triangles.
  static bool is_single_fan(const Adjacency_tables& adj, Adjacency_tables::size_type v)
  {
    std::size_t visited = 0;
    walk_ring(adj, v, [&](Adjacency_tables::size_type) { ++visited; });
    return visited == adj.degree(v);
  }

  /// calls `f(q)` for the ring vertices `q_0, q_1, ...` of `v` in the order of the fan of its
  /// first triangle `(v, q_0, q_1)`, until the walk returns to that triangle or meets a
  /// border or non-manifold edge. Returns after at most `degree(v)` calls.
  template <class F>
  static void walk_ring(const Adjacency_tables& adj, Adjacency_tables::size_type v, F f)
  {
    using size_type = Adjacency_tables::size_type;
    const size_type t0 = adj.triangles_around_vertex(v)[0];
    size_type t = t0;
    const int iv = adj.local_index(t0, v);
    size_type q = adj.vertex(t0, (iv + 1) % 3);
    for(std::size_t step = 0; step < adj.degree(v); ++step) {
      f(q);
      // the third vertex of t, then the neighbor across (v, third)
      const int iq = adj.local_index(t, q), jv = adj.local_index(t, v);
      const size_type next = adj.vertex(t, 3 - iq - jv);
      const size_type u = adj.neighbor(t, adj.edge_index(t, v, next));
      q = next;
      if(u >= Adjacency_tables::non_manifold_edge || u == t0) return;
      t = u;
    }
  }

  /// writes the triangles of the next level (see `refine()`) into `faces` (resized).
  template <class ConcurrencyTag = CGAL::Sequential_tag, class FaceRange>
  void write_children(std::size_t n, FaceRange& faces) const
  {
    using Face = typename FaceRange::value_type;
    const std::size_t m = triangles.size();
    resize_in_huge_pages(faces, 4 * m);
    for_each_index<ConcurrencyTag>(m, [&](std::size_t t) {
      const std::array<Index, 3>& v = triangles[t];
      const std::size_t e[3] = {n + edge_of[3 * t], n + edge_of[3 * t + 1], n + edge_of[3 * t + 2]};
      faces[4 * t + 0] = make_triangle<Face>(v[0], e[0], e[2]);
      faces[4 * t + 1] = make_triangle<Face>(v[1], e[1], e[0]);
      faces[4 * t + 2] = make_triangle<Face>(v[2], e[2], e[1]);
      faces[4 * t + 3] = make_triangle<Face>(e[0], e[1], e[2]);
    });
  }

  /// the next level: triangle `t = (v0, v1, v2)` with edge points `e0, e1, e2` (edge `i` =
  /// `(v_i, v_{i+1})`) becomes `4t + k = (v_k, e_k, e_{k+2})` for `k = 0, 1, 2` and
  /// `4t + 3 = (e0, e1, e2)`; vertex `v` keeps its index, the point of edge `e` is `n + e`.
  /// The halves of edge `e` become edges `2e` (at its end vertex of smaller index) and `2e + 1`;
  /// the three inner edges of `t` are `2E + 3t + k`. The halves and counts of the new edges follow
  /// from the old ones without a search. Every triangle and every edge is done on its own (in
  /// parallel with the tag).
  ///
  /// Stored ring rows are carried on: stored again if `store_ring_rows` (`refine_ring_rows()`),
  /// otherwise kept with the old level's edges as the new level's `parent`, from which the new
  /// rows follow: less memory, and less time, for the last level of a subdivision, whose rows no
  /// refinement reads. Rows that are not stored are not carried on: the smoothing of the new level
  /// is then sequential.
  template <class ConcurrencyTag = CGAL::Sequential_tag>
  void refine(std::size_t n, bool store_ring_rows = true)
  {
    const std::size_t m = triangles.size(), E = number_of_edges, E2 = 2 * E + 3 * m;
    Uninitialized_vector<std::array<Index, 3>> children(4 * m); // 4 per triangle, written below
    Uninitialized_vector<Index> child_edges(12 * m);            // 12 per triangle, written below
    for_each_index<ConcurrencyTag>(m, [&](std::size_t t) {
      const std::array<Index, 3> v = triangles[t];
      const Index e[3] = {static_cast<Index>(n + edge_of[3 * t]), static_cast<Index>(n + edge_of[3 * t + 1]),
                          static_cast<Index>(n + edge_of[3 * t + 2])};
      for(std::size_t k = 0; k < 3; ++k) children[4 * t + k] = {v[k], e[k], e[(k + 2) % 3]};
      children[4 * t + 3] = {e[0], e[1], e[2]};
      Index* ce = child_edges.data() + 12 * t;
      const Index inner = static_cast<Index>(2 * E + 3 * t);
      for(int k = 0; k < 3; ++k) {
        const Index vk = v[std::size_t(k)], vn = v[std::size_t((k + 1) % 3)], vp = v[std::size_t((k + 2) % 3)];
        ce[3 * k + 0] = 2 * edge_of[3 * t + std::size_t(k)] + (vk < vn ? 0 : 1);
        ce[3 * k + 1] = inner + Index(k);
        ce[3 * k + 2] = 2 * edge_of[3 * t + std::size_t((k + 2) % 3)] + (vk < vp ? 0 : 1);
      }
      ce[9] = inner + 1;
      ce[10] = inner + 2;
      ce[11] = inner + 0;
    });
    // The half of child edge 2e (s = 0) or 2e + 1 (s = 1) inside the children of half h of e.
    auto child_half = [&](Index h, int s) -> Index {
      if(h == none) return none;
      const Index t = h / 3, i = h % 3;
      const Index a = triangles[t][i], b = triangles[t][(i + 1) % 3];
      const bool at_a = (a < b) == (s == 0);
      return at_a ? 3 * (4 * t + i) : 3 * (4 * t + (i + 1) % 3) + 2;
    };
    // the 2E halves of the old edges and the 3m inner edges, each written once below
    Uninitialized_vector<Index> h1(E2), h2(E2);
    Uninitialized_vector<std::uint8_t> c(E2);
    for_each_index<ConcurrencyTag>(E, [&](std::size_t i) {
      const Index e = static_cast<Index>(i);
      for(int s = 0; s < 2; ++s) {
        h1[2 * e + Index(s)] = child_half(half1[e], s);
        h2[2 * e + Index(s)] = child_half(half2[e], s);
        c[2 * e + Index(s)] = count[e];
      }
    });
    for_each_index<ConcurrencyTag>(m, [&](std::size_t i) {
      const Index t = static_cast<Index>(i);
      for(Index k = 0; k < 3; ++k) {
        const Index inner = static_cast<Index>(2 * E + 3 * t + k);
        h1[inner] = 3 * (4 * t + k) + 1;
        h2[inner] = 3 * (4 * t + 3) + (k + 2) % 3;
        c[inner] = 2;
      }
    });
    kind.resize(n + E);
    for_each_index<ConcurrencyTag>(E, [&](std::size_t e) {
      kind[n + e] = is_crease(static_cast<Index>(e)) ? Loop_vertex_kind::CREASE : Loop_vertex_kind::SMOOTH;
    });
    std::shared_ptr<Loop_level> old;
    if(stores_ring_rows(n) && store_ring_rows) {
      refine_ring_rows<ConcurrencyTag>(n);
    } else if(stores_ring_rows(n)) {
      old = std::make_shared<Loop_level>();
      old->triangles.swap(triangles);
      old->edge_of.swap(edge_of);
      old->half1.swap(half1);
      old->half2.swap(half2);
      old->count.swap(count);
      old->number_of_edges = E;
      old->ring_first.swap(ring_first);
      old->ring.swap(ring);
    } else {
      decltype(ring_first)().swap(ring_first);
      decltype(ring)().swap(ring);
    }
    parent = std::move(old);
    parent_vertices = parent != nullptr ? n : 0;
    edge_of.swap(child_edges);
    number_of_edges = E2;
    triangles.swap(children);
    half1.swap(h1);
    half2.swap(h2);
    count.swap(c);
  }

  /// the ring rows of the next level (called by `refine()` before it replaces this level). An
  /// old vertex `v` keeps its row, each edge `e` (other end `w`) replaced by its half at `v`
  /// (`2e` if `v < w`, else `2e + 1`: the same order) whose other end is the point `n + e`. The
  /// point of a crease edge `e = (a, b)` sums the crease edges `2e` and `2e + 1` (other ends
  /// `min(a, b)` and `max(a, b)`), that of a smooth edge also its four inner edges, two in each of
  /// its triangles (the smaller triangle's first), whose other ends are the triangle's other edge
  /// points. Vertex by vertex, edge by edge on TBB's threads with the tag; none is sorted.
  template <class ConcurrencyTag>
  void refine_ring_rows(std::size_t n)
  {
    const std::size_t E = number_of_edges;
    Uninitialized_vector<std::size_t> first(n + E + 1); // every entry written below
    // old vertices: the same rows at the same places; edge points: 2 or 6 edges each, placed by blocks
    for_each_index<ConcurrencyTag>(n + 1, [&](std::size_t v) { first[v] = ring_first[v]; });
    std::vector<std::size_t> in_block(number_of_blocks(E), 0);
    for_each_block<ConcurrencyTag>(E, default_block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
      std::size_t c = 0;
      for(std::size_t e = begin; e != end; ++e) c += is_crease(static_cast<Index>(e)) ? 2 : 6;
      in_block[b] = c;
    });
    const std::size_t total = ring_first[n] + exclusive_prefix_sums(in_block);
    Uninitialized_vector<Ring_entry> rows(total); // every entry written below
    for_each_index<ConcurrencyTag>(n, [&](std::size_t i) {
      const Index v = static_cast<Index>(i);
      for(std::size_t j = ring_first[v]; j != ring_first[v + 1]; ++j) {
        const Ring_entry r = ring[j];
        rows[j] = {2 * r.edge + (v < r.other ? 0 : 1), static_cast<Index>(n + r.edge)};
      }
    });
    for_each_block<ConcurrencyTag>(E, default_block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
      std::size_t at = ring_first[n] + in_block[b];
      for(std::size_t i = begin; i != end; ++i) {
        first[n + i] = at;
        ring_of_edge_point(static_cast<Index>(i), n, [&](Index edge, Index other) { rows[at++] = {edge, other}; });
      }
    });
    first[n + E] = total;
    ring_first.swap(first);
    ring.swap(rows);
  }

  /// calls `f(edge, other)` for the entries of the ring row that the point of edge `e` of this
  /// level (of `n` vertices) has in the next level (see `refine_ring_rows()`), in order: 2
  /// entries for a crease edge, 6 for a smooth one.
  template <class F>
  void ring_of_edge_point(Index e, std::size_t n, const F& f) const
  {
    const std::size_t E = number_of_edges;
    const Index a = first_vertex(e), c = second_vertex(e);
    f(2 * e, std::min(a, c));
    f(2 * e + 1, std::max(a, c));
    if(is_crease(e)) return;
    // The point of e, edge k of triangle t, is on the inner edges k (to the point of edge
    // k + 2) and k + 1 (to that of edge k + 1), numbered 2E + 3t + k and 2E + 3t + (k + 1) % 3.
    for(const Index half : {std::min(half1[e], half2[e]), std::max(half1[e], half2[e])}) {
      const Index t = half / 3, k = half % 3, inner = static_cast<Index>(2 * E + 3 * t);
      const Index to_k2 = static_cast<Index>(n + edge_of[3 * t + (k + 2) % 3]);
      const Index to_k1 = static_cast<Index>(n + edge_of[3 * t + (k + 1) % 3]);
      if(k < 2) {
        f(inner + k, to_k2);
        f(inner + k + 1, to_k1);
      } else {
        f(inner, to_k1);
        f(inner + 2, to_k2);
      }
    }
  }
};

/// Loop's two stencils on the points `in` of one level, with the kernel's constructions: both
/// ways of computing a level (sequential and parallel) build their points here, so that they agree
/// bit for bit.
template <class GT>
class Loop_stencils
{
public:
  using FT = typename GT::FT;
  using Point = typename GT::Point_3;
  using Vector = typename GT::Vector_3;
  using Index = Loop_level::Index;

  Loop_stencils(const Loop_level& level, const std::vector<Point>& in, const GT& gt)
    : level_(level), in_(in), to_vector_(gt.construct_vector_3_object()),
      add_(gt.construct_sum_of_vectors_3_object()), scale_(gt.construct_scaled_vector_3_object()),
      translate_(gt.construct_translated_point_3_object()),
      origin_(gt.construct_point_3_object()(CGAL::ORIGIN))
  {}

  /// the position vector of vertex `v` of the level
  Vector vec(Index v) const { return to_vector_(origin_, in_[v]); }
  Vector add(const Vector& a, const Vector& b) const { return add_(a, b); }

  /// the two end points of edge `e`, in the order of its first half-edge
  void ends(Index e, Index& a, Index& b) const
  {
    const Index h = level_.half1[e];
    const std::array<Index, 3>& tr = level_.triangles[h / 3];
    a = tr[h % 3];
    b = tr[(h % 3 + 1) % 3];
  }

  /// the point of edge `e`: the midpoint of a crease, `3/8 (a + b) + 1/8 (c + d)` elsewhere
  Point edge_point(Index e) const
  {
    const Index h = level_.half1[e];
    const std::array<Index, 3>& tr = level_.triangles[h / 3];
    const Index k = h % 3;
    const Vector ab = add_(vec(tr[k]), vec(tr[(k + 1) % 3]));
    if(level_.is_crease(e)) return translate_(origin_, scale_(ab, FT(0.5)));
    const Index h2 = level_.half2[e];
    const Index c = tr[(k + 2) % 3], d = level_.triangles[h2 / 3][(h2 + 2) % 3];
    return translate_(origin_, scale_(add_(scale_(ab, FT(3)), add_(vec(c), vec(d))), FT(0.125)));
  }

  /// the moved smooth vertex `v` of `valence` ring vertices summing to `ring`, weight `beta` each
  Point smooth_vertex_point(Index v, const Vector& ring, std::size_t valence, double beta) const
  {
    const FT centre(1. - double(valence) * beta);
    return translate_(origin_, add_(scale_(vec(v), centre), scale_(ring, FT(beta))));
  }

  /// the moved crease vertex `v` whose two crease neighbours sum to `ring`
  Point crease_vertex_point(Index v, const Vector& ring) const
  {
    return translate_(origin_, add_(scale_(vec(v), FT(0.75)), scale_(ring, FT(0.125))));
  }

private:
  const Loop_level& level_;
  const std::vector<Point>& in_;
  decltype(std::declval<const GT&>().construct_vector_3_object()) to_vector_;
  decltype(std::declval<const GT&>().construct_sum_of_vectors_3_object()) add_;
  decltype(std::declval<const GT&>().construct_scaled_vector_3_object()) scale_;
  decltype(std::declval<const GT&>().construct_translated_point_3_object()) translate_;
  Point origin_;
};

/// One level of Loop's rules computed in parallel: the edge points each on their own, the ring
/// sum of every vertex over the other ends of its ring row (`Loop_level::ring`), in increasing
/// edge order: the order of the sequential sums, so the floating-point results are the same bit
/// for bit.
template <class ConcurrencyTag, class GT>
void loop_smooth_in_parallel(const Loop_level& level, const std::vector<typename GT::Point_3>& in,
                             std::vector<typename GT::Point_3>& out, Loop_beta choice, const GT& gt)
{
  using Vector = typename GT::Vector_3;
  using Index = Loop_level::Index;
  const Loop_stencils<GT> stencils(level, in, gt);
  const std::size_t n = in.size(), E = level.number_of_edges;
  resize_in_huge_pages(out, n + E);
  for_each_index<ConcurrencyTag>(E, [&](std::size_t e) { out[n + e] = stencils.edge_point(static_cast<Index>(e)); });
  for_each_index<ConcurrencyTag>(n, [&](std::size_t i) {
    const Index v = static_cast<Index>(i);
    const Loop_vertex_kind kind = level.kind[v];
    if(kind == Loop_vertex_kind::CORNER) { out[v] = in[v]; return; }
    Vector sum(CGAL::NULL_VECTOR);
    std::size_t valence = 0;
    level.for_each_ring_entry(v, [&](Index, Index other) {
      sum = stencils.add(sum, stencils.vec(other));
      ++valence;
    });
    out[v] = kind == Loop_vertex_kind::SMOOTH ? stencils.smooth_vertex_point(v, sum, valence, loop_beta_value(choice, valence))
                                              : stencils.crease_vertex_point(v, sum);
  });
}

/// `true` if `loop_smooth()` runs in parallel: with the tag, on several threads, and for `double`
/// coordinates (lazily exact numbers share state between the points they were computed from).
/// The caller then builds the ring rows of the level (`Loop_level::build_ring_rows()`).
template <class ConcurrencyTag, class GT>
bool loop_smooths_in_parallel()
{
  if constexpr(runs_in_parallel<ConcurrencyTag>() && std::is_same<typename GT::FT, double>::value)
    return runs_on_several_threads<ConcurrencyTag>();
  else
    return false;
}

/// One level of Loop's rules: `out` receives the `n` moved vertices then the `E` edge points.
template <class ConcurrencyTag = CGAL::Sequential_tag, class GT>
void loop_smooth(const Loop_level& level, const std::vector<typename GT::Point_3>& in,
                 std::vector<typename GT::Point_3>& out, Loop_beta choice, const GT& gt)
{
  // In parallel when the level has its ring rows (see `loop_smooths_in_parallel()`); otherwise
  // the sequential pass below, which gives the same points bit for bit (and on one thread is the
  // faster: it needs no rows).
  if constexpr(runs_in_parallel<ConcurrencyTag>() && std::is_same<typename GT::FT, double>::value) {
    if(level.has_ring_rows(in.size())) {
      loop_smooth_in_parallel<ConcurrencyTag>(level, in, out, choice, gt);
      return;
    }
  }
  using Vector = typename GT::Vector_3;
  using Index = Loop_level::Index;
  const Loop_stencils<GT> stencils(level, in, gt);
  const std::size_t n = in.size(), E = level.number_of_edges;
  resize_in_huge_pages(out, n + E);
  // the sum of the ring of every vertex and its valence, side by side (one cache line per update;
  // updated in the order of the edges, at random across the vertices: in huge pages from 4 MiB on)
  struct Ring { Vector sum; Index valence; };
  Uninitialized_vector<Ring> ring(n, Ring{Vector(CGAL::NULL_VECTOR), 0});
  for(Index e = 0; e < E; ++e) {
    out[n + e] = stencils.edge_point(e);
    Index a, b;
    stencils.ends(e, a, b);
    const Loop_vertex_kind kind_of_edge = level.is_crease(e) ? Loop_vertex_kind::CREASE : Loop_vertex_kind::SMOOTH;
    if(level.kind[a] == kind_of_edge) { ring[a].sum = stencils.add(ring[a].sum, stencils.vec(b)); ++ring[a].valence; }
    if(level.kind[b] == kind_of_edge) { ring[b].sum = stencils.add(ring[b].sum, stencils.vec(a)); ++ring[b].valence; }
  }
  std::vector<double> betas;
  for(Index v = 0; v < n; ++v) {
    switch(level.kind[v]) {
    case Loop_vertex_kind::SMOOTH: {
      const std::size_t k = ring[v].valence;
      if(k >= betas.size()) {
        const std::size_t old = betas.size();
        betas.resize(k + 1);
        for(std::size_t j = old; j <= k; ++j) betas[j] = loop_beta_value(choice, j);
      }
      out[v] = stencils.smooth_vertex_point(v, ring[v].sum, k, betas[k]);
      break;
    }
    case Loop_vertex_kind::CREASE:
      out[v] = stencils.crease_vertex_point(v, ring[v].sum);
      break;
    default:
      out[v] = in[v];
    }
  }
}

/// The local subdivision matrix of a smooth vertex of valence `k` acting on `(p, q_0, ...,
/// q_{k-1})` (the vertex then its ring in fan order): row 0 is the vertex rule
/// `(1 - k beta, beta, ..., beta)`, row `1 + i` the edge rule of edge `(p, q_i)`:
/// `3/8 p + 3/8 q_i + 1/8 q_{i-1} + 1/8 q_{i+1}`.
inline Eigen::MatrixXd loop_subdivision_matrix(std::size_t k, double beta)
{
  const Eigen::Index K = static_cast<Eigen::Index>(k);
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(K + 1, K + 1);
  M(0, 0) = 1. - double(k) * beta;
  for(Eigen::Index i = 0; i < K; ++i) {
    M(0, 1 + i) = beta;
    M(1 + i, 0) += 3. / 8.;
    M(1 + i, 1 + i) += 3. / 8.;
    M(1 + i, 1 + (i + 1) % K) += 1. / 8.;
    M(1 + i, 1 + (i + K - 1) % K) += 1. / 8.;
  }
  return M;
}

/// The local subdivision matrix of a crease vertex acting on `(p, c_0, c_1)` (the vertex and
/// its two crease neighbors): `p' = 3/4 p + 1/8 (c_0 + c_1)`, `c_i' = (p + c_i) / 2`.
inline Eigen::MatrixXd crease_subdivision_matrix()
{
  Eigen::MatrixXd M(3, 3);
  M << 0.75, 0.125, 0.125,
       0.5, 0.5, 0.,
       0.5, 0., 0.5;
  return M;
}

/// What the eigen-analysis of a local subdivision matrix gives.
struct Loop_eigen_analysis
{
  Eigen::VectorXd eigenvalues;   ///< real parts, by decreasing modulus
  Eigen::VectorXd limit;         ///< left eigenvector of 1, entries summing to 1: the limit mask
  Eigen::VectorXd tangent1;      ///< first subdominant left eigenvector (see `analyze_subdivision_matrix()`)
  Eigen::VectorXd tangent2;      ///< second one (empty for a crease matrix)
};

/// eigen-analysis of `M` (a smooth matrix when `pair` is true, a crease matrix otherwise).
/// Checks that 1 is a simple and dominant eigenvalue, and that the subdominant eigenvalue is a
/// real pair of equal values (smooth) or simple (crease) strictly above the others in modulus;
/// throws `Invalid_input` naming the failing property otherwise.
///
/// The limit mask is the left eigenvector of eigenvalue 1 normalised to a sum of 1. For a smooth
/// matrix, the left eigenspace of the subdominant pair is two-dimensional; its canonical basis
/// is `tangent2`, the element with a zero entry on `q_0` and a positive one on `q_1`, and
/// `tangent1`, the element orthogonal to it with entry 1 on `q_0`, `tangent2` scaled to the
/// same norm. (For Loop's scheme these are `cos(2 pi i / k)` and `sin(2 pi i / k)` on `q_i`.)
/// For a crease matrix `tangent1` is the left eigenvector of 1/2 with entry 1 on `c_0`.
inline Loop_eigen_analysis analyze_subdivision_matrix(const Eigen::MatrixXd& M, bool pair, const std::string& what)
{
  const Eigen::Index N = M.rows();
  const double tol = 1e-9;
  Eigen::EigenSolver<Eigen::MatrixXd> solver(M, false);
  if(solver.info() != Eigen::Success) throw Invalid_input(what + ": the eigen-decomposition failed");
  Eigen::VectorXcd lambda = solver.eigenvalues();
  std::vector<std::complex<double>> sorted(lambda.data(), lambda.data() + N);
  std::sort(sorted.begin(), sorted.end(), [](const std::complex<double>& a, const std::complex<double>& b) {
    return std::abs(a) > std::abs(b) || (std::abs(a) == std::abs(b) && a.real() > b.real());
  });
  Loop_eigen_analysis result;
  result.eigenvalues.resize(N);
  for(Eigen::Index i = 0; i < N; ++i) result.eigenvalues(i) = sorted[std::size_t(i)].real();
  auto text = [](const std::complex<double>& z) { return std::to_string(z.real()) + (std::abs(z.imag()) > 0 ? "+" + std::to_string(z.imag()) + "i" : std::string()); };
  if(std::abs(sorted[0] - 1.) > tol)
    throw Invalid_input(what + ": the dominant eigenvalue is " + text(sorted[0]) + ", not 1 (no convergence)");
  if(N > 1 && std::abs(sorted[1]) > 1. - tol)
    throw Invalid_input(what + ": the eigenvalue 1 is not simple and dominant (next eigenvalue " + text(sorted[1]) + ")");
  const std::size_t sub = pair ? 2 : 1;
  if(std::size_t(N) < 1 + sub)
    throw Invalid_input(what + ": the matrix is too small for a subdominant eigenvalue");
  if(pair) {
    if(std::abs(sorted[1] - sorted[2]) > tol || std::abs(sorted[1].imag()) > tol || std::abs(sorted[2].imag()) > tol)
      throw Invalid_input(what + ": the subdominant eigenvalues " + text(sorted[1]) + " and " + text(sorted[2]) +
                              " are not an equal real pair");
  } else if(std::abs(sorted[1].imag()) > tol) {
    throw Invalid_input(what + ": the subdominant eigenvalue " + text(sorted[1]) + " is not real");
  }
  if(std::size_t(N) > 1 + sub && std::abs(sorted[1 + sub]) > std::abs(sorted[1]) - tol)
    throw Invalid_input(what + ": the subdominant eigenvalue " + text(sorted[1]) + " is not strictly above " +
                            text(sorted[1 + sub]) + " in modulus");

  // Left eigenvectors: the null spaces of M^T - lambda I, from the singular value decomposition.
  auto null_space = [&](double value, Eigen::Index dimension) {
    const Eigen::MatrixXd A = M.transpose() - value * Eigen::MatrixXd::Identity(N, N);
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
    const Eigen::VectorXd& s = svd.singularValues();   // decreasing
    for(Eigen::Index i = N - dimension; i < N; ++i)
      if(s(i) > tol) throw Invalid_input(what + ": no left eigenvector for eigenvalue " + std::to_string(value));
    if(N - dimension - 1 >= 0 && s(N - dimension - 1) < tol)
      throw Invalid_input(what + ": the eigenspace of " + std::to_string(value) + " is larger than expected");
    return Eigen::MatrixXd(svd.matrixV().rightCols(dimension));
  };
  result.limit = null_space(1., 1).col(0);
  result.limit /= result.limit.sum();
  if(pair) {
    const double mu = 0.5 * (sorted[1].real() + sorted[2].real());
    const Eigen::MatrixXd B = null_space(mu, 2);
    Eigen::VectorXd s = B.col(0) * B(1, 1) - B.col(1) * B(1, 0);   // zero entry on q_0
    if(s.norm() < tol) throw Invalid_input(what + ": degenerate subdominant eigenspace");
    s /= s.norm();
    const Eigen::Index j = std::abs(B.col(0).dot(s)) < std::abs(B.col(1).dot(s)) ? 0 : 1;
    Eigen::VectorXd c = B.col(j);
    c -= c.dot(s) * s;
    if(std::abs(c(1)) < tol) throw Invalid_input(what + ": degenerate subdominant eigenspace");
    c /= c(1);
    s *= c.norm();
    if(s(2) < 0) s = -s;
    result.tangent1 = c;
    result.tangent2 = s;
  } else {
    Eigen::VectorXd c = null_space(sorted[1].real(), 1).col(0);
    if(std::abs(c(1)) < tol) throw Invalid_input(what + ": degenerate subdominant eigenvector");
    result.tangent1 = c / c(1);
  }
  return result;
}

/// The per-valence cache of the eigen-analysis used by the limit functions.
class Loop_mask_cache
{
public:
  explicit Loop_mask_cache(Loop_beta choice) : choice_(choice) {}
  const Loop_eigen_analysis& smooth(std::size_t k)
  {
    if(k >= smooth_.size()) smooth_.resize(k + 1);
    if(!smooth_[k])
      smooth_[k] = std::make_unique<Loop_eigen_analysis>(analyze_subdivision_matrix(
        loop_subdivision_matrix(k, loop_beta_value(choice_, k)), true,
        "Loop subdivision matrix of valence " + std::to_string(k)));
    return *smooth_[k];
  }
  const Loop_eigen_analysis& crease()
  {
    if(!crease_)
      crease_ = std::make_unique<Loop_eigen_analysis>(
        analyze_subdivision_matrix(crease_subdivision_matrix(), false, "crease subdivision matrix"));
    return *crease_;
  }
  /// the analysis of valence `k`, computed before by `smooth(k)`.
  const Loop_eigen_analysis& computed_smooth(std::size_t k) const { return *smooth_[k]; }
private:
  Loop_beta choice_;
  std::vector<std::unique_ptr<Loop_eigen_analysis>> smooth_;
  std::unique_ptr<Loop_eigen_analysis> crease_;
};

/// The shared body of `loop_limit_points()` and `loop_limit_tangents()`: calls
/// `f(v, kind, ring, weights)` for every vertex, `ring` the indices (vertex first) the weights apply to.
/// With the tag the vertices are visited in parallel (`f` must then only write what belongs to
/// `v`): the eigen-analyses are computed first, in the order the sequential visit asks for them
/// (so that a refused matrix is reported as it is there).
template <class ConcurrencyTag = CGAL::Sequential_tag, class PointRange, class TriangleRange, class F>
void for_each_limit_stencil(const PointRange& points, const TriangleRange& triangles, Loop_beta choice, F f)
{
  using Index = Loop_level::Index;
  const std::size_t n = static_cast<std::size_t>(std::distance(std::begin(points), std::end(points)));
  const Adjacency_tables adj(triangles, n, ConcurrencyTag());
  Loop_level level;
  level.initialize<ConcurrencyTag>(adj);
  // the two crease neighbors of every crease vertex, in edge order
  std::vector<std::array<Index, 2>> crease_ring(n, {Loop_level::none, Loop_level::none});
  for(Index e = 0; e < level.number_of_edges; ++e) {
    if(!level.is_crease(e)) continue;
    const Index a = level.first_vertex(e), b = level.second_vertex(e);
    (crease_ring[a][0] == Loop_level::none ? crease_ring[a][0] : crease_ring[a][1]) = b;
    (crease_ring[b][0] == Loop_level::none ? crease_ring[b][0] : crease_ring[b][1]) = a;
  }
  Loop_mask_cache cache(choice);
  if constexpr(runs_in_parallel<ConcurrencyTag>()) {
    std::vector<std::uint32_t> valence(n, 0);
    for_each_index<ConcurrencyTag>(n, [&](std::size_t v) {
      if(level.kind[v] == Loop_vertex_kind::SMOOTH)
        Loop_level::walk_ring(adj, static_cast<Index>(v), [&](Index) { ++valence[v]; });
    });
    for(std::size_t v = 0; v < n; ++v) {
      if(level.kind[v] == Loop_vertex_kind::SMOOTH) cache.smooth(valence[v]);
      else cache.crease();
    }
    const Loop_mask_cache& analyses = cache;
    const Loop_eigen_analysis& crease = cache.crease();
    for_each_index<ConcurrencyTag>(n, [&](std::size_t i) {
      const Index v = static_cast<Index>(i);
      std::vector<Index> ring{v};
      switch(level.kind[v]) {
      case Loop_vertex_kind::SMOOTH:
        ring.reserve(std::size_t(valence[v]) + 1);
        Loop_level::walk_ring(adj, v, [&](Index q) { ring.push_back(q); });
        f(v, Loop_vertex_kind::SMOOTH, ring, analyses.computed_smooth(ring.size() - 1));
        break;
      case Loop_vertex_kind::CREASE:
        ring.push_back(crease_ring[v][0]);
        ring.push_back(crease_ring[v][1]);
        f(v, Loop_vertex_kind::CREASE, ring, crease);
        break;
      default:
        f(v, Loop_vertex_kind::CORNER, ring, crease);
      }
    }, 1024);
    return;
  }
  std::vector<Index> ring;
  for(Index v = 0; v < n; ++v) {
    ring.clear();
    ring.push_back(v);
    switch(level.kind[v]) {
    case Loop_vertex_kind::SMOOTH:
      Loop_level::walk_ring(adj, v, [&](Index q) { ring.push_back(q); });
      f(v, Loop_vertex_kind::SMOOTH, ring, cache.smooth(ring.size() - 1));
      break;
    case Loop_vertex_kind::CREASE:
      ring.push_back(crease_ring[v][0]);
      ring.push_back(crease_ring[v][1]);
      f(v, Loop_vertex_kind::CREASE, ring, cache.crease());
      break;
    default:
      f(v, Loop_vertex_kind::CORNER, ring, cache.crease());
    }
  }
}

/// the value of the named parameter `loop_beta` of `np` (`Loop_beta::LOOP` by default).
template <class NamedParameters>
Loop_beta get_loop_beta(const NamedParameters& np)
{
  return CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, internal_np::loop_beta),
                                            Loop_beta::LOOP);
}

/// The shared body of `loop_limit_points()` and `loop_limit_tangents()`: reads the points of
/// `points` through the point map of `np`, then sets the value of every vertex `v` to
/// `corner_value(p)` at a corner (`p` its point) and to `stencil(combine, analysis)` elsewhere,
/// where `combine(weights)` is the vector from the origin to the combination of the points of the
/// ring of `v` (the vertex first) with the weights `weights`.
template <class Value, class ConcurrencyTag = CGAL::Sequential_tag, class PointRange, class TriangleRange,
          class NamedParameters, class CornerValue, class Stencil>
std::vector<Value> evaluate_limit_stencils(const PointRange& points, const TriangleRange& triangles,
                                           const NamedParameters& np, CornerValue corner_value, Stencil stencil)
{
  using NP_helper = Soup_np_helper<PointRange, NamedParameters>;
  using GT = typename NP_helper::Geom_traits;
  using Point = typename GT::Point_3;
  using Vector = typename GT::Vector_3;
  using FT = typename GT::FT;

  const GT gt = NP_helper::get_geom_traits(np);
  check_finite_points(points, NP_helper::get_point_map(np));
  auto to_vector = gt.construct_vector_3_object();
  auto add = gt.construct_sum_of_vectors_3_object();
  auto scale = gt.construct_scaled_vector_3_object();
  const Point origin = gt.construct_point_3_object()(CGAL::ORIGIN);

  const std::vector<Point> input = NP_helper::read_points(points, np);
  std::vector<Value> result;
  result.reserve(input.size());
  for(const Point& p : input) result.push_back(corner_value(p));
  // Constructions in parallel only for double coordinates (lazily exact numbers share state).
  using Stencil_tag = std::conditional_t<std::is_same<FT, double>::value, ConcurrencyTag, CGAL::Sequential_tag>;
  (void)runs_in_parallel<ConcurrencyTag>();
  for_each_limit_stencil<Stencil_tag>(points, triangles, get_loop_beta(np),
    [&](std::size_t v, Loop_vertex_kind kind, const std::vector<std::uint32_t>& ring, const Loop_eigen_analysis& a) {
      if(kind == Loop_vertex_kind::CORNER) return;
      const auto combine = [&](const Eigen::VectorXd& weights) {
        Vector sum = CGAL::NULL_VECTOR;
        for(std::size_t i = 0; i < ring.size(); ++i)
          sum = add(sum, scale(to_vector(origin, input[ring[i]]), FT(weights(Eigen::Index(i)))));
        return sum;
      };
      result[v] = stencil(combine, a);
    });
  return result;
}

} // namespace internal

/// \ingroup PkgSoupTopologySubdivision
/// \brief subdivides the indexed triangle soup `(points, triangles)` in place with Loop's scheme.
///
/// Each level splits every triangle `t = (v0, v1, v2)` into four, `(v0, e0, e2)`, `(v1, e1, e0)`,
/// `(v2, e2, e1)` and `(e0, e1, e2)` at indices `4t` to `4t + 3`, where `e_i` is the new point of
/// edge `i = (v_i, v_{i+1})` (orientation is kept). The old points keep their indices (and move);
/// the edge points are appended, one per edge of the adjacency tables (an edge shared by two
/// triangles gets one point). The rules:
/// - **smooth edge** (exactly two triangles): `3/8 (a + b) + 1/8 (c + d)`, `c` and `d` the
///   opposite vertices;
/// - **crease edge** (a border edge, or a non-manifold edge of three or more triangles): the
///   midpoint `1/2 (a + b)`;
/// - **smooth vertex** (no crease edge and a single fan of triangles, valence `k`):
///   `(1 - k beta) p + beta sum(q_i)`, with `beta` chosen by `loop_beta`;
/// - **crease vertex** (exactly two crease edges, to `c_0` and `c_1`, whatever its fans:
///   a border vertex, or a vertex inside a non-manifold seam): `3/4 p + 1/8 (c_0 + c_1)`;
/// - **corner** (one or more than two crease edges, no crease edge but several fans (a pinch),
///   or isolated): fixed.
///
/// The smooth and border rules are those of `CGAL::Subdivision_method_3::Loop_subdivision` for
/// `Loop_beta::LOOP`. Only the first level builds `Adjacency_tables`: the edges of the next level
/// are derived from the current ones in constant time per triangle, and the vertex kinds are
/// inherited (an edge point is smooth on a smooth edge, a crease vertex on a crease edge).
/// Linear time and memory per level.
///
/// With `CGAL::Parallel_tag` every rule runs on TBB's threads (for coordinates stored as `double`;
/// the tables and the edge bookkeeping whatever the coordinates): the points and triangles are
/// the same, bit for bit and in the same order, on any number of threads
/// (`doc/Soup_topology/Parallel.md`). The input points are then read through `point_map` on one
/// of TBB's threads, beside the build of the tables.
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` (the default), `CGAL::Parallel_tag` (needs TBB)
///         or `CGAL::Parallel_if_available_tag`
/// \tparam PointRange a resizable random-access container (`std::vector`) whose value type is
///         default constructible; its points are read and written through `point_map`
/// \tparam TriangleRange a `std::vector`-like container of triangles (`std::array<std::size_t,3>`,
///         `std::vector<int>`, ...)
/// \param points the points of the soup; subdivided in place
/// \param triangles the triangles of the soup, indices into `points`; replaced by the subdivided triangles
/// \param np an optional sequence of named parameters among the ones listed below
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{number_of_iterations}
///     \cgalParamDescription{the number of levels of subdivision}
///     \cgalParamType{unsigned int} \cgalParamDefault{1} \cgalParamNEnd
///   \cgalParamNBegin{loop_beta}
///     \cgalParamDescription{the weight `beta` of Loop's vertex rule}
///     \cgalParamType{`Soup_topology::Loop_beta`} \cgalParamDefault{`Loop_beta::LOOP`} \cgalParamNEnd
///   \cgalParamNBegin{output_adjacency_tables}
///     \cgalParamDescription{if not null, receives the tables of the result (built from the result's
///     triangles, linear time)}
///     \cgalParamType{`Adjacency_tables*`} \cgalParamDefault{`nullptr`} \cgalParamNEnd
///   \cgalParamNBegin{point_map}
///     \cgalParamDescription{a property map through which the points of `points` are read and written}
///     \cgalParamType{a model of `ReadWritePropertyMap` from the value type of `PointRange` to `Point_3`}
///     \cgalParamDefault{`CGAL::Identity_property_map`} \cgalParamNEnd
///   \cgalParamNBegin{geom_traits}
///     \cgalParamDescription{the constructions of the rules (vectors, their sums and multiples)}
///     \cgalParamType{a CGAL Kernel} \cgalParamDefault{the kernel of the point type} \cgalParamNEnd
/// \cgalNamedParamsEnd
/// \throws Invalid_input for a face that is not a triangle, a repeated or out-of-range index or a
///         non-finite coordinate; `points` and `triangles` are unchanged then.
/// \sa `loop_limit_points()`, `loop_limit_tangents()`
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename PointRange, typename TriangleRange,
          class NamedParameters = CGAL::parameters::Default_named_parameters>
void loop_subdivision(PointRange& points, TriangleRange& triangles,
                      const NamedParameters& np = CGAL::parameters::default_values())
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  using NP_helper = internal::Soup_np_helper<PointRange, NamedParameters>;
  using GT = typename NP_helper::Geom_traits;
  using Point = typename GT::Point_3;
  using Point_map = typename NP_helper::Writable_point_map;

  const Point_map point_map = NP_helper::get_writable_point_map(np);
  const GT gt = NP_helper::get_geom_traits(np);
  const unsigned int iterations =
    static_cast<unsigned int>(choose_parameter(get_parameter(np, CGAL::internal_np::number_of_iterations), 1u));
  const Loop_beta choice = internal::get_loop_beta(np);
  Adjacency_tables* tables = choose_parameter(get_parameter(np, internal_np::output_adjacency_tables),
                                              static_cast<Adjacency_tables*>(nullptr));

  const std::size_t n = static_cast<std::size_t>(std::distance(std::begin(points), std::end(points)));
  internal::check_finite_points(points, point_map);
  // the tables (which validate the triangles) and the copy of the points, side by side with the tag
  Adjacency_tables adj;
  std::vector<Point> current;
  internal::run_side_by_side<ConcurrencyTag>(
    [&] {
      internal::reserve_in_huge_pages(current, n);
      for(const auto& p : points) current.push_back(get(point_map, p));
    },
    [&] { adj = Adjacency_tables(triangles, n, ConcurrencyTag()); });
  if(iterations > 0) {
    internal::Loop_level level;
    level.initialize<ConcurrencyTag>(adj);
    if(internal::loop_smooths_in_parallel<ConcurrencyTag, GT>()) level.build_ring_rows<ConcurrencyTag>(adj);
    std::vector<Point> next;
    for(unsigned int it = 0; it < iterations; ++it) {
      const std::uint64_t size = std::uint64_t(current.size()) + level.number_of_edges;
      if(size >= std::uint64_t(Adjacency_tables::non_manifold_edge) ||
         4 * std::uint64_t(level.triangles.size()) >= std::uint64_t(Adjacency_tables::non_manifold_edge))
        throw Invalid_input("loop_subdivision: level " + std::to_string(it + 1) + " would exceed 32-bit indices");
      if(it + 1 < iterations) {
        internal::loop_smooth<ConcurrencyTag>(level, current, next, choice, gt);
        // (the rows of the last level follow from those of the level before: not stored)
        level.refine<ConcurrencyTag>(current.size(), it + 2 < iterations);
      } else {
        // The caller's triangles are grown (their `resize()` zeroes them) beside the last smoothing,
        // which does not read them; if either fails, they are shrunk back to what they were.
        const std::size_t held = static_cast<std::size_t>(std::distance(std::begin(triangles), std::end(triangles)));
        try {
          internal::run_side_by_side<ConcurrencyTag>(
            [&] { internal::resize_in_huge_pages(triangles, 4 * level.triangles.size()); },
            [&] { internal::loop_smooth<ConcurrencyTag>(level, current, next, choice, gt); });
        } catch(...) {
          triangles.resize(held);
          throw;
        }
        level.write_children<ConcurrencyTag>(current.size(), triangles);
      }
      current.swap(next);
    }
    // Nothing above but the growth of the caller's triangles and `write_children()` modified the
    // caller's containers.
    if constexpr(std::is_same<PointRange, std::vector<Point>>::value &&
                 std::is_same<Point_map, CGAL::Identity_property_map<Point>>::value) {
      points.swap(current);
      if(tables != nullptr) *tables = Adjacency_tables(triangles, points.size(), ConcurrencyTag());
      return;
    } else {
      points.resize(current.size());
      std::size_t i = 0;
      for(auto& p : points) put(point_map, p, current[i++]);
    }
  }
  if(tables != nullptr) *tables = Adjacency_tables(triangles, current.size(), ConcurrencyTag());
}

/// \ingroup PkgSoupTopologySubdivision
/// \brief returns the limit position under Loop's scheme of every point of `points`, in input order.
///
/// The limit mask of each vertex is the left eigenvector of eigenvalue 1 of its local subdivision
/// matrix, computed with Eigen once per valence and normalised to a sum of 1:
/// - smooth vertex of valence `k`: the `(k + 1) x (k + 1)` matrix of `internal::loop_subdivision_matrix()`,
///   whose mask is `(1 - k chi) p + chi sum(q_i)`, `chi = 1 / (3 / (8 beta) + k)`;
/// - crease vertex (see `loop_subdivision()`): the 3 x 3 matrix of the crease curve (a cubic
///   B-spline), mask `2/3 p + 1/6 (c_0 + c_1)`;
/// - corner: the point itself.
///
/// Bad input and the vertex kinds are those of `loop_subdivision()`. With `CGAL::Parallel_tag`
/// the vertices are done on TBB's threads, with the same result on any number of threads.
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` (the default), `CGAL::Parallel_tag` (needs TBB)
///         or `CGAL::Parallel_if_available_tag`
/// \tparam PointRange a random-access container whose points are read through `point_map`
/// \tparam TriangleRange a `std::vector`-like container of triangles
/// \param points the points of the soup
/// \param triangles the triangles of the soup, indices into `points`
/// \param np an optional sequence of named parameters among the ones listed below
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{loop_beta}
///     \cgalParamDescription{the weight `beta` of Loop's vertex rule, which the limit masks depend on}
///     \cgalParamType{`Soup_topology::Loop_beta`} \cgalParamDefault{`Loop_beta::LOOP`} \cgalParamNEnd
///   \cgalParamNBegin{point_map}
///     \cgalParamDescription{a property map through which the points of `points` are read}
///     \cgalParamType{a model of `ReadablePropertyMap` from the value type of `PointRange` to `Point_3`}
///     \cgalParamDefault{`CGAL::Identity_property_map`} \cgalParamNEnd
///   \cgalParamNBegin{geom_traits}
///     \cgalParamDescription{the constructions of the masks (vectors, their sums and multiples)}
///     \cgalParamType{a CGAL Kernel} \cgalParamDefault{the kernel of the point type} \cgalParamNEnd
/// \cgalNamedParamsEnd
/// \throws Invalid_input as `loop_subdivision()`, and if a local matrix has not 1 as a simple
///         dominant eigenvalue followed by an equal real subdominant pair (it never happens for
///         `Loop_beta::LOOP` and `Loop_beta::WARREN`).
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename PointRange, typename TriangleRange,
          class NamedParameters = CGAL::parameters::Default_named_parameters>
std::vector<typename internal::Soup_np_helper<PointRange, NamedParameters>::Geom_traits::Point_3>
loop_limit_points(const PointRange& points, const TriangleRange& triangles,
                  const NamedParameters& np = CGAL::parameters::default_values())
{
  using GT = typename internal::Soup_np_helper<PointRange, NamedParameters>::Geom_traits;
  using Point = typename GT::Point_3;
  const GT gt = internal::Soup_np_helper<PointRange, NamedParameters>::get_geom_traits(np);
  const Point origin = gt.construct_point_3_object()(CGAL::ORIGIN);
  auto translate = gt.construct_translated_point_3_object();
  return internal::evaluate_limit_stencils<Point, ConcurrencyTag>(
    points, triangles, np, [](const Point& p) { return p; },
    [&](const auto& combine, const internal::Loop_eigen_analysis& a) { return translate(origin, combine(a.limit)); });
}

/// \ingroup PkgSoupTopologySubdivision
/// \brief returns two tangent vectors of the Loop limit surface at every point of `points`, in input order.
///
/// At a smooth vertex of valence `k` they are the subdominant left eigenvectors of its local
/// subdivision matrix applied to its ring `(p, q_0, ..., q_{k-1})` (in the fan order of its
/// first triangle, so `t_1 x t_2` points to the side its orientation sees as outside). The
/// eigenspace is two-dimensional; its canonical basis is described in
/// `internal::analyze_subdivision_matrix()` and equals `t_1 = sum cos(2 pi i / k) q_i`,
/// `t_2 = sum sin(2 pi i / k) q_i`. At a crease vertex, `t_1` is the tangent of the crease
/// curve from the subdominant eigenvector (1/2) of the crease matrix, `c_0 - c_1`, and `t_2` is
/// the null vector: Loop's boundary rules give no subdominant pair there in general. At a corner
/// both are null vectors.
///
/// \tparam ConcurrencyTag as for `loop_limit_points()`
/// \tparam PointRange a random-access container whose points are read through `point_map`
/// \tparam TriangleRange a `std::vector`-like container of triangles
/// \param points the points of the soup
/// \param triangles the triangles of the soup, indices into `points`
/// \param np an optional sequence of named parameters: those of `loop_limit_points()`
/// \throws Invalid_input as `loop_limit_points()`.
template <typename ConcurrencyTag = CGAL::Sequential_tag, typename PointRange, typename TriangleRange,
          class NamedParameters = CGAL::parameters::Default_named_parameters>
std::vector<std::array<typename internal::Soup_np_helper<PointRange, NamedParameters>::Geom_traits::Vector_3, 2>>
loop_limit_tangents(const PointRange& points, const TriangleRange& triangles,
                    const NamedParameters& np = CGAL::parameters::default_values())
{
  using GT = typename internal::Soup_np_helper<PointRange, NamedParameters>::Geom_traits;
  using Vector = typename GT::Vector_3;
  using Tangents = std::array<Vector, 2>;
  return internal::evaluate_limit_stencils<Tangents, ConcurrencyTag>(
    points, triangles, np,
    [](const typename GT::Point_3&) { return Tangents{Vector(CGAL::NULL_VECTOR), Vector(CGAL::NULL_VECTOR)}; },
    [](const auto& combine, const internal::Loop_eigen_analysis& a) {
      return Tangents{combine(a.tangent1),
                      a.tangent2.size() > 0 ? combine(a.tangent2) : Vector(CGAL::NULL_VECTOR)};
    });
}

} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_LOOP_SUBDIVISION_H
