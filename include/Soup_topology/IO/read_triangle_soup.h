// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// One entry point that reads any supported file into an exactly welded, indexed triangle soup.

#ifndef SOUP_TOPOLOGY_IO_READ_TRIANGLE_SOUP_H
#define SOUP_TOPOLOGY_IO_READ_TRIANGLE_SOUP_H

#include <Soup_topology/IO/OFF.h>
#include <Soup_topology/IO/Read_error.h>
#include <Soup_topology/IO/STL.h>
#include <Soup_topology/IO/VRML.h>
#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/index_triangles.h>
#include <Soup_topology/internal/PLY_header.h>
#include <Soup_topology/internal/soup_checks.h>

#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/property_map.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstddef>
#include <string>
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
  std::size_t input_triangles = 0;        ///< triangles after fan triangulation of polygons
  std::size_t skipped_polygons = 0;       ///< faces with fewer than 3 vertices, left out
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

/// \ingroup PkgSoupTopologyIO
/// \brief reads `filename` (STL binary or ASCII, OFF, OBJ, PLY, VRML 2.0 `.wrl`, chosen by the
/// extension) into an
/// indexed triangle soup whose exactly equal points are merged: `points` holds distinct points,
/// `triangles` index triples of distinct vertices. Polygons are fan-triangulated.
///
/// STL goes through `read_STL_triangles()` and `index_triangles()`; OFF through
/// `read_OFF_polygons()`, OBJ and PLY through `CGAL::IO::read_polygon_soup()`, then
/// `merge_duplicate_points()`; VRML through `read_VRML()`
/// (every shape's points appended, then merged the same way).
/// \throws Read_error if the file cannot be read or is malformed; Invalid_input for an index out of
/// range or a non-finite coordinate. `points` and `triangles` are unchanged then.
template <class Point, class Face>
Soup_read_report read_triangle_soup(const std::string& filename, std::vector<Point>& points,
                                    std::vector<Face>& triangles)
{
  Soup_read_report report;
  report.format = file_extension(filename);
  std::vector<Point> pts;
  std::vector<Face> tris;
  if(report.format == "stl") {
    const std::string data = read_file_contents(filename);
    std::vector<std::array<Point, 3>> explicit_triangles;
    read_STL_triangles(data, explicit_triangles, filename);
    report.input_polygons = report.input_triangles = explicit_triangles.size();
    report.input_vertices = 3 * explicit_triangles.size();
    for(std::size_t t = 0; t < explicit_triangles.size(); ++t)
      for(const Point& p : explicit_triangles[t])
        if(!std::isfinite(CGAL::to_double(p.x())) || !std::isfinite(CGAL::to_double(p.y())) ||
           !std::isfinite(CGAL::to_double(p.z())))
          throw Invalid_input(filename + ": facet " + std::to_string(t) + " has a non-finite coordinate");
    const Index_report ir = index_triangles(explicit_triangles, pts, tris);
    report.exact_duplicates = ir.input_corners - ir.vertices;
    report.collapsed_triangles = ir.collapsed_triangles;
  } else if(report.format == "off" || report.format == "obj" || report.format == "ply") {
    {
      std::ifstream probe(filename, std::ios::binary);
      if(!probe) throw Read_error(filename + ": cannot open the file for reading");
    }
    std::vector<std::vector<std::size_t>> polygons;
    if(report.format == "off") {
      // Our reader: it checks the header against the data before allocating (see IO/OFF.h).
      read_OFF_polygons(read_file_contents(filename), pts, polygons, filename);
    } else {
      if(report.format == "ply") Soup_topology::internal::check_PLY_header(filename); // see internal/PLY_header.h
      bool ok = false;
      try {
        ok = CGAL::IO::read_polygon_soup(filename, pts, polygons, CGAL::parameters::verbose(false));
      } catch(const std::exception& e) {
        throw Read_error(filename + ": malformed " + report.format + " file (" + e.what() + ")");
      }
      if(!ok) throw Read_error(filename + ": malformed or unsupported " + report.format + " file");
    }
    report.input_polygons = polygons.size();
    report.input_vertices = pts.size();
    Soup_topology::internal::check_finite_points(pts, CGAL::Identity_property_map<Point>());
    for(std::size_t f = 0; f < polygons.size(); ++f) {
      const std::vector<std::size_t>& poly = polygons[f];
      for(std::size_t v : poly)
        if(v >= pts.size())
          throw Invalid_input(filename + ": face " + std::to_string(f) + " has vertex index " + std::to_string(v) +
                              ", out of range (" + std::to_string(pts.size()) + " vertices)");
      if(poly.size() < 3) { ++report.skipped_polygons; continue; }
      for(std::size_t k = 1; k + 1 < poly.size(); ++k)
        tris.push_back(Soup_topology::internal::make_triangle<Face>(poly[0], poly[k], poly[k + 1]));
    }
    report.input_triangles = tris.size();
    report.exact_duplicates = merge_duplicate_points(pts, tris);
    report.collapsed_triangles = remove_collapsed_triangles(tris);
  } else if(report.format == "wrl") {
    const VRML_read_result vr = read_VRML(filename, pts, tris);
    report.input_polygons = vr.number_of_polygons;
    report.input_vertices = pts.size();
    report.input_triangles = tris.size();
    report.skipped_polygons = vr.number_of_short_polygons;
    Soup_topology::internal::check_finite_points(pts, CGAL::Identity_property_map<Point>());
    report.exact_duplicates = merge_duplicate_points(pts, tris);
    report.collapsed_triangles = remove_collapsed_triangles(tris);
  } else {
    throw Read_error(filename + ": unknown file extension '" + report.format +
                     "' (expected .stl, .off, .obj, .ply or .wrl)");
  }
  points.swap(pts);
  triangles.swap(tris);
  return report;
}

} // namespace IO
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_IO_READ_TRIANGLE_SOUP_H
