// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The repair of a soup cut into tiles (doc/Soup_topology/Tiled_repair_design.md): every tile is
// repaired on its region with the in-memory pipeline, the taint of its points is followed phase
// by phase, and only the triangles it owns, untainted, are kept; a tile with a tainted owned
// triangle is repaired again on a larger region. The result is the in-memory result in a
// canonical order.

#ifndef SOUP_TOPOLOGY_TILED_RECONSTRUCT_TOPOLOGY_H
#define SOUP_TOPOLOGY_TILED_RECONSTRUCT_TOPOLOGY_H

#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/Soup_tiling.h>
#include <Soup_topology/parameters.h>
#include <Soup_topology/reconstruct_topology.h>
#include <Soup_topology/internal/coordinate_scale.h>
#include <Soup_topology/internal/tile_parts.h>
#include <Soup_topology/internal/tile_taint.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/tags.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace Soup_topology {

/// \ingroup PkgSoupTopologyTiling
/// \brief what `tiled_reconstruct_topology()` did.
struct Tiled_reconstruction_report
{
  double tolerance = 0;                  ///< the absolute tolerance
  std::size_t input_triangles = 0;       ///< triangles of the source
  std::size_t tiles = 0;                 ///< tiles of the plan
  double first_halo = 0;                 ///< the halo of the first run of every tile
  double largest_halo = 0;               ///< the largest halo a tile was repaired with
  std::size_t tile_runs = 0;             ///< repairs of a tile's region, the repeated ones included
  std::size_t repeated_tiles = 0;        ///< tiles repaired again on a larger region
  std::size_t discarded_triangles = 0;   ///< owned triangles found tainted, in the runs discarded
  std::size_t largest_tile_triangles = 0; ///< the most input triangles of one run (its memory)
  std::size_t halo_triangles = 0;        ///< triangles spilled to the halo of a tile that does not own them
  bool whole_soup = false;               ///< `true` if the soup was repaired as one tile (see `whole_soup_reason`)
  std::string whole_soup_reason;         ///< why the soup was repaired as one tile
  std::size_t output_points = 0;
  std::size_t output_triangles = 0;
};

/// \ingroup PkgSoupTopologyTiling
/// \brief the canonical order of an indexed triangle soup: the points are the distinct
/// coordinates of the triangles' corners in lexicographic order (points no triangle uses are left
/// out, equal points merged), every triangle starts at its smallest point index (its orientation
/// kept), and the triangles are sorted. Two soups that are the same set of triangles on the same
/// coordinates, however ordered and indexed, have the same canonical order.
template <class PointRange, class TriangleRange>
void canonical_triangle_soup(const PointRange& points_in, const TriangleRange& triangles_in,
                             std::vector<CGAL::Epick::Point_3>& points, std::vector<std::array<std::uint32_t, 3>>& triangles)
{
  std::vector<internal::Soup_part> parts(1);
  constexpr std::uint32_t unused = static_cast<std::uint32_t>(-1);
  std::vector<std::uint32_t> local(points_in.size(), unused);
  for(const auto& t : triangles_in) {
    std::array<std::uint32_t, 3> l;
    for(std::size_t k = 0; k < 3; ++k) {
      const std::size_t v = static_cast<std::size_t>(t[k]);
      if(local[v] == unused) {
        local[v] = static_cast<std::uint32_t>(parts[0].points.size());
        const auto& p = points_in[v];
        parts[0].points.push_back({{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}});
      }
      l[k] = local[v];
    }
    parts[0].triangles.push_back(l);
  }
  internal::merge_in_canonical_order(parts, points, triangles);
}

/// \ingroup PkgSoupTopologyTiling
/// \brief where a tiled repair stands, for the named parameter `tile_progress`: counts of the
/// process that calls it.
struct Tile_progress
{
  std::size_t round = 0;              ///< 0 for the first runs, then one per doubling of the halo
  std::size_t runs_done = 0;          ///< runs of this round done by this process
  std::size_t runs = 0;               ///< runs of this round for this process
  std::size_t triangles_done = 0;     ///< triangles owned by the tiles this process kept so far
  std::size_t triangles = 0;          ///< triangles owned by the tiles of this process's first round
};

