// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The vertex-neighbour and edge-neighbour tables of an indexed triangle soup (pipeline step 1).

#ifndef SOUP_TOPOLOGY_ADJACENCY_TABLES_H
#define SOUP_TOPOLOGY_ADJACENCY_TABLES_H

#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/internal/parallel.h>
#include <Soup_topology/internal/soup_checks.h>
#include <Soup_topology/internal/uninitialized_vector.h>
#include <Soup_topology/internal/union_find.h>

#include <CGAL/assertions.h>
#include <CGAL/tags.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <memory>
#include <numeric>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace Soup_topology {

namespace internal {

/// Whether a reader of triangles around vertex after vertex should ask for the rows of the
/// triangles ahead (prefetch). On a soup listed in a spatial order the rows are in cache already
/// and asking costs time for nothing; in random order every row is a miss that asking in advance
/// hides. The reader asks during the first 64 vertices of every 1024 and counts the triangles
/// numbered far (more than 16) from the previous one asked for; it goes on asking for the rest of
/// those 1024 only if more than an eighth of them were far. A hint: no result depends on it.
class Read_ahead_switch
{
public:
  bool on() const { return on_; }
  /// whether `t` is far from the triangle passed before it; every call is counted, and the counts
  /// of the first `probe` vertices of a window decide (`next_vertex()`)
  bool far(std::uint32_t t)
  {
    const bool is_far = t - last_ + 16 > 32; // |t - last| > 16, in unsigned arithmetic
    last_ = t;
    ++checked_;
    far_ += is_far ? 1 : 0;
    return is_far;
  }
  /// after each vertex
  void next_vertex()
  {
    ++step_;
    if(step_ == probe) on_ = 8 * far_ > checked_;
    else if(step_ == window) {
      step_ = 0;
      far_ = checked_ = 0;
      on_ = true;
    }
  }

private:
  static constexpr std::size_t probe = 64, window = 1024;
  std::size_t step_ = 0, far_ = 0, checked_ = 0;
  std::uint32_t last_ = 0;
  bool on_ = true;
};

} // namespace internal

/// \ingroup PkgSoupTopologyRef
/// \brief the topology of an indexed triangle soup: for every vertex the triangles around it, and
/// for every triangle its three edge neighbours.
///
/// **Edge numbering.** Edge `i` of a triangle `(v0, v1, v2)` is `(v_i, v_{(i+1) mod 3})`: edge 0 is
/// `(v0, v1)`, edge 1 is `(v1, v2)`, edge 2 is `(v2, v0)`. This is the numbering of the patent's
/// tables and the only one used in the package.
///
/// **Edge neighbours.** Two triangles are neighbours across an edge when both contain its two end
/// vertices, whatever the direction they traverse it in. `neighbor(t, i)` is
/// - the other triangle when exactly two triangles contain the edge;
/// - `border_edge` when `t` is the only one (an unconnected edge: the patent's `-1`);
/// - `non_manifold_edge` when three or more triangles contain it. Such edges are never silently
///   paired; `triangles_around_edge()` lists their triangles.
///
/// **Vertex neighbours.** `triangles_around_vertex(v)` lists the triangles that contain `v` in
/// increasing order (stored as compressed rows with room to grow, so local updates are cheap).
///
/// **Construction** is linear in the size of the soup, whatever the soup: one pass fills the
/// vertex table, then the edges of each vertex `a` are grouped by their other end `b > a` (a few
/// sorted in place, many bucketed; on several threads, many sorted: `O(k log k)` for the `k` edges
/// of a vertex), so every edge is met with all its triangles at once (a triangle repeated many
/// times, or many triangles on one edge, cost no more than as many separate triangles). The
/// global queries (`non_manifold_edges()`, `non_manifold_vertices()`,
/// `number_of_connected_components()`, ...) are linear too.
///
/// **Local updates.** `replace_vertex()` (welding, the patent's rules (a)-(c)) and
/// `split_triangle()` (T-junction repair, rule tables (15) and (17)) change the tables locally:
/// only the edges whose set of triangles changes are resolved again, each once, by scanning the
/// shorter of the triangle lists of its two end vertices. A vertex of high degree is therefore
/// not scanned by an update unless both ends of a changed edge have high degree.
///
/// Indices are stored on 32 bits; a soup must have fewer than 2^32 - 2 points and triangles.
class Adjacency_tables
{
public:
  /// the type of vertex and triangle indices.
  using size_type = std::uint32_t;
  /// the three vertex indices of a triangle.
  using Triangle = std::array<size_type, 3>;
  /// the container of `triangles()`: a `std::vector` of `Triangle` whose allocator leaves the
  /// elements that `resize()` adds unwritten (the parallel construction writes every triangle on
  /// the thread of its block, and nothing zeroes them before). Compare it with a
  /// `std::vector<Triangle>` element by element (`std::equal`), or copy it into one by its
  /// iterators.
  using Triangle_vector = internal::Uninitialized_vector<Triangle>;
  /// the value of `neighbor(t, i)` for an edge that belongs to `t` alone.
  static constexpr size_type border_edge = static_cast<size_type>(-1);
  /// the value of `neighbor(t, i)` for an edge shared by three or more triangles.
  static constexpr size_type non_manifold_edge = static_cast<size_type>(-2);

  /// an edge of a triangle: `triangle` and local index `index` in {0,1,2}.
  struct Edge
  {
    size_type triangle;
    int index;
    friend bool operator==(const Edge& a, const Edge& b)
    { return a.triangle == b.triangle && a.index == b.index; }
    friend bool operator<(const Edge& a, const Edge& b)
    { return a.triangle < b.triangle || (a.triangle == b.triangle && a.index < b.index); }
  };

  /// a read-only view on a list of triangle indices.
  class Id_range
  {
  public:
    Id_range(const size_type* b, const size_type* e) : b_(b), e_(e) {}
    const size_type* begin() const { return b_; }
    const size_type* end() const { return e_; }
    std::size_t size() const { return static_cast<std::size_t>(e_ - b_); }
    bool empty() const { return b_ == e_; }
    size_type operator[](std::size_t k) const { return b_[k]; }
  private:
    const size_type* b_;
    const size_type* e_;
  };

  /// an empty soup.
  Adjacency_tables() = default;

  /// builds the tables of `faces` over `number_of_points` points.
  /// \tparam FaceRange a range of faces, each a random-access range of 3 vertex indices
  ///         (`std::array<std::size_t,3>`, `std::vector<int>`, ...).
  /// \param faces the triangles of the soup
  /// \param number_of_points the number of points of the soup; the indices of `faces` are below it
  /// \throws Invalid_input if a face is not a triangle, repeats an index or has an index out of
  ///         range; the message names the face.
  template <class FaceRange>
  Adjacency_tables(const FaceRange& faces, std::size_t number_of_points)
    : Adjacency_tables(faces, number_of_points, CGAL::Sequential_tag())
  {}

