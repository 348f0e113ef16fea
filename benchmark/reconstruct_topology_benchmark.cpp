// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The whole repair end to end (issue 5), side by side in one run with the CGAL pipeline a user
// would otherwise write. Reading is excluded for both: every benchmark starts from the indexed
// soup in memory (copied outside the timed region when the algorithm works in place).
//
// Inputs, made once per process by soup_test::t_junction_soup (8 slabs along x) from
// clean/bunny00.off (75,408 triangles):
// - "1M": bunny00 split 1-to-4 twice (1,206,528 triangles before the T-junction splits);
// - "300k": split once (301,632 triangles), for CGAL if it is too slow at 1M;
// each without jitter ("exact": T-junctions exact up to rounding, the seams' vertices duplicated
// exactly) and with every copy of a vertex jittered by up to 1e-7 x the bounding-box diagonal on
// each coordinate ("jitter"). The tolerance is 1e-6 x the diagonal everywhere.
//
// Benchmarks (CPU time):
// - BM_ours_in_place: Soup_topology::reconstruct_topology(points, triangles, np);
// - BM_ours_in_place_oriented: the same, then orient_triangle_soup(points, triangles) (the soup
//   the command line writes); "orient_ms" counter;
// - BM_ours_to_mesh: reconstruct_topology(points, triangles, mesh, np) into a Surface_mesh;
// - BM_CGAL_pipeline: PMP::repair_polygon_soup, orient_polygon_soup, polygon_soup_to_polygon_mesh,
//   experimental::snap_borders (constant tolerance), stitch_borders; "*_ms" counters per phase.
// - BM_read_and_reconstruct_STL: read_triangle_soup of a 1.2M-triangle jittered exploded binary
//   STL, then the pipeline welding once (as the command line does) or twice (the public
//   function on the soup read), triangles in mesh order and shuffled; "peak_rss_bytes_per_triangle"
//   is the peak resident memory of the process so far (run it alone with --benchmark_filter);
// - BM_read_and_reconstruct_given_STL: the same on the binary STL and tolerance named by
//   SOUP_TOPOLOGY_BENCHMARK_STL and SOUP_TOPOLOGY_BENCHMARK_TOLERANCE (skipped without them).
// Counter "border_edges": the border edges left (the input is a closed bunny: 0 is the answer).
// Target (issue 5): ours closed, at least 10x faster than CGAL, no more border edges than CGAL.
//
// Run: reconstruct_topology_benchmark [--benchmark_filter=...]; data from SOUP_TOPOLOGY_DATA_DIR.

#include <Soup_topology/IO/read_triangle_soup.h>
#include <Soup_topology/orient_triangle_soup.h>
#include <Soup_topology/parameters.h>
#include <Soup_topology/reconstruct_topology.h>

#include "../test/soup_generators.h"
#include "../test/test_utilities.h"
#include "benchmark_utilities.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/internal/Snapping/snap.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/stitch_borders.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/property_map.h>

#include <benchmark/benchmark.h>

#include <sys/resource.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace ST = Soup_topology;
namespace PMP = CGAL::Polygon_mesh_processing;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Index_triangle = std::array<std::size_t, 3>;
using Mesh = CGAL::Surface_mesh<Point>;

