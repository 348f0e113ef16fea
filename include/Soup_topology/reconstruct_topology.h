// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The whole pipeline in one call: exact weld, adjacency tables, epsilon welding and T-junction
// splitting iterated to a fixpoint, and the output into any CGAL MutableFaceGraph
// (through triangle_soup_to_face_graph.h); a FaceGraph with open seams is repaired in place.

#ifndef SOUP_TOPOLOGY_RECONSTRUCT_TOPOLOGY_H
#define SOUP_TOPOLOGY_RECONSTRUCT_TOPOLOGY_H

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/Triangle_adjacency_graph.h>
#include <Soup_topology/analyze_gaps.h>
#include <Soup_topology/index_triangles.h>
#include <Soup_topology/parameters.h>
#include <Soup_topology/snap_vertices.h>
#include <Soup_topology/split_t_junctions.h>
#include <Soup_topology/triangle_soup_to_face_graph.h>
#include <Soup_topology/internal/coordinate_scale.h>
#include <Soup_topology/internal/parallel.h>
#include <Soup_topology/internal/small_feature_degenerate.h>
#include <Soup_topology/internal/soup_checks.h>
#include <Soup_topology/internal/soup_self_intersections.h>
#include <Soup_topology/internal/tolerance.h>
#include <Soup_topology/internal/triangulate_polygon.h>
#include <Soup_topology/internal/uninitialized_vector.h>

#include <CGAL/Kernel_traits.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/Polygon_mesh_processing/polygon_mesh_to_polygon_soup.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/property_map.h>
#include <CGAL/tags.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <iterator>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace Soup_topology {

/// \ingroup PkgSoupTopologyPipeline
/// \brief everything `reconstruct_topology()` did: nothing is changed silently.
struct Reconstruction_report
{
  /// the absolute tolerance used; with `vertex_tolerance_map`, the largest tolerance of the map
  /// (over the points given)
  double tolerance = 0;
  std::size_t input_points = 0;             ///< points given
  std::size_t input_triangles = 0;          ///< triangles given
  std::size_t exact_duplicates = 0;         ///< points merged by the exact weld
  std::size_t collapsed_triangles = 0;      ///< triangles removed because the exact weld collapsed them
  std::size_t rounds = 0;                   ///< weld/split rounds run (the last one changes nothing)
  // Welding, summed over the rounds.
  std::size_t snapped_vertices = 0;         ///< vertices merged within the tolerance
  std::size_t clusters = 0;                 ///< representatives that received vertices
  std::size_t refused_same_triangle = 0;    ///< welds refused: the vertices share a triangle
  std::size_t refused_degenerate = 0;       ///< welds refused: a triangle would degenerate
  std::size_t refused_flip = 0;             ///< welds refused: a triangle would flip
  std::size_t refused_holds_welds = 0;      ///< welds refused: the vertex received welds in an earlier round
  std::size_t ambiguous_sites = 0;          ///< sites where the minimum feature separation is not met
  std::size_t short_edges = 0;              ///< edges shorter than the tolerance (first round)
  Small_features small_features = Small_features::REFUSE; ///< the policy for features smaller than the tolerance
  std::size_t small_features_resolved = 0;  ///< `Small_features::COLLAPSE`: pairs of vertices of one triangle within the tolerance merged
  std::size_t small_feature_collapsed_triangles = 0; ///< `Small_features::COLLAPSE`: triangles removed because two of their corners merged
  std::size_t refused_uncovered_collapse = 0; ///< `Small_features::COLLAPSE`: welds refused because a triangle would collapse onto an edge or point of no kept triangle (a part smaller than the tolerance is kept)
  std::size_t flipped_degenerate_triangles = 0; ///< `Small_features::COLLAPSE`: degenerate input triangles (collinear corners) removed by an edge flip
  std::size_t removed_degenerate_triangles = 0; ///< `Small_features::COLLAPSE`: degenerate input triangles that no flip removes, removed where the other triangles cover them
  std::size_t degenerate_triangles_after = 0;   ///< triangles of the result with collinear corners
  // T-junctions, summed over the rounds.
  std::size_t t_junctions = 0;              ///< vertices found on the interior of a border edge
  std::size_t split_triangles = 0;          ///< triangle splits (each adds one triangle)
  std::size_t refused_splits = 0;           ///< T-junctions refused (overlap, degenerate, flip)
  std::size_t ambiguous_t_junctions = 0;    ///< vertices near several border edges
  // Before (after the exact weld) and after.
  std::size_t border_edges_before = 0;
  std::size_t border_edges_after = 0;
  std::size_t non_manifold_edges_before = 0;
  std::size_t non_manifold_edges_after = 0;
  std::size_t non_manifold_vertices_after = 0;
  std::size_t components_before = 0;
  std::size_t components = 0;               ///< edge-connected components of the result
  std::size_t removed_points = 0;           ///< points no triangle uses any more, removed at the end
  std::size_t output_points = 0;
  std::size_t output_triangles = 0;
  double max_displacement = 0;              ///< largest distance from an input point to its output point
  // Writing into a FaceGraph.
  std::size_t duplicate_triangles = 0;      ///< triangles with the same three vertices as another, left out
  std::size_t orientation_flips = 0;        ///< triangles reversed to orient their component
  std::size_t duplicated_points = 0;        ///< points duplicated to separate non-manifold vertices and edges
  // Asked for with `count_self_intersections(true)`.
  bool self_intersections_counted = false;  ///< whether `self_intersecting_pairs` was computed
  std::size_t self_intersecting_pairs = 0;  ///< pairs of output triangles that meet beyond a shared vertex or edge
  // A mesh given as input (`reconstruct_topology(mesh, np)`).
  std::size_t triangulated_polygons = 0;    ///< faces of more than 3 vertices cut into triangles
  std::size_t unclipped_corners = 0;        ///< corners of such faces that no ear could be cut at (their triangles are left out)
  // Asked for with `automatic_tolerance(true)`: why `tolerance` is what it is.
  bool automatic_tolerance = false;         ///< whether the gap analysis chose `tolerance`
  Gap_verdict tolerance_verdict = Gap_verdict::CLOSED; ///< the analysis' verdict (`CLOSED`, `NOTHING_TO_CLOSE` or `SUGGESTED`)
  std::string tolerance_reasoning;          ///< the analysis' reasoning: which gaps the tolerance closes, what margins it keeps

  /// the total number of refused welds.
  std::size_t refused_welds() const
  { return refused_same_triangle + refused_degenerate + refused_flip + refused_holds_welds + refused_uncovered_collapse; }
  /// `true` if the result has no border edge.
  bool closed() const { return border_edges_after == 0; }
};