  /// builds the tables of `faces` over `number_of_points` points, on TBB's threads when
  /// `ConcurrencyTag` asks for it (`doc/Soup_topology/Parallel.md`). The tables are the same,
  /// entry for entry, as those of the sequential constructor, on any number of threads. When TBB
  /// allows one thread only, the sequential construction runs (it does less work).
  /// \tparam FaceRange a range of faces, each a random-access range of 3 vertex indices.
  /// \tparam ConcurrencyTag `CGAL::Sequential_tag`, `CGAL::Parallel_tag` (needs TBB) or
  ///         `CGAL::Parallel_if_available_tag`
  /// \param faces the triangles of the soup
  /// \param number_of_points the number of points of the soup; the indices of `faces` are below it
  /// \param tag selects the sequential or the parallel construction (its value is not used)
  /// \throws Invalid_input if a face is not a triangle, repeats an index or has an index out of
  ///         range; the message names the face.
  template <class FaceRange, class ConcurrencyTag>
  Adjacency_tables(const FaceRange& faces, std::size_t number_of_points, ConcurrencyTag tag)
  {
    (void)tag;
    const std::size_t m = static_cast<std::size_t>(std::distance(std::begin(faces), std::end(faces)));
    using Face_iterator = decltype(std::begin(faces));
    constexpr bool random_access = std::is_base_of<std::random_access_iterator_tag,
      typename std::iterator_traits<Face_iterator>::iterator_category>::value;
    if constexpr(internal::runs_in_parallel<ConcurrencyTag>() && random_access) {
      // Checked and copied in one pass by blocks; a block that meets a face that is not a
      // triangle of distinct indices in range says so, and `check_triangle_soup()` then throws
      // the message of the first such face, as it does before any copy otherwise.
      bool checked = false;
      if(internal::fits_in_32_bit_indices(number_of_points, m)) {
        triangles_.resize(m); // unwritten: every triangle is written below, on the thread of its block
        internal::fault_in_pages(triangles_);
        std::vector<unsigned char> bad_in_block(internal::number_of_blocks(m), 0);
        internal::for_each_block<ConcurrencyTag>(m, internal::default_block_size,
                                                 [&](std::size_t b, std::size_t begin, std::size_t end) {
          std::array<std::size_t, 3> v;
          for(std::size_t t = begin; t != end; ++t) {
            if(!internal::is_triangle_of_distinct_indices(*(std::begin(faces) + static_cast<std::ptrdiff_t>(t)),
                                                          number_of_points, v)) {
              bad_in_block[b] = 1;
              return;
            }
            triangles_[t] = {static_cast<size_type>(v[0]), static_cast<size_type>(v[1]), static_cast<size_type>(v[2])};
          }
        });
        checked = std::find(bad_in_block.begin(), bad_in_block.end(), 1) == bad_in_block.end();
      }
      if(!checked) {
        internal::check_triangle_soup<ConcurrencyTag>(faces, number_of_points); // throws
        CGAL_error_msg("check_triangle_soup() accepted a face that is_triangle_of_distinct_indices() refused");
      }
    } else {
      internal::check_triangle_soup<ConcurrencyTag>(faces, number_of_points);
      triangles_.reserve(m);
      std::size_t face_id = 0;
      for(const auto& f : faces) {
        triangles_.push_back({static_cast<size_type>(internal::corner(f, 0, face_id)),
                              static_cast<size_type>(internal::corner(f, 1, face_id)),
                              static_cast<size_type>(internal::corner(f, 2, face_id))});
        ++face_id;
      }
    }
    // (on one thread, the sequential build: the same tables in fewer passes over memory)
    if(internal::runs_on_several_threads<ConcurrencyTag>())
      build_in_parallel<ConcurrencyTag>(number_of_points);
    else
      build(number_of_points);
  }

  /// \name Sizes and triangles
  /// @{
  std::size_t number_of_vertices() const { return vertex_begin_.size(); }
  std::size_t number_of_triangles() const { return triangles_.size(); }
  /// the vertex indices of triangle `t`.
  /// \param t a triangle index, in `[0, number_of_triangles())`
  const Triangle& triangle(size_type t) const { return triangles_[t]; }
  /// all triangles, in index order (they change with `replace_vertex()` and `split_triangle()`).
  const Triangle_vector& triangles() const { return triangles_; }
  /// vertex `i` (0, 1 or 2) of triangle `t`.
  /// \param t a triangle index, in `[0, number_of_triangles())`
  /// \param i the local index of the vertex, 0, 1 or 2
  size_type vertex(size_type t, int i) const { return triangles_[t][static_cast<std::size_t>(i)]; }
  /// @}

  /// \name The vertex-neighbour table
  /// @{
  /// the triangles that contain `v`, in increasing order.
  /// \param v a vertex index, in `[0, number_of_vertices())`
  Id_range triangles_around_vertex(size_type v) const
  {
    const size_type* b = ids_.data() + vertex_begin_[v];
    return Id_range(b, b + vertex_size_[v]);
  }
  /// the number of triangles that contain `v`.
  /// \param v a vertex index, in `[0, number_of_vertices())`
  std::size_t degree(size_type v) const { return vertex_size_[v]; }

  /// asks the processor to bring in where the list of `v`'s triangles starts and its length, for
  /// a `triangles_around_vertex(v)` a few steps later. A hint: nothing is read, changed or decided
  /// (it does nothing without GCC's or Clang's builtins).
  /// \param v a vertex index, in `[0, number_of_vertices())`
#if defined(__GNUC__) || defined(__clang__)
  // (always inlined: GCC finds a function that only prefetches free of side effects and drops
  // the calls to it)
  __attribute__((always_inline))
#endif
  void prefetch_vertex(size_type v) const
  {
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(vertex_begin_.data() + v);
    __builtin_prefetch(vertex_size_.data() + v);
#else
    (void)v;
#endif
  }

  /// asks the processor to bring in the first triangles of `v`'s list. Reads where the list
  /// starts, which `prefetch_vertex(v)` asked for a few steps before; a hint otherwise.
  /// \param v a vertex index, in `[0, number_of_vertices())`
#if defined(__GNUC__) || defined(__clang__)
  __attribute__((always_inline))
#endif
  void prefetch_triangles_around_vertex(size_type v) const
  {
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(ids_.data() + vertex_begin_[v]);
#else
    (void)v;
#endif
  }

  /// asks the processor to bring in the corners and the edge neighbours of triangle `t`. A hint.
  /// \param t a triangle index, in `[0, number_of_triangles())`
#if defined(__GNUC__) || defined(__clang__)
  __attribute__((always_inline))
#endif
  void prefetch_triangle(size_type t) const
  {
#if defined(__GNUC__) || defined(__clang__)
    __builtin_prefetch(triangles_.data() + t);
    __builtin_prefetch(neighbors_.data() + 3 * std::size_t(t));
#else
    (void)t;
#endif
  }

