// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Writing an indexed triangle soup (points and index triples) as OFF, OBJ, PLY or binary STL,
// without building a mesh first: what is written is exactly the soup, in its order.
//
// Why not a CGAL mesh and `CGAL::IO::write_polygon_mesh()`: the soup is already what a file
// holds (a point list and index triples), a mesh of 1M triangles costs time and memory only to
// be walked back into the same lists, and CGAL's STL writer rounds to float without saying
// what the rounding did. Here STL output is refused when float rounding would make a coordinate
// infinite, merge two distinct points, or make a triangle degenerate or flip.

#ifndef SOUP_TOPOLOGY_IO_WRITE_TRIANGLE_SOUP_H
#define SOUP_TOPOLOGY_IO_WRITE_TRIANGLE_SOUP_H

#include <Soup_topology/IO/Read_error.h>
#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/internal/Point_hash_map.h>
#include <Soup_topology/internal/first_equal_points_by_blocks.h>
#include <Soup_topology/internal/parallel.h>
#include <Soup_topology/internal/soup_checks.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Kernel_traits.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <ostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace Soup_topology {
namespace IO {

namespace internal {

// The three coordinates of point `p` as doubles.
template <class Point>
std::array<double, 3> write_coordinates(const Point& p)
{
  return {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
}

// `x` rounded to the nearest float, as a double. Through a volatile float: GCC 12.2 at -O3
// (x86-64) vectorizes the conversions of neighbouring coordinates to float and back into a plain
// copy, which leaves them unrounded (seen when this check was first run by blocks).
inline double rounded_to_float(double x)
{
  volatile float f = static_cast<float>(x);
  return f;
}

// Whether the iterators of `Range` are random-access (the triangles can be checked and written
// by blocks).
template <class Range>
using is_random_access_range = std::is_base_of<
  std::random_access_iterator_tag,
  typename std::iterator_traits<decltype(std::begin(std::declval<const Range&>()))>::iterator_category>;

// Calls `f(a, b, c)` with the indices of every triangle, as `std::size_t`, in order; the soup
// must have been checked (`check_triangle_soup()`).
template <class TriangleRange, class Function>
void for_each_triangle(const TriangleRange& triangles, const Function& f)
{
  for(const auto& t : triangles) {
    const std::array<std::size_t, 3> v = Soup_topology::internal::triangle_indices(t);
    f(v[0], v[1], v[2]);
  }
}

// Whether two of the points `order` lists have different coordinates (as doubles) but equal
// `rounded` points; `rounded[i]` is point i rounded to float. The points equal in float are found
// as the exact weld finds equal points (`first_equal_points_by_blocks()`, on TBB's threads with
// the tag), each compared with the first of its kind.
template <class ConcurrencyTag, class PointRange, class Float_point>
bool has_distinct_points_equal_in_float(const PointRange& points, const std::vector<Float_point>& rounded,
                                        const std::vector<std::size_t>& order)
{
  const auto first_of = Soup_topology::internal::first_equal_points_by_blocks<ConcurrencyTag>(
    order.size(), [&](std::size_t k) -> const Float_point& { return rounded[order[k]]; });
  const auto moves = [&](std::size_t k) {
    return first_of[k] != k && write_coordinates(points[order[first_of[k]]]) != write_coordinates(points[order[k]]);
  };
  return Soup_topology::internal::first_index_where<ConcurrencyTag>(order.size(), moves) != order.size();
}

template <class PointRange>
void check_finite_for_writing(const PointRange& points)
{
  std::size_t i = 0;
  for(const auto& p : points) {
    for(double c : write_coordinates(p))
      if(!std::isfinite(c)) throw Write_error("point " + std::to_string(i) + " has a non-finite coordinate");
    ++i;
  }
}

// Text buffer with the number formats of the text writers: doubles with 17 significant
// digits (enough to read back the same double), integers in decimal.
class Text_line
{
public:
  Text_line& operator<<(const char* s) { text_.append(s); return *this; }
  Text_line& operator<<(char c) { text_.push_back(c); return *this; }
  Text_line& integer(std::size_t v)
  {
    char buffer[24];
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
    text_.append(buffer, end);
    return *this;
  }
  Text_line& real(double v, int precision)
  {
    char buffer[64];
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, v, std::chars_format::general, precision).ptr;
    text_.append(buffer, end);
    return *this;
  }
  // Sends the text to `os` once it is large, so that a 1M-triangle file is not held twice.
  void flush_to(std::ostream& os, bool force = false)
  {
    if(force || text_.size() > (1u << 16)) {
      os.write(text_.data(), static_cast<std::streamsize>(text_.size()));
      text_.clear();
    }
  }

private:
  std::string text_;
};

// Writes one line per point: `prefix` and the three coordinates.
template <class PointRange>
void write_text_points(std::ostream& os, Text_line& t, const PointRange& points, const char* prefix, int precision)
{
  for(const auto& p : points) {
    const auto c = write_coordinates(p);
    t << prefix;
    t.real(c[0], precision) << ' ';
    t.real(c[1], precision) << ' ';
    t.real(c[2], precision) << '\n';
    t.flush_to(os);
  }
}

// Writes one line per triangle: `prefix` and the three indices plus `first_index`.
template <class TriangleRange>
void write_text_triangles(std::ostream& os, Text_line& t, const TriangleRange& triangles, const char* prefix,
                          std::size_t first_index)
{
  for_each_triangle(triangles, [&](std::size_t a, std::size_t b, std::size_t c) {
    t << prefix;
    t.integer(a + first_index) << ' ';
    t.integer(b + first_index) << ' ';
    t.integer(c + first_index) << '\n';
    t.flush_to(os);
  });
}

// What every writer does first: the triangles checked, the points checked finite; returns
// the number of triangles.
template <class PointRange, class TriangleRange>
std::size_t check_soup_for_writing(const PointRange& points, const TriangleRange& triangles)
{
  Soup_topology::internal::check_triangle_soup(triangles, points.size());
  check_finite_for_writing(points);
  return static_cast<std::size_t>(std::distance(std::begin(triangles), std::end(triangles)));
}

// The number of significant digits given by `np` (`stream_precision`), 17 by default.
template <class NamedParameters>
int stream_precision(const NamedParameters& np)
{
  return CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, CGAL::internal_np::stream_precision), 17);
}

