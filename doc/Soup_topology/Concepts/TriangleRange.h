/*!
\ingroup PkgSoupTopologyConcepts
\cgalConcept

A range of triangles of an indexed soup: a random-access range whose elements are random-access
ranges of 3 vertex indices into a point range. Algorithms that change the soup need a
`std::vector`-like container (`push_back`, `resize`, `erase`).

Local edge numbering, used everywhere in the package: edge `i` of a triangle `(v0, v1, v2)` is
`(v_i, v_{(i+1) mod 3})`.

| Valid expression | Meaning |
|---|---|
| `std::begin(f)`, `std::end(f)` for an element `f` | its 3 indices, any integral type (signed ones must be >= 0) |
| `f[k]` | index `k` |
| `triangles.size()` | number of triangles |

Bad elements (not 3 indices, an index out of range, a repeated index) make every function throw
`Soup_topology::Invalid_input`, naming the face, before anything is changed.

\cgalHasModelsBegin
\cgalHasModels{`std::vector<std::array<std::size_t,3>>`}
\cgalHasModels{`std::vector<std::vector<int>>`}
\cgalHasModels{`std::vector<std::array<std::uint32_t,3>>`}
\cgalHasModelsEnd
*/
class TriangleRange {};