  /// `true` if the triangles around `v` (at least one) form one fan: they are all connected by
  /// crossing the edges incident to `v` that are manifold and for which `linked(t, i)` is true
  /// (edge `i` of triangle `t`; `linked` returning `true` always: the manifold edges alone).
  /// Walked from the first triangle of `v` both ways around `v` (in a fan every triangle has at
  /// most one such neighbour on each of its two edges at `v`, so the walk is a path or a cycle):
  /// one fan if it meets every triangle of `v`. Constant memory, linear in the degree of `v`.
  /// \param v a vertex index, in `[0, number_of_vertices())`
  /// \param linked a predicate on (triangle, local edge index)
  template <class Linked>
  bool is_one_fan(size_type v, const Linked& linked) const
  {
    const Id_range around = triangles_around_vertex(v);
    const std::size_t d = around.size();
    if(d <= 1) return true;
    const size_type first = around[0];
    std::size_t met = 1;
    const int iv = local_index(first, v);
    for(int side = 0; side < 2; ++side) {
      // crossing the edge of t at v whose other end is w
      size_type t = first;
      size_type w = vertex(first, side == 0 ? (iv + 1) % 3 : (iv + 2) % 3);
      for(;;) {
        const int it = local_index(t, v);
        const int e = vertex(t, (it + 1) % 3) == w ? it : (it + 2) % 3;
        const size_type u = neighbor(t, e);
        if(u >= non_manifold_edge || !linked(t, e)) break;
        if(u == first) return met == d; // around a closed fan
        if(++met > d) return false;      // (tables that do not describe fans)
        const int iu = local_index(u, v);
        const size_type next = vertex(u, (iu + 1) % 3);
        w = next == w ? vertex(u, (iu + 2) % 3) : next;
        t = u;
      }
    }
    return met == d;
  }

  /// calls `emit(v)` for every vertex `v` of `[begin, end)`, in increasing order, whose triangles
  /// (two or more) do not form one fan by `is_one_fan(v, linked)`. The lists and the triangles of
  /// the vertices a few steps ahead are asked for before they are walked
  /// (`prefetch_triangles_around_vertex()`, `prefetch_triangle()`): a walk waits for each
  /// triangle's row before it can ask for the next one, which on a soup in random order is a
  /// cache miss at every step; asked for ahead, the rows of many triangles are on their way at
  /// once. (On a soup in spatial order the rows are in cache already: they are asked for only
  /// while they are found far apart, `internal::Read_ahead_switch`.)
  template <class Linked, class Emit>
  void for_each_vertex_of_several_fans(std::size_t begin, std::size_t end, const Linked& linked, const Emit& emit) const
  {
    // The vertices to walk (two triangles or more) are queued `in_flight` ahead, their lists asked
    // for as they are queued; the rows of the triangles of the vertex half-way in the queue are
    // asked for at every step, as long as they are found far from each other
    // (`internal::Read_ahead_switch`). (Plain loops: GCC drops a lambda or a function whose only
    // effects are prefetches.)
    constexpr std::size_t in_flight = 8, rows_at = in_flight / 2, rows_per_vertex = 8;
    std::array<size_type, in_flight> queue{};
    std::size_t first = 0, queued = 0, scout = begin;
    internal::Read_ahead_switch read_ahead;
    for(;;) {
      while(queued < in_flight && scout < end) {
        const auto s = static_cast<size_type>(scout++);
        if(degree(s) < 2) continue;
        prefetch_triangles_around_vertex(s);
        queue[(first + queued++) % in_flight] = s;
      }
      if(queued == 0) break;
      if(read_ahead.on() && queued > rows_at) {
        const Id_range ahead = triangles_around_vertex(queue[(first + rows_at) % in_flight]);
        const std::size_t some = std::min<std::size_t>(ahead.size(), rows_per_vertex);
        for(std::size_t k = 0; k < some; ++k)
          if(read_ahead.far(ahead[k])) prefetch_triangle(ahead[k]);
      }
      read_ahead.next_vertex();
      const size_type v = queue[first];
      first = (first + 1) % in_flight;
      --queued;
      if(!is_one_fan(v, linked)) emit(v);
    }
  }
  /// @}

  /// \name The edge-neighbour table
  /// @{
  /// the neighbour of `t` across its edge `i`, or `border_edge`, or `non_manifold_edge`.
  /// \param t a triangle index, in `[0, number_of_triangles())`
  /// \param i the local index of the edge, 0, 1 or 2
  size_type neighbor(size_type t, int i) const { return neighbors_[3 * std::size_t(t) + std::size_t(i)]; }
  /// `true` if edge `i` of `t` belongs to `t` alone.
  /// \param t a triangle index, in `[0, number_of_triangles())`
  /// \param i the local index of the edge, 0, 1 or 2
  bool is_border_edge(size_type t, int i) const { return neighbor(t, i) == border_edge; }
  /// `true` if edge `i` of `t` is shared by three or more triangles.
  /// \param t a triangle index, in `[0, number_of_triangles())`
  /// \param i the local index of the edge, 0, 1 or 2
  bool is_non_manifold_edge(size_type t, int i) const { return neighbor(t, i) == non_manifold_edge; }
  /// the local index (0, 1, 2) of vertex `v` in triangle `t`, or -1.
  /// \param t a triangle index, in `[0, number_of_triangles())`
  /// \param v a vertex index
  int local_index(size_type t, size_type v) const
  {
    const Triangle& tr = triangles_[t];
    return tr[0] == v ? 0 : tr[1] == v ? 1 : tr[2] == v ? 2 : -1;
  }
  /// the local index of the edge `{a, b}` in triangle `t` (either direction), or -1.
  /// \param t a triangle index, in `[0, number_of_triangles())`
  /// \param a a vertex index, one end of the edge
  /// \param b a vertex index, the other end
  int edge_index(size_type t, size_type a, size_type b) const
  {
    const int ia = local_index(t, a), ib = local_index(t, b);
    if(ia < 0 || ib < 0) return -1;
    if((ia + 1) % 3 == ib) return ia;
    if((ib + 1) % 3 == ia) return ib;
    return -1;
  }
  /// writes to `out` every triangle other than `t` that contains edge `i` of `t`, in increasing order.
  /// Time linear in the smaller degree of the two end vertices.
  /// \tparam OutputIterator an output iterator accepting `size_type`
  /// \param t a triangle index, in `[0, number_of_triangles())`
  /// \param i the local index of the edge, 0, 1 or 2
  /// \param out where the triangles are written
  /// \return `out` past the last triangle written
  template <class OutputIterator>
  OutputIterator triangles_around_edge(size_type t, int i, OutputIterator out) const
  {
    const size_type a = vertex(t, i), b = vertex(t, (i + 1) % 3);
    const size_type s = degree(a) <= degree(b) ? a : b, o = (s == a) ? b : a;
    for(size_type u : triangles_around_vertex(s))
      if(u != t && local_index(u, o) >= 0) *out++ = u;
    return out;
  }
  /// all border (unconnected) edges, ordered by triangle then local index.
  std::vector<Edge> border_edges() const { return edges_with(border_edge); }
  /// the number of border edges.
  std::size_t number_of_border_edges() const
  { return static_cast<std::size_t>(std::count(neighbors_.begin(), neighbors_.end(), border_edge)); }
  /// one `Edge` per distinct non-manifold edge: the one of its smallest triangle, ordered by
  /// triangle then local index. Linear time.
  std::vector<Edge> non_manifold_edges() const
  {
    std::vector<Edge> result;
    if(std::find(neighbors_.begin(), neighbors_.end(), non_manifold_edge) == neighbors_.end()) return result;
    for_each_edge([&](size_type, size_type, const Edge* first, const Edge* last) {
      if(last - first >= 3) result.push_back(*first);
    });
    std::sort(result.begin(), result.end());
    return result;
  }
  /// the edges whose two triangles traverse them in the same direction (inconsistent
  /// orientation), one `Edge` per edge, the one of the smaller triangle.
  /// \tparam ConcurrencyTag with `CGAL::Parallel_tag`, the triangles are examined by blocks on
  ///         TBB's threads; the list is the same, in the order of the triangles
  template <class ConcurrencyTag = CGAL::Sequential_tag>
  std::vector<Edge> inconsistently_oriented_edges() const
  {
    const std::size_t n = triangles_.size();
    std::vector<std::vector<Edge>> blocks(internal::number_of_blocks(n));
    internal::for_each_block<ConcurrencyTag>(n, internal::default_block_size,
                                             [&](std::size_t g, std::size_t begin, std::size_t end) {
      for(std::size_t k = begin; k < end; ++k) {
        const auto t = static_cast<size_type>(k);
        for(int i = 0; i < 3; ++i) {
          const size_type u = neighbor(t, i);
          if(u >= non_manifold_edge || u < t) continue;
          const int j = edge_index(u, vertex(t, i), vertex(t, (i + 1) % 3));
          if(vertex(u, j) == vertex(t, i)) blocks[g].push_back(Edge{t, i});
        }
      }
    });
    std::vector<Edge> result;
    internal::concatenate_in_block_order(blocks, result);
    return result;
  }
  /// @}

