// Copyright (c) 2024 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

/*!
\ingroup PkgSoupTopologyConcepts
\cgalConcept

The concept `SpatialIndex` describes the proximity queries the snapping code asks of an index over
the points of a random-access range (the vertices of a soup). A point is designated by its index
in the range given at construction. The two questions of snapping are "which vertices are within
`radius` of this point" and "which vertices are within `radius` of this closed segment".

A model decides every answer with the kernel's predicates: `p` is within `radius` of `q` if
`Compare_squared_distance_3()(q, p, radius*radius) != LARGER`, and within `radius` of `[a,b]` if
`Compare_squared_distance_3()(p, Segment_3(a,b), radius*radius) != LARGER`, so that with an exact
predicates kernel the answers are exact for the input coordinates. Any pruning done in floating
point must be conservative. All queries are `const` and may run concurrently.

\cgalHasModelsBegin
\cgalHasModels{Soup_topology::Octree<GeomTraits, PointMap>}
\cgalHasModelsEnd

\sa `Soup_topology::Octree`
*/
class SpatialIndex
{
public:
  /// \name Types
  /// @{

  /// a CGAL kernel
  typedef unspecified_type Geom_traits;
  /// `Geom_traits::FT`
  typedef unspecified_type FT;
  /// `Geom_traits::Point_3`
  typedef unspecified_type Point_3;

  /// @}

  /// \name Queries
  /// Each throws `std::invalid_argument` if `radius` is negative or NaN. An empty index answers nothing.
  /// @{

  /// returns the index of the point closest to `q` among the points within `radius` of `q`,
  /// the smallest index among equally close points, or `std::nullopt`.
  std::optional<std::size_t> nearest_vertex(const Point_3& q, const FT& radius) const;

  /// writes to `out` the index of every point within `radius` of `q`, in increasing order.
  /// \tparam OutputIterator an output iterator accepting `std::size_t`
  template <typename OutputIterator>
  OutputIterator vertices_near_point(const Point_3& q, const FT& radius, OutputIterator out) const;

  /// writes to `out` the index of every point within `radius` of the closed segment `[a,b]`
  /// (not of the line through `a` and `b`), in increasing order; `a == b` is allowed.
  /// \tparam OutputIterator an output iterator accepting `std::size_t`
  template <typename OutputIterator>
  OutputIterator vertices_near_segment(const Point_3& a, const Point_3& b, const FT& radius,
                                       OutputIterator out) const;

  /// the number of points
  std::size_t size() const;

  /// @}
};
