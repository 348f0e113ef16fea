// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// soup_topology_mpi under mpirun against `soup_topology repair --tiles N` in one process: the same
// file, byte for byte, and the same report, for 1, 2 and 4 processes (oversubscribed); a
// streamed STL and a soup read whole by rank 0; a soup repaired whole; errors end the job.

#include "soup_generators.h"
#include "test_utilities.h"

#include <Soup_topology/IO/write_triangle_soup.h>
#include <Soup_topology/Soup_tiling.h>
#include <Soup_topology/tiled_reconstruct_topology.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

// The names of this file live in a namespace of its own: test/CMakeLists.txt compiles several
// test files as one translation unit.
namespace mpi_repair_test {

namespace {

namespace ST = Soup_topology;
using Point = CGAL::Epick::Point_3;

std::string file_content(const std::string& file)
{
  std::ifstream in(file, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// The report without the lines that name the output or count the processes (and without what
// follows a line "stderr:").
std::string report_without_names(std::string text)
{
  const std::size_t errors = text.find("stderr:\n");
  if(errors != std::string::npos) text.erase(errors);
  std::string out, line;
  for(std::size_t at = 0; at < text.size();) {
    const std::size_t end = text.find('\n', at);
    line = text.substr(at, end == std::string::npos ? std::string::npos : end - at);
    at = end == std::string::npos ? text.size() : end + 1;
    if(line.rfind("  output ", 0) == 0 || line.rfind("  processes ", 0) == 0) continue;
    out += line + "\n";
  }
  return out;
}

class MpiRepair : public ::testing::Test
{
protected:
  void SetUp() override
  {
    if(std::string(SOUP_TOPOLOGY_MPI_CLI).empty() || std::string(SOUP_TOPOLOGY_CLI).empty())
      GTEST_SKIP() << "soup_topology_mpi is not built (MPI not found, or SOUP_TOPOLOGY_WITH_MPI=OFF)";
    folder_ = soup_test::temporary_folder("mpi_repair");
  }
  void TearDown() override
  {
    if(!folder_.empty()) std::filesystem::remove_all(folder_);
  }

  std::pair<std::string, int> single(const std::string& in, const std::string& out, const std::string& options) const
  {
    return soup_test::run_command("'" + std::string(SOUP_TOPOLOGY_CLI) + "' repair '" + in + "' -o '" + out + "' " +
                                  options);
  }
  // The standard output (the report), then, after a line "stderr:", the standard error: Open MPI
  // may write notes of its own there, which the comparisons of reports must not see.
  std::pair<std::string, int> mpi(int processes, const std::string& in, const std::string& out,
                                  const std::string& options) const
  {
    const std::string errors = folder_ + "/stderr.txt";
    // No single-copy transfers between the ranks: containers often forbid them (ptrace).
    auto r = soup_test::run_command("OMPI_MCA_btl_vader_single_copy_mechanism=none '" + std::string(SOUP_TOPOLOGY_MPIEXEC) +
                                    "' --allow-run-as-root --oversubscribe -np " + std::to_string(processes) + " '" +
                                    std::string(SOUP_TOPOLOGY_MPI_CLI) + "' '" + in + "' -o '" + out + "' " + options +
                                    " 2> '" + errors + "'");
    r.first += "stderr:\n" + file_content(errors);
    return r;
  }
  // The single process and K processes write the same file and the same report.
  void expect_same(const std::string& in, const std::string& options, std::initializer_list<int> processes)
  {
    const std::string expected_file = folder_ + "/single.stl";
    const auto expected = single(in, expected_file, options);
    ASSERT_EQ(expected.second, 0) << expected.first;
    for(int k : processes) {
      const std::string out = folder_ + "/mpi_" + std::to_string(k) + ".stl";
      const auto got = mpi(k, in, out, options);
      ASSERT_EQ(got.second, 0) << k << " processes\n" << got.first;
      EXPECT_EQ(file_content(out), file_content(expected_file)) << k << " processes: " << in;
      EXPECT_EQ(report_without_names(got.first), report_without_names(expected.first)) << k << " processes";
      if(k > 1) {
        EXPECT_NE(got.first.find("  processes "), std::string::npos) << got.first;
      }
    }
    // No spill or part file is left in the folder the spill went to.
    for(const auto& entry : std::filesystem::directory_iterator(spill_))
      ADD_FAILURE() << entry.path() << " was left";
  }

  // The elephant, subdivided 1-to-4 `subdivisions` times, cut into patches whose seams are
  // jittered by 1e-6 of its diagonal (`seed`), the points as an STL holds them; `tolerance` is
  // 1e-5 of the diagonal, written in full. The spill folder is made.
  soup_test::T_junction_soup<Point> elephant_seams(int subdivisions, unsigned seed, std::string& tolerance)
  {
    std::vector<Point> points;
    std::vector<std::array<std::size_t, 3>> triangles;
    soup_test::read_data_mesh("clean/elephant.off", points, triangles);
    for(int i = 0; i < subdivisions; ++i) soup_test::subdivide_midpoints(points, triangles);
    const CGAL::Bbox_3 box = CGAL::bbox_3(points.begin(), points.end());
    const double diagonal = std::sqrt(CGAL::square(box.xmax() - box.xmin()) + CGAL::square(box.ymax() - box.ymin()) +
                                      CGAL::square(box.zmax() - box.zmin()));
    auto soup = soup_test::t_junction_soup(points, triangles, 6, 1e-6 * diagonal, seed);
    for(Point& p : soup.points) p = soup_test::rounded_to_float(p);
    char text[32];
    std::snprintf(text, sizeof text, "%.17g", 1e-5 * diagonal);
    tolerance = text;
    spill_ = folder_ + "/spill";
    std::filesystem::create_directory(spill_);
    return soup;
  }

  std::string folder_, spill_;
};

// A real mesh cut into patches with jittered T-junction seams, as a binary STL (streamed by
// rank 0's plan and spill), in 8 tiles.
TEST_F(MpiRepair, JitteredSeamsGiveTheSingleProcessFile)
{
  std::string tolerance;
  const auto soup = elephant_seams(0, 5, tolerance);
  const std::string in = folder_ + "/seams.stl";
  ST::IO::write_triangle_soup(in, soup.points, soup.triangles);
  const std::string options = "--tolerance " + tolerance + " --tiles 8 --spill-folder '" + spill_ + "'";
  expect_same(in, options, {1, 2, 4});
  // The same soup as an assembly of two files.
  const std::size_t half = soup.triangles.size() / 2;
  ST::IO::write_triangle_soup(folder_ + "/front.stl", soup.points,
                              std::vector<std::array<std::size_t, 3>>(soup.triangles.begin(), soup.triangles.begin() + std::ptrdiff_t(half)));
  ST::IO::write_triangle_soup(folder_ + "/back.stl", soup.points,
                              std::vector<std::array<std::size_t, 3>>(soup.triangles.begin() + std::ptrdiff_t(half), soup.triangles.end()));
  const auto parts = mpi(2, folder_ + "/front.stl' '" + folder_ + "/back.stl", folder_ + "/parts.stl", options);
  ASSERT_EQ(parts.second, 0) << parts.first;
  EXPECT_EQ(file_content(folder_ + "/parts.stl"), file_content(folder_ + "/single.stl"));
}

// Under `--max-memory` every rank executes itself again before `MPI_Init`, with its large blocks
// in huge pages (tools/memory_reuse.h), as `mpirun` started it: the job runs as before and writes
// the single process's file and report, the tiles chosen by the same model. A soup of about 90,000
// triangles (the elephant, subdivided twice, cut into patches with jittered seams) under 50M: in
// tiles. With the user's own GLIBC_TUNABLES (which the program then leaves alone), the same. Under
// 2G: in memory, on rank 0, as the single process.
TEST_F(MpiRepair, MemoryLimitGivesTheSingleProcessFile)
{
  std::string tolerance;
  const auto soup = elephant_seams(2, 3, tolerance);
  const std::string in = folder_ + "/soup.stl";
  ST::IO::write_triangle_soup(in, soup.points, soup.triangles);
  const std::string options = "--tolerance " + tolerance + " --max-memory 50M --spill-folder '" + spill_ + "'";
  expect_same(in, options, {2});
  // in tiles, chosen by the model (the text report: "  tiles   N")
  const auto report = single(in, folder_ + "/again.stl", options);
  ASSERT_EQ(report.second, 0) << report.first;
  const std::size_t at = report.first.find("\n  tiles ");
  ASSERT_NE(at, std::string::npos) << report.first;
  EXPECT_GT(std::stol(report.first.substr(at + 9)), 1) << report.first;
  ASSERT_EQ(setenv("GLIBC_TUNABLES", "glibc.malloc.perturb=0", 1), 0);
  const auto tuned = mpi(2, in, folder_ + "/tuned.stl", options);
  ASSERT_EQ(unsetenv("GLIBC_TUNABLES"), 0);
  ASSERT_EQ(tuned.second, 0) << tuned.first;
  EXPECT_EQ(file_content(folder_ + "/tuned.stl"), file_content(folder_ + "/single.stl"));
  // Under a limit that the repair in memory fits: rank 0 repairs in memory, as the single process
  // does (the tiles' canonical order would give another file), the same report.
  const std::string roomy = "--tolerance " + tolerance + " --max-memory 2G";
  const auto whole = single(in, folder_ + "/whole.stl", roomy);
  ASSERT_EQ(whole.second, 0) << whole.first;
  EXPECT_EQ(whole.first.find("\n  tiles "), std::string::npos) << whole.first;
  const auto job = mpi(2, in, folder_ + "/job.stl", roomy);
  ASSERT_EQ(job.second, 0) << job.first;
  EXPECT_EQ(file_content(folder_ + "/job.stl"), file_content(folder_ + "/whole.stl"));
  EXPECT_EQ(report_without_names(job.first), report_without_names(whole.first));
}

// An OFF file (read whole by rank 0; the other ranks never read the source), the processes'
// default number of tiles against the single process's 8: the output does not depend on either.
TEST_F(MpiRepair, SoupReadWholeByRankZero)
{
  spill_ = folder_ + "/spill";
  std::filesystem::create_directory(spill_);
  const std::string in = soup_test::data_file("cad/ALSTOM_TEST4.off");
  const std::string expected_file = folder_ + "/single.stl";
  const auto expected = single(in, expected_file, "--tolerance 1e-6 --tiles 8");
  ASSERT_EQ(expected.second, 0) << expected.first;
  const auto got = mpi(3, in, folder_ + "/mpi.stl", "--tolerance 1e-6 --spill-folder '" + spill_ + "'");
  ASSERT_EQ(got.second, 0) << got.first;
  EXPECT_EQ(file_content(folder_ + "/mpi.stl"), file_content(expected_file));
  EXPECT_EQ(soup_test::json_integer("{" + got.first + "}", "tiles"), -1); // text report
  EXPECT_NE(got.first.find("  tiles                          12"), std::string::npos) << got.first;
}

// A crowd of points within the tolerance: a rank finds the region crowded, every rank stops,
// and rank 0 repairs the whole soup, as the single process does.
TEST_F(MpiRepair, CrowdedSoupIsRepairedWholeByRankZero)
{
  std::vector<Point> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  std::mt19937 random(2);
  std::uniform_real_distribution<double> offset(0, 1e-4);
  for(std::size_t i = 0; i < 3000; ++i) {
    for(int k = 0; k < 3; ++k) points.emplace_back(0.5 + offset(random), 0.5 + offset(random), 0.5 + offset(random));
    triangles.push_back({3 * i, 3 * i + 1, 3 * i + 2});
  }
  for(int k = 0; k < 4; ++k) {
    const std::size_t first = points.size();
    points.emplace_back(k, 0, 0);
    points.emplace_back(k + 1, 0, 0);
    points.emplace_back(k, 1, 0);
    triangles.push_back({first, first + 1, first + 2});
  }
  const std::string in = folder_ + "/crowd.stl";
  ST::IO::write_triangle_soup(in, points, triangles);
  spill_ = folder_ + "/spill";
  std::filesystem::create_directory(spill_);
  expect_same(in, "--tolerance 1e-3 --tiles 4 --spill-folder '" + spill_ + "'", {4});
  const auto got = mpi(2, in, folder_ + "/again.stl", "--json --tolerance 1e-3 --tiles 4");
  ASSERT_EQ(got.second, 0) << got.first;
  EXPECT_TRUE(soup_test::json_bool(got.first, "whole_soup")) << got.first;
}

// Errors: a missing input (rank 0, which reads the inputs, tells the others) and a missing
// tolerance (a usage error, seen by every rank) stop every rank with exit code 2 and one message;
// a spill folder that does not exist ends the job.
TEST_F(MpiRepair, ErrorsEndTheJob)
{
  const auto missing = mpi(2, folder_ + "/missing.stl", folder_ + "/out.stl", "--tolerance 1e-3");
  EXPECT_EQ(missing.second, 2) << missing.first;
  EXPECT_NE(missing.first.find("soup_topology_mpi: " + folder_ + "/missing.stl: cannot open the file for reading ("),
            std::string::npos) << missing.first;
  const std::string in = soup_test::data_file("cad/ALSTOM_TEST4.off");
  const auto no_tolerance = mpi(2, in, folder_ + "/out.stl", "--tiles 4");
  EXPECT_EQ(no_tolerance.second, 2) << no_tolerance.first;
  EXPECT_NE(no_tolerance.first.find("--tolerance"), std::string::npos) << no_tolerance.first;
  const auto no_option = mpi(2, in, folder_ + "/out.stl", "");
  EXPECT_EQ(no_option.second, 2) << no_option.first;
  EXPECT_NE(no_option.first.find("soup_topology_mpi: give an absolute --tolerance T\n"), std::string::npos)
    << no_option.first;
  const auto folder_input = mpi(2, folder_, folder_ + "/out.stl", "--tolerance 1e-3");
  EXPECT_EQ(folder_input.second, 2) << folder_input.first;
  EXPECT_NE(folder_input.first.find("soup_topology_mpi: " + folder_ + ": is a folder, not a file"), std::string::npos)
    << folder_input.first;
  for(const auto& run : {missing, folder_input, no_tolerance, no_option})
    EXPECT_EQ(run.first.find("soup_topology_mpi:"), run.first.rfind("soup_topology_mpi:"))
      << "one message, from rank 0: " << run.first;
  const auto no_folder = mpi(2, in, folder_ + "/out.stl", "--tolerance 1e-6 --spill-folder '" + folder_ + "/nowhere'");
  EXPECT_NE(no_folder.second, 0) << no_folder.first;
  EXPECT_NE(no_folder.first.find("no such folder"), std::string::npos) << no_folder.first;
  EXPECT_FALSE(std::filesystem::exists(folder_ + "/out.stl"));
}

} // namespace

} // namespace mpi_repair_test
