// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The commands of soup_topology, the command-line face of the library, and of soup_topology_mpi
// (tools/tool_commands.h):
//   soup_topology stats FILE [--json] [--html REPORT.html] [--threads N]
//   soup_topology gaps FILE [--json] [--threads N]
//   soup_topology repair IN -o OUT [--tolerance T|auto|per-part | --relative-tolerance R] [--report FILE.json]
//                        [--json] [--check] [--no-t-junctions] [--self-intersections]
//                        [--orientation P] [--small-features collapse|refuse] [--html REPORT.html]
//                        [--threads N]
//   mpirun -np K soup_topology_mpi IN -o OUT --tolerance T [--tiles N | --max-memory SIZE] ...
// (the usage texts below describe every option)
// Exit codes: 0 success, 1 `--check` found the written result not closed, not manifold or (with
//             --self-intersections) self-intersecting, 2 bad input, arguments or a file that
//             cannot be written (message on stderr).

#include "tool_commands.h"

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/IO/read_triangle_soup.h>
#include <Soup_topology/reconstruct_topology.h>
#include <Soup_topology/tiled_reconstruct_topology.h>
#include <Soup_topology/IO/write_triangle_soup.h>
#include <Soup_topology/orient_triangle_soup.h>
#include <Soup_topology/internal/orient_soup_in_parts.h>
#include <Soup_topology/soup_statistics.h>

#include "gaps_command.h"
#include "html_command.h"
#include "memory_reuse.h"
#include "output_files.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/tags.h>

#if defined(CGAL_LINKED_WITH_TBB)
#include <tbb/global_control.h>
#include <tbb/task_scheduler_observer.h>

#include <pthread.h>
#include <unistd.h>
#include <signal.h>
#endif

#include <boost/iterator/function_output_iterator.hpp>

#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Triangle = std::array<std::uint32_t, 3>; // 4-byte indices: the readers refuse a soup of more points
namespace ST = Soup_topology;
namespace tool = soup_topology_tool;
// The steps run on TBB's threads when the tool is built with TBB; the output is the same.
using Concurrency = CGAL::Parallel_if_available_tag;

struct Usage_error : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

const char* usage_text =
  "usage:\n"
  "  soup_topology stats FILE [--json] [--html REPORT.html] [--threads N]\n"
  "      reads FILE (.stl ASCII or binary, .off, .obj, .ply, .wrl), welds exactly equal points,\n"
  "      builds the adjacency tables and prints what it found.\n"
  "  soup_topology gaps FILE [--json] [--threads N]\n"
  "      measures the gaps between the borders and the feature sizes, and suggests a tolerance.\n"
  "  soup_topology repair IN -o OUT [--tolerance T|auto|per-part | --relative-tolerance R]\n"
  "                       [--report FILE.json]\n"
  "                       [--json] [--check] [--no-t-junctions] [--self-intersections]\n"
  "                       [--orientation bound-volume|keep-input|outward]\n"
  "                       [--small-features collapse|refuse] [--html REPORT.html] [--threads N]\n"
  "                       [--tiles N [--spill-folder DIR] | --max-memory SIZE]\n"
  "      reads IN (formats as for stats, and .wrl VRML 2.0), welds exact duplicates, welds vertices\n"
  "      within the tolerance (absolute T, or R times the bounding-box diagonal; auto: the one the\n"
  "      gap analysis suggests; per-part: the one it suggests for each part, two points welded\n"
  "      within the smaller of theirs; default: exact duplicates only), splits T-junctions,\n"
  "      repeats until nothing changes, orients every component, separates non-manifold vertices\n"
  "      and edges by duplicating their points, and\n"
  "      writes OUT (.off, .obj, .ply binary, or .stl binary: refused if float rounding would\n"
  "      change the mesh). Prints the report (--json: one JSON object); --report also writes it\n"
  "      to FILE.json. The report's counts (closed, border_edges, ...) describe the file written;\n"
  "      soup_* fields describe the repaired soup before the separation.\n"
  "      --self-intersections counts the pairs of written triangles that intersect.\n"
  "      --orientation chooses how closed parts are turned: bound-volume (default: nested shells\n"
  "      alternate, outermost outward, so a part with a cavity keeps it), keep-input (every part\n"
  "      consistent as read keeps its orientation) or outward (every closed part outward).\n"
  "      --small-features chooses what becomes of two vertices of one triangle within the\n"
  "      tolerance (a sliver): collapse (default: merged, the triangle removed) or refuse (left\n"
  "      apart and reported as ambiguous).\n"
  "      --html writes a self-contained HTML page with a 3D view of the result (stats: of the\n"
  "      input), its border edges, the holes, the report and the gap histogram of the input;\n"
  "      for repair also the sites where it welded, split, refused or found ambiguity.\n"
  "      --tiles N repairs the soup in N tiles, one after the other (a binary STL is streamed,\n"
  "      never held whole), with --tolerance T: the same triangles on the same points, in a\n"
  "      canonical order; the report gives the tiles' runs instead of the weld's counts.\n"
  "      With --tiles N or --max-memory SIZE, IN may be several binary STL files, the parts of\n"
  "      an assembly, streamed and repaired together as one soup.\n"
  "      --spill-folder DIR (with --tiles or --max-memory): where the tiles' spill files go (in\n"
  "      a new folder, removed at the end; default: the temporary directory).\n"
  "      --max-memory SIZE (e.g. 500M, 4G; with --tolerance T) keeps the peak resident memory\n"
  "      under SIZE by a model of it: in memory when the soup fits, else in the fewest tiles\n"
  "      (a power of two) that fit; the output is oriented one part (whole components) at a\n"
  "      time when it does not fit whole (the same file); refused (exit 2) when SIZE is below\n"
  "      what the merge and the orientation of the output need. The report gives the model's\n"
  "      peak and the output's parts.\n"
  "      --check exits with code 1 when the written result is not closed, not manifold, or\n"
  "      (with --self-intersections) self-intersecting.\n"
  "      OUT and the report are written completely to private temporary files, then renamed\n"
  "      over their targets (keeping an existing file's permissions); on an error or a signal\n"
  "      nothing is replaced and no temporary file is left. OUT and the report must differ\n"
  "      from IN and from each other.\n"
  "  --threads N (stats, gaps, repair): use at most N threads (default: all cores; the result is the\n"
  "      same for every N).\n"
"exit codes: 0 success, 1 --check failed, 2 bad input or arguments, or an output that cannot be written\n";

