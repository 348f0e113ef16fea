// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The cut of a soup into tiles: the plan (balanced, independent of the order of the triangles),
// the tiles a triangle's halo reaches (checked against the cells one by one), the spill files.

#include <Soup_topology/Soup_tiling.h>

#include <Soup_topology/IO/write_triangle_soup.h>

#include "test_utilities.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <set>
#include <string>
#include <vector>

namespace soup_tiling_test {

namespace ST = Soup_topology;
using Point = CGAL::Epick::Point_3;
using Triangle = std::array<std::size_t, 3>;

// An exploded, jittered wavy sheet: `n` x `n` quads, every triangle with its own corners.
void exploded_sheet(int n, double jitter, unsigned seed, std::vector<Point>& points, std::vector<Triangle>& triangles)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> move(-jitter, jitter);
  const auto at = [&](int i, int j) {
    const double x = double(i) / n, y = double(j) / n;
    return Point(x + move(random), y + move(random), 0.1 * std::sin(6 * x) * std::cos(5 * y) + move(random));
  };
  for(int i = 0; i < n; ++i)
    for(int j = 0; j < n; ++j) {
      const std::size_t b = points.size();
      points.push_back(at(i, j));
      points.push_back(at(i + 1, j));
      points.push_back(at(i + 1, j + 1));
      points.push_back(at(i, j + 1));
      points.push_back(at(i, j));
      points.push_back(at(i + 1, j + 1));
      triangles.push_back({b, b + 1, b + 2});
      triangles.push_back({b + 3, b + 4, b + 5});
    }
}

ST::Tile_corners corners_of(const std::vector<Point>& points, const Triangle& t)
{
  ST::Tile_corners c;
  for(std::size_t k = 0; k < 3; ++k) c[k] = {{points[t[k]].x(), points[t[k]].y(), points[t[k]].z()}};
  return c;
}

// The distance from the point `p` to the closed box of cell `(x, y, z)` of the plan.
double distance_to_cell(const ST::Tile_plan& plan, const std::array<double, 3>& p, const std::array<std::uint64_t, 3>& cell)
{
  const double size = plan.side() / std::ldexp(1.0, int(plan.level()));
  double d2 = 0;
  for(std::size_t i = 0; i < 3; ++i) {
    const double lo = plan.origin()[i] + double(cell[i]) * size, hi = lo + size;
    const double gap = p[i] < lo ? lo - p[i] : (p[i] > hi ? p[i] - hi : 0.);
    d2 += gap * gap;
  }
  return std::sqrt(d2);
}

std::uint64_t morton(const std::array<std::uint64_t, 3>& c)
{
  return ST::internal::spread_by_three(c[0]) << 2 | ST::internal::spread_by_three(c[1]) << 1 |
         ST::internal::spread_by_three(c[2]);
}

TEST(SoupTiling, PlanOwnsEveryTriangleOnceInBalancedTiles)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  exploded_sheet(60, 1e-5, 1, points, triangles);
  const ST::Soup_triangle_source<std::vector<Point>, std::vector<Triangle>> source(points, triangles);
  for(std::size_t tiles : {1u, 2u, 8u, 64u}) {
    const ST::Tile_plan plan = ST::plan_tiles(source, tiles, 0.01, 6);
    ASSERT_EQ(plan.number_of_tiles(), tiles);
    EXPECT_EQ(plan.first_cell(0), 0u);
    EXPECT_EQ(plan.first_cell(tiles), std::uint64_t(1) << 18);
    std::vector<std::size_t> owned(tiles, 0);
    for(const Triangle& t : triangles) {
      const std::size_t owner = plan.owner(corners_of(points, t));
      ASSERT_LT(owner, tiles);
      const std::uint64_t cell = plan.cell_of(ST::Tile_plan::anchor(corners_of(points, t)));
      EXPECT_LE(plan.first_cell(owner), cell);
      EXPECT_LT(cell, plan.first_cell(owner + 1));
      ++owned[owner];
    }
    // the largest cell count bounds the imbalance
    std::map<std::uint64_t, std::size_t> per_cell;
    for(const Triangle& t : triangles) ++per_cell[plan.cell_of(ST::Tile_plan::anchor(corners_of(points, t)))];
    std::size_t fattest = 0;
    for(const auto& c : per_cell) fattest = std::max(fattest, c.second);
    for(std::size_t t = 0; t < tiles; ++t) {
      EXPECT_EQ(plan.owned_triangles(t), owned[t]) << tiles << " tiles, tile " << t;
      EXPECT_LE(owned[t], triangles.size() / tiles + fattest) << tiles << " tiles, tile " << t;
      if(t + 1 < tiles) {
        EXPECT_LE(plan.first_cell(t), plan.first_cell(t + 1));
      }
    }
  }
}

