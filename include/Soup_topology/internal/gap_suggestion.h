// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The summaries of the gap analysis: log-scaled histograms, size distributions, and the choice of
// the tolerance from the sorted gaps and the feature bound.

#ifndef SOUP_TOPOLOGY_INTERNAL_GAP_SUGGESTION_H
#define SOUP_TOPOLOGY_INTERNAL_GAP_SUGGESTION_H

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace Soup_topology {
namespace internal {

/// bins per decade of the log-scaled histograms.
constexpr int gap_histogram_bins_per_decade = 4;

/// a tolerance is suggested only between two gaps (or a gap and the feature bound) whose ratio is
/// at least this: the tolerance, their geometric mean, then keeps a factor sqrt(2) on both sides.
constexpr double gap_separation_factor = 2;

/// a bin of a log-scaled histogram: the values in [lower, upper).
template <class Bin>
std::vector<Bin> log_histogram(const std::vector<double>& sorted_values)
{
  std::vector<Bin> bins;
  const auto first = std::upper_bound(sorted_values.begin(), sorted_values.end(), 0.0);
  if(first == sorted_values.end()) return bins;
  const double step = 1.0 / gap_histogram_bins_per_decade;
  const auto edge = [step](long k) { return std::pow(10.0, static_cast<double>(k) * step); };
  long k = static_cast<long>(std::floor(std::log10(*first) / step));
  while(edge(k) > *first) --k;                 // rounding of log10 and pow
  while(edge(k + 1) <= *first) ++k;
  for(auto it = first; it != sorted_values.end();) {
    const double upper = edge(k + 1);
    const auto end = std::lower_bound(it, sorted_values.end(), upper);
    bins.push_back(Bin{edge(k), upper, static_cast<std::size_t>(end - it)});
    it = end;
    ++k;
  }
  return bins;
}

/// where the tolerance goes in the sorted gaps: the largest `closed` such that the gaps
/// `sorted[0..closed)` lie below `bound` and the next value (the next gap, or `bound`) is at least
/// `gap_separation_factor` times the last closed gap; 0 if none.
inline std::size_t closed_gap_count(const std::vector<double>& sorted, double bound)
{
  std::size_t best = 0;
  for(std::size_t k = 0; k < sorted.size() && sorted[k] < bound; ++k) {
    const double next = k + 1 < sorted.size() ? std::min(sorted[k + 1], bound) : bound;
    if(next >= gap_separation_factor * sorted[k] && next > sorted[k]) best = k + 1;
  }
  return best;
}

/// the tolerance between the largest closed gap `low` and the first value kept open `high`:
/// their geometric mean, or `high / 2` when `low` is 0.
inline double tolerance_between(double low, double high)
{
  return low > 0 ? std::sqrt(low) * std::sqrt(high) : high / 2;
}

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_GAP_SUGGESTION_H