  /// \name Global queries
  /// @{
  /// `true` if no edge is a border edge.
  bool is_closed() const { return std::find(neighbors_.begin(), neighbors_.end(), border_edge) == neighbors_.end(); }

  /// the vertices around which the triangles do not form a single fan: the triangles that contain
  /// `v` are grouped by the manifold edges incident to `v`; more than one group makes `v`
  /// non-manifold. (A vertex of a non-manifold edge is therefore non-manifold too.) Isolated
  /// vertices are not listed.
  /// \tparam ConcurrencyTag with `CGAL::Parallel_tag`, the vertices are examined by blocks on
  ///         TBB's threads; the list is the same, in increasing order
  template <class ConcurrencyTag = CGAL::Sequential_tag>
  std::vector<size_type> non_manifold_vertices() const
  {
    const std::size_t n = number_of_vertices();
    std::vector<std::vector<size_type>> blocks(internal::number_of_blocks(n));
    internal::for_each_block<ConcurrencyTag>(n, internal::default_block_size,
                                             [&](std::size_t g, std::size_t begin, std::size_t end) {
      for_each_vertex_of_several_fans(begin, end, [](size_type, int) { return true; },
                                      [&](size_type v) { blocks[g].push_back(v); });
    });
    std::vector<size_type> result;
    internal::concatenate_in_block_order(blocks, result);
    return result;
  }

  /// the number of edge-connected components of the triangles (triangles sharing an edge, manifold
  /// or not, are connected). If `component` is not null it receives, for every triangle, the id
  /// of its component; ids are numbered by their smallest triangle, from 0.
  /// Linear time (union-find; the triangles of a non-manifold edge are joined to its smallest one).
  /// \tparam ConcurrencyTag with `CGAL::Parallel_tag`, the triangles are joined across their
  ///         manifold edges by blocks on TBB's threads, the sets keeping their smallest triangle as
  ///         root whatever the order of the unions, and the ids are numbered by blocks: the same
  ///         count and ids
  /// \param component null, or the vector that receives the component of every triangle
  template <class ConcurrencyTag = CGAL::Sequential_tag>
  std::size_t number_of_connected_components(std::vector<size_type>* component = nullptr) const
  {
    const std::size_t n = triangles_.size();
    // Whether an edge is non-manifold (its triangles are then joined in one more pass).
    std::atomic<bool> non_manifold(false);
    if(internal::runs_on_several_threads<ConcurrencyTag>()) {
      // Each block makes its triangles singletons and unites them across the edges inside it,
      // alone with its ids (in a mesh stored in any spatial order most edges are inside a block),
      // and lists its edges to later blocks; one thread then unites across those.
      internal::Concurrent_union_find sets(n, internal::Concurrent_union_find::Unset{});
      std::vector<std::vector<std::pair<size_type, size_type>>> between(internal::number_of_blocks(n));
      internal::for_each_block<ConcurrencyTag>(n, internal::default_block_size,
                                               [&](std::size_t g, std::size_t begin, std::size_t end) {
        sets.make_singletons(begin, end);
        for(std::size_t t = begin; t < end; ++t)
          for(int i = 0; i < 3; ++i) {
            const size_type u = neighbor(static_cast<size_type>(t), i);
            if(u == non_manifold_edge) non_manifold.store(true, std::memory_order_relaxed);
            else if(u <= t || u == border_edge) continue;
            else if(u < end) sets.unite_alone(static_cast<size_type>(t), u);
            else between[g].emplace_back(static_cast<size_type>(t), u);
          }
      });
      for(const auto& edges : between)
        for(const auto& [t, u] : edges) sets.unite_alone(t, u);
      if(non_manifold) join_around_non_manifold_edges(sets);
      internal::Uninitialized_vector<size_type> root(n);
      internal::for_each_block<ConcurrencyTag>(n, internal::default_block_size,
                                               [&](std::size_t, std::size_t begin, std::size_t end) {
        // in increasing order: a parent in the block holds its root already
        for(std::size_t t = begin; t < end; ++t) {
          const size_type p = sets.parent(static_cast<size_type>(t));
          root[t] = p == t ? p : p >= begin ? root[p] : sets.find(p);
        }
      });
      return number_components<ConcurrencyTag>(root, component);
    }
    internal::Union_find sets(n);
    for(size_type t = 0; t < n; ++t) join_across_manifold_edges(t, sets, non_manifold);
    if(non_manifold) join_around_non_manifold_edges(sets);
    return number_components<ConcurrencyTag>(sets.take_roots(), component);
  }
  /// @}

