// Copyright (c) 2024 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// A Morton-addressed octree over a point range, with exact proximity queries.

#ifndef SOUP_TOPOLOGY_OCTREE_H
#define SOUP_TOPOLOGY_OCTREE_H

#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/internal/Octree_morton.h>
#include <Soup_topology/internal/octree_distance_filters.h>
#include <Soup_topology/internal/parallel.h>
#include <Soup_topology/internal/uninitialized_vector.h>
#include <Soup_topology/parameters.h>

#include <CGAL/Iterator_range.h>
#include <CGAL/Named_function_parameters.h>
#include <CGAL/property_map.h>
#include <CGAL/number_utils.h>
#include <CGAL/tags.h>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <numeric>
#include <memory>
#include <optional>
#include <stdexcept>
#include <type_traits>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

namespace Soup_topology {

/// \ingroup PkgSoupTopologyOctree
/// The two ways of `Octree::vertices_near_segment()` to choose the boxes whose points are tested.
enum class Segment_query_strategy
{
  /// the patent's equations (22)-(27): every leaf whose integer index range meets the index-space
  /// box of the segment grown by the radius.
  INDEX_SPACE_BOX,
  /// the patent's equations (28)-(29): only the boxes that meet the radius-neighbourhood of the
  /// segment itself (a box grown by the radius must be crossed by the segment).
  NEIGHBORHOOD_CULLING
};

/// \ingroup PkgSoupTopologyOctree
/// The order of the indices that the joins of `Octree` (`for_each_neighborhood()`,
/// `for_each_segment_neighborhood()` and their concurrent versions) hand to their callback.
enum class Neighborhood_order
{
  /// in increasing order (the default)
  INCREASING,
  /// in an order fixed by the tree, the same on any number of threads, but not sorted: for a
  /// caller whose use of a neighbourhood does not depend on its order (a minimum, a count), which
  /// then does not pay for the sort
  TREE
};

/// \ingroup PkgSoupTopologyOctree
/// \brief a Morton-addressed octree over the points of a random-access range, answering the two
/// proximity questions of snapping (vertex near vertex, vertex near segment) exactly.
///
/// The coordinates are normalised to the workspace cube (the bounding box of the points, made
/// cubic), scaled by `2^n` (`n` the maximum depth) and rounded down: every point keeps its integer
/// address, whose Morton interleaving is the path from the root to its leaf. A box holding more
/// than the bucket capacity is split into 8 equal children.
///
/// **Layout.** The tree is pointer-free and linear: the points are stored once, sorted by
/// (Morton code, index), so that every node of the tree is a contiguous index range of that
/// array; nodes are 16-byte records in one vector, the 8 children of a node consecutive. We chose
/// this over a pointer-based tree (CGAL's `Orthtree`) because building it is one sort plus a
/// binary-search pass (no per-node allocation), it is compact (about 60 bytes per point for a
/// double kernel), the points of a leaf are contiguous in memory (the leaf scan is the hot loop of
/// every query), and a Morton-prefix range is exactly the shard of a spatial partition.
///
/// **Exactness.** Every final decision is taken by the kernel: a point `p` is within `radius`
/// of `q` if `Compare_squared_distance_3()(q, p, radius*radius) != LARGER`, and within `radius`
/// of the segment `[a,b]` if `Compare_squared_distance_3()(p, Segment_3(a,b), radius*radius) !=
/// LARGER` (`radius*radius` evaluated in `FT`). With `Exact_predicates_inexact_constructions_kernel`
/// and `Exact_predicates_exact_constructions_kernel` these answers are exact for the input
/// coordinates. The box pruning and a per-point prefilter run in `double` with margins larger than
/// every rounding error involved, so they may keep a candidate too many but never lose one; with
/// double coordinates, a point whose distance computed in `double` is below the radius by more
/// than every rounding error is accepted without the kernel (it would say the same).
///
/// \tparam GeomTraits a CGAL Kernel (`Point_3`, `Segment_3`, `FT`, `Compare_squared_distance_3`,
///         `Compare_distance_3`, `Equal_3`, `Construct_segment_3`)
/// \tparam PointMap a model of `ReadablePropertyMap` from the value type of the range to `Point_3`
///
/// `snap_vertices()` and `split_t_junctions()` use this class directly; it is not a template
/// parameter of theirs.
template <typename GeomTraits,
          typename PointMap = CGAL::Identity_property_map<typename GeomTraits::Point_3>>
class Octree
{
public:
  using Geom_traits = GeomTraits;
  using Point_map = PointMap;
  using FT = typename Geom_traits::FT;
  using Point_3 = typename Geom_traits::Point_3;
  using Segment_3 = typename Geom_traits::Segment_3;

  /// index of a node of the tree (the root is 0)
  using Node_index = std::uint32_t;
  /// the integer address of a point or of a box at the maximum depth, one coordinate per axis
  using Address = std::array<std::uint32_t, 3>;
  /// the indices of the points of a node (into the range given at construction)
  using Point_index_range = CGAL::Iterator_range<const std::uint32_t*>;

  static constexpr std::size_t default_bucket_capacity = 16;
  static constexpr std::size_t default_maximum_depth = 21;
  static constexpr std::size_t largest_maximum_depth = 21;

  /// \name Construction
  /// @{

  /// builds the tree over `points` with the default parameters.
  /// \tparam PointRange a random-access range whose values `point_map` maps to `Point_3`
  /// \param points the points to index (copied: the range may be discarded afterwards)
  /// \param point_map the map from the values of `points` to `Point_3`
  /// \param gt the kernel that takes every decision
  /// \throw Invalid_input if a coordinate is not finite (the message names the point)
  template <typename PointRange>
  explicit Octree(const PointRange& points, PointMap point_map = PointMap(),
                  const Geom_traits& gt = Geom_traits())
    : gt_(gt)
  {
    build(points, point_map, default_bucket_capacity, default_maximum_depth);
  }

  /// builds the tree over `points` with the default parameters, on TBB's threads with
  /// `CGAL::Parallel_tag` (or `CGAL::Parallel_if_available_tag` with TBB) when the coordinates
  /// are stored as `double`: the box, the Morton codes, their sort and the copy of the points in
  /// their order run in parallel, the nodes are split on one thread. The tree is the same as the
  /// sequential one, on any number of threads.
  /// \tparam ConcurrencyTag `CGAL::Sequential_tag`, `CGAL::Parallel_tag` or
  ///         `CGAL::Parallel_if_available_tag` (given as the last argument)
  template <typename PointRange, typename ConcurrencyTag>
  Octree(const PointRange& points, PointMap point_map, const Geom_traits& gt, ConcurrencyTag)
    : gt_(gt)
  {
    build<ConcurrencyTag>(points, point_map, default_bucket_capacity, default_maximum_depth);
  }

  /// builds the tree over `points`.
  ///
  /// \tparam PointRange a random-access range whose values `point_map` maps to `Point_3`
  /// \param points the points to index (copied: the range may be discarded afterwards)
  /// \param np a sequence of named parameters among the ones listed below
  ///
  /// \cgalNamedParamsBegin
  ///   \cgalParamNBegin{bucket_capacity} \cgalParamDescription{the largest number of points of a
  ///     leaf, unless they share one address or the maximum depth is reached}
  ///     \cgalParamType{`std::size_t`, at least 1} \cgalParamDefault{16} \cgalParamNEnd
  ///   \cgalParamNBegin{maximum_depth} \cgalParamDescription{the depth of the deepest leaf, and the
  ///     number of bits per axis of an address} \cgalParamType{`std::size_t`, in [1,21]}
  ///     \cgalParamDefault{21} \cgalParamNEnd
  ///   \cgalParamNBegin{segment_query_strategy} \cgalParamDescription{the boxes tested by
  ///     `vertices_near_segment()` when no strategy is passed to it}
  ///     \cgalParamType{`Segment_query_strategy`}
  ///     \cgalParamDefault{`Segment_query_strategy::INDEX_SPACE_BOX` (the faster on short segments)} \cgalParamNEnd
  ///   \cgalParamNBegin{point_map} \cgalParamDescription{the map from the values of `points` to
  ///     `Point_3`} \cgalParamType{`PointMap`} \cgalParamDefault{`PointMap()`} \cgalParamNEnd
  ///   \cgalParamNBegin{geom_traits} \cgalParamDescription{the kernel that takes every decision}
  ///     \cgalParamType{`GeomTraits`} \cgalParamDefault{`GeomTraits()`} \cgalParamNEnd
  /// \cgalNamedParamsEnd
  ///
  /// \throw Invalid_input if a coordinate is not finite (the message names the point) or a
  ///        parameter is out of range
  template <typename PointRange, typename T, typename Tag, typename Base>
  Octree(const PointRange& points, const CGAL::Named_function_parameters<T, Tag, Base>& np)
    : Octree(points, np, CGAL::Sequential_tag())
  {
  }

  /// builds the tree over `points` with the named parameters `np` (see above), in parallel as the
  /// constructor with a `ConcurrencyTag` above: the same tree.
  template <typename PointRange, typename T, typename Tag, typename Base, typename ConcurrencyTag>
  Octree(const PointRange& points, const CGAL::Named_function_parameters<T, Tag, Base>& np, ConcurrencyTag)
    : gt_(CGAL::parameters::choose_parameter(
          CGAL::parameters::get_parameter(np, CGAL::internal_np::geom_traits), Geom_traits()))
  {
    using CGAL::parameters::choose_parameter;
    using CGAL::parameters::get_parameter;
    const PointMap pm =
      choose_parameter(get_parameter(np, CGAL::internal_np::point_map), PointMap());
    const std::size_t capacity = static_cast<std::size_t>(
      choose_parameter(get_parameter(np, internal_np::bucket_capacity), default_bucket_capacity));
    const std::size_t depth = static_cast<std::size_t>(
      choose_parameter(get_parameter(np, internal_np::maximum_depth), default_maximum_depth));
    strategy_ = choose_parameter(get_parameter(np, internal_np::segment_query_strategy),
                                 Segment_query_strategy::INDEX_SPACE_BOX);
    build<ConcurrencyTag>(points, pm, capacity, depth);
  }

  /// @}

  /// \name Queries
  /// Each query throws `Invalid_input` if `radius` is negative or NaN.
  /// @{

  /// returns the index of the point closest to `q` among those within `radius` of `q`
  /// (the smallest index among equally close points), or nothing.
  /// \param q the query point
  /// \param radius the largest distance from `q`
  std::optional<std::size_t> nearest_vertex(const Point_3& q, const FT& radius) const
  {
    check_radius(radius);
    if(empty())
      return std::nullopt;
    const FT r2 = radius * radius;
    const Query_point qa = approximate(q);
    double bound = radius_bound(r2, qa.err);
    double bound2 = bound * bound;

    typename Geom_traits::Compare_squared_distance_3 compare_sq =
      gt_.compare_squared_distance_3_object();
    typename Geom_traits::Compare_distance_3 compare_dist = gt_.compare_distance_3_object();

    std::uint32_t best = npos;  // sorted position of the best point so far
    const auto near_box = [&](const Frame& f, double& d2) {
      d2 = box_point_squared_distance(f, qa.c);
      return !(d2 > bound2);
    };
    traverse<Child_order::NEAREST_FIRST>(near_box, [&](const Frame&, const Node& nd) {
      for(std::uint32_t k = nd.begin; k != nd.end; ++k)
      {
        const double d2 = point_squared_distance(k, qa.c);
        if(d2 > bound2)
          continue;
        bool better;
        if(best == npos)
          better = compare_sq(q, points_[k], r2) != CGAL::LARGER;
        else
        {
          const CGAL::Comparison_result c = compare_dist(q, points_[k], points_[best]);
          better = (c == CGAL::SMALLER) || (c == CGAL::EQUAL && ids_[k] < ids_[best]);
        }
        if(better)
        {
          best = k;
          const double b = (std::sqrt(d2) + 2 * (margin_ + qa.err)) * (1 + 1e-12);
          if(b < bound)
          {
            bound = b;
            bound2 = b * b;
          }
        }
      }
    }, frame_holding_box(qa.c, qa.c, bound));
    if(best == npos)
      return std::nullopt;
    return std::optional<std::size_t>(ids_[best]);
  }

