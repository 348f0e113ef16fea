// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Named-parameter tags and builders of `Soup_topology::loop_subdivision()` and of the limit
// functions. Included by `Soup_topology/loop_subdivision.h` (and by the package's `parameters.h`).

#ifndef SOUP_TOPOLOGY_INTERNAL_SUBDIVISION_PARAMETERS_H
#define SOUP_TOPOLOGY_INTERNAL_SUBDIVISION_PARAMETERS_H

#include <CGAL/Named_function_parameters.h>

namespace Soup_topology {

class Adjacency_tables;

/// \ingroup PkgSoupTopologyRef
/// \brief the weight `beta` given to each of the `k` neighbours of a smooth vertex of valence `k`
/// by Loop's vertex rule `(1 - k beta) p + beta sum(q_i)`.
enum class Loop_beta
{
  /// Loop's original choice, `beta = (5/8 - (3/8 + 1/4 cos(2 pi / k))^2) / k` (the default; the
  /// one of `CGAL::Subdivision_method_3::Loop_subdivision`).
  loop,
  /// Warren's simplification, `beta = 3 / (8 k)` for `k > 3` and `3/16` for `k = 3`.
  warren
};

namespace internal_np {

/// the choice of `beta` of Loop's vertex rule, a value of `Soup_topology::Loop_beta`
enum loop_beta_t { loop_beta };
/// a pointer to an `Adjacency_tables` that receives the tables of the subdivided soup
enum output_adjacency_tables_t { output_adjacency_tables };

} // namespace internal_np

namespace parameters {

using CGAL::parameters::default_values;

// loop_beta

/// starts a named-parameter chain with `loop_beta`
inline CGAL::Named_function_parameters<Loop_beta, internal_np::loop_beta_t>
loop_beta(Loop_beta b)
{
  return CGAL::Named_function_parameters<Loop_beta, internal_np::loop_beta_t>(b);
}

/// appends `loop_beta` to an existing named-parameter chain
template <typename T, typename Tag, typename Base>
CGAL::Named_function_parameters<Loop_beta, internal_np::loop_beta_t, CGAL::Named_function_parameters<T, Tag, Base>>
loop_beta(Loop_beta b, const CGAL::Named_function_parameters<T, Tag, Base>& np)
{
  return CGAL::Named_function_parameters<Loop_beta, internal_np::loop_beta_t,
                                         CGAL::Named_function_parameters<T, Tag, Base>>(b, np);
}

// output_adjacency_tables

/// starts a named-parameter chain with `output_adjacency_tables`
inline CGAL::Named_function_parameters<Adjacency_tables*, internal_np::output_adjacency_tables_t>
output_adjacency_tables(Adjacency_tables* tables)
{
  return CGAL::Named_function_parameters<Adjacency_tables*, internal_np::output_adjacency_tables_t>(tables);
}

/// appends `output_adjacency_tables` to an existing named-parameter chain
template <typename T, typename Tag, typename Base>
CGAL::Named_function_parameters<Adjacency_tables*, internal_np::output_adjacency_tables_t,
                                CGAL::Named_function_parameters<T, Tag, Base>>
output_adjacency_tables(Adjacency_tables* tables, const CGAL::Named_function_parameters<T, Tag, Base>& np)
{
  return CGAL::Named_function_parameters<Adjacency_tables*, internal_np::output_adjacency_tables_t,
                                         CGAL::Named_function_parameters<T, Tag, Base>>(tables, np);
}

} // namespace parameters
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_SUBDIVISION_PARAMETERS_H
