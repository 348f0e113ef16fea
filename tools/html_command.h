// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The HTML report of the command-line tool:
//   soup_topology stats FILE --html REPORT.html
//   soup_topology repair IN -o OUT ... --html REPORT.html
// The page embeds the object that `--json` prints, and shows the soup (as read for `stats`, as
// written for `repair`), the gap histogram of the input and, for `repair`, the sites where the
// repair acted (welds, splits, refusals, ambiguous sites) at the points of the input. Like the
// other outputs, the page is written to a temporary file and renamed over REPORT.html.

#ifndef SOUP_TOPOLOGY_TOOLS_HTML_COMMAND_H
#define SOUP_TOPOLOGY_TOOLS_HTML_COMMAND_H

#include <Soup_topology/IO/write_html_report.h>
#include <Soup_topology/analyze_gaps.h>
#include <Soup_topology/reconstruct_topology.h>
#include <Soup_topology/soup_statistics.h>

#include "output_files.h"

#include <array>
#include <cstdint>
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace soup_topology_tool {

/// the soup as read, kept for the page of a repair (the repair changes it in place), and the
/// sites the repair tells, as indices of its points.
template <class Point>
struct Html_input_soup
{
  std::vector<Point> points;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  Soup_topology::IO::Html_report_site_recorder sites;
};

/// checks that REPORT.html is none of the other files of the command and can be written.
inline void check_html_path(const std::string& html, const std::vector<std::string>& other_files)
{
  for(const std::string& f : other_files)
    if(!f.empty() && same_file(html, f))
      throw File_error(html + ": the HTML report would replace '" + f + "'; choose another name");
  check_writable_target(html, "HTML report");
}

/// the gap histogram of `points`, `triangles` into `content` (or why there is none). The soup is
/// the one `read_triangle_soup` gave, exactly welded already: the analysis does not weld a copy.
template <class Point>
void add_input_gaps(Soup_topology::IO::Html_report_content& content, const std::vector<Point>& points,
                    const std::vector<std::array<std::uint32_t, 3>>& triangles)
{
  try {
    using Kernel = typename CGAL::Kernel_traits<Point>::Kernel;
    const Soup_topology::Gap_analysis gaps =
      Soup_topology::internal::analyze_exactly_welded_gaps(points, triangles, Kernel());
    content.gap_histogram = gaps.gap_histogram;
    if(gaps.gap_histogram.empty())
      content.gap_note = gaps.border_edges == 0 ? "The input has no border edge: no gap to measure."
                                                : "No positive gap was measured within the search radius.";
  } catch(const Soup_topology::Invalid_input& e) {
    content.gap_note = std::string("The gaps were not measured: ") + e.what();
  }
}

/// writes `content` and the soup to `file` through a temporary file.
template <class Point>
void write_html_page(const std::string& file, const std::vector<Point>& points,
                     const std::vector<std::array<std::uint32_t, 3>>& triangles,
                     const Soup_topology::IO::Html_report_content& content)
{
  Temporary_output page(file);
  Soup_topology::IO::write_html_report(page.stream(), points, triangles, content);
  page.finish();
  page.commit();
}

/// the page of `soup_topology stats`: the soup as read (exactly welded).
template <class Point>
void write_stats_html(const std::string& file, const std::string& input, const std::vector<Point>& points,
                      const std::vector<std::array<std::uint32_t, 3>>& triangles,
                      const Soup_topology::Soup_statistics& s, const std::string& report_json)
{
  Soup_topology::IO::Html_report_content c;
  c.title = "soup_topology stats " + std::filesystem::path(input).filename().string();
  c.report_json = report_json;
  c.table_header = {"", "input"};
  c.table = {{"vertices", std::to_string(s.vertices)},
             {"triangles", std::to_string(s.triangles)},
             {"border edges", std::to_string(s.border_edges)},
             {"non-manifold edges", std::to_string(s.non_manifold_edges)},
             {"non-manifold vertices", std::to_string(s.non_manifold_vertices)},
             {"components", std::to_string(s.components)},
             {"closed", s.closed ? "yes" : "no"}};
  add_input_gaps(c, points, triangles);
  write_html_page(file, points, triangles, c);
}

/// the page of `soup_topology repair`: the soup written, the counts of `r`, the input's gaps
/// and the sites recorded in `input.sites`, at the points of `input`.
template <class Point>
void write_repair_html(const std::string& file, const std::string& input_name, const Html_input_soup<Point>& input,
                       const std::vector<Point>& points, const std::vector<std::array<std::uint32_t, 3>>& triangles,
                       const Soup_topology::Reconstruction_report& r, const std::string& report_json)
{
  Soup_topology::IO::Html_report_content c = Soup_topology::IO::html_report_content(r);
  c.title = "soup_topology repair " + std::filesystem::path(input_name).filename().string();
  c.report_json = report_json;
  add_input_gaps(c, input.points, input.triangles);
  Soup_topology::IO::add_site_positions(c, input.sites, input.points);
  write_html_page(file, points, triangles, c);
}

} // namespace soup_topology_tool

#endif // SOUP_TOPOLOGY_TOOLS_HTML_COMMAND_H