namespace internal {

template <class T>
struct is_named_parameters : std::false_type {};
template <class T, class Tag, class Base>
struct is_named_parameters<CGAL::Named_function_parameters<T, Tag, Base>> : std::true_type {};

/// removes the points no triangle uses and renumbers the triangles; returns the new index of
/// every old point (or -1). With a parallel `ConcurrencyTag` the marks, the new indices and the
/// renumbering run by blocks on TBB's threads (the points keep their order: the result is that
/// of one thread); the points are moved down on this thread, in place.
template <class ConcurrencyTag = CGAL::Sequential_tag, class PointRange, class TriangleRange>
Uninitialized_vector<std::uint32_t> remove_unreferenced_points(PointRange& points, TriangleRange& triangles)
{
  constexpr std::uint32_t unused = static_cast<std::uint32_t>(-1);
  const std::size_t n = points.size(), m = triangles.size();
  const auto triangle = [&triangles](std::size_t t) -> auto& {
    return *(triangles.begin() + static_cast<std::ptrdiff_t>(t));
  };
  // whether a triangle uses each point: two triangles of two blocks may mark one point at once,
  // hence bytes written atomically (relaxed: read after the blocks have joined)
  std::unique_ptr<std::atomic<unsigned char>[]> used(new std::atomic<unsigned char>[n]);
  for_each_block<ConcurrencyTag>(n, default_block_size, [&](std::size_t, std::size_t begin, std::size_t end) {
    for(std::size_t i = begin; i != end; ++i) used[i].store(0, std::memory_order_relaxed);
  });
  for_each_block<ConcurrencyTag>(m, default_block_size, [&](std::size_t, std::size_t begin, std::size_t end) {
    for(std::size_t t = begin; t != end; ++t)
      for(const auto& v : triangle(t)) used[static_cast<std::size_t>(v)].store(1, std::memory_order_relaxed);
  });
  Uninitialized_vector<std::uint32_t> new_index(n); // (written whole below)
  for_each_block<ConcurrencyTag>(n, default_block_size, [&](std::size_t, std::size_t begin, std::size_t end) {
    for(std::size_t i = begin; i != end; ++i) new_index[i] = unused;
  });
  const std::size_t kept = compact_in_order<ConcurrencyTag>(
    n, [&](std::size_t i) { return used[i].load(std::memory_order_relaxed) != 0; },
    [&](std::size_t i, std::size_t position) { new_index[i] = static_cast<std::uint32_t>(position); });
  used.reset();
  // (a point moves down to a place no later point is read from)
  for(std::size_t i = 0; i < n; ++i)
    if(new_index[i] != unused && new_index[i] != i) points[new_index[i]] = points[i];
  points.resize(kept);
  for_each_block<ConcurrencyTag>(m, default_block_size, [&](std::size_t, std::size_t begin, std::size_t end) {
    for(std::size_t t = begin; t != end; ++t)
      for(auto& v : triangle(t)) v = static_cast<std::decay_t<decltype(v)>>(new_index[static_cast<std::size_t>(v)]);
  });
  return new_index;
}

/// the geometric traits given by `np` for points read through a map of type `PointMap`.
template <class PointMap, class NamedParameters>
using Pipeline_geom_traits = typename CGAL::internal_np::Lookup_named_param_def<
  CGAL::internal_np::geom_traits_t, NamedParameters,
  typename CGAL::Kernel_traits<typename boost::property_traits<PointMap>::value_type>::Kernel>::type;

/// `p` as a point of the traits: the same coordinates, exactly when the number types allow it.
template <class PointOut, class FT, class PointIn>
PointOut convert_point(const PointIn& p)
{
  if constexpr(std::is_same<PointIn, PointOut>::value)
    return p;
  else if constexpr(std::is_convertible<decltype(p.x()), FT>::value)
    return PointOut(FT(p.x()), FT(p.y()), FT(p.z()));
  else
    return PointOut(FT(CGAL::to_double(p.x())), FT(CGAL::to_double(p.y())), FT(CGAL::to_double(p.z())));
}

/// the index in the input of the point that the pipeline's point `k` is: `input_index[k]`, or
/// `k` itself while `input_index` is empty (no point has been removed or moved yet).
inline std::size_t input_point_index(const std::vector<std::uint32_t>& input_index, std::size_t k)
{
  return input_index.empty() ? k : input_index[k];
}

/// the visitor that `reconstruct_topology()` gives `snap_vertices()`: records every weld for the
/// displacement and tells the caller's visitor, with the caller's indices.
template <class User_visitor>
struct Pipeline_visitor
{
  // (a merge writes the entry of its duplicate only: the merges may be told on several threads
  // when the caller's visitor allows it)
  static constexpr bool tells_merges_concurrently =
    ::Soup_topology::internal::tells_merges_concurrently<User_visitor>::value;

  Uninitialized_vector<std::uint32_t>* merged_into;
  const std::vector<std::uint32_t>* input_index;
  User_visitor* user;
  std::size_t in(std::size_t k) const { return input_point_index(*input_index, k); }
  void on_merge(std::size_t duplicate, std::size_t representative)
  {
    (*merged_into)[duplicate] = static_cast<std::uint32_t>(representative);
    user->on_merge(in(duplicate), in(representative));
  }
  void on_refusal(std::size_t vertex, std::size_t representative, Refusal_reason reason)
  {
    user->on_refusal(in(vertex), in(representative), reason);
  }
  // Given to `split_t_junctions()` when the caller's visitor is also a split visitor.
  void on_split(std::size_t vertex, std::size_t a, std::size_t b)
  {
    user->on_split(in(vertex), in(a), in(b));
  }
  void on_split_refusal(std::size_t vertex, std::size_t a, std::size_t b, Split_refusal_reason reason)
  {
    user->on_split_refusal(in(vertex), in(a), in(b), reason);
  }
  void on_ambiguous_t_junction(std::size_t vertex, std::size_t a, std::size_t b)
  {
    user->on_ambiguous_t_junction(in(vertex), in(a), in(b));
  }
};

/// whether `Visitor` has `on_ambiguous_site(std::size_t)`.
template <class Visitor, class = void>
struct tells_ambiguous_sites : std::false_type {};
template <class Visitor>
struct tells_ambiguous_sites<Visitor, std::void_t<decltype(std::declval<Visitor&>().on_ambiguous_site(std::size_t()))>>
  : std::true_type {};

/// calls `f(visitor)` with the caller's visitor of `np`: a reference when given as `std::ref(v)`,
/// otherwise a copy (a `Default_snap_visitor` when none is given). A visitor given by value
/// comes back as a temporary, bound here directly so that it lives long enough to be copied
/// (`choose_parameter` would return a reference to it that dangles).
template <class NamedParameters, class Function>
void with_user_visitor(const NamedParameters& np, const Function& f)
{
  auto&& visitor_given = CGAL::parameters::get_parameter_reference(np, CGAL::internal_np::visitor);
  using Visitor_given = decltype(visitor_given);
  constexpr bool no_visitor = std::is_same<std::decay_t<Visitor_given>, CGAL::internal_np::Param_not_found>::value;
  constexpr bool by_reference =
    std::is_lvalue_reference<Visitor_given>::value && !std::is_const<std::remove_reference_t<Visitor_given>>::value;
  if constexpr(by_reference) {
    f(visitor_given);
  } else if constexpr(no_visitor) {
    Default_snap_visitor visitor;
    f(visitor);
  } else {
    std::decay_t<Visitor_given> visitor(visitor_given);
    f(visitor);
  }
}

/// the observer of the phases of `Soup_reconstruction::weld_and_split_in_rounds()` that does nothing.
struct No_phase_observer
{
  template <class Points>
  void before_weld(const Points&, const Adjacency_tables&) {}
  template <class Points>
  void after_weld(const Points&, const Adjacency_tables&) {}
  template <class Points>
  void before_split(const Points&, const Adjacency_tables&) {}
  template <class Points>
  void after_split(const Points&, const Adjacency_tables&) {}
};

/// whether the soup given to the pipeline may still hold exactly equal points.
enum class Exact_weld { TO_DO, DONE };

/// the steps of the pipeline on a validated soup, in the order `reconstruct_soup()` calls them.
/// It works on `pts`, the points converted to the traits' points, and repairs `triangles` in
/// place; `input_index[k]` is the index in the input of the point that `pts[k]` is. While no
/// point has been removed `input_index` stays empty, meaning that every point is its own input
/// point (`input_point_index()`): the weld and the splits do not remove points, so a soup that
/// arrives exactly welded carries no such table until `finish()`.
/// `ConcurrencyTag` is passed on to every step.
template <class Geom_traits, class TriangleRange, class ConcurrencyTag = CGAL::Sequential_tag>
class Soup_reconstruction
{
public:
  using Point = typename Geom_traits::Point_3;
  using FT = typename Geom_traits::FT;