  /// \name Local updates
  /// @{
  /// replaces every reference to vertex `duplicate` by `original` (the patent's rules (a)-(c)):
  /// the triangle table is rewritten, the triangles of `duplicate` join those of `original` and
  /// the edge neighbours around `original` are recomputed. `duplicate` is left isolated.
  /// Only the edges `{original, w}`, `w` a neighbour of `duplicate`, are resolved again; the
  /// triangle lists are merged in time linear in the two degrees (constant time per moved
  /// triangle when they all come after those of `original`, as in a weld of later copies).
  /// \param duplicate the vertex that disappears
  /// \param original the vertex that replaces it
  /// \throws Invalid_input if a triangle contains both vertices (it would degenerate); nothing is
  ///         changed then.
  void replace_vertex(size_type duplicate, size_type original)
  {
    if(duplicate == original) return;
    check_vertex(duplicate);
    check_vertex(original);
    for(size_type t : triangles_around_vertex(duplicate))
      if(local_index(t, original) >= 0)
        throw Invalid_input("replace_vertex: triangle " + std::to_string(t) + " contains both vertex " +
                            std::to_string(duplicate) + " and vertex " + std::to_string(original));
    const Id_range moved_range = triangles_around_vertex(duplicate);
    const std::vector<size_type> moved(moved_range.begin(), moved_range.end());
    // The other ends of the edges that change: {duplicate, w} becomes {original, w}.
    std::vector<size_type> ends;
    ends.reserve(2 * moved.size());
    for(size_type t : moved) {
      const int k = local_index(t, duplicate);
      ends.push_back(vertex(t, (k + 1) % 3));
      ends.push_back(vertex(t, (k + 2) % 3));
      triangles_[t][static_cast<std::size_t>(k)] = original;
    }
    // Merge the two sorted lists into the original's entry (appending when the moved triangles
    // all come after the original's).
    const Id_range kept = triangles_around_vertex(original);
    if(kept.empty() || moved.empty() || kept[kept.size() - 1] < moved.front()) {
      for(size_type t : moved) append_to_list(original, t);
    } else {
      merge_buffer_.clear();
      std::merge(kept.begin(), kept.end(), moved.begin(), moved.end(), std::back_inserter(merge_buffer_));
      assign_list(original, merge_buffer_);
    }
    keep_capacities();
    vertex_size_[duplicate] = 0;
    // Only the edges {original, w} gain triangles; the edges opposite the moved vertex keep theirs.
    std::sort(ends.begin(), ends.end());
    ends.erase(std::unique(ends.begin(), ends.end()), ends.end());
    for(size_type w : ends) resolve_edge(original, w);
  }

  /// splits triangle `t` at vertex `v_new` lying on its edge `i` (rule table (15)): `t` keeps its
  /// index with `v_{i+1}` replaced by `v_new`, and a new triangle with `v_i` replaced by `v_new` is
  /// appended. The vertex table is updated by rule table (17) and the edge neighbours of the
  /// touched vertices are recomputed. Returns the index of the new triangle.
  /// \param t the triangle split
  /// \param i the local index of the edge of `t` that `v_new` lies on, 0, 1 or 2
  /// \param v_new the vertex that splits that edge
  /// \throws Invalid_input if `v_new` is a vertex of `t` or an index is out of range.
  size_type split_triangle(size_type t, int i, size_type v_new)
  {
    if(t >= triangles_.size() || i < 0 || i > 2)
      throw Invalid_input("split_triangle: no edge " + std::to_string(i) + " of triangle " + std::to_string(t));
    check_vertex(v_new);
    if(local_index(t, v_new) >= 0)
      throw Invalid_input("split_triangle: vertex " + std::to_string(v_new) + " is already a vertex of triangle " +
                          std::to_string(t));
    if(triangles_.size() + 1 >= std::size_t(non_manifold_edge))
      throw Invalid_input("split_triangle: too many triangles for 32-bit indices");
    const std::size_t si = static_cast<std::size_t>(i);
    const Triangle old = triangles_[t];
    const size_type vi = old[si], vj = old[(si + 1) % 3], vk = old[(si + 2) % 3];
    // The neighbours of t across (v_i, v_{i+1}) and (v_{i+1}, v_{i+2}) before the split.
    const size_type across_ij = neighbor(t, i), across_jk = neighbor(t, (i + 1) % 3);
    Triangle created = old;
    created[si] = v_new;
    triangles_[t][(si + 1) % 3] = v_new;
    const size_type t_new = static_cast<size_type>(triangles_.size());
    triangles_.push_back(created);
    neighbors_.insert(neighbors_.end(), {border_edge, border_edge, border_edge});
    // Rule table (17): v_i keeps t; v_{i+1}: t -> t_new; v_{i+2}: + t_new; v_new: + t, + t_new.
    // t_new is the largest triangle: it goes at the end of the sorted lists.
    remove_from_list(vj, t);
    append_to_list(vj, t_new);
    append_to_list(vk, t_new);
    insert_in_list(v_new, t);
    append_to_list(v_new, t_new);
    // Edge neighbours. (v_{i+2}, v_i) keeps its triangles, and its local index in t.
    // (v_{i+1}, v_{i+2}) moves from t to t_new at the same local index: its other triangles only
    // need their entry for t changed.
    set_neighbor(t_new, (i + 1) % 3, across_jk);
    if(across_jk < non_manifold_edge) set_neighbor(across_jk, edge_index(across_jk, vj, vk), t_new);
    // (v_i, v_{i+1}) loses t.
    if(across_ij == non_manifold_edge) resolve_edge(vi, vj);
    else if(across_ij != border_edge) set_neighbor(across_ij, edge_index(across_ij, vi, vj), border_edge);
    // The three edges of v_new.
    resolve_edge(vi, v_new);
    resolve_edge(v_new, vk);
    resolve_edge(v_new, vj);
    return t_new;
  }
  /// @}

private:
  // unites `t` with its neighbours of larger index across its manifold edges; notes a non-manifold edge
  template <class Sets>
  void join_across_manifold_edges(size_type t, Sets& sets, std::atomic<bool>& non_manifold) const
  {
    for(int i = 0; i < 3; ++i) {
      const size_type u = neighbor(t, i);
      if(u == non_manifold_edge) non_manifold.store(true, std::memory_order_relaxed);
      else if(u != border_edge && u > t) sets.unite(t, u);
    }
  }