/// \ingroup PkgSoupTopologyTiling
/// \brief the team of one process: `tiled_reconstruct_topology()` without a team uses it.
struct Single_process_team
{
  std::size_t rank() const { return 0; }
  std::size_t size() const { return 1; }
  void broadcast(std::vector<char>&) {}
  std::vector<std::uint64_t> all_gather(const std::vector<std::uint64_t>& values) { return values; }
};

namespace internal {

/// what one repair of a tile's region gives back.
struct Tile_run
{
  Soup_part owned;                     // the owned triangles, untainted, on the points they use
  std::size_t tainted_owned = 0;       // owned triangles with a tainted corner
  bool degenerate_under_collapse = false; // a degenerate triangle under COLLAPSE: not tiled
  bool crowded = false;                // the taint exceeded its budget (`Tile_taint::crowded()`): not tiled
};

/// repairs the region of tile `tile` given by the corners of its triangles, with the halo `halo`,
/// and keeps the owned triangles and the count of the tainted ones. Under `COLLAPSE`, a region
/// with a degenerate triangle is not repaired unless it is the whole soup (`whole_soup`, or a
/// region that holds every cell of the plan).
template <class ConcurrencyTag>
Tile_run repair_tile_region(const std::vector<Tile_corners>& region, const Tile_plan& plan, std::size_t tile, double halo,
                            double tolerance, std::size_t max_rounds, bool do_split, Small_features policy,
                            bool whole_soup = false)
{
  using Kernel = CGAL::Epick;
  using Point = Kernel::Point_3;
  using Triangles = std::vector<std::array<std::uint32_t, 3>>;
  const Kernel kernel;
  Tile_run run;
  std::vector<Point> given, points;
  Triangles triangles;
  given.reserve(3 * region.size());
  triangles.reserve(region.size());
  for(const Tile_corners& c : region) {
    const std::uint32_t first = static_cast<std::uint32_t>(given.size());
    for(const auto& p : c) given.emplace_back(p[0], p[1], p[2]);
    triangles.push_back({first, first + 1, first + 2});
  }
  std::vector<std::uint32_t> input_index;
  Soup_reconstruction<Kernel, Triangles, ConcurrencyTag> steps(points, triangles, input_index, kernel);
  steps.take_points(given);
  steps.weld_exact_duplicates();
  // A region that holds every cell holds the whole soup (no triangle leaves the cube).
  const bool everything = whole_soup || plan.holds_every_cell(tile);
  if(policy == Small_features::COLLAPSE && !everything) {
    // The flips of degenerate triangles are not followed by the taint: such a soup is not tiled.
    const Kernel::Collinear_3 collinear = kernel.collinear_3_object();
    for(const auto& t : triangles)
      if(collinear(points[t[0]], points[t[1]], points[t[2]])) {
        run.degenerate_under_collapse = true;
        return run;
      }
  }
  if(policy == Small_features::COLLAPSE) steps.flip_degenerate_triangles_away();
  steps.build_tables();
  Default_snap_visitor visitor;
  // The whole soup taints nothing (no point is shallow, no tainted point to start from): it is
  // repaired without the observer.
  std::optional<Tile_taint<Kernel>> taint;
  if(everything) {
    // (`snap_vertices()` and `split_t_junctions()` scale a soup at an extreme scale by a power
    // of two on their own, as in memory)
    steps.weld_and_split_in_rounds(tolerance, max_rounds, do_split, policy, visitor);
  } else {
    // The depth of a point: the region holds every point within it.
    const std::vector<std::array<double, 6>> boxes = plan.block_boxes(tile);
    std::vector<double> depth(points.size());
    for(std::size_t v = 0; v < points.size(); ++v)
      depth[v] = halo - plan.distance_to_tile({{points[v].x(), points[v].y(), points[v].z()}}, tile, boxes);
    taint.emplace(points, std::move(depth), tolerance, policy == Small_features::COLLAPSE, kernel);
    steps.weld_and_split_in_rounds(tolerance, max_rounds, do_split, policy, visitor, *taint);
    if(taint->crowded()) {
      run.crowded = true;
      return run;
    }
  }
  const auto tainted = [&](std::uint32_t v) { return taint && taint->tainted(v); };
  constexpr std::uint32_t unused = static_cast<std::uint32_t>(-1);
  std::vector<std::uint32_t> local(points.size(), unused);
  for(const auto& t : triangles) {
    Tile_corners c;
    for(std::size_t k = 0; k < 3; ++k) c[k] = {{points[t[k]].x(), points[t[k]].y(), points[t[k]].z()}};
    if(plan.owner(c) != tile) continue;
    if(tainted(t[0]) || tainted(t[1]) || tainted(t[2])) {
      ++run.tainted_owned;
      continue;
    }
    std::array<std::uint32_t, 3> l;
    for(std::size_t k = 0; k < 3; ++k) {
      if(local[t[k]] == unused) {
        local[t[k]] = static_cast<std::uint32_t>(run.owned.points.size());
        run.owned.points.push_back(c[k]);
      }
      l[k] = local[t[k]];
    }
    run.owned.triangles.push_back(l);
  }
  return run;
}

/// the settings of the repair of every tile, from the named parameters of
/// `tiled_reconstruct_topology()` (checked).
struct Tiled_repair_settings
{
  double tolerance = 0;
  std::size_t max_rounds = 8;
  bool do_split = true;
  Small_features policy = Small_features::COLLAPSE;
};

template <class NamedParameters>
Tiled_repair_settings tiled_repair_settings(const NamedParameters& np)
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  using CGAL::parameters::is_default_parameter;
  static_assert(!is_default_parameter<NamedParameters, CGAL::internal_np::snapping_tolerance_t>::value,
                "tiled_reconstruct_topology: give the absolute tolerance (snapping_tolerance)");
  static_assert(is_default_parameter<NamedParameters, internal_np::relative_tolerance_t>::value &&
                  !has_vertex_tolerance_map<NamedParameters>(),
                "tiled_reconstruct_topology: one absolute tolerance only (snapping_tolerance)");
  Tiled_repair_settings settings;
  settings.tolerance = CGAL::to_double(get_parameter(np, CGAL::internal_np::snapping_tolerance));
  const double t = settings.tolerance;
  if(!(t >= 0) || !std::isfinite(t))
    throw Invalid_input("tiled_reconstruct_topology: the tolerance must be a finite number >= 0");
  // (whether it is too large depends on the scale the soup is repaired at: checked once planned,
  // `check_tolerance_square()`)
  settings.max_rounds = choose_parameter(get_parameter(np, internal_np::maximum_number_of_rounds), std::size_t(8));
  settings.do_split = choose_parameter(get_parameter(np, internal_np::do_split_t_junctions), true);
  settings.policy = small_features_policy(np);
  if(!is_default_parameter<NamedParameters, internal_np::tile_halo_t>::value) {
    const double given = choose_parameter(get_parameter(np, internal_np::tile_halo), 1.0);
    if(!(given > 0) || !std::isfinite(given)) throw Invalid_input("tiled_reconstruct_topology: the halo must be finite and positive");
  }
  return settings;
}