  Soup_reconstruction(std::vector<Point>& pts, TriangleRange& triangles, std::vector<std::uint32_t>& input_index,
                      const Geom_traits& gt)
    : pts_(pts), triangles_(triangles), input_index_(input_index), gt_(gt)
  {}

  /// copies the points read through `pm` into `pts`; every point is its own input point.
  template <class PointRange, class PointMap>
  void copy_points(const PointRange& points, const PointMap& pm)
  {
    report_.input_points = static_cast<std::size_t>(std::distance(points.begin(), points.end()));
    report_.input_triangles = triangles_.size();
    pts_.clear();
    reserve_in_huge_pages(pts_, report_.input_points);
    for(const auto& e : points) pts_.push_back(convert_point<Point, FT>(get(pm, e)));
    input_index_.clear();
  }

  /// moves `points` into `pts` (leaving `points` empty), when they are already the traits' points.
  void take_points(std::vector<Point>& points)
  {
    report_.input_points = points.size();
    report_.input_triangles = triangles_.size();
    pts_.clear();
    pts_.swap(points);
    input_index_.clear();
  }

  /// gives every point its own tolerance (`vertex_tolerance_map`): `tolerances[k]` is that of
  /// `pts[k]`, checked. Called before the exact weld, which keeps them with the points.
  void set_vertex_tolerances(std::vector<FT>&& tolerances) { tolerances_ = std::move(tolerances); }

  /// merges exactly equal points (a merged point is known by the first of the equal input
  /// points) and removes the triangles that collapse. With per-vertex tolerances, a merged point
  /// takes the smallest tolerance of the equal points (which does not depend on their order).
  void weld_exact_duplicates()
  {
    const std::vector<std::size_t> exact_index = merge_duplicate_points_and_map<ConcurrencyTag>(pts_, triangles_);
    report_.exact_duplicates = exact_index.size() - pts_.size();
    if(!tolerances_.empty()) {
      std::vector<FT> merged(pts_.size());
      std::vector<char> seen(pts_.size(), 0);
      for(std::size_t i = 0; i < exact_index.size(); ++i) {
        FT& t = merged[exact_index[i]];
        if(!seen[exact_index[i]] || tolerances_[i] < t) t = tolerances_[i];
        seen[exact_index[i]] = 1;
      }
      tolerances_.swap(merged);
    }
    std::vector<std::uint32_t> first(pts_.size());
    for(std::size_t i = exact_index.size(); i-- > 0;)
      first[exact_index[i]] = static_cast<std::uint32_t>(input_point_index(input_index_, i));
    input_index_.swap(first);
    report_.collapsed_triangles = remove_collapsed_triangles(triangles_);
  }

  /// removes the degenerate triangles (three distinct collinear corners) by edge flips, where
  /// the triangle across the longest edge allows it (`flip_degenerate_triangles()`), then the
  /// degenerate triangles left whose points the other triangles cover
  /// (`remove_covered_degenerate_triangles()`): the surface does not move. Under
  /// `Small_features::COLLAPSE`, before the tables are built.
  void flip_degenerate_triangles_away()
  {
    report_.flipped_degenerate_triangles = flip_degenerate_triangles<ConcurrencyTag>(pts_, triangles_, gt_).flipped;
    report_.removed_degenerate_triangles = remove_covered_degenerate_triangles<ConcurrencyTag>(pts_, triangles_, gt_);
  }

  /// builds the adjacency tables and records what they show before the repair.
  void build_tables()
  {
    tables_.emplace(triangles_, pts_.size(), ConcurrencyTag());
    report_.border_edges_before = tables_->number_of_border_edges();
    report_.non_manifold_edges_before = tables_->non_manifold_edges().size();
    report_.components_before = tables_->template number_of_connected_components<ConcurrencyTag>();
  }