// An ordered list of "key": value pairs, printed as one JSON object or as aligned text.
class Report
{
public:
  void add(const std::string& key, std::size_t value) { items_.emplace_back(key, std::to_string(value)); }
  void add(const std::string& key, bool value) { items_.emplace_back(key, value ? "true" : "false"); }
  void add(const std::string& key, double value)
  {
    // Shortest text that reads back as the same double.
    char buffer[64];
    const auto end = std::to_chars(buffer, buffer + sizeof buffer, value).ptr;
    items_.emplace_back(key, std::string(buffer, end));
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
  static std::string quote(const std::string& s) { return tool::json_string(s); }
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

// Prints `text` on standard output and checks that it got there (a full disk, a closed pipe).
void print(const std::string& text)
{
  std::cout << text;
  std::cout.flush();
  if(!std::cout) {
    const int e = errno;
    throw std::runtime_error(std::string("cannot write to standard output (") +
                             (e ? std::strerror(e) : "write failed") + ")");
  }
}

// What the reader left out or triangulated: nothing read is dropped without a count.
void add_read_counts(Report& r, const ST::IO::Soup_read_report& read)
{
  r.add("skipped_polygons", read.skipped_polygons);
  r.add("non_simple_polygons", read.non_simple_polygons);
  r.add("non_convex_polygons", read.non_convex_polygons);
  r.add("ear_clipping_failures", read.ear_clipping_failures);
}

#if defined(CGAL_LINKED_WITH_TBB)
// TBB's worker threads block SIGINT, SIGTERM and SIGHUP when they join: those signals reach the
// main thread, where the output files block them while a temporary file is being registered.
class Worker_signal_mask : public tbb::task_scheduler_observer
{
public:
  Worker_signal_mask() { observe(true); }
  void on_scheduler_entry(bool is_worker) override
  {
    if(!is_worker) return;
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    sigaddset(&set, SIGTERM);
    sigaddset(&set, SIGHUP);
    pthread_sigmask(SIG_BLOCK, &set, nullptr);
  }
};

// The mask holds for the whole process: a worker may join until the process ends. The observer
// is never destroyed, so it never leaves TBB's list while a thread still counts it as the last
// observer it told (TBB then keeps its record alive, unreferenced, until exit, and the leak
// checker of the sanitizer build reports it).
void mask_signals_in_worker_threads()
{
  static Worker_signal_mask* const mask = new Worker_signal_mask;
  (void)mask;
}
#endif

// At most `threads` threads for the steps that run in parallel (0: TBB's default, all cores).
class Thread_limit
{
public:
  explicit Thread_limit(std::size_t threads)
  {
#if defined(CGAL_LINKED_WITH_TBB)
    mask_signals_in_worker_threads();
    if(threads > 0) limit_.emplace(tbb::global_control::max_allowed_parallelism, threads);
#else
    (void)threads;
#endif
  }
private:
#if defined(CGAL_LINKED_WITH_TBB)
  std::optional<tbb::global_control> limit_;
#endif
};

std::size_t parse_threads(const std::string& command, const std::string& text)
{
  std::size_t n = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), n);
  if(error != std::errc() || end != text.data() + text.size() || n == 0 || n > 4096)
    throw Usage_error(command + ": --threads takes a number of threads from 1 to 4096, not '" + text + "'");
  return n;
}

int run_stats(const std::vector<std::string>& args)
{
  std::string file;
  bool json = false;
  std::string html;
  std::size_t threads = 0;
  for(std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    if(a == "--json") json = true;
    else if(a == "--html") {
      if(i + 1 >= args.size()) throw Usage_error("stats: --html needs a value");
      html = args[++i];
    }
    else if(a == "--threads") {
      if(i + 1 >= args.size()) throw Usage_error("stats: --threads needs a value");
      threads = parse_threads("stats", args[++i]);
    }
    else if(!a.empty() && a[0] == '-') throw Usage_error("stats: unknown option '" + a + "'");
    else if(file.empty()) file = a;
    else throw Usage_error("stats: more than one input file ('" + file + "' and '" + a + "')");
  }
  if(file.empty()) throw Usage_error("stats: no input file");
  if(!html.empty()) tool::check_html_path(html, {file});
  const Thread_limit limit(threads);

  std::vector<Point> points;
  std::vector<Triangle> triangles;
  const ST::IO::Soup_read_report read = ST::IO::read_triangle_soup<Concurrency>(file, points, triangles);
  const ST::Adjacency_tables tables(triangles, points.size(), Concurrency());
  const ST::Soup_statistics s = ST::compute_statistics<Concurrency>(points, tables);

  Report r;
  r.add_string("file", file);
  r.add_string("format", read.format);
  r.add("input_vertices", read.input_vertices);
  r.add("input_polygons", read.input_polygons);
  add_read_counts(r, read);
  r.add("exact_duplicates", read.exact_duplicates);
  add_statistics(r, s, read.collapsed_triangles);
  if(!html.empty()) tool::write_stats_html(html, file, points, triangles, s, r.json());
  print(json ? r.json() + "\n" : "soup_topology stats\n" + r.text());
  return 0;
}

ST::Orientation_policy parse_orientation_policy(const std::string& text)
{
  if(text == "bound-volume") return ST::Orientation_policy::BOUND_VOLUME;
  if(text == "keep-input") return ST::Orientation_policy::KEEP_INPUT;
  if(text == "outward") return ST::Orientation_policy::OUTWARD;
  throw Usage_error("repair: --orientation takes bound-volume, keep-input or outward, not '" + text + "'");
}

ST::Small_features parse_small_features(const std::string& text)
{
  if(text == "collapse") return ST::Small_features::COLLAPSE;
  if(text == "refuse") return ST::Small_features::REFUSE;
  throw Usage_error("repair: --small-features takes collapse or refuse, not '" + text + "'");
}

double parse_number(const std::string& option, const std::string& text)
{
  char* end = nullptr;
  errno = 0;
  const double x = std::strtod(text.c_str(), &end);
  // ERANGE also reports an underflow: a subnormal (1e-320) or zero result is a valid tolerance,
  // an overflow (1e999) is not a number the tool can use.
  if(text.empty() || *end != '\0' || (errno == ERANGE && std::abs(x) > 1))
    throw Usage_error(option + ": '" + text + "' is not a number");
  if(!std::isfinite(x) || x < 0) throw Usage_error(option + ": the tolerance must be a finite number >= 0, got '" + text + "'");
  return x;
}

class Progress
{
public:
  explicit Progress(bool on) : on_(on), start_(std::chrono::steady_clock::now()) {}
  void operator()(const std::string& what) const
  {
    if(!on_) return;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    std::cerr << "[" << std::fixed << std::setprecision(2) << s << " s] " << what << std::endl;
  }
private:
  bool on_;
  std::chrono::steady_clock::time_point start_;
};

// Checks the paths of a repair before anything is read: OUT and the report are neither IN nor
// each other, their folders exist and can be written, neither is a directory.
void check_repair_paths(const std::string& in, const std::string& out, const std::string& report_file)
{
  if(tool::same_file(in, out))
    throw Usage_error("repair: the output file is the input file ('" + out + "'); choose another name");
  if(!report_file.empty()) {
    if(tool::same_file(in, report_file))
      throw Usage_error("repair: the report file is the input file ('" + report_file + "'); choose another name");
    if(tool::same_file(out, report_file))
      throw Usage_error("repair: the report file is the output file ('" + report_file + "'); choose another name");
  }
  tool::check_writable_target(out, "output");
  if(!report_file.empty()) {
    const std::filesystem::path rp(report_file);
    if(rp.has_parent_path() && !std::filesystem::is_directory(rp.parent_path()))
      throw Usage_error("repair: the folder of the report file does not exist ('" + report_file + "')");
    tool::check_writable_target(report_file, "report");
  }
}

