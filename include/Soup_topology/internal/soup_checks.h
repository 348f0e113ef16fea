// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Validation of indexed triangle soups, shared by every public entry point.

#ifndef SOUP_TOPOLOGY_INTERNAL_SOUP_CHECKS_H
#define SOUP_TOPOLOGY_INTERNAL_SOUP_CHECKS_H

#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/internal/parallel.h>

#include <CGAL/number_utils.h>
#include <CGAL/tags.h>

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>

namespace Soup_topology {
namespace internal {

/// number of corners of a face of a `FaceRange`, whatever its type.
template <class Face>
std::size_t face_size(const Face& f)
{
  return static_cast<std::size_t>(std::distance(std::begin(f), std::end(f)));
}

/// index of corner `k` of face `f`, as `std::size_t`; throws on a negative index.
template <class Face>
std::size_t corner(const Face& f, std::size_t k, std::size_t face_id)
{
  auto it = std::begin(f);
  std::advance(it, static_cast<std::ptrdiff_t>(k));
  const auto value = *it;
  if constexpr(std::is_signed<std::decay_t<decltype(value)>>::value) {
    if(value < 0)
      throw Invalid_input("face " + std::to_string(face_id) + ": negative vertex index " +
                          std::to_string(static_cast<long long>(value)));
  }
  return static_cast<std::size_t>(value);
}

/// the three indices of the triangle `f` of any `FaceRange` type, as `std::size_t` (unchecked).
template <class Face>
std::array<std::size_t, 3> triangle_indices(const Face& f)
{
  auto it = std::begin(f);
  const std::size_t a = static_cast<std::size_t>(*it++), b = static_cast<std::size_t>(*it++);
  return {a, b, static_cast<std::size_t>(*it)};
}

/// `v` as the index type `Index` of a face; throws `Invalid_input` if an integer `Index` cannot
/// hold it (a soup read into 4-byte or 2-byte indices with more points than they count).
template <class Index>
Index narrow_vertex_index(std::size_t v)
{
  if constexpr(std::is_integral<Index>::value) {
    constexpr auto largest = static_cast<std::make_unsigned_t<Index>>(std::numeric_limits<Index>::max());
    if constexpr(largest < std::numeric_limits<std::size_t>::max()) {
      if(v > largest)
        throw Invalid_input("vertex index " + std::to_string(v) + " does not fit in the index type of the triangles (at most " +
                            std::to_string(largest) + ")");
    }
  }
  return static_cast<Index>(v);
}

/// writes the three indices of a triangle into a face of any `FaceRange` type (checked: see
/// `narrow_vertex_index()`).
template <class Face>
void assign_triangle(Face& f, std::size_t a, std::size_t b, std::size_t c)
{
  using Index = std::decay_t<decltype(*std::begin(f))>;
  auto it = std::begin(f);
  *it++ = narrow_vertex_index<Index>(a);
  *it++ = narrow_vertex_index<Index>(b);
  *it = narrow_vertex_index<Index>(c);
}
template <class Face, class = void>
struct has_resize : std::false_type {};
template <class Face>
struct has_resize<Face, std::void_t<decltype(std::declval<Face&>().resize(3))>> : std::true_type {};

template <class Face>
Face make_triangle(std::size_t a, std::size_t b, std::size_t c)
{
  Face f;
  if constexpr(has_resize<Face>::value) f.resize(3); // std::vector-like faces
  assign_triangle(f, a, b, c);
  return f;
}

/// throws `Invalid_input` if the vertex index `v` of face `face_id` is not below `number_of_points`.
inline void check_vertex_index(std::size_t v, std::size_t number_of_points, std::size_t face_id)
{
  if(v >= number_of_points)
    throw Invalid_input("face " + std::to_string(face_id) + ": vertex index " + std::to_string(v) +
                        " is out of range (" + std::to_string(number_of_points) + " points)");
}

/// throws `Invalid_input` if the face `f`, number `face_id`, is not a triangle of three distinct
/// vertex indices below `number_of_points`.
template <class Face>
void check_triangle(const Face& f, std::size_t face_id, std::size_t number_of_points)
{
  const std::size_t n = face_size(f);
  if(n != 3)
    throw Invalid_input("face " + std::to_string(face_id) + " has " + std::to_string(n) +
                        " vertices; a triangle soup needs exactly 3");
  std::size_t v[3];
  for(std::size_t k = 0; k < 3; ++k) {
    v[k] = corner(f, k, face_id);
    check_vertex_index(v[k], number_of_points, face_id);
  }
  if(v[0] == v[1] || v[1] == v[2] || v[2] == v[0])
    throw Invalid_input("face " + std::to_string(face_id) + " repeats a vertex index (" + std::to_string(v[0]) +
                        ", " + std::to_string(v[1]) + ", " + std::to_string(v[2]) + ")");
}

/// `true` if `check_triangle(f, face_id, number_of_points)` would not throw, without building a
/// message: the face is a triangle of three distinct vertex indices below `number_of_points`,
/// which `v` receives. (A negative index converts to a `std::size_t` above any number of points.)
template <class Face>
bool is_triangle_of_distinct_indices(const Face& f, std::size_t number_of_points, std::array<std::size_t, 3>& v)
{
  if(face_size(f) != 3) return false;
  auto it = std::begin(f);
  for(std::size_t k = 0; k < 3; ++k, ++it) {
    v[k] = static_cast<std::size_t>(*it);
    if(v[k] >= number_of_points) return false;
  }
  return v[0] != v[1] && v[1] != v[2] && v[2] != v[0];
}

/// `true` if `check_triangle_soup()` accepts the sizes of a soup of `number_of_points` points and
/// `number_of_faces` faces (their indices are stored on 32 bits).
inline bool fits_in_32_bit_indices(std::size_t number_of_points, std::size_t number_of_faces)
{
  constexpr std::size_t limit = static_cast<std::size_t>(std::numeric_limits<std::uint32_t>::max() - 2);
  return number_of_points < limit && number_of_faces < limit;
}

/// `true` if the iterators of `Range` are random access.
template <class Range>
constexpr bool has_random_access()
{
  using Iterator = decltype(std::begin(std::declval<const Range&>()));
  return std::is_base_of<std::random_access_iterator_tag,
                         typename std::iterator_traits<Iterator>::iterator_category>::value;
}

/// throws `Invalid_input` naming the first face that is not a triangle of three distinct,
/// in-range vertex indices. Reads only: the caller's data is never changed. With a parallel
/// `ConcurrencyTag` (and a random-access range) the faces are checked by blocks, and the first
/// bad face is checked again alone: the same face and the same message as sequentially.
template <class ConcurrencyTag = CGAL::Sequential_tag, class FaceRange>
void check_triangle_soup(const FaceRange& faces, std::size_t number_of_points)
{
  if(number_of_points >= static_cast<std::size_t>(std::numeric_limits<std::uint32_t>::max() - 2))
    throw Invalid_input("too many points (" + std::to_string(number_of_points) +
                        "): indices are stored on 32 bits");
  std::size_t face_id = 0;
  if constexpr(runs_in_parallel<ConcurrencyTag>() && has_random_access<FaceRange>()) {
    const auto first = std::begin(faces);
    const std::size_t m = static_cast<std::size_t>(std::distance(first, std::end(faces)));
    auto face = [&](std::size_t i) -> decltype(auto) { return *(first + static_cast<std::ptrdiff_t>(i)); };
    const std::size_t bad = first_index_where<ConcurrencyTag>(m, [&](std::size_t i) {
      try {
        check_triangle(face(i), i, number_of_points);
        return false;
      } catch(const Invalid_input&) {
        return true;
      }
    });
    if(bad != m) check_triangle(face(bad), bad, number_of_points);
    face_id = m;
  } else {
    for(const auto& f : faces) {
      check_triangle(f, face_id, number_of_points);
      ++face_id;
    }
  }
  if(face_id >= static_cast<std::size_t>(std::numeric_limits<std::uint32_t>::max() - 2))
    throw Invalid_input("too many triangles (" + std::to_string(face_id) +
                        "): indices are stored on 32 bits");
}

/// throws `Invalid_input` naming the first point with a NaN or infinite coordinate (checked by
/// blocks with a parallel `ConcurrencyTag`, a random-access range and `double` coordinates: the
/// same point named).
template <class ConcurrencyTag = CGAL::Sequential_tag, class PointRange, class PointMap>
void check_finite_points(const PointRange& points, const PointMap& point_map)
{
  using Point = std::decay_t<decltype(get(point_map, *std::begin(points)))>;
  // (lazily exact coordinates are read on one thread: reading them may update shared state)
  if constexpr(runs_in_parallel<ConcurrencyTag>() && has_random_access<PointRange>() &&
               std::is_same<std::decay_t<decltype(std::declval<const Point&>().x())>, double>::value) {
    const auto first = std::begin(points);
    const std::size_t n = static_cast<std::size_t>(std::distance(first, std::end(points)));
    const std::size_t bad = first_index_where<ConcurrencyTag>(n, [&](std::size_t k) {
      const auto& q = get(point_map, *(first + static_cast<std::ptrdiff_t>(k)));
      return !(std::isfinite(q.x()) && std::isfinite(q.y()) && std::isfinite(q.z()));
    });
    if(bad != n) throw Invalid_input("point " + std::to_string(bad) + " has a non-finite coordinate");
    return;
  }
  std::size_t i = 0;
  for(const auto& p : points) {
    const auto& q = get(point_map, p);
    const double c[3] = {CGAL::to_double(q.x()), CGAL::to_double(q.y()), CGAL::to_double(q.z())};
    for(double x : c)
      if(!std::isfinite(x))
        throw Invalid_input("point " + std::to_string(i) + " has a non-finite coordinate");
    ++i;
  }
}

/// throws `Invalid_input` as `check_triangle_soup()` and `check_finite_points()` do: the one
/// validation of an indexed soup (`faces` over the points of `points` read through `point_map`).
template <class ConcurrencyTag = CGAL::Sequential_tag, class PointRange, class PointMap, class FaceRange>
void check_indexed_soup(const PointRange& points, const PointMap& point_map, const FaceRange& faces)
{
  check_triangle_soup<ConcurrencyTag>(faces, static_cast<std::size_t>(std::distance(std::begin(points), std::end(points))));
  check_finite_points<ConcurrencyTag>(points, point_map);
}

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_SOUP_CHECKS_H
