// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The gap analysis in the command-line tool:
//   soup_topology gaps FILE [--json]
// `repair --tolerance auto` passes `automatic_tolerance(true)` to the pipeline, which runs the same
// analysis. A soup whose gaps and features overlap has no automatic tolerance: `repair --tolerance
// auto` then stops with exit code 2 and says why, before anything is written (the user gives a
// tolerance by hand, knowing the risk).

#ifndef SOUP_TOPOLOGY_TOOLS_GAPS_COMMAND_H
#define SOUP_TOPOLOGY_TOOLS_GAPS_COMMAND_H

#include <Soup_topology/IO/read_triangle_soup.h>
#include <Soup_topology/analyze_gaps.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <array>
#include <cstdint>
#include <charconv>
#include <cmath>
#include <cstddef>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace soup_topology_tool {

/// a wrong use of `soup_topology gaps` (exit code 2).
struct Gaps_usage_error : std::invalid_argument
{
  using std::invalid_argument::invalid_argument;
};

/// shortest text that reads back as the same double; `null` for an infinite or NaN value.
inline std::string json_number(double x)
{
  if(!std::isfinite(x)) return "null";
  char buffer[64];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, x).ptr;
  return std::string(buffer, end);
}

inline std::string json_string(const std::string& s)
{
  std::string out = "\"";
  for(char c : s) {
    if(c == '"' || c == '\\') { out += '\\'; out += c; }
    else if(static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
      out += buf;
    } else out += c;
  }
  return out + "\"";
}

inline std::string json_histogram(const std::vector<Soup_topology::Gap_histogram_bin>& bins)
{
  std::string out = "[";
  for(std::size_t i = 0; i < bins.size(); ++i) {
    if(i) out += ", ";
    out += "{\"lower\": " + json_number(bins[i].lower) + ", \"upper\": " + json_number(bins[i].upper) +
           ", \"count\": " + std::to_string(bins[i].count) + "}";
  }
  return out + "]";
}

inline std::string json_distribution(const Soup_topology::Size_distribution& d)
{
  return "{\"count\": " + std::to_string(d.count) + ", \"minimum\": " + json_number(d.minimum) +
         ", \"median\": " + json_number(d.median) + ", \"maximum\": " + json_number(d.maximum) + "}";
}

/// the analysis as one JSON object (one line).
inline std::string gap_analysis_json(const std::string& file, const Soup_topology::Gap_analysis& a)
{
  std::string out = "{";
  out += "\"file\": " + json_string(file);
  out += ", \"vertices\": " + std::to_string(a.vertices);
  out += ", \"triangles\": " + std::to_string(a.triangles);
  out += ", \"border_edges\": " + std::to_string(a.border_edges);
  out += ", \"border_vertices\": " + std::to_string(a.border_vertices);
  out += ", \"degenerate_triangles\": " + std::to_string(a.degenerate_triangles);
  out += ", \"bounding_box_diagonal\": " + json_number(a.bounding_box_diagonal);
  out += ", \"search_radius\": " + json_number(a.search_radius);
  out += ", \"measured_gaps\": " + std::to_string(a.gaps.size());
  out += ", \"gaps_beyond_search_radius\": " + std::to_string(a.gaps_beyond_search_radius);
  out += ", \"zero_gaps\": " + std::to_string(a.zero_gaps);
  out += ", \"smallest_gap\": " + (a.gaps.empty() ? std::string("null") : json_number(a.gaps.front()));
  out += ", \"gap_histogram\": " + json_histogram(a.gap_histogram);
  out += ", \"shortest_edges\": " + json_distribution(a.shortest_edges);
  out += ", \"smallest_heights\": " + json_distribution(a.smallest_heights);
  out += ", \"feature_histogram\": " + json_histogram(a.feature_histogram);
  out += ", \"border_features\": " + json_distribution(a.border_features);
  out += ", \"feature_bound\": " + json_number(a.feature_bound);
  out += ", \"verdict\": " + json_string(Soup_topology::verdict_name(a.verdict));
  out += ", \"suggested_tolerance\": " + json_number(a.suggested_tolerance);
  out += ", \"closed_gaps\": " + std::to_string(a.closed_gaps);
  out += ", \"largest_closed_gap\": " + json_number(a.largest_closed_gap);
  out += ", \"smallest_open_gap\": " + json_number(a.smallest_open_gap);
  out += ", \"closing_margin\": " + json_number(a.closing_margin);
  out += ", \"keeping_margin\": " + json_number(a.keeping_margin);
  out += ", \"reasoning\": " + json_string(a.reasoning);
  return out + "}";
}