// Number of pairs of triangles of the oriented, separated soup that intersect other than by a
// shared vertex or edge.
std::size_t count_self_intersecting_pairs(const std::vector<Point>& points, const std::vector<Triangle>& triangles)
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  if(!PMP::is_polygon_soup_a_polygon_mesh(triangles))
    throw std::logic_error("the oriented soup is not a polygon mesh");
  CGAL::Surface_mesh<Point> mesh;
  PMP::polygon_soup_to_polygon_mesh(points, triangles, mesh);
  std::size_t pairs = 0;
  PMP::self_intersections(mesh, boost::make_function_output_iterator([&pairs](const auto&) { ++pairs; }));
  return pairs;
}

struct Repair_options
{
  std::string in, out, report_file, out_format, html_file;
  bool json = false, check = false, split = true, self_intersections = false;
  std::optional<double> tolerance, relative;
  bool automatic = false;        // --tolerance auto: the gap analysis chooses the tolerance
  bool per_part = false;         // --tolerance per-part: the analysis per part, a tolerance per point
  std::size_t threads = 0;       // --threads N; 0: all cores
  std::size_t tiles = 0;         // --tiles N; 0: the soup in memory
  std::string spill_folder;      // --spill-folder DIR; empty: the temporary directory
  std::vector<std::string> more_inputs; // the other files of an assembly (binary STL, in tiles)
  std::optional<double> max_memory; // --max-memory SIZE, in bytes: the number of tiles is chosen
  ST::Orientation_policy orientation_policy = ST::Orientation_policy::BOUND_VOLUME;
  ST::Small_features small_features = ST::internal::small_features_policy(CGAL::parameters::default_values());
};

// "500M", "4G", "1.5G", "300000K", or bytes: powers of 1024.
double parse_memory(const std::string& text)
{
  char* end = nullptr;
  const double x = std::strtod(text.c_str(), &end);
  double unit = 1;
  const std::string suffix(end);
  if(suffix == "K" || suffix == "k") unit = 1024.0;
  else if(suffix == "M" || suffix == "m") unit = 1024.0 * 1024;
  else if(suffix == "G" || suffix == "g") unit = 1024.0 * 1024 * 1024;
  else if(!suffix.empty()) unit = 0;
  if(text.empty() || end == text.c_str() || unit == 0 || !std::isfinite(x) || x <= 0)
    throw Usage_error("repair: --max-memory takes a size such as 500M or 4G, not '" + text + "'");
  return x * unit;
}

std::size_t parse_tiles(const std::string& text)
{
  char* end = nullptr;
  const unsigned long n = std::strtoul(text.c_str(), &end, 10);
  if(text.empty() || *end != '\0' || text[0] == '-' || n < 1 || n > 4096)
    throw Usage_error("repair: --tiles takes a number of tiles from 1 to 4096, not '" + text + "'");
  return n;
}

Repair_options parse_repair_arguments(const std::vector<std::string>& args)
{
  Repair_options o;
  for(std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& {
      if(i + 1 >= args.size()) throw Usage_error("repair: " + a + " needs a value");
      return args[++i];
    };
    if(a == "-o" || a == "--output") o.out = value();
    else if(a == "--tolerance") {
      const std::string& v = value();
      o.automatic = v == "auto";
      o.per_part = v == "per-part";
      if(o.automatic || o.per_part) o.tolerance.reset();
      else o.tolerance = parse_number(a, v);
    }
    else if(a == "--relative-tolerance") o.relative = parse_number(a, value());
    else if(a == "--report") o.report_file = value();
    else if(a == "--html") o.html_file = value();
    else if(a == "--json") o.json = true;
    else if(a == "--check") o.check = true;
    else if(a == "--no-t-junctions") o.split = false;
    else if(a == "--self-intersections") o.self_intersections = true;
    else if(a == "--orientation") o.orientation_policy = parse_orientation_policy(value());
    else if(a == "--small-features") o.small_features = parse_small_features(value());
    else if(a == "--threads") o.threads = parse_threads("repair", value());
    else if(a == "--tiles") o.tiles = parse_tiles(value());
    else if(a == "--spill-folder") o.spill_folder = value();
    else if(a == "--max-memory") o.max_memory = parse_memory(value());
    else if(!a.empty() && a[0] == '-') throw Usage_error("repair: unknown option '" + a + "'");
    else if(o.in.empty()) o.in = a;
    else o.more_inputs.push_back(a);
  }
  if(o.in.empty()) throw Usage_error("repair: no input file");
  if(o.out.empty()) throw Usage_error("repair: no output file (-o OUT)");
  if((o.tolerance || o.automatic || o.per_part) && o.relative)
    throw Usage_error("repair: give --tolerance or --relative-tolerance, not both");
  if(o.tiles > 0 && (!o.tolerance || !o.html_file.empty()))
    throw Usage_error("repair: --tiles needs an absolute --tolerance T, and makes no --html page");
  if(o.max_memory && (o.tiles > 0 || !o.tolerance || !o.html_file.empty()))
    throw Usage_error("repair: --max-memory needs an absolute --tolerance T, and goes without --tiles N and --html");
  if(!o.more_inputs.empty() && o.tiles == 0 && !o.max_memory)
    throw Usage_error("repair: more than one input file ('" + o.in + "' and '" + o.more_inputs[0] +
                      "'): the files of an assembly are repaired together with --tiles N or --max-memory SIZE");
  o.out_format = ST::IO::file_extension(o.out);
  if(o.out_format != "off" && o.out_format != "obj" && o.out_format != "ply" && o.out_format != "stl")
    throw Usage_error("repair: unknown output extension '" + o.out_format + "' (expected .off, .obj, .ply or .stl)");
  return o;
}

// What --tolerance per-part chose, in words: the parts (largest first), each with its tolerance
// and its verdict; past the first `listed` parts (an assembly may have thousands), their number
// and the range of their tolerances only, so that the report stays short.
std::string per_part_choice(const std::vector<ST::Part_gap_analysis>& parts, std::size_t listed = 10)
{
  std::string text = std::to_string(parts.size()) + (parts.size() == 1 ? " part" : " parts");
  char buffer[64];
  auto tolerance = [](const ST::Part_gap_analysis& p) {
    return p.verdict == ST::Gap_verdict::SUGGESTED ? p.suggested_tolerance : 0.0;
  };
  for(std::size_t k = 0; k < std::min(parts.size(), listed); ++k) {
    const ST::Part_gap_analysis& p = parts[k];
    std::snprintf(buffer, sizeof buffer, "%.3g", tolerance(p));
    text += std::string(k == 0 ? ": " : "; ") + std::to_string(p.triangles) + " triangles, tolerance " + buffer + " (" +
            ST::verdict_name(p.verdict) + ")";
  }
  if(parts.size() > listed) {
    double smallest = tolerance(parts[listed]), largest = smallest;
    std::size_t suggested = 0;
    for(std::size_t k = listed; k < parts.size(); ++k) {
      smallest = std::min(smallest, tolerance(parts[k]));
      largest = std::max(largest, tolerance(parts[k]));
      suggested += parts[k].verdict == ST::Gap_verdict::SUGGESTED ? 1 : 0;
    }
    std::snprintf(buffer, sizeof buffer, "%.3g to %.3g", smallest, largest);
    text += "; " + std::to_string(parts.size() - listed) + " more parts, " + std::to_string(suggested) +
            " with a suggestion, tolerances " + buffer;
  }
  return text;
}

