// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// One entry point that reads any supported file into an exactly welded, indexed triangle soup.

#ifndef SOUP_TOPOLOGY_IO_READ_TRIANGLE_SOUP_H
#define SOUP_TOPOLOGY_IO_READ_TRIANGLE_SOUP_H

#include <Soup_topology/IO/OBJ.h>
#include <Soup_topology/IO/OFF.h>
#include <Soup_topology/IO/PLY.h>
#include <Soup_topology/IO/Read_error.h>
#include <Soup_topology/IO/STL.h>
#include <Soup_topology/IO/VRML.h>
#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/index_triangles.h>
#include <Soup_topology/internal/PLY_header.h>
#include <Soup_topology/internal/soup_checks.h>
#include <Soup_topology/internal/triangulate_polygon.h>

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/property_map.h>
#include <CGAL/tags.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstddef>
#include <istream>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

namespace Soup_topology {
namespace IO {

/// \ingroup PkgSoupTopologyIO
/// \brief what `read_triangle_soup()` read and what the exact weld did.
struct Soup_read_report
{
  std::string format;                     ///< "stl", "off", "obj", "ply", "wrl"
  std::size_t input_polygons = 0;         ///< faces or facets in the file
  std::size_t input_vertices = 0;         ///< vertices in the file (3 per facet for STL)
  std::size_t input_triangles = 0;        ///< triangles after the triangulation of polygons
  std::size_t skipped_polygons = 0;       ///< faces left out: fewer than 3 vertices, or not simple
  std::size_t non_simple_polygons = 0;    ///< of those, faces of more than 3 corners that repeat a vertex index
  std::size_t non_convex_polygons = 0;    ///< polygons (OFF, OBJ, PLY) found non-convex, ear-clipped
  /// of those, the polygons where ear clipping found no ear for some corners: those were fanned
  std::size_t ear_clipping_failures = 0;
  std::size_t exact_duplicates = 0;       ///< vertices merged with an equal earlier one
  std::size_t collapsed_triangles = 0;    ///< triangles with two equal corners after the weld, left out
};

/// the lower-case extension of `filename`, without the dot ("" if none).
inline std::string file_extension(const std::string& filename)
{
  const std::size_t dot = filename.find_last_of('.');
  const std::size_t slash = filename.find_last_of("/\\");
  if(dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = filename.substr(dot + 1);
  for(char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

/// \cond SKIP_IN_MANUAL
namespace internal {

/// "stl", "off", ... from a format given by the caller ("STL", ".stl", "vrml").
inline std::string normalized_format(const std::string& format)
{
  std::string f = format;
  if(!f.empty() && f[0] == '.') f.erase(0, 1);
  for(char& c : f) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if(f == "vrml") f = "wrl";
  return f;
}

/// refuses at once an input of unknown size whose first bytes cannot start a file of `format`.
struct Format_prefix_check
{
  std::string format;
  std::string name;
  Soup_topology::internal::Input_size operator()(const char* b, const char* e) const
  {
    if(format == "stl") return STL_prefix_check()(b, e);
    if(format == "ply") {
      if(e - b < 4 || std::string(b, 3) != "ply" || (b[3] != '\n' && b[3] != '\r'))
        throw Read_error(name + ":1: not a PLY file (it does not start with the line 'ply')");
    } else {
      for(const char* p = b; p < e; ++p)
        if(*p == '\0')
          throw Read_error(name + ": a NUL byte at offset " + std::to_string(p - b) + ": not a text ." + format + " file");
    }
    return Soup_topology::internal::Input_size();
  }
};

inline void check_format(const std::string& format, const std::string& name)
{
  if(format != "stl" && format != "off" && format != "obj" && format != "ply" && format != "wrl")
    throw Read_error(name + ": unknown file extension '" + format + "' (expected .stl, .off, .obj, .ply or .wrl)");
}

/// `true` if the polygon `poly` of more than 3 corners is convex in the plane of its Newell
/// normal (the test of the VRML reader: no right turn, and the edge directions sweep around
/// once), or degenerate (all corners collinear: nothing better than a fan). `uv` is scratch.
template <class Point>
bool is_convex_polygon(const std::vector<Point>& points, const std::vector<std::size_t>& poly, std::vector<double>& uv)
{
  const std::size_t k = poly.size();
  const Soup_topology::internal::Polygon_projection projection = Soup_topology::internal::project_polygon(
    k,
    [&](std::size_t i) {
      const Point& p = points[poly[i]];
      return std::array<double, 3>{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
    },
    uv);
  if(projection.degenerate()) return true;
  int sign_changes = 0, last_sign = 0;
  for(std::size_t i = 0; i < k; ++i) {
    const std::size_t j = (i + 1) % k, l = (i + 2) % k;
    const double turn = (uv[2 * j] - uv[2 * i]) * (uv[2 * l + 1] - uv[2 * i + 1]) -
                        (uv[2 * j + 1] - uv[2 * i + 1]) * (uv[2 * l] - uv[2 * i]);
    if(turn < 0) return false;
    const double du = uv[2 * j] - uv[2 * i];
    const int sign = (du > 0) - (du < 0);
    if(sign != 0) {
      if(last_sign != 0 && sign != last_sign) ++sign_changes;
      last_sign = sign;
    }
  }
  return sign_changes <= 2;
}

/// triangulates `polygons` into `triangles` as the VRML reader does: a convex polygon by a fan
/// from its first corner, a non-convex one by ear clipping (`internal/triangulate_polygon.h`);
/// skipping (and counting in `report`) those of fewer than 3 corners and those of more than 3
/// that repeat a vertex (not simple polygons: the triangles of `1 2 3 4 1 2 3 4 ...` would be a
/// pile of copies of the same ones). The check of repeats is linear in the number of corners.
template <class Point, class Face>
void triangulate_polygons(const std::vector<std::vector<std::size_t>>& polygons, const std::vector<Point>& points,
                          const std::string& name, std::vector<Face>& triangles, Soup_read_report& report)
{
  const std::size_t number_of_points = points.size();
  std::vector<std::array<std::size_t, 3>> clipped;
  std::vector<double> uv;
  const std::size_t none = static_cast<std::size_t>(-1);
  std::vector<std::size_t> last_seen_in(number_of_points, none);
  for(std::size_t f = 0; f < polygons.size(); ++f) {
    const std::vector<std::size_t>& poly = polygons[f];
    for(std::size_t v : poly)
      if(v >= number_of_points)
        throw Invalid_input(name + ": face " + std::to_string(f) + " has vertex index " + std::to_string(v) +
                            ", out of range (" + std::to_string(number_of_points) + " vertices)");
    if(poly.size() < 3) { ++report.skipped_polygons; continue; }
    if(poly.size() > 3) {
      bool repeats = false;
      for(std::size_t v : poly) {
        if(last_seen_in[v] == f) { repeats = true; break; }
        last_seen_in[v] = f;
      }
      if(repeats) {
        ++report.skipped_polygons;
        ++report.non_simple_polygons;
        continue;
      }
    }
    if(poly.size() == 3 || is_convex_polygon(points, poly, uv)) {
      for(std::size_t k = 1; k + 1 < poly.size(); ++k)
        triangles.push_back(Soup_topology::internal::make_triangle<Face>(poly[0], poly[k], poly[k + 1]));
      continue;
    }
    ++report.non_convex_polygons;
    clipped.clear();
    if(Soup_topology::internal::triangulate_polygon(points, poly, clipped) != 0) ++report.ear_clipping_failures;
    for(const std::array<std::size_t, 3>& t : clipped)
      triangles.push_back(Soup_topology::internal::make_triangle<Face>(t[0], t[1], t[2]));
  }
}

/// throws `Invalid_input` naming the first facet of `count` with a corner that has a NaN or
/// infinite coordinate, corner `i` being `corner_point(i)` (checked in parallel with a parallel
/// `ConcurrencyTag`: the first bad facet is named whatever the threads).
template <class ConcurrencyTag = CGAL::Sequential_tag, class CornerAccess>
void check_finite_facets(std::size_t count, const CornerAccess& corner_point, const std::string& name)
{
  const std::size_t bad = Soup_topology::internal::first_index_where<ConcurrencyTag>(
    3 * count, [&](std::size_t i) { return !Soup_topology::internal::is_finite_point(corner_point(i)); });
  if(bad != 3 * count)
    throw Invalid_input(name + ": facet " + std::to_string(bad / 3) + " has a non-finite coordinate");
}


/// reads an STL file into `pts` and `tris`, exactly welded. A binary file is welded while it is
/// decoded: its corners are read from the bytes where they are, never copied into triangles.
/// With a parallel `ConcurrencyTag` the checks and the weld run on TBB's threads, with the
/// same result.
template <class ConcurrencyTag, class Point, class Face>
void read_STL_soup(const char* data, std::size_t size, const std::string& name, std::vector<Point>& pts,
                   std::vector<Face>& tris, Soup_read_report& report)
{
  const std::size_t bom = Soup_topology::internal::utf8_bom_size(data, data + size);
  Index_report ir;
  if(looks_like_ascii_stl(data + bom, data + size)) {
    std::vector<std::array<Point, 3>> explicit_triangles;
    read_STL_triangles(data, size, explicit_triangles, name);
    check_finite_facets<Soup_topology::internal::Point_concurrency<ConcurrencyTag, Point>>(
      explicit_triangles.size(), [&](std::size_t i) -> const Point& { return explicit_triangles[i / 3][i % 3]; }, name);
    ir = index_triangles<ConcurrencyTag>(explicit_triangles, pts, tris);
  } else {
    const std::size_t count = binary_STL_facet_count(data, size, name);
    const auto corner_point = [data](std::size_t i) { return binary_STL_corner<Point>(data, i); };
    using Tag = Soup_topology::internal::Point_concurrency<ConcurrencyTag, Point>;
    ir.input_triangles = count;
    ir.input_corners = 3 * count;
    // (the weld tests the coordinates it decodes; if one is not finite, the facet is named)
    const auto refuse_non_finite = [&] { check_finite_facets<Tag>(count, corner_point, name); };
    // (the parallel renumbering fills more arrays: on one thread, the sequential one, same result)
    if(Soup_topology::internal::runs_on_several_threads<Tag>())
      Soup_topology::internal::index_corners_in_parallel<Tag>(ir.input_corners, corner_point, pts, tris, ir,
                                                              refuse_non_finite);
    else
      Soup_topology::internal::index_corners(ir.input_corners, corner_point, pts, tris, ir, refuse_non_finite);
  }
  report.input_polygons = report.input_triangles = ir.input_triangles;
  report.input_vertices = ir.input_corners;
  report.exact_duplicates = ir.input_corners - ir.vertices;
  report.collapsed_triangles = ir.collapsed_triangles;
}

/// reads a VRML file into `pts` and `tris` (not yet welded).
template <class Point, class Face>
void read_VRML_soup(const char* data, std::size_t size, const std::string& name, std::vector<Point>& pts,
                    std::vector<Face>& tris, Soup_read_report& report)
{
  std::istringstream in(std::string(data, size));
  const VRML_read_result vr = internal::read_VRML(in, name, pts, tris, VRML_read_options());
  report.input_polygons = vr.number_of_polygons;
  report.input_vertices = pts.size();
  report.input_triangles = tris.size();
  report.skipped_polygons = vr.number_of_short_polygons;
}

/// reads an OFF, OBJ or PLY file into `pts` and `tris` (not yet welded), triangulating its polygons.
template <class Point, class Face>
void read_polygon_soup(const char* data, std::size_t size, const std::string& format, const std::string& name,
                       std::vector<Point>& pts, std::vector<Face>& tris, Soup_read_report& report)
{
  std::vector<std::vector<std::size_t>> polygons;
  if(format == "off") {
    read_OFF_polygons(data, size, pts, polygons, name);
  } else if(format == "obj") {
    read_OBJ_polygons(data, size, pts, polygons, name);
  } else {
    // The header checks that CGAL's reader needed are kept: their refusals are documented.
    Soup_topology::internal::check_PLY_header(data, size, name);
    read_PLY_polygons(data, size, pts, polygons, name);
  }
  report.input_polygons = polygons.size();
  report.input_vertices = pts.size();
  Soup_topology::internal::check_finite_points(pts, CGAL::Identity_property_map<Point>());
  triangulate_polygons(polygons, pts, name, tris, report);
  report.input_triangles = tris.size();
}

template <class ConcurrencyTag, class Point, class Face>
Soup_read_report read_triangle_soup(const char* data, std::size_t size, const std::string& format,
                                    const std::string& name, std::vector<Point>& points, std::vector<Face>& triangles)
{
  Soup_read_report report;
  report.format = format;
  check_format(format, name);
  std::vector<Point> pts;
  std::vector<Face> tris;
  if(format == "stl") {
    read_STL_soup<ConcurrencyTag>(data, size, name, pts, tris, report);
  } else {
    if(format == "wrl") {
      read_VRML_soup(data, size, name, pts, tris, report);
      Soup_topology::internal::check_finite_points(pts, CGAL::Identity_property_map<Point>());
    } else {
      read_polygon_soup(data, size, format, name, pts, tris, report);
    }
    const std::size_t before = pts.size();
    Soup_topology::internal::merge_duplicate_points_and_map<ConcurrencyTag>(pts, tris);
    report.exact_duplicates = before - pts.size();
    report.collapsed_triangles = remove_collapsed_triangles(tris);
  }
  points.swap(pts);
  triangles.swap(tris);
  return report;
}

} // namespace internal
/// \endcond

/// \ingroup PkgSoupTopologyIO
/// \brief reads `filename` (STL binary or ASCII, OFF, OBJ, PLY, VRML 2.0 `.wrl`, chosen by the
/// extension) into an indexed triangle soup whose exactly equal points are merged: `points`
/// holds distinct points, `triangles` index triples of distinct vertices. Polygons are
/// triangulated as `read_VRML()` does: a convex one by a fan from its first corner, a non-convex
/// one by ear clipping in the plane of its Newell normal (counted in `non_convex_polygons`; the
/// corners left when no ear is found are fanned and counted in `ear_clipping_failures`).
///
/// STL goes through `read_STL_triangles()` and `index_triangles()`; OFF through
/// `read_OFF_polygons()`, OBJ through `read_OBJ_polygons()`, PLY through
/// `read_PLY_polygons()` (after the checks of `internal/PLY_header.h`), then
/// `merge_duplicate_points()`; VRML
/// through `read_VRML()` (every shape's points appended, then merged the same way). A polygon of
/// fewer than 3 corners, or of more than 3 corners that repeats a vertex index (not a simple
/// polygon), is skipped and counted (`skipped_polygons`, `non_simple_polygons`).
///
/// A regular file is read whole into memory; any other input (a pipe, a device such as
/// `/dev/stdin`) is read up to `limit` bytes, and refused beyond (`Read_error`). Compressed
/// files (`.gz`, `.xz`) are not read: decompress them first, or give the decompressed bytes to
/// the overloads that take a stream or a buffer.
/// \param filename the file; its extension gives the format
/// \param points receives the distinct points
/// \param triangles receives the triangles, index triples into `points`
///
/// With `CGAL::Parallel_tag` (or `CGAL::Parallel_if_available_tag` with TBB) the checks and the
/// exact weld run on TBB's threads (points of `double` coordinates; the parse of a text format
/// stays sequential); the points, the triangles, their order and the report are the same on any
/// number of threads.
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` (the default), `CGAL::Parallel_tag` (needs TBB)
///         or `CGAL::Parallel_if_available_tag`
/// \param limit the most bytes read from an input that is not a regular file
/// \throws Read_error if the file cannot be read, is a folder, or is malformed; Invalid_input for
/// an index out of range or a non-finite coordinate. `points` and `triangles` are unchanged then.
template <class ConcurrencyTag = CGAL::Sequential_tag, class Point, class Face>
Soup_read_report read_triangle_soup(const std::string& filename, std::vector<Point>& points,
                                    std::vector<Face>& triangles, std::size_t limit = default_stream_size_limit)
{
  const std::string format = file_extension(filename);
  internal::check_format(format, filename);
  const std::string data =
    Soup_topology::internal::read_file_bounded(filename, limit, internal::Format_prefix_check{format, filename});
  return internal::read_triangle_soup<ConcurrencyTag>(data.data(), data.size(), format, filename, points, triangles);
}

/// \ingroup PkgSoupTopologyIO
/// \brief reads the file held in `[data, data + size)`, of the given `format` ("stl", "off",
/// "obj", "ply" or "wrl", any case, with or without a dot), see the overload above; `name`
/// starts the messages of the errors.
/// \param data the first byte of the file
/// \param size the number of bytes of the file
/// \param format the format of the file
/// \param points receives the distinct points
/// \param triangles receives the triangles, index triples into `points`
/// \param name the name of the input in the messages
template <class ConcurrencyTag = CGAL::Sequential_tag, class Point, class Face>
Soup_read_report read_triangle_soup(const char* data, std::size_t size, const std::string& format,
                                    std::vector<Point>& points, std::vector<Face>& triangles,
                                    const std::string& name = "<memory>")
{
  return internal::read_triangle_soup<ConcurrencyTag>(data, size, internal::normalized_format(format), name, points,
                                                      triangles);
}

/// \ingroup PkgSoupTopologyIO
/// \brief reads what is left of `in` (opened in binary mode for a binary STL or PLY), of the
/// given `format`, see the overloads above. At most `limit` bytes are read: more is a
/// `Read_error`.
/// \param in the stream, read to its end
/// \param format the format of the data
/// \param points receives the distinct points
/// \param triangles receives the triangles, index triples into `points`
/// \param name the name of the input in the messages
/// \param limit the most bytes read
template <class ConcurrencyTag = CGAL::Sequential_tag, class Point, class Face>
Soup_read_report read_triangle_soup(std::istream& in, const std::string& format, std::vector<Point>& points,
                                    std::vector<Face>& triangles, const std::string& name = "<stream>",
                                    std::size_t limit = default_stream_size_limit)
{
  const std::string f = internal::normalized_format(format);
  internal::check_format(f, name);
  const std::string data = Soup_topology::internal::read_bounded(in, name, limit, internal::Format_prefix_check{f, name});
  return internal::read_triangle_soup<ConcurrencyTag>(data.data(), data.size(), f, name, points, triangles);
}

} // namespace IO
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_IO_READ_TRIANGLE_SOUP_H
