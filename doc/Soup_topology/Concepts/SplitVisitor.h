/*!
\ingroup PkgSoupTopologyConcepts
\cgalConcept

The visitor of `split_t_junctions()`, given with `CGAL::parameters::visitor(v)` (a copy) or
`CGAL::parameters::visitor(std::ref(v))` (the caller's object). Every call names a vertex and the
border edge `[a, b]` it was found near, by their indices in the point range; the vertex lies
within the tolerance of that edge, so its point locates the event. The calls come in the same
order on any number of threads. `reconstruct_topology()` calls these members too when its visitor
has all three, with the indices of its input points.

| Valid expression | Meaning |
|---|---|
| `v.on_split(vertex, a, b)` | the triangle along the border edge `[a, b]` is split at `vertex` |
| `v.on_split_refusal(vertex, a, b, reason)` | the split is refused, `reason` a `Soup_topology::Split_refusal_reason` |
| `v.on_ambiguous_t_junction(vertex, a, b)` | `vertex` is near several border edges (`[a, b]` the nearest) or within twice the tolerance of an end point |

\cgalHasModelsBegin
\cgalHasModels{`Soup_topology::Default_split_visitor`}
\cgalHasModels{`Soup_topology::IO::Html_report_site_recorder`}
\cgalHasModelsEnd
*/
class SplitVisitor {};