// The soup as read is exactly welded already (read_triangle_soup): the pipeline does not weld
// it a second time.
// `visitor` is told what the repair did (the sites of the HTML report), or is a
// `Default_snap_visitor` that records nothing.
template <class Visitor>
ST::Reconstruction_report reconstruct(const Repair_options& o, std::vector<Point>& points, std::vector<Triangle>& triangles,
                                      Visitor& visitor)
{
  const auto told = CGAL::parameters::visitor(std::ref(visitor));
  const auto split = ST::parameters::small_features(o.small_features, ST::parameters::do_split_t_junctions(o.split, told));
  if(o.tolerance)
    return ST::internal::reconstruct_exactly_welded_soup<Concurrency>(
      points, triangles, ST::parameters::small_features(o.small_features, ST::parameters::do_split_t_junctions(
                                                          o.split, told.snapping_tolerance(*o.tolerance))));
  if(o.relative)
    return ST::internal::reconstruct_exactly_welded_soup<Concurrency>(
      points, triangles, ST::parameters::small_features(o.small_features, ST::parameters::do_split_t_junctions(
                                                          o.split, ST::parameters::relative_tolerance(*o.relative, told))));
  if(o.automatic) {
    try {
      return ST::internal::reconstruct_exactly_welded_soup<Concurrency>(
        points, triangles, ST::parameters::small_features(o.small_features, ST::parameters::do_split_t_junctions(
                                                            o.split, ST::parameters::automatic_tolerance(true, told))));
    } catch(const ST::Invalid_input& e) {
      throw std::runtime_error(std::string("--tolerance auto: ") + e.what() + " with --tolerance T (see 'soup_topology gaps')");
    }
  }
  if(o.per_part) {
    // Each part of the soup gets the tolerance its own analysis suggests (0 for a part without
    // suggestion: only exact duplicates there), and two points weld within the smaller of theirs.
    std::vector<ST::Part_gap_analysis> parts;
    try {
      parts = ST::analyze_gaps_per_part<Concurrency>(points, triangles);
    } catch(const ST::Invalid_input& e) {
      throw std::runtime_error(std::string("--tolerance per-part: ") + e.what() + " with --tolerance T (see 'soup_topology gaps')");
    }
    const std::vector<double> tolerances = ST::per_part_vertex_tolerances(parts, points.size());
    ST::Reconstruction_report r = ST::internal::reconstruct_exactly_welded_soup<Concurrency>(
      points, triangles, ST::parameters::small_features(o.small_features, ST::parameters::do_split_t_junctions(
                           o.split, ST::parameters::vertex_tolerance_map(CGAL::make_property_map(tolerances), told))));
    r.tolerance_reasoning = per_part_choice(parts);
    return r;
  }
  return ST::internal::reconstruct_exactly_welded_soup<Concurrency>(points, triangles, split);
}

// The report of a repair. `r` describes the repaired soup (its final counts are those of the
// soup before the orientation), `s` the soup written.
Report repair_report(const Repair_options& o, const ST::IO::Soup_read_report& read, const ST::Reconstruction_report& r,
                     const ST::Orientation_report& orientation, const ST::Soup_statistics& s,
                     const std::optional<std::size_t>& intersecting)
{
  Report rep;
  rep.add_string("input", o.in);
  rep.add_string("output", o.out);
  rep.add_string("format", read.format);
  rep.add("input_vertices", read.input_vertices);
  rep.add("input_triangles", read.input_triangles);
  add_read_counts(rep, read);
  rep.add("exact_duplicates", read.exact_duplicates);
  rep.add("tolerance", r.tolerance);
  if(r.automatic_tolerance)
    rep.add_string("tolerance_choice", std::string(ST::verdict_name(r.tolerance_verdict)) + ": " + r.tolerance_reasoning);
  else if(o.per_part)
    rep.add_string("tolerance_choice", "per part: " + r.tolerance_reasoning);
  add_statistics(rep, s, 0);
  if(intersecting) rep.add("self_intersecting_pairs", *intersecting);
  rep.add("soup_vertices", r.output_points);
  rep.add("soup_triangles", r.output_triangles);
  rep.add("soup_border_edges", r.border_edges_after);
  rep.add("soup_non_manifold_edges", r.non_manifold_edges_after);
  rep.add("soup_non_manifold_vertices", r.non_manifold_vertices_after);
  rep.add("soup_components", r.components);
  rep.add("soup_closed", r.closed());
  rep.add("border_edges_before", r.border_edges_before);
  rep.add("border_edges_after", r.border_edges_after);
  rep.add("non_manifold_edges_before", r.non_manifold_edges_before);
  rep.add("non_manifold_edges_after", r.non_manifold_edges_after);
  rep.add("snapped_vertices", r.snapped_vertices);
  rep.add("refused", r.refused_welds() + r.refused_splits);
  rep.add("refused_welds", r.refused_welds());
  rep.add("refused_splits", r.refused_splits);
  rep.add("ambiguous", r.ambiguous_sites + r.ambiguous_t_junctions);
  rep.add("short_edges", r.short_edges);
  rep.add_string("small_features", r.small_features == ST::Small_features::COLLAPSE ? "collapse" : "refuse");
  rep.add("small_features_resolved", r.small_features_resolved);
  rep.add("small_feature_collapsed_triangles", r.small_feature_collapsed_triangles);
  rep.add("flipped_degenerate_triangles", r.flipped_degenerate_triangles);
  rep.add("removed_degenerate_triangles", r.removed_degenerate_triangles);
  rep.add("refused_uncovered_collapse", r.refused_uncovered_collapse);
  rep.add("t_junctions", r.t_junctions);
  rep.add("split_triangles", r.split_triangles);
  rep.add("rounds", r.rounds);
  rep.add("collapsed_triangles_removed", read.collapsed_triangles);
  rep.add("removed_points", r.removed_points);
  rep.add("max_displacement", r.max_displacement);
  rep.add("duplicate_triangles_removed", orientation.duplicate_triangles);
  rep.add("orientation_flips", orientation.orientation_flips);
  rep.add("duplicated_points", orientation.duplicated_points);
  rep.add("output_vertices", s.vertices);
  rep.add("output_triangles", s.triangles);
  return rep;
}

// Every output complete in its temporary file before any is renamed: a report that cannot be
// written leaves OUT as it was.
void write_repair_outputs(const Repair_options& o, const std::vector<Point>& points,
                          const std::vector<Triangle>& triangles, const Report& rep, const Progress& progress)
{
  tool::Temporary_output mesh_file(o.out);
  try {
    ST::IO::write_triangle_soup<Concurrency>(mesh_file.stream(), o.out_format, points, triangles);
  } catch(const ST::IO::Write_error& e) {
    throw tool::File_error(o.out + ": " + e.what());
  }
  mesh_file.finish();
  progress("wrote " + o.out);
  std::optional<tool::Temporary_output> report_output;
  if(!o.report_file.empty()) {
    report_output.emplace(o.report_file);
    report_output->stream() << rep.json() << "\n";
    report_output->finish();
  }
  mesh_file.commit();
  if(report_output) report_output->commit();
}

