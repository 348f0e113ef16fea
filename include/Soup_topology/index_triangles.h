// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Pipeline step 0: the index representation of a soup of explicit triangles, and the exact weld
// of an indexed soup.

#ifndef SOUP_TOPOLOGY_INDEX_TRIANGLES_H
#define SOUP_TOPOLOGY_INDEX_TRIANGLES_H

#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/internal/Point_hash_map.h>
#include <Soup_topology/internal/first_equal_points_by_blocks.h>
#include <Soup_topology/internal/parallel.h>
#include <Soup_topology/internal/soup_checks.h>
#include <Soup_topology/internal/uninitialized_vector.h>

#include <CGAL/tags.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <limits>
#include <numeric>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace Soup_topology {

/// \ingroup PkgSoupTopologyRef
/// \brief what `index_triangles()` found.
struct Index_report
{
  std::size_t input_triangles = 0;       ///< triangles read
  std::size_t input_corners = 0;         ///< 3 x `input_triangles`
  std::size_t vertices = 0;              ///< distinct points, i.e. the size of the point range
  std::size_t collapsed_triangles = 0;   ///< triangles dropped because two corners are equal
};



namespace internal {

/// `true` if the points of type `Point` are read and copied in parallel with `ConcurrencyTag`:
/// only for coordinates stored as `double` (lazily exact numbers share state between copies).
template <class ConcurrencyTag, class Point>
constexpr bool runs_in_parallel_on_points()
{
  return runs_in_parallel<ConcurrencyTag>() &&
         std::is_same<typename CGAL::Kernel_traits<Point>::Kernel::FT, double>::value;
}

/// `ConcurrencyTag` where points of type `Point` are read and welded in parallel (see
/// `runs_in_parallel_on_points()`), `CGAL::Sequential_tag` otherwise.
template <class ConcurrencyTag, class Point>
using Point_concurrency =
  std::conditional_t<runs_in_parallel_on_points<ConcurrencyTag, Point>(), ConcurrencyTag, CGAL::Sequential_tag>;

/// calls `refuse_non_finite()` if the weld found a NaN or infinite coordinate; it must throw, and
/// if it does not, `Invalid_input` is thrown all the same.
template <class RefuseNonFinite>
void refuse_if_non_finite(const Exact_weld_extras& weld, const RefuseNonFinite& refuse_non_finite)
{
  if(weld.all_finite) return;
  refuse_non_finite();
  throw Invalid_input("non-finite coordinate");
}

/// `index_corners()` computed in parallel (see `first_equal_points_by_blocks()`): the points
/// are numbered by the rank of their first corner, found by prefix sums over blocks, so the
/// points, the triangles and their order are those of the sequential pass. Three passes follow
/// the weld, each by blocks: the first corners numbered and their points copied (the weld counted
/// them by blocks); the later corners numbered from their first corners, the triangles that keep
/// three distinct points counted by blocks; the kept triangles written. `refuse_non_finite()` is
/// called (and must throw) if a corner has a NaN or infinite coordinate, before `points` and
/// `faces` are touched.
template <class ConcurrencyTag, class CornerAccess, class PointRange, class FaceRange, class RefuseNonFinite>
void index_corners_in_parallel(std::size_t corners, const CornerAccess& corner_point, PointRange& points,
                               FaceRange& faces, Index_report& report, const RefuseNonFinite& refuse_non_finite)
{
  using Face = typename FaceRange::value_type;
  constexpr std::size_t block_size = default_block_size;
  Exact_weld_extras weld;
  // (without the weld's last pass: the later corners below are renumbered in increasing order
  // within their blocks, so that a corner reads the number of the entry it names)
  weld.links_to_block_representatives = true;
  const Uninitialized_vector<std::uint32_t> first_of =
    first_equal_points_by_blocks<ConcurrencyTag>(corners, corner_point, 0, &weld);
  refuse_if_non_finite(weld, refuse_non_finite);
  // the first corners of every block of corners, then the number of the block's first point
  std::vector<std::size_t>& point_place = weld.firsts_by_block;
  const std::size_t distinct = exclusive_prefix_sums(point_place);
  Uninitialized_vector<std::uint32_t> point_of(corners); // the first corners first, then the others
  fault_in_pages(point_of);
  points.clear();
  resize_in_huge_pages(points, distinct);
  for_each_block<ConcurrencyTag>(corners, block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
    std::size_t position = point_place[b];
    for(std::size_t i = begin; i != end; ++i) {
      if(first_of[i] != i) continue;
      points[position] = corner_point(i);
      point_of[i] = static_cast<std::uint32_t>(position++);
    }
  });
  // every first corner has its number now: the later corners read it; blocks of whole triangles
  // (three blocks of corners each: a corner's entry names a first corner or an earlier corner of
  // its block of corners, numbered before it)
  const std::size_t m = corners / 3;
  std::vector<std::size_t> face_place(number_of_blocks(m, block_size), 0);
  for_each_block<ConcurrencyTag>(m, block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
    std::size_t kept = 0;
    for(std::size_t k = begin; k != end; ++k) {
      for(std::size_t i = 3 * k; i != 3 * k + 3; ++i)
        if(first_of[i] != i) point_of[i] = point_of[first_of[i]];
      const std::uint32_t a = point_of[3 * k], c = point_of[3 * k + 1], d = point_of[3 * k + 2];
      kept += a != c && c != d && d != a ? 1u : 0u;
    }
    face_place[b] = kept;
  });
  const std::size_t kept_count = exclusive_prefix_sums(face_place);
  faces.clear();
  resize_in_huge_pages(faces, kept_count);
  for_each_block<ConcurrencyTag>(m, block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
    std::size_t position = face_place[b];
    for(std::size_t k = begin; k != end; ++k) {
      const std::uint32_t a = point_of[3 * k], c = point_of[3 * k + 1], d = point_of[3 * k + 2];
      if(a != c && c != d && d != a) faces[position++] = make_triangle<Face>(a, c, d);
    }
  });
  report.collapsed_triangles += m - kept_count;
  report.vertices = points.size();
}