inline void check_stream(const std::ostream& os)
{
  if(!os) throw Write_error("the write failed");
}

constexpr bool big_endian_host()
{
#if defined(__BYTE_ORDER__) && defined(__ORDER_BIG_ENDIAN__)
  return __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__;
#else
  return false;
#endif
}

template <class T>
void put_little_endian(std::string& out, T value)
{
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if(big_endian_host()) std::reverse(bytes, bytes + sizeof(T));
  out.append(reinterpret_cast<const char*>(bytes), sizeof(T));
}

} // namespace internal

/// \ingroup PkgSoupTopologyIO
/// \brief checks that writing the soup as STL, whose coordinates are 32-bit floats, keeps it:
/// throws `Write_error` naming the first point whose coordinate rounds to infinity, the first two
/// distinct points that round to the same float point, or the first triangle that becomes
/// degenerate (collinear corners) or flips (its normal turns by more than 90 degrees) once its
/// corners are rounded. The message suggests OFF or PLY, which keep doubles.
///
/// Only points used by a triangle are checked. Triangles already degenerate before rounding are
/// not refused, since rounding did not make them so.
///
/// \tparam ConcurrencyTag with `CGAL::Parallel_tag`, the points and the triangles (of a
///         random-access range, with `double` coordinates) are checked by blocks on TBB's threads;
///         the first refusal in the order of the points, then of the triangles, is the one thrown,
///         as sequentially
/// \tparam PointRange a random-access range of `Point_3`
/// \tparam TriangleRange a range of faces of 3 indices
/// \param points the points of the soup
/// \param triangles the triangles of the soup
/// \param np an optional sequence of named parameters among the ones listed below
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{geom_traits}
///     \cgalParamDescription{the predicate `Collinear_3` that tells which triangles were degenerate before rounding}
///     \cgalParamType{a model of `SoupTopologyTraits`}
///     \cgalParamDefault{the kernel of the point type}
///   \cgalParamNEnd
/// \cgalNamedParamsEnd
template <class ConcurrencyTag = CGAL::Sequential_tag, class PointRange, class TriangleRange,
          class NamedParameters = CGAL::parameters::Default_named_parameters>