// What is written: repeated triangles left out, components oriented, non-manifold vertices and
// edges separated by duplicated points; its statistics (the report's counts) and, when asked,
// its self-intersections. With `part_triangles`, the soup is oriented and measured one part of
// at most that many triangles at a time (whole components; the same file and counts), so that the
// tables of the whole soup are never held.
struct Written_soup
{
  ST::Orientation_report orientation;
  ST::Soup_statistics statistics;
  std::optional<std::size_t> intersecting;
  std::size_t parts = 1;
  std::size_t largest_part = 0; // triangles of the largest part (0: oriented whole)

  Written_soup(const Repair_options& o, std::vector<Point>& points, std::vector<Triangle>& triangles,
               const Progress& progress, std::optional<std::size_t> part_triangles = std::nullopt)
  {
    const auto policy = ST::parameters::orientation_policy(o.orientation_policy);
    if(part_triangles) {
      const ST::internal::Oriented_in_parts r =
        ST::internal::orient_triangle_soup_in_parts<Concurrency>(points, triangles, *part_triangles, policy);
      orientation = r.report;
      statistics = r.statistics;
      parts = r.parts;
      largest_part = r.largest_part_triangles;
    } else {
      orientation = ST::orient_triangle_soup<Concurrency>(points, triangles, policy);
      statistics =
        ST::compute_statistics<Concurrency>(points, ST::Adjacency_tables(triangles, points.size(), Concurrency()));
    }
    progress(part_triangles ? "oriented the soup in " + std::to_string(parts) + " parts"
                            : std::string("oriented the soup"));
    if(o.self_intersections) {
      intersecting = count_self_intersecting_pairs(points, triangles);
      progress("counted self-intersections");
    }
  }
  // the exit code: 1 when `--check` finds the written soup not closed, not manifold or
  // self-intersecting, else 0
  int exit_code(const Repair_options& o) const
  {
    const bool failed = !statistics.closed || statistics.non_manifold_edges > 0 || statistics.non_manifold_vertices > 0 ||
                        (intersecting && *intersecting > 0);
    return o.check && failed ? 1 : 0;
  }
};

// `true` if `file` is a binary STL whose size matches its facet count (the tiling streams it).
bool is_binary_stl(const std::string& file)
{
  if(ST::IO::file_extension(file) != "stl") return false;
  std::ifstream in(file, std::ios::binary);
  char header[84];
  if(!in.read(header, 84)) return false;
  if(ST::IO::internal::starts_with_solid(header, header + 84) && !ST::IO::internal::has_binary_byte(header, header + 84))
    return false;
  std::uint32_t n;
  std::memcpy(&n, header + 80, 4);
  in.seekg(0, std::ios::end);
  return static_cast<std::uint64_t>(in.tellg()) == 84 + 50 * std::uint64_t(n);
}

// A folder of its own for the spill files, made in `base` (default: the temporary directory),
// removed with everything in it.
class Spill_folder
{
public:
  explicit Spill_folder(const std::string& base)
  {
    namespace fs = std::filesystem;
    const fs::path parent = base.empty() ? fs::temp_directory_path() : fs::path(base);
    if(!fs::is_directory(parent)) throw ST::IO::Write_error(parent.string() + ": no such folder for the spill files");
    for(unsigned k = 0;; ++k) {
      path_ = parent / ("soup_topology_tiles_" + std::to_string(::getpid()) + "_" + std::to_string(k));
      if(fs::create_directory(path_)) break;
    }
  }
  ~Spill_folder()
  {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  Spill_folder(const Spill_folder&) = delete;
  Spill_folder& operator=(const Spill_folder&) = delete;
  std::string path() const { return path_.string(); }
private:
  std::filesystem::path path_;
};

// The model of the peak resident memory of `repair --tiles N` (doc/Soup_topology/Tiled_repair.md,
// "Bounded memory"), in bytes, for a soup of `n` triangles of which `held` bytes are held whole
// (a soup that is not a binary STL is read whole first). Measured on the jittered tori of 1M and
// 4M triangles: the largest region is at most 1.25 times a tile's share plus 25,000 triangles of
// halo, and a region costs at most 640 bytes a triangle of that bound while it is repaired (560
// measured with 4 KiB pages; with its large blocks in huge pages, 566 on 1 thread and 598 on 2,
// the regions of 8 tiles of 4M; the triangles kept go to part files). After the tiles: the
// merge, 12 bytes an output triangle and 56 an output point (the points of the parts with their
// order and their output index, the output points, then the output triangles), then the
// orientation and the statistics, 64 a triangle and 48 a point (the soup and the tables of the
// output). For one point to two triangles, as on a closed mesh, that is 88 a triangle (78
// measured at 4M, 86 at 40M); a soup of loose triangles (3 points a triangle) needs 208 (300k:
// 93 MiB measured while the kept triangles were in memory). Where the whole output does not fit,
// it is oriented in parts of whole components (`orient_triangle_soup_in_parts()`): the soup held
// (12 a triangle, 24 a point) with a state a triangle and a part a point (1 and 4), the closed
// patches of parts whose boxes meet (4 a triangle at most: counted), and one part at a time, 88
// a triangle of the part (84 measured on closed tori, with its points, copy, tables and
// orientation).
struct Tiled_memory_model
{
  static constexpr double base = 16.0 * 1024 * 1024, per_region_triangle = 640, merge_per_triangle = 12,
                          merge_per_point = 56, per_output_triangle = 64, per_output_point = 48,
                          parts_per_triangle = 17, parts_per_point = 28,
                          per_part_triangle = 88, smallest_part = 65536;
  double n, held;
  // the peak while the tiles are repaired
  double tiles_peak(std::size_t tiles) const
  {
    const double region = tiles == 1 ? n : std::min(n, 1.25 * n / double(tiles) + 25000);
    return base + held + per_region_triangle * region;
  }
  // the peak of the merge of `triangles` on `points`
  static double merge_need(double triangles, double points)
  {
    return base + merge_per_triangle * triangles + merge_per_point * points;
  }
  // the peak of the merge, the orientation of the whole soup and the writing
  static double output_need(double triangles, double points)
  {
    return std::max(merge_need(triangles, points), base + per_output_triangle * triangles + per_output_point * points);
  }
  // the largest part of the orientation in parts that `limit` allows (the soup held, its parts'
  // numbers and states, then one part's copy, tables and orientation); 0 if none
  static double largest_part(double triangles, double points, double limit)
  {
    const double room = limit - base - parts_per_triangle * triangles - parts_per_point * points;
    return room > 0 ? std::floor(room / per_part_triangle) : 0;
  }
  // whether the output fits under `limit`: the merge, then the orientation whole or in parts of
  // at least `smallest_part` triangles
  static bool output_fits(double triangles, double points, double limit)
  {
    return merge_need(triangles, points) <= limit &&
           (output_need(triangles, points) <= limit || largest_part(triangles, points, limit) >= smallest_part);
  }
  // the peak of the merge, the orientation in parts of at most `part` triangles and the writing
  static double output_in_parts_need(double triangles, double points, double part)
  {
    return std::max(merge_need(triangles, points),
                    base + parts_per_triangle * triangles + parts_per_point * points + per_part_triangle * part);
  }
  // the least the output needs: whole, or in parts of `smallest_part` triangles
  static double least_output_need(double triangles, double points)
  {
    return std::min(output_need(triangles, points), output_in_parts_need(triangles, points, smallest_part));
  }
  // the modelled peak of the output under `limit`, one point for two triangles: whole if that
  // fits, else in the largest parts the limit allows
  double output_peak(double limit) const
  {
    const double p = n / 2;
    if(output_need(n, p) <= limit) return output_need(n, p);
    return output_in_parts_need(n, p, std::min(n, largest_part(n, p, limit)));
  }
  double peak(std::size_t tiles, double limit) const { return std::max(tiles_peak(tiles), output_peak(limit)); }
};

std::string mebibytes(double bytes)
{
  return std::to_string(static_cast<long long>(std::ceil(bytes / (1024.0 * 1024)))) + "M";
}

// --max-memory: the fewest tiles (a power of two up to 4096) whose modelled peak fits.
std::size_t choose_tiles(const Tiled_memory_model& model, double limit)
{
  if(!Tiled_memory_model::output_fits(model.n, model.n / 2, limit))
    throw std::runtime_error("repair: --max-memory " + mebibytes(limit) + " is too small for " +
                      std::to_string(static_cast<long long>(model.n)) + " triangles: the merge and the orientation of the " +
                      "output are in memory and need about " +
                      mebibytes(Tiled_memory_model::least_output_need(model.n, model.n / 2)));
  for(std::size_t tiles = 1; tiles <= 4096; tiles *= 2)
    if(model.tiles_peak(tiles) <= limit) return tiles;
  throw std::runtime_error("repair: --max-memory " + mebibytes(limit) + " is too small: 4096 tiles need about " +
                    mebibytes(model.peak(4096, limit)));
}

// Every input file: IN, then the other files of an assembly.
std::vector<std::string> all_inputs(const Repair_options& o)
{
  std::vector<std::string> files{o.in};
  files.insert(files.end(), o.more_inputs.begin(), o.more_inputs.end());
  return files;
}

// The inputs as the report names them: separated by spaces.
std::string input_names(const Repair_options& o)
{
  std::string names = o.in;
  for(const std::string& file : o.more_inputs) names += " " + file;
  return names;
}

// The number of triangles of a binary STL (is_binary_stl() checked it).
std::uint64_t binary_stl_triangles(const std::string& file)
{
  std::ifstream in(file, std::ios::binary);
  char header[84];
  in.read(header, 84);
  std::uint32_t n = 0;
  std::memcpy(&n, header + 80, 4);
  return n;
}

// A soup read whole before the choice between the repair in memory and in tiles.
struct Read_soup
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  ST::IO::Soup_read_report read;
};

