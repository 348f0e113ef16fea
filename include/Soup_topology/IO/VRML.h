// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// This file is part of Soup_topology, a header-only C++17 library that rebuilds the topology
// of triangle soups.

#ifndef SOUP_TOPOLOGY_IO_VRML_H
#define SOUP_TOPOLOGY_IO_VRML_H

#include <cstddef>
#include <fstream>
#include <istream>
#include <map>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <Soup_topology/IO/Read_error.h>
#include <Soup_topology/index_triangles.h>
#include <Soup_topology/internal/uninitialized_vector.h>

/// \file VRML.h
/// A reader for the polygon geometry of VRML 2.0 (VRML97) files, as written by CAD exporters:
/// every `IndexedFaceSet` of every `Shape` becomes triangles of one soup.
///
/// Supported: the `#VRML V2.0 utf8` header (a file without header is read too; a VRML 1.0
/// header is an error, and so is a gzip-compressed file), `#` comments, whitespace (space, tab,
/// carriage return, line feed) and commas (any other control byte outside comments and strings
/// is an error: binary data is not read as an empty scene); `Shape { geometry
/// IndexedFaceSet { coord Coordinate { point [...] } coordIndex [...] ccw ... } }` with `-1`
/// separators (the last polygon may lack its `-1`); `DEF`/`USE` of any node (every use is a new instance; the instances of the whole file are
/// bounded by `VRML_read_options::instance_budget`, by default proportional to the file size,
/// and subtrees that hold no geometry are not instantiated at all); grouping nodes
/// `Transform`, `Group`, `Anchor` and `Collision` with their `children`, nested to any depth;
/// `Transform`'s `translation`, `rotation` (axis-angle), `scale`, `scaleOrientation` and
/// `center`, composed along the path from the root. The other fields of `IndexedFaceSet`
/// (`normal`, `color`, `texCoord`, their index fields, `solid`, `convex`, `creaseAngle`, ...)
/// are parsed and ignored; `ccw FALSE` reverses the orientation of the triangles, and so does a
/// mirroring transform (negative determinant) unless `VRML_read_options::keep_mirrored_orientation`.
///
/// Skipped, with a count by node name in `VRML_read_result::skipped_nodes`: every other node
/// (`Appearance`, `Material`, `Viewpoint`, `Box`, `Switch`, `LOD`, instances of `PROTO`s, ...),
/// `PROTO`/`EXTERNPROTO` declarations and `ROUTE` statements. Only the outermost skipped node is
/// counted (the `Material` inside a skipped `Appearance` is not). A `USE` of a skipped node
/// counts again.
///
/// Polygons: a triangle is taken as it is; a polygon of 4 or more corners is tested for
/// convexity in the plane of its Newell normal (its best-fit plane, so slightly non-planar
/// polygons are handled like planar ones); a convex one is fan-triangulated from its first
/// corner, a non-convex one is ear-clipped in that plane (or fanned, see
/// `Non_convex_polygon_rule`), keeping the polygon's orientation; if ear clipping finds no ear
/// (self-intersecting polygon) the rest is fanned and counted. A polygon of fewer than 3
/// corners is dropped and counted. Ear clipping is that of
/// `Soup_topology/internal/triangulate_polygon.h`: near-linear in practice, and capped at
/// O(k log k) work for a polygon of k corners, beyond which the rest is fanned and counted as an
/// ear clipping failure. Nothing is welded: every instance of an `IndexedFaceSet` appends the
/// points of its `Coordinate` that its `coordIndex` names (all of them, in a file that names
/// every point), in their order, and its triangles refer to them.
///
/// Malformed input (unbalanced brackets, an index out of range, a number that does not parse,
/// an unexpected end of file, a `USE` of an undefined name, a point that overflows once
/// transformed, instances beyond the budget) throws `Read_error` (from
/// `Soup_topology/IO/Read_error.h`), whose message reads `"<name>:<line>: <description>"`, where
/// `<name>` is the file name (`VRML` when reading a stream) and `<line>` is 1-based. The caller's ranges are left as they were when an exception is thrown.

namespace Soup_topology {
namespace IO {

/// \ingroup PkgSoupTopologyIO
/// what to do with a non-convex polygon.
enum class Non_convex_polygon_rule
{
  EAR_CLIPPING, ///< ear clipping in the plane of the polygon's Newell normal (default)
  FAN           ///< fan from the first corner, as for convex polygons (may overlap itself)
};

/// \ingroup PkgSoupTopologyIO
/// options of `read_VRML()`.
struct VRML_read_options
{
  Non_convex_polygon_rule non_convex_rule = Non_convex_polygon_rule::EAR_CLIPPING;
  /// if `false` (default), the triangles of a shape seen through a mirroring transform
  /// (negative determinant) are reversed so that they keep their orientation in world space
  bool keep_mirrored_orientation = false;
  /// the most node instances (grouping nodes, shapes) the file may expand to through
  /// `DEF`/`USE`; beyond it `read_VRML()` throws `Read_error`. 0 (default): 2^20 + 2 per byte
  /// of the file, which a file without `USE` never reaches (a node takes more than 2 bytes)
  std::size_t instance_budget = 0;
  /// the most points and triangles the file may expand to through `DEF`/`USE`; beyond it
  /// `read_VRML()` throws `Read_error`. 0 (default): 2^21 + 8 per byte of the file, which a
  /// file without `USE` never reaches (it needs at least 6 bytes per point and 2 per triangle)
  std::size_t output_budget = 0;

