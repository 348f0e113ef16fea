// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The processes of an MPI communicator as a team of `tiled_reconstruct_topology()`.

#ifndef SOUP_TOPOLOGY_MPI_TILE_TEAM_H
#define SOUP_TOPOLOGY_MPI_TILE_TEAM_H

// The C interface only: the deprecated C++ bindings are not used (and warn under -Wextra).
#ifndef OMPI_SKIP_MPICXX
#define OMPI_SKIP_MPICXX 1
#endif
#ifndef MPICH_SKIP_MPICXX
#define MPICH_SKIP_MPICXX 1
#endif
#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <vector>

namespace Soup_topology {

/// \ingroup PkgSoupTopologyTiling
/// \brief the processes of an MPI communicator (`MPI_COMM_WORLD` by default) as the team of
/// `tiled_reconstruct_topology()`: rank 0 plans, spills and merges, every rank repairs its share
/// of the tiles. `MPI_Init()` must have been called. Needs MPI (the package's other headers do
/// not); link with `MPI::MPI_CXX`.
class Mpi_tile_team
{
public:
  explicit Mpi_tile_team(MPI_Comm communicator = MPI_COMM_WORLD)
    : communicator_(communicator)
  {
    int rank = 0, size = 1;
    MPI_Comm_rank(communicator_, &rank);
    MPI_Comm_size(communicator_, &size);
    rank_ = static_cast<std::size_t>(rank);
    size_ = static_cast<std::size_t>(size);
  }

  std::size_t rank() const { return rank_; }
  std::size_t size() const { return size_; }

  /// rank 0's `bytes` to every rank.
  void broadcast(std::vector<char>& bytes)
  {
    std::uint64_t n = bytes.size();
    MPI_Bcast(&n, 1, MPI_UINT64_T, 0, communicator_);
    if(n > std::uint64_t(std::numeric_limits<int>::max()))
      throw std::length_error("Mpi_tile_team::broadcast: more than 2^31 bytes");
    bytes.resize(static_cast<std::size_t>(n));
    if(n > 0) MPI_Bcast(bytes.data(), static_cast<int>(n), MPI_CHAR, 0, communicator_);
  }

  /// every rank's `values`, rank 0's first, on every rank.
  std::vector<std::uint64_t> all_gather(const std::vector<std::uint64_t>& values)
  {
    if(values.size() > std::size_t(std::numeric_limits<int>::max()))
      throw std::length_error("Mpi_tile_team::all_gather: too many values");
    const int mine = static_cast<int>(values.size());
    std::vector<int> counts(size_), offsets(size_);
    MPI_Allgather(&mine, 1, MPI_INT, counts.data(), 1, MPI_INT, communicator_);
    std::size_t total = 0;
    for(std::size_t r = 0; r < size_; ++r) {
      if(total > std::size_t(std::numeric_limits<int>::max()))
        throw std::length_error("Mpi_tile_team::all_gather: too many values");
      offsets[r] = static_cast<int>(total);
      total += static_cast<std::size_t>(counts[r]);
    }
    std::vector<std::uint64_t> all(total);
    MPI_Allgatherv(values.data(), mine, MPI_UINT64_T, all.data(), counts.data(), offsets.data(), MPI_UINT64_T,
                   communicator_);
    return all;
  }

private:
  MPI_Comm communicator_;
  std::size_t rank_ = 0, size_ = 1;
};

} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_MPI_TILE_TEAM_H
