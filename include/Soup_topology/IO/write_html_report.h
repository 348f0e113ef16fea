// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The HTML report of a repair: one self-contained page (no network request, works from file://)
// with a 3D view of the soup, its remaining border and non-manifold edges, the sites where the
// repair acted, the holes, the before/after table, the tolerance and the gap histogram.

#ifndef SOUP_TOPOLOGY_IO_WRITE_HTML_REPORT_H
#define SOUP_TOPOLOGY_IO_WRITE_HTML_REPORT_H

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/analyze_gaps.h>
#include <Soup_topology/reconstruct_topology.h>
#include <Soup_topology/internal/html_report_mesh.h>
#include <Soup_topology/internal/html_report_page.h>
#include <Soup_topology/internal/tolerance.h>

#include <CGAL/Named_function_parameters.h>
#include <CGAL/number_utils.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace Soup_topology {
namespace IO {

/// \ingroup PkgSoupTopologyIO
/// the number of triangles above which the report page shows a simplified mesh.
constexpr std::size_t default_html_report_display_triangle_limit = 300000;

/// \ingroup PkgSoupTopologyIO
/// the most marker positions of one kind written into a page.
constexpr std::size_t html_report_marker_limit = 100000;

/// \ingroup PkgSoupTopologyIO
/// \brief sites of one kind shown as markers: how many there are, and the positions known.
/// `count` may exceed `positions.size()` when the positions were not all recorded.
struct Html_report_sites
{
  std::size_t count = 0;                          ///< number of sites
  std::vector<std::array<double, 3>> positions;   ///< the positions known, in the coordinates of the points
};

/// \ingroup PkgSoupTopologyIO
/// \brief what the report page shows besides the soup itself.
struct Html_report_content
{
  std::string title = "Soup_topology report";     ///< the page's title
  /// one JSON object, written as it is into the element `report-json` of the page.
  std::string report_json = "{}";
  std::vector<std::string> table_header;          ///< the head of the table (one entry per column)
  std::vector<std::vector<std::string>> table;    ///< its rows: a label, then one value per column
  double tolerance = 0;                           ///< the tolerance, drawn on the gap histogram
  /// the gaps of the input, as `analyze_gaps()` gives them (empty: no histogram, `gap_note` instead).
  std::vector<Gap_histogram_bin> gap_histogram;
  std::string gap_note = "The gaps of the input were not measured.";  ///< said when there is no histogram
  Html_report_sites welded_vertices;              ///< vertices merged within the tolerance
  Html_report_sites t_junction_splits;            ///< triangles split at T-junctions
  Html_report_sites refused_welds;                ///< welds refused
  Html_report_sites refused_splits;               ///< T-junction splits refused
  Html_report_sites ambiguous_sites;              ///< sites where the features are below the tolerance
  std::vector<std::string> notes;                 ///< lines shown under the title
  /// the soup is simplified for display above this many triangles.
  std::size_t display_triangle_limit = default_html_report_display_triangle_limit;
  /// the page's module script; empty: the viewer built with the package (see the manual).
  std::string viewer_script;
  /// the license text of what `viewer_script` holds (written with it).
  std::string viewer_license;
};

/// \ingroup PkgSoupTopologyIO
/// \brief the fields of `report` as one JSON object (its counts, under the names of the
/// `Reconstruction_report` members).
/// \param report the report of `reconstruct_topology()`
inline std::string reconstruction_report_json(const Reconstruction_report& report)
{
  std::string out = "{";
  const auto add = [&out](const char* key, const std::string& value) {
    if(out.size() > 1) out += ", ";
    out += "\"";
    out += key;
    out += "\": " + value;
  };
  const auto count = [&add](const char* key, std::size_t n) { add(key, std::to_string(n)); };
  add("tolerance", ::Soup_topology::internal::html_json_number(report.tolerance));
  count("input_points", report.input_points);
  count("input_triangles", report.input_triangles);
  count("exact_duplicates", report.exact_duplicates);
  count("collapsed_triangles", report.collapsed_triangles);
  count("rounds", report.rounds);
  count("snapped_vertices", report.snapped_vertices);
  count("refused_welds", report.refused_welds());
  count("ambiguous_sites", report.ambiguous_sites);
  count("short_edges", report.short_edges);
  count("t_junctions", report.t_junctions);
  count("split_triangles", report.split_triangles);
  count("refused_splits", report.refused_splits);
  count("ambiguous_t_junctions", report.ambiguous_t_junctions);
  count("border_edges_before", report.border_edges_before);
  count("border_edges_after", report.border_edges_after);
  count("non_manifold_edges_before", report.non_manifold_edges_before);
  count("non_manifold_edges_after", report.non_manifold_edges_after);
  count("non_manifold_vertices_after", report.non_manifold_vertices_after);
  count("components_before", report.components_before);
  count("components", report.components);
  count("output_points", report.output_points);
  count("output_triangles", report.output_triangles);
  add("max_displacement", ::Soup_topology::internal::html_json_number(report.max_displacement));
  add("closed", report.closed() ? "true" : "false");
  return out + "}";
}

/// \ingroup PkgSoupTopologyIO
/// \brief the content of the report page of a repair: the JSON of `report`, the before/after
/// table, the tolerance and the counts of the marker kinds (without positions: a caller that
/// records them with a visitor adds them).
/// \param report the report of `reconstruct_topology()`
inline Html_report_content html_report_content(const Reconstruction_report& report)
{
  Html_report_content c;
  c.title = "Soup_topology repair report";
  c.report_json = reconstruction_report_json(report);
  c.table_header = {"", "before", "after"};
  c.table = {
    {"points", std::to_string(report.input_points), std::to_string(report.output_points)},
    {"triangles", std::to_string(report.input_triangles), std::to_string(report.output_triangles)},
    {"border edges", std::to_string(report.border_edges_before), std::to_string(report.border_edges_after)},
    {"non-manifold edges", std::to_string(report.non_manifold_edges_before), std::to_string(report.non_manifold_edges_after)},
    {"components", std::to_string(report.components_before), std::to_string(report.components)},
    {"closed", report.border_edges_before == 0 ? "yes" : "no", report.closed() ? "yes" : "no"}};
  c.tolerance = report.tolerance;
  c.welded_vertices.count = report.snapped_vertices;
  c.t_junction_splits.count = report.split_triangles;
  c.refused_welds.count = report.refused_welds();
  c.refused_splits.count = report.refused_splits;
  c.ambiguous_sites.count = report.ambiguous_sites + report.ambiguous_t_junctions;
  return c;
}

} // namespace IO

