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
#include <Soup_topology/internal/coordinate_scale.h>
#include <Soup_topology/internal/html_report_mesh.h>
#include <Soup_topology/internal/html_report_page.h>
#include <Soup_topology/internal/tolerance.h>

#include <CGAL/Named_function_parameters.h>
#include <CGAL/number_utils.h>

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <ostream>
#include <string>
#include <utility>
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
/// \brief sites of one kind shown as markers: how many the report counts, and where they are.
/// `count` is the number of events of the report; `positions` holds each place once (an event
/// repeated in several rounds, or a vertex near two border edges, is one place), and is empty
/// when the positions were not recorded (`add_site_positions()`).
struct Html_report_sites
{
  std::size_t count = 0;                          ///< number of events
  std::vector<std::array<double, 3>> positions;   ///< the places known, in the coordinates of the points
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
/// table, the tolerance and the counts of the marker kinds (without positions: see
/// `add_site_positions()`).
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

/// \ingroup PkgSoupTopologyIO
/// \brief a visitor of `reconstruct_topology()` that records where the repair acted, for the
/// markers of the report page (`add_site_positions()`). Give it as `visitor(std::ref(recorder))`.
///
/// It is a snap visitor and a split visitor (the members of `Default_snap_visitor` and
/// `Default_split_visitor`) and is told the ambiguous sites of the weld; it keeps the indices of
/// the points given to `reconstruct_topology()`, one entry per event the `Reconstruction_report`
/// counts.
struct Html_report_site_recorder
{
  std::vector<std::size_t> welded_vertices;   ///< the vertex merged into another, per weld
  std::vector<std::size_t> t_junction_splits; ///< the vertex a triangle was split at, per split
  /// the two vertices (the one refused, the representative) of each refused weld
  std::vector<std::array<std::size_t, 2>> refused_welds;
  std::vector<std::size_t> refused_splits;    ///< the vertex of each refused split
  /// the smallest point of each ambiguous site of the weld, and the vertex of each ambiguous T-junction
  std::vector<std::size_t> ambiguous_sites;

  /// `duplicate` is merged into `representative`.
  void on_merge(std::size_t duplicate, std::size_t /*representative*/) { welded_vertices.push_back(duplicate); }
  /// the merge of `vertex` into `representative` is refused.
  void on_refusal(std::size_t vertex, std::size_t representative, Refusal_reason /*reason*/)
  { refused_welds.push_back({vertex, representative}); }
  /// a triangle along the border edge `[a,b]` is split at `vertex`.
  void on_split(std::size_t vertex, std::size_t /*a*/, std::size_t /*b*/) { t_junction_splits.push_back(vertex); }
  /// the split of `[a,b]` at `vertex` is refused.
  void on_split_refusal(std::size_t vertex, std::size_t /*a*/, std::size_t /*b*/, Split_refusal_reason /*reason*/)
  { refused_splits.push_back(vertex); }
  /// `vertex` is an ambiguous T-junction near `[a,b]`.
  void on_ambiguous_t_junction(std::size_t vertex, std::size_t /*a*/, std::size_t /*b*/)
  { ambiguous_sites.push_back(vertex); }
  /// `vertex` is the smallest point of an ambiguous site of the weld.
  void on_ambiguous_site(std::size_t vertex) { ambiguous_sites.push_back(vertex); }
};

} // namespace IO