// The cut and the owners depend on the triangles, not on their order (nor on the order of the
// corners of a triangle).
TEST(SoupTiling, ShuffledSoupGivesTheSamePlan)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  exploded_sheet(40, 1e-5, 2, points, triangles);
  std::vector<Triangle> shuffled = triangles;
  std::mt19937 random(3);
  std::shuffle(shuffled.begin(), shuffled.end(), random);
  for(Triangle& t : shuffled) std::rotate(t.begin(), t.begin() + std::uniform_int_distribution<int>(0, 2)(random), t.end());
  const ST::Soup_triangle_source<std::vector<Point>, std::vector<Triangle>> a(points, triangles), b(points, shuffled);
  const ST::Tile_plan pa = ST::plan_tiles(a, 8, 0.02), pb = ST::plan_tiles(b, 8, 0.02);
  for(std::size_t t = 0; t <= 8; ++t) EXPECT_EQ(pa.first_cell(t), pb.first_cell(t));
  for(std::size_t t = 0; t < 8; ++t) EXPECT_EQ(pa.owned_triangles(t), pb.owned_triangles(t));
  std::vector<std::size_t> ta, tb;
  for(std::size_t i = 0; i < shuffled.size(); ++i) {
    EXPECT_EQ(pa.owner(corners_of(points, shuffled[i])), pb.owner(corners_of(points, shuffled[i])));
    ta.clear();
    tb.clear();
    pa.tiles_meeting(corners_of(points, shuffled[i]), std::back_inserter(ta));
    pb.tiles_meeting(corners_of(points, shuffled[i]), std::back_inserter(tb));
    EXPECT_EQ(ta, tb);
  }
}

// A plan sent as bytes to the other processes of a team is the same plan: the same cells, owners,
// tiles met, boxes and distances; a truncated or altered plan is refused.
TEST(SoupTiling, PlanAsBytesIsTheSamePlan)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  exploded_sheet(30, 1e-5, 4, points, triangles);
  const ST::Soup_triangle_source<std::vector<Point>, std::vector<Triangle>> source(points, triangles);
  const ST::Tile_plan plan = ST::plan_tiles(source, 7, 0.03, 5);
  const std::vector<char> bytes = plan.to_bytes();
  const ST::Tile_plan copy = ST::Tile_plan::from_bytes(bytes);
  EXPECT_EQ(copy.to_bytes(), bytes);
  ASSERT_EQ(copy.number_of_tiles(), plan.number_of_tiles());
  EXPECT_EQ(copy.level(), plan.level());
  EXPECT_EQ(copy.halo(), plan.halo());
  EXPECT_EQ(copy.side(), plan.side());
  EXPECT_EQ(copy.origin(), plan.origin());
  EXPECT_EQ(copy.mean_edge_length(), plan.mean_edge_length());
  EXPECT_EQ(copy.number_of_triangles(), plan.number_of_triangles());
  for(std::size_t t = 0; t < plan.number_of_tiles(); ++t) {
    EXPECT_EQ(copy.first_cell(t), plan.first_cell(t));
    EXPECT_EQ(copy.owned_triangles(t), plan.owned_triangles(t));
    EXPECT_EQ(copy.block_boxes(t), plan.block_boxes(t));
  }
  std::vector<std::size_t> a, b;
  for(const Triangle& tr : triangles) {
    const ST::Tile_corners c = corners_of(points, tr);
    EXPECT_EQ(copy.owner(c), plan.owner(c));
    a.clear();
    b.clear();
    plan.tiles_meeting(c, std::back_inserter(a));
    copy.tiles_meeting(c, std::back_inserter(b));
    EXPECT_EQ(a, b);
    EXPECT_EQ(copy.distance_to_tile(c[0], 3), plan.distance_to_tile(c[0], 3));
  }
  std::vector<char> truncated(bytes.begin(), bytes.end() - 8);
  EXPECT_THROW(ST::Tile_plan::from_bytes(truncated), ST::Invalid_input);
  std::vector<char> bad_level = bytes;
  bad_level[0] = 9;
  EXPECT_THROW(ST::Tile_plan::from_bytes(bad_level), ST::Invalid_input);
  EXPECT_THROW(ST::Tile_plan::from_bytes(std::vector<char>(3)), ST::Invalid_input);
}