namespace internal {

inline void write_html_sites(std::ostream& os, const char* key, const IO::Html_report_sites& sites,
                             const Html_point& origin, bool& first)
{
  os << (first ? "" : ", ") << '"' << key << "\": [";
  first = false;
  const std::size_t n = std::min(sites.positions.size(), IO::html_report_marker_limit);
  for(std::size_t i = 0; i < n; ++i) {
    const auto& p = sites.positions[i];
    os << (i ? "," : "") << '[' << html_json_float(static_cast<float>(p[0] - origin[0])) << ','
       << html_json_float(static_cast<float>(p[1] - origin[1])) << ','
       << html_json_float(static_cast<float>(p[2] - origin[2])) << ']';
  }
  os << ']';
}

} // namespace internal

namespace IO {

/// \ingroup PkgSoupTopologyIO
/// \brief writes the HTML report page of the soup `points`, `triangles` to `os`.
///
/// The page is one self-contained file: it makes no network request and opens from `file://`.
/// It shows the soup shaded, its border edges (red) and non-manifold edges (magenta) as found
/// by `Adjacency_tables`, the sites of `content` as markers that can be switched on and off by
/// kind, the holes (chains of border edges, longest first; a click flies the camera there), the
/// table, the tolerance and the gap histogram. `content.report_json` is written unchanged
/// (but for `</` written `<\/`, the same JSON value) into
/// `<script type="application/json" id="report-json">`. `<body>` gets `data-ready="true"`
/// once the first frame is drawn.
///
/// A soup of more than `content.display_triangle_limit` triangles is shown simplified by
/// vertex clustering, with the triangles that touch a border or non-manifold edge kept as they
/// are; the holes and the edges are computed on the full soup.
///
/// The viewer script (three.js and the viewer's own code) comes from the header
/// `Soup_topology/internal/html_report_viewer_script.h` that the package's CMake configuration
/// generates and installs, or from `content.viewer_script` when it is not empty.
///
/// \tparam PointRange a random-access range of points (read through `point_map`)
/// \tparam TriangleRange a range of triangles, each a random-access range of 3 indices into `points`
/// \param os the stream the page is written to
/// \param points the points of the soup
/// \param triangles the triangles of the soup
/// \param content the report, the table, the sites and the histogram the page shows
/// \param np optional named parameters among the ones listed below
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{point_map} \cgalParamDescription{the point of an element of `points`}
///     \cgalParamType{a model of `ReadablePropertyMap` whose value is a point of a CGAL kernel}
///     \cgalParamDefault{`CGAL::Identity_property_map`} \cgalParamNEnd
/// \cgalNamedParamsEnd
///
/// \throws Invalid_input on a triangle that does not have 3 indices below `points.size()`.
template <class PointRange, class TriangleRange, class NamedParameters = CGAL::parameters::Default_named_parameters>
void write_html_report(std::ostream& os, const PointRange& points, const TriangleRange& triangles,
                       const Html_report_content& content,
                       const NamedParameters& np = CGAL::parameters::default_values())
{
  using NP_helper = ::Soup_topology::internal::Soup_np_helper<PointRange, NamedParameters>;
  using ::Soup_topology::internal::Html_point;
  using ::Soup_topology::internal::Html_triangle;
  const auto pm = NP_helper::get_point_map(np);

  std::vector<Html_point> pts;
  pts.reserve(points.size());
  for(const auto& e : points) {
    const auto& p = get(pm, e);
    pts.push_back({CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())});
  }
  std::vector<Html_triangle> tris;
  tris.reserve(triangles.size());
  for(const auto& f : triangles) {
    if(f.size() != 3)
      throw Invalid_input("face " + std::to_string(tris.size()) + " has " + std::to_string(f.size()) + " vertices");
    Html_triangle t{};
    for(std::size_t i = 0; i < 3; ++i) {
      const auto v = static_cast<std::size_t>(f[i]);
      if(v >= pts.size())
        throw Invalid_input("face " + std::to_string(tris.size()) + " has the index " + std::to_string(v) +
                            ", beyond the " + std::to_string(pts.size()) + " points");
      t[i] = static_cast<std::uint32_t>(v);
    }
    tris.push_back(t);
  }