  // The number of components whose sets have the roots `root` (the smallest triangle of each
  // set), and, if `component` is not null, the component of every triangle. Ids in the order of
  // the roots: the roots of a block are numbered after those of the blocks before it.
  template <class ConcurrencyTag, class Roots>
  std::size_t number_components(const Roots& root, std::vector<size_type>* component) const
  {
    const std::size_t n = triangles_.size();
    const std::size_t blocks = internal::number_of_blocks(n);
    std::vector<size_type> roots_before(blocks + 1, 0);
    internal::for_each_block<ConcurrencyTag>(n, internal::default_block_size,
                                             [&](std::size_t g, std::size_t begin, std::size_t end) {
      for(std::size_t t = begin; t < end; ++t) roots_before[g + 1] += root[t] == t ? 1 : 0;
    });
    for(std::size_t g = 0; g < blocks; ++g) roots_before[g + 1] += roots_before[g];
    const std::size_t count = roots_before[blocks];
    if(component != nullptr) {
      std::vector<size_type> cc(n);
      // first the ids of the roots, then every triangle takes its root's (a root precedes its set)
      internal::for_each_block<ConcurrencyTag>(n, internal::default_block_size,
                                               [&](std::size_t g, std::size_t begin, std::size_t end) {
        size_type next = roots_before[g];
        for(std::size_t t = begin; t < end; ++t)
          if(root[t] == t) cc[t] = next++;
      });
      internal::for_each_block<ConcurrencyTag>(n, internal::default_block_size,
                                               [&](std::size_t, std::size_t begin, std::size_t end) {
        for(std::size_t t = begin; t < end; ++t)
          if(root[t] != t) cc[t] = cc[root[t]];
      });
      component->swap(cc);
    }
    return count;
  }

  // unites the triangles of every non-manifold edge
  template <class Sets>
  void join_around_non_manifold_edges(Sets& sets) const
  {
    for_each_edge([&](size_type, size_type, const Edge* first, const Edge* last) {
      if(last - first < 3) return;
      for(const Edge* e = first + 1; e != last; ++e) sets.unite(first->triangle, e->triangle);
    });
  }

  void check_vertex(size_type v) const
  {
    if(v >= number_of_vertices())
      throw Invalid_input("vertex " + std::to_string(v) + " is out of range (" +
                          std::to_string(number_of_vertices()) + " vertices)");
  }

  std::vector<Edge> edges_with(size_type value) const
  {
    std::vector<Edge> result;
    for(std::size_t k = 0; k < neighbors_.size(); ++k)
      if(neighbors_[k] == value) result.push_back(Edge{static_cast<size_type>(k / 3), int(k % 3)});
    return result;
  }

  void set_neighbor(size_type t, int i, size_type value) { neighbors_[3 * std::size_t(t) + std::size_t(i)] = value; }

  // The most edges of one vertex (to vertices after it) that `for_each_edge()` sorts by insertion:
  // a vertex of a mesh has about 12, so nearly every vertex of a soup takes the short path.
  static constexpr std::size_t sorted_row_limit = 32;

  // An end of an edge {a, b} met in the pass of a: b, and the copy of the edge.
  struct Edge_end
  {
    size_type other;
    Edge edge;
  };

  // What the pass of the edges reuses from one vertex to the next.
  struct Edge_pass_scratch
  {
    std::vector<Edge_end> ends;
    std::vector<Edge> grouped;
    std::vector<size_type> mark;  // mark[b] == a + 1: b has a bucket in the pass of a (long lists, `with_marks`)
    std::vector<size_type> slot;  // the bucket of b, valid when marked
    std::vector<size_type> others, count, cursor;
  };

  // Calls f(a, b, first, last) once for every distinct edge {a, b} (a < b) of the triangles, with
  // [first, last) its copies (triangle, local index) in increasing triangle order (the edges of
  // one vertex a come in no particular order of b): `for_each_edge_of_vertices()` over them all.
  template <class F>
  void for_each_edge(F&& f) const
  {
    Edge_pass_scratch scratch;
    for_each_edge_of_vertices(0, number_of_vertices(), true, scratch, f);
  }

  // `f(a, b, first, last)` for the edges {a, b}, a < b, of the vertices a of [begin, end). The
  // edges of each vertex a to the vertices b > a are gathered from its triangles, which are read
  // once, and grouped by b:
  // - up to `sorted_row_limit` of them, by a stable insertion sort on b, in place: it reads
  //   nothing but the vertex's own triangles, which matters when the other ends are far apart in
  //   memory (a soup whose triangles are not in mesh order);
  // - more, `with_marks`, by buckets (count, then place, with a mark per vertex b made at the
  //   first such vertex: two arrays over all the vertices, made once for the whole pass), so the
  //   enumeration is linear in the size of the soup however many triangles share a vertex or an
  //   edge; without marks (a pass of one block of vertices among many, on TBB's threads, which
  //   must not each hold arrays over all the vertices), by a sort on (b, copy), which gives the same
  //   groups in the same order, in O(k log k) for the k edges of the vertex.
  template <class F>
  void for_each_edge_of_vertices(std::size_t begin, std::size_t end, bool with_marks, Edge_pass_scratch& s,
                                 F& f) const
  {
    const std::size_t nv = number_of_vertices();
    std::vector<Edge_end>& ends = s.ends;
    std::vector<Edge>& grouped = s.grouped;
    // (the rows of the triangles of the vertices ahead asked for while they are found far from
    // each other, as in `for_each_vertex_of_several_fans()`: on triangles in random order every
    // row is a miss)
    constexpr size_type lists_ahead = 16, rows_ahead = 8, rows_per_vertex = 8;
    internal::Read_ahead_switch read_ahead;
    for(size_type a = static_cast<size_type>(begin); a < end; ++a) {
      if(read_ahead.on()) {
        if(a + lists_ahead < end) prefetch_triangles_around_vertex(a + lists_ahead);
        if(a + rows_ahead < end) {
          const Id_range ahead = triangles_around_vertex(a + rows_ahead);
          const std::size_t some = std::min<std::size_t>(ahead.size(), rows_per_vertex);
          for(std::size_t k = 0; k < some; ++k)
            if(read_ahead.far(ahead[k])) prefetch_triangle(ahead[k]);
        }
      }
      read_ahead.next_vertex();
      const Id_range around = triangles_around_vertex(a);
      if(around.empty()) continue;
      ends.clear();
      // in increasing triangle order; the two ends of one triangle are distinct
      for(size_type t : around) {
        const int ia = local_index(t, a);
        const size_type next = vertex(t, (ia + 1) % 3), previous = vertex(t, (ia + 2) % 3);
        if(next > a) ends.push_back(Edge_end{next, Edge{t, ia}});
        if(previous > a) ends.push_back(Edge_end{previous, Edge{t, (ia + 2) % 3}});
      }
      grouped.resize(ends.size());
      if(ends.size() <= sorted_row_limit || !with_marks) {
        if(ends.size() <= sorted_row_limit) {
          for(std::size_t k = 1; k < ends.size(); ++k) {
            const Edge_end e = ends[k];
            std::size_t j = k;
            for(; j > 0 && e.other < ends[j - 1].other; --j) ends[j] = ends[j - 1];
            ends[j] = e;
          }
        } else {
          std::sort(ends.begin(), ends.end(), [](const Edge_end& x, const Edge_end& y) {
            return x.other < y.other || (x.other == y.other && x.edge < y.edge);
          });
        }
        for(std::size_t k = 0; k < ends.size(); ++k) grouped[k] = ends[k].edge;
        std::size_t k = 0;
        while(k < ends.size()) {
          std::size_t l = k + 1;
          while(l < ends.size() && ends[l].other == ends[k].other) ++l;
          f(a, ends[k].other, grouped.data() + k, grouped.data() + l);
          k = l;
        }
        continue;
      }
      std::vector<size_type>& mark = s.mark;
      std::vector<size_type>& slot = s.slot;
      if(mark.empty()) {
        mark.assign(nv, 0);
        slot.resize(nv);
      }
      std::vector<size_type>& others = s.others;
      std::vector<size_type>& count = s.count;
      std::vector<size_type>& cursor = s.cursor;
      others.clear();
      count.clear();
      for(const Edge_end& e : ends) {
        if(mark[e.other] != a + 1) {
          mark[e.other] = a + 1;
          slot[e.other] = static_cast<size_type>(others.size());
          others.push_back(e.other);
          count.push_back(0);
        }
        ++count[slot[e.other]];
      }
      cursor.resize(others.size());
      std::size_t total = 0;
      for(std::size_t k = 0; k < others.size(); ++k) { cursor[k] = static_cast<size_type>(total); total += count[k]; }
      for(const Edge_end& e : ends) grouped[cursor[slot[e.other]]++] = e.edge;
      const Edge* first = grouped.data();
      for(std::size_t k = 0; k < others.size(); ++k) {
        f(a, others[k], first, first + count[k]);
        first += count[k];
      }
    }
  }