// Every tile with a cell within the halo of a corner of a triangle is among the tiles the
// triangle meets, the owner always is, and a tile met has a cell within reach of the triangle's
// box grown by the halo: checked against every cell of a coarse plan, and the answer cell by
// cell equals the answer by blocks.
TEST(SoupTiling, TilesMeetingAgreeWithTheCellsOneByOne)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  exploded_sheet(12, 1e-4, 4, points, triangles);
  // long triangles across the sheet: their boxes cover many cells
  points.push_back(Point(0, 0, 0));
  points.push_back(Point(1, 0.9, 0.05));
  points.push_back(Point(0.5, 1, -0.05));
  triangles.push_back({points.size() - 3, points.size() - 2, points.size() - 1});
  const ST::Soup_triangle_source<std::vector<Point>, std::vector<Triangle>> source(points, triangles);
  const unsigned level = 3;
  const std::uint64_t side = 8;
  for(double halo : {0.0, 0.03, 0.2}) {
    const ST::Tile_plan plan = ST::plan_tiles(source, 7, halo, level);
    for(const Triangle& t : triangles) {
      const ST::Tile_corners c = corners_of(points, t);
      std::vector<std::size_t> by_cells, by_blocks;
      plan.tiles_meeting(c, std::back_inserter(by_cells), 1u << 20);
      plan.tiles_meeting(c, std::back_inserter(by_blocks), 0);
      EXPECT_EQ(by_cells, by_blocks) << "halo " << halo;
      EXPECT_TRUE(std::binary_search(by_cells.begin(), by_cells.end(), plan.owner(c)));
      std::set<std::size_t> near_a_corner, within_box;
      for(std::uint64_t x = 0; x < side; ++x)
        for(std::uint64_t y = 0; y < side; ++y)
          for(std::uint64_t z = 0; z < side; ++z) {
            const std::array<std::uint64_t, 3> cell{{x, y, z}};
            const std::size_t tile = plan.tile_of_cell(morton(cell));
            for(const auto& p : c)
              if(distance_to_cell(plan, p, cell) <= halo) near_a_corner.insert(tile);
            // the box of the triangle grown by the halo (and a little more) meets the cell
            bool meets = true;
            const double size = plan.side() / double(side);
            for(std::size_t i = 0; i < 3; ++i) {
              const double lo = plan.origin()[i] + double(cell[i]) * size;
              const double a = std::min({c[0][i], c[1][i], c[2][i]}) - halo - 1e-9;
              const double b = std::max({c[0][i], c[1][i], c[2][i]}) + halo + 1e-9;
              meets = meets && b >= lo && a <= lo + size;
            }
            if(meets) within_box.insert(tile);
          }
      for(std::size_t tile : near_a_corner)
        EXPECT_TRUE(std::binary_search(by_cells.begin(), by_cells.end(), tile)) << "halo " << halo << ", tile " << tile;
      for(std::size_t tile : by_cells) EXPECT_TRUE(within_box.count(tile)) << "halo " << halo << ", tile " << tile;
    }
  }
}