  /// writes to `out`, in increasing order, the index of every point within `radius` of `q`.
  /// \tparam OutputIterator an output iterator accepting `std::size_t`
  /// \param q the query point
  /// \param radius the largest distance from `q`
  /// \param out where the indices are written
  /// \return `out` past the last index written
  template <typename OutputIterator>
  OutputIterator vertices_near_point(const Point_3& q, const FT& radius, OutputIterator out) const
  {
    Found_indices found;
    unsorted_vertices_near_point(q, radius, found);
    std::sort(found.begin(), found.end());
    return std::copy(found.begin(), found.end(), out);
  }

  /// the number of points within `radius` of `q`: the size of the answer of
  /// `vertices_near_point()`, found by the same decisions, without sorting the indices.
  /// \param q the query point
  /// \param radius the largest distance from `q`
  std::size_t number_of_vertices_near_point(const Point_3& q, const FT& radius) const
  {
    Found_indices found;
    unsorted_vertices_near_point(q, radius, found);
    return found.size();
  }

  /// the number of points within `radius` of the closed segment `[a,b]`: the size of the answer
  /// of `vertices_near_segment()`, found by the same decisions, without sorting the indices.
  /// \param a the source of the segment
  /// \param b the target of the segment (`a == b` is allowed)
  /// \param radius the largest distance from the segment
  std::size_t number_of_vertices_near_segment(const Point_3& a, const Point_3& b, const FT& radius) const
  {
    return unsorted_vertices_near_segment(a, b, radius, strategy_).size();
  }

  /// calls `callback(i, near)` for every point `i`, in Morton order, with `near` the indices of
  /// the points within `radius` of it (itself included), in increasing order: the answers of
  /// `vertices_near_point(point i, radius)` for all points at once (a self-join, as welding
  /// needs). The candidates are gathered once per leaf: the points in the box of the leaf's
  /// points grown by the radius, found from the deepest node that holds that box rather than
  /// from the root; each point of the leaf then keeps the candidates within `radius` of it by
  /// the decisions of `vertices_near_point()`.
  /// \tparam Callback callable as `callback(std::size_t, const std::vector<std::size_t>&)`
  /// \param radius the largest distance between neighbors
  /// \param callback called once per point
  /// \param order `Neighborhood_order::TREE` hands `near` over unsorted
  template <typename Callback>
  void for_each_neighborhood(const FT& radius, Callback callback,
                             Neighborhood_order order = Neighborhood_order::INCREASING) const
  {
    for_each_neighborhood<CGAL::Sequential_tag>(radius, callback, order);
  }

  /// the same; with `CGAL::Parallel_tag` (and coordinates stored as `double`) the neighborhoods
  /// are found on TBB's threads, a batch of leaves at a time, and `callback` is called on the
  /// calling thread, in Morton order, with the same arguments as the sequential search.
  /// \tparam ConcurrencyTag `CGAL::Sequential_tag`, `CGAL::Parallel_tag` (needs TBB) or
  ///         `CGAL::Parallel_if_available_tag`
  /// \tparam Callback callable as `callback(std::size_t, const std::vector<std::size_t>&)`
  /// \param radius the largest distance between neighbors
  /// \param callback called once per point
  /// \param order `Neighborhood_order::TREE` hands `near` over unsorted
  template <typename ConcurrencyTag, typename Callback>
  void for_each_neighborhood(const FT& radius, Callback callback,
                             Neighborhood_order order = Neighborhood_order::INCREASING) const
  {
    check_radius(radius);
    if(empty())
      return;
    const FT r2 = radius * radius;
    if constexpr(internal::runs_in_parallel<ConcurrencyTag>() && double_coordinates)
    {
      // The leaves in traversal (Morton) order, cut into groups of about 2048 points; a batch of
      // groups is searched in parallel, each group into its own buffer, then the callbacks of the
      // batch are made in order.
      const Leaf_groups leaf_groups =
        leaves_in_groups<ConcurrencyTag>([](const Node& nd) { return std::size_t(nd.end - nd.begin); });
      constexpr std::size_t batch = 64;
      const std::size_t groups = leaf_groups.size();
      struct Found
      {
        std::vector<std::size_t> near;    // the neighborhoods one after the other
        std::vector<std::size_t> end;     // where the neighborhood of each point ends
        std::vector<std::uint32_t> point; // the points, in order
      };
      std::vector<Found> found(std::min(batch, groups));
      std::vector<std::size_t> one;
      for(std::size_t first = 0; first < groups; first += batch)
      {
        const std::size_t last = std::min(groups, first + batch);
        internal::for_each_block<ConcurrencyTag>(last - first, 1, [&](std::size_t g, std::size_t, std::size_t) {
          Found& out = found[g];
          out.near.clear();
          out.end.clear();
          out.point.clear();
          Join_scratch scratch;
          for(std::size_t l = leaf_groups.begin[first + g]; l != leaf_groups.begin[first + g + 1]; ++l)
            leaf_neighborhoods(nodes_[leaf_groups.leaves[l].node], r2, scratch,
                               [&](std::uint32_t k, const std::vector<std::size_t>& near) {
                                 out.near.insert(out.near.end(), near.begin(), near.end());
                                 out.end.push_back(out.near.size());
                                 out.point.push_back(k);
                               }, order);
        });
        for(std::size_t g = 0; g < last - first; ++g)
        {
          const Found& in = found[g];
          for(std::size_t j = 0, begin = 0; j < in.point.size(); begin = in.end[j], ++j)
          {
            one.assign(in.near.begin() + static_cast<std::ptrdiff_t>(begin),
                       in.near.begin() + static_cast<std::ptrdiff_t>(in.end[j]));
            callback(std::size_t(ids_[in.point[j]]), static_cast<const std::vector<std::size_t>&>(one));
          }
        }
      }
      return;
    }
    (void)internal::runs_in_parallel<ConcurrencyTag>();
    Join_scratch scratch;
    traverse([](const Frame&, double&) { return true; }, [&](const Frame&, const Node& nd) {
      leaf_neighborhoods(nd, r2, scratch, [&](std::uint32_t k, const std::vector<std::size_t>& near) {
        callback(std::size_t(ids_[k]), near);
      }, order);
    });
  }

  /// writes to `out`, in increasing order, the index of every point within `radius` of the
  /// closed segment `[a,b]`, choosing the candidate boxes with `strategy`.
  /// \tparam OutputIterator an output iterator accepting `std::size_t`
  /// \param a the source of the segment
  /// \param b the target of the segment (`a == b` is allowed)
  /// \param radius the largest distance from the segment
  /// \param out where the indices are written
  /// \param strategy how the candidate boxes are chosen (the answer is the same)
  /// \return `out` past the last index written
  template <typename OutputIterator>
  OutputIterator vertices_near_segment(const Point_3& a, const Point_3& b, const FT& radius,
                                       OutputIterator out, Segment_query_strategy strategy) const
  {
    std::vector<std::size_t> found = unsorted_vertices_near_segment(a, b, radius, strategy);
    std::sort(found.begin(), found.end());
    return std::copy(found.begin(), found.end(), out);
  }

  /// same as above with the strategy chosen at construction
  /// (`Segment_query_strategy::INDEX_SPACE_BOX` by default: the faster one for the short segments
  /// of snapping, see the manual).
  /// \param a the source of the segment
  /// \param b the target of the segment
  /// \param radius the largest distance from the segment
  /// \param out where the indices are written
  template <typename OutputIterator>
  OutputIterator vertices_near_segment(const Point_3& a, const Point_3& b, const FT& radius,
                                       OutputIterator out) const
  {
    return vertices_near_segment(a, b, radius, out, strategy_);
  }

  /// calls `callback(s, near)` for every segment `s` of `segments`, whose ends are points of
  /// the tree (`segments[s][0]` and `segments[s][1]`, indices into the range given at
  /// construction), with `near` the indices of the points within `radius` of the closed segment
  /// between them, in increasing order: the answers of `vertices_near_segment()` for all the
  /// segments at once, with the strategy chosen at construction. The segments are visited in
  /// the Morton order of their first ends (the segments of one first end in the order of
  /// `segments`). The segments of one leaf that are short beside it (the box of their
  /// candidates no wider than the leaf's cell), as the border edges of a soup are against a tree
  /// of their ends, share their candidates: the points of the union of their boxes, gathered by
  /// one descent, each then tested against each segment. The other segments, and all those of a
  /// leaf whose union holds a crowd, are queried one by one, each from the smallest box around the
  /// leaf of its first end that holds the segment grown by the radius, not from the root. The
  /// decisions are the same as in `vertices_near_segment()`, so are the answers.
  ///
  /// A callback callable as `callback(s, near, squared_distances)` also receives, for each point
  /// `near[i]`, the squared distance from it to the segment that the double filter computed to
  /// decide it (`squared_distances[i]`; NaN where the query computed none). With coordinates
  /// stored as `double` it is the squared distance of the exact point to the segment between the
  /// exact ends, evaluated in double: its square root is within a few units in the last place of
  /// (length + distance) of the exact distance, so a caller that leaves a point out by it must
  /// keep a margin of that size.
  /// \tparam SegmentRange a random-access range whose elements `e` give the ends as `e[0]`
  ///         and `e[1]` (e.g. `std::vector<std::array<std::size_t, 2>>`)
  /// \tparam Callback callable as `callback(std::size_t, const std::vector<std::size_t>&)`, or
  ///         with a third argument `const std::vector<double>&`
  /// \param segments the segments, by the indices of their ends
  /// \param radius the largest distance from a segment
  /// \param callback called once per segment
  /// \param order `Neighborhood_order::TREE` hands `near` over unsorted
  /// \throw Invalid_input if an end is not a point of the tree, or as the other queries
  template <typename SegmentRange, typename Callback>
  void for_each_segment_neighborhood(const SegmentRange& segments, const FT& radius, Callback callback,
                                     Neighborhood_order order = Neighborhood_order::INCREASING) const
  {
    check_radius(radius);
    const Segments_by_first_end by_first = segments_by_first_end(segments);
    if(by_first.order.empty())
      return;
    Segment_scratch scratch;
    traverse([](const Frame&, double&) { return true; }, [&](const Frame& f, const Node& nd) {
      segments_of_leaf(f, nd, by_first, radius, scratch, callback, order);
    });
  }

  /// calls `callback(i, near)` for every point `i` with the arguments of `for_each_neighborhood()`;
  /// with `CGAL::Parallel_tag` (and coordinates stored as `double`) the calls are made on TBB's
  /// threads, several at once and in no particular order, so `callback` must be safe to call
  /// concurrently for different points (e.g. write only what belongs to point `i`). Sequentially,
  /// the calls are those of `for_each_neighborhood()`, in Morton order. Nothing is buffered: the
  /// neighborhoods are handed over as they are found.
  /// \tparam ConcurrencyTag `CGAL::Sequential_tag`, `CGAL::Parallel_tag` (needs TBB) or
  ///         `CGAL::Parallel_if_available_tag`
  /// \tparam Callback callable as `callback(std::size_t, const std::vector<std::size_t>&)`
  /// \param radius the largest distance between neighbors
  /// \param callback called once per point
  /// \param order `Neighborhood_order::TREE` hands `near` over unsorted
  template <typename ConcurrencyTag, typename Callback>
  void for_each_neighborhood_concurrently(const FT& radius, Callback callback,
                                          Neighborhood_order order = Neighborhood_order::INCREASING) const
  {
    if constexpr(internal::runs_in_parallel<ConcurrencyTag>() && double_coordinates)
    {
      check_radius(radius);
      if(empty())
        return;
      const FT r2 = radius * radius;
      const Leaf_groups groups =
        leaves_in_groups<ConcurrencyTag>([](const Node& nd) { return std::size_t(nd.end - nd.begin); });
      internal::for_each_block<ConcurrencyTag>(groups.size(), 1, [&](std::size_t g, std::size_t, std::size_t) {
        Join_scratch scratch;
        for(std::size_t l = groups.begin[g]; l != groups.begin[g + 1]; ++l)
          leaf_neighborhoods(nodes_[groups.leaves[l].node], r2, scratch,
                             [&](std::uint32_t k, const std::vector<std::size_t>& near) {
                               callback(std::size_t(ids_[k]), near);
                             }, order);
      });
    }
    else
      for_each_neighborhood<CGAL::Sequential_tag>(radius, callback, order);
  }

