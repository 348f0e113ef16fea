// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The pipeline on 1 thread and on all threads (issue 14): the wall time of every phase, and the
// speedup, in one run. A plain program (not a Google Benchmark): after one untimed run of each
// side, which warms the allocator, the outputs' memory and the file-system cache, each phase runs
// `--repetitions R` times on 1 thread and R times on all threads, the two sides interleaved, and
// the smallest time of each side is reported (the runs of one side differ by up to 20 % on a
// shared 2-core machine: one run of each is not enough to decide a speedup target). A phase that
// changes its input in place is given a copy of it before each run, untimed.
//
// Inputs, made once per process from clean/bunny00.off.xz (75,408 triangles) of the shared data
// folder, split 1-to-4 at the edge midpoints (soup_test::subdivide_midpoints):
// - "4M exploded": split 3 times (4,826,112 triangles), every triangle with its own 3 corners (as
//   an STL export gives): index_triangles + Adjacency_tables;
// - "4M jittered": the same soup with every corner moved by up to 1e-6 x the bounding-box diagonal
//   on each coordinate, welded with the tolerance 1e-5 x the diagonal: index_triangles then
//   reconstruct_topology;
// - "4M T-junction patches": soup_test::t_junction_soup (8 slabs, jitter 1e-7 x the diagonal) of
//   the 3-times split mesh, reconstruct_topology with the tolerance 1e-6 x the diagonal;
// - "Loop": 2 levels of loop_subdivision of the mesh split twice (1,206,528 triangles);
// - "CLI repair": `soup_topology repair IN.stl -o OUT.stl --relative-tolerance 1e-5 --threads N`
//   on the 4M jittered soup written as a binary STL (float coordinates), timed as a process.
// The jittered and the T-junction soups are also repaired "step by step": the steps of the first
// round of reconstruct_topology (Adjacency_tables, snap_vertices, split_t_junctions,
// orient_triangle_soup) called one by one and timed each, so that every step has its speedup and
// serial fraction; the orientation twice: building its own tables (orient_triangle_soup) and
// reading the tables of the round (as the pipeline holds them), with the same result.
// Every parallel result is compared with the 1-thread result (points and triangles): a
// difference is printed and makes the exit code 1.
// First, two rows of the machine itself, the ceiling of every phase bound by memory: the same
// total work on 1 thread and on all threads, split evenly: "streaming reads" sums 1 GiB of
// 8-byte words read in order; "random reads" follows 8 independent chains a thread through a
// random cycle of 32 Mi 4-byte entries (128 MiB), as the weld and the tables read a soup whose
// neighbours lie far apart. On a machine whose cores share a memory system that one core nearly
// saturates, these speedups stay well below the number of threads, and so do the phases that
// spend their time waiting for memory.
//
// Run: parallel_benchmark [--repetitions R] [path of the soup_topology tool] (R: default 3;
// the tool: default ../tools/soup_topology beside this program); it needs about 4 GB of memory
// and writes two STL files to a temporary folder.

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/index_triangles.h>
#include <Soup_topology/loop_subdivision.h>
#include <Soup_topology/orient_triangle_soup.h>
#include <Soup_topology/reconstruct_topology.h>
#include <Soup_topology/snap_vertices.h>
#include <Soup_topology/split_t_junctions.h>