  /// welds (`snap_vertices()`) and splits T-junctions (`split_t_junctions()`) in rounds, until a
  /// round changes nothing or `max_rounds` have run; tells `user_visitor` every weld.
  ///
  /// The rounds end: every round but the last merges a vertex (the number of distinct vertices
  /// the triangles use strictly decreases; a triangle is removed only when two of its corners
  /// merge) or splits a triangle at a vertex already in the soup (no vertex is added, and a
  /// split vertex is no longer on that border edge); `max_rounds` bounds them in any case.
  ///
  /// `observer` (a `No_phase_observer` by default) is told before and after each phase, the weld
  /// and the split of every round, with the points and the tables as they are then: the tiled
  /// repair follows what each phase may have decided differently from the whole soup.
  template <class User_visitor, class Phase_observer = No_phase_observer>
  void weld_and_split_in_rounds(const FT& eps, std::size_t max_rounds, bool do_split, Small_features policy,
                                User_visitor& user_visitor, Phase_observer&& observer = Phase_observer())
  {
    report_.tolerance = CGAL::to_double(eps);
    report_.small_features = policy;
    // Per-vertex tolerances: the rounds read those of the pipeline's points, without copy.
    if(tolerances_.empty())
      run_rounds(CGAL::parameters::snapping_tolerance(eps).geom_traits(gt_), max_rounds, do_split, policy, user_visitor,
                 observer);
    else
      run_rounds(parameters::vertex_tolerance_map(Vertex_tolerance_vector<FT>{&tolerances_}).geom_traits(gt_), max_rounds,
                 do_split, policy, user_visitor, observer);
  }

private:
  template <class WeldNamedParameters, class User_visitor, class Phase_observer>
  void run_rounds(const WeldNamedParameters& weld_np, std::size_t max_rounds, bool do_split, Small_features policy,
                  User_visitor& user_visitor, Phase_observer& observer)
  {
    // (by blocks, on TBB's threads with the tag: they share the first touch of its pages)
    merged_into_.resize(pts_.size());
    for_each_block<ConcurrencyTag>(merged_into_.size(), default_block_size,
                                   [&](std::size_t, std::size_t begin, std::size_t end) {
                                     for(std::size_t i = begin; i < end; ++i)
                                       merged_into_[i] = static_cast<std::uint32_t>(i);
                                   });
    Pipeline_visitor<User_visitor> recorder{&merged_into_, &input_index_, &user_visitor};
    // A vertex that received welds is never moved in a later round (its welded points would
    // move farther than the tolerance); it may still receive more.
    std::vector<char> holds_welds(pts_.size(), 0);
    std::vector<std::size_t> sites;
    for(std::size_t round = 0; round < max_rounds; ++round) {
      ++report_.rounds;
      observer.before_weld(pts_, *tables_);
      const Snap_report s = snap_vertices<ConcurrencyTag>(
        pts_, triangles_, *tables_,
        parameters::small_features(policy, parameters::fixed_vertices(static_cast<const std::vector<char>*>(&holds_welds),
                                                                      weld_np.visitor(std::ref(recorder)))));
      for(std::size_t v = 0; v < merged_into_.size(); ++v)
        if(merged_into_[v] != v) holds_welds[merged_into_[v]] = 1;
      add_weld_report(s, round);
      observer.after_weld(pts_, *tables_);
      sites.insert(sites.end(), s.ambiguous_sites.begin(), s.ambiguous_sites.end());
      std::size_t splits = 0;
      if(do_split) {
        observer.before_split(pts_, *tables_);
        if constexpr(is_split_visitor<User_visitor>::value)
          splits = add_split_report(
            split_t_junctions<ConcurrencyTag>(pts_, triangles_, *tables_, weld_np.visitor(std::ref(recorder))));
        else
          splits = add_split_report(split_t_junctions<ConcurrencyTag>(pts_, triangles_, *tables_, weld_np));
        observer.after_split(pts_, *tables_);
      }
      if(s.merged_vertices == 0 && splits == 0) break;
    }
    std::sort(sites.begin(), sites.end());
    sites.erase(std::unique(sites.begin(), sites.end()), sites.end());
    report_.ambiguous_sites = sites.size();
    if constexpr(tells_ambiguous_sites<User_visitor>::value)
      for(std::size_t v : sites) user_visitor.on_ambiguous_site(input_point_index(input_index_, v));
  }

public:

  /// how far the points moved: every input point follows its exact-weld image (same
  /// coordinates) and then the chain of welds; only the points that were welded can move.
  /// The largest distance is the same in any order: with the tag and double coordinates it is
  /// taken by blocks on TBB's threads.
  void measure_displacement()
  {
    using Tag = std::conditional_t<std::is_same<typename Geom_traits::FT, double>::value, ConcurrencyTag,
                                   CGAL::Sequential_tag>;
    const typename Geom_traits::Compute_squared_distance_3 squared_distance = gt_.compute_squared_distance_3_object();
    const double largest = largest_by_blocks<Tag>(merged_into_.size(), [&](std::size_t v) {
      std::size_t w = merged_into_[v];
      if(w == v) return 0.;
      while(merged_into_[w] != w) w = merged_into_[w];
      return std::sqrt(CGAL::to_double(squared_distance(pts_[v], pts_[w])));
    });
    report_.max_displacement = std::max(report_.max_displacement, largest);
    Uninitialized_vector<std::uint32_t>().swap(merged_into_);
  }

  /// the final counts, from the live tables (removing unused points changes none of them), then
  /// the removal of the points no triangle uses.
  void finish(bool count_intersections)
  {
    report_.border_edges_after = tables_->number_of_border_edges();
    report_.non_manifold_edges_after = tables_->non_manifold_edges().size();
    report_.non_manifold_vertices_after = tables_->template non_manifold_vertices<ConcurrencyTag>().size();
    report_.components = tables_->template number_of_connected_components<ConcurrencyTag>();
    // On TBB's threads with double coordinates, whose predicates share no lazily computed state.
    using Collinear_tag =
      std::conditional_t<std::is_same<typename Geom_traits::FT, double>::value, ConcurrencyTag, CGAL::Sequential_tag>;
    const typename Geom_traits::Collinear_3 collinear = gt_.collinear_3_object();
    const Adjacency_tables::Triangle_vector& final_triangles = tables_->triangles();
    std::vector<Adjacency_tables::size_type> collinear_triangles;
    append_indices_where<Collinear_tag>(final_triangles.size(), [&](std::size_t k) {
      const Adjacency_tables::Triangle& t = final_triangles[k];
      return collinear(pts_[t[0]], pts_[t[1]], pts_[t[2]]);
    }, collinear_triangles);
    report_.degenerate_triangles_after = collinear_triangles.size();
    tables_.reset();
    const std::size_t before = pts_.size();
    const Uninitialized_vector<std::uint32_t> kept_index = remove_unreferenced_points<ConcurrencyTag>(pts_, triangles_);
    // the input index of every point kept (each written once: by blocks on TBB's threads with
    // the tag, into a new array)
    std::vector<std::uint32_t> kept_input_index(pts_.size());
    for_each_block<ConcurrencyTag>(
      kept_index.size(), default_block_size, [&](std::size_t, std::size_t begin, std::size_t end) {
        for(std::size_t i = begin; i != end; ++i)
          if(kept_index[i] != static_cast<std::uint32_t>(-1))
            kept_input_index[kept_index[i]] = static_cast<std::uint32_t>(input_point_index(input_index_, i));
      });
    input_index_.swap(kept_input_index);
    report_.removed_points = before - pts_.size();
    report_.output_points = pts_.size();
    report_.output_triangles = triangles_.size();
    if(count_intersections) {
      report_.self_intersections_counted = true;
      report_.self_intersecting_pairs = count_soup_self_intersections(pts_, triangles_, gt_);
    }
  }

  const std::vector<Point>& points() const { return pts_; }

