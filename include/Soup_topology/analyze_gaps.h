// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The gap analysis: how far apart the copies of the seams of a soup are, how small its own
// features are, and which snapping tolerance closes the first without collapsing the second.

#ifndef SOUP_TOPOLOGY_ANALYZE_GAPS_H
#define SOUP_TOPOLOGY_ANALYZE_GAPS_H

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/index_triangles.h>
#include <Soup_topology/parameters.h>
#include <Soup_topology/internal/coordinate_scale.h>
#include <Soup_topology/internal/gap_distances.h>
#include <Soup_topology/internal/gap_suggestion.h>
#include <Soup_topology/internal/soup_checks.h>
#include <Soup_topology/internal/tolerance.h>

#include <CGAL/Named_function_parameters.h>
#include <CGAL/tags.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

namespace Soup_topology {

/// \ingroup PkgSoupTopologyGaps
/// \brief a bin of a log-scaled histogram: `count` values in [`lower`, `upper`). The bins are
/// `internal::gap_histogram_bins_per_decade` (4) per decade, from the bin of the smallest
/// positive value to that of the largest, empty bins included.
struct Gap_histogram_bin
{
  double lower = 0;       ///< smallest value of the bin
  double upper = 0;       ///< bound above the bin's values
  std::size_t count = 0;  ///< number of values in the bin
};

/// \ingroup PkgSoupTopologyGaps
/// \brief the smallest, median and largest of a set of sizes.
struct Size_distribution
{
  std::size_t count = 0;  ///< number of sizes
  double minimum = 0;     ///< smallest size (0 if `count` is 0)
  double median = 0;      ///< the size of rank `count / 2` in increasing order
  double maximum = 0;     ///< largest size
};

/// \ingroup PkgSoupTopologyGaps
/// \brief what the analysis concludes.
enum class Gap_verdict
{
  CLOSED,            ///< no border edge after the exact weld: the tolerance 0 is enough
  NOTHING_TO_CLOSE,  ///< every gap is wider than the feature bound: the borders are real, tolerance 0
  SUGGESTED,         ///< a tolerance closes the gap cluster with a margin on both sides
  OVERLAP            ///< the gaps and the features overlap: no tolerance is suggested
};

/// \ingroup PkgSoupTopologyGaps
/// \brief the result of `analyze_gaps()`. All lengths are in the units of the points.
///
/// A *gap* is measured for every border vertex (a vertex of a border edge, after the exact weld):
/// the distance to the nearest border vertex or border edge that shares no triangle with it,
/// within `search_radius`. The *border features* are the sizes the weld and the T-junction split
/// decide on: the length of every border edge, and the height of a triangle from a border vertex
/// onto a border edge of the same triangle. Following Hoffmann, Hopcroft and Karasick's minimum
/// feature separation (edges longer than 3 epsilon, no vertex closer than 3 epsilon to an edge),
/// the tolerance must stay below `feature_bound`, a third of the smallest border feature.
struct Gap_analysis
{
  /// \name The soup after the exact weld
  /// @{
  std::size_t vertices = 0;                   ///< distinct points used by the triangles
  std::size_t triangles = 0;                  ///< triangles left by the exact weld
  std::size_t border_edges = 0;               ///< edges of one triangle only
  std::size_t border_vertices = 0;            ///< vertices of border edges (one gap each)
  std::size_t degenerate_triangles = 0;       ///< triangles with collinear corners (not features)
  double bounding_box_diagonal = 0;           ///< of the points used
  /// @}

  /// \name The gaps
  /// @{
  double search_radius = 0;                   ///< gaps larger than this are not measured
  std::vector<double> gaps;                   ///< the measured gaps, in increasing order
  std::size_t gaps_beyond_search_radius = 0;  ///< border vertices with no border element within `search_radius`
  std::size_t zero_gaps = 0;                  ///< gaps of length 0 (a vertex on another border edge)
  std::vector<Gap_histogram_bin> gap_histogram; ///< the positive gaps, log-scaled
  /// @}

  /// \name The features
  /// @{
  Size_distribution shortest_edges;           ///< the shortest edge of every non-degenerate triangle
  Size_distribution smallest_heights;         ///< the smallest height of every non-degenerate triangle
  std::vector<Gap_histogram_bin> feature_histogram; ///< min(shortest edge, smallest height) per non-degenerate triangle
  Size_distribution border_features;          ///< border edge lengths and heights onto border edges
  double feature_bound = 0;                   ///< a third of `border_features.minimum` (infinite without border feature)
  /// @}

  /// \name The suggestion
  /// @{
  Gap_verdict verdict = Gap_verdict::CLOSED;  ///< what the analysis concludes
  double suggested_tolerance = 0;             ///< the tolerance (0 unless `SUGGESTED`; `NaN` for `OVERLAP`)
  std::size_t closed_gaps = 0;                ///< gaps at most the tolerance
  double largest_closed_gap = 0;              ///< the largest of them
  double smallest_open_gap = std::numeric_limits<double>::infinity(); ///< the smallest gap kept open (infinite: none measured)
  double closing_margin = 0;                  ///< tolerance / largest closed gap (infinite if that gap is 0)
  double keeping_margin = 0;                  ///< min(smallest open gap, feature bound) / tolerance
  std::string reasoning;                      ///< the conclusion in words, with the numbers
  /// @}