// `repair --tiles N` (or `--max-memory SIZE`): tiled_reconstruct_topology() by `team` (one
// process, or the ranks of soup_topology_mpi), then rank 0 orients and writes as `repair` does.
// `given`: the soup, if it is read already.
int run_tiled_repair(const Repair_options& o, tool::Tile_team& team, Read_soup* given = nullptr)
{
  const bool root = team.rank() == 0;
  // On a terminal, rank 0's progress: tiles done, triangles a second, time left.
  const bool show = root && ::isatty(STDERR_FILENO) == 1;
  const auto start = std::chrono::steady_clock::now();
  const auto display = [show, start](const ST::Tile_progress& p) {
    if(!show) return;
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double rate = seconds > 0 ? double(p.triangles_done) / seconds : 0;
    std::cerr << "\rtile " << p.runs_done << "/" << p.runs;
    if(p.round > 0) std::cerr << " (again, round " << p.round << ")";
    std::cerr << ", " << static_cast<long long>(rate) << " triangles/s";
    if(rate > 0) std::cerr << ", about " << static_cast<long long>(double(p.triangles - p.triangles_done) / rate) << " s left";
    std::cerr << "     " << std::flush;
  };
  const auto np = ST::parameters::tile_progress(
    display, ST::parameters::small_features(o.small_features,
                                            ST::parameters::do_split_t_junctions(
                                              o.split, CGAL::parameters::snapping_tolerance(*o.tolerance))));
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  ST::Tiled_reconstruction_report t;
  std::string format = "stl";
  std::optional<Tiled_memory_model> model;
  std::size_t tiles = o.tiles;
  {
    // Rank 0 makes the folder; the others are told its path.
    std::optional<Spill_folder> own;
    std::vector<char> path;
    if(root) {
      own.emplace(o.spill_folder);
      const std::string p = own->path();
      path.assign(p.begin(), p.end());
    }
    team.broadcast(path);
    const std::string folder(path.begin(), path.end());
    if(given == nullptr && is_binary_stl(o.in)) {
      // The files of an assembly are streamed as one soup.
      const std::vector<std::string> files = all_inputs(o);
      double n = 0;
      for(const std::string& file : files) {
        if(!is_binary_stl(file))
          throw Usage_error("repair: '" + file + "' is not a binary STL: the files of an assembly are streamed, each must be one");
        n += double(binary_stl_triangles(file));
      }
      if(o.max_memory) {
        model = Tiled_memory_model{n, 0.0};
        tiles = choose_tiles(*model, *o.max_memory);
      }
      t = ST::tiled_reconstruct_topology<Concurrency>(team, ST::Binary_STL_source(files), tiles, folder, points, triangles, np);
    } else {
      if(!o.more_inputs.empty())
        throw Usage_error("repair: '" + o.in + "' is not a binary STL: the files of an assembly are streamed, each must be one");
      // Only rank 0 reads the soup (the others never read the source).
      std::vector<Point> in_points;
      std::vector<Triangle> in_triangles;
      if(given != nullptr) {
        in_points.swap(given->points);
        in_triangles.swap(given->triangles);
        format = given->read.format;
      } else if(root) {
        format = ST::IO::read_triangle_soup<Concurrency>(o.in, in_points, in_triangles).format;
      }
      if(o.max_memory) {
        model = Tiled_memory_model{double(in_triangles.size()),
                                   double(in_points.capacity() * sizeof(Point) + in_triangles.capacity() * sizeof(Triangle))};
        tiles = choose_tiles(*model, *o.max_memory);
      }
      t = ST::tiled_reconstruct_topology<Concurrency>(team, ST::Soup_triangle_source<std::vector<Point>, std::vector<Triangle>>(
                                                              in_points, in_triangles),
                                                      tiles, folder, points, triangles, np);
    }
  }
  if(show) std::cerr << "\n";
  if(!root) return 0;
  // Under --max-memory, an output whose orientation as a whole would not fit is oriented in the
  // largest parts the limit allows (the same file).
  std::optional<std::size_t> part_triangles;
  const double n = double(triangles.size()), p = double(points.size()); // (before the orientation)
  if(model) {
    // The model took one point for two triangles; a soup left with more (loose triangles, open
    // seams) may need more for its output than the limit allowed for.
    if(!Tiled_memory_model::output_fits(n, p, *o.max_memory))
      std::cerr << "repair: warning: the repaired soup has " << points.size() << " points for " << triangles.size()
                << " triangles (the model of --max-memory takes one for two); its merge and orientation need about "
                << mebibytes(Tiled_memory_model::least_output_need(n, p)) << ", above --max-memory "
                << mebibytes(*o.max_memory) << "\n";
    if(Tiled_memory_model::output_need(n, p) > *o.max_memory)
      part_triangles = static_cast<std::size_t>(
        std::max(Tiled_memory_model::smallest_part, Tiled_memory_model::largest_part(n, p, *o.max_memory)));
    // (a soup the tiles cannot decide is repaired whole: its memory is that of the repair in memory)
    if(t.whole_soup)
      std::cerr << "repair: warning: the soup was repaired as one tile (" << t.whole_soup_reason
                << "): its memory is that of the repair in memory, which --max-memory " << mebibytes(*o.max_memory)
                << " did not allow for\n";
  }
  const Progress progress(t.input_triangles > 1000000);
  progress("repaired " + std::to_string(t.input_triangles) + " triangles in " + std::to_string(t.tiles) + " tiles");
  const Written_soup written(o, points, triangles, progress, part_triangles);
  if(part_triangles && written.largest_part > *part_triangles)
    std::cerr << "repair: warning: a part of the output (whole components) has " << written.largest_part
              << " triangles, more than the " << *part_triangles << " that --max-memory " << mebibytes(*o.max_memory)
              << " allows for its orientation\n";
  Report rep;
  rep.add_string("input", input_names(o));
  rep.add_string("output", o.out);
  rep.add_string("format", format);
  rep.add("input_triangles", t.input_triangles);
  rep.add("tolerance", t.tolerance);
  add_statistics(rep, written.statistics, 0);
  if(written.intersecting) rep.add("self_intersecting_pairs", *written.intersecting);
  rep.add("soup_vertices", t.output_points);
  rep.add("soup_triangles", t.output_triangles);
  if(model) {
    rep.add("max_memory", static_cast<std::size_t>(*o.max_memory));
    // (oriented in parts: the output's need with its largest part, known now)
    const double peak = part_triangles ? std::max(model->tiles_peak(tiles),
                                                  Tiled_memory_model::output_in_parts_need(
                                                    n, p, double(written.largest_part)))
                                       : model->peak(tiles, *o.max_memory);
    rep.add("modelled_peak", static_cast<std::size_t>(peak));
    rep.add("output_parts", written.parts);
  }
  rep.add("tiles", t.tiles);
  rep.add("tile_runs", t.tile_runs);
  rep.add("repeated_tiles", t.repeated_tiles);
  rep.add("discarded_triangles", t.discarded_triangles);
  rep.add("first_halo", t.first_halo);
  rep.add("largest_halo", t.largest_halo);
  rep.add("largest_tile_triangles", t.largest_tile_triangles);
  rep.add("halo_triangles", t.halo_triangles);
  rep.add("whole_soup", t.whole_soup);
  if(t.whole_soup) rep.add_string("whole_soup_reason", t.whole_soup_reason);
  if(team.size() > 1) rep.add("processes", team.size());
  rep.add("duplicate_triangles_removed", written.orientation.duplicate_triangles);
  rep.add("orientation_flips", written.orientation.orientation_flips);
  rep.add("duplicated_points", written.orientation.duplicated_points);
  rep.add("output_vertices", written.statistics.vertices);
  rep.add("output_triangles", written.statistics.triangles);
  write_repair_outputs(o, points, triangles, rep, progress);
  print(o.json ? rep.json() + "\n" : "soup_topology repair\n" + rep.text());
  return written.exit_code(o);
}