  /// multiplies every point by 2^exponent, and the lengths of the report (exact for points that
  /// `moderate_scale_exponent_of()` accepted, whose output points are input points): the
  /// pipeline runs on the scaled points, then `scale(-exponent)` gives them and the report back
  /// at the scale of the input.
  void scale(int exponent)
  {
    for(Point& p : pts_) p = scaled_point(p, exponent);
    report_.tolerance = std::ldexp(report_.tolerance, exponent);
    report_.max_displacement = std::ldexp(report_.max_displacement, exponent);
  }
  const Reconstruction_report& report() const { return report_; }

private:
  void add_weld_report(const Snap_report& s, std::size_t round)
  {
    report_.snapped_vertices += s.merged_vertices;
    report_.clusters += s.clusters;
    report_.refused_same_triangle += s.refused_same_triangle;
    report_.refused_degenerate += s.refused_degenerate;
    report_.refused_flip += s.refused_flip;
    report_.refused_holds_welds += s.refused_holds_welds;
    report_.small_features_resolved += s.small_features_resolved;
    report_.small_feature_collapsed_triangles += s.collapsed_triangles;
    report_.refused_uncovered_collapse += s.refused_uncovered_collapse;
    if(round == 0) report_.short_edges = s.short_edges;
  }
  std::size_t add_split_report(const Split_report& t)
  {
    report_.t_junctions += t.t_junctions;
    report_.split_triangles += t.split_triangles;
    report_.refused_splits += t.refused_overlap + t.refused_degenerate + t.refused_flip;
    report_.ambiguous_t_junctions += t.ambiguous;
    return t.split_triangles;
  }

  std::vector<Point>& pts_;
  TriangleRange& triangles_;
  std::vector<std::uint32_t>& input_index_;
  const Geom_traits& gt_;
  std::optional<Adjacency_tables> tables_;
  Uninitialized_vector<std::uint32_t> merged_into_;
  std::vector<FT> tolerances_;  // per point (`vertex_tolerance_map`), or empty: one tolerance
  Reconstruction_report report_;
};

/// the gap analysis of `automatic_tolerance(true)`, on the soup given to the pipeline before
/// anything is changed: on a copy welded by `analyze_gaps()`, or, with `Exact_weld::DONE`, on the
/// soup itself; on TBB's threads with `CGAL::Parallel_tag` (the same analysis).
/// \throws Invalid_input if a tolerance is given too, or if the analysis suggests none (its reasoning says why)
template <class ConcurrencyTag, class Point, class TriangleRange, class NamedParameters, class Geom_traits>
Gap_analysis automatic_tolerance_analysis(const std::vector<Point>& pts, const TriangleRange& triangles,
                                          const NamedParameters&, const Geom_traits& gt, Exact_weld exact_weld)
{
  using CGAL::parameters::is_default_parameter;
  if(!is_default_parameter<NamedParameters, CGAL::internal_np::snapping_tolerance_t>::value ||
     !is_default_parameter<NamedParameters, internal_np::relative_tolerance_t>::value)
    throw Invalid_input("automatic_tolerance(true) chooses the tolerance: give no snapping_tolerance or relative_tolerance with it");
  Gap_analysis a = exact_weld == Exact_weld::DONE
                     ? analyze_exactly_welded_gaps<ConcurrencyTag>(pts, triangles, gt)
                     : analyze_gaps<ConcurrencyTag>(pts, triangles, CGAL::parameters::geom_traits(gt));
  if(!a.has_suggestion())
    throw Invalid_input("automatic tolerance: " + a.reasoning + "; give a tolerance by hand");
  return a;
}

/// the pipeline on a validated soup (`check_indexed_soup()`): `put_points(steps)` gives the
/// points to `steps` (`Soup_reconstruction::copy_points()` or `take_points()`), `triangles` is
/// repaired in place. On return `pts` holds the output points and `input_index[k]` is the index
/// in the input of the point that output point `k` is. With `Exact_weld::DONE` the caller
/// guarantees that no two points are equal.
template <class ConcurrencyTag = CGAL::Sequential_tag, class PutPoints, class TriangleRange, class NamedParameters,
          class Geom_traits>
Reconstruction_report reconstruct_soup(const PutPoints& put_points, TriangleRange& triangles, const NamedParameters& np,
                                       const Geom_traits& gt, std::vector<typename Geom_traits::Point_3>& pts,
                                       std::vector<std::uint32_t>& input_index, Exact_weld exact_weld = Exact_weld::TO_DO)
{
  using CGAL::parameters::choose_parameter;
  using CGAL::parameters::get_parameter;
  using FT = typename Geom_traits::FT;
  Soup_reconstruction<Geom_traits, TriangleRange, ConcurrencyTag> steps(pts, triangles, input_index, gt);
  put_points(steps);
  // Coordinates beyond 2^128 or below 2^-128 (a file in another unit): the pipeline runs on the
  // points scaled by a power of two (`exponent`, 0 otherwise), with the tolerances scaled alike,
  // and gives the points and the report's lengths back at the input's scale. The decisions are
  // then those taken on the soup at a moderate scale: squared tolerances and distances neither
  // overflow nor underflow (internal/coordinate_scale.h).
  const int exponent = moderate_scale_exponent_of<ConcurrencyTag>(steps.points());
  FT eps = resolve_tolerance<FT>(steps.points(), CGAL::Identity_property_map<typename Geom_traits::Point_3>(), np,
                                 exponent);
  if constexpr(has_vertex_tolerance_map<NamedParameters>()) {
    // Read once at the input index of every point (every point is its own input point here),
    // checked; the exact weld keeps them with the points. The report's tolerance is the largest.
    std::vector<FT> tolerances;
    read_vertex_tolerances<FT>(np, steps.points().size(), tolerances, "reconstruct_topology", exponent);
    eps = largest_tolerance(tolerances);
    steps.set_vertex_tolerances(std::move(tolerances));
  }
  std::optional<Gap_analysis> automatic;
  if constexpr(!CGAL::parameters::is_default_parameter<NamedParameters, internal_np::automatic_tolerance_t>::value) {
    if(choose_parameter(get_parameter(np, internal_np::automatic_tolerance), false)) {
      // (the analysis scales the soup on its own, and speaks of lengths at the input's scale)
      automatic = automatic_tolerance_analysis<ConcurrencyTag>(steps.points(), triangles, np, gt, exact_weld);
      eps = FT(std::ldexp(automatic->suggested_tolerance, exponent));
    }
  }
  if(exponent != 0) steps.scale(exponent);
  try {
    if(exact_weld == Exact_weld::TO_DO) steps.weld_exact_duplicates();
    const Small_features policy = small_features_policy(np);
    if(policy == Small_features::COLLAPSE) steps.flip_degenerate_triangles_away();
    steps.build_tables();
    with_user_visitor(np, [&](auto& visitor) {
      steps.weld_and_split_in_rounds(
        eps, choose_parameter(get_parameter(np, internal_np::maximum_number_of_rounds), std::size_t(8)),
        choose_parameter(get_parameter(np, internal_np::do_split_t_junctions), true), policy, visitor);
    });
    steps.measure_displacement();
    steps.finish(choose_parameter(get_parameter(np, internal_np::count_self_intersections), false));
  } catch(...) {
    if(exponent != 0) steps.scale(-exponent);
    throw;
  }
  if(exponent != 0) steps.scale(-exponent);
  Reconstruction_report report = steps.report();
  if(automatic) {
    report.automatic_tolerance = true;
    report.tolerance_verdict = automatic->verdict;
    report.tolerance_reasoning = automatic->reasoning;
  }
  return report;
}

/// writes output point `k` into element `k` of `points` through `pm`, from input element
/// `input_index[k] >= k` (the order is kept, so the elements read are not yet overwritten),
/// and resizes `points` to the output points.
template <class PointRange, class PointMap>
void move_output_points(PointRange& points, const PointMap& pm, const std::vector<std::uint32_t>& input_index)
{
  for(std::size_t k = 0; k < input_index.size(); ++k) {
    if(input_index[k] == k) continue;
    const auto from = points.begin() + static_cast<std::ptrdiff_t>(input_index[k]);
    const auto to = points.begin() + static_cast<std::ptrdiff_t>(k);
    put(pm, *to, get(pm, *from));
  }
  points.resize(input_index.size());
}

/// the pipeline on the soup (`points`, `triangles`) read through the point map of `np`, in
/// place: validated, repaired, and the output points written back into `points`. Points that
/// are already the traits' points in a `std::vector` read through the identity are moved into
/// the pipeline and back rather than copied (they come back if the tolerance is refused).
template <class ConcurrencyTag = CGAL::Sequential_tag, class PointRange, class TriangleRange, class NamedParameters>
Reconstruction_report reconstruct_soup_in_place(PointRange& points, TriangleRange& triangles, const NamedParameters& np,
                                                Exact_weld exact_weld)
{
  using PointMap = typename CGAL::GetPointMap<PointRange, NamedParameters>::type;
  using Geom_traits = Pipeline_geom_traits<PointMap, NamedParameters>;
  using Point = typename Geom_traits::Point_3;
  const PointMap pm =
    CGAL::parameters::choose_parameter<PointMap>(CGAL::parameters::get_parameter(np, CGAL::internal_np::point_map));
  const Geom_traits gt =
    CGAL::parameters::choose_parameter<Geom_traits>(CGAL::parameters::get_parameter(np, CGAL::internal_np::geom_traits));
  check_indexed_soup<ConcurrencyTag>(points, pm, triangles);
  std::vector<Point> pts;
  std::vector<std::uint32_t> input_index;
  if constexpr(std::is_same<PointRange, std::vector<Point>>::value &&
               std::is_same<PointMap, CGAL::Identity_property_map<Point>>::value) {
    Reconstruction_report report;
    try {
      report = reconstruct_soup<ConcurrencyTag>([&](auto& steps) { steps.take_points(points); }, triangles, np, gt, pts,
                                                input_index, exact_weld);
    } catch(const Invalid_input&) {
      if(points.empty()) points.swap(pts);
      throw;
    }
    points.swap(pts);
    return report;
  } else {
    const Reconstruction_report report =
      reconstruct_soup<ConcurrencyTag>([&](auto& steps) { steps.copy_points(points, pm); }, triangles, np, gt, pts,
                                       input_index, exact_weld);
    move_output_points(points, pm, input_index);
    return report;
  }
}

/// `reconstruct_topology(points, triangles, np)` on a soup whose points are already exactly
/// welded and whose triangles have three distinct corners each, as `index_triangles()` and
/// `IO::read_triangle_soup()` return them: the exact weld is not run again (the report's
/// `exact_duplicates` and `collapsed_triangles` are 0). The soup is validated as by the public
/// function; that no two points are equal is trusted, not checked.
template <class ConcurrencyTag = CGAL::Sequential_tag, class PointRange, class TriangleRange,
          class NamedParameters = CGAL::parameters::Default_named_parameters>
Reconstruction_report reconstruct_exactly_welded_soup(PointRange& points, TriangleRange& triangles,
                                                      const NamedParameters& np = CGAL::parameters::default_values())
{
  return reconstruct_soup_in_place<ConcurrencyTag>(points, triangles, np, Exact_weld::DONE);
}

/// adds what writing into a FaceGraph did to `report`.
inline void add_face_graph_output_report(const Face_graph_output_report& written, Reconstruction_report& report)
{
  copy_orientation_counts(written, report);
}

/// empties a FaceGraph, keeping its property maps (a vertex point map given by the caller
/// stays valid) where the graph can.
template <class PolygonMesh>
auto clear_keeping_property_maps(PolygonMesh& mesh, int) -> decltype(mesh.clear_without_removing_property_maps(), void())
{
  mesh.clear_without_removing_property_maps();
}
template <class PolygonMesh>
void clear_keeping_property_maps(PolygonMesh& mesh, long)
{
  CGAL::clear(mesh);
}

} // namespace internal