  /// `true` if a tolerance is known: `CLOSED`, `NOTHING_TO_CLOSE` (0) or `SUGGESTED`.
  bool has_suggestion() const { return verdict != Gap_verdict::OVERLAP; }
};

/// \ingroup PkgSoupTopologyGaps
/// \brief the name of a verdict, as the tool prints it (`"closed"`, `"nothing_to_close"`,
/// `"suggested"`, `"overlap"`).
/// \param verdict the verdict
inline const char* verdict_name(Gap_verdict verdict)
{
  switch(verdict) {
    case Gap_verdict::CLOSED: return "closed";
    case Gap_verdict::NOTHING_TO_CLOSE: return "nothing_to_close";
    case Gap_verdict::SUGGESTED: return "suggested";
    case Gap_verdict::OVERLAP: return "overlap";
  }
  return "";
}

namespace internal {

inline Size_distribution size_distribution(std::vector<double>& sizes)
{
  Size_distribution d;
  d.count = sizes.size();
  if(sizes.empty()) return d;
  // Linear: a selection for the median, no sort (the sizes are left in an unspecified order).
  const auto middle = sizes.begin() + static_cast<std::ptrdiff_t>(sizes.size() / 2);
  std::nth_element(sizes.begin(), middle, sizes.end());
  d.median = *middle;
  d.minimum = *std::min_element(sizes.begin(), middle + 1);
  d.maximum = *std::max_element(middle, sizes.end());
  return d;
}

inline std::string format_length(double x)
{
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.3g", x);
  return buffer;
}

/// sorts sizes in increasing order, as `std::sort` does. Large vectors of sizes that are all
/// non-negative (sign bit clear, no NaN) are sorted by their bit patterns, which then compare as
/// the values do, with a least-significant-digit radix sort of 16 bits a pass.
template <class ConcurrencyTag>
void sort_sizes(std::vector<double>& sizes)
{
  if(sizes.size() < (std::size_t(1) << 16) ||
     !std::all_of(sizes.begin(), sizes.end(), [](double x) { return !std::signbit(x) && !std::isnan(x); })) {
    std::sort(sizes.begin(), sizes.end());
    return;
  }
  Uninitialized_vector<std::uint64_t> keys(sizes.size()), buffer(sizes.size()); // written whole before they are read
  for_each_index<ConcurrencyTag>(sizes.size(), [&](std::size_t i) { std::memcpy(&keys[i], &sizes[i], sizeof(double)); });
  for(unsigned shift = 0; shift < 64; shift += 16) {
    std::vector<std::size_t> count((std::size_t(1) << 16) + 1, 0);
    for(std::uint64_t k : keys) ++count[((k >> shift) & 0xffff) + 1];
    if(count[1 + ((keys[0] >> shift) & 0xffff)] == keys.size()) continue; // one digit value: nothing moves
    for(std::size_t d = 1; d < count.size(); ++d) count[d] += count[d - 1];
    for(std::uint64_t k : keys) buffer[count[(k >> shift) & 0xffff]++] = k;
    keys.swap(buffer);
  }
  for_each_index<ConcurrencyTag>(sizes.size(), [&](std::size_t i) { std::memcpy(&sizes[i], &keys[i], sizeof(double)); });
}

/// fills the suggestion of `a` from its gaps and its feature bound.
inline void suggest_tolerance(Gap_analysis& a)
{
  const std::size_t measured = a.gaps.size();
  const std::size_t all_gaps = measured + a.gaps_beyond_search_radius;
  if(a.border_edges == 0) {
    a.verdict = Gap_verdict::CLOSED;
    a.reasoning = "no border edge after the exact weld: nothing to close, tolerance 0";
    return;
  }
  // Without a border feature (every border triangle degenerate) the gaps measured, up to the
  // search radius, are all that is known.
  const double bound = std::min(a.feature_bound, a.search_radius);
  const std::size_t below_bound =
    static_cast<std::size_t>(std::lower_bound(a.gaps.begin(), a.gaps.end(), bound) - a.gaps.begin());
  if(below_bound == 0) {
    a.verdict = Gap_verdict::NOTHING_TO_CLOSE;
    a.smallest_open_gap = measured ? a.gaps.front() : std::numeric_limits<double>::infinity();
    a.reasoning = "every gap (" + std::to_string(all_gaps) + ") is at least the feature bound " + format_length(bound) +
                  " (a third of the smallest border feature " + format_length(a.border_features.minimum) +
                  "): the borders are real, tolerance 0";
    return;
  }
  const std::size_t closed = closed_gap_count(a.gaps, bound);
  if(closed == 0) {
    a.verdict = Gap_verdict::OVERLAP;
    a.suggested_tolerance = std::numeric_limits<double>::quiet_NaN();
    a.reasoning = std::to_string(below_bound) + " gaps lie below the feature bound " + format_length(bound) +
                  " (a third of the smallest border feature " + format_length(a.border_features.minimum) +
                  "), but no two consecutive ones (nor the largest and the bound) are a factor " +
                  format_length(gap_separation_factor) +
                  " apart: the gaps and the features overlap, no tolerance is suggested";
    return;
  }
  a.verdict = Gap_verdict::SUGGESTED;
  a.closed_gaps = closed;
  a.largest_closed_gap = a.gaps[closed - 1];
  a.smallest_open_gap = closed < measured ? a.gaps[closed] : std::numeric_limits<double>::infinity();
  const double high = std::min(a.smallest_open_gap, bound);
  a.suggested_tolerance = tolerance_between(a.largest_closed_gap, high);
  a.closing_margin = a.largest_closed_gap > 0 ? a.suggested_tolerance / a.largest_closed_gap
                                              : std::numeric_limits<double>::infinity();
  a.keeping_margin = high / a.suggested_tolerance;
  a.reasoning = "closes " + std::to_string(closed) + " of " + std::to_string(all_gaps) + " gaps (the largest " +
                format_length(a.largest_closed_gap) + ", margin " + format_length(a.closing_margin) +
                "), keeps open " + std::to_string(all_gaps - closed) + " (the smallest " +
                (closed < measured ? format_length(a.smallest_open_gap) : std::string("beyond ") + format_length(a.search_radius)) +
                ") and stays below the feature bound " + format_length(bound) + " (a third of the smallest border feature " +
                format_length(a.border_features.minimum) + "), margin " + format_length(a.keeping_margin);
}

} // namespace internal

namespace internal {

/// the soup of `points` and `triangles` exactly welded into `pts` and `tris`: validated, equal
/// points merged, collapsed triangles removed, and only the points some triangle uses kept. If
/// `welded_index` is not null, it receives the index in `pts` of every input point (-1 for a
/// point no kept triangle uses).
template <class Point, class PointRange, class TriangleRange, class PointMap>
void exactly_welded_copy(const PointRange& points, const TriangleRange& triangles, const PointMap& pm,
                         std::vector<Point>& pts, std::vector<std::array<std::size_t, 3>>& tris,
                         std::vector<std::size_t>* welded_index = nullptr)
{
  using FT = typename CGAL::Kernel_traits<Point>::Kernel::FT;
  tris.reserve(triangles.size());
  std::size_t face_id = 0;
  for(const auto& f : triangles) {
    if(face_size(f) != 3)
      throw Invalid_input("face " + std::to_string(face_id) + " has " + std::to_string(face_size(f)) +
                          " vertices; a triangle soup needs exactly 3");
    tris.push_back({corner(f, 0, face_id), corner(f, 1, face_id), corner(f, 2, face_id)});
    ++face_id;
  }
  check_triangle_soup(tris, points.size());
  check_finite_points(points, pm);
  pts.reserve(points.size());
  for(const auto& e : points) {
    const auto& p = get(pm, e);
    if constexpr(std::is_same<std::decay_t<decltype(p)>, Point>::value)
      pts.push_back(p);
    else
      pts.push_back(Point(FT(CGAL::to_double(p.x())), FT(CGAL::to_double(p.y())), FT(CGAL::to_double(p.z()))));
  }
  const std::vector<std::size_t> merged_index = merge_duplicate_points_and_map(pts, tris);
  remove_collapsed_triangles(tris);
  std::vector<std::size_t> index(pts.size(), static_cast<std::size_t>(-1));
  std::size_t kept = 0;
  for(const auto& t : tris)
    for(std::size_t v : t) index[v] = 0;
  for(std::size_t i = 0; i < pts.size(); ++i)
    if(index[i] == 0) { index[i] = kept; pts[kept++] = pts[i]; }
  pts.resize(kept);
  for(auto& t : tris)
    for(std::size_t& v : t) v = index[v];
  if(welded_index != nullptr) {
    welded_index->resize(merged_index.size());
    for(std::size_t i = 0; i < merged_index.size(); ++i) (*welded_index)[i] = index[merged_index[i]];
  }
}

/// appends to `border_features` the features of triangle `(p, q, r)` (index `t`) that involve its
/// border edges: each border edge's length, and the height of the third corner over it when that
/// corner is a border vertex too.
template <class Point>
void add_border_features(const Point& p, const Point& q, const Point& r, Adjacency_tables::size_type t,
                         const Adjacency_tables& tables, std::vector<double>& border_features)
{
  const double corner[3][3] = {
    {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())},
    {CGAL::to_double(q.x()), CGAL::to_double(q.y()), CGAL::to_double(q.z())},
    {CGAL::to_double(r.x()), CGAL::to_double(r.y()), CGAL::to_double(r.z())}};
  const double u[3] = {corner[1][0] - corner[0][0], corner[1][1] - corner[0][1], corner[1][2] - corner[0][2]};
  const double v[3] = {corner[2][0] - corner[0][0], corner[2][1] - corner[0][1], corner[2][2] - corner[0][2]};
  const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  const double twice_area = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  std::array<bool, 3> on_border{false, false, false};
  for(int i = 0; i < 3; ++i)
    if(tables.is_border_edge(t, i)) on_border[static_cast<std::size_t>(i)] = on_border[static_cast<std::size_t>((i + 1) % 3)] = true;
  for(int i = 0; i < 3; ++i) {
    if(!tables.is_border_edge(t, i)) continue;
    const double* a0 = corner[i];
    const double* b0 = corner[(i + 1) % 3];
    const double d[3] = {b0[0] - a0[0], b0[1] - a0[1], b0[2] - a0[2]};
    const double length = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    border_features.push_back(length);
    // The third corner is a border vertex: its distance to this border edge is a feature.
    if(on_border[static_cast<std::size_t>((i + 2) % 3)] && length > 0) border_features.push_back(twice_area / length);
  }
}

/// the feature sizes of the soup into `a`: shortest edges and smallest heights of the
/// non-degenerate triangles, the border features, and the bound a tolerance must stay below.
/// The sizes measured on `pts` are multiplied by `unscale` (see `scale_for_analysis()`).
/// The triangles are measured by blocks (in parallel with `CGAL::Parallel_tag`), each into buffers
/// of its own, put together in the order of the blocks: the sizes come in the order of the
/// triangles, as measured one by one.
template <class ConcurrencyTag, class Geom_traits, class TriangleRange>
void measure_feature_sizes(const std::vector<typename Geom_traits::Point_3>& pts, const TriangleRange& tris,
                           const Adjacency_tables& tables, const Geom_traits& gt, Gap_analysis& a,
                           double unscale = 1)
{
  using Point = typename Geom_traits::Point_3;
  struct Sizes
  {
    std::vector<double> shortest, heights, smallest, border_features;
    std::size_t degenerate = 0;
  };
  using Tag = Geometric_concurrency<ConcurrencyTag, Geom_traits>;
  std::vector<Sizes> blocks(number_of_blocks(tris.size()));
  for_each_block<Tag>(tris.size(), default_block_size, [&](std::size_t g, std::size_t begin, std::size_t end) {
    typename Geom_traits::Collinear_3 collinear = gt.collinear_3_object();
    Sizes& out = blocks[g];
    out.shortest.reserve(end - begin);
    out.heights.reserve(end - begin);
    out.smallest.reserve(end - begin);
    for(std::size_t t = begin; t < end; ++t) {
      const Point& p = pts[static_cast<std::size_t>(tris[t][0])];
      const Point& q = pts[static_cast<std::size_t>(tris[t][1])];
      const Point& r = pts[static_cast<std::size_t>(tris[t][2])];
      if(collinear(p, q, r)) { ++out.degenerate; continue; }
      const Triangle_feature_sizes s = triangle_feature_sizes(p, q, r);
      out.shortest.push_back(s.shortest_edge);
      out.heights.push_back(s.smallest_height);
      out.smallest.push_back(std::min(s.shortest_edge, s.smallest_height));
      const auto tt = static_cast<Adjacency_tables::size_type>(t);
      if(tables.is_border_edge(tt, 0) || tables.is_border_edge(tt, 1) || tables.is_border_edge(tt, 2))
        add_border_features(p, q, r, tt, tables, out.border_features);
    }
  });
  std::vector<double> shortest, heights, smallest, border_features;
  const auto gather = [&](std::vector<double> Sizes::*member, std::vector<double>& to) {
    std::vector<std::vector<double>> parts(blocks.size());
    for(std::size_t g = 0; g < blocks.size(); ++g) parts[g].swap(blocks[g].*member);
    concatenate_in_block_order(parts, to);
  };
  gather(&Sizes::shortest, shortest);
  gather(&Sizes::heights, heights);
  gather(&Sizes::smallest, smallest);
  gather(&Sizes::border_features, border_features);
  if(unscale != 1)
    for(std::vector<double>* sizes : {&shortest, &heights, &smallest, &border_features})
      for(double& x : *sizes) x *= unscale;
  for(const Sizes& b : blocks) a.degenerate_triangles += b.degenerate;
  a.shortest_edges = size_distribution(shortest);
  a.smallest_heights = size_distribution(heights);
  sort_sizes<ConcurrencyTag>(smallest);
  a.feature_histogram = log_histogram<Gap_histogram_bin>(smallest);
  a.border_features = size_distribution(border_features);
  a.feature_bound = border_features.empty() ? std::numeric_limits<double>::infinity() : a.border_features.minimum / 3;
}

/// the gaps of the border vertices `border` into `a`, measured up to the median border edge
/// length (at least the smallest border feature, so that every gap below the bound and the first
/// one above it are measured when they exist); returns the nearest element of every border vertex.
/// The lengths measured on `pts` are multiplied by `unscale` (see `scale_for_analysis()`): `a`
/// and the distances returned are at the scale of the soup.
template <class ConcurrencyTag, class Geom_traits, class TriangleRange>
Nearest_border_elements measure_gaps(const std::vector<typename Geom_traits::Point_3>& pts, const TriangleRange& tris,
                                     const Adjacency_tables& tables, const std::vector<std::size_t>& border,
                                     const Geom_traits& gt, Gap_analysis& a, double unscale = 1)
{
  using Tag = Geometric_concurrency<ConcurrencyTag, Geom_traits>;
  std::vector<std::vector<double>> lengths(number_of_blocks(tris.size()));
  for_each_block<Tag>(tris.size(), default_block_size, [&](std::size_t g, std::size_t begin, std::size_t end) {
    typename Geom_traits::Compute_squared_distance_3 squared_distance = gt.compute_squared_distance_3_object();
    for(std::size_t t = begin; t < end; ++t)
      for(int i = 0; i < 3; ++i)
        if(tables.is_border_edge(static_cast<Adjacency_tables::size_type>(t), i))
          lengths[g].push_back(std::sqrt(CGAL::to_double(squared_distance(
            pts[static_cast<std::size_t>(tris[t][static_cast<std::size_t>(i)])],
            pts[static_cast<std::size_t>(tris[t][static_cast<std::size_t>((i + 1) % 3)])]))));
  });
  std::vector<double> border_lengths;
  concatenate_in_block_order(lengths, border_lengths);
  if(unscale != 1)
    for(double& x : border_lengths) x *= unscale;
  std::nth_element(border_lengths.begin(), border_lengths.begin() + static_cast<std::ptrdiff_t>(border_lengths.size() / 2),
                   border_lengths.end());
  a.search_radius = border_lengths[border_lengths.size() / 2];
  if(a.border_features.count > 0) a.search_radius = std::max(a.search_radius, a.border_features.minimum);
  Nearest_border_elements nearest =
    nearest_border_elements<ConcurrencyTag>(pts, tables, border, a.search_radius / unscale, gt);
  if(unscale != 1)
    for(Nearest_border_element& e : nearest) e.distance *= unscale;
  a.gaps.reserve(a.gaps.size() + nearest.size());
  for(const Nearest_border_element& e : nearest) {
    if(std::isfinite(e.distance)) a.gaps.push_back(e.distance);
    else ++a.gaps_beyond_search_radius;
  }
  sort_sizes<ConcurrencyTag>(a.gaps);
  a.zero_gaps = static_cast<std::size_t>(std::upper_bound(a.gaps.begin(), a.gaps.end(), 0.0) - a.gaps.begin());
  a.gap_histogram = log_histogram<Gap_histogram_bin>(a.gaps);
  return nearest;
}

/// the diagonal of the bounding box of the points of `pts` that a triangle of `tris` uses.
template <class Point, class TriangleRange>
double used_points_diagonal(const std::vector<Point>& pts, const TriangleRange& tris, std::size_t& used_points)
{
  std::vector<char> used(pts.size(), 0);
  for(std::size_t t = 0; t < tris.size(); ++t)
    for(std::size_t j = 0; j < 3; ++j) used[static_cast<std::size_t>(tris[t][j])] = 1;
  used_points = static_cast<std::size_t>(std::count(used.begin(), used.end(), char(1)));
  if(used_points == pts.size()) return bounding_box_diagonal(pts, CGAL::Identity_property_map<Point>());
  std::vector<Point> kept;
  kept.reserve(used_points);
  for(std::size_t i = 0; i < pts.size(); ++i)
    if(used[i]) kept.push_back(pts[i]);
  return bounding_box_diagonal(kept, CGAL::Identity_property_map<Point>());
}

/// the factor by which the lengths measured on `scaled` give those of `pts`: 1 when the soup is
/// measured as it is (`scaled` left empty), else 2^-e for the e of `moderate_scale_exponent()`
/// of the points a triangle of `tris` uses (`used_points` of the points of `pts`), `scaled` then
/// holding every point of `pts` times 2^e. A soup that the scaling would round (double
/// coordinates that span more than the range of the exponents) is measured as it is.
template <class Point, class TriangleRange>
double scale_for_analysis(const std::vector<Point>& pts, const TriangleRange& tris, std::size_t used_points,
                          std::vector<Point>& scaled)
{
  const auto for_each_used_point = [&](const auto& f) {
    if(used_points == pts.size())
      for(const Point& p : pts) f(p);
    else
      for(const auto& t : tris)
        for(std::size_t j = 0; j < 3; ++j) f(pts[static_cast<std::size_t>(t[j])]);
  };
  double largest = 0;
  for_each_used_point([&largest](const Point& p) { largest = std::max(largest, largest_coordinate(p)); });
  const int e = moderate_scale_exponent(largest);
  if(e == 0) return 1;
  bool exact = true;
  for_each_used_point([&](const Point& p) { exact = exact && scales_exactly(p, e); });
  if(!exact) return 1;
  scaled.reserve(pts.size());
  for(const Point& p : pts) scaled.push_back(scaled_point(p, e));
  return std::ldexp(1.0, -e);
}

/// `analyze_gaps()` of a soup that is exactly welded already, as `IO::read_triangle_soup()`,
/// `index_triangles()` and the exact weld of `reconstruct_topology()` leave it: no two points of
/// `pts` are equal and every triangle of `tris` (3 indices into `pts`) has three distinct
/// corners. Trusted, not checked; points no triangle uses are allowed and ignored. The soup is
/// neither copied nor welded again: the answer is that of `analyze_gaps()` on the same soup.
///
/// Coordinates beyond 2^128 or below 2^-128 are measured on a copy scaled by a power of two (see
/// `moderate_scale_exponent()`), the lengths scaled back: the answer is then that of the soup
/// at a moderate scale, scaled.
template <class ConcurrencyTag = CGAL::Sequential_tag, class Geom_traits, class TriangleRange>
Gap_analysis analyze_exactly_welded_gaps(const std::vector<typename Geom_traits::Point_3>& pts,
                                         const TriangleRange& tris, const Geom_traits& gt)
{
  const Adjacency_tables tables(tris, pts.size());
  Gap_analysis a;
  a.triangles = tris.size();
  a.border_edges = tables.number_of_border_edges();
  a.bounding_box_diagonal = used_points_diagonal(pts, tris, a.vertices);
  const std::vector<std::size_t> border = border_vertices(tables);
  a.border_vertices = border.size();
  std::vector<typename Geom_traits::Point_3> scaled;
  const double unscale = scale_for_analysis(pts, tris, a.vertices, scaled);
  const auto& measured = unscale == 1 ? pts : scaled;
  measure_feature_sizes<ConcurrencyTag>(measured, tris, tables, gt, a, unscale);
  if(!border.empty()) measure_gaps<ConcurrencyTag>(measured, tris, tables, border, gt, a, unscale);
  suggest_tolerance(a);
  return a;
}

} // namespace internal