/// `true` if the square of twice `tolerance` is a finite double: the predicates compare squared
/// distances with it. (A soup at an extreme scale is not asked: it is repaired whole, by steps
/// that check the tolerance at the scale they repair it at, as in memory.)
inline bool tolerance_square_is_finite(double tolerance) { return std::isfinite(4 * tolerance * tolerance); }

/// throws `Invalid_input` unless `tolerance_square_is_finite(tolerance)`.
inline void check_tolerance_square(double tolerance)
{
  if(tolerance_square_is_finite(tolerance)) return;
  char value[32];
  std::snprintf(value, sizeof value, "%g", tolerance);
  throw Invalid_input(std::string("tiled_reconstruct_topology: the tolerance is too large (") + value +
                      "): the square of twice its value overflows a double");
}

/// the largest absolute coordinate of a corner of the cube of `plan`.
inline double largest_coordinate_of_cube(const Tile_plan& plan)
{
  double largest = 0;
  for(std::size_t i = 0; i < 3; ++i)
    largest = std::max({largest, std::abs(plan.origin()[i]), std::abs(plan.origin()[i] + plan.side())});
  return largest;
}

/// `true` if the cube of `plan` reaches coordinates beyond 2^128 or stays below 2^-128 (all of
/// them, in absolute value). The plan, the halos, the depths and the taint of the tiles square
/// lengths at the input's scale (near 1e-270 the squared tolerance and the distances to the tiles
/// rounded to 0 and nothing was welded), where the pipeline in memory scales such a soup by a
/// power of two first (internal/coordinate_scale.h): such a soup is repaired as one tile, whose
/// weld and splits scale it as in memory. Every process of a team holds the plan and decides alike.
inline bool reaches_extreme_scale(const Tile_plan& plan)
{
  return moderate_scale_exponent(largest_coordinate_of_cube(plan)) != 0;
}

