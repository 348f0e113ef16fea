// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The vertex-neighbour and edge-neighbour tables of an indexed triangle soup (pipeline step 1).

#ifndef SOUP_TOPOLOGY_ADJACENCY_TABLES_H
#define SOUP_TOPOLOGY_ADJACENCY_TABLES_H

#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/internal/soup_checks.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <string>
#include <utility>
#include <vector>

namespace Soup_topology {

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
/// **Construction** is linear in the size of the soup: one pass fills the vertex table, then each
/// edge is resolved by scanning the (short) triangle list of its first vertex.
///
/// **Local updates.** `replace_vertex()` (welding, the patent's rules (a)-(c)) and
/// `split_triangle()` (T-junction repair, rule tables (15) and (17)) change the tables locally:
/// only the entries around the touched vertices are recomputed.
///
/// Indices are stored on 32 bits; a soup must have fewer than 2^32 - 2 points and triangles.
class Adjacency_tables
{
public:
  /// the type of vertex and triangle indices.
  using size_type = std::uint32_t;
  /// the three vertex indices of a triangle.
  using Triangle = std::array<size_type, 3>;
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
  /// \throws Invalid_input if a face is not a triangle, repeats an index or has an index out of
  ///         range; the message names the face.
  template <class FaceRange>
  Adjacency_tables(const FaceRange& faces, std::size_t number_of_points)
  {
    internal::check_triangle_soup(faces, number_of_points);
    triangles_.reserve(static_cast<std::size_t>(std::distance(std::begin(faces), std::end(faces))));
    std::size_t face_id = 0;
    for(const auto& f : faces) {
      triangles_.push_back({static_cast<size_type>(internal::corner(f, 0, face_id)),
                            static_cast<size_type>(internal::corner(f, 1, face_id)),
                            static_cast<size_type>(internal::corner(f, 2, face_id))});
      ++face_id;
    }
    build(number_of_points);
  }

  /// \name Sizes and triangles
  /// @{
  std::size_t number_of_vertices() const { return vertex_begin_.size(); }
  std::size_t number_of_triangles() const { return triangles_.size(); }
  /// the vertex indices of triangle `t`.
  const Triangle& triangle(size_type t) const { return triangles_[t]; }
  /// all triangles, in index order (they change with `replace_vertex()` and `split_triangle()`).
  const std::vector<Triangle>& triangles() const { return triangles_; }
  /// vertex `i` (0, 1 or 2) of triangle `t`.
  size_type vertex(size_type t, int i) const { return triangles_[t][static_cast<std::size_t>(i)]; }
  /// @}

  /// \name The vertex-neighbour table
  /// @{
  /// the triangles that contain `v`, in increasing order.
  Id_range triangles_around_vertex(size_type v) const
  {
    const size_type* b = ids_.data() + vertex_begin_[v];
    return Id_range(b, b + vertex_size_[v]);
  }
  /// the number of triangles that contain `v`.
  std::size_t degree(size_type v) const { return vertex_size_[v]; }
  /// @}