/// \ingroup PkgSoupTopologyGaps
/// \brief measures the gaps between the borders of a triangle soup and the soup's own feature
/// sizes, and suggests the snapping tolerance that closes the gaps without collapsing features.
///
/// The soup is taken as given (any indexing): the function merges exactly equal points on its
/// own copy and drops the triangles this collapses, as `reconstruct_topology()` does first, so the
/// gaps are those the tolerance of `reconstruct_topology()` acts on. `points` and `triangles` are
/// not changed.
///
/// **The rule.** With the gaps in increasing order g_1 <= ... <= g_n and the feature bound
/// `b` (see `Gap_analysis`), the suggested tolerance closes the gaps g_1..g_k for the largest k
/// such that g_k < b and min(g_{k+1}, b) >= 2 g_k; it is the geometric mean of g_k and
/// min(g_{k+1}, b) (half of the latter when g_k = 0), so a factor of at least sqrt(2) separates it
/// from the largest gap it closes and from the smallest one it keeps open or the bound. A gap at least
/// `b` is never closed: a crack wider than three times the smallest border feature stays open.
/// No border: `CLOSED`; no gap below `b`: `NOTHING_TO_CLOSE`; gaps below `b` but no such k:
/// `OVERLAP` and no suggestion. The gaps and the features do not depend on the order of the
/// points or the triangles, so neither does the suggestion.
///
/// **Exactness.** The candidates are found by exact radius queries of an `Octree` over the border
/// vertices; the distances are then evaluated in `double` (from the kernel's squared distance).
/// A decision of the weld at the suggested tolerance could differ from the analysis only for a gap
/// within a rounding error of the tolerance, and the tolerance is a factor sqrt(2) away from every gap.
///
/// **Threads.** With `CGAL::Parallel_tag` the searches of the nearest border elements and the
/// feature sizes run on TBB's threads (coordinates stored as `double`; with exact number types,
/// which share cached state between points, the measures are sequential); the result is the
/// same, to the bit, as with `CGAL::Sequential_tag`, on any number of threads.
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` (default), `CGAL::Parallel_tag` (needs TBB) or
///         `CGAL::Parallel_if_available_tag`
/// \tparam PointRange a random-access range of points (read through `point_map`)
/// \tparam TriangleRange a range of triangles (3 indices each)
/// \param points the points of the soup
/// \param triangles the triangles of the soup
/// \param np optional named parameters among the ones listed below
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{point_map} \cgalParamDescription{the point of an element of `points`}
///     \cgalParamType{a model of `ReadablePropertyMap` whose value is a point of a CGAL kernel}
///     \cgalParamDefault{`CGAL::Identity_property_map`} \cgalParamNEnd
///   \cgalParamNBegin{geom_traits} \cgalParamDescription{the kernel of the octree queries and
///     the distances} \cgalParamType{a CGAL kernel} \cgalParamDefault{the kernel of the point type} \cgalParamNEnd
/// \cgalNamedParamsEnd
///
/// \returns a `Gap_analysis`.
/// \throws Invalid_input on a face that is not a triangle, an index out of range, a repeated
///         index in a face or a non-finite coordinate; and when the border vertices are so
///         crowded within the search radius that more than 2^24 + 256 per border vertex
///         candidate pairs would have to be examined (the work stays bounded; give the
///         tolerance by hand then).
template <class ConcurrencyTag = CGAL::Sequential_tag, class PointRange, class TriangleRange,
          class NamedParameters = CGAL::parameters::Default_named_parameters>
Gap_analysis analyze_gaps(const PointRange& points, const TriangleRange& triangles,
                          const NamedParameters& np = CGAL::parameters::default_values())
{
  using NP_helper = internal::Soup_np_helper<PointRange, NamedParameters>;
  using Geom_traits = typename NP_helper::Geom_traits;
  using Point = typename Geom_traits::Point_3;
  const Geom_traits gt = NP_helper::get_geom_traits(np);

  std::vector<Point> pts;
  std::vector<std::array<std::size_t, 3>> tris;
  internal::exactly_welded_copy<Point>(points, triangles, NP_helper::get_point_map(np), pts, tris);
  return internal::analyze_exactly_welded_gaps<ConcurrencyTag>(pts, tris, gt);
}

/// \ingroup PkgSoupTopologyGaps
/// \brief the suggestion of the gap analysis for one part of a soup (`analyze_gaps_per_part()`).
struct Part_gap_analysis
{
  std::size_t triangles = 0;                  ///< triangles of the part (after the exact weld)
  std::size_t border_edges = 0;               ///< its border edges
  std::size_t border_vertices = 0;            ///< its border vertices (one gap each)
  double feature_bound = std::numeric_limits<double>::infinity(); ///< a third of its smallest border feature
  Gap_verdict verdict = Gap_verdict::CLOSED;  ///< the verdict of the rule on its gaps and its bound
  double suggested_tolerance = 0;             ///< the tolerance (0 unless `SUGGESTED`; `NaN` for `OVERLAP`)
  std::string reasoning;                      ///< the conclusion in words, with the numbers
  /// the points of the part, as indices into the points given, in increasing order (a point no
  /// triangle uses belongs to no part); `per_part_vertex_tolerances()` reads them.
  std::vector<std::size_t> points;
};

namespace internal {

/// the representative of `x` in the union-find forest `parent` (paths halved).
inline std::size_t find_set(std::vector<std::size_t>& parent, std::size_t x)
{
  while(parent[x] != x) {
    parent[x] = parent[parent[x]];
    x = parent[x];
  }
  return x;
}

/// joins the sets of `x` and `y`; the smaller representative stays.
inline void join_sets(std::vector<std::size_t>& parent, std::size_t x, std::size_t y)
{
  x = find_set(parent, x);
  y = find_set(parent, y);
  if(x < y) parent[y] = x;
  else if(y < x) parent[x] = y;
}

/// the pieces of a soup: the connected components of `tables` (`component` of every triangle)
/// joined where they share a vertex; returns the union-find forest over the components.
inline std::vector<std::size_t> pieces_sharing_vertices(const Adjacency_tables& tables,
                                                        const std::vector<Adjacency_tables::size_type>& component,
                                                        std::size_t components)
{
  std::vector<std::size_t> piece(components);
  for(std::size_t c = 0; c < components; ++c) piece[c] = c;
  for(std::size_t v = 0; v < tables.number_of_vertices(); ++v) {
    const auto around = tables.triangles_around_vertex(static_cast<Adjacency_tables::size_type>(v));
    for(const auto t : around) join_sets(piece, component[*around.begin()], component[t]);
  }
  return piece;
}

/// the smallest border feature of every piece (indexed by its representative component;
/// infinity for a piece without a border).
template <class Geom_traits>
std::vector<double> smallest_border_feature_per_piece(const std::vector<typename Geom_traits::Point_3>& pts,
                                                      const std::vector<std::array<std::size_t, 3>>& tris,
                                                      const Adjacency_tables& tables,
                                                      const std::vector<Adjacency_tables::size_type>& component,
                                                      std::vector<std::size_t>& piece, const Geom_traits& gt)
{
  using size_type = Adjacency_tables::size_type;
  typename Geom_traits::Collinear_3 collinear = gt.collinear_3_object();
  std::vector<double> piece_feature(piece.size(), std::numeric_limits<double>::infinity());
  std::vector<double> features;
  for(std::size_t t = 0; t < tris.size(); ++t) {
    const auto tt = static_cast<size_type>(t);
    if(!(tables.is_border_edge(tt, 0) || tables.is_border_edge(tt, 1) || tables.is_border_edge(tt, 2))) continue;
    const auto& p = pts[tris[t][0]];
    const auto& q = pts[tris[t][1]];
    const auto& r = pts[tris[t][2]];
    if(collinear(p, q, r)) continue;
    features.clear();
    add_border_features(p, q, r, tt, tables, features);
    double& f = piece_feature[find_set(piece, component[t])];
    for(double x : features) f = std::min(f, x);
  }
  return piece_feature;
}

/// the public summary of the analysis of every part, in the documented order of
/// `analyze_gaps_per_part()`.
inline std::vector<Part_gap_analysis> summarize_parts(std::vector<Gap_analysis>& parts,
                                                      std::vector<std::vector<std::size_t>>& points_of_parts)
{
  std::vector<Part_gap_analysis> out;
  for(std::size_t k = 0; k < parts.size(); ++k) {
    Gap_analysis& a = parts[k];
    std::sort(a.gaps.begin(), a.gaps.end());
    a.feature_bound = a.border_features.minimum / 3;
    suggest_tolerance(a);
    Part_gap_analysis p;
    p.triangles = a.triangles;
    p.border_edges = a.border_edges;
    p.border_vertices = a.border_vertices;
    p.feature_bound = a.feature_bound;
    p.verdict = a.verdict;
    p.suggested_tolerance = a.suggested_tolerance;
    p.reasoning = a.reasoning;
    p.points = std::move(points_of_parts[k]);
    out.push_back(std::move(p));
  }
  std::sort(out.begin(), out.end(), [](const Part_gap_analysis& x, const Part_gap_analysis& y) {
    if(x.triangles != y.triangles) return x.triangles > y.triangles;
    if(x.feature_bound != y.feature_bound) return x.feature_bound > y.feature_bound;
    if(x.border_edges != y.border_edges) return x.border_edges > y.border_edges;
    if(x.border_vertices != y.border_vertices) return x.border_vertices > y.border_vertices;
    if(x.reasoning != y.reasoning) return x.reasoning < y.reasoning;
    return x.points < y.points;
  });
  return out;
}

} // namespace internal

/// \ingroup PkgSoupTopologyGaps
/// \brief proposes a snapping tolerance per part of the soup, where one tolerance does not fit
/// all: a small part and a large part in one assembly, each with seams at its own scale.
///
/// `per_part_vertex_tolerances()` turns the result into a tolerance per point, for the
/// `vertex_tolerance_map` of `reconstruct_topology()`. The soup is welded exactly
/// as by `analyze_gaps()`, and its gaps and border features are measured the same way. The
/// *parts* are then the groups of triangles connected by shared vertices or by a gap smaller
/// than the feature bounds of both sides: a *piece* is a set of triangles connected by shared
/// vertices, its bound a third of its smallest border feature, and a border vertex joins its piece
/// to the piece of its nearest border element when the gap is below the bounds of both pieces (so
/// a seam joins the patches it separates, but no gap joins two parts it would collapse). The rule
/// of `analyze_gaps()` is applied to the gaps and the bound of every part.
///
/// The parts do not depend on the order of the points or the triangles; they are listed by
/// decreasing number of triangles, then decreasing feature bound, border edges and border
/// vertices, then by their reasoning (then by their points). Each lists its points
/// (`Part_gap_analysis::points`, indices into `points`).
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` (default), `CGAL::Parallel_tag` (needs TBB) or
///         `CGAL::Parallel_if_available_tag`: the measures of `analyze_gaps()` on TBB's threads,
///         the same result
/// \tparam PointRange a random-access range of points (read through `point_map`)
/// \tparam TriangleRange a range of triangles (3 indices each)
/// \param points the points of the soup
/// \param triangles the triangles of the soup
/// \param np optional named parameters among the ones listed below
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{point_map} \cgalParamDescription{the point of an element of `points`}
///     \cgalParamType{a model of `ReadablePropertyMap` whose value is a point of a CGAL kernel}
///     \cgalParamDefault{`CGAL::Identity_property_map`} \cgalParamNEnd
///   \cgalParamNBegin{geom_traits} \cgalParamDescription{the kernel of the octree queries and
///     the distances} \cgalParamType{a CGAL kernel} \cgalParamDefault{the kernel of the point type} \cgalParamNEnd
/// \cgalNamedParamsEnd
///
/// \returns one `Part_gap_analysis` per part.
/// \throws Invalid_input as `analyze_gaps()`
template <class ConcurrencyTag = CGAL::Sequential_tag, class PointRange, class TriangleRange,
          class NamedParameters = CGAL::parameters::Default_named_parameters>