/// the reason given in the report when `reaches_extreme_scale()`.
inline std::string extreme_scale_reason(const Tile_plan& plan)
{
  const double largest = largest_coordinate_of_cube(plan);
  char value[32];
  std::snprintf(value, sizeof value, "%g", largest);
  return std::string("coordinates that reach ") + value +
         ", beyond 2^128 or below 2^-128 (the tiles work at the input's scale; the whole soup is scaled by a power of "
         "two, as in memory)";
}

/// the plan of the tiles, with the halo of the first runs: rank 0 plans and spills `source` into
/// `folder` (and counts the halo triangles into `report`), then sends the plan to the others.
///
/// The halo of the first runs: the taint of a region starts at its edge, where the stars are
/// cut, spreads by about one star in the first weld, and further only through decisions taken
/// near tainted points (the design page): four mean edges cover the jittered seams measured. The
/// check grows it where that is not enough. The mean edge length comes with the plan.
template <class TileTeam, class TriangleSource, class NamedParameters>
Tile_plan plan_and_spill(TileTeam& team, const TriangleSource& source, std::size_t number_of_tiles,
                         const std::string& folder, double tolerance, const NamedParameters& np,
                         Tiled_reconstruction_report& report)
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  Tile_plan plan;
  if(team.rank() == 0) {
    plan = plan_tiles(source, number_of_tiles, 0);
    // A soup at an extreme scale is repaired whole, and a tolerance too large for a soup at a
    // moderate scale is refused, by every process once it holds the plan: nothing is spilled.
    if(!reaches_extreme_scale(plan) && tolerance_square_is_finite(tolerance)) {
      const double fallback = 4 * tolerance + 4 * plan.mean_edge_length();
      plan = plan.with_halo(choose_parameter(get_parameter(np, internal_np::tile_halo), fallback > 0 ? fallback : 1.0));
      const Tile_files files = write_tile_files(source, plan, folder);
      for(std::size_t h : files.halo) report.halo_triangles += h;
    }
  }
  if(team.size() > 1) {
    // The plan, once the spill files are written.
    std::vector<char> bytes;
    if(team.rank() == 0) bytes = plan.to_bytes();
    team.broadcast(bytes);
    if(team.rank() != 0) plan = Tile_plan::from_bytes(bytes);
  }
  return plan;
}

/// how a run of a tile ended.
enum Tile_outcome : std::uint64_t { kept_clean, tainted_owned, degenerate_under_collapse, crowded };

/// this process's runs of a round: the tiles at positions `rank`, `rank + size`, ... of `to_do`,
/// each repaired from its spill file (then removed) with the halo `halo`. The owned triangles of
/// a clean run are written to the tile's part file in `folder`.
/// Returns four values a run: its position in `to_do`, its `Tile_outcome`, the size of its
/// region, its tainted owned triangles. A process stops at its first run that needs the whole
/// soup: `walk_round_outcomes()` stops there, or before.
template <class ConcurrencyTag, class TileTeam, class Progress>
std::vector<std::uint64_t> repair_round_share(TileTeam& team, const Tile_plan& plan, const std::vector<std::size_t>& to_do,
                                              const std::string& folder, double halo, const Tiled_repair_settings& settings,
                                              Tile_progress& where, const Progress& progress)
{
  std::vector<std::uint64_t> runs;
  std::vector<Tile_corners> region;
  where.runs_done = 0;
  where.runs = to_do.size() > team.rank() ? (to_do.size() - team.rank() + team.size() - 1) / team.size() : 0;
  for(std::size_t k = team.rank(); k < to_do.size(); k += team.size()) {
    const std::size_t tile = to_do[k];
    const std::string file = tile_file_name(folder, tile);
    region.clear();
    for(const Tile_triangle& t : read_tile_file(file)) region.push_back(t.corners);
    std::remove(file.c_str());
    Tile_run run = repair_tile_region<ConcurrencyTag>(region, plan, tile, halo, settings.tolerance, settings.max_rounds,
                                                      settings.do_split, settings.policy);
    const Tile_outcome outcome = run.degenerate_under_collapse ? degenerate_under_collapse
                                 : run.crowded                 ? crowded
                                 : run.tainted_owned == 0      ? kept_clean
                                                               : tainted_owned;
    runs.insert(runs.end(), {k, outcome, region.size(), run.tainted_owned});
    ++where.runs_done;
    if(outcome == kept_clean) where.triangles_done += plan.owned_triangles(tile);
    progress(where);
    if(outcome == kept_clean) write_part_file(part_file_name(folder, tile), run.owned);
    if(outcome == degenerate_under_collapse || outcome == crowded) break;
  }
  return runs;
}