namespace internal {

/// the point of element `v` of `points`, read through `pm`, in double.
template <class PointRange, class PointMap>
Html_point html_point_at(const PointRange& points, const PointMap& pm, std::size_t v)
{
  const auto& p = get(pm, *(points.begin() + static_cast<std::ptrdiff_t>(v)));
  return {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
}

/// `positions` sorted lexicographically, each once.
inline std::vector<Html_point> html_sorted_positions(std::vector<Html_point> positions)
{
  std::sort(positions.begin(), positions.end());
  positions.erase(std::unique(positions.begin(), positions.end()), positions.end());
  return positions;
}

/// the positions of `sites` (indices into `points`, read through `pm`), sorted, each once.
template <class PointRange, class PointMap>
std::vector<Html_point> html_site_positions(const std::vector<std::size_t>& sites, const PointRange& points,
                                            const PointMap& pm)
{
  std::vector<Html_point> out;
  out.reserve(sites.size());
  for(std::size_t v : sites) out.push_back(html_point_at(points, pm, v));
  return html_sorted_positions(std::move(out));
}

/// throws `Invalid_input` if an index held by `recorder` is not below `n`.
inline void check_site_indices(const IO::Html_report_site_recorder& recorder, std::size_t n)
{
  const auto check = [n](std::size_t v) {
    if(v >= n)
      throw Invalid_input("add_site_positions: the vertex " + std::to_string(v) + " is beyond the " +
                          std::to_string(n) + " input points");
  };
  for(const auto* list : {&recorder.welded_vertices, &recorder.t_junction_splits, &recorder.refused_splits,
                          &recorder.ambiguous_sites})
    for(std::size_t v : *list) check(v);
  for(const auto& pair : recorder.refused_welds) { check(pair[0]); check(pair[1]); }
}

} // namespace internal

namespace IO {

/// \ingroup PkgSoupTopologyIO
/// \brief sets the marker positions of `content` from what `recorder` was told during
/// `reconstruct_topology()`.
///
/// The positions are those of the points given to `reconstruct_topology()` (`input_points`, as
/// they were before the call replaced them; an output point keeps the coordinates of the input
/// point it comes from): for a weld, the vertex merged away; for a split, a refused split and an
/// ambiguous T-junction, the vertex found near the border edge (within the tolerance of it); for
/// a refused weld, the midpoint of the two vertices (within half the tolerance of each); for an
/// ambiguous site of the weld, its lexicographically smallest point. Each kind is sorted
/// lexicographically and holds each position once, so the content does not depend on the order of
/// the input; the counts of `content` (from `html_report_content()`) are left as they are.
///
/// \tparam PointRange a random-access range of points (read through `point_map`)
/// \param content the content whose `welded_vertices`, `t_junction_splits`, `refused_welds`,
///        `refused_splits` and `ambiguous_sites` positions are replaced
/// \param recorder the visitor given to `reconstruct_topology()`
/// \param input_points the points given to `reconstruct_topology()`
/// \param np optional named parameters among the ones listed below
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{point_map} \cgalParamDescription{the point of an element of `input_points`}
///     \cgalParamType{a model of `ReadablePropertyMap` whose value is a point of a CGAL kernel}
///     \cgalParamDefault{`CGAL::Identity_property_map`} \cgalParamNEnd
/// \cgalNamedParamsEnd
///
/// \throws Invalid_input when an index held by `recorder` is not below the number of `input_points`.
template <class PointRange, class NamedParameters = CGAL::parameters::Default_named_parameters>
void add_site_positions(Html_report_content& content, const Html_report_site_recorder& recorder,
                        const PointRange& input_points,
                        const NamedParameters& np = CGAL::parameters::default_values())
{
  namespace in = ::Soup_topology::internal;
  const auto pm = in::Soup_np_helper<PointRange, NamedParameters>::get_point_map(np);
  in::check_site_indices(recorder, static_cast<std::size_t>(std::distance(input_points.begin(), input_points.end())));
  content.welded_vertices.positions = in::html_site_positions(recorder.welded_vertices, input_points, pm);
  content.t_junction_splits.positions = in::html_site_positions(recorder.t_junction_splits, input_points, pm);
  content.refused_splits.positions = in::html_site_positions(recorder.refused_splits, input_points, pm);
  content.ambiguous_sites.positions = in::html_site_positions(recorder.ambiguous_sites, input_points, pm);
  std::vector<in::Html_point> midpoints;
  midpoints.reserve(recorder.refused_welds.size());
  for(const auto& pair : recorder.refused_welds) {
    const in::Html_point p = in::html_point_at(input_points, pm, pair[0]);
    const in::Html_point q = in::html_point_at(input_points, pm, pair[1]);
    // The same sum whichever vertex comes first: the midpoint does not depend on the order.
    midpoints.push_back({p[0] / 2 + q[0] / 2, p[1] / 2 + q[1] / 2, p[2] / 2 + q[2] / 2});
  }
  content.refused_welds.positions = in::html_sorted_positions(std::move(midpoints));
}

} // namespace IO

namespace internal {

/// the soup as the page uses it: the points in double, the triangles checked.
struct Html_soup
{
  std::vector<Html_point> points;
  std::vector<Html_triangle> triangles;
};

/// reads `points` through `pm` and checks that every element of `triangles` has 3 indices below
/// `points.size()`.
template <class PointRange, class TriangleRange, class PointMap>
Html_soup html_soup(const PointRange& points, const TriangleRange& triangles, const PointMap& pm)
{
  Html_soup soup;
  soup.points.reserve(points.size());
  for(const auto& e : points) {
    const auto& p = get(pm, e);
    soup.points.push_back({CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())});
  }
  soup.triangles.reserve(triangles.size());
  for(const auto& f : triangles) {
    if(f.size() != 3)
      throw Invalid_input("face " + std::to_string(soup.triangles.size()) + " has " + std::to_string(f.size()) +
                          " vertices");
    Html_triangle t{};
    for(std::size_t i = 0; i < 3; ++i) {
      const auto v = static_cast<std::size_t>(f[i]);
      if(v >= soup.points.size())
        throw Invalid_input("face " + std::to_string(soup.triangles.size()) + " has the index " + std::to_string(v) +
                            ", beyond the " + std::to_string(soup.points.size()) + " points");
      t[i] = static_cast<std::uint32_t>(v);
    }
    soup.triangles.push_back(t);
  }
  return soup;
}

/// the center of the bounding box of `points` (the origin of the coordinates written in float),
/// and in `half_extent` the largest half side of that box. Halves are added rather than the
/// sum halved so that coordinates near the largest double do not overflow (the same value
/// otherwise: halving a normal double is exact).
inline Html_point html_center(const std::vector<Html_point>& points, double& half_extent)
{
  Html_point origin{0, 0, 0};
  half_extent = 0;
  if(points.empty()) return origin;
  Html_point low = points.front(), high = points.front();
  for(const Html_point& p : points)
    for(std::size_t c = 0; c < 3; ++c) { low[c] = std::min(low[c], p[c]); high[c] = std::max(high[c], p[c]); }
  for(std::size_t c = 0; c < 3; ++c) {
    origin[c] = low[c] / 2 + high[c] / 2;
    half_extent = std::max(half_extent, high[c] / 2 - low[c] / 2);
  }
  return origin;
}

/// the exponent e of the view's unit: the page writes the points at `(p - origin) * 2^e`, in
/// float. It is 0 (the soup's own unit) when the half extent of the soup lies between 2^-32 and
/// 2^32; otherwise the half extent becomes a length between 1 and 2. Beyond that range, float
/// coordinates relative to the center would lose their digits to underflow or overflow (a soup
/// near 1e-270 was drawn as one point, one near 1e300 not at all), and so would the viewer's
/// camera, which works in float on the GPU. A power of two changes no digit of a coordinate.
inline int html_view_exponent(double half_extent)
{
  return exponent_into_unit_range(half_extent, 32);
}

/// `values` as a JSON array of strings.
inline std::string html_json_strings(const std::vector<std::string>& values)
{
  std::string out = "[";
  for(std::size_t i = 0; i < values.size(); ++i) out += (i ? ", " : "") + html_script_safe(html_json_string(values[i]));
  return out + "]";
}

/// where the page's coordinates are: a point `p` of the soup is drawn at `(p - origin) * 2^exponent`.
struct Html_view
{
  Html_point origin{0, 0, 0};
  int exponent = 0;