  /// calls `callback(s, near)` for every segment `s` of `segments` with the arguments of
  /// `for_each_segment_neighborhood()`; with `CGAL::Parallel_tag` (and coordinates stored as
  /// `double`) the calls are made on TBB's threads, several at once and in no particular order,
  /// so `callback` must be safe to call concurrently for different segments. Sequentially, the
  /// calls are those of `for_each_segment_neighborhood()`.
  /// \tparam ConcurrencyTag `CGAL::Sequential_tag`, `CGAL::Parallel_tag` (needs TBB) or
  ///         `CGAL::Parallel_if_available_tag`
  /// \tparam SegmentRange as for `for_each_segment_neighborhood()`
  /// \tparam Callback as for `for_each_segment_neighborhood()` (two or three arguments)
  /// \param segments the segments, by the indices of their ends
  /// \param radius the largest distance from a segment
  /// \param callback called once per segment
  /// \param order `Neighborhood_order::TREE` hands `near` over unsorted
  template <typename ConcurrencyTag, typename SegmentRange, typename Callback>
  void for_each_segment_neighborhood_concurrently(const SegmentRange& segments, const FT& radius,
                                                  Callback callback,
                                                  Neighborhood_order order = Neighborhood_order::INCREASING) const
  {
    if constexpr(internal::runs_in_parallel<ConcurrencyTag>() && double_coordinates)
    {
      check_radius(radius);
      const Segments_by_first_end by_first = segments_by_first_end(segments);
      if(by_first.order.empty())
        return;
      const Leaf_groups groups = leaves_in_groups<ConcurrencyTag>([&](const Node& nd) {
        return by_first.bucket[nd.end] - by_first.bucket[nd.begin];
      });
      internal::for_each_block<ConcurrencyTag>(groups.size(), 1, [&](std::size_t g, std::size_t, std::size_t) {
        Segment_scratch scratch;
        for(std::size_t l = groups.begin[g]; l != groups.begin[g + 1]; ++l)
          segments_of_leaf(groups.leaves[l], nodes_[groups.leaves[l].node], by_first, radius, scratch, callback,
                           order);
      });
    }
    else
      for_each_segment_neighborhood(segments, radius, callback, order);
  }

  /// @}

  /// \name The bi-directional structure
  /// @{

  /// the number of points
  std::size_t size() const { return ids_.size(); }
  /// point `i` of the range given at construction, as the tree holds it (its own copy, in
  /// Morton order: the range may be freed once the tree is built)
  /// \param i the index of a point in the range given at construction
  /// \throw Invalid_input if `i` is out of range
  const Point_3& point(std::size_t i) const { return points_[position(i)]; }
  /// whether the tree holds no point
  bool empty() const { return ids_.empty(); }
  /// the maximum depth `n`: addresses have `n` bits per axis
  std::size_t maximum_depth() const { return depth_; }
  /// the largest number of points of a leaf (unless they share an address or the leaf is at the maximum depth)
  std::size_t bucket_capacity() const { return capacity_; }
  /// the strategy of `vertices_near_segment()` when none is passed
  Segment_query_strategy segment_query_strategy() const { return strategy_; }
  /// the number of nodes (leaves and inner nodes, empty children included)
  std::size_t number_of_nodes() const { return nodes_.size(); }

  /// the integer address of point `i`: its coordinates normalised to the workspace cube,
  /// scaled by `2^n` and rounded down (the "address embedded in the coordinate")
  /// \param i the index of a point in the range given at construction
  /// \throw Invalid_input if `i` is out of range
  Address address(std::size_t i) const
  {
    Address r;
    internal::morton_decode_3(morton_code(i), r[0], r[1], r[2]);
    return r;
  }

  /// the Morton code of point `i` (the interleaved bits of its address, `3n` bits)
  /// \param i the index of a point in the range given at construction
  std::uint64_t morton_code(std::size_t i) const { return code_of(coords(position(i))); }

  /// the leaf holding point `i`, found by following the bits of its address from the root
  /// \param i the index of a point in the range given at construction
  Node_index leaf(std::size_t i) const
  {
    const std::uint64_t code = morton_code(i);
    Node_index n = 0;
    while(nodes_[n].first_child != 0)
    {
      const unsigned shift = 3 * (depth_ - 1 - nodes_[n].level);
      n = nodes_[n].first_child + Node_index((code >> shift) & 7);
    }
    return n;
  }

  /// whether node `n` has no children
  /// \param n a node
  bool is_leaf(Node_index n) const { return nodes_[n].first_child == 0; }
  /// the depth of node `n` (the root has depth 0)
  /// \param n a node
  std::size_t depth(Node_index n) const { return nodes_[n].level; }
  /// the `i`-th child of the inner node `n`, `i` the octant `4*x + 2*y + z` (bits of the address)
  /// \param n an inner node
  /// \param i the octant, in [0,8)
  Node_index child(Node_index n, int i) const { return nodes_[n].first_child + Node_index(i); }
  /// the indices of the points inside node `n`, in Morton order
  /// \param n a node
  Point_index_range points(Node_index n) const
  {
    return Point_index_range(ids_.data() + nodes_[n].begin, ids_.data() + nodes_[n].end);
  }

  /// numbers the points in the order of the tree from now on: point `i` of every later query,
  /// callback and `point(i)` is the `i`-th point in Morton order (`points(0)` becomes 0, 1, 2,
  /// ...). The tree is otherwise unchanged. Returns the former numbering: the `i`-th point in
  /// Morton order was `order[i]`. For a caller that then keeps its own data about the points in
  /// the tree's order, where neighbours are close in memory too.
  internal::Uninitialized_vector<std::uint32_t> number_points_in_tree_order()
  {
    internal::Uninitialized_vector<std::uint32_t> order;
    order.swap(ids_);
    ids_.resize(order.size());
    std::iota(ids_.begin(), ids_.end(), 0u);
    std::copy(ids_.begin(), ids_.end(), positions_.begin());
    return order;
  }

  /// the workspace cube: minimal corner and side length
  std::array<double, 3> workspace_origin() const { return origin_; }
  /// the side length of the workspace cube
  double workspace_side() const { return side_; }

  /// @}

private:
  /// the indices found by one query: in place up to `local_capacity`, on the heap beyond (a
  /// query of a small radius allocates nothing)
  class Found_indices
  {
  public:
    void push_back(std::size_t i)
    {
      if(size_ < local_capacity)
        local_[size_] = i;
      else
      {
        if(size_ == local_capacity)
          heap_.assign(local_.begin(), local_.end());
        heap_.push_back(i);
      }
      ++size_;
    }
    std::size_t* begin() { return size_ <= local_capacity ? local_.data() : heap_.data(); }
    std::size_t* end() { return begin() + size_; }
    std::size_t size() const { return size_; }

  private:
    static constexpr std::size_t local_capacity = 64;
    std::array<std::size_t, local_capacity> local_;
    std::vector<std::size_t> heap_;
    std::size_t size_ = 0;
  };

  /// appends to `found` the points within `radius` of `q`, in the order the leaves are scanned
  /// (the decisions of `vertices_near_point()`). The descent starts from the deepest node that
  /// holds the box of the ball (see `frame_holding_box()`).
  template <typename Collector>
  void unsorted_vertices_near_point(const Point_3& q, const FT& radius, Collector& found) const
  {
    check_radius(radius);
    if(empty())
      return;
    const FT r2 = radius * radius;
    const Query_point qa = approximate(q);
    const double bound = radius_bound(r2, qa.err);
    const double bound2 = bound * bound;
    traverse(
      [&](const Frame& f, double&) { return !(box_point_squared_distance(f, qa.c) > bound2); },
      [&](const Frame&, const Node& nd) { scan_leaf(nd, q, qa.c, r2, bound2, found); },
      frame_holding_box(qa.c, qa.c, bound));
  }

  /// the points within `radius` of the closed segment `[a,b]`, unsorted (the decisions of
  /// `vertices_near_segment()`).
  std::vector<std::size_t> unsorted_vertices_near_segment(const Point_3& a, const Point_3& b, const FT& radius,
                                                          Segment_query_strategy strategy) const
  {
    check_radius(radius);
    if(empty())
      return {};
    std::vector<std::size_t> found;
    if(gt_.equal_3_object()(a, b))
    {
      unsorted_vertices_near_point(a, radius, found);
      return found;
    }
    scan_near_segment(a, b, radius, strategy, [](const std::array<double, 3>&, const std::array<double, 3>&, double) {
      return Frame{0, {{0, 0, 0}}};
    }, found);
    return found;
  }
  struct Node
  {
    std::uint32_t begin, end;  // range of sorted positions
    std::uint32_t first_child; // 0 for a leaf (the root is never a child)
    std::uint32_t level;
  };
  struct Frame
  {
    Node_index node;
    std::array<std::uint32_t, 3> c; // cell coordinates at the node's level
  };
  struct Frame_stack
  {
    // a depth-first traversal holds at most 7 pending siblings per level
    std::array<Frame, 8 * (largest_maximum_depth + 2)> data;
    std::size_t n = 0;
    bool empty() const { return n == 0; }
    void push_back(const Frame& f) { data[n++] = f; }
    const Frame& back() const { return data[n - 1]; }
    void pop_back() { --n; }
  };
  using Stack = Frame_stack;
  struct Query_point
  {
    std::array<double, 3> c;
    double err; // bound on the distance between the exact point and c
  };
  struct Segment_approx
  {
    std::array<double, 3> a, d;
    double len2;
  };

  static constexpr std::uint32_t npos = std::numeric_limits<std::uint32_t>::max();
  static constexpr bool double_coordinates = std::is_same<FT, double>::value;

  enum class Child_order { OCTANT, NEAREST_FIRST };

  // One segment query prepared: the approximate segment, the widened radius of its pruning and
  // the box of its candidates, and what the exact decision needs.
  struct Segment_query
  {
    Query_point aa, ba;             // the ends, approximated
    Segment_approx s;
    double bound = 0, bound2 = 0;   // the radius widened by every error of the double computations
    std::array<double, 3> lo, hi;   // the box of the approximate ends
    double box_lo[3], box_hi[3];    // that box grown by the bound and the margin: every point within the radius lies in it
    double r2d = 0;                 // the squared radius in double (with double coordinates)
  };

  Segment_query prepare_segment_query(const Point_3& a, const Point_3& b, const FT& r2) const
  {
    Segment_query q;
    q.aa = approximate(a);
    q.ba = approximate(b);
    double len2 = 0;
    for(std::size_t i = 0; i < 3; ++i)
    {
      q.s.a[i] = q.aa.c[i];
      q.s.d[i] = q.ba.c[i] - q.aa.c[i];
      len2 += q.s.d[i] * q.s.d[i];
    }
    q.s.len2 = len2;
    const double len = std::sqrt(len2);
    const double rhi = radius_bound(r2, 0);
    // the double point-segment distance may be off by a few ulps of (length + distance); a
    // segment whose squared length underflows is treated as the point a (error at most len)
    q.bound = (rhi + 2 * std::max(q.aa.err, q.ba.err) + 1e-10 * (len + rhi) +
               (len2 < 1e-280 ? len : 0.)) * (1 + 1e-12);
    q.bound2 = q.bound * q.bound;
    for(std::size_t i = 0; i < 3; ++i)
    {
      q.lo[i] = std::min(q.aa.c[i], q.ba.c[i]);
      q.hi[i] = std::max(q.aa.c[i], q.ba.c[i]);
      // a point within the radius of the segment lies in the box of its ends grown by the
      // radius: that box, grown by the bound and the margin of the approximations, rejects most
      // candidates before their distance is computed
      q.box_lo[i] = q.lo[i] - q.bound - margin_;
      q.box_hi[i] = q.hi[i] + q.bound + margin_;
    }
    // with double coordinates, a point clearly within the radius is accepted in double
    q.r2d = double_coordinates ? CGAL::to_double(r2) : 0.;
    return q;
  }