/// the runs of a round (`repair_round_share()`'s values, of every process) walked in the order
/// of `to_do`, as one process runs them: counted into `report`; returns the tiles to repair
/// again, or sets `whole` (with `report.whole_soup_reason`) at the first run that needs the
/// whole soup.
inline std::vector<std::size_t> walk_round_outcomes(const std::vector<std::uint64_t>& runs, const std::vector<std::size_t>& to_do,
                                                    Tiled_reconstruction_report& report, bool& whole)
{
  constexpr std::uint64_t not_run = static_cast<std::uint64_t>(-1);
  std::vector<std::array<std::uint64_t, 3>> by_position(to_do.size(), {{not_run, 0, 0}});
  for(std::size_t r = 0; r + 3 < runs.size(); r += 4) by_position[runs[r]] = {{runs[r + 1], runs[r + 2], runs[r + 3]}};
  std::vector<std::size_t> tainted;
  for(std::size_t k = 0; k < to_do.size(); ++k) {
    const std::array<std::uint64_t, 3>& run = by_position[k];
    if(run[0] == not_run) throw std::logic_error("tiled_reconstruct_topology: a tile of the round was not repaired");
    report.largest_tile_triangles = std::max(report.largest_tile_triangles, std::size_t(run[1]));
    ++report.tile_runs;
    if(run[0] == degenerate_under_collapse) {
      whole = true;
      report.whole_soup_reason = "a degenerate triangle under Small_features::COLLAPSE (its flips are not tiled)";
      break;
    }
    if(run[0] == crowded) {
      whole = true;
      report.whole_soup_reason = "a crowd of points within the tolerance of each other (more than " +
                                 std::to_string(Tile_taint<CGAL::Epick>::crowd_budget) +
                                 " points read a point of a tile in a phase of its taint)";
      break;
    }
    if(run[0] == tainted_owned) {
      report.discarded_triangles += std::size_t(run[2]);
      tainted.push_back(to_do[k]);
    }
  }
  return tainted;
}

/// removes the spill files of the tiles of `plan` from `folder` (those that are there).
inline void remove_tile_files(const Tile_plan& plan, const std::string& folder)
{
  for(std::size_t tile = 0; tile < plan.number_of_tiles(); ++tile) std::remove(tile_file_name(folder, tile).c_str());
}

/// the soup repaired as one tile holding everything, deep enough that nothing is tainted (the
/// spill files left in `folder` removed first).
template <class ConcurrencyTag, class TriangleSource>
Soup_part repair_whole_soup(const TriangleSource& source, const Tile_plan& plan, const std::string& folder,
                            const Tiled_repair_settings& settings, Tiled_reconstruction_report& report)
{
  remove_tile_files(plan, folder);
  const Tile_plan one = plan_tiles(source, 1, 0);
  std::vector<Tile_corners> region;
  source.for_each([&](const Tile_corners& c, std::uint64_t) { region.push_back(c); });
  report.whole_soup = true;
  ++report.tile_runs;
  report.largest_tile_triangles = std::max(report.largest_tile_triangles, region.size());
  const double deep = 4 * (one.side() + settings.tolerance);
  return repair_tile_region<ConcurrencyTag>(region, one, 0, deep, settings.tolerance, settings.max_rounds, settings.do_split,
                                            settings.policy, true)
    .owned;
}

} // namespace internal