inline std::string text_histogram(const std::vector<Soup_topology::Gap_histogram_bin>& bins)
{
  std::size_t largest = 1;
  for(const auto& b : bins) largest = std::max(largest, b.count);
  std::string out;
  for(const auto& b : bins) {
    if(b.count == 0) continue; // the JSON output lists the empty bins too
    char line[96];
    std::snprintf(line, sizeof line, "    [%9.3g, %9.3g) %8zu ", b.lower, b.upper, b.count);
    out += line + std::string((b.count * 40 + largest - 1) / largest, '#') + "\n";
  }
  return out;
}

/// the analysis as text for a reader.
inline std::string gap_analysis_text(const std::string& file, const Soup_topology::Gap_analysis& a)
{
  const auto g = [](double x) {
    char buffer[32];
    std::snprintf(buffer, sizeof buffer, "%.6g", x);
    return std::string(buffer);
  };
  std::string out = "soup_topology gaps\n";
  out += "  file                  " + file + "\n";
  out += "  vertices              " + std::to_string(a.vertices) + "\n";
  out += "  triangles             " + std::to_string(a.triangles) + "\n";
  out += "  border_edges          " + std::to_string(a.border_edges) + "\n";
  out += "  border_vertices       " + std::to_string(a.border_vertices) + "\n";
  out += "  bounding_box_diagonal " + g(a.bounding_box_diagonal) + "\n";
  out += "  gaps (nearest border element sharing no triangle, up to " + g(a.search_radius) + "): " +
         std::to_string(a.gaps.size()) + " measured, " + std::to_string(a.zero_gaps) + " of them 0, " +
         std::to_string(a.gaps_beyond_search_radius) + " beyond\n";
  out += text_histogram(a.gap_histogram);
  out += "  shortest edges        min " + g(a.shortest_edges.minimum) + ", median " + g(a.shortest_edges.median) +
         ", max " + g(a.shortest_edges.maximum) + "\n";
  out += "  smallest heights      min " + g(a.smallest_heights.minimum) + ", median " + g(a.smallest_heights.median) +
         ", max " + g(a.smallest_heights.maximum) + "\n";
  out += "  feature sizes (min of shortest edge and smallest height per triangle):\n";
  out += text_histogram(a.feature_histogram);
  out += "  border features       min " + g(a.border_features.minimum) + ", median " + g(a.border_features.median) +
         " (" + std::to_string(a.border_features.count) + ")\n";
  out += "  feature bound         " + g(a.feature_bound) + "\n";
  out += "  verdict               " + std::string(Soup_topology::verdict_name(a.verdict)) + "\n";
  out += "  suggested_tolerance   " + (a.has_suggestion() ? g(a.suggested_tolerance) : std::string("none")) + "\n";
  out += "  reasoning             " + a.reasoning + "\n";
  return out;
}

/// `soup_topology gaps FILE [--json]`: prints the analysis (on TBB's threads with
/// `ConcurrencyTag` = `CGAL::Parallel_tag`: the same output); returns the exit code.
template <class ConcurrencyTag>
int run_gaps(const std::vector<std::string>& args)
{
  std::string file;
  bool json = false;
  for(const std::string& a : args) {
    if(a == "--json") json = true;
    else if(!a.empty() && a[0] == '-') throw Gaps_usage_error("gaps: unknown option '" + a + "'");
    else if(file.empty()) file = a;
    else throw Gaps_usage_error("gaps: more than one input file ('" + file + "' and '" + a + "')");
  }
  if(file.empty()) throw Gaps_usage_error("gaps: no input file");
  std::vector<CGAL::Exact_predicates_inexact_constructions_kernel::Point_3> points;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  Soup_topology::IO::read_triangle_soup<ConcurrencyTag>(file, points, triangles);
  // The soup as read is exactly welded already: the analysis does not weld a copy of it.
  const Soup_topology::Gap_analysis a =
    Soup_topology::internal::analyze_exactly_welded_gaps<ConcurrencyTag>(points, triangles,
                                                                         CGAL::Exact_predicates_inexact_constructions_kernel());
  std::cout << (json ? gap_analysis_json(file, a) + "\n" : gap_analysis_text(file, a));
  std::cout.flush();
  if(!std::cout) throw std::runtime_error("cannot write to standard output");
  return 0;
}

} // namespace soup_topology_tool

#endif // SOUP_TOPOLOGY_TOOLS_GAPS_COMMAND_H