  void build(std::size_t number_of_points)
  {
    const std::size_t nv = number_of_points;
    vertex_begin_.assign(nv, 0);
    vertex_size_.assign(nv, 0);
    decltype(vertex_capacity_)().swap(vertex_capacity_); // every list is full: see `keep_capacities()`
    for(const Triangle& tr : triangles_)
      for(size_type v : tr) ++vertex_size_[v];
    std::size_t offset = 0;
    for(std::size_t v = 0; v < nv; ++v) {
      vertex_begin_[v] = offset;
      offset += vertex_size_[v];
      vertex_size_[v] = 0;
    }
    ids_.resize(offset);
    for(size_type t = 0; t < triangles_.size(); ++t)
      for(size_type v : triangles_[t]) ids_[vertex_begin_[v] + vertex_size_[v]++] = t;
    neighbors_.assign(3 * triangles_.size(), border_edge);
    for_each_edge([this](size_type, size_type, const Edge* first, const Edge* last) { set_group(first, last); });
  }

  // build() on TBB's threads, with the same result, and no atomic operation: the vertex table is
  // filled by `fill_vertex_rows_by_buckets()`, then the edges of blocks of vertices are grouped
  // as `build()` groups them (`for_each_edge_of_vertices()`), the blocks in parallel: the entries
  // of an edge {a, b}, a < b, are written in the pass of a only.
  template <class ConcurrencyTag>
  void build_in_parallel(std::size_t number_of_points)
  {
    const std::size_t nv = number_of_points, m = triangles_.size();
    decltype(vertex_capacity_)().swap(vertex_capacity_); // every list is full: see `keep_capacities()`
    fill_vertex_rows_by_buckets<ConcurrencyTag>(nv);
    internal::for_each_index<ConcurrencyTag>(3 * m, [&](std::size_t k) { neighbors_[k] = border_edge; });
    internal::for_each_block<ConcurrencyTag>(nv, 4096, [&](std::size_t, std::size_t begin, std::size_t end) {
      Edge_pass_scratch scratch;
      const auto write_group = [this](size_type, size_type, const Edge* first, const Edge* last) {
        set_group(first, last);
      };
      for_each_edge_of_vertices(begin, end, false, scratch, write_group);
    });
  }

  // The vertex table of `build()` (each row in increasing triangle order, the rows in vertex
  // order), filled on TBB's threads as a two-level counting sort of the corners by vertex:
  // - the vertices are cut into buckets of 2^shift consecutive vertices (at most
  //   `most_vertex_buckets` buckets), the triangles into at most `most_triangle_blocks` blocks;
  //   neither depends on the number of threads;
  // - each block of triangles counts its corners per bucket (an array of one entry per bucket:
  //   the counting stays in cache whatever the order of the triangles);
  // - those counts, taken bucket after bucket and in each bucket block after block, give every
  //   block its place in every bucket's range of `ids_`: each block copies its corners there, in
  //   the order of its triangles (the triangle into `ids_`, its vertex into `neighbors_`, whose
  //   3 entries a triangle are rewritten with the neighbours afterwards: no memory is added);
  // - each bucket, whose range of `ids_` now holds its corners in increasing triangle order,
  //   counts the degrees of its vertices, which gives their rows, and places its corners in them
  //   by a stable counting sort through a buffer of the bucket's size.
  // A row is thus in increasing triangle order without a sort, as in `build()`.
  template <class ConcurrencyTag>
  void fill_vertex_rows_by_buckets(std::size_t nv)
  {
    const std::size_t m = triangles_.size();
    vertex_begin_.resize(nv); // (written whole below, bucket by bucket)
    vertex_size_.resize(nv);
    ids_.resize(3 * m);
    neighbors_.resize(3 * m);
    internal::fault_in_pages(vertex_begin_);
    internal::fault_in_pages(vertex_size_);
    internal::fault_in_pages(ids_);
    internal::fault_in_pages(neighbors_);
    if(nv == 0) return;
    std::size_t shift = 10;
    while((nv >> shift) >= most_vertex_buckets) ++shift;
    const std::size_t buckets = ((nv - 1) >> shift) + 1;
    const std::size_t block = std::max<std::size_t>(internal::default_block_size,
                                                    (m + most_triangle_blocks - 1) / most_triangle_blocks);
    const std::size_t blocks = internal::number_of_blocks(m, block);
    // place[g * buckets + b]: the corners of block g in bucket b, then where they go
    std::vector<std::size_t> place(blocks * buckets, 0);
    internal::for_each_block<ConcurrencyTag>(m, block, [&](std::size_t g, std::size_t begin, std::size_t end) {
      std::size_t* count = place.data() + g * buckets;
      for(std::size_t t = begin; t != end; ++t)
        for(size_type v : triangles_[t]) ++count[v >> shift];
    });
    std::vector<std::size_t> bucket_begin(buckets + 1);
    std::size_t offset = 0;
    for(std::size_t b = 0; b < buckets; ++b) {
      bucket_begin[b] = offset;
      for(std::size_t g = 0; g < blocks; ++g) {
        const std::size_t here = place[g * buckets + b];
        place[g * buckets + b] = offset;
        offset += here;
      }
    }
    bucket_begin[buckets] = offset;
    internal::for_each_block<ConcurrencyTag>(m, block, [&](std::size_t g, std::size_t begin, std::size_t end) {
      std::size_t* next = place.data() + g * buckets;
      for(std::size_t t = begin; t != end; ++t)
        for(size_type v : triangles_[t]) {
          const std::size_t k = next[v >> shift]++;
          ids_[k] = static_cast<size_type>(t);
          neighbors_[k] = v;
        }
    });
    internal::for_each_block<ConcurrencyTag>(buckets, 1, [&](std::size_t b, std::size_t, std::size_t) {
      const std::size_t first_vertex = b << shift, last_vertex = std::min(nv, (b + 1) << shift);
      const std::size_t begin = bucket_begin[b], end = bucket_begin[b + 1];
      std::vector<std::size_t> cursor(last_vertex - first_vertex, 0);
      for(std::size_t k = begin; k != end; ++k) ++cursor[neighbors_[k] - first_vertex];
      std::size_t row = begin;
      for(std::size_t v = first_vertex; v != last_vertex; ++v) {
        const std::size_t d = cursor[v - first_vertex];
        vertex_begin_[v] = row;
        vertex_size_[v] = static_cast<size_type>(d);
        cursor[v - first_vertex] = row;
        row += d;
      }
      const std::vector<size_type> corners(ids_.begin() + static_cast<std::ptrdiff_t>(begin),
                                           ids_.begin() + static_cast<std::ptrdiff_t>(end));
      for(std::size_t k = begin; k != end; ++k) ids_[cursor[neighbors_[k] - first_vertex]++] = corners[k - begin];
    });
  }