void check_STL_float_rounding(const PointRange& points, const TriangleRange& triangles,
                              const NamedParameters& np = CGAL::parameters::default_values())
{
  using Point = typename PointRange::value_type;
  using Geom_traits = typename CGAL::internal_np::Lookup_named_param_def<
    CGAL::internal_np::geom_traits_t, NamedParameters, typename CGAL::Kernel_traits<Point>::Kernel>::type;
  using Float_point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;
  const Geom_traits gt =
    CGAL::parameters::choose_parameter<Geom_traits>(CGAL::parameters::get_parameter(np, CGAL::internal_np::geom_traits));
  // Points other than `double` ones (lazily exact numbers) and ranges without random access
  // are checked on one thread.
  using Tag = std::conditional_t<std::is_same<typename Geom_traits::FT, double>::value &&
                                   internal::is_random_access_range<TriangleRange>::value,
                                 ConcurrencyTag, CGAL::Sequential_tag>;
  Soup_topology::internal::check_triangle_soup<Tag>(triangles, points.size());
  const std::string advice = "; STL stores coordinates as 32-bit floats: write .off, .obj or .ply to keep them as doubles";
  auto describe = [](const std::array<double, 3>& c) {
    internal::Text_line t;
    t << '(';
    t.real(c[0], 17) << ", ";
    t.real(c[1], 17) << ", ";
    t.real(c[2], 17) << ')';
    std::ostringstream s;
    t.flush_to(s, true);
    return s.str();
  };
  std::vector<char> used(points.size(), 0);
  internal::for_each_triangle(triangles, [&](std::size_t a, std::size_t b, std::size_t c) { used[a] = used[b] = used[c] = 1; });
  std::vector<Float_point> rounded(points.size());
  const double float_max = static_cast<double>(std::numeric_limits<float>::max());
  // Converting a double outside the float range is undefined behaviour: test first.
  const auto beyond_float = [&](std::size_t i) {
    if(!used[i]) return false;
    for(double c : internal::write_coordinates(points[i]))
      if(!std::isfinite(c) || std::abs(c) > float_max) return true;
    return false;
  };
  const std::size_t first_beyond = Soup_topology::internal::first_index_where<Tag>(points.size(), beyond_float);
  if(first_beyond < points.size())
    throw Write_error("point " + std::to_string(first_beyond) + " " + describe(internal::write_coordinates(points[first_beyond])) +
                      " becomes infinite in float" + advice);
  Soup_topology::internal::for_each_block<Tag>(points.size(), Soup_topology::internal::default_block_size,
                                               [&](std::size_t, std::size_t begin, std::size_t end) {
    for(std::size_t i = begin; i < end; ++i) {
      if(!used[i]) continue;
      const std::array<double, 3> c = internal::write_coordinates(points[i]);
      rounded[i] = Float_point(internal::rounded_to_float(c[0]), internal::rounded_to_float(c[1]),
                               internal::rounded_to_float(c[2]));
    }
  });
  std::vector<std::size_t> order;
  for(std::size_t i = 0; i < points.size(); ++i)
    if(used[i]) order.push_back(i);
  // Distinct points that become equal: a reader welds them, and the mesh read back changes.
  // Whether there is such a pair is found by hashing; only then are the points sorted, so that
  // the pair named is the first in lexicographic order whatever the hashing.
  if(internal::has_distinct_points_equal_in_float<Tag>(points, rounded, order))
    std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
      return rounded[a] < rounded[b] || (rounded[a] == rounded[b] && a < b);
    });
  else
    order.clear();
  for(std::size_t k = 1; k < order.size(); ++k) {
    const std::size_t a = order[k - 1], b = order[k];
    if(rounded[a] == rounded[b] && internal::write_coordinates(points[a]) != internal::write_coordinates(points[b]))
      throw Write_error("points " + std::to_string(std::min(a, b)) + " and " + std::to_string(std::max(a, b)) + " " +
                        describe(internal::write_coordinates(points[a])) + " and " +
                        describe(internal::write_coordinates(points[b])) + " become the same point in float" + advice);
  }
  auto normal = [](const std::array<double, 3>& a, const std::array<double, 3>& b, const std::array<double, 3>& c) {
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    return std::array<double, 3>{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  };
  auto coordinates = [](const Float_point& p) { return std::array<double, 3>{p.x(), p.y(), p.z()}; };
  // What rounding does to triangle `triangle` (corners i, j, k): nothing (an empty string), or
  // the refusal.
  const auto refusal = [&](std::size_t triangle, std::size_t i, std::size_t j, std::size_t k) -> std::string {
    const Float_point &a = rounded[i], &b = rounded[j], &c = rounded[k];
    const bool was_degenerate = gt.collinear_3_object()(points[i], points[j], points[k]);
    if(was_degenerate) return {};
    const auto which = [&]() {
      return "triangle " + std::to_string(triangle) + " (points " + std::to_string(i) + ", " + std::to_string(j) + ", " +
             std::to_string(k) + ")";
    };
    if(CGAL::collinear(a, b, c)) return which() + " becomes degenerate in float" + advice;
    const std::array<double, 3> n0 =
      normal(internal::write_coordinates(points[i]), internal::write_coordinates(points[j]), internal::write_coordinates(points[k]));
    const std::array<double, 3> n1 = normal(coordinates(a), coordinates(b), coordinates(c));
    if(n0[0] * n1[0] + n0[1] * n1[1] + n0[2] * n1[2] <= 0) return which() + " flips in float" + advice;
    return {};
  };
  if constexpr(internal::is_random_access_range<TriangleRange>::value) {
    const auto at = [&](std::size_t t) { return Soup_topology::internal::triangle_indices(std::begin(triangles)[t]); };
    const std::size_t n = static_cast<std::size_t>(std::distance(std::begin(triangles), std::end(triangles)));
    const std::size_t first = Soup_topology::internal::first_index_where<Tag>(n, [&](std::size_t t) {
      const std::array<std::size_t, 3> v = at(t);
      return !refusal(t, v[0], v[1], v[2]).empty();
    });
    if(first < n) {
      const std::array<std::size_t, 3> v = at(first);
      throw Write_error(refusal(first, v[0], v[1], v[2]));
    }
  }
  else {
    std::size_t t = 0;
    internal::for_each_triangle(triangles, [&](std::size_t i, std::size_t j, std::size_t k) {
      const std::string refused = refusal(t++, i, j, k);
      if(!refused.empty()) throw Write_error(refused);
    });
  }
}