  const Adjacency_tables tables(tris, pts.size());
  const std::vector<std::uint32_t> border = ::Soup_topology::internal::html_edge_vertices(tables, tables.border_edges());
  const std::vector<std::uint32_t> non_manifold = ::Soup_topology::internal::html_edge_vertices(tables, tables.non_manifold_edges());
  const std::vector<::Soup_topology::internal::Html_hole> holes = ::Soup_topology::internal::html_holes(pts, border);
  const ::Soup_topology::internal::Html_display_mesh display =
    ::Soup_topology::internal::html_display_mesh(pts, tris, border, non_manifold, content.display_triangle_limit);

  // Coordinates are written relative to the center of the bounding box, in float.
  Html_point origin{0, 0, 0};
  if(!pts.empty()) {
    Html_point low = pts.front(), high = pts.front();
    for(const Html_point& p : pts)
      for(int c = 0; c < 3; ++c) { low[c] = std::min(low[c], p[c]); high[c] = std::max(high[c], p[c]); }
    for(int c = 0; c < 3; ++c) origin[c] = (low[c] + high[c]) / 2;
  }
  std::vector<float> positions;
  positions.reserve(3 * display.points.size());
  for(const Html_point& p : display.points)
    for(int c = 0; c < 3; ++c) positions.push_back(static_cast<float>(p[c] - origin[c]));
  std::vector<std::uint32_t> indices;
  indices.reserve(3 * display.triangles.size());
  for(const Html_triangle& t : display.triangles) indices.insert(indices.end(), t.begin(), t.end());

  using ::Soup_topology::internal::html_json_number;
  using ::Soup_topology::internal::html_json_string;
  using ::Soup_topology::internal::html_script_safe;
  os << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
     << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
     << "<title>" << ::Soup_topology::internal::html_escape(content.title) << "</title>\n"
     << "<style>" << ::Soup_topology::internal::html_report_style() << "</style>\n</head>\n"
     << "<body data-ready=\"false\">\n<div id=\"panel\"></div>\n<canvas id=\"view\"></canvas>\n"
     << "<script type=\"application/json\" id=\"report-json\">" << html_script_safe(content.report_json)
     << "</script>\n";