  /// \name The edge-neighbour table
  /// @{
  /// the neighbour of `t` across its edge `i`, or `border_edge`, or `non_manifold_edge`.
  size_type neighbor(size_type t, int i) const { return neighbors_[3 * std::size_t(t) + std::size_t(i)]; }
  bool is_border_edge(size_type t, int i) const { return neighbor(t, i) == border_edge; }
  bool is_non_manifold_edge(size_type t, int i) const { return neighbor(t, i) == non_manifold_edge; }
  /// the local index (0, 1, 2) of vertex `v` in triangle `t`, or -1.
  int local_index(size_type t, size_type v) const
  {
    const Triangle& tr = triangles_[t];
    return tr[0] == v ? 0 : tr[1] == v ? 1 : tr[2] == v ? 2 : -1;
  }
  /// the local index of the edge `{a, b}` in triangle `t` (either direction), or -1.
  int edge_index(size_type t, size_type a, size_type b) const
  {
    const int ia = local_index(t, a), ib = local_index(t, b);
    if(ia < 0 || ib < 0) return -1;
    if((ia + 1) % 3 == ib) return ia;
    if((ib + 1) % 3 == ia) return ib;
    return -1;
  }
  /// writes to `out` every triangle other than `t` that contains edge `i` of `t`, in increasing order.
  template <class OutputIterator>
  OutputIterator triangles_around_edge(size_type t, int i, OutputIterator out) const
  {
    const size_type a = vertex(t, i), b = vertex(t, (i + 1) % 3);
    for(size_type u : triangles_around_vertex(a))
      if(u != t && local_index(u, b) >= 0) *out++ = u;
    return out;
  }
  /// all border (unconnected) edges, ordered by triangle then local index.
  std::vector<Edge> border_edges() const { return edges_with(border_edge); }
  /// the number of border edges.
  std::size_t number_of_border_edges() const
  { return static_cast<std::size_t>(std::count(neighbors_.begin(), neighbors_.end(), border_edge)); }
  /// one `Edge` per distinct non-manifold edge: the one of its smallest triangle.
  std::vector<Edge> non_manifold_edges() const
  {
    std::vector<Edge> result;
    for(const Edge& e : edges_with(non_manifold_edge)) {
      const size_type a = vertex(e.triangle, e.index), b = vertex(e.triangle, (e.index + 1) % 3);
      bool smallest = true;
      for(size_type u : triangles_around_vertex(a)) {
        if(u >= e.triangle) break;
        if(local_index(u, b) >= 0) { smallest = false; break; }
      }
      if(smallest) result.push_back(e);
    }
    return result;
  }
  /// the edges whose two triangles traverse them in the same direction (inconsistent
  /// orientation), one `Edge` per edge, the one of the smaller triangle.
  std::vector<Edge> inconsistently_oriented_edges() const
  {
    std::vector<Edge> result;
    for(size_type t = 0; t < triangles_.size(); ++t)
      for(int i = 0; i < 3; ++i) {
        const size_type u = neighbor(t, i);
        if(u >= non_manifold_edge || u < t) continue;
        const int j = edge_index(u, vertex(t, i), vertex(t, (i + 1) % 3));
        if(vertex(u, j) == vertex(t, i)) result.push_back(Edge{t, i});
      }
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
  std::vector<size_type> non_manifold_vertices() const
  {
    std::vector<size_type> result;
    for(size_type v = 0; v < number_of_vertices(); ++v)
      if(degree(v) > 1 && fan_size(v) != degree(v)) result.push_back(v);
    return result;
  }

  /// the number of edge-connected components of the triangles (triangles sharing an edge, manifold
  /// or not, are connected). If `component` is not null it receives, for every triangle, the id
  /// of its component; ids are numbered by their smallest triangle, from 0.
  std::size_t number_of_connected_components(std::vector<size_type>* component = nullptr) const
  {
    std::vector<size_type> cc(triangles_.size(), border_edge);
    std::vector<size_type> stack;
    std::vector<size_type> around_edge;
    size_type count = 0;
    for(size_type seed = 0; seed < triangles_.size(); ++seed) {
      if(cc[seed] != border_edge) continue;
      cc[seed] = count;
      stack.push_back(seed);
      while(!stack.empty()) {
        const size_type t = stack.back();
        stack.pop_back();
        for(int i = 0; i < 3; ++i) {
          const size_type u = neighbor(t, i);
          if(u == border_edge) continue;
          around_edge.clear();
          if(u == non_manifold_edge) triangles_around_edge(t, i, std::back_inserter(around_edge));
          else around_edge.push_back(u);
          for(size_type w : around_edge)
            if(cc[w] == border_edge) { cc[w] = count; stack.push_back(w); }
        }
      }
      ++count;
    }
    if(component != nullptr) component->swap(cc);
    return count;
  }
  /// @}

  /// \name Local updates
  /// @{
  /// replaces every reference to vertex `duplicate` by `original` (the patent's rules (a)-(c)):
  /// the triangle table is rewritten, the triangles of `duplicate` join those of `original` and
  /// the edge neighbours around `original` are recomputed. `duplicate` is left isolated.
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
    const Id_range moved = triangles_around_vertex(duplicate);
    for(size_type t : moved)
      triangles_[t][static_cast<std::size_t>(local_index(t, duplicate))] = original;
    // Merge the two sorted lists into the original's entry.
    merge_buffer_.clear();
    const Id_range kept = triangles_around_vertex(original);
    std::merge(kept.begin(), kept.end(), moved.begin(), moved.end(), std::back_inserter(merge_buffer_));
    assign_list(original, merge_buffer_);
    vertex_size_[duplicate] = 0;
    recompute_edges_around(original);
  }