  // whether the point stored at `k` is within the radius of the segment `seg` of query `q`: the
  // decision of every segment query
  bool is_near_segment(std::uint32_t k, const Segment_query& q, const Segment_3& seg, const FT& r2,
                       typename Geom_traits::Compare_squared_distance_3& compare_sq) const
  {
    if(!in_box(k, q.box_lo, q.box_hi))
      return false;
    double d2 = 0;
    return is_near_segment_in_box(coords(k), k, q, seg, r2, compare_sq, d2);
  }

  // the same for the point stored at `k`, whose approximate coordinates `c` lie in the box of
  // the query (tested by the caller); `d2` receives the squared distance computed in double
  // from `c` to the approximate segment
  bool is_near_segment_in_box(const std::array<double, 3>& c, std::uint32_t k, const Segment_query& q,
                              const Segment_3& seg, const FT& r2,
                              typename Geom_traits::Compare_squared_distance_3& compare_sq, double& d2) const
  {
    double scale = 0;
    d2 = point_segment_squared_distance(c, q.s, scale);
    if(!(d2 <= q.bound2))
      return false;
    // with double coordinates, `d2` and `scale` are those of `surely_within_segment(coords(k),
    // a, b, r2d)` (the same operations on the same numbers), computed once
    if constexpr(double_coordinates)
      if(internal::surely_within(d2, scale, q.r2d))
        return true;
    return compare_sq(points_[k], seg, r2) != CGAL::LARGER;
  }

  // Appends to `found` (unsorted) the index of every point within `radius` of the segment [a,b]
  // (a != b), visiting the subtree of the frame `start(lo, hi, grow)` only: `lo` and `hi` are the
  // corners of the box of the segment's approximate ends, `grow` the widened radius; the frame
  // returned must hold every point of that box grown by `grow` (the root always does).
  template <typename Start>
  void scan_near_segment(const Point_3& a, const Point_3& b, const FT& radius, Segment_query_strategy strategy,
                         const Start& start, std::vector<std::size_t>& found) const
  {
    const FT r2 = radius * radius;
    const Segment_query q = prepare_segment_query(a, b, r2);
    const Segment_3 seg = gt_.construct_segment_3_object()(a, b);
    typename Geom_traits::Compare_squared_distance_3 compare_sq =
      gt_.compare_squared_distance_3_object();
    // index-space box of the segment grown by the bound (equations (22)-(24))
    Address ilo{}, ihi{};
    if(strategy == Segment_query_strategy::INDEX_SPACE_BOX)
    {
      for(std::size_t i = 0; i < 3; ++i)
      {
        ilo[i] = index_of(q.lo[i] - q.bound, i, -1);
        ihi[i] = index_of(q.hi[i] + q.bound, i, +1);
      }
    }

    const auto box_may_meet = [&](const Frame& f, double&) {
      if(strategy == Segment_query_strategy::INDEX_SPACE_BOX)
        return index_range_meets(f, ilo, ihi);
      return box_meets_segment(f, q.s, q.bound);
    };
    traverse(box_may_meet, [&](const Frame&, const Node& nd) {
      for(std::uint32_t k = nd.begin; k != nd.end; ++k)
        if(is_near_segment(k, q, seg, r2, compare_sq))
          found.push_back(ids_[k]);
    }, start(q.lo, q.hi, q.bound));
  }

  // the deepest node on the way from the root whose box holds the integer addresses of every
  // coordinate of the box `[lo - grow, hi + grow]` (the root if a bound is not finite). Every
  // point whose approximate coordinates lie in that box is in its subtree: an address is the
  // rounded-down image of the coordinate by a monotone computation, so a coordinate between
  // two others has an address between theirs, whatever the roundings.
  Frame frame_holding_box(const std::array<double, 3>& lo, const std::array<double, 3>& hi, double grow) const
  {
    Frame f{0, {{0, 0, 0}}};
    Address ilo, ihi;
    for(std::size_t i = 0; i < 3; ++i)
    {
      const double a = lo[i] - grow, b = hi[i] + grow;
      if(!(std::isfinite(a) && std::isfinite(b)))
        return f;
      ilo[i] = index_of(a, i, 0);
      ihi[i] = index_of(b, i, 0);
    }
    for(;;)
    {
      const Node& nd = nodes_[f.node];
      if(nd.first_child == 0)
        return f;
#if defined(__GNUC__) || defined(__clang__)
      // where the blocks of the next levels are when one child only is split (depth-first layout)
      if(std::size_t(nd.first_child) + 24 <= nodes_.size())
        for(std::size_t ahead = 8; ahead < 24; ahead += 4)
          __builtin_prefetch(nodes_.data() + nd.first_child + ahead);
#endif
      const unsigned shift = depth_ - 1 - nd.level;
      const Address c{{ilo[0] >> shift, ilo[1] >> shift, ilo[2] >> shift}};
      if(c[0] != (ihi[0] >> shift) || c[1] != (ihi[1] >> shift) || c[2] != (ihi[2] >> shift))
        return f;
      f = child_frame(f, nd, int((c[0] & 1) << 2 | (c[1] & 1) << 1 | (c[2] & 1)));
    }
  }

  // the frames from the root (`path[0]`) to the leaf of frame `f` (`path[level of f]`)
  void frames_to_leaf(const Frame& f, std::array<Frame, largest_maximum_depth + 1>& path) const
  {
    const unsigned level = nodes_[f.node].level;
    path[level] = f;
    Frame g{0, {{0, 0, 0}}};
    path[0] = g;
    for(unsigned l = 0; l < level; ++l)
    {
      const unsigned shift = level - 1 - l;
      const int octant = int(((f.c[0] >> shift) & 1) << 2 | ((f.c[1] >> shift) & 1) << 1 | ((f.c[2] >> shift) & 1));
      g = child_frame(g, nodes_[g.node], octant);
      path[l + 1] = g;
    }
  }

  // the deepest frame of `path[0..level]` whose box holds the box [lo, hi] grown by twice `grow`
  // on every side (the margin covers the rounding of the box corners and of the addresses);
  // the root holds every point
  Frame smallest_box_holding(const std::array<Frame, largest_maximum_depth + 1>& path, unsigned level,
                             const std::array<double, 3>& lo, const std::array<double, 3>& hi, double grow) const
  {
    if(!std::isfinite(grow))
      return path[0];
    for(unsigned l = level; l > 0; --l)
    {
      const Frame& f = path[l];
      const double cs = cell_size_[l];
      bool inside = true;
      for(std::size_t i = 0; i < 3 && inside; ++i)
      {
        const double box_lo = origin_[i] + f.c[i] * cs;
        inside = lo[i] - box_lo > 2 * grow && (box_lo + cs) - hi[i] > 2 * grow;
      }
      if(inside)
        return f;
    }
    return path[0];
  }

  // The segments of `for_each_segment_neighborhood()` bucketed by the sorted position of their
  // first ends (a counting sort): the segments whose first end is at position k are
  // `order[bucket[k]], ..., order[bucket[k + 1] - 1]`, in the order of the range.
  struct Segments_by_first_end
  {
    internal::Uninitialized_vector<std::uint32_t> second_end; // by segment, the sorted position of its second end
    internal::Uninitialized_vector<std::size_t> bucket;
    internal::Uninitialized_vector<std::uint32_t> order;
  };
  template <typename SegmentRange>
  Segments_by_first_end segments_by_first_end(const SegmentRange& segments) const
  {
    const std::size_t m = static_cast<std::size_t>(std::distance(std::begin(segments), std::end(segments)));
    Segments_by_first_end out;
    internal::Uninitialized_vector<std::uint32_t> first_end(m); // (these arrays are written whole before they are read)
    out.second_end.resize(m);
    out.bucket.assign(size() + 1, 0);
    for(std::size_t s = 0; s < m; ++s)
    {
      const auto& e = *(std::begin(segments) + static_cast<std::ptrdiff_t>(s));
      first_end[s] = position(static_cast<std::size_t>(e[0]));
      out.second_end[s] = position(static_cast<std::size_t>(e[1]));
      ++out.bucket[first_end[s] + 1];
    }
    if(m == 0)
      return out;
    for(std::size_t k = 1; k < out.bucket.size(); ++k)
      out.bucket[k] += out.bucket[k - 1];
    out.order.resize(m);
    internal::Uninitialized_vector<std::size_t> next(out.bucket.begin(), out.bucket.end() - 1);
    for(std::size_t s = 0; s < m; ++s)
      out.order[next[first_end[s]]++] = static_cast<std::uint32_t>(s);
    return out;
  }

  // a point of the shared box of a leaf's segments: its approximate coordinates and its position
  struct Shared_candidate
  {
    std::array<double, 3> c;
    std::uint32_t position;
  };

  // The shared candidates of a leaf in slabs across the longest side of their box, so that a
  // segment tests only the candidates of the slabs its own box meets (on the exploded torus of
  // `benchmark/exploded_torus.py`, 29 of the 76 candidates of a leaf, on average over the
  // segments: each short segment's box is a fraction of the leaf's shared box). A candidate's
  // slab is a monotone function of its coordinate along that side, so the slabs between those of
  // a box's two faces hold every candidate of the box; each candidate is then tested against the
  // box as before. The candidates are in slab order, and in their order of gathering within a slab.
  struct Candidate_slabs
  {
    static constexpr std::size_t most_slabs = 16;
    std::size_t axis = 0;
    double low = 0, slabs_per_unit = 0;
    std::size_t count = 1;
    std::array<std::uint32_t, most_slabs + 1> begin{};
    std::vector<Shared_candidate> sorted;

    // the slab of coordinate `x` along the axis (non-decreasing in `x`)
    std::size_t slab_of(double x) const
    {
      const double t = (x - low) * slabs_per_unit;
      if(!(t >= 1))
        return 0;
      return t >= double(count - 1) ? count - 1 : static_cast<std::size_t>(t);
    }

    // `candidates`, which lie in the box [lo, hi], in slabs
    void fill(const std::vector<Shared_candidate>& candidates, const std::array<double, 3>& lo,
              const std::array<double, 3>& hi)
    {
      axis = 0;
      for(std::size_t i = 1; i < 3; ++i)
        if(hi[i] - lo[i] > hi[axis] - lo[axis])
          axis = i;
      low = lo[axis];
      const double width = hi[axis] - lo[axis];
      count = std::min(most_slabs, std::max<std::size_t>(candidates.size() / 4, 1));
      slabs_per_unit = double(count) / width;
      if(!(width > 0) || !std::isfinite(slabs_per_unit))
      {
        count = 1;
        slabs_per_unit = 0;
      }
      begin.fill(0);
      for(const Shared_candidate& c : candidates)
        ++begin[slab_of(c.c[axis]) + 1];
      for(std::size_t k = 1; k <= count; ++k)
        begin[k] += begin[k - 1];
      sorted.resize(candidates.size());
      std::array<std::uint32_t, most_slabs> next;
      std::copy(begin.begin(), begin.begin() + count, next.begin());
      for(const Shared_candidate& c : candidates)
        sorted[next[slab_of(c.c[axis])]++] = c;
    }

