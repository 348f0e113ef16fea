/*!
\ingroup PkgSoupTopologyConcepts
\cgalConcept

The visitor of `snap_vertices()`, given with `CGAL::parameters::visitor(v)` (a copy) or
`CGAL::parameters::visitor(std::ref(v))` (the caller's object).

| Valid expression | Meaning |
|---|---|
| `v.on_merge(duplicate, representative)` | every reference to `duplicate` is replaced by `representative` |
| `v.on_refusal(vertex, representative, reason)` | the merge was refused, `reason` a `Soup_topology::Refusal_reason` |

\cgalHasModelsBegin
\cgalHasModels{`Soup_topology::Default_snap_visitor`}
\cgalHasModelsEnd
*/
class SnapVisitor {};
