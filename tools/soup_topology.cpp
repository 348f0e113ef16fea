// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// soup_topology: the command-line face of the library.
//   soup_topology stats FILE [--json]
// Exit codes: 0 success, 2 bad input or arguments (message on stderr).

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/IO/read_triangle_soup.h>
#include <Soup_topology/soup_statistics.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = std::array<std::size_t, 3>;
namespace ST = Soup_topology;

struct Usage_error : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

const char* usage_text =
  "usage:\n"
  "  soup_topology stats FILE [--json]\n"
  "      reads FILE (.stl ASCII or binary, .off, .obj, .ply), welds exactly equal points,\n"
  "      builds the adjacency tables and prints what it found.\n"
  "exit codes: 0 success, 2 bad input or arguments\n";

// An ordered list of "key": value pairs, printed as one JSON object or as aligned text.
class Report
{
public:
  void add(const std::string& key, std::size_t value) { items_.emplace_back(key, std::to_string(value)); }
  void add(const std::string& key, bool value) { items_.emplace_back(key, value ? "true" : "false"); }
  void add(const std::string& key, double value)
  {
    std::ostringstream s;
    s.precision(17);
    s << value;
    items_.emplace_back(key, s.str());
  }
  void add_string(const std::string& key, const std::string& value) { items_.emplace_back(key, quote(value)); }

  std::string json() const
  {
    std::string out = "{";
    for(std::size_t i = 0; i < items_.size(); ++i) {
      if(i) out += ", ";
      out += quote(items_[i].first) + ": " + items_[i].second;
    }
    return out + "}";
  }
  std::string text() const
  {
    std::size_t width = 0;
    for(const auto& kv : items_) width = std::max(width, kv.first.size());
    std::string out;
    for(const auto& kv : items_) {
      std::string v = kv.second;
      if(!v.empty() && v.front() == '"') v = v.substr(1, v.size() - 2);
      out += "  " + kv.first + std::string(width - kv.first.size(), ' ') + "  " + v + "\n";
    }
    return out;
  }

private:
  static std::string quote(const std::string& s)
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
  std::vector<std::pair<std::string, std::string>> items_;
};

void add_statistics(Report& r, const ST::Soup_statistics& s, std::size_t collapsed, const std::string& suffix = "")
{
  r.add("vertices" + suffix, s.vertices);
  r.add("triangles" + suffix, s.triangles);
  r.add("border_edges" + suffix, s.border_edges);
  r.add("non_manifold_edges" + suffix, s.non_manifold_edges);
  r.add("non_manifold_vertices" + suffix, s.non_manifold_vertices);
  r.add("inconsistently_oriented_edges" + suffix, s.inconsistent_edges);
  r.add("components" + suffix, s.components);
  r.add("closed" + suffix, s.closed);
  r.add("degenerate_triangles" + suffix, collapsed + s.zero_area_triangles);
  r.add("collapsed_triangles" + suffix, collapsed);
  r.add("zero_area_triangles" + suffix, s.zero_area_triangles);
}

int run_stats(const std::vector<std::string>& args)
{
  std::string file;
  bool json = false;
  for(const std::string& a : args) {
    if(a == "--json") json = true;
    else if(!a.empty() && a[0] == '-') throw Usage_error("stats: unknown option '" + a + "'");
    else if(file.empty()) file = a;
    else throw Usage_error("stats: more than one input file ('" + file + "' and '" + a + "')");
  }
  if(file.empty()) throw Usage_error("stats: no input file");

  std::vector<Point> points;
  std::vector<Triangle> triangles;
  const ST::IO::Soup_read_report read = ST::IO::read_triangle_soup(file, points, triangles);
  const ST::Adjacency_tables tables(triangles, points.size());
  const ST::Soup_statistics s = ST::compute_statistics(points, tables);

  Report r;
  r.add_string("file", file);
  r.add_string("format", read.format);
  r.add("input_vertices", read.input_vertices);
  r.add("input_polygons", read.input_polygons);
  r.add("exact_duplicates", read.exact_duplicates);
  add_statistics(r, s, read.collapsed_triangles);
  if(json) std::cout << r.json() << "\n";
  else std::cout << "soup_topology stats\n" << r.text();
  return 0;
}

} // namespace

int main(int argc, char** argv)
{
  std::vector<std::string> args(argv + 1, argv + argc);
  if(args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    (args.empty() ? std::cerr : std::cout) << usage_text;
    return args.empty() ? 2 : 0;
  }
  const std::string command = args[0];
  args.erase(args.begin());
  try {
    if(command == "stats") return run_stats(args);
    throw Usage_error("unknown command '" + command + "'");
  } catch(const Usage_error& e) {
    std::cerr << "soup_topology: " << e.what() << "\n" << usage_text;
    return 2;
  } catch(const ST::IO::Read_error& e) {
    std::cerr << "soup_topology: " << e.what() << "\n";
    return 2;
  } catch(const ST::Invalid_input& e) {
    std::cerr << "soup_topology: invalid input: " << e.what() << "\n";
    return 2;
  } catch(const std::bad_alloc&) {
    std::cerr << "soup_topology: out of memory\n";
    return 2;
  } catch(const std::exception& e) {
    std::cerr << "soup_topology: error: " << e.what() << "\n";
    return 2;
  }
}