/// \ingroup PkgSoupTopologyTiling
/// \brief repairs the soup of `source` as `reconstruct_topology()` does (exact weld, then rounds of
/// welding and T-junction splitting), tile by tile: the same triangles on the same points,
/// written to `points` and `triangles` in the canonical order of `canonical_triangle_soup()`.
///
/// The soup is planned into `number_of_tiles` tiles (`plan_tiles()`, level 7) and spilled into
/// `folder` (`write_tile_files()`, one file per tile, removed as each tile is done). Every tile
/// is repaired on its region (its cells grown by the halo) with the pipeline's own steps while the
/// taint of its points is followed phase by phase (`doc/Soup_topology/Tiled_repair_design.md`);
/// the triangles the tile owns (by the anchor of their output corners) are kept when none of their
/// corners is tainted. Otherwise the tile is repaired again with the halo doubled, until it is
/// clean: the output never holds a decision the region could not certify. The tiles to repair
/// again are spilled together, in one stream of the source per round of doubling.
/// A region that grows past the bounding cube is the whole soup, which taints nothing. A soup
/// whose coordinates reach beyond 2^128 or stay below 2^-128, which the tiles would decide at the
/// input's scale, is repaired as one tile, scaled as in memory (the report says so).
///
/// Memory: one tile's region and its repair. The owned triangles of each tile done go to a part
/// file in `folder` on the points they use (12 bytes a triangle, 24 a point on disk), read back
/// by the merge at the end (the points of all parts, then the triangles part by part).
///
/// \tparam ConcurrencyTag passed on to the steps of each tile's repair (the tiles run one after
///         the other)
/// \tparam TriangleSource as for `plan_tiles()`: `Soup_triangle_source`, `Binary_STL_source`, ...
/// \param source the soup, streamed three times (the plan, the spill) and once more per round of
///        tiles repaired again
/// \param number_of_tiles at least 1
/// \param folder an existing folder for the spill files
/// \param points the output points, sorted
/// \param triangles the output triangles, sorted
/// \param np named parameters:
///   - `snapping_tolerance`: the absolute tolerance (required);
///   - `maximum_number_of_rounds` (8) and `do_split_t_junctions` (`true`), as for
///     `reconstruct_topology()`;
///   - `small_features` (`Small_features::COLLAPSE`), as for `reconstruct_topology()`; a soup
///     with a degenerate triangle under `COLLAPSE` is repaired as one tile (the report says so);
///   - `tile_halo`: the halo of the first runs (default: four times the tolerance plus four times
///     the mean edge length of the soup); it changes the time, never the result;
///   - `tile_progress`: a callable taking a `const Tile_progress&`, called after each run of a
///     tile (default: none).
/// \throws Invalid_input for a missing or bad tolerance or a bad argument; the exceptions of the
///         source and of the spill files
template <class ConcurrencyTag = CGAL::Sequential_tag, class TriangleSource,
          class NamedParameters = CGAL::parameters::Default_named_parameters>
Tiled_reconstruction_report tiled_reconstruct_topology(const TriangleSource& source, std::size_t number_of_tiles,
                                                       const std::string& folder,
                                                       std::vector<CGAL::Epick::Point_3>& points,
                                                       std::vector<std::array<std::uint32_t, 3>>& triangles,
                                                       const NamedParameters& np = CGAL::parameters::default_values())
{
  Single_process_team alone;
  return tiled_reconstruct_topology<ConcurrencyTag>(alone, source, number_of_tiles, folder, points, triangles, np);
}