/// \ingroup PkgSoupTopologyIO
/// \brief writes the soup to `os` as OFF: the header `OFF`, the counts, one point per line, one
/// `3 i j k` line per triangle.
///
/// \tparam PointRange a range of `Point_3`
/// \tparam TriangleRange a range of faces of 3 indices into `points`
/// \param os the stream (opened in binary mode or not: only `\n` is written)
/// \param points the points, all written, in their order
/// \param triangles the triangles, written in their order
/// \param np an optional sequence of named parameters among the ones listed below
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{stream_precision}
///     \cgalParamDescription{the number of significant digits of the coordinates}
///     \cgalParamType{int}
///     \cgalParamDefault{`17`, enough for every double to read back as itself}
///   \cgalParamNEnd
/// \cgalNamedParamsEnd
///
/// \throws Write_error if a coordinate is not finite or the stream fails.
/// \throws Invalid_input if a face is not a triangle of distinct, in-range indices.
template <class PointRange, class TriangleRange, class NamedParameters = CGAL::parameters::Default_named_parameters>
void write_OFF_triangle_soup(std::ostream& os, const PointRange& points, const TriangleRange& triangles,
                             const NamedParameters& np = CGAL::parameters::default_values())
{
  const std::size_t number_of_triangles = internal::check_soup_for_writing(points, triangles);
  const int precision = internal::stream_precision(np);
  internal::Text_line t;
  t << "OFF\n";
  t.integer(points.size()) << ' ';
  t.integer(number_of_triangles) << " 0\n";
  internal::write_text_points(os, t, points, "", precision);
  internal::write_text_triangles(os, t, triangles, "3 ", 0);
  t.flush_to(os, true);
  os.flush();
  internal::check_stream(os);
}