std::vector<Part_gap_analysis> analyze_gaps_per_part(const PointRange& points, const TriangleRange& triangles,
                                                     const NamedParameters& np = CGAL::parameters::default_values())
{
  using NP_helper = internal::Soup_np_helper<PointRange, NamedParameters>;
  using Geom_traits = typename NP_helper::Geom_traits;
  using Point = typename Geom_traits::Point_3;
  using size_type = Adjacency_tables::size_type;
  const Geom_traits gt = NP_helper::get_geom_traits(np);
  std::vector<Point> pts;
  std::vector<std::array<std::size_t, 3>> tris;
  std::vector<std::size_t> welded_index;
  internal::exactly_welded_copy<Point>(points, triangles, NP_helper::get_point_map(np), pts, tris, &welded_index);
  const Adjacency_tables tables(tris, pts.size());
  // (coordinates beyond 2^128 or below 2^-128 measured on a scaled copy, as by analyze_gaps():
  // every point of the copy is used)
  std::vector<Point> scaled;
  const double unscale = internal::scale_for_analysis(pts, tris, pts.size(), scaled);
  if(unscale != 1) pts.swap(scaled);

  // The pieces (the triangles connected by shared vertices) and their smallest border features:
  // a third of that is the bound of a piece.
  std::vector<size_type> component;
  const std::size_t components = tables.number_of_connected_components(&component);
  std::vector<std::size_t> piece = internal::pieces_sharing_vertices(tables, component, components);
  std::vector<double> piece_feature =
    internal::smallest_border_feature_per_piece(pts, tris, tables, component, piece, gt);
  if(unscale != 1)
    for(double& f : piece_feature) f *= unscale;
  // The gaps, as analyze_gaps() measures them, with their nearest elements.
  Gap_analysis global;
  const std::vector<std::size_t> border = internal::border_vertices(tables);
  internal::measure_feature_sizes<ConcurrencyTag>(pts, tris, tables, gt, global, unscale);
  internal::Nearest_border_elements nearest;
  if(!border.empty()) nearest = internal::measure_gaps<ConcurrencyTag>(pts, tris, tables, border, gt, global, unscale);
  // A gap below the bounds of the pieces on both sides joins them (decided on the pieces, so
  // that the order of the joins does not matter).
  const auto piece_of_vertex = [&](std::size_t v) {
    return internal::find_set(piece, component[*tables.triangles_around_vertex(static_cast<size_type>(v)).begin()]);
  };
  std::vector<std::size_t> part(piece);
  for(std::size_t k = 0; k < border.size(); ++k) {
    const internal::Nearest_border_element& e = nearest[k];
    if(!std::isfinite(e.distance)) continue;
    const std::size_t a = piece_of_vertex(border[k]);
    const std::size_t b = e.vertex != static_cast<std::size_t>(-1) ? piece_of_vertex(e.vertex)
                                                                     : internal::find_set(piece, component[e.edge.triangle]);
    if(e.distance < piece_feature[a] / 3 && e.distance < piece_feature[b] / 3) internal::join_sets(part, a, b);
  }
  // The rule on every part.
  std::vector<std::size_t> index_of_part(components, static_cast<std::size_t>(-1));
  std::vector<Gap_analysis> parts;
  const auto part_of_piece = [&](std::size_t c) {
    const std::size_t p = internal::find_set(part, internal::find_set(piece, c));
    if(index_of_part[p] == static_cast<std::size_t>(-1)) {
      index_of_part[p] = parts.size();
      parts.emplace_back();
      parts.back().search_radius = global.search_radius;
    }
    return index_of_part[p];
  };
  for(std::size_t t = 0; t < tris.size(); ++t) {
    Gap_analysis& a = parts[part_of_piece(component[t])];
    ++a.triangles;
    for(int i = 0; i < 3; ++i)
      if(tables.is_border_edge(static_cast<size_type>(t), i)) ++a.border_edges;
  }
  for(std::size_t c = 0; c < components; ++c) {
    if(internal::find_set(piece, c) != c) continue;
    Gap_analysis& a = parts[part_of_piece(c)];
    a.border_features.minimum = std::min(a.border_features.count ? a.border_features.minimum : piece_feature[c], piece_feature[c]);
    a.border_features.count = 1;
  }
  for(std::size_t k = 0; k < border.size(); ++k) {
    Gap_analysis& a = parts[part_of_piece(component[*tables.triangles_around_vertex(static_cast<size_type>(border[k])).begin()])];
    ++a.border_vertices;
    if(std::isfinite(nearest[k].distance)) a.gaps.push_back(nearest[k].distance);
    else ++a.gaps_beyond_search_radius;
  }
  // The input points of every part, through the exact weld (in increasing order).
  std::vector<std::vector<std::size_t>> points_of_parts(parts.size());
  for(std::size_t i = 0; i < welded_index.size(); ++i) {
    const std::size_t v = welded_index[i];
    if(v == static_cast<std::size_t>(-1)) continue;
    points_of_parts[part_of_piece(component[*tables.triangles_around_vertex(static_cast<size_type>(v)).begin()])]
      .push_back(i);
  }
  return internal::summarize_parts(parts, points_of_parts);
}