    // the candidates of the slabs that the box [lo, hi] meets, as a range of `sorted`
    std::pair<const Shared_candidate*, const Shared_candidate*> meeting(const double* lo, const double* hi) const
    {
      return {sorted.data() + begin[slab_of(lo[axis])], sorted.data() + begin[slab_of(hi[axis]) + 1]};
    }
  };

  // what the segment queries of one leaf reuse for the next
  struct Segment_scratch
  {
    std::array<Frame, largest_maximum_depth + 1> path; // from the root to the leaf
    std::vector<Segment_query> queries;                 // the leaf's segments, prepared
    std::vector<char> shared;                           // whether a query takes the shared candidates
    std::vector<Shared_candidate> candidates;           // the points in the shared box
    Candidate_slabs slabs;                              // those points in slabs across the box
    std::vector<std::size_t> near;                      // the answer of one segment
    std::vector<double> near_squared_distances;         // their estimates, if the callback takes them
  };

  // The queries of the segments whose first ends lie in the leaf `nd` (frame `f`). The segments
  // short beside the leaf (the box of their candidates no wider than the leaf's cell, the common
  // case on a mesh) share their candidates: the points of the union of their boxes, gathered by
  // one traversal, then tested against each segment with the decisions of `scan_near_segment()`
  // (a point within the radius of a segment lies in that segment's box, hence among them), those
  // of the slabs that the segment's box meets only (`Candidate_slabs`). The
  // others, and the segments of a leaf whose shared box holds more than `shared_candidate_limit()`
  // points (a crowd nearby, which every short segment would test), are each queried alone, from
  // the smallest box around the leaf that holds the segment grown by the radius. The answers are
  // the same either way.
  template <typename Callback>
  void segments_of_leaf(const Frame& f, const Node& nd, const Segments_by_first_end& by_first, const FT& radius,
                        Segment_scratch& scratch, Callback& callback, Neighborhood_order order) const
  {
    if(by_first.bucket[nd.begin] == by_first.bucket[nd.end])
      return;
    frames_to_leaf(f, scratch.path);
    const FT r2 = radius * radius;
    const double cell = cell_size_[nd.level];
    const double infinity = std::numeric_limits<double>::infinity();
    std::array<double, 3> shared_lo{{infinity, infinity, infinity}}, shared_hi{{-infinity, -infinity, -infinity}};
    scratch.queries.clear();
    scratch.shared.clear();
    bool any_shared = false;
    for(std::uint32_t k = nd.begin; k != nd.end; ++k)
      for(std::size_t j = by_first.bucket[k]; j != by_first.bucket[k + 1]; ++j)
      {
        const Point_3& b = points_[by_first.second_end[by_first.order[j]]];
        if(gt_.equal_3_object()(points_[k], b))
          continue;
        scratch.queries.push_back(prepare_segment_query(points_[k], b, r2));
        const Segment_query& q = scratch.queries.back();
        bool short_segment = true;
        for(std::size_t i = 0; i < 3; ++i)
          short_segment = short_segment && q.box_hi[i] - q.box_lo[i] <= cell; // false if not finite
        scratch.shared.push_back(short_segment);
        if(!short_segment)
          continue;
        any_shared = true;
        for(std::size_t i = 0; i < 3; ++i)
        {
          shared_lo[i] = std::min(shared_lo[i], q.box_lo[i]);
          shared_hi[i] = std::max(shared_hi[i], q.box_hi[i]);
        }
      }
    const bool sharing = any_shared && gather_shared_candidates(shared_lo, shared_hi, scratch.candidates);
    if(sharing)
      scratch.slabs.fill(scratch.candidates, shared_lo, shared_hi);

    const auto smallest_box_around = [&](const std::array<double, 3>& lo, const std::array<double, 3>& hi,
                                         double grow) {
      return smallest_box_holding(scratch.path, nd.level, lo, hi, grow);
    };
    typename Geom_traits::Compare_squared_distance_3 compare_sq = gt_.compare_squared_distance_3_object();
    std::vector<std::size_t>& near = scratch.near;
    std::vector<double>& near_d2 = scratch.near_squared_distances;
    constexpr bool with_distances = takes_squared_distances<Callback>();
    const double unknown = std::numeric_limits<double>::quiet_NaN();
    std::size_t query = 0;
    for(std::uint32_t k = nd.begin; k != nd.end; ++k)
      for(std::size_t j = by_first.bucket[k]; j != by_first.bucket[k + 1]; ++j)
      {
        const std::uint32_t s = by_first.order[j];
        near.clear();
        near_d2.clear();
        const Point_3& b = points_[by_first.second_end[s]];
        if(gt_.equal_3_object()(points_[k], b))
          vertices_near_point(b, radius, std::back_inserter(near));
        else
        {
          if(sharing && scratch.shared[query])
          {
            const Segment_query& q = scratch.queries[query];
            const Segment_3 seg = gt_.construct_segment_3_object()(points_[k], b);
            double d2 = 0;
            const auto [first, last] = scratch.slabs.meeting(q.box_lo, q.box_hi);
            for(const Shared_candidate* c = first; c != last; ++c)
              if(c->c[0] >= q.box_lo[0] && c->c[0] <= q.box_hi[0] && c->c[1] >= q.box_lo[1] &&
                 c->c[1] <= q.box_hi[1] && c->c[2] >= q.box_lo[2] && c->c[2] <= q.box_hi[2] &&
                 is_near_segment_in_box(c->c, c->position, q, seg, r2, compare_sq, d2))
              {
                near.push_back(ids_[c->position]);
                if constexpr(with_distances)
                  near_d2.push_back(d2);
              }
          }
          else
            scan_near_segment(points_[k], b, radius, strategy_, smallest_box_around, near);
          ++query;
        }
        if constexpr(with_distances)
        {
          near_d2.resize(near.size(), unknown); // (the queries that computed none)
          if(order == Neighborhood_order::INCREASING)
            sort_with_distances(near, near_d2);
          callback(std::size_t(s), static_cast<const std::vector<std::size_t>&>(near),
                   static_cast<const std::vector<double>&>(near_d2));
        }
        else
        {
          if(order == Neighborhood_order::INCREASING)
            std::sort(near.begin(), near.end());
          callback(std::size_t(s), static_cast<const std::vector<std::size_t>&>(near));
        }
      }
  }

  // whether a callback of the segment joins takes the estimates of the squared distances
  template <typename Callback>
  static constexpr bool takes_squared_distances()
  {
    return std::is_invocable<Callback&, std::size_t, const std::vector<std::size_t>&,
                             const std::vector<double>&>::value;
  }