/// \ingroup PkgSoupTopologyIO
/// \brief writes the soup to `os` as Wavefront OBJ: `v x y z` lines, then `f i j k` lines
/// (1-based). Parameters as for `write_OFF_triangle_soup()`.
template <class PointRange, class TriangleRange, class NamedParameters = CGAL::parameters::Default_named_parameters>
void write_OBJ_triangle_soup(std::ostream& os, const PointRange& points, const TriangleRange& triangles,
                             const NamedParameters& np = CGAL::parameters::default_values())
{
  internal::check_soup_for_writing(points, triangles);
  internal::Text_line t;
  internal::write_text_points(os, t, points, "v ", internal::stream_precision(np));
  internal::write_text_triangles(os, t, triangles, "f ", 1);
  t.flush_to(os, true);
  os.flush();
  internal::check_stream(os);
}

/// \ingroup PkgSoupTopologyIO
/// \brief writes the soup to `os` as PLY: an element `vertex` of three `double` properties
/// `x y z`, an element `face` with a `list uchar int vertex_indices`; binary little-endian or ASCII.
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{use_binary_mode}
///     \cgalParamDescription{`binary_little_endian` if `true`, `ascii` if `false`}
///     \cgalParamType{bool}
///     \cgalParamDefault{`true`}
///   \cgalParamNEnd
///   \cgalParamNBegin{stream_precision}
///     \cgalParamDescription{the number of significant digits of the coordinates in ASCII mode}
///     \cgalParamType{int}
///     \cgalParamDefault{`17`}
///   \cgalParamNEnd
/// \cgalNamedParamsEnd
///
/// The stream must be opened in binary mode for binary output.
/// \throws Write_error if a coordinate is not finite, an index does not fit in an `int`, or the
/// stream fails.
template <class PointRange, class TriangleRange, class NamedParameters = CGAL::parameters::Default_named_parameters>
void write_PLY_triangle_soup(std::ostream& os, const PointRange& points, const TriangleRange& triangles,
                             const NamedParameters& np = CGAL::parameters::default_values())
{
  const bool binary = CGAL::parameters::choose_parameter(CGAL::parameters::get_parameter(np, CGAL::internal_np::use_binary_mode), true);
  const std::size_t number_of_triangles = internal::check_soup_for_writing(points, triangles);
  if(points.size() > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()))
    throw Write_error("PLY face indices are written as int: " + std::to_string(points.size()) + " points are too many");
  internal::Text_line t;
  t << "ply\nformat " << (binary ? "binary_little_endian" : "ascii") << " 1.0\nelement vertex ";
  t.integer(points.size()) << "\nproperty double x\nproperty double y\nproperty double z\nelement face ";
  t.integer(number_of_triangles) << "\nproperty list uchar int vertex_indices\nend_header\n";
  t.flush_to(os, true);
  if(binary) {
    std::string data;
    auto flush = [&](bool force) {
      if(force || data.size() > (1u << 16)) {
        os.write(data.data(), static_cast<std::streamsize>(data.size()));
        data.clear();
      }
    };
    for(const auto& p : points) {
      for(double c : internal::write_coordinates(p)) internal::put_little_endian(data, c);
      flush(false);
    }
    internal::for_each_triangle(triangles, [&](std::size_t a, std::size_t b, std::size_t c) {
      data.push_back(3);
      for(std::size_t v : {a, b, c}) internal::put_little_endian(data, static_cast<std::int32_t>(v));
      flush(false);
    });
    flush(true);
  } else {
    const int precision = internal::stream_precision(np);
    internal::write_text_points(os, t, points, "", precision);
    internal::write_text_triangles(os, t, triangles, "3 ", 0);
    t.flush_to(os, true);
  }
  os.flush();
  internal::check_stream(os);
}