namespace {

using soup_benchmark::thread_cpu_ms;
using soup_benchmark::peak_resident_bytes;
using soup_benchmark::diagonal;
using soup_benchmark::write_binary_STL;

enum class Size { one_million, three_hundred_thousand };
enum class Jitter { exact, jittered };

struct Input
{
  std::vector<Point> points;
  std::vector<Index_triangle> triangles;
  std::size_t t_junctions = 0;
  double tolerance = 0;
};

Input make_input(Size size, Jitter jitter)
{
  std::vector<Point> points;
  std::vector<Index_triangle> triangles;
  soup_test::read_data_mesh("clean/bunny00.off.xz", points, triangles);
  soup_test::subdivide_midpoints(points, triangles);
  if(size == Size::one_million) soup_test::subdivide_midpoints(points, triangles);
  const double diag = diagonal(points);
  const auto soup =
    soup_test::t_junction_soup(points, triangles, 8, jitter == Jitter::jittered ? 1e-7 * diag : 0.0, 2026u);
  Input in;
  in.points = soup.points;
  in.triangles = soup.triangles;
  in.t_junctions = soup.t_junctions;
  in.tolerance = 1e-6 * diag;
  return in;
}

const Input& input(Size size, Jitter jitter)
{
  if(size == Size::one_million) {
    if(jitter == Jitter::exact) { static const Input a = make_input(size, jitter); return a; }
    static const Input b = make_input(size, jitter);
    return b;
  }
  if(jitter == Jitter::exact) { static const Input c = make_input(size, jitter); return c; }
  static const Input d = make_input(size, jitter);
  return d;
}

std::size_t border_edges(const Mesh& mesh)
{
  std::size_t n = 0;
  for(Mesh::Halfedge_index h : mesh.halfedges())
    if(mesh.is_border(h)) ++n;
  return n;
}

void set_input_counters(benchmark::State& state, const Input& in)
{
  state.counters["triangles"] = static_cast<double>(in.triangles.size());
  state.counters["t_junctions"] = static_cast<double>(in.t_junctions);
}

void report_counters(benchmark::State& state, const ST::Reconstruction_report& r)
{
  state.counters["border_before"] = static_cast<double>(r.border_edges_before);
  state.counters["border_edges"] = static_cast<double>(r.border_edges_after);
  state.counters["rounds"] = static_cast<double>(r.rounds);
  state.counters["snapped"] = static_cast<double>(r.snapped_vertices);
  state.counters["splits"] = static_cast<double>(r.split_triangles);
  state.counters["non_manifold_edges"] = static_cast<double>(r.non_manifold_edges_after);
}

// The pipeline in place on a fresh copy of the input each iteration (the copy not timed); with
// `orient`, then the orientation, whose CPU time of the last iteration is "orient_ms".
void run_in_place(benchmark::State& state, Size size, Jitter jitter, bool orient)
{
  const Input& in = input(size, jitter);
  ST::Reconstruction_report report;
  double orient_ms = 0;
  for(auto _ : state) {
    state.PauseTiming();
    std::vector<Point> points = in.points;
    std::vector<Index_triangle> triangles = in.triangles;
    state.ResumeTiming();
    report = ST::reconstruct_topology(points, triangles, CGAL::parameters::snapping_tolerance(in.tolerance));
    if(orient) {
      const double t0 = thread_cpu_ms();
      ST::orient_triangle_soup(points, triangles);
      orient_ms = thread_cpu_ms() - t0;
    }
    benchmark::DoNotOptimize(triangles.data());
  }
  set_input_counters(state, in);
  report_counters(state, report);
  if(orient) state.counters["orient_ms"] = orient_ms;
}

void BM_ours_in_place(benchmark::State& state, Size size, Jitter jitter) { run_in_place(state, size, jitter, false); }

// The soup the command line writes: repaired in place, then oriented (repeated triangles left
// out, patches oriented, non-manifold vertices separated), the counterpart of CGAL's repair and
// orientation without the mesh; "orient_ms" is the orientation's share.
void BM_ours_in_place_oriented(benchmark::State& state, Size size, Jitter jitter)
{
  run_in_place(state, size, jitter, true);
}

void BM_ours_to_mesh(benchmark::State& state, Size size, Jitter jitter)
{
  const Input& in = input(size, jitter);
  ST::Reconstruction_report report;
  std::size_t mesh_border = 0;
  bool valid = false;
  for(auto _ : state) {
    Mesh mesh;
    report = ST::reconstruct_topology(in.points, in.triangles, mesh, CGAL::parameters::snapping_tolerance(in.tolerance));
    state.PauseTiming();
    mesh_border = border_edges(mesh);
    valid = CGAL::is_valid_polygon_mesh(mesh);
    state.ResumeTiming();
  }
  set_input_counters(state, in);
  report_counters(state, report);
  state.counters["border_edges"] = static_cast<double>(mesh_border);
  state.counters["valid"] = valid ? 1 : 0;
}

void BM_CGAL_pipeline(benchmark::State& state, Size size, Jitter jitter)
{
  const Input& in = input(size, jitter);
  double repair_ms = 0, orient_ms = 0, mesh_ms = 0, snap_ms = 0, stitch_ms = 0;
  std::size_t border_before = 0, border = 0, faces = 0;
  for(auto _ : state) {
    state.PauseTiming();
    std::vector<Point> points = in.points;
    std::vector<Index_triangle> polygons = in.triangles;
    state.ResumeTiming();
    const double t0 = thread_cpu_ms();
    PMP::repair_polygon_soup(points, polygons);
    const double t1 = thread_cpu_ms();
    PMP::orient_polygon_soup(points, polygons);
    const double t2 = thread_cpu_ms();
    Mesh mesh;
    PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
    const double t3 = thread_cpu_ms();
    state.PauseTiming();
    border_before = border_edges(mesh);
    state.ResumeTiming();
    const double t4 = thread_cpu_ms();
    PMP::experimental::snap_borders(mesh, CGAL::Constant_property_map<Mesh::Vertex_index, double>(in.tolerance));
    const double t5 = thread_cpu_ms();
    PMP::stitch_borders(mesh);
    const double t6 = thread_cpu_ms();
    repair_ms = t1 - t0;
    orient_ms = t2 - t1;
    mesh_ms = t3 - t2;
    snap_ms = t5 - t4;
    stitch_ms = t6 - t5;
    state.PauseTiming();
    border = border_edges(mesh);
    faces = mesh.number_of_faces();
    state.ResumeTiming();
  }
  set_input_counters(state, in);
  state.counters["repair_ms"] = repair_ms;
  state.counters["orient_ms"] = orient_ms;
  state.counters["to_mesh_ms"] = mesh_ms;
  state.counters["snap_ms"] = snap_ms;
  state.counters["stitch_ms"] = stitch_ms;
  state.counters["border_before"] = static_cast<double>(border_before);
  state.counters["border_edges"] = static_cast<double>(border);
  state.counters["faces"] = static_cast<double>(faces);
}

// The exploded soup of the command-line path: clean/bunny00.off split 1-to-4 twice (1,206,528
// triangles), every triangle with its own corners, every corner jittered by up to 1e-6 x the
// diagonal (float coordinates), written as a binary STL in mesh order and shuffled. The
// tolerance is 1e-5 x the diagonal.
struct STL_input
{
  std::string mesh_order_file, shuffled_file;
  std::size_t triangles = 0;
  double tolerance = 0;
};

const STL_input& stl_input()
{
  static const STL_input in = [] {
    std::vector<Point> points;
    std::vector<Index_triangle> triangles;
    soup_test::read_data_mesh("clean/bunny00.off.xz", points, triangles);
    soup_test::subdivide_midpoints(points, triangles);
    soup_test::subdivide_midpoints(points, triangles);
    const double diag = diagonal(points);
    std::vector<std::array<Point, 3>> soup = soup_test::explode(points, triangles);
    std::mt19937_64 rng(2026);
    const double j = 1e-6 * diag / std::sqrt(3.0);
    std::uniform_real_distribution<double> d(-j, j);
    for(auto& t : soup)
      for(Point& p : t) p = Point(p.x() + d(rng), p.y() + d(rng), p.z() + d(rng));
    STL_input r;
    const std::string folder = soup_test::temporary_folder("reconstruct_topology_benchmark");
    r.mesh_order_file = folder + "/bunny_exploded_jittered.stl";
    r.shuffled_file = folder + "/bunny_exploded_jittered_shuffled.stl";
    write_binary_STL(r.mesh_order_file, soup);
    std::shuffle(soup.begin(), soup.end(), rng);
    write_binary_STL(r.shuffled_file, soup);
    r.triangles = soup.size();
    r.tolerance = 1e-5 * diag;
    return r;
  }();
  return in;
}

enum class Order { mesh, shuffled };
enum class Weld { once, twice };

// What `soup_topology repair FILE -o OUT --tolerance T` does before orienting and writing: the
// file read (a binary STL welded while it is decoded), then the pipeline. `Weld::twice` is the
// public reconstruct_topology(), which welds the soup read again; `Weld::once` trusts the
// reader's weld, as the command line does. The label gives the file and the tolerance, for
// timing the whole command-line process on the same input.
void BM_read_and_reconstruct_STL(benchmark::State& state, Order order, Weld weld)
{
  const STL_input& in = stl_input();
  const std::string& file = order == Order::mesh ? in.mesh_order_file : in.shuffled_file;
  ST::Reconstruction_report report;
  double read_ms = 0, repair_ms = 0;
  for(auto _ : state) {
    const double t0 = thread_cpu_ms();
    std::vector<Point> points;
    std::vector<Index_triangle> triangles;
    ST::IO::read_triangle_soup(file, points, triangles);
    const double t1 = thread_cpu_ms();
    const auto np = CGAL::parameters::snapping_tolerance(in.tolerance);
    report = weld == Weld::once ? ST::internal::reconstruct_exactly_welded_soup(points, triangles, np)
                                : ST::reconstruct_topology(points, triangles, np);
    read_ms = t1 - t0;
    repair_ms = thread_cpu_ms() - t1;
    benchmark::DoNotOptimize(triangles.data());
  }
  report_counters(state, report);
  state.counters["triangles"] = static_cast<double>(in.triangles);
  state.counters["read_ms"] = read_ms;
  state.counters["repair_ms"] = repair_ms;
  state.counters["peak_rss_bytes_per_triangle"] = peak_resident_bytes() / static_cast<double>(in.triangles);
  state.SetLabel(file + " --tolerance " + std::to_string(in.tolerance));
}
BENCHMARK_CAPTURE(BM_read_and_reconstruct_STL, 1M_jitter_welded_once, Order::mesh, Weld::once)
  ->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK_CAPTURE(BM_read_and_reconstruct_STL, 1M_jitter_welded_twice, Order::mesh, Weld::twice)
  ->Unit(benchmark::kMillisecond)->Iterations(2);
BENCHMARK_CAPTURE(BM_read_and_reconstruct_STL, 1M_jitter_shuffled_welded_once, Order::shuffled, Weld::once)
  ->Unit(benchmark::kMillisecond)->Iterations(2);

// The same on a binary STL named by the environment: SOUP_TOPOLOGY_BENCHMARK_STL, with the
// absolute tolerance SOUP_TOPOLOGY_BENCHMARK_TOLERANCE (for example the exploded torus of
// benchmark/exploded_torus.py). It is the in-process side of the ratio with the whole process
// `soup_topology repair FILE -o OUT --tolerance T --threads 1`: one thread, the file read and
// welded while decoded, then the pipeline trusting that weld. Skipped when the file is not given.
void BM_read_and_reconstruct_given_STL(benchmark::State& state)
{
  const char* file = std::getenv("SOUP_TOPOLOGY_BENCHMARK_STL");
  const char* tolerance_text = std::getenv("SOUP_TOPOLOGY_BENCHMARK_TOLERANCE");
  if(!file || !tolerance_text) {
    state.SkipWithError("set SOUP_TOPOLOGY_BENCHMARK_STL and SOUP_TOPOLOGY_BENCHMARK_TOLERANCE");
    for(auto _ : state) {}
    return;
  }
  const double tolerance = std::strtod(tolerance_text, nullptr);
  ST::Reconstruction_report report;
  double read_ms = 0, repair_ms = 0;
  std::size_t triangles_read = 0;
  for(auto _ : state) {
    const double t0 = thread_cpu_ms();
    std::vector<Point> points;
    std::vector<Index_triangle> triangles;
    triangles_read = ST::IO::read_triangle_soup(file, points, triangles).input_triangles;
    const double t1 = thread_cpu_ms();
    report = ST::internal::reconstruct_exactly_welded_soup(points, triangles,
                                                           CGAL::parameters::snapping_tolerance(tolerance));
    read_ms = t1 - t0;
    repair_ms = thread_cpu_ms() - t1;
    benchmark::DoNotOptimize(triangles.data());
  }
  report_counters(state, report);
  state.counters["triangles"] = static_cast<double>(triangles_read);
  state.counters["read_ms"] = read_ms;
  state.counters["repair_ms"] = repair_ms;
  state.counters["peak_rss_bytes_per_triangle"] = peak_resident_bytes() / static_cast<double>(triangles_read);
  state.SetLabel(std::string(file) + " --tolerance " + tolerance_text);
}
BENCHMARK(BM_read_and_reconstruct_given_STL)->Unit(benchmark::kMillisecond)->Iterations(1);

#define SOUP_TOPOLOGY_RECONSTRUCT_BENCHMARKS(name, iterations)                                          \
  BENCHMARK_CAPTURE(name, 1M_exact, Size::one_million, Jitter::exact)                                   \
    ->Unit(benchmark::kMillisecond)->Iterations(iterations);                                            \
  BENCHMARK_CAPTURE(name, 1M_jitter, Size::one_million, Jitter::jittered)                               \
    ->Unit(benchmark::kMillisecond)->Iterations(iterations);                                            \
  BENCHMARK_CAPTURE(name, 300k_exact, Size::three_hundred_thousand, Jitter::exact)                      \
    ->Unit(benchmark::kMillisecond)->Iterations(iterations);                                            \
  BENCHMARK_CAPTURE(name, 300k_jitter, Size::three_hundred_thousand, Jitter::jittered)                  \
    ->Unit(benchmark::kMillisecond)->Iterations(iterations)

SOUP_TOPOLOGY_RECONSTRUCT_BENCHMARKS(BM_ours_in_place, 2);
SOUP_TOPOLOGY_RECONSTRUCT_BENCHMARKS(BM_ours_in_place_oriented, 2);
SOUP_TOPOLOGY_RECONSTRUCT_BENCHMARKS(BM_ours_to_mesh, 2);
SOUP_TOPOLOGY_RECONSTRUCT_BENCHMARKS(BM_CGAL_pipeline, 1);

} // namespace

BENCHMARK_MAIN();