  // sorts `near` increasingly, `d2` along with it
  static void sort_with_distances(std::vector<std::size_t>& near, std::vector<double>& d2)
  {
    std::vector<std::pair<std::size_t, double>> both(near.size());
    for(std::size_t i = 0; i < near.size(); ++i)
      both[i] = {near[i], d2[i]};
    std::sort(both.begin(), both.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
    for(std::size_t i = 0; i < near.size(); ++i)
    {
      near[i] = both[i].first;
      d2[i] = both[i].second;
    }
  }

  // the most points the short segments of one leaf test one by one: beyond it they are queried alone
  std::size_t shared_candidate_limit() const { return 8 * std::max<std::size_t>(capacity_, 16); }

  // the points in the box [lo, hi] (which holds the margins already), gathered from the deepest
  // node holding it; false, with the gathering stopped, past
  // `shared_candidate_limit()` points
  bool gather_shared_candidates(const std::array<double, 3>& lo, const std::array<double, 3>& hi,
                                std::vector<Shared_candidate>& candidates) const
  {
    candidates.clear();
    const std::size_t limit = shared_candidate_limit();
    bool crowded = false;
    traverse(
      [&](const Frame& g, double&) { return !crowded && box_meets_box(g, lo.data(), hi.data()); },
      [&](const Frame&, const Node& c) {
        for(std::uint32_t j = c.begin; j != c.end && !crowded; ++j)
          if(in_box(j, lo.data(), hi.data()))
          {
            candidates.push_back(Shared_candidate{coords(j), j});
            crowded = candidates.size() > limit;
          }
      },
      frame_holding_box(lo, hi, 0.));
    return !crowded;
  }

  // The leaves in traversal (Morton) order, cut into groups of about `group_weight` of
  // `weight(leaf)` each: the blocks of the concurrent searches (they do not depend on the number
  // of threads). A leaf is known by its frame (which names its node).
  struct Leaf_groups
  {
    internal::Uninitialized_vector<Frame> leaves;
    std::vector<std::size_t> begin; // group g holds leaves[begin[g]], ..., leaves[begin[g + 1] - 1]
    std::size_t size() const { return begin.size() - 1; }
  };

  // the smallest number of subtrees `leaves_in_groups()` looks for below its level
  static constexpr std::size_t leaf_listing_subtrees = 64;

  // With a parallel `ConcurrencyTag` and more than one thread allowed, the leaves are listed by
  // subtrees on TBB's threads: the inner nodes of the first level with
  // `leaf_listing_subtrees` of them (or of the deepest level with any), and the leaves above that
  // level, in traversal order; the leaves of each subtree counted, then written at their places
  // in the list (sized once): the sequential list.
  template <typename ConcurrencyTag, typename Weight>
  Leaf_groups leaves_in_groups(const Weight& weight, std::size_t group_weight = 2048) const
  {
    Leaf_groups out;
    const auto is_inner = [&](const Frame& f) { return nodes_[f.node].first_child != 0; };
    if(!internal::runs_on_several_threads<ConcurrencyTag>())
      traverse([](const Frame&, double&) { return true; },
               [&](const Frame& f, const Node&) { out.leaves.push_back(f); });
    else
    {
      std::vector<Frame> starts;
      for(std::uint32_t level = 1;; ++level)
      {
        std::vector<Frame> found;
        std::size_t inner = 0;
        traverse(
          [&](const Frame& f, double&) {
            if(nodes_[f.node].level < level || !is_inner(f))
              return true;
            found.push_back(f);
            ++inner;
            return false;
          },
          [&](const Frame& f, const Node&) { found.push_back(f); });
        starts.swap(found);
        if(inner >= leaf_listing_subtrees || inner == 0 || level >= depth_)
          break;
      }
      std::vector<std::size_t> first(starts.size() + 1, 0);
      internal::for_each_index<ConcurrencyTag>(starts.size(), [&](std::size_t k) {
        std::size_t count = 1;
        if(is_inner(starts[k]))
        {
          count = 0;
          traverse([](const Frame&, double&) { return true; }, [&](const Frame&, const Node&) { ++count; }, starts[k]);
        }
        first[k + 1] = count;
      }, 1);
      for(std::size_t k = 0; k < starts.size(); ++k)
        first[k + 1] += first[k];
      out.leaves.resize(first.back()); // (every entry written below)
      internal::for_each_index<ConcurrencyTag>(starts.size(), [&](std::size_t k) {
        std::size_t at = first[k];
        if(is_inner(starts[k]))
          traverse([](const Frame&, double&) { return true; },
                   [&](const Frame& f, const Node&) { out.leaves[at++] = f; }, starts[k]);
        else
          out.leaves[at] = starts[k];
      }, 1);
    }
    out.begin.push_back(0);
    for(std::size_t l = 0, w = 0; l < out.leaves.size(); ++l)
    {
      w += weight(nodes_[out.leaves[l].node]);
      if(w >= group_weight || l + 1 == out.leaves.size())
      {
        out.begin.push_back(l + 1);
        w = 0;
      }
    }
    return out;
  }

  // what the self-join reuses from one leaf to the next
  struct Join_scratch
  {
    std::vector<Query_point> queries;      // the points of the leaf, approximated
    std::vector<std::uint32_t> candidates; // positions of the points near the leaf
    std::vector<std::size_t> near;         // the neighborhood of one point
  };

  // The neighborhoods of the points of leaf `nd`: `emit(k, near)` for every position `k` of the
  // leaf in increasing order, `near` the indices of the points within sqrt(r2) of point `k`, in
  // increasing order (with `Neighborhood_order::TREE`, in the order of their positions). The candidates are the points whose approximate coordinates lie in the box
  // of the leaf's points grown by the largest of their bounds (every neighbor of a point of the
  // leaf does, as for the pruning of `vertices_near_point()`), gathered once from the deepest
  // node holding that box; each point keeps the candidates that `scan_leaf()` would keep for it.
  template <typename Emit>
  void leaf_neighborhoods(const Node& nd, const FT& r2, Join_scratch& scratch, Emit emit,
                          Neighborhood_order order) const
  {
    std::array<double, 3> lo{}, hi{};
    double err = 0;
    scratch.queries.clear();
    for(std::uint32_t k = nd.begin; k != nd.end; ++k)
    {
      const Query_point qa = approximate(points_[k]);
      scratch.queries.push_back(qa);
      err = std::max(err, qa.err);
      for(std::size_t i = 0; i < 3; ++i)
      {
        lo[i] = k == nd.begin ? qa.c[i] : std::min(lo[i], qa.c[i]);
        hi[i] = k == nd.begin ? qa.c[i] : std::max(hi[i], qa.c[i]);
      }
    }
    const double grow = radius_bound(r2, err);
    double box_lo[3], box_hi[3];
    for(std::size_t i = 0; i < 3; ++i)
    {
      box_lo[i] = lo[i] - grow;
      box_hi[i] = hi[i] + grow;
    }
    const bool bounded = std::isfinite(box_lo[0]) && std::isfinite(box_lo[1]) && std::isfinite(box_lo[2]) &&
                         std::isfinite(box_hi[0]) && std::isfinite(box_hi[1]) && std::isfinite(box_hi[2]);
    scratch.candidates.clear();
    traverse(
      [&](const Frame& f, double&) { return !bounded || box_meets_box(f, box_lo, box_hi); },
      [&](const Frame&, const Node& c) {
        for(std::uint32_t j = c.begin; j != c.end; ++j)
          if(!bounded || in_box(j, box_lo, box_hi))
            scratch.candidates.push_back(j);
      },
      frame_holding_box(lo, hi, grow));
    typename Geom_traits::Compare_squared_distance_3 compare_sq = gt_.compare_squared_distance_3_object();
    for(std::uint32_t k = nd.begin; k != nd.end; ++k)
    {
      const Query_point& qa = scratch.queries[k - nd.begin];
      const double bound = radius_bound(r2, qa.err);
      scratch.near.clear();
      for(const std::uint32_t j : scratch.candidates)
        if(is_near(j, points_[k], qa.c, r2, bound * bound, compare_sq))
          scratch.near.push_back(ids_[j]);
      if(order == Neighborhood_order::INCREASING)
        std::sort(scratch.near.begin(), scratch.near.end());
      emit(k, static_cast<const std::vector<std::size_t>&>(scratch.near));
    }
  }

  // does the box of `f`, widened by the margin of the addresses, meet the box [lo, hi]?
  bool box_meets_box(const Frame& f, const double* lo, const double* hi) const
  {
    const double cs = cell_size_[nodes_[f.node].level];
    for(std::size_t i = 0; i < 3; ++i)
    {
      const double box_lo = origin_[i] + f.c[i] * cs;
      if(box_lo - margin_ > hi[i] || box_lo + cs + margin_ < lo[i])
        return false;
    }
    return true;
  }

  // The depth-first traversal of every query, from the root or from `start`. A node is entered
  // if it holds points and `box_test(frame, key)` returns true; `leaf_action(frame, node)` is
  // called on the leaves entered. The children of an inner node are visited in octant order, or, with NEAREST_FIRST,
  // those passing `box_test` when pushed in increasing `key` (they are tested again when popped:
  // the test may have tightened meanwhile).
  template <Child_order order = Child_order::OCTANT, typename Box_test, typename Leaf_action>
  void traverse(Box_test box_test, Leaf_action leaf_action, const Frame& start = Frame{0, {{0, 0, 0}}}) const
  {
    Stack stack;
    stack.push_back(start);
    while(!stack.empty())
    {
      const Frame f = stack.back();
      stack.pop_back();
      const Node& nd = nodes_[f.node];
      double key = 0;
      if(nd.begin == nd.end || !box_test(f, key))
        continue;
      if(nd.first_child == 0)
        leaf_action(f, nd);
      else if constexpr(order == Child_order::NEAREST_FIRST)
        push_children_nearest_first(f, nd, box_test, stack);
      else
        for(int i = 7; i >= 0; --i)
          if(nodes_[nd.first_child + Node_index(i)].begin != nodes_[nd.first_child + Node_index(i)].end)
            stack.push_back(child_frame(f, nd, i));
    }
  }

  // pushes the non-empty children of `nd` that pass `box_test`, farthest first (insertion sort
  // on their keys, at most 8), so that the nearest is visited first
  template <typename Box_test>
  void push_children_nearest_first(const Frame& f, const Node& nd, Box_test& box_test, Stack& stack) const
  {
    double key[8];
    Frame child[8];
    int count = 0;
    for(int i = 0; i < 8; ++i)
    {
      const Frame c = child_frame(f, nd, i);
      const Node& cn = nodes_[c.node];
      double k = 0;
      if(cn.begin == cn.end || !box_test(c, k))
        continue;
      int j = count++;
      for(; j > 0 && key[j - 1] < k; --j)
      {
        key[j] = key[j - 1];
        child[j] = child[j - 1];
      }
      key[j] = k;
      child[j] = c;
    }
    for(int i = 0; i < count; ++i)
      stack.push_back(child[i]);
  }

  // does the index range of the box of `f` meet [ilo, ihi] on every axis (equations (26)-(27))?
  bool index_range_meets(const Frame& f, const Address& ilo, const Address& ihi) const
  {
    const unsigned shift = depth_ - nodes_[f.node].level;
    for(std::size_t i = 0; i < 3; ++i)
    {
      const std::uint64_t lo = std::uint64_t(f.c[i]) << shift;
      const std::uint64_t hi = ((std::uint64_t(f.c[i]) + 1) << shift) - 1;
      if(!(lo <= ihi[i] && ilo[i] <= hi))
        return false;
    }
    return true;
  }

  struct Key
  {
    std::uint64_t code;
    std::uint32_t id;
  };
  // (`Uninitialized_vector`: the keys, the indices and the positions of a build are written whole,
  // on TBB's threads in a parallel build, and nothing zeroes them before.)
  using Keys = internal::Uninitialized_vector<Key>;

  // the bounding box of the approximate coordinates and the largest error of the approximation
  struct Approximate_box
  {
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    double max_abs = 0, err = 0;
  };

  // With a parallel `ConcurrencyTag` and coordinates stored as `double`, the box, the keys, their
  // sort and the gather of the points run on TBB's threads (the nodes are split on one); every
  // step gives the sequential result, so the tree is the same.
  template <typename ConcurrencyTag = CGAL::Sequential_tag, typename PointRange>
  void build(const PointRange& range, const PointMap& pm, std::size_t capacity, std::size_t depth)
  {
    using Tag = std::conditional_t<double_coordinates && internal::runs_in_parallel<ConcurrencyTag>(), ConcurrencyTag,
                                   CGAL::Sequential_tag>;
    if constexpr(internal::runs_in_parallel<Tag>())
    {
      // the parallel sort makes more passes: on one thread, the sequential build (the same tree)
      if(!internal::runs_on_several_threads<Tag>())
        return build<CGAL::Sequential_tag>(range, pm, capacity, depth);
    }
    check_build_parameters(capacity, depth);
    capacity_ = capacity;
    depth_ = static_cast<unsigned>(depth);
    const std::size_t n = static_cast<std::size_t>(std::distance(std::begin(range), std::end(range)));
    if(n >= std::size_t(npos))
      throw std::length_error("Soup_topology::Octree: too many points (at most 2^32 - 2)");
    std::vector<std::array<double, 3>> approx; // kept only for a non-double kernel
    const Approximate_box box = internal::runs_in_parallel<Tag>() ? box_in_parallel<Tag>(range, pm, n)
                                                                  : approximate_points(range, pm, n, approx);
    set_workspace(box);
    Keys keys = sorted_keys<Tag>(range, pm, n, approx);
    gather_points<Tag>(range, pm, keys, approx);
    build_nodes<Tag>(keys);
  }

  static void throw_non_finite_point(std::size_t i)
  {
    throw Invalid_input("Soup_topology::Octree: point " + std::to_string(i) + " has a non-finite coordinate");
  }

  // step 1 by blocks (`double` coordinates), in one pass: each block's box, or its first
  // non-finite point; the first bad point of all is named, else the boxes are put together in
  // block order with the comparisons of `approximate_points()` (the first of equal extreme
  // coordinates is kept, so even the sign of a zero is the sequential one)
  template <typename Tag, typename PointRange>
  Approximate_box box_in_parallel(const PointRange& range, const PointMap& pm, std::size_t n) const
  {
    const auto first = std::begin(range);
    std::vector<Approximate_box> boxes(internal::number_of_blocks(n));
    std::vector<std::size_t> bad(boxes.size(), n);
    internal::for_each_block<Tag>(n, internal::default_block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
      for(std::size_t i = begin; i != end; ++i)
      {
        const auto& p = get(pm, *(first + static_cast<std::ptrdiff_t>(i)));
        const std::array<double, 3> c{{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}};
        if(!(std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2])))
        {
          bad[b] = i;
          return;
        }
        extend(boxes[b], c, i == begin);
      }
    });
    for(const std::size_t i : bad)
      if(i != n)
        throw_non_finite_point(i);
    Approximate_box box;
    for(std::size_t b = 0; b < boxes.size(); ++b)
    {
      for(std::size_t k = 0; k < 3; ++k)
      {
        if(b == 0 || boxes[b].lo[k] < box.lo[k]) box.lo[k] = boxes[b].lo[k];
        if(b == 0 || boxes[b].hi[k] > box.hi[k]) box.hi[k] = boxes[b].hi[k];
      }
      box.max_abs = std::max(box.max_abs, boxes[b].max_abs);
    }
    return box;
  }

  // `box` grown to hold `c` (`first`: the box holds nothing yet)
  static void extend(Approximate_box& box, const std::array<double, 3>& c, bool first)
  {
    for(std::size_t k = 0; k < 3; ++k)
    {
      if(first || c[k] < box.lo[k]) box.lo[k] = c[k];
      if(first || c[k] > box.hi[k]) box.hi[k] = c[k];
      box.max_abs = std::max(box.max_abs, std::abs(c[k]));
    }
  }

  static void check_build_parameters(std::size_t capacity, std::size_t depth)
  {
    if(capacity < 1)
      throw Invalid_input("Soup_topology::Octree: the bucket capacity must be at least 1");
    if(depth < 1 || depth > largest_maximum_depth)
      throw Invalid_input("Soup_topology::Octree: the maximum depth must be in [1, 21]");
  }

  // step 1: approximate coordinates (stored in `approx` only for a non-double kernel), checked,
  // and their box
  template <typename PointRange>
  Approximate_box approximate_points(const PointRange& range, const PointMap& pm, std::size_t n,
                                     std::vector<std::array<double, 3>>& approx) const
  {
    const auto first = std::begin(range);
    if(!double_coordinates)
      approx.resize(n);
    Approximate_box box;
    for(std::size_t i = 0; i < n; ++i)
    {
      const auto& p = get(pm, *(first + static_cast<std::ptrdiff_t>(i)));
      const std::pair<double, double> iv[3] = {CGAL::to_interval(p.x()), CGAL::to_interval(p.y()),
                                              CGAL::to_interval(p.z())};
      for(std::size_t k = 0; k < 3; ++k)
      {
        if(!std::isfinite(iv[k].first) || !std::isfinite(iv[k].second))
          throw_non_finite_point(i);
        const double c = iv[k].first == iv[k].second ? iv[k].first
                                                     : 0.5 * iv[k].first + 0.5 * iv[k].second;
        if(!double_coordinates)
        {
          approx[i][k] = c;
          box.err = std::max(box.err, iv[k].second - iv[k].first);
        }
        if(i == 0 || c < box.lo[k]) box.lo[k] = c;
        if(i == 0 || c > box.hi[k]) box.hi[k] = c;
        box.max_abs = std::max(box.max_abs, std::abs(c));
      }
    }
    return box;
  }

  // step 2: the workspace cube, the cell sizes and the margin of the double computations
  void set_workspace(const Approximate_box& box)
  {
    double side = std::max({box.hi[0] - box.lo[0], box.hi[1] - box.lo[1], box.hi[2] - box.lo[2]});
    if(!(side >= 1e-280))
      side = box.max_abs >= 1e-280 ? box.max_abs : 1.0;
    origin_ = {box.lo[0], box.lo[1], box.lo[2]};
    side_ = side;
    scale_ = std::ldexp(1.0, int(depth_)) / side;
    top_ = (std::uint32_t(1) << depth_) - 1;
    cell_size_.resize(depth_ + 1);
    for(unsigned l = 0; l <= depth_; ++l)
      cell_size_[l] = std::ldexp(side, -int(l));
    // every rounding error of the address computation, of the box corners and of the distance
    // computations is a few ulps of the largest coordinate; the exact points are at most `err`
    // away from their approximations (0 for a double kernel)
    margin_ = 64 * DBL_EPSILON * (box.max_abs + side) + 2 * box.err + 1e-300;
  }

  // step 3: Morton codes, sorted with the point index as tie-breaker (a deterministic layout)
  template <typename Tag, typename PointRange>
  Keys sorted_keys(const PointRange& range, const PointMap& pm, std::size_t n,
                   const std::vector<std::array<double, 3>>& approx) const
  {
    const auto first = std::begin(range);
    Keys keys(n);
    internal::for_each_index<Tag>(n, [&](std::size_t i) {
      if constexpr(double_coordinates)
      {
        const auto& p = get(pm, *(first + static_cast<std::ptrdiff_t>(i)));
        keys[i] = Key{code_of(std::array<double, 3>{{p.x(), p.y(), p.z()}}), std::uint32_t(i)};
      }
      else
        keys[i] = Key{code_of(approx[i]), std::uint32_t(i)};
    });
    sort_keys<Tag>(keys);
    return keys;
  }

  // sorts by (code, id), on TBB's threads when `Tag` asks for it, with the same result on any
  // number of threads: the keys are made in index order, so the stable LSD radix sort
  // (`internal::sort_by_digits()`, 11-bit digits) of the 33 most significant bits of the codes (10
  // to 11 levels, enough to separate almost every point) orders them by (those bits, id); each of
  // the few runs of keys that share those bits is then sorted by std::sort, by the block of keys
  // where it starts
  template <typename Tag>
  void sort_keys(Keys& keys) const
  {
    const unsigned bits = 3 * depth_;
    const unsigned low = bits - std::min(bits, 33u);
    {
      Keys buffer;
      internal::sort_by_digits<Tag>(keys, buffer, low, bits, 11, [](const Key& k) { return k.code; });
    }
    if(low == 0)
      return;
    // First where the runs start (reading only), so that each block sorts whole runs that no
    // other block reads: those that start in [run_start[b], run_start[b + 1]).
    const std::size_t n = keys.size();
    std::vector<std::size_t> run_start(internal::number_of_blocks(n) + 1, n);
    internal::for_each_block<Tag>(n, internal::default_block_size, [&](std::size_t b, std::size_t begin, std::size_t end) {
      std::size_t s = begin;
      while(s != 0 && s < end && (keys[s].code >> low) == (keys[s - 1].code >> low))
        ++s; // the run of the block before
      run_start[b] = s;
    });
    internal::for_each_block<Tag>(n, internal::default_block_size, [&](std::size_t b, std::size_t, std::size_t) {
      sort_runs(keys, run_start[b], run_start[b + 1], low);
    });
  }

  // step 4: the points in the order of the keys, with their indices both ways
  template <typename Tag, typename PointRange>
  void gather_points(const PointRange& range, const PointMap& pm, const Keys& keys,
                     const std::vector<std::array<double, 3>>& approx)
  {
    const auto first = std::begin(range);
    const std::size_t n = keys.size();
    if constexpr(internal::runs_in_parallel<Tag>())
    {
      // by blocks of positions: each position and each id is written once
      approx_.clear();
      points_.clear();
      points_.resize(n);
      ids_.resize(n);
      positions_.resize(n);
      internal::for_each_index<Tag>(n, [&](std::size_t j) {
        const std::uint32_t id = keys[j].id;
        points_[j] = get(pm, first[id]);
        ids_[j] = id;
        positions_[id] = std::uint32_t(j);
      });
      return;
    }
    points_.clear();
    points_.reserve(n);
    approx_.clear();
    if(!double_coordinates)
      approx_.resize(n);
    ids_.resize(n);
    positions_.resize(n);
    // the gather is random access into the input: prefetching a few points ahead hides most of
    // the cache misses
    constexpr std::size_t ahead = 16;
    for(std::size_t j = 0; j < n; ++j)
    {
      const std::uint32_t id = keys[j].id;
#if defined(__GNUC__) || defined(__clang__)
      if(j + ahead < n)
        __builtin_prefetch(std::addressof(*(first + std::ptrdiff_t(keys[j + ahead].id))));
#endif
      points_.push_back(get(pm, first[id]));
      if constexpr(!double_coordinates)
        approx_[j] = approx[id];
      ids_[j] = id;
      positions_[id] = std::uint32_t(j);
    }
  }

  // step 5: the nodes; a node is split if it holds more than `capacity` points of at least two
  // different addresses (splitting identical addresses cannot separate them). The blocks of 8
  // children are laid out depth first: the blocks of a path from the root to a leaf come in
  // increasing order, and those of a small subtree are close together, so that a descent reads
  // memory forward.
  //
  // With a parallel `ConcurrencyTag`, the subtrees below one level are laid out on TBB's threads:
  // the layout is depth first, so the blocks of the subtree of a node of that level form one run,
  // whose length is that subtree's number of nodes. The nodes above that level are split first,
  // counting only, which lists the subtrees in the order of the layout; the subtrees are
  // counted (in parallel); the nodes above the level are split again, into place, leaving each
  // subtree's run its room; then every subtree is split into its room (in parallel). The nodes
  // are those of the sequential build, in the same places; their array is sized once (no growth
  // by copies into fresh memory), and its pages are first touched by the threads that fill it.
  template <typename ConcurrencyTag = CGAL::Sequential_tag>
  void build_nodes(const Keys& keys)
  {
    const Node root{0, std::uint32_t(keys.size()), 0, 0};
    nodes_.clear();
    if constexpr(internal::runs_in_parallel<ConcurrencyTag>())
    {
      build_nodes_by_subtrees<ConcurrencyTag>(keys, root);
      return;
    }
    Growing_nodes grown{nodes_};
    nodes_.push_back(root);
    split_depth_first(keys, root, 0, grown, [](const Node&, Node_index) { return false; });
  }

  // whether node `nd` is split (`build_nodes()`)
  bool is_split(const Keys& keys, const Node& nd) const
  {
    return nd.end - nd.begin > capacity_ && nd.level < depth_ && keys[nd.begin].code != keys[nd.end - 1].code;
  }

  // The places `split_depth_first()` puts the nodes it makes: `size()` is the index of the next
  // node, `push_back()` puts it there, `set_first_child()` links a node to its children.
  // `Growing_nodes` appends to the array of nodes; `Counted_nodes` keeps nothing and counts.
  struct Growing_nodes
  {
    internal::Uninitialized_vector<Node>& nodes;
    Node_index size() const { return Node_index(nodes.size()); }
    void push_back(const Node& nd) { nodes.push_back(nd); }
    void set_first_child(Node_index parent, Node_index first) { nodes[parent].first_child = first; }
  };
  struct Counted_nodes
  {
    Node_index next = 0;
    Node_index size() const { return next; }
    void push_back(const Node&) { ++next; }
    void set_first_child(Node_index, Node_index) {}
  };
  // `Placed_nodes` writes into a room of a sized array, from `next` on, and links the parents
  // from `first_own` on (the parent of the room's first block, outside it, is linked by the
  // caller); `Listed_nodes` keeps the nodes it is given with their places (in increasing order),
  // for the caller to write them later.
  struct Placed_nodes
  {
    Node* nodes;
    Node_index next, first_own;
    Node_index size() const { return next; }
    void push_back(const Node& nd) { nodes[next++] = nd; }
    void set_first_child(Node_index parent, Node_index first)
    {
      if(parent >= first_own)
        nodes[parent].first_child = first;
    }
  };
  struct Listed_nodes
  {
    std::vector<std::pair<Node_index, Node>> listed;
    Node_index next;
    Node_index size() const { return next; }
    void push_back(const Node& nd) { listed.emplace_back(next++, nd); }
    void set_first_child(Node_index parent, Node_index first)
    {
      const auto at = std::lower_bound(listed.begin(), listed.end(), parent,
                                       [](const std::pair<Node_index, Node>& x, Node_index p) { return x.first < p; });
      at->second.first_child = first;
    }
  };

  // Splits `root` (at index `root_index` of `out`) and its descendants, depth first, each split
  // node's 8 children appended to `out` as one block: the sequential layout from `out.size()` on.
  // A node to split for which `defer(node, index)` returns `true` is left to the caller.
  template <typename Out, typename Defer>
  void split_depth_first(const Keys& keys, const Node& root, Node_index root_index, Out& out, const Defer& defer) const
  {
    std::vector<std::pair<Node, Node_index>> pending{{root, root_index}};
    while(!pending.empty())
    {
      const std::pair<Node, Node_index> top = pending.back();
      pending.pop_back();
      const Node& nd = top.first;
      if(!is_split(keys, nd) || defer(nd, top.second))
        continue;
      const unsigned shift = 3 * (depth_ - 1 - nd.level);
      const Node_index first = out.size();
      out.set_first_child(top.second, first);
      std::array<Node, 8> children;
      std::uint32_t begin = nd.begin;
      for(std::uint64_t oct = 0; oct < 8; ++oct)
      {
        std::uint32_t end = nd.end;
        if(oct < 7)
          end = std::uint32_t(std::partition_point(keys.begin() + begin, keys.begin() + nd.end,
                                                   [&](const Key& k) {
                                                     return ((k.code >> shift) & 7) <= oct;
                                                   }) -
                              keys.begin());
        children[oct] = Node{begin, end, 0, nd.level + 1};
        out.push_back(children[oct]);
        begin = end;
      }
      for(Node_index oct = 8; oct-- > 0;)
        if(children[oct].end - children[oct].begin > capacity_)
          pending.emplace_back(children[oct], first + oct);
    }
  }

  // the smallest number of subtrees `build_nodes_by_subtrees()` looks for below its level
  static constexpr std::size_t subtrees_wanted = 64;

  template <typename ConcurrencyTag>
  void build_nodes_by_subtrees(const Keys& keys, const Node& root)
  {
    // The level: the first with `subtrees_wanted` nodes to split, or the deepest holding any
    // (it depends on the keys only). The subtrees below it, in the order of the layout.
    std::vector<Node> subtrees;
    Node_index above = 1; // the nodes above the level and on it, the root included
    std::uint32_t subtree_level = 1;
    for(std::uint32_t level = 1;; ++level)
    {
      std::vector<Node> found;
      Counted_nodes counted{1};
      split_depth_first(keys, root, 0, counted, [&](const Node& nd, Node_index) {
        if(nd.level < level)
          return false;
        found.push_back(nd);
        return true;
      });
      if(found.empty() && level > 1)
        break; // the level above held the deepest nodes to split
      subtrees.swap(found);
      above = counted.next;
      subtree_level = level;
      if(subtrees.size() >= subtrees_wanted || subtrees.empty() || level >= depth_)
        break;
    }
    std::vector<Node_index> room(subtrees.size());
    internal::for_each_index<ConcurrencyTag>(subtrees.size(), [&](std::size_t k) {
      Counted_nodes counted;
      split_depth_first(keys, subtrees[k], 0, counted, [](const Node&, Node_index) { return false; });
      room[k] = counted.next;
    }, 1);
    std::size_t total = above;
    for(Node_index r : room)
      total += r;
    if(total >= std::size_t(npos))
      throw std::length_error("Soup_topology::Octree: too many nodes");
    // The nodes above the level, each subtree's room left after its root's block, listed first:
    // they lie between the rooms, all over the array, whose pages the subtrees' threads touch
    // first; they are written last.
    std::vector<std::pair<Node_index, Node_index>> placed(subtrees.size()); // (root's index, start of its room)
    std::size_t k = 0;
    Listed_nodes above_level{{{0, root}}, 1};
    split_depth_first(keys, root, 0, above_level, [&](const Node& nd, Node_index ni) {
      if(nd.level < subtree_level)
        return false;
      placed[k] = {ni, above_level.next};
      above_level.set_first_child(ni, above_level.next);
      above_level.next += room[k++];
      return true;
    });
    nodes_.resize(total); // (every node written below)
    internal::for_each_index<ConcurrencyTag>(subtrees.size(), [&](std::size_t j) {
      Placed_nodes in_room{nodes_.data(), placed[j].second, placed[j].second};
      split_depth_first(keys, subtrees[j], placed[j].first, in_room, [](const Node&, Node_index) { return false; });
    }, 1);
    for(const std::pair<Node_index, Node>& listed : above_level.listed)
      nodes_[listed.first] = listed.second;
  }

  // sorts by (code, id) each run of keys that share the bits above `low` in [first, last), which
  // starts and ends with a run
  static void sort_runs(Keys& keys, std::size_t first, std::size_t last, unsigned low)
  {
    const auto less = [](const Key& x, const Key& y) {
      return x.code < y.code || (x.code == y.code && x.id < y.id);
    };
    for(std::size_t b = first; b < last;)
    {
      std::size_t e = b + 1;
      while(e < last && (keys[e].code >> low) == (keys[b].code >> low))
        ++e;
      if(e - b > 1)
        std::sort(keys.begin() + std::ptrdiff_t(b), keys.begin() + std::ptrdiff_t(e), less);
      b = e;
    }
  }

  std::uint64_t code_of(const std::array<double, 3>& c) const
  {
    return internal::morton_encode_3(index_of(c[0], 0, 0), index_of(c[1], 1, 0),
                                     index_of(c[2], 2, 0));
  }

  std::array<double, 3> coords(std::uint32_t k) const
  {
    if constexpr(double_coordinates)
    {
      const Point_3& p = points_[k];
      return {{p.x(), p.y(), p.z()}};
    }
    else
      return approx_[k];
  }

  // integer address along `axis` of coordinate `x`, clamped; `widen` moves it one cell away
  std::uint32_t index_of(double x, std::size_t axis, int widen) const
  {
    const double t = (x - origin_[axis]) * scale_;
    if(std::isnan(t))
      return widen > 0 ? top_ : 0;
    if(t < 0)
      return 0;
    if(t >= double(top_) + 1)
      return top_;
    const std::int64_t i = std::int64_t(t) + widen; // truncation is floor here, t >= 0
    return i <= 0 ? 0 : (i >= std::int64_t(top_) ? top_ : std::uint32_t(i));
  }

  std::uint32_t position(std::size_t i) const
  {
    if(i >= positions_.size())
      throw Invalid_input("Soup_topology::Octree: point index out of range");
    return positions_[i];
  }

  static void check_radius(const FT& radius)
  {
    if(!(radius >= FT(0)))
      throw Invalid_input("Soup_topology::Octree: the radius must be non-negative");
  }

  Query_point approximate(const Point_3& p) const
  {
    Query_point r;
    r.err = 0;
    const std::pair<double, double> iv[3] = {CGAL::to_interval(p.x()), CGAL::to_interval(p.y()),
                                            CGAL::to_interval(p.z())};
    for(std::size_t k = 0; k < 3; ++k)
    {
      r.c[k] = iv[k].first == iv[k].second ? iv[k].first : 0.5 * iv[k].first + 0.5 * iv[k].second;
      const double e = iv[k].second - iv[k].first;
      r.err = std::max(r.err, std::isfinite(e) ? e : std::numeric_limits<double>::infinity());
    }
    if(!std::isfinite(r.c[0]) || !std::isfinite(r.c[1]) || !std::isfinite(r.c[2]))
      r.err = std::numeric_limits<double>::infinity();
    return r;
  }

  // appends to `found` the index of every point of leaf `nd` within sqrt(r2) of `q` (`qc` its
  // coordinates in double, `bound2` the widened squared radius of the pruning). With double
  // coordinates the squared distance computed in double is within a few ulps of the exact one:
  // far from r2 it decides alone, near it the kernel decides.
  template <typename Collector>
  void scan_leaf(const Node& nd, const Point_3& q, const std::array<double, 3>& qc, const FT& r2, double bound2,
                 Collector& found) const
  {
    typename Geom_traits::Compare_squared_distance_3 compare_sq = gt_.compare_squared_distance_3_object();
    for(std::uint32_t j = nd.begin; j != nd.end; ++j)
      if(is_near(j, q, qc, r2, bound2, compare_sq))
        found.push_back(ids_[j]);
  }

  // whether the point stored at `j` is within sqrt(r2) of `q`: the decision of every radius
  // query. A point whose squared distance computed in double exceeds `bound2` is out; with
  // double coordinates that distance is within a relative 5 ulps of the exact one (a sum of
  // rounded squares of rounded differences, all non-negative, away from underflow), so that far
  // enough from r2 it decides alone; near r2 the kernel decides.
  bool is_near(std::uint32_t j, const Point_3& q, const std::array<double, 3>& qc, const FT& r2, double bound2,
               typename Geom_traits::Compare_squared_distance_3& compare_sq) const
  {
    const double d2 = point_squared_distance(j, qc);
    if(d2 > bound2)
      return false;
    if constexpr(double_coordinates)
    {
      const double r2d = r2;
      if(r2d > 1e-250 && r2d < 1e250)
      {
        if(d2 < r2d * (1 - 1e-12) && (d2 == 0 || d2 > 1e-250))
          return true;
        if(d2 > r2d * (1 + 1e-12))
          return false;
      }
    }
    return compare_sq(q, points_[j], r2) != CGAL::LARGER;
  }

  // an upper bound on the radius, widened by every error of the double computations
  double radius_bound(const FT& r2, double query_err) const
  {
    const double r2hi = CGAL::to_interval(r2).second;
    return (std::sqrt(r2hi) + margin_ + 2 * query_err) * (1 + 1e-12);
  }

  Frame child_frame(const Frame& f, const Node& nd, int i) const
  {
    Frame c;
    c.node = nd.first_child + Node_index(i);
    c.c[0] = (f.c[0] << 1) | std::uint32_t((i >> 2) & 1);
    c.c[1] = (f.c[1] << 1) | std::uint32_t((i >> 1) & 1);
    c.c[2] = (f.c[2] << 1) | std::uint32_t(i & 1);
    return c;
  }

  double box_point_squared_distance(const Frame& f, const std::array<double, 3>& q) const
  {
    const double cs = cell_size_[nodes_[f.node].level];
    double d2 = 0;
    for(std::size_t i = 0; i < 3; ++i)
    {
      const double lo = origin_[i] + f.c[i] * cs;
      const double g = std::max({lo - q[i], q[i] - (lo + cs), 0.});
      d2 += g * g;
    }
    return d2;
  }

  double point_squared_distance(std::uint32_t k, const std::array<double, 3>& q) const
  {
    const std::array<double, 3> p = coords(k);
    const double dx = p[0] - q[0], dy = p[1] - q[1], dz = p[2] - q[2];
    return dx * dx + dy * dy + dz * dz;
  }

  // whether the coordinates of the point stored at `k` lie in the box [lo, hi]
  bool in_box(std::uint32_t k, const double* lo, const double* hi) const
  {
    const std::array<double, 3> p = coords(k);
    return p[0] >= lo[0] && p[0] <= hi[0] && p[1] >= lo[1] && p[1] <= hi[1] && p[2] >= lo[2] && p[2] <= hi[2];
  }

  double point_segment_squared_distance(std::uint32_t k, const Segment_approx& s) const
  {
    double scale = 0;
    return point_segment_squared_distance(k, s, scale);
  }

  // the squared distance computed in double from the point stored at `k` to the approximate
  // segment `s` (to its point at the projection parameter computed in double), and in `scale` the
  // largest absolute coordinate difference of the computation (of `p - a` and of the direction)
  double point_segment_squared_distance(std::uint32_t k, const Segment_approx& s, double& scale) const
  {
    return point_segment_squared_distance(coords(k), s, scale);
  }

  // the same for the approximate coordinates `p` of a stored point
  static double point_segment_squared_distance(const std::array<double, 3>& p, const Segment_approx& s, double& scale)
  {
    const double v[3] = {p[0] - s.a[0], p[1] - s.a[1], p[2] - s.a[2]};
    scale = std::max({std::abs(v[0]), std::abs(v[1]), std::abs(v[2]), std::abs(s.d[0]), std::abs(s.d[1]), std::abs(s.d[2])});
    double t = 0;
    if(s.len2 > 0)
    {
      t = (v[0] * s.d[0] + v[1] * s.d[1] + v[2] * s.d[2]) / s.len2;
      t = t < 0 ? 0 : (t > 1 ? 1 : t);
    }
    double d2 = 0;
    for(std::size_t i = 0; i < 3; ++i)
    {
      const double w = v[i] - t * s.d[i];
      d2 += w * w;
    }
    return d2;
  }

  // does the segment cross the box of `f` grown by `grow` (equations (28)-(29), conservative)?
  bool box_meets_segment(const Frame& f, const Segment_approx& s, double grow) const
  {
    const double cs = cell_size_[nodes_[f.node].level];
    const double tol = 1e-9;
    double tmin = -tol, tmax = 1 + tol;
    for(std::size_t i = 0; i < 3; ++i)
    {
      const double lo = origin_[i] + f.c[i] * cs - grow;
      const double hi = origin_[i] + f.c[i] * cs + cs + grow;
      if(s.d[i] == 0)
      {
        if(s.a[i] < lo || s.a[i] > hi)
          return false;
        continue;
      }
      const double inv = 1.0 / s.d[i];
      double t0 = (lo - s.a[i]) * inv, t1 = (hi - s.a[i]) * inv;
      if(t0 > t1)
        std::swap(t0, t1);
      tmin = std::max(tmin, t0 - tol);
      tmax = std::min(tmax, t1 + tol);
      if(tmin > tmax)
        return false;
    }
    return true;
  }

  Geom_traits gt_;
  Segment_query_strategy strategy_ = Segment_query_strategy::INDEX_SPACE_BOX;
  std::size_t capacity_ = default_bucket_capacity;
  unsigned depth_ = default_maximum_depth;
  std::array<double, 3> origin_{};
  double side_ = 1, scale_ = 1, margin_ = 0;
  std::uint32_t top_ = 0; // the largest address, 2^n - 1
  std::vector<double> cell_size_;

  // (the large arrays below are `Uninitialized_vector`s: their blocks come in huge pages, and a
  // copy of the points is written whole by the build)
  internal::Uninitialized_vector<Point_3> points_; // sorted by (Morton code, index)
  std::vector<std::array<double, 3>> approx_;    // their coordinates in double (if FT is not)
  internal::Uninitialized_vector<std::uint32_t> ids_;       // their indices in the input range
  internal::Uninitialized_vector<std::uint32_t> positions_; // input index -> sorted position
  internal::Uninitialized_vector<Node> nodes_;
};

} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_OCTREE_H