/// \ingroup PkgSoupTopologyGaps
/// \brief the tolerance of every point given by the analysis per part: every point of a part
/// (`Part_gap_analysis::points`) gets the tolerance suggested for its part, 0 for a part without
/// suggestion (verdict other than `SUGGESTED`) and for a point of no part. The result is meant for
/// the `vertex_tolerance_map` of `reconstruct_topology()`:
/// \code
/// const std::vector<Part_gap_analysis> parts = analyze_gaps_per_part(points, triangles);
/// const std::vector<double> tolerances = per_part_vertex_tolerances(parts, points.size());
/// reconstruct_topology(points, triangles,
///                      parameters::vertex_tolerance_map(CGAL::make_property_map(tolerances)));
/// \endcode
/// Two points of different parts are then welded only within the smaller of their tolerances.
/// \param parts the result of `analyze_gaps_per_part()` on the soup
/// \param number_of_points the number of points of the soup analysed
/// \returns `number_of_points` tolerances, indexed like the points.
/// \throws Invalid_input if a part lists a point `>= number_of_points`.
inline std::vector<double> per_part_vertex_tolerances(const std::vector<Part_gap_analysis>& parts,
                                                      std::size_t number_of_points)
{
  std::vector<double> tolerances(number_of_points, 0.0);
  for(const Part_gap_analysis& part : parts) {
    const double t = part.verdict == Gap_verdict::SUGGESTED && std::isfinite(part.suggested_tolerance)
                       ? part.suggested_tolerance : 0.0;
    for(std::size_t i : part.points) {
      if(i >= number_of_points)
        throw Invalid_input("per_part_vertex_tolerances: a part lists point " + std::to_string(i) + " of a soup of " +
                            std::to_string(number_of_points) + " points");
      tolerances[i] = t;
    }
  }
  return tolerances;
}

} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_ANALYZE_GAPS_H
