/*!
\ingroup PkgSoupTopologyConcepts
\cgalConcept

The geometric traits of the package: the few types and functors the algorithms ask geometry for.
Only two questions decide the topology (is a vertex within the tolerance of a vertex, and of a
segment), plus the orientation tests that keep triangles from degenerating or flipping. With
`CGAL::Exact_predicates_inexact_constructions_kernel` and
`CGAL::Exact_predicates_exact_constructions_kernel` every answer is exact for the input
coordinates; no algorithm of the package constructs a point, except `loop_subdivision()`.

| Valid expression | Type | Meaning |
|---|---|---|
| `GT::FT` | a field number type | coordinates, tolerances |
| `GT::Point_3`, `GT::Segment_3` | | points, the segments of border edges |
| `gt.compare_squared_distance_3_object()(p, q, d2)` | `CGAL::Comparison_result` | vertex within the tolerance of a vertex |
| `gt.compare_squared_distance_3_object()(p, s, d2)` | `CGAL::Comparison_result` | vertex within the tolerance of a segment (not of its line) |
| `gt.compare_distance_3_object()(p, q, r)` | `CGAL::Comparison_result` | nearest first, along an edge |
| `gt.less_xyz_3_object()(p, q)` | `bool` | canonical representatives and orders |
| `gt.equal_3_object()(p, q)` | `bool` | exact weld (non-`double` number types) |
| `gt.collinear_3_object()(p, q, r)` | `bool` | degenerate triangles |
| `gt.orientation_3_object()(p, q, r, s)`, `gt.coplanar_orientation_3_object()(p, q, r, s)` | `CGAL::Orientation` | overlapping triangles at a T-junction |
| `gt.construct_segment_3_object()(p, q)` | `GT::Segment_3` | |
| `gt.compute_squared_distance_3_object()(p, q)` | `GT::FT` | the reported displacement |

`reconstruct_topology()` converts the points to `GT::Point_3` (constructed from three `GT::FT`),
so the traits need not be the kernel of the points. With
`Soup_topology::parameters::count_self_intersections(true)` it also needs `GT::Triangle_3`,
`gt.construct_triangle_3_object()`, `gt.coplanar_3_object()` and `gt.do_intersect_3_object()`
on a triangle and a triangle or a segment, and `GT::Point_3::bbox()`.

The sign of the dot product of two triangle normals (the flip test) is evaluated exactly by the
package itself: intervals first, exact rationals when they do not decide, for `double`
coordinates; the number type itself otherwise.

\cgalHasModelsBegin
\cgalHasModels{every CGAL Kernel: `CGAL::Simple_cartesian<double>`, `CGAL::Exact_predicates_inexact_constructions_kernel`, `CGAL::Exact_predicates_exact_constructions_kernel`, `CGAL::Simple_cartesian<CGAL::Exact_rational>`}
\cgalHasModelsEnd
The default is the kernel of the point type, `CGAL::Kernel_traits<Point_3>::Kernel`.
*/
class SoupTopologyTraits {};