  /// `p`, in the soup's coordinates, in the view's. A larger unit scales first, so that a
  /// difference of coordinates near the largest double does not overflow; a smaller one scales
  /// the difference, so that a small soup far from the origin does not overflow either.
  Html_point to_view(const Html_point& p) const
  {
    Html_point q;
    for(std::size_t c = 0; c < 3; ++c)
      q[c] = exponent <= 0 ? std::ldexp(p[c], exponent) - std::ldexp(origin[c], exponent)
                           : std::ldexp(p[c] - origin[c], exponent);
    return q;
  }
  /// a length of the view as a length of the soup.
  double to_soup_length(double length) const { return std::ldexp(length, -exponent); }
};

/// `view.to_view(p)` as a JSON array of three floats.
inline std::string html_json_relative_point(const Html_point& p, const Html_view& view)
{
  const Html_point q = view.to_view(p);
  return '[' + html_json_float(static_cast<float>(q[0])) + ',' + html_json_float(static_cast<float>(q[1])) + ',' +
         html_json_float(static_cast<float>(q[2])) + ']';
}

/// the text of the side panel: title, tolerance, notes, table and gap histogram.
inline void write_html_tables(std::ostream& os, const IO::Html_report_content& content)
{
  os << "\"title\": " << html_script_safe(html_json_string(content.title));
  os << ", \"tolerance\": " << html_json_number(content.tolerance);
  os << ", \"notes\": " << html_json_strings(content.notes);
  os << ", \"table_header\": " << html_json_strings(content.table_header) << ", \"table\": [";
  for(std::size_t r = 0; r < content.table.size(); ++r) os << (r ? ", " : "") << html_json_strings(content.table[r]);
  os << "], \"gap_histogram\": [";
  for(std::size_t i = 0; i < content.gap_histogram.size(); ++i) {
    const Gap_histogram_bin& b = content.gap_histogram[i];
    os << (i ? ", " : "") << "{\"lower\": " << html_json_number(b.lower) << ", \"upper\": " << html_json_number(b.upper)
       << ", \"count\": " << b.count << '}';
  }
  os << "], \"gap_note\": " << html_script_safe(html_json_string(content.gap_note));
}

/// the holes, longest first (at most `listed` of them), measured on the points `points_origin`
/// away from the view's origin, in the view's unit: their lengths and sizes in the soup's unit,
/// their radii and centers in the view's.
inline void write_html_holes(std::ostream& os, const std::vector<Html_hole>& holes, const Html_point& points_origin,
                             const Html_view& view)
{
  constexpr std::size_t listed = 500;
  os << ", \"holes_total\": " << holes.size() << ", \"holes\": [";
  for(std::size_t i = 0; i < std::min(holes.size(), listed); ++i) {
    const Html_hole& h = holes[i];
    os << (i ? ", " : "") << "{\"edges\": " << h.edges
       << ", \"length\": " << html_json_number(view.to_soup_length(h.length))
       << ", \"size\": " << html_json_number(view.to_soup_length(h.size))
       << ", \"radius\": " << html_json_number(h.size / 2)
       << ", \"center\": [" << html_json_number(h.center[0] - points_origin[0]) << ", "
       << html_json_number(h.center[1] - points_origin[1]) << ", " << html_json_number(h.center[2] - points_origin[2])
       << "]}";
  }
  os << ']';
}

/// the counts and the positions (in the view's coordinates, at most `IO::html_report_marker_limit`)
/// of every marker kind.
inline void write_html_markers(std::ostream& os, const IO::Html_report_content& content, const Html_view& view)
{
  const std::pair<const char*, const IO::Html_report_sites*> kinds[] = {
    {"welded_vertices", &content.welded_vertices}, {"t_junction_splits", &content.t_junction_splits},
    {"refused_welds", &content.refused_welds},     {"refused_splits", &content.refused_splits},
    {"ambiguous_sites", &content.ambiguous_sites}};
  os << ", \"marker_counts\": {";
  for(std::size_t k = 0; k < std::size(kinds); ++k)
    os << (k ? ", " : "") << '"' << kinds[k].first << "\": " << kinds[k].second->count;
  os << "}, \"markers\": {";
  for(std::size_t k = 0; k < std::size(kinds); ++k) {
    const std::vector<std::array<double, 3>>& positions = kinds[k].second->positions;
    os << (k ? ", " : "") << '"' << kinds[k].first << "\": [";
    for(std::size_t i = 0; i < std::min(positions.size(), IO::html_report_marker_limit); ++i)
      os << (i ? "," : "") << html_json_relative_point(positions[i], view);
    os << ']';
  }
  os << '}';
}

/// the display mesh: its size, and its points (`points_origin` away from the view's origin, in
/// float), triangles and edges in base64; the view's origin and exponent.
inline void write_html_display_mesh(std::ostream& os, const Html_display_mesh& display, std::size_t soup_triangles,
                                    std::size_t limit, const Html_point& points_origin, const Html_view& view)
{
  std::vector<float> positions;
  positions.reserve(3 * display.points.size());
  for(const Html_point& p : display.points)
    for(std::size_t c = 0; c < 3; ++c) positions.push_back(static_cast<float>(p[c] - points_origin[c]));
  std::vector<std::uint32_t> indices;
  indices.reserve(3 * display.triangles.size());
  for(const Html_triangle& t : display.triangles) indices.insert(indices.end(), t.begin(), t.end());
  os << ", \"origin\": [" << html_json_number(view.origin[0]) << ", " << html_json_number(view.origin[1]) << ", "
     << html_json_number(view.origin[2]) << "], \"view_exponent\": " << view.exponent;
  os << ", \"soup_triangles\": " << soup_triangles << ", \"displayed_triangles\": " << display.triangles.size()
     << ", \"display_triangle_limit\": " << limit << ", \"decimated\": " << (display.decimated ? "true" : "false");
  os << ", \"positions\": \"" << html_base64(positions) << '"';
  os << ", \"triangles\": \"" << html_base64(indices) << '"';
  os << ", \"border_edges\": \"" << html_base64(display.border_edges) << '"';
  os << ", \"non_manifold_edges\": \"" << html_base64(display.non_manifold_edges) << '"';
}

/// the page up to the element `viewer-data`: the head, the panel, the canvas and `report-json`.
inline void write_html_page_head(std::ostream& os, const IO::Html_report_content& content)
{
  os << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
     << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
     << "<title>" << html_escape(content.title) << "</title>\n"
     << "<style>" << html_report_style() << "</style>\n</head>\n"
     << "<body data-ready=\"false\">\n<div id=\"panel\"></div>\n<canvas id=\"view\"></canvas>\n"
     << "<script type=\"application/json\" id=\"report-json\">" << html_script_safe(content.report_json)
     << "</script>\n";
}

/// the page after the element `viewer-data`: the viewer's license and script.
inline void write_html_page_scripts(std::ostream& os, const IO::Html_report_content& content)
{
  os << "<script type=\"text/plain\" id=\"viewer-license\">\n";
  if(content.viewer_script.empty())
    for(const char* part : html_report_viewer_license) os << part;
  else
    os << html_script_safe(content.viewer_license);
  os << "</script>\n<script type=\"module\">\n";
  if(content.viewer_script.empty())
    for(const char* part : html_report_viewer_script) os << part;
  else
    os << html_script_safe(content.viewer_script);
  os << "</script>\n</body>\n</html>\n";
}

} // namespace internal