// The spill files of a binary STL, streamed: every triangle once as owned, in its owner's file,
// and in the file of every tile it meets; read back with the coordinates of the file.
TEST(SoupTiling, SpillFilesOfAStreamedBinarySTL)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  exploded_sheet(30, 1e-5, 5, points, triangles);
  // float coordinates, as the STL holds them
  for(Point& p : points) p = soup_test::rounded_to_float(p);
  const std::string folder = soup_test::temporary_folder("tiling");
  const std::string file = folder + "/sheet.stl";
  {
    std::ofstream out(file, std::ios::binary);
    ST::IO::write_STL_triangle_soup(out, points, triangles);
  }
  const ST::Binary_STL_source source({file});
  const ST::Tile_plan plan = ST::plan_tiles(source, 8, 0.02);
  const ST::Tile_files files = ST::write_tile_files(source, plan, folder);
  ASSERT_EQ(files.files.size(), 8u);
  std::vector<int> owned_times(triangles.size(), 0);
  std::size_t records = 0;
  for(std::size_t t = 0; t < 8; ++t) {
    const std::vector<ST::Tile_triangle> tile = ST::read_tile_file(files.files[t]);
    records += tile.size();
    std::size_t owned = 0;
    for(std::size_t k = 0; k < tile.size(); ++k) {
      const ST::Tile_triangle& r = tile[k];
      ASSERT_LT(r.index, triangles.size());
      EXPECT_EQ(r.corners, corners_of(points, triangles[r.index]));
      EXPECT_EQ(r.owned, plan.owner(r.corners) == t);
      std::vector<std::size_t> meeting;
      plan.tiles_meeting(r.corners, std::back_inserter(meeting));
      EXPECT_TRUE(std::binary_search(meeting.begin(), meeting.end(), t));
      if(k > 0) {
        EXPECT_LT(tile[k - 1].index, r.index); // in the order of the source
      }
      if(r.owned) {
        ++owned;
        ++owned_times[r.index];
      }
    }
    EXPECT_EQ(owned, files.owned[t]);
    EXPECT_EQ(owned, plan.owned_triangles(t));
    EXPECT_EQ(tile.size() - owned, files.halo[t]);
  }
  for(int times : owned_times) EXPECT_EQ(times, 1);
  // every (triangle, tile met) pair is a record
  std::size_t pairs = 0;
  for(const Triangle& t : triangles) {
    std::vector<std::size_t> meeting;
    plan.tiles_meeting(corners_of(points, t), std::back_inserter(meeting));
    pairs += meeting.size();
  }
  EXPECT_EQ(records, pairs);
  EXPECT_GT(records, triangles.size()); // the halos hold copies

  // Only the tiles wanted, with a larger halo: their files hold what a spill of every tile with
  // that halo holds; the others have no file.
  const ST::Tile_plan wider = plan.with_halo(0.05);
  const std::string all_folder = folder + "/all", some_folder = folder + "/some";
  std::filesystem::create_directories(all_folder);
  std::filesystem::create_directories(some_folder);
  const ST::Tile_files all = ST::write_tile_files(source, wider, all_folder);
  std::vector<char> wanted(8, 0);
  wanted[2] = wanted[5] = 1;
  const ST::Tile_files some = ST::write_tile_files(source, wider, some_folder, &wanted);
  for(std::size_t t = 0; t < 8; ++t) {
    if(!wanted[t]) {
      EXPECT_TRUE(some.files[t].empty());
      EXPECT_FALSE(std::filesystem::exists(ST::internal::tile_file_name(some_folder, t)));
      continue;
    }
    const std::vector<ST::Tile_triangle> a = ST::read_tile_file(all.files[t]), b = ST::read_tile_file(some.files[t]);
    ASSERT_EQ(a.size(), b.size());
    for(std::size_t k = 0; k < a.size(); ++k) {
      EXPECT_EQ(a[k].corners, b[k].corners);
      EXPECT_EQ(a[k].index, b[k].index);
      EXPECT_EQ(a[k].owned, b[k].owned);
    }
    EXPECT_EQ(some.owned[t], all.owned[t]);
    EXPECT_EQ(some.halo[t], all.halo[t]);
    EXPECT_GT(all.halo[t], files.halo[t]); // the larger halo holds more
  }
  EXPECT_THROW(ST::write_tile_files(source, wider, some_folder, &(wanted = std::vector<char>(3, 1))), ST::Invalid_input);

  // a damaged file is refused
  std::filesystem::resize_file(files.files[0], std::filesystem::file_size(files.files[0]) - 1);
  EXPECT_THROW(ST::read_tile_file(files.files[0]), ST::IO::Read_error);
  std::filesystem::remove_all(folder);
}