int repair_in_memory(const Repair_options& o, Read_soup& soup, bool soup_read,
                     const std::optional<Tiled_memory_model>& model);

// --max-memory: the model of the input `o.in`, whether it is repaired in memory or in tiles (a
// binary STL is not read for that: its header gives the number of triangles; another file is
// read into `soup`, and `soup_read` set).
Tiled_memory_model memory_model_of_input(const Repair_options& o, Read_soup& soup, bool& soup_read)
{
  if(is_binary_stl(o.in)) return Tiled_memory_model{double(binary_stl_triangles(o.in)), 0.0};
  soup.read = ST::IO::read_triangle_soup<Concurrency>(o.in, soup.points, soup.triangles);
  soup_read = true;
  const std::size_t soup_bytes = soup.points.capacity() * sizeof(Point) + soup.triangles.capacity() * sizeof(Triangle);
  return Tiled_memory_model{double(soup.triangles.size()), double(soup_bytes)};
}

int run_repair(const std::vector<std::string>& args)
{
  Repair_options o = parse_repair_arguments(args);
  // Under --max-memory the memory model's limit comes first: freed memory goes back to the system,
  // and large blocks come in huge pages (the program is executed again for that, before it reads
  // or writes anything).
  if(o.max_memory) {
    std::vector<std::string> arguments{"repair"};
    arguments.insert(arguments.end(), args.begin(), args.end());
    tool::restart_with_huge_page_mappings(arguments);
  } else {
    tool::keep_freed_memory_for_reuse();
  }
  if(!o.spill_folder.empty() && o.tiles == 0 && !o.max_memory)
    throw Usage_error("repair: --spill-folder goes with --tiles N or --max-memory SIZE");
  for(const std::string& in : all_inputs(o)) check_repair_paths(in, o.out, o.report_file);
  if(!o.html_file.empty()) tool::check_html_path(o.html_file, {o.in, o.out, o.report_file});
  tool::install_signal_handlers();
  const Thread_limit limit(o.threads);
  ST::Single_process_team process;
  tool::Tile_team_of<ST::Single_process_team> alone(process);
  if(o.tiles > 0 || !o.more_inputs.empty()) return run_tiled_repair(o, alone);
  Read_soup soup;
  bool soup_read = false;
  std::optional<Tiled_memory_model> model;
  if(o.max_memory) {
    model = memory_model_of_input(o, soup, soup_read);
    if(choose_tiles(*model, *o.max_memory) > 1) return run_tiled_repair(o, alone, soup_read ? &soup : nullptr);
  }
  return repair_in_memory(o, soup, soup_read, model);
}