#include "../test/soup_generators.h"
#include "../test/test_utilities.h"
#include "benchmark_utilities.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#if defined(CGAL_LINKED_WITH_TBB)
#include <tbb/global_control.h>
#include <tbb/info.h>
#endif

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace {

using soup_benchmark::diagonal;
using soup_benchmark::write_binary_STL;

namespace ST = Soup_topology;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Triangle = std::array<std::size_t, 3>;
using Explicit_triangle = std::array<Point, 3>;
using Parallel = CGAL::Parallel_if_available_tag;

double seconds_since(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

template <class F>
double timed(const F& f)
{
  const auto start = std::chrono::steady_clock::now();
  f();
  return seconds_since(start);
}

std::size_t all_threads()
{
#if defined(CGAL_LINKED_WITH_TBB)
  return static_cast<std::size_t>(tbb::info::default_concurrency());
#else
  return 1;
#endif
}

// Runs `f` with TBB limited to `threads`.
template <class F>
void with_threads(std::size_t threads, const F& f)
{
#if defined(CGAL_LINKED_WITH_TBB)
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
#endif
  (void)threads;
  f();
}

// One line of the table: a phase, its time on 1 thread and on all threads.
struct Row
{
  std::string phase;
  double one = 0, all = 0;
};

std::vector<Row> rows;
bool identical = true;
std::size_t repetitions = 3; // timed runs of each side, interleaved; the smallest time is reported

// Times `one()` and `all()` `repetitions` times each, interleaved (one, all, one, all, ...), and
// keeps the smallest time of each side in `r`. `before_one()` and `before_all()`, untimed, run
// before each timed run of their side (e.g. the copy of the input that a phase changes in place).
void time_interleaved(Row& r, const std::function<void()>& one, const std::function<void()>& all,
                      const std::function<void()>& before_one = [] {},
                      const std::function<void()>& before_all = [] {})
{
  r.one = r.all = std::numeric_limits<double>::infinity();
  for(std::size_t i = 0; i < repetitions; ++i) {
    before_one();
    r.one = std::min(r.one, timed(one));
    before_all();
    r.all = std::min(r.all, timed(all));
  }
}

void print_row(const Row& r, std::size_t threads)
{
  const double speedup = r.one / r.all;
  // Amdahl: speedup s on p threads gives the serial fraction f = (p / s - 1) / (p - 1).
  const double p = static_cast<double>(threads);
  const double serial = threads > 1 ? std::clamp((p / speedup - 1) / (p - 1), 0.0, 1.0) : 1.0;
  auto amdahl = [&](double cores) { return 1 / (serial + (1 - serial) / cores); };
  std::printf("%-44s %9.3f %9.3f %8.2fx %8.2f %8.1fx %8.1fx\n", r.phase.c_str(), r.one, r.all, speedup, serial,
              amdahl(16), amdahl(64));
  std::fflush(stdout);
}

// Runs `run_one` once untimed, then times it on 1 thread and `run_all` on all threads
// (`time_interleaved()`); `same()` compares their results (of the last runs). A phase that
// changes its input in place is given it by `copy_one()` and `copy_all()`, untimed, before each
// run of its side: the time is the phase's alone (the copy of a 4M soup, one thread's memory
// traffic, would otherwise weigh on both sides as a serial part of the phase).
void measure(const std::string& name, std::size_t threads, const std::function<void()>& run_one,
             const std::function<void()>& run_all, const std::function<bool()>& same,
             const std::function<void()>& copy_one = [] {}, const std::function<void()>& copy_all = [] {})
{
  // Both sides run once untimed first: the vectors that they assign keep their capacity, so that
  // neither timed run is the first to fault in the memory of its outputs.
  copy_one();
  run_one();
  copy_all();
  with_threads(threads, run_all);
  Row r{name, 0, 0};
  time_interleaved(r, [&] { with_threads(1, run_one); }, [&] { with_threads(threads, run_all); }, copy_one, copy_all);
  if(!same()) {
    std::printf("%s: the parallel result differs from the 1-thread result\n", name.c_str());
    identical = false;
  }
  rows.push_back(r);
  print_row(r, threads);
}

// The soup after each step of one round of the repair, and the wall time of each step.
struct Round_of_steps
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  std::vector<double> seconds;
};

// One round of the steps that `reconstruct_topology()` repeats, called one by one on an indexed
// soup: the tables, the weld, the T-junction split, the orientation (with the pipeline's default
// small-feature policy, so the same work as its first round), the last without and with the
// round's tables.
Round_of_steps run_steps(const std::vector<Point>& points, const std::vector<Triangle>& triangles, double tolerance)
{
  Round_of_steps r{points, triangles, {}};
  const auto np = ST::parameters::small_features(ST::Small_features::COLLAPSE, CGAL::parameters::snapping_tolerance(tolerance));
  std::unique_ptr<ST::Adjacency_tables> tables;
  r.seconds.push_back(timed([&] {
    tables = std::make_unique<ST::Adjacency_tables>(r.triangles, r.points.size(), Parallel());
  }));
  r.seconds.push_back(timed([&] { ST::snap_vertices<Parallel>(r.points, r.triangles, *tables, np); }));
  r.seconds.push_back(timed([&] { ST::split_t_junctions<Parallel>(r.points, r.triangles, *tables, np); }));
  // the orientation as a caller without tables runs it (it builds its own), on a copy ...
  std::vector<Point> oriented_points = r.points;
  std::vector<Triangle> oriented_triangles = r.triangles;
  r.seconds.push_back(timed([&] { ST::orient_triangle_soup<Parallel>(oriented_points, oriented_triangles); }));
  // ... and with the tables of the round, as the pipeline holds them
  r.seconds.push_back(timed([&] { ST::internal::orient_triangle_soup_with_tables<Parallel>(r.points, r.triangles, tables.get()); }));
  if(oriented_points != r.points || oriented_triangles != r.triangles) {
    std::printf("the orientation with the round's tables differs from the orientation without them\n");
    identical = false;
  }
  return r;
}

// The steps of one round on `name`'s soup, each as a row: 1 thread against all threads, the
// smallest time of each step over `repetitions` interleaved rounds of each side.
void measure_steps(const std::string& name, std::size_t threads, const std::vector<Point>& points,
                   const std::vector<Triangle>& triangles, double tolerance)
{
  run_steps(points, triangles, tolerance);
  Round_of_steps one, all;
  std::vector<double> best_one, best_all;
  const auto keep_smallest = [](std::vector<double>& best, const std::vector<double>& seconds) {
    if(best.empty()) best = seconds;
    for(std::size_t i = 0; i < best.size(); ++i) best[i] = std::min(best[i], seconds[i]);
  };
  for(std::size_t i = 0; i < repetitions; ++i) {
    with_threads(1, [&] { one = run_steps(points, triangles, tolerance); });
    with_threads(threads, [&] { all = run_steps(points, triangles, tolerance); });
    keep_smallest(best_one, one.seconds);
    keep_smallest(best_all, all.seconds);
  }
  if(one.points != all.points || one.triangles != all.triangles) {
    std::printf("%s: the parallel steps differ from the 1-thread steps\n", name.c_str());
    identical = false;
  }
  const char* const steps[] = {"Adjacency_tables", "snap_vertices", "split_t_junctions", "orient_triangle_soup",
                               "orientation, the round's tables"};
  for(std::size_t i = 0; i < best_one.size(); ++i) {
    rows.push_back(Row{name + ": " + steps[i], best_one[i], best_all[i]});
    print_row(rows.back(), threads);
  }
}

// The two rows of the machine (see the top of this file).
void measure_memory_ceiling(std::size_t threads)
{
  const std::size_t words = std::size_t(1) << 27, cycle = std::size_t(1) << 25, steps = std::size_t(1) << 24;
  std::vector<std::uint64_t> data(words);
  for(std::size_t i = 0; i < words; ++i) data[i] = i;
  std::vector<std::uint32_t> next(cycle);
  {
    std::vector<std::uint32_t> order(cycle);
    for(std::size_t i = 0; i < cycle; ++i) order[i] = static_cast<std::uint32_t>(i);
    std::shuffle(order.begin(), order.end(), std::mt19937(1));
    for(std::size_t i = 0; i < cycle; ++i) next[order[i]] = order[(i + 1) % cycle];
  }
  std::atomic<std::uint64_t> sink{0};
  // `work(k, n)`: part k of n, on thread k of n
  const auto on_threads = [](std::size_t n, const std::function<void(std::size_t, std::size_t)>& work) {
    std::vector<std::thread> team;
    for(std::size_t k = 0; k < n; ++k) team.emplace_back(work, k, n);
    for(std::thread& t : team) t.join();
  };
  const auto stream = [&](std::size_t k, std::size_t n) {
    std::uint64_t sum = 0;
    for(std::size_t i = k * words / n; i < (k + 1) * words / n; ++i) sum += data[i];
    sink += sum;
  };
  const auto chase = [&](std::size_t k, std::size_t n) {
    constexpr std::size_t chains = 8;
    std::uint32_t at[chains];
    for(std::size_t j = 0; j < chains; ++j) at[j] = static_cast<std::uint32_t>((k * chains + j) * 104729 % cycle);
    for(std::size_t i = 0; i < steps / chains / n; ++i)
      for(std::size_t j = 0; j < chains; ++j) at[j] = next[at[j]];
    for(std::size_t j = 0; j < chains; ++j) sink += at[j];
  };
  using Work = std::function<void(std::size_t, std::size_t)>;
  const std::pair<const char*, Work> machine_rows[] = {{"machine: streaming reads of 1 GiB", stream},
                                                       {"machine: random reads, 8 chains a thread", chase}};
  for(const auto& machine_row : machine_rows) {
    const Work& work = machine_row.second; // (a reference, not a structured binding: lambdas capture it)
    on_threads(1, work);
    Row r{machine_row.first, 0, 0};
    time_interleaved(r, [&] { on_threads(1, work); }, [&] { on_threads(threads, work); });
    rows.push_back(r);
    print_row(r, threads);
  }
}

} // namespace