// A real mesh, streamed from its file as one of two files of an assembly: the indices go on from
// one file to the next, and the second copy's triangles are owned where the first's are.
TEST(SoupTiling, RealMeshAsAnAssemblyOfTwoFiles)
{
  const std::string pig = soup_test::data_file("cgal_repair/pig.stl.xz");
  const ST::Binary_STL_source one({pig}), two({pig, pig});
  const ST::Tile_plan plan = ST::plan_tiles(two, 4, 0.3);
  std::size_t n = 0;
  std::vector<std::size_t> owners;
  one.for_each([&](const ST::Tile_corners& c, std::uint64_t index) {
    EXPECT_EQ(index, n);
    ++n;
    owners.push_back(plan.owner(c));
  });
  ASSERT_EQ(plan.number_of_triangles(), 2 * n);
  std::size_t owned = 0;
  two.for_each([&](const ST::Tile_corners& c, std::uint64_t index) { EXPECT_EQ(plan.owner(c), owners[index % n]); });
  for(std::size_t t = 0; t < 4; ++t) {
    owned += plan.owned_triangles(t);
    EXPECT_EQ(plan.owned_triangles(t) % 2, 0u); // each triangle twice, in the same tile
  }
  EXPECT_EQ(owned, 2 * n);
}

TEST(SoupTiling, BadArgumentsAndFilesAreRefused)
{
  std::vector<Point> points{Point(0, 0, 0), Point(1, 0, 0), Point(0, 1, 0),
                            Point(std::numeric_limits<double>::quiet_NaN(), 0, 0)};
  std::vector<Triangle> good{{0, 1, 2}}, bad{{0, 1, 2}, {0, 1, 3}};
  const ST::Soup_triangle_source<std::vector<Point>, std::vector<Triangle>> source(points, good), nan(points, bad);
  EXPECT_THROW(ST::plan_tiles(source, 0, 0.1), ST::Invalid_input);
  EXPECT_THROW(ST::plan_tiles(source, 2, -1), ST::Invalid_input);
  EXPECT_THROW(ST::plan_tiles(source, 2, std::numeric_limits<double>::infinity()), ST::Invalid_input);
  EXPECT_THROW(ST::plan_tiles(source, 2, 0.1, 9), ST::Invalid_input);
  try {
    ST::plan_tiles(nan, 2, 0.1);
    ADD_FAILURE() << "not refused";
  } catch(const ST::Invalid_input& e) {
    EXPECT_NE(std::string(e.what()).find("triangle 1"), std::string::npos) << e.what();
  }
  const std::string folder = soup_test::temporary_folder("tiling_bad");
  const std::string ascii = folder + "/ascii.stl", truncated = folder + "/truncated.stl";
  std::ofstream(ascii) << "solid x\nendsolid x\n";
  {
    std::ofstream out(truncated, std::ios::binary);
    ST::IO::write_STL_triangle_soup(out, std::vector<Point>(points.begin(), points.begin() + 3), good);
  }
  std::filesystem::resize_file(truncated, std::filesystem::file_size(truncated) - 10);
  EXPECT_THROW(ST::plan_tiles(ST::Binary_STL_source({ascii}), 2, 0.1), ST::IO::Read_error);
  EXPECT_THROW(ST::plan_tiles(ST::Binary_STL_source({truncated}), 2, 0.1), ST::IO::Read_error);
  EXPECT_THROW(ST::plan_tiles(ST::Binary_STL_source({folder + "/missing.stl"}), 2, 0.1), ST::IO::Read_error);
  // a plan used with another soup
  const ST::Tile_plan plan = ST::plan_tiles(source, 2, 0.1);
  std::vector<Triangle> more{{0, 1, 2}, {2, 1, 0}};
  EXPECT_THROW(ST::write_tile_files(ST::Soup_triangle_source<std::vector<Point>, std::vector<Triangle>>(points, more), plan,
                                    folder),
               ST::Invalid_input);
  std::filesystem::remove_all(folder);
}

} // namespace soup_tiling_test