// The repair in memory of `repair` (and of `soup_topology_mpi --max-memory` on rank 0 when the
// soup fits): `soup` is the input if `soup_read`, else it is read here; `model` is the memory
// model of `--max-memory`, reported.
int repair_in_memory(const Repair_options& o, Read_soup& soup, bool soup_read,
                     const std::optional<Tiled_memory_model>& model)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  ST::IO::Soup_read_report read;
  if(soup_read) {
    points.swap(soup.points);
    triangles.swap(soup.triangles);
    read = soup.read;
  } else {
    read = ST::IO::read_triangle_soup<Concurrency>(o.in, points, triangles);
  }
  const Progress progress(read.input_triangles > 1000000);
  progress("read " + std::to_string(read.input_triangles) + " triangles");
  tool::Html_input_soup<Point> html_input;
  if(!o.html_file.empty()) html_input = {points, triangles, {}};
  ST::Default_snap_visitor no_sites;
  const ST::Reconstruction_report r = o.html_file.empty() ? reconstruct(o, points, triangles, no_sites)
                                                          : reconstruct(o, points, triangles, html_input.sites);
  progress("repaired the soup");

  // The report's statistics describe the soup written.
  const Written_soup written(o, points, triangles, progress);
  Report rep = repair_report(o, read, r, written.orientation, written.statistics, written.intersecting);
  if(model) {
    rep.add("max_memory", static_cast<std::size_t>(*o.max_memory));
    rep.add("modelled_peak", static_cast<std::size_t>(model->peak(1, *o.max_memory)));
  }
  write_repair_outputs(o, points, triangles, rep, progress);
  if(!o.html_file.empty()) tool::write_repair_html(o.html_file, o.in, html_input, points, triangles, r, rep.json());
  print(o.json ? rep.json() + "\n" : "soup_topology repair\n" + rep.text());
  return written.exit_code(o);
}

// `gaps`: the options of the analysis are read by tool::run_gaps(), `--threads N` here.
int run_gaps(std::vector<std::string> args)
{
  std::size_t threads = 0;
  for(std::size_t i = 0; i < args.size(); ++i)
    if(args[i] == "--threads") {
      if(i + 1 >= args.size()) throw Usage_error("gaps: --threads needs a value");
      threads = parse_threads("gaps", args[i + 1]);
      args.erase(args.begin() + static_cast<std::ptrdiff_t>(i), args.begin() + static_cast<std::ptrdiff_t>(i + 2));
      --i;
    }
  const Thread_limit limit(threads);
  return tool::run_gaps<Concurrency>(args);
}

const char* mpi_usage_text =
  "usage:\n"
  "  mpirun -np K soup_topology_mpi IN -o OUT --tolerance T [--tiles N | --max-memory SIZE]\n"
  "                                 [--spill-folder DIR]\n"
  "                                 [the other options of soup_topology repair, but --html]\n"
  "      repairs IN as 'soup_topology repair IN -o OUT --tolerance T --tiles N' does, with the\n"
  "      tiles shared by the K processes: rank 0 plans and spills the tiles into a folder of\n"
  "      DIR (default: the temporary directory; on several machines, a folder they share), every\n"
  "      rank repairs its share, rank 0 merges, orients and writes OUT and prints the report.\n"
  "      The output is the same for every K and N. Default N: 4 K. --max-memory SIZE chooses N\n"
  "      for rank 0's memory (the others hold one tile's region at a time); one input that fits\n"
  "      is repaired in memory by rank 0, as 'soup_topology repair --max-memory SIZE' does.\n"
  "exit codes: as soup_topology repair\n";

// soup_topology_mpi: the options of `repair --tiles N`, checked by every rank alike.
Repair_options mpi_repair_options(const std::vector<std::string>& args, const tool::Tile_team& team)
{
  Repair_options o = parse_repair_arguments(args);
  if(!o.tolerance) throw Usage_error("give an absolute --tolerance T");
  if(o.tiles == 0 && !o.max_memory) o.tiles = std::min<std::size_t>(4096, 4 * team.size());
  for(const std::string& in : all_inputs(o)) check_repair_paths(in, o.out, o.report_file);
  return o;
}

} // namespace

int soup_topology_tool::run_tool(std::vector<std::string> args)
{
  if(args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    (args.empty() ? std::cerr : std::cout) << usage_text;
    return args.empty() ? 2 : 0;
  }
  const std::string command = args[0];
  args.erase(args.begin());
  try {
    if(command == "stats" || command == "gaps") tool::keep_freed_memory_for_reuse();
    // (the commands of this file, not soup_topology_tool::run_gaps(), which `gaps` calls)
    if(command == "stats") return ::run_stats(args);
    if(command == "repair") return ::run_repair(args);
    if(command == "gaps") return ::run_gaps(args);
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

void soup_topology_tool::restart_mpi_tool_for_its_memory_limit(const std::vector<std::string>& args)
{
  try {
    if(!parse_repair_arguments(args).max_memory) return;
  } catch(const std::exception&) {
    return;
  }
  tool::restart_with_huge_page_mappings(args, "soup_topology_mpi");
}

int soup_topology_tool::run_mpi_tool(const std::vector<std::string>& args, Tile_team& team)
{
  const bool root = team.rank() == 0;
  if(args.empty() || args[0] == "--help" || args[0] == "-h") {
    if(root) (args.empty() ? std::cerr : std::cout) << mpi_usage_text;
    return args.empty() ? 2 : 0;
  }
  Repair_options o;
  try {
    o = mpi_repair_options(args, team);
    if(!o.max_memory) tool::keep_freed_memory_for_reuse();
  } catch(const std::exception& e) {
    // Every rank checks the same arguments: every rank stops here.
    if(root) std::cerr << "soup_topology_mpi: " << e.what() << "\n" << mpi_usage_text;
    return 2;
  }
  // Only rank 0 reads the inputs (the others may run on machines that do not see them): it
  // checks that it can open them, and tells the others, so that every rank stops alike, with one
  // message, instead of rank 0 failing alone and ending the job.
  std::vector<char> unreadable;
  if(root) {
    try {
      for(const std::string& in : all_inputs(o)) {
        std::ifstream stream;
        ST::internal::open_input_file(in, stream); // the readers' own check: missing, a folder, unreadable
      }
    } catch(const ST::IO::Read_error& e) {
      const std::string message = e.what();
      unreadable.assign(message.begin(), message.end());
    }
  }
  team.broadcast(unreadable);
  if(!unreadable.empty()) {
    if(root) std::cerr << "soup_topology_mpi: " << std::string(unreadable.begin(), unreadable.end()) << "\n";
    return 2;
  }
  tool::install_signal_handlers();
  const Thread_limit limit(o.threads);
  // --max-memory on one input: a soup whose repair in memory fits is repaired in memory by rank 0,
  // as `soup_topology repair --max-memory` does (the same file); the other ranks have nothing to do.
  if(o.max_memory && o.more_inputs.empty()) {
    Read_soup soup;
    bool soup_read = false;
    std::optional<Tiled_memory_model> model;
    std::vector<char> in_memory(1, 0);
    if(root) {
      model = memory_model_of_input(o, soup, soup_read);
      in_memory[0] = choose_tiles(*model, *o.max_memory) <= 1;
    }
    team.broadcast(in_memory);
    if(in_memory[0]) return root ? repair_in_memory(o, soup, soup_read, model) : 0;
    return run_tiled_repair(o, team, soup_read ? &soup : nullptr);
  }
  return run_tiled_repair(o, team);
}