int main(int argc, char** argv)
{
  std::string tool = (std::filesystem::path(argv[0]).parent_path() / ".." / "tools" / "soup_topology").string();
  for(int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if(arg == "--repetitions" && i + 1 < argc) {
      const long r = std::strtol(argv[++i], nullptr, 10);
      if(r < 1) {
        std::fprintf(stderr, "parallel_benchmark: --repetitions takes a positive number\n");
        return EXIT_FAILURE;
      }
      repetitions = static_cast<std::size_t>(r);
    }
    else
      tool = arg;
  }
  const std::size_t threads = all_threads();
  std::printf("parallel_benchmark: %zu threads (TBB's default concurrency), the smallest of %zu interleaved runs "
              "of each side\n", threads, repetitions);

  measure_memory_ceiling(threads);

  // The inputs.
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  soup_test::read_data_mesh("clean/bunny00.off.xz", points, triangles);
  soup_test::subdivide_midpoints(points, triangles);
  soup_test::subdivide_midpoints(points, triangles);
  const std::vector<Point> loop_points = points;
  const std::vector<Triangle> loop_triangles = triangles;
  soup_test::subdivide_midpoints(points, triangles);
  const double diag = diagonal(points);
  std::vector<Explicit_triangle> exploded = soup_test::explode(points, triangles);
  std::vector<Explicit_triangle> jittered = exploded;
  {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> move(-1e-6 * diag, 1e-6 * diag);
    for(Explicit_triangle& t : jittered)
      for(Point& p : t) p = Point(p.x() + move(rng), p.y() + move(rng), p.z() + move(rng));
  }
  std::printf("inputs: %zu triangles (exploded, jittered), Loop input %zu triangles\n", exploded.size(),
              loop_triangles.size());
  std::printf("%-44s %9s %9s %9s %8s %9s %9s\n", "phase (wall seconds)", "1 thread", "all", "speedup", "serial",
              "Amdahl16", "Amdahl64");

  // 1. exact weld + tables of the exploded soup
  {
    std::vector<Point> p1, pn;
    std::vector<Triangle> t1, tn;
    measure("4M exploded: index_triangles", threads, [&] { ST::index_triangles<Parallel>(exploded, p1, t1); },
            [&] { ST::index_triangles<Parallel>(exploded, pn, tn); }, [&] { return p1 == pn && t1 == tn; });
    std::size_t b1 = 0, bn = 0;
    measure("4M exploded: Adjacency_tables", threads,
            [&] { b1 = ST::Adjacency_tables(t1, p1.size(), Parallel()).number_of_border_edges(); },
            [&] { bn = ST::Adjacency_tables(t1, p1.size(), Parallel()).number_of_border_edges(); },
            [&] { return b1 == bn; });
  }
  // 2. the jittered epsilon weld
  {
    std::vector<Point> p1, pn, q1, qn;
    std::vector<Triangle> t1, tn, u1, un;
    measure("4M jittered: index_triangles", threads, [&] { ST::index_triangles<Parallel>(jittered, p1, t1); },
            [&] { ST::index_triangles<Parallel>(jittered, pn, tn); }, [&] { return p1 == pn && t1 == tn; });
    const auto np = CGAL::parameters::snapping_tolerance(1e-5 * diag);
    measure("4M jittered: reconstruct_topology", threads,
            [&] { ST::internal::reconstruct_exactly_welded_soup<Parallel>(q1, u1, np); },
            [&] { ST::internal::reconstruct_exactly_welded_soup<Parallel>(qn, un, np); },
            [&] { return q1 == qn && u1 == un; }, [&] { q1 = p1; u1 = t1; }, [&] { qn = p1; un = t1; });
    measure_steps("4M jittered, step by step", threads, p1, t1, 1e-5 * diag);
  }
  std::vector<Explicit_triangle>().swap(exploded);
  // 3. the T-junction patch soup
  {
    const auto soup = soup_test::t_junction_soup(points, triangles, 8, 1e-7 * diag, 17);
    const auto np = CGAL::parameters::snapping_tolerance(1e-6 * diag);
    std::vector<Point> p1, pn;
    std::vector<Triangle> t1, tn;
    measure("4M T-junction patches: reconstruct_topology", threads,
            [&] { ST::reconstruct_topology<Parallel>(p1, t1, np); },
            [&] { ST::reconstruct_topology<Parallel>(pn, tn, np); },
            [&] { return p1 == pn && t1 == tn; }, [&] { p1 = soup.points; t1 = soup.triangles; },
            [&] { pn = soup.points; tn = soup.triangles; });
    measure_steps("4M T-junction patches, step by step", threads, soup.points, soup.triangles, 1e-6 * diag);
  }
  // 4. Loop subdivision
  {
    std::vector<Point> p1, pn;
    std::vector<Triangle> t1, tn;
    const auto np = CGAL::parameters::number_of_iterations(2);
    measure("Loop: 2 levels of 1.2M triangles", threads,
            [&] { ST::loop_subdivision<Parallel>(p1, t1, np); }, [&] { ST::loop_subdivision<Parallel>(pn, tn, np); },
            [&] { return p1 == pn && t1 == tn; }, [&] { p1 = loop_points; t1 = loop_triangles; },
            [&] { pn = loop_points; tn = loop_triangles; });
  }
  // 5. the command line, end to end
  {
    const std::string folder = soup_test::temporary_folder("parallel_benchmark");
    const std::string in = folder + "/jittered.stl";
    write_binary_STL(in, jittered);
    std::vector<Explicit_triangle>().swap(jittered);
    auto repair = [&](std::size_t n, const std::string& out) {
      const std::string command = "'" + tool + "' repair '" + in + "' -o '" + out +
                                  "' --relative-tolerance 1e-5 --threads " + std::to_string(n) + " > '" + out + ".log'";
      if(std::system(command.c_str()) != 0) throw std::runtime_error("failed: " + command);
    };
    const std::string out1 = folder + "/out1.stl", outn = folder + "/outn.stl";
    Row r{"4M jittered STL: soup_topology repair", 0, 0};
    repair(1, out1);
    time_interleaved(r, [&] { repair(1, out1); }, [&] { repair(threads, outn); });
    std::ifstream a(out1, std::ios::binary), b(outn, std::ios::binary);
    const std::string sa((std::istreambuf_iterator<char>(a)), {}), sb((std::istreambuf_iterator<char>(b)), {});
    if(sa != sb) {
      std::printf("soup_topology repair: the files written on 1 and %zu threads differ\n", threads);
      identical = false;
    }
    rows.push_back(r);
    print_row(r, threads);
    std::filesystem::remove_all(folder);
  }
  std::printf(identical ? "every parallel result is identical to the 1-thread result\n"
                        : "SOME PARALLEL RESULTS DIFFER\n");
  return identical ? EXIT_SUCCESS : EXIT_FAILURE;
}