/// the exact weld of `corners` corners, corner `i` being `corner_point(i)` (triangle `i / 3`):
/// `points` receives the distinct points in order of first appearance, `faces` the triangles of
/// three distinct points (both cleared first); `report` receives the counts of points and
/// collapsed triangles. `corners` is a multiple of 3 below 2^32. `refuse_non_finite()` is called
/// (and must throw) if a corner has a NaN or infinite coordinate, before `points` and `faces` are
/// touched: the weld's first pass tests the coordinates it reads.
template <class CornerAccess, class PointRange, class FaceRange, class RefuseNonFinite>
void index_corners(std::size_t corners, const CornerAccess& corner_point, PointRange& points, FaceRange& faces,
                   Index_report& report, const RefuseNonFinite& refuse_non_finite)
{
  using Face = typename FaceRange::value_type;
  // point_of[i] is i for the first corner of each point, else an earlier corner equal to corner i
  // (`Exact_weld_extras::links_to_block_representatives`); it is overwritten in place by the
  // index of the point of corner i (the entry a corner names is renumbered before it).
  Exact_weld_extras weld;
  weld.links_to_block_representatives = true;
  Uninitialized_vector<std::uint32_t> point_of =
    first_equal_points_by_blocks<CGAL::Sequential_tag>(corners, corner_point, 0, &weld);
  refuse_if_non_finite(weld, refuse_non_finite);
  // The points are counted by the weld, so that `points` holds exactly them, without the spare
  // room of a vector grown one point at a time.
  std::size_t distinct = 0;
  for(const std::size_t firsts : weld.firsts_by_block) distinct += firsts;
  points.clear();
  reserve_in_huge_pages(points, distinct);
  for(std::size_t i = 0; i < corners; ++i) {
    if(point_of[i] == i) {
      point_of[i] = static_cast<std::uint32_t>(points.size());
      points.push_back(corner_point(i));
    } else {
      point_of[i] = point_of[point_of[i]];
    }
  }
  faces.clear();
  reserve_in_huge_pages(faces, corners / 3);
  for(std::size_t k = 0; k < corners / 3; ++k) {
    const std::size_t a = point_of[3 * k], b = point_of[3 * k + 1], c = point_of[3 * k + 2];
    if(a == b || b == c || c == a) { ++report.collapsed_triangles; continue; }
    faces.push_back(make_triangle<Face>(a, b, c));
  }
  report.vertices = points.size();
}

} // namespace internal