  // the most buckets of vertices and blocks of triangles of `fill_vertex_rows_by_buckets()`: its
  // table of places has at most their product (256 Ki entries, 2 MiB)
  static constexpr std::size_t most_vertex_buckets = 4096, most_triangle_blocks = 64;

  // Writes the neighbour entries of [first, last), all the copies of one edge.
  void set_group(const Edge* first, const Edge* last)
  {
    const std::ptrdiff_t n = last - first;
    if(n == 1) {
      set_neighbor(first->triangle, first->index, border_edge);
    } else if(n == 2) {
      set_neighbor(first[0].triangle, first[0].index, first[1].triangle);
      set_neighbor(first[1].triangle, first[1].index, first[0].triangle);
    } else {
      for(const Edge* e = first; e != last; ++e) set_neighbor(e->triangle, e->index, non_manifold_edge);
    }
  }

  // Finds every triangle containing the edge {a, b}, by scanning the shorter of the two vertex
  // lists, and writes the neighbour entries of all of them.
  void resolve_edge(size_type a, size_type b)
  {
    const size_type s = degree(a) <= degree(b) ? a : b;
    group_.clear();
    for(size_type u : triangles_around_vertex(s)) {
      const int j = edge_index(u, a, b);
      if(j >= 0) group_.push_back(Edge{u, j});
    }
    if(!group_.empty()) set_group(group_.data(), group_.data() + group_.size());
  }

  // A build leaves every list exactly full, so the room of the lists is not stored then (4 bytes
  // per vertex): it is made equal to the sizes before the first local update changes a size.
  void keep_capacities()
  {
    if(vertex_capacity_.size() != vertex_size_.size()) vertex_capacity_ = vertex_size_;
  }

  // Gives the list of v room for at least `capacity` entries; a list that outgrows its room moves
  // to the end of the pool with twice the room (amortised constant time per insertion).
  void reserve_list(size_type v, std::size_t capacity)
  {
    keep_capacities();
    if(capacity <= vertex_capacity_[v]) return;
    capacity = std::max<std::size_t>(capacity, std::max<std::size_t>(2 * std::size_t(vertex_capacity_[v]), 4));
    const std::size_t old_begin = vertex_begin_[v], new_begin = ids_.size();
    ids_.resize(new_begin + capacity, border_edge);
    std::copy(ids_.begin() + static_cast<std::ptrdiff_t>(old_begin),
              ids_.begin() + static_cast<std::ptrdiff_t>(old_begin + vertex_size_[v]),
              ids_.begin() + static_cast<std::ptrdiff_t>(new_begin));
    vertex_begin_[v] = new_begin;
    vertex_capacity_[v] = static_cast<size_type>(capacity);
  }

  // Stores `list` (sorted) as the triangle list of v.
  void assign_list(size_type v, const std::vector<size_type>& list)
  {
    keep_capacities();
    if(list.size() > vertex_capacity_[v]) {
      vertex_size_[v] = 0; // the old entries are overwritten: nothing to move
      reserve_list(v, 2 * list.size());
    }
    std::copy(list.begin(), list.end(), ids_.begin() + static_cast<std::ptrdiff_t>(vertex_begin_[v]));
    vertex_size_[v] = static_cast<size_type>(list.size());
  }

  // Appends t, larger than every triangle of v, to the list of v.
  void append_to_list(size_type v, size_type t)
  {
    reserve_list(v, std::size_t(vertex_size_[v]) + 1);
    ids_[vertex_begin_[v] + vertex_size_[v]++] = t;
  }

  // Inserts t at its place in the sorted list of v.
  void insert_in_list(size_type v, size_type t)
  {
    reserve_list(v, std::size_t(vertex_size_[v]) + 1);
    size_type* b = ids_.data() + vertex_begin_[v];
    size_type* e = b + vertex_size_[v];
    size_type* p = std::upper_bound(b, e, t);
    std::copy_backward(p, e, e + 1);
    *p = t;
    ++vertex_size_[v];
  }

  // Removes t from the sorted list of v.
  void remove_from_list(size_type v, size_type t)
  {
    keep_capacities();
    size_type* b = ids_.data() + vertex_begin_[v];
    size_type* e = b + vertex_size_[v];
    size_type* p = std::lower_bound(b, e, t);
    if(p == e || *p != t) return;
    std::copy(p + 1, e, p);
    --vertex_size_[v];
  }

  Triangle_vector triangles_;
  // Vertex table: compressed rows with spare capacity; a row that outgrows its capacity moves to
  // the end of `ids_` (amortised constant time per insertion).
  // (`Uninitialized_vector`: a build writes every entry of these tables, on TBB's threads in the
  // parallel build, and nothing zeroes them before.)
  internal::Uninitialized_vector<std::size_t> vertex_begin_;
  internal::Uninitialized_vector<size_type> vertex_size_;
  internal::Uninitialized_vector<size_type> vertex_capacity_; // empty while every list is full (after a build)
  internal::Uninitialized_vector<size_type> ids_;
  // Edge table: neighbors_[3 t + i] is the neighbour of t across its edge i.
  internal::Uninitialized_vector<size_type> neighbors_;
  // Scratch space of the local updates.
  std::vector<size_type> merge_buffer_;
  std::vector<Edge> group_;
};

} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_ADJACENCY_TABLES_H