namespace IO {

/// \ingroup PkgSoupTopologyIO
/// \brief writes the HTML report page of the soup `points`, `triangles` to `os`.
///
/// The page is one self-contained file: it makes no network request and opens from `file://`.
/// It shows the soup shaded, its border edges (red) and non-manifold edges (magenta) as found
/// by `Adjacency_tables`, the sites of `content` as markers that can be switched on and off by
/// kind (the ambiguous sites in yellow), the open problems (the holes, chains of border edges,
/// longest first, then the ambiguous sites; a click flies the camera there), the table, the
/// tolerance and the gap histogram. `content.report_json` is written unchanged
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
  namespace in = ::Soup_topology::internal;
  // The tables and the holes, on the full soup.
  in::Html_soup soup =
    in::html_soup(points, triangles, in::Soup_np_helper<PointRange, NamedParameters>::get_point_map(np));
  // The view: coordinates are written relative to the center of the bounding box, in float, in
  // a unit that keeps their digits (`html_view_exponent()`). In the soup's own unit, the points
  // are used as they are; in another, they are moved into the view's coordinates first, and so
  // the holes and the display mesh are computed there.
  double half_extent = 0;
  in::Html_view view;
  view.origin = in::html_center(soup.points, half_extent);
  view.exponent = in::html_view_exponent(half_extent);
  in::Html_point points_origin = view.origin;
  if(view.exponent != 0) {
    for(in::Html_point& p : soup.points) p = view.to_view(p);
    points_origin = {0, 0, 0};
  }
  const Adjacency_tables tables(soup.triangles, soup.points.size());
  const std::vector<std::uint32_t> border = in::html_edge_vertices(tables, tables.border_edges());
  const std::vector<std::uint32_t> non_manifold = in::html_edge_vertices(tables, tables.non_manifold_edges());
  const std::vector<in::Html_hole> holes = in::html_holes(soup.points, border);
  // The display mesh, simplified above the limit.
  const in::Html_display_mesh display =
    in::html_display_mesh(soup.points, soup.triangles, border, non_manifold, content.display_triangle_limit);
  // The markers and the page.
  in::write_html_page_head(os, content);
  os << "<script type=\"application/json\" id=\"viewer-data\">{";
  in::write_html_tables(os, content);
  in::write_html_markers(os, content, view);
  in::write_html_holes(os, holes, points_origin, view);
  in::write_html_display_mesh(os, display, soup.triangles.size(), content.display_triangle_limit, points_origin, view);
  os << "}</script>\n";
  in::write_html_page_scripts(os, content);
}

} // namespace IO
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_IO_WRITE_HTML_REPORT_H