/// \ingroup PkgSoupTopologyIO
/// \brief writes the soup to `os` as binary STL: an 80-byte header, the count, then per triangle
/// its unit normal and its three corners as 32-bit floats, little-endian.
///
/// `check_STL_float_rounding()` is called first: nothing is written when float rounding would
/// change the soup. STL holds no indices: a reader gets the triangles back by welding equal
/// corners, so points equal in double (duplicated to separate a non-manifold vertex or edge)
/// are welded again.
///
/// The stream must be opened in binary mode.
/// \tparam ConcurrencyTag with `CGAL::Parallel_tag` and a random-access range of triangles, the
///         check and the records are made by blocks on TBB's threads (the bytes are the same)
/// \throws Write_error as `check_STL_float_rounding()`, if there are more than 2^32 - 1
/// triangles, or if the stream fails.
template <class ConcurrencyTag = CGAL::Sequential_tag, class PointRange, class TriangleRange>
void write_STL_triangle_soup(std::ostream& os, const PointRange& points, const TriangleRange& triangles)
{
  const std::size_t number_of_triangles = static_cast<std::size_t>(std::distance(std::begin(triangles), std::end(triangles)));
  if(number_of_triangles > std::numeric_limits<std::uint32_t>::max())
    throw Write_error("binary STL counts facets on 32 bits: " + std::to_string(number_of_triangles) + " triangles are too many");
  check_STL_float_rounding<ConcurrencyTag>(points, triangles);
  std::string header = "binary STL written by Soup_topology";
  header.resize(80, ' ');
  internal::put_little_endian(header, static_cast<std::uint32_t>(number_of_triangles));
  os.write(header.data(), static_cast<std::streamsize>(header.size()));
  // The 50 bytes of the facet with corners i, j, k at `out`: its unit normal and its corners as
  // floats, little-endian, then two zero bytes.
  const auto facet = [&](std::size_t i, std::size_t j, std::size_t k, char* out) {
    const auto a = internal::write_coordinates(points[i]);
    const auto b = internal::write_coordinates(points[j]);
    const auto c = internal::write_coordinates(points[k]);
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for(double& x : n) x = (length > 0 && std::isfinite(length)) ? x / length : 0.0;
    const auto put = [&out](double x) {
      const float f = static_cast<float>(x);
      std::uint32_t bits;
      std::memcpy(&bits, &f, 4);
      for(int byte = 0; byte < 4; ++byte) *out++ = static_cast<char>((bits >> (8 * byte)) & 0xff);
    };
    for(double x : n) put(x);
    for(const auto* corner : {&a, &b, &c})
      for(double x : *corner) put(x);
    out[0] = out[1] = '\0';
  };
  // Written by chunks of facets, each made by blocks (in parallel with `Parallel_tag`, random
  // access and `double` coordinates: lazily exact numbers are converted on one thread), then
  // written in order.
  using Point = typename std::iterator_traits<decltype(std::begin(points))>::value_type;
  using Tag = std::conditional_t<std::is_same<typename CGAL::Kernel_traits<Point>::Kernel::FT, double>::value,
                                 ConcurrencyTag, CGAL::Sequential_tag>;
  constexpr std::size_t chunk = std::size_t(1) << 16;
  std::vector<char> data(50 * std::min(chunk, number_of_triangles));
  if constexpr(internal::is_random_access_range<TriangleRange>::value) {
    for(std::size_t first = 0; first < number_of_triangles; first += chunk) {
      const std::size_t count = std::min(chunk, number_of_triangles - first);
      Soup_topology::internal::for_each_block<Tag>(count, 4096, [&](std::size_t, std::size_t begin, std::size_t end) {
        for(std::size_t f = begin; f < end; ++f) {
          const std::array<std::size_t, 3> t = Soup_topology::internal::triangle_indices(std::begin(triangles)[first + f]);
          facet(t[0], t[1], t[2], data.data() + 50 * f);
        }
      });
      os.write(data.data(), static_cast<std::streamsize>(50 * count));
    }
  }
  else {
    std::size_t f = 0;
    internal::for_each_triangle(triangles, [&](std::size_t i, std::size_t j, std::size_t k) {
      facet(i, j, k, data.data() + 50 * f);
      if(++f == chunk) {
        os.write(data.data(), static_cast<std::streamsize>(50 * f));
        f = 0;
      }
    });
    os.write(data.data(), static_cast<std::streamsize>(50 * f));
  }
  os.flush();
  internal::check_stream(os);
}

