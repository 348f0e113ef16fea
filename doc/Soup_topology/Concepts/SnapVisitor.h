/*!
\ingroup PkgSoupTopologyConcepts
\cgalConcept

The visitor of `snap_vertices()` and `reconstruct_topology()`, given with
`CGAL::parameters::visitor(v)` (a copy) or `CGAL::parameters::visitor(std::ref(v))` (the caller's
object). `reconstruct_topology()` calls it for every weld and every refused weld of every round,
with the indices of its input points (a point merged by the exact weld is known by the first of
the equal points; for a mesh, the index of the vertex in the order of `vertices(mesh)`). A
visitor of `reconstruct_topology()` may also be a `SplitVisitor` (its members are then called by
the T-junction step), and may have `v.on_ambiguous_site(vertex)`, called once for every ambiguous
site of the weld, named by its smallest point.

| Valid expression | Meaning |
|---|---|
| `v.on_merge(duplicate, representative)` | every reference to `duplicate` is replaced by `representative` |
| `v.on_refusal(vertex, representative, reason)` | the merge was refused, `reason` a `Soup_topology::Refusal_reason` |

The merges are told on one thread, in increasing order of the merged vertices. A visitor class
with a member `static constexpr bool tells_merges_concurrently = true` allows them in any order:
with `CGAL::Parallel_tag`, `on_merge()` may then be called on TBB's threads, several at once
(each call must touch only what belongs to its `duplicate`); the calls are the same, on any number
of threads. `Soup_topology::Default_snap_visitor` takes them so, and so does the visitor that
`reconstruct_topology()` gives `snap_vertices()` when the caller gives none.

\cgalHasModelsBegin
\cgalHasModels{`Soup_topology::Default_snap_visitor`}
\cgalHasModels{`Soup_topology::IO::Html_report_site_recorder`}
\cgalHasModelsEnd
*/
class SnapVisitor {};