/// \ingroup PkgSoupTopologyPipeline
/// \brief repairs an indexed triangle soup in place: merges exactly equal points, builds the
/// adjacency tables, then welds duplicate vertices within the tolerance (`snap_vertices()`) and
/// splits T-junctions (`split_t_junctions()`) in rounds until a round changes nothing (a split
/// can expose a new duplicate and a weld a new T-junction: Milenkovic's normalisation). Finally
/// the points no triangle uses are removed.
///
/// Triangles that the exact weld collapses (two equal corners) are removed and counted. The
/// output points are a subset of the input points (no coordinate is constructed), in input order.
///
/// The points are read once through the point map into a `std::vector` of `geom_traits::Point_3`
/// and the pipeline runs on that copy; at the end output point `k` is written into element `k`
/// of `points` through the point map (the value read from the input element it comes from, so
/// its coordinates are exactly the input ones, whatever the traits), and `points` is resized to
/// the output points. Only the point map is written: other data held by the elements (another
/// property of a `CGAL::Point_set_3`, say) is not moved with the points.
///
/// With `CGAL::Parallel_tag` the data-parallel steps (exact weld, tables, candidate searches) run
/// on TBB's threads; the output and the report are the same on any number of threads
/// (`doc/Soup_topology/Parallel.md`).
///
/// **Scale.** Points whose largest coordinate lies beyond 2^128 or below 2^-128 (a file in
/// another unit) are repaired scaled by the power of two that brings it into [1, 2), with the
/// tolerances scaled alike, then scaled back; the report's lengths are given at the input's
/// scale. A power of two changes only exponents: the decisions are those taken on the soup at a
/// moderate scale, where squared tolerances and distances neither overflow nor underflow
/// (`internal/coordinate_scale.h`).
///
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` (the default), `CGAL::Parallel_tag` (needs TBB)
///         or `CGAL::Parallel_if_available_tag`
/// \tparam PointRange a range of elements with `size()` and `resize()` whose iterators are
///         random access, e.g. `std::vector<Point_3>`, `std::vector<std::array<double, 3>>` (with a
///         point map) or `CGAL::Point_set_3` (with its `point_map()`)
/// \tparam TriangleRange a `std::vector`-like container of triangles (3 indices each)
/// \param points the points of the soup, replaced by the output points
/// \param triangles the triangles of the soup, indices into `points`, repaired in place
/// \param np an optional sequence of named parameters among the ones listed below
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{point_map} \cgalParamDescription{the point of an element of `points`}
///     \cgalParamType{a model of `ReadWritePropertyMap` whose key is the value type of `PointRange`
///     and whose value is a point of a CGAL kernel} \cgalParamDefault{`CGAL::Identity_property_map`} \cgalParamNEnd
///   \cgalParamNBegin{geom_traits} \cgalParamDescription{the predicates and the point type of the
///     pipeline (the points are converted to its `Point_3`)} \cgalParamType{a model of `SoupTopologyTraits`}
///     \cgalParamDefault{the kernel of the point type} \cgalParamNEnd
///   \cgalParamNBegin{snapping_tolerance} \cgalParamDescription{the distance within which vertices are
///     welded and T-junctions split} \cgalParamType{`geom_traits::FT`} \cgalParamDefault{0: exact
///     duplicates only} \cgalParamNEnd
///   \cgalParamNBegin{relative_tolerance} \cgalParamType{`double`} \cgalParamDescription{the tolerance as a
///     fraction of the bounding-box diagonal} \cgalParamNEnd
///   \cgalParamNBegin{automatic_tolerance} \cgalParamDescription{if `true`, the tolerance is the one
///     `analyze_gaps()` suggests for the soup (0 for a soup without border or without gap to close);
///     the report gives it, the verdict and the reasoning (`Reconstruction_report::automatic_tolerance`,
///     `tolerance_verdict`, `tolerance_reasoning`). When the analysis suggests none (its gaps and
///     features overlap) or the border is too crowded to analyse, `Invalid_input` is thrown and the
///     soup is unchanged: the caller gives a tolerance by hand. Not with `snapping_tolerance` or
///     `relative_tolerance`. `geom_traits` then also needs `Segment_3`, `Construct_segment_3` and
///     `Compute_squared_distance_3`.} \cgalParamType{`bool`} \cgalParamDefault{`false`} \cgalParamNEnd
///   \cgalParamNBegin{vertex_tolerance_map} \cgalParamDescription{a tolerance per point instead of one:
///     two vertices u and v are welded only when |uv| <= min(t_u, t_v), a vertex c is split into a
///     border edge [a,b] only when its distance to it is <= min(t_c, t_a, t_b) (see `snap_vertices()`
///     and `split_t_junctions()`); no point moves farther than its own tolerance. The map is read once,
///     at the index of every element of `points`; exactly equal points take the smallest of their
///     tolerances. `Reconstruction_report::tolerance` is then the largest tolerance of the map.
///     `per_part_vertex_tolerances()` makes one from `analyze_gaps_per_part()`. Exclusive with
///     `snapping_tolerance`, `relative_tolerance` and `automatic_tolerance`.} \cgalParamType{a
///     `ReadablePropertyMap` from the index of a point (`std::size_t`) to a finite number >= 0
///     convertible to `geom_traits::FT`} \cgalParamDefault{none: one tolerance} \cgalParamNEnd
///   \cgalParamNBegin{visitor} \cgalParamDescription{told every weld and every refused weld of every
///     round, with the indices of `points` (a point merged by the exact weld is known by the first
///     of the equal points). If it also has the member functions of `Default_split_visitor`, it is
///     told every split, refused split and ambiguous T-junction of every round; if it has
///     `on_ambiguous_site(std::size_t vertex)`, it is told once, after the rounds, each ambiguous
///     site of the weld (`Snap_report::ambiguous_sites` over all rounds, each once; the vertex is the
///     lexicographically smallest point of the site). Same indices. A visitor without these members
///     costs nothing more.} \cgalParamType{a model of `SnapVisitor`, a copy or `std::ref(v)`}
///     \cgalParamDefault{`Default_snap_visitor`} \cgalParamNEnd
///   \cgalParamNBegin{maximum_number_of_rounds} \cgalParamDescription{the most weld/split rounds run}
///     \cgalParamType{`std::size_t`} \cgalParamDefault{8} \cgalParamNEnd
///   \cgalParamNBegin{do_split_t_junctions} \cgalParamDescription{whether T-junctions are split (welding only
///     otherwise)} \cgalParamType{`bool`} \cgalParamDefault{`true`} \cgalParamNEnd
///   \cgalParamNBegin{small_features} \cgalParamDescription{what the weld does with two vertices of one
///     triangle within the tolerance: merge them and remove the triangles that collapse (`COLLAPSE`),
///     or refuse the merge and report the site as ambiguous (`REFUSE`); see `snap_vertices()`}
///     \cgalParamType{`Soup_topology::Small_features`} \cgalParamDefault{`Small_features::COLLAPSE`} \cgalParamNEnd
///   \cgalParamNBegin{count_self_intersections} \cgalParamDescription{count the pairs of output
///     triangles that intersect beyond a shared vertex or edge (`geom_traits` then also needs
///     `Triangle_3`, `Do_intersect_3`, `Coplanar_3`)} \cgalParamType{`bool`} \cgalParamDefault{`false`} \cgalParamNEnd
/// \cgalNamedParamsEnd
/// \returns a `Reconstruction_report`.
/// \throws Invalid_input on an index out of range, a face that is not a triangle, a repeated index
///         in a face, a non-finite coordinate or an invalid tolerance (also in `vertex_tolerance_map`, or a
///         map given with another tolerance parameter), or when `automatic_tolerance(true)`
///         finds no tolerance; `points` and `triangles` are unchanged then.
template <class ConcurrencyTag = CGAL::Sequential_tag, class PointRange, class TriangleRange,
          class NamedParameters = CGAL::parameters::Default_named_parameters,
          std::enable_if_t<internal::is_named_parameters<NamedParameters>::value &&
                             !internal::is_named_parameters<std::remove_const_t<TriangleRange>>::value,
                           int> = 0>
Reconstruction_report reconstruct_topology(PointRange& points, TriangleRange& triangles,
                                           const NamedParameters& np = CGAL::parameters::default_values())
{
  return internal::reconstruct_soup_in_place<ConcurrencyTag>(points, triangles, np, internal::Exact_weld::TO_DO);
}

/// \ingroup PkgSoupTopologyPipeline
/// \brief repairs a copy of the soup with `reconstruct_topology(points, triangles, np_soup)` and
/// writes the result into `mesh` with `triangle_soup_to_face_graph()`; the report gathers both.
/// `points` and `triangles` are not changed. The points written are those of `points` (read
/// through `point_map`), so they must convert to the point type of `mesh`.
///
/// \tparam ConcurrencyTag as for the function above
/// \param points the points of the soup (not changed)
/// \param triangles the triangles of the soup, indices into `points` (not changed)
/// \param mesh receives the repaired surface (added to what it holds)
/// \param np_soup the parameters of `reconstruct_topology()` for the soup (`point_map` may be
///        a readable map only)
/// \param np_mesh parameters for the mesh: `vertex_point_map`
template <class ConcurrencyTag = CGAL::Sequential_tag, class PointRange, class TriangleRange, class PolygonMesh,
          class NamedParametersSoup = CGAL::parameters::Default_named_parameters,
          class NamedParametersMesh = CGAL::parameters::Default_named_parameters,
          std::enable_if_t<!internal::is_named_parameters<PolygonMesh>::value, int> = 0>
Reconstruction_report reconstruct_topology(const PointRange& points, const TriangleRange& triangles, PolygonMesh& mesh,
                                           const NamedParametersSoup& np_soup = CGAL::parameters::default_values(),
                                           const NamedParametersMesh& np_mesh = CGAL::parameters::default_values())
{
  using Point_map = typename CGAL::GetPointMap<PointRange, NamedParametersSoup>::const_type;
  using Geom_traits = internal::Pipeline_geom_traits<Point_map, NamedParametersSoup>;
  using Point = typename boost::property_traits<Point_map>::value_type;
  const Point_map pm =
    CGAL::parameters::choose_parameter<Point_map>(CGAL::parameters::get_parameter(np_soup, CGAL::internal_np::point_map));
  const Geom_traits gt =
    CGAL::parameters::choose_parameter<Geom_traits>(CGAL::parameters::get_parameter(np_soup, CGAL::internal_np::geom_traits));
  internal::check_indexed_soup(points, pm, triangles);
  std::vector<std::array<std::size_t, 3>> tris;
  tris.reserve(triangles.size());
  for(const auto& f : triangles) tris.push_back(internal::triangle_indices(f));
  std::vector<typename Geom_traits::Point_3> pts;
  std::vector<std::uint32_t> input_index;
  Reconstruction_report report = internal::reconstruct_soup<ConcurrencyTag>(
    [&](auto& steps) { steps.copy_points(points, pm); }, tris, np_soup, gt, pts, input_index);
  std::vector<Point> out;
  out.reserve(input_index.size());
  for(const std::size_t i : input_index) out.push_back(get(pm, *(points.begin() + static_cast<std::ptrdiff_t>(i))));
  const Face_graph_output_report written = triangle_soup_to_face_graph(out, tris, mesh, np_mesh);
  internal::add_face_graph_output_report(written, report);
  return report;
}

/// \ingroup PkgSoupTopologyPipeline
/// \brief repairs a FaceGraph in place: its faces become a soup (the detour
/// `CGAL::Polygon_mesh_processing::polygon_mesh_to_polygon_soup()`, faces of more than three
/// vertices cut into triangles by ear clipping), the soup is repaired by
/// `reconstruct_topology(points, triangles, np)` and written back into `mesh` (emptied first)
/// with `triangle_soup_to_face_graph()`. The points written are those of the mesh, unchanged;
/// vertices no face uses are removed.
///
/// Faces are cut along the plane most parallel to their Newell normal; a corner at which no ear
/// can be cut (a face that folds onto itself in that projection) leaves its triangles out and is
/// counted in `Reconstruction_report::unclipped_corners`.
///
/// \tparam PolygonMesh a model of `MutableFaceGraph` (e.g. `CGAL::Surface_mesh`, `CGAL::Polyhedron_3`)
/// \param mesh the mesh, repaired in place
/// \param np an optional sequence of named parameters among the ones listed below
///
/// \cgalNamedParamsBegin
///   \cgalParamNBegin{vertex_point_map} \cgalParamDescription{the point of a vertex, read and
///     then written for the new vertices} \cgalParamType{a model of `ReadWritePropertyMap` from
///     `boost::graph_traits<PolygonMesh>::vertex_descriptor` to a point of a CGAL kernel}
///     \cgalParamDefault{`boost::get(CGAL::vertex_point, mesh)`} \cgalParamNEnd
///   \cgalParamNBegin{geom_traits, snapping_tolerance, relative_tolerance, vertex_tolerance_map, visitor,
///     maximum_number_of_rounds, do_split_t_junctions, small_features, count_self_intersections}
///     \cgalParamDescription{as for the soup; the visitor's indices and the keys of the tolerance map
///     are those of the vertices in the order of `vertices(mesh)`} \cgalParamNEnd
/// \cgalNamedParamsEnd
/// \returns a `Reconstruction_report`.
/// \throws Invalid_input on a non-finite coordinate or an invalid tolerance; `mesh` is unchanged then.
template <class PolygonMesh, class NamedParameters = CGAL::parameters::Default_named_parameters,
          std::enable_if_t<internal::is_named_parameters<NamedParameters>::value &&
                             !internal::is_named_parameters<PolygonMesh>::value,
                           int> = 0>
Reconstruction_report reconstruct_topology(PolygonMesh& mesh, const NamedParameters& np = CGAL::parameters::default_values())
{
  using Vertex_point_map = typename CGAL::GetVertexPointMap<PolygonMesh, NamedParameters>::type;
  using Point = typename boost::property_traits<Vertex_point_map>::value_type;
  using Geom_traits = internal::Pipeline_geom_traits<CGAL::Identity_property_map<Point>, NamedParameters>;
  const Vertex_point_map vpm = CGAL::parameters::choose_parameter(
    CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point), get_property_map(CGAL::vertex_point, mesh));
  const Geom_traits gt =
    CGAL::parameters::choose_parameter<Geom_traits>(CGAL::parameters::get_parameter(np, CGAL::internal_np::geom_traits));

  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  CGAL::Polygon_mesh_processing::polygon_mesh_to_polygon_soup(mesh, points, polygons,
                                                              CGAL::parameters::vertex_point_map(vpm));
  std::vector<std::array<std::size_t, 3>> triangles;
  triangles.reserve(polygons.size());
  std::size_t polygons_cut = 0, unclipped = 0;
  for(const std::vector<std::size_t>& polygon : polygons) {
    if(polygon.size() == 3) {
      triangles.push_back({polygon[0], polygon[1], polygon[2]});
    } else if(polygon.size() > 3) {
      ++polygons_cut;
      unclipped += internal::triangulate_polygon(points, polygon, triangles);
    }
  }
  internal::check_indexed_soup(points, CGAL::Identity_property_map<Point>(), triangles);
  std::vector<typename Geom_traits::Point_3> pts;
  std::vector<std::uint32_t> input_index;
  Reconstruction_report report = internal::reconstruct_soup(
    [&](auto& steps) { steps.copy_points(points, CGAL::Identity_property_map<Point>()); }, triangles, np, gt, pts,
    input_index);
  report.triangulated_polygons = polygons_cut;
  report.unclipped_corners = unclipped;
  std::vector<Point> out;
  out.reserve(input_index.size());
  for(const std::size_t i : input_index) out.push_back(points[i]);
  internal::clear_keeping_property_maps(mesh, 0);
  const Face_graph_output_report written =
    triangle_soup_to_face_graph(out, triangles, mesh, CGAL::parameters::vertex_point_map(vpm));
  internal::add_face_graph_output_report(written, report);
  return report;
}

} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_RECONSTRUCT_TOPOLOGY_H