/// \ingroup PkgSoupTopologyIO
/// \brief writes the soup to `os` in `format` (`"off"`, `"obj"`, `"ply"` or `"stl"`, lower
/// case), with the named parameters of the format's writer.
/// \tparam ConcurrencyTag passed on to `write_STL_triangle_soup()` (the other writers run on one
///         thread)
/// \throws Write_error for an unknown format and as the format's writer.
template <class ConcurrencyTag = CGAL::Sequential_tag, class PointRange, class TriangleRange,
          class NamedParameters = CGAL::parameters::Default_named_parameters>
void write_triangle_soup(std::ostream& os, const std::string& format, const PointRange& points,
                         const TriangleRange& triangles, const NamedParameters& np = CGAL::parameters::default_values())
{
  if(format == "off") write_OFF_triangle_soup(os, points, triangles, np);
  else if(format == "obj") write_OBJ_triangle_soup(os, points, triangles, np);
  else if(format == "ply") write_PLY_triangle_soup(os, points, triangles, np);
  else if(format == "stl") write_STL_triangle_soup<ConcurrencyTag>(os, points, triangles);
  else throw Write_error("unknown output format '" + format + "' (expected off, obj, ply or stl)");
}

/// \ingroup PkgSoupTopologyIO
/// \brief writes the soup to `filename`, in the format of its extension (`.off`, `.obj`, `.ply`,
/// `.stl`, any case); see `write_OFF_triangle_soup()`, `write_OBJ_triangle_soup()`,
/// `write_PLY_triangle_soup()` and `write_STL_triangle_soup()` for the named parameters.
///
/// The file is written in place (opened, truncated, written): a caller who must never leave a
/// half-written file writes to a temporary file and renames it. Nothing is opened when the soup
/// cannot be written in the format (the checks come first).
///
/// \throws Write_error naming `filename`: unknown extension, cannot be opened, failed write,
/// STL float rounding; Invalid_input for a face that is not a triangle of in-range indices.
/// \tparam ConcurrencyTag passed on to `write_STL_triangle_soup()` and its check (the other
///         writers run on one thread)
template <class ConcurrencyTag = CGAL::Sequential_tag, class PointRange, class TriangleRange,
          class NamedParameters = CGAL::parameters::Default_named_parameters>
void write_triangle_soup(const std::string& filename, const PointRange& points, const TriangleRange& triangles,
                         const NamedParameters& np = CGAL::parameters::default_values())
{
  std::string format;
  {
    const std::size_t dot = filename.find_last_of('.');
    const std::size_t slash = filename.find_last_of("/\\");
    if(dot != std::string::npos && (slash == std::string::npos || dot > slash)) format = filename.substr(dot + 1);
    for(char& c : format) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  try {
    if(format != "off" && format != "obj" && format != "ply" && format != "stl")
      throw Write_error("unknown output extension '" + format + "' (expected .off, .obj, .ply or .stl)");
    if(format == "stl") check_STL_float_rounding<ConcurrencyTag>(points, triangles);
    else internal::check_finite_for_writing(points);
    std::ofstream os(filename, std::ios::binary | std::ios::trunc);
    if(!os) throw Write_error(std::string("cannot open the file for writing (") + std::strerror(errno) + ")");
    write_triangle_soup<ConcurrencyTag>(os, format, points, triangles, np);
    os.close();
    if(!os) throw Write_error("the write failed");
  } catch(const Write_error& e) {
    throw Write_error(filename + ": " + e.what());
  }
}

} // namespace IO
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_IO_WRITE_TRIANGLE_SOUP_H