/// \ingroup PkgSoupTopologyTiling
/// \brief `tiled_reconstruct_topology()` by a team of processes that share the tiles (e.g.
/// `Mpi_tile_team`): every process of `team` calls it with the same arguments, and the processes
/// share one `folder` (a shared file system when they run on several machines).
///
/// Rank 0 plans and spills (it alone reads `source`) and sends the plan to the others. In each
/// round, process `r` repairs the tiles at positions `r`, `r + size`, ... of the round's list, and
/// writes the owned triangles it keeps to a part file in `folder`; the outcomes of the runs are
/// gathered by every process, which walks them in the list's order as a single process does: the
/// same tiles to repeat, the same report, the same output. Rank 0 spills the tiles to repeat, then
/// merges the part files. The output and the report are rank 0's; the other processes return
/// an empty soup and a report with the counts of the tiles only.
///
/// An exception on one process leaves the others waiting: the caller ends the team (e.g.
/// `MPI_Abort()`).
///
/// \tparam TileTeam a model of the team: `rank()` and `size()`; `broadcast(std::vector<char>&)`
///         (rank 0's bytes to every process); `all_gather(const std::vector<std::uint64_t>&)`
///         (every process's values, rank 0's first, then rank 1's, ...)
template <class ConcurrencyTag = CGAL::Sequential_tag, class TileTeam, class TriangleSource, class NamedParameters>
Tiled_reconstruction_report tiled_reconstruct_topology(TileTeam& team, const TriangleSource& source,
                                                       std::size_t number_of_tiles, const std::string& folder,
                                                       std::vector<CGAL::Epick::Point_3>& points,
                                                       std::vector<std::array<std::uint32_t, 3>>& triangles,
                                                       const NamedParameters& np)
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  const internal::Tiled_repair_settings settings = internal::tiled_repair_settings(np);
  if(number_of_tiles == 0) throw Invalid_input("plan_tiles: at least one tile is needed");
  const bool root = team.rank() == 0, alone = team.size() == 1;
  auto progress =
    choose_parameter(get_parameter(np, internal_np::tile_progress), [](const Tile_progress&) {});

  Tiled_reconstruction_report report;
  report.tolerance = settings.tolerance;
  const Tile_plan plan = internal::plan_and_spill(team, source, number_of_tiles, folder, settings.tolerance, np, report);
  // A soup at an extreme scale is repaired as one tile (`internal::reaches_extreme_scale()`).
  bool whole = internal::reaches_extreme_scale(plan);
  if(whole) report.whole_soup_reason = internal::extreme_scale_reason(plan);
  else internal::check_tolerance_square(settings.tolerance); // (on every process; nothing was spilled then)
  const double halo = plan.halo();
  report.first_halo = report.largest_halo = halo;
  report.input_triangles = plan.number_of_triangles();
  report.tiles = plan.number_of_tiles();

  // Rounds: every tile to do is repaired from its spill file; the tiles with a tainted owned
  // triangle are spilled again, together in one stream of the source, with the halo doubled.
  std::vector<std::size_t> to_do(plan.number_of_tiles());
  for(std::size_t tile = 0; tile < to_do.size(); ++tile) to_do[tile] = tile;
  // Past this halo every point is deeper than twice the tolerance plus the cube's diagonal.
  const double enough = 4 * (plan.side() + settings.tolerance) + halo;
  Tile_progress where;
  for(std::size_t k = team.rank(); k < to_do.size(); k += team.size()) where.triangles += plan.owned_triangles(to_do[k]);
  for(double h = halo; !to_do.empty() && !whole; h *= 2) {
    report.largest_halo = std::max(report.largest_halo, h);
    std::vector<std::uint64_t> runs =
      internal::repair_round_share<ConcurrencyTag>(team, plan, to_do, folder, h, settings, where, progress);
    if(!alone) runs = team.all_gather(runs);
    std::vector<std::size_t> tainted = internal::walk_round_outcomes(runs, to_do, report, whole);
    if(whole || tainted.empty()) break;
    if(h == halo) report.repeated_tiles = tainted.size();
    if(h > enough) throw std::logic_error("tiled_reconstruct_topology: a region holding the whole soup is tainted");
    if(root) {
      std::vector<char> wanted(plan.number_of_tiles(), 0);
      for(std::size_t tile : tainted) wanted[tile] = 1;
      write_tile_files(source, plan.with_halo(2 * h), folder, &wanted);
    }
    if(!alone) {
      std::vector<char> spilled; // the spill files of the next round are written
      team.broadcast(spilled);
    }
    to_do.swap(tainted);
    ++where.round;
  }
  points.clear();
  triangles.clear();
  if(!root) return report;
  // Every process's part files are written (with a team: the gather of the last round); rank 0
  // merges them, reading them back, or, for the whole soup, removes those of the runs before.
  std::vector<std::string> part_files;
  for(std::size_t tile = 0; tile < plan.number_of_tiles(); ++tile)
    part_files.push_back(internal::part_file_name(folder, tile));
  if(whole) {
    for(const std::string& part : part_files) std::remove(part.c_str());
    std::vector<internal::Soup_part> one(1);
    one[0] = internal::repair_whole_soup<ConcurrencyTag>(source, plan, folder, settings, report);
    internal::merge_in_canonical_order(one, points, triangles);
  } else {
    internal::Part_files parts(std::move(part_files));
    internal::merge_in_canonical_order(parts, points, triangles);
  }
  report.output_points = points.size();
  report.output_triangles = triangles.size();
  return report;
}

} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_TILED_RECONSTRUCT_TOPOLOGY_H