  /// `base` + `per_byte` * `bytes`, saturated
  static std::size_t budget(std::size_t base, std::size_t per_byte, std::size_t bytes)
  {
    if(bytes > (std::size_t(-1) - base) / per_byte)
      return std::size_t(-1);
    return base + per_byte * bytes;
  }
};

/// \ingroup PkgSoupTopologyIO
/// what `read_VRML()` read.
struct VRML_read_result
{
  /// for each triangle appended (in order), the shape it comes from: 0 for the first
  /// `Shape`-with-`IndexedFaceSet` instance met in traversal order, 1 for the next, ...
  std::vector<std::size_t> triangle_shape_ids;
  std::size_t number_of_shapes = 0;             ///< `Shape` instances with an `IndexedFaceSet` (a `USE` counts again)
  std::size_t number_of_points = 0;             ///< points appended (those named by `coordIndex`)
  std::size_t number_of_triangles = 0;          ///< triangles appended
  std::size_t number_of_polygons = 0;           ///< polygons read (`coordIndex` entries)
  std::size_t number_of_short_polygons = 0;     ///< polygons of fewer than 3 corners, dropped
  std::size_t number_of_non_convex_polygons = 0;///< polygons of 4+ corners found non-convex
  std::size_t number_of_ear_clipping_failures = 0; ///< non-convex polygons where no ear was found: rest fanned
  std::size_t number_of_mirrored_shapes = 0;    ///< shape instances under a mirroring transform
  std::map<std::string, std::size_t> skipped_nodes; ///< unsupported node (or statement) name -> count

  /// the total of `skipped_nodes`
  std::size_t number_of_skipped_nodes() const
  {
    std::size_t n = 0;
    for(const auto& entry : skipped_nodes)
      n += entry.second;
    return n;
  }
};

} // namespace IO
} // namespace Soup_topology

#include <Soup_topology/internal/VRML_parser.h>

namespace Soup_topology {
namespace IO {

/// \cond SKIP_IN_MANUAL
namespace internal {

using Soup_topology::internal::Has_reserve;

template <typename PointRange, typename TriangleRange>
void append_VRML_soup(const Soup_topology::internal::VRML::Soup& soup,
                      PointRange& points, TriangleRange& triangles)
{
  using Point = typename PointRange::value_type;
  using Face = typename TriangleRange::value_type;
  const std::size_t base = points.size();
  const std::size_t n = soup.xyz.size() / 3;
  if constexpr(Has_reserve<PointRange>::value)
    points.reserve(base + n);
  if constexpr(Has_reserve<TriangleRange>::value)
    triangles.reserve(triangles.size() + soup.triangles.size());
  for(std::size_t i = 0; i < n; ++i)
    points.push_back(Point(soup.xyz[3 * i], soup.xyz[3 * i + 1], soup.xyz[3 * i + 2]));
  for(const auto& t : soup.triangles)
    triangles.push_back(Soup_topology::internal::make_triangle<Face>(base + t[0], base + t[1], base + t[2]));
}

template <typename PointRange, typename TriangleRange>
VRML_read_result read_VRML(std::istream& is, const std::string& name, PointRange& points,
                           TriangleRange& triangles, const VRML_read_options& options)
{
  std::string text;
  char chunk[1 << 16];
  while(is.read(chunk, sizeof(chunk)) || is.gcount() > 0)
    text.append(chunk, static_cast<std::size_t>(is.gcount()));
  if(is.bad())
    throw Read_error(name + ": cannot read the input");

  VRML_read_result result;
  Soup_topology::internal::VRML::Soup soup;
  Soup_topology::internal::VRML::Parser parser(text.data(), text.data() + text.size(), name,
                                               options, result, soup);
  parser.run();
  append_VRML_soup(soup, points, triangles);
  return result;
}

} // namespace internal
/// \endcond

/// \ingroup PkgSoupTopologyIO
/// reads the `IndexedFaceSet` geometry of the VRML 2.0 text in `is` and appends it to the soup
/// (`points`, `triangles`): the points of every shape instance, transformed to world
/// coordinates, and the triangles of its polygons, whose indices refer to `points` (offset by
/// the size `points` had on entry).
///
/// \tparam PointRange a back-insertion sequence of points constructible from three `double`
///         (`CGAL::Point_3` of any kernel)
/// \tparam TriangleRange a back-insertion sequence of faces of 3 indices
///         (`std::array<std::size_t,3>`, `std::vector<int>`, ...)
/// \param is the stream the VRML text is read from (to its end)
/// \param points the points the points of the file are appended to
/// \param triangles the triangles the triangles of the file are appended to
/// \param options how polygons, mirroring transforms and the instance budgets are handled
/// \return what was read: the shape of each triangle and the counts of the file header.
/// \throws Read_error on malformed input; `points` and `triangles` are then unchanged.
template <typename PointRange, typename TriangleRange>
VRML_read_result read_VRML(std::istream& is, PointRange& points, TriangleRange& triangles,
                           const VRML_read_options& options = VRML_read_options())
{
  return internal::read_VRML(is, "VRML", points, triangles, options);
}

/// \ingroup PkgSoupTopologyIO
/// reads the VRML 2.0 file `filename`, see above.
/// \param filename the name of the file, which also starts the messages of `Read_error`
/// \param points the points the points of the file are appended to
/// \param triangles the triangles the triangles of the file are appended to
/// \param options how polygons, mirroring transforms and the instance budgets are handled
/// \throws Read_error also when the file cannot be opened or read.
template <typename PointRange, typename TriangleRange>
VRML_read_result read_VRML(const std::string& filename, PointRange& points, TriangleRange& triangles,
                           const VRML_read_options& options = VRML_read_options())
{
  std::ifstream in(filename, std::ios::binary);
  if(!in)
    throw Read_error(filename + ": cannot open the file for reading");
  return internal::read_VRML(in, filename, points, triangles, options);
}

} // namespace IO
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_IO_VRML_H