/// \ingroup PkgSoupTopologyRef
/// \brief builds the index representation (patent, Figure 2) of a soup of explicit triangles,
/// such as an STL file gives: a point range of distinct points and a face range of index
/// triples, merging exactly equal coordinates.
///
/// Vertex indices follow the order of first appearance in `triangles` (corner by corner), so the
/// result is deterministic. Triangles with two equal corners cannot be represented by three
/// distinct indices: they are left out and counted in `Index_report::collapsed_triangles`.
/// Expected linear time for kernels whose coordinates are `double` (hashing); O(n log n) for
/// exact number types (sorting).
///
/// With `CGAL::Parallel_tag` the weld runs on TBB's threads (`doc/Soup_topology/Parallel.md`); the
/// result is the same, bit for bit and in the same order, on any number of threads.
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` (the default), `CGAL::Parallel_tag` (needs TBB)
///         or `CGAL::Parallel_if_available_tag`
/// \tparam TriangleRange a range whose elements are ranges of 3 `Point_3`
///         (`std::array<Point_3,3>`, ...)
/// \tparam PointRange a `std::vector`-like container of the same `Point_3`
/// \tparam FaceRange a `std::vector`-like container of triangles (`std::array<std::size_t,3>`,
///         `std::vector<std::size_t>`, ...)
/// \param triangles the input triangles (not modified)
/// \param points receives the distinct points (cleared first)
/// \param faces receives the triangles (cleared first)
/// \throws Invalid_input if an element of `triangles` does not have 3 points, or if a corner has a
///         NaN or infinite coordinate (the message names the triangle and the corner);
///         `points` and `faces` are unchanged then.
template <class ConcurrencyTag = CGAL::Sequential_tag, class TriangleRange, class PointRange, class FaceRange>
Index_report index_triangles(const TriangleRange& triangles, PointRange& points, FaceRange& faces)
{
  using Point = typename PointRange::value_type;
  Index_report report;
  std::size_t t = 0;
  for(const auto& tr : triangles) {
    if(internal::face_size(tr) != 3)
      throw Invalid_input("triangle " + std::to_string(t) + " has " + std::to_string(internal::face_size(tr)) +
                          " corners; expected 3");
    ++t;
  }
  report.input_triangles = t;
  report.input_corners = 3 * t;
  if(report.input_corners >= std::size_t(0xFFFFFFF0u))
    throw Invalid_input("too many corners (" + std::to_string(report.input_corners) + ") for 32-bit indices");
  // The corners are read in place when the range is random access, copied once otherwise.
  using Triangle_iterator = decltype(std::begin(triangles));
  constexpr bool random_access = std::is_base_of<std::random_access_iterator_tag,
    typename std::iterator_traits<Triangle_iterator>::iterator_category>::value;
  std::vector<Point> copied;
  if constexpr(!random_access) {
    copied.reserve(report.input_corners);
    for(const auto& tr : triangles) for(const auto& p : tr) copied.push_back(p);
  }
  auto corner_point = [&](std::size_t i) -> const Point& {
    if constexpr(random_access) {
      const auto& tr = *(std::begin(triangles) + static_cast<std::ptrdiff_t>(i / 3));
      return *(std::begin(tr) + static_cast<std::ptrdiff_t>(i % 3));
    } else {
      return copied[i];
    }
  };
  const std::size_t corners = report.input_corners;
  // Points of exact number types are handled sequentially (see `runs_in_parallel_on_points()`).
  using Tag = std::conditional_t<internal::runs_in_parallel_on_points<ConcurrencyTag, Point>(), ConcurrencyTag,
                                 CGAL::Sequential_tag>;
  // A NaN equals nothing, not even itself: it would silently make a point of its own. The weld
  // tests the coordinates as it reads them; if one is not finite, the first such corner is named.
  const auto refuse_non_finite = [&] {
    const std::size_t bad = internal::first_index_where<Tag>(
      corners, [&](std::size_t i) { return !internal::is_finite_point(corner_point(i)); });
    throw Invalid_input("triangle " + std::to_string(bad / 3) + ", corner " + std::to_string(bad % 3) +
                        ": non-finite coordinate");
  };
  // (on one thread, the sequential pass: it renumbers in place, with fewer arrays to fill)
  if(internal::runs_on_several_threads<Tag>())
    internal::index_corners_in_parallel<Tag>(corners, corner_point, points, faces, report, refuse_non_finite);
  else
    internal::index_corners(corners, corner_point, points, faces, report, refuse_non_finite);
  return report;
}

namespace internal {

// merge_duplicate_points(), returning the new index of every old point.
template <class ConcurrencyTag = CGAL::Sequential_tag, class PointRange, class FaceRange>
std::vector<std::size_t> merge_duplicate_points_and_map(PointRange& points, FaceRange& faces)
{
  using Point = typename PointRange::value_type;
  using Tag = Point_concurrency<ConcurrencyTag, Point>;
  const std::size_t n = points.size();
  // the indices checked by blocks (the faces of random-access ranges), the first bad face again
  // alone: the message of the sequential check
  const auto check_face = [n](const auto& f, std::size_t face_id) {
    for(std::size_t k = 0; k < face_size(f); ++k) check_vertex_index(corner(f, k, face_id), n, face_id);
  };
  if constexpr(runs_in_parallel<ConcurrencyTag>() && has_random_access<FaceRange>()) {
    const std::size_t m = faces.size();
    const std::size_t bad_face = first_index_where<ConcurrencyTag>(m, [&](std::size_t f) {
      try {
        check_face(faces[f], f);
        return false;
      } catch(const Invalid_input&) {
        return true;
      }
    });
    if(bad_face != m) check_face(faces[bad_face], bad_face);
  } else {
    std::size_t face_id = 0;
    for(const auto& f : faces) check_face(f, face_id++);
  }
  if(n >= std::size_t(0xFFFFFFF0u))
    throw Invalid_input("too many points (" + std::to_string(n) + ") for 32-bit indices");
  // A NaN equals nothing, not even itself: it would silently make a point of its own. The weld
  // tests the coordinates as it reads them; if one is not finite, the first such point is named.
  Exact_weld_extras weld;
  const Uninitialized_vector<std::uint32_t> first_of =
    first_equal_points_by_blocks<Tag>(n, [&](std::size_t i) -> const Point& { return points[i]; }, 0, &weld);
  refuse_if_non_finite(weld, [&] {
    const std::size_t bad = first_index_where<Tag>(n, [&](std::size_t i) { return !is_finite_point(points[i]); });
    throw Invalid_input("point " + std::to_string(bad) + " has a non-finite coordinate");
  });
  std::vector<std::size_t> new_index(n);
  if constexpr(runs_in_parallel<Tag>()) {
    // the kept points are numbered by prefix sums over blocks and copied out of place
    const std::size_t kept = compact_in_order<Tag>(
      n, [&](std::size_t i) { return first_of[i] == i; },
      [&](std::size_t i, std::size_t position) { new_index[i] = position; });
    for_each_index<Tag>(n, [&](std::size_t i) {
      if(first_of[i] != i) new_index[i] = new_index[first_of[i]];
    });
    if(kept != n) {
      PointRange compacted;
      compacted.resize(kept);
      for_each_index<Tag>(n, [&](std::size_t i) {
        if(first_of[i] == i) compacted[new_index[i]] = points[i];
      });
      points.swap(compacted);
    }
    for_each_index<Tag>(faces.size(), [&](std::size_t f) {
      for(auto& v : faces[f]) v = static_cast<std::decay_t<decltype(v)>>(new_index[static_cast<std::size_t>(v)]);
    });
    return new_index;
  }
  std::size_t kept = 0;
  for(std::size_t i = 0; i < n; ++i) {
    if(first_of[i] == i) {
      new_index[i] = kept;
      if(kept != i) points[kept] = points[i];
      ++kept;
    } else {
      new_index[i] = new_index[first_of[i]];
    }
  }
  points.resize(kept);
  for(auto& f : faces)
    for(auto& v : f) v = static_cast<std::decay_t<decltype(v)>>(new_index[static_cast<std::size_t>(v)]);
  return new_index;
}

} // namespace internal

/// \ingroup PkgSoupTopologyRef
/// \brief merges the points of an indexed soup that have exactly the same coordinates: every
/// face refers to the first of equal points afterwards, and the later copies are removed from
/// `points` (the remaining points keep their relative order).
///
/// Faces may be polygons of any size. Faces that end up with a repeated index are not removed
/// here (see `remove_collapsed_triangles()`).
/// \tparam PointRange a `std::vector`-like container of `Point_3`
/// \tparam FaceRange a random-access range of faces, each a range of vertex indices
/// \param points the points, the later copies of equal points removed
/// \param faces the faces, renumbered
/// \returns the number of points removed.
/// \throws Invalid_input if an index is out of range, or if a point has a NaN or infinite
///         coordinate (the message names it); nothing is changed then.
template <class PointRange, class FaceRange>
std::size_t merge_duplicate_points(PointRange& points, FaceRange& faces)
{
  const std::size_t before = points.size();
  internal::merge_duplicate_points_and_map(points, faces);
  return before - points.size();
}

/// \ingroup PkgSoupTopologyRef
/// \brief removes the triangles that repeat a vertex index (collapsed by a weld).
/// \param faces the triangles, the collapsed ones removed (the others keep their order)
/// \returns the number of triangles removed.
template <class FaceRange>
std::size_t remove_collapsed_triangles(FaceRange& faces)
{
  const std::size_t before = faces.size();
  faces.erase(std::remove_if(faces.begin(), faces.end(),
                             [](const auto& f) {
                               auto it = std::begin(f);
                               const auto a = *it++, b = *it++, c = *it;
                               return a == b || b == c || c == a;
                             }),
              faces.end());
  return before - faces.size();
}

} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INDEX_TRIANGLES_H