  os << "<script type=\"application/json\" id=\"viewer-data\">{";
  os << "\"title\": " << html_script_safe(html_json_string(content.title));
  os << ", \"origin\": [" << html_json_number(origin[0]) << ", " << html_json_number(origin[1]) << ", "
     << html_json_number(origin[2]) << "]";
  os << ", \"soup_triangles\": " << tris.size() << ", \"displayed_triangles\": " << display.triangles.size()
     << ", \"display_triangle_limit\": " << content.display_triangle_limit
     << ", \"decimated\": " << (display.decimated ? "true" : "false");
  os << ", \"tolerance\": " << html_json_number(content.tolerance);
  os << ", \"notes\": [";
  for(std::size_t i = 0; i < content.notes.size(); ++i)
    os << (i ? ", " : "") << html_script_safe(html_json_string(content.notes[i]));
  os << "], \"table_header\": [";
  for(std::size_t i = 0; i < content.table_header.size(); ++i)
    os << (i ? ", " : "") << html_script_safe(html_json_string(content.table_header[i]));
  os << "], \"table\": [";
  for(std::size_t r = 0; r < content.table.size(); ++r) {
    os << (r ? ", " : "") << '[';
    for(std::size_t i = 0; i < content.table[r].size(); ++i)
      os << (i ? ", " : "") << html_script_safe(html_json_string(content.table[r][i]));
    os << ']';
  }
  os << "], \"gap_histogram\": [";
  for(std::size_t i = 0; i < content.gap_histogram.size(); ++i) {
    const Gap_histogram_bin& b = content.gap_histogram[i];
    os << (i ? ", " : "") << "{\"lower\": " << html_json_number(b.lower) << ", \"upper\": " << html_json_number(b.upper)
       << ", \"count\": " << b.count << '}';
  }
  os << "], \"gap_note\": " << html_script_safe(html_json_string(content.gap_note));
  os << ", \"marker_counts\": {\"welded_vertices\": " << content.welded_vertices.count
     << ", \"t_junction_splits\": " << content.t_junction_splits.count
     << ", \"refused_welds\": " << content.refused_welds.count
     << ", \"refused_splits\": " << content.refused_splits.count
     << ", \"ambiguous_sites\": " << content.ambiguous_sites.count << '}';
  os << ", \"markers\": {";
  bool first = true;
  ::Soup_topology::internal::write_html_sites(os, "welded_vertices", content.welded_vertices, origin, first);
  ::Soup_topology::internal::write_html_sites(os, "t_junction_splits", content.t_junction_splits, origin, first);
  ::Soup_topology::internal::write_html_sites(os, "refused_welds", content.refused_welds, origin, first);
  ::Soup_topology::internal::write_html_sites(os, "refused_splits", content.refused_splits, origin, first);
  ::Soup_topology::internal::write_html_sites(os, "ambiguous_sites", content.ambiguous_sites, origin, first);
  os << "}, \"holes_total\": " << holes.size() << ", \"holes\": [";
  constexpr std::size_t listed_holes = 500;
  for(std::size_t i = 0; i < std::min(holes.size(), listed_holes); ++i) {
    const ::Soup_topology::internal::Html_hole& h = holes[i];
    os << (i ? ", " : "") << "{\"edges\": " << h.edges << ", \"length\": " << html_json_number(h.length)
       << ", \"size\": " << html_json_number(h.size) << ", \"radius\": " << html_json_number(h.size / 2)
       << ", \"center\": [" << html_json_number(h.center[0] - origin[0]) << ", "
       << html_json_number(h.center[1] - origin[1]) << ", " << html_json_number(h.center[2] - origin[2]) << "]}";
  }
  os << "], \"positions\": \"" << ::Soup_topology::internal::html_base64(positions) << '"';
  os << ", \"triangles\": \"" << ::Soup_topology::internal::html_base64(indices) << '"';
  os << ", \"border_edges\": \"" << ::Soup_topology::internal::html_base64(display.border_edges) << '"';
  os << ", \"non_manifold_edges\": \"" << ::Soup_topology::internal::html_base64(display.non_manifold_edges) << '"';
  os << "}</script>\n";

  os << "<script type=\"text/plain\" id=\"viewer-license\">\n";
  if(content.viewer_script.empty())
    for(const char* part : ::Soup_topology::internal::html_report_viewer_license) os << part;
  else
    os << html_script_safe(content.viewer_license);
  os << "</script>\n<script type=\"module\">\n";
  if(content.viewer_script.empty())
    for(const char* part : ::Soup_topology::internal::html_report_viewer_script) os << part;
  else
    os << html_script_safe(content.viewer_script);
  os << "</script>\n</body>\n</html>\n";
}

} // namespace IO
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_IO_WRITE_HTML_REPORT_H