  /// splits triangle `t` at vertex `v_new` lying on its edge `i` (rule table (15)): `t` keeps its
  /// index with `v_{i+1}` replaced by `v_new`, and a new triangle with `v_i` replaced by `v_new` is
  /// appended. The vertex table is updated by rule table (17) and the edge neighbours of the
  /// touched vertices are recomputed. Returns the index of the new triangle.
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
    Triangle created = old;
    created[si] = v_new;
    triangles_[t][(si + 1) % 3] = v_new;
    const size_type t_new = static_cast<size_type>(triangles_.size());
    triangles_.push_back(created);
    neighbors_.insert(neighbors_.end(), {border_edge, border_edge, border_edge});
    // Rule table (17): v_i keeps t; v_{i+1}: t -> t_new; v_{i+2}: + t_new; v_new: + t, + t_new.
    replace_in_list(vj, t, t_new);
    insert_in_list(vk, t_new);
    insert_in_list(v_new, t);
    insert_in_list(v_new, t_new);
    // Edge neighbours: everything incident to the four vertices involved.
    recompute_edges_around(vi);
    recompute_edges_around(vj);
    recompute_edges_around(vk);
    recompute_edges_around(v_new);
    return t_new;
  }
  /// @}

private:
  // The number of triangles reached from the first triangle of v by crossing manifold edges
  // incident to v, in both directions (the fan of that triangle). Equal to degree(v) exactly when
  // the triangles of v form one fan.
  std::size_t fan_size(size_type v) const
  {
    const Id_range around = triangles_around_vertex(v);
    const size_type start = around[0];
    const std::size_t limit = around.size();
    // Walks from `start` across its edge `first_edge` (incident to v); returns the number of
    // triangles met after `start`, and whether the walk came back to `start`.
    auto walk = [&](int first_edge, bool& closed) {
      std::size_t count = 0;
      size_type t = start;
      int e = first_edge;
      closed = false;
      while(count <= limit) {
        const size_type u = neighbor(t, e);
        if(u >= non_manifold_edge) return count;
        if(u == start) { closed = true; return count; }
        const size_type w = vertex(t, e) == v ? vertex(t, (e + 1) % 3) : vertex(t, e); // the other end
        const int iv = local_index(u, v);
        // the edge of u incident to v that is not {v, w}
        const int crossed = edge_index(u, v, w);
        e = (crossed == iv) ? (iv + 2) % 3 : iv;
        t = u;
        ++count;
      }
      return count;
    };
    const int iv = local_index(start, v);
    bool closed = false;
    const std::size_t forward = walk(iv, closed);
    if(closed) return forward + 1;
    const std::size_t backward = walk((iv + 2) % 3, closed);
    return forward + backward + 1;
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

  void build(std::size_t number_of_points)
  {
    const std::size_t nv = number_of_points;
    vertex_begin_.assign(nv, 0);
    vertex_size_.assign(nv, 0);
    vertex_capacity_.assign(nv, 0);
    for(const Triangle& tr : triangles_)
      for(size_type v : tr) ++vertex_size_[v];
    std::size_t offset = 0;
    for(std::size_t v = 0; v < nv; ++v) {
      vertex_begin_[v] = offset;
      vertex_capacity_[v] = vertex_size_[v];
      offset += vertex_size_[v];
      vertex_size_[v] = 0;
    }
    ids_.resize(offset);
    for(size_type t = 0; t < triangles_.size(); ++t)
      for(size_type v : triangles_[t]) ids_[vertex_begin_[v] + vertex_size_[v]++] = t;
    neighbors_.assign(3 * triangles_.size(), border_edge);
    std::vector<size_type> group;
    for(size_type t = 0; t < triangles_.size(); ++t)
      for(int i = 0; i < 3; ++i)
        if(neighbors_[3 * std::size_t(t) + std::size_t(i)] == border_edge) resolve_edge(t, i, group);
  }

  // Finds every triangle containing edge i of t and writes the neighbour entries of all of them.
  void resolve_edge(size_type t, int i, std::vector<size_type>& group)
  {
    const size_type a = vertex(t, i), b = vertex(t, (i + 1) % 3);
    // Scan the shorter of the two vertex lists.
    const size_type s = degree(a) <= degree(b) ? a : b, o = (s == a) ? b : a;
    group.clear();
    for(size_type u : triangles_around_vertex(s))
      if(local_index(u, o) >= 0) group.push_back(u);
    if(group.size() == 1) {
      neighbors_[3 * std::size_t(t) + std::size_t(i)] = border_edge;
    } else if(group.size() == 2) {
      const size_type u = group[0] == t ? group[1] : group[0];
      neighbors_[3 * std::size_t(t) + std::size_t(i)] = u;
      neighbors_[3 * std::size_t(u) + std::size_t(edge_index(u, a, b))] = t;
    } else {
      for(size_type u : group) neighbors_[3 * std::size_t(u) + std::size_t(edge_index(u, a, b))] = non_manifold_edge;
    }
  }

  void recompute_edges_around(size_type v)
  {
    std::vector<size_type> group;
    for(size_type t : triangles_around_vertex(v)) {
      const int iv = local_index(t, v);
      resolve_edge(t, iv, group);
      resolve_edge(t, (iv + 2) % 3, group);
    }
  }

  // Stores `list` (sorted) as the triangle list of v, moving it to the end of the pool if needed.
  void assign_list(size_type v, const std::vector<size_type>& list)
  {
    if(list.size() > vertex_capacity_[v]) {
      const std::size_t capacity = std::max<std::size_t>(2 * list.size(), 4);
      vertex_begin_[v] = ids_.size();
      vertex_capacity_[v] = static_cast<size_type>(capacity);
      ids_.resize(ids_.size() + capacity, border_edge);
    }
    std::copy(list.begin(), list.end(), ids_.begin() + static_cast<std::ptrdiff_t>(vertex_begin_[v]));
    vertex_size_[v] = static_cast<size_type>(list.size());
  }

  void insert_in_list(size_type v, size_type t)
  {
    const Id_range r = triangles_around_vertex(v);
    merge_buffer_.assign(r.begin(), r.end());
    merge_buffer_.insert(std::upper_bound(merge_buffer_.begin(), merge_buffer_.end(), t), t);
    assign_list(v, merge_buffer_);
  }

  void replace_in_list(size_type v, size_type old_t, size_type new_t)
  {
    const Id_range r = triangles_around_vertex(v);
    merge_buffer_.clear();
    for(size_type u : r) if(u != old_t) merge_buffer_.push_back(u);
    merge_buffer_.insert(std::upper_bound(merge_buffer_.begin(), merge_buffer_.end(), new_t), new_t);
    assign_list(v, merge_buffer_);
  }

  std::vector<Triangle> triangles_;
  // Vertex table: compressed rows with spare capacity; a row that outgrows its capacity moves to
  // the end of `ids_` (amortised constant time per insertion).
  std::vector<std::size_t> vertex_begin_;
  std::vector<size_type> vertex_size_;
  std::vector<size_type> vertex_capacity_;
  std::vector<size_type> ids_;
  // Edge table: neighbors_[3 t + i] is the neighbour of t across its edge i.
  std::vector<size_type> neighbors_;
  std::vector<size_type> merge_buffer_;
};

} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_ADJACENCY_TABLES_H
