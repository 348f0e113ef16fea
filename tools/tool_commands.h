// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The commands of the command-line tools, compiled once (tools/tool_commands.cpp) for both
// programs: `soup_topology` (tools/soup_topology.cpp) and `soup_topology_mpi`
// (tools/soup_topology_mpi.cpp), whose own sources hold little more than `main`.

#ifndef SOUP_TOPOLOGY_TOOL_COMMANDS_H
#define SOUP_TOPOLOGY_TOOL_COMMANDS_H

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace soup_topology_tool {

/// The team of processes that share the tiles of `repair --tiles N`: the `TileTeam` of
/// `Soup_topology::tiled_reconstruct_topology()` behind virtual functions, so that the tiled repair
/// of the tool is compiled once, for one process and for the ranks of an MPI job alike.
class Tile_team
{
public:
  virtual ~Tile_team() = default;
  virtual std::size_t rank() const = 0;
  virtual std::size_t size() const = 0;
  /// rank 0's `bytes` to every rank.
  virtual void broadcast(std::vector<char>& bytes) = 0;
  /// every rank's `values`, rank 0's first, on every rank.
  virtual std::vector<std::uint64_t> all_gather(const std::vector<std::uint64_t>& values) = 0;
};

/// `team`, a model of `TileTeam`, as a `Tile_team` (it refers to `team`, which must outlive it).
template <class TileTeam>
class Tile_team_of final : public Tile_team
{
public:
  explicit Tile_team_of(TileTeam& team) : team_(team) {}
  std::size_t rank() const override { return team_.rank(); }
  std::size_t size() const override { return team_.size(); }
  void broadcast(std::vector<char>& bytes) override { team_.broadcast(bytes); }
  std::vector<std::uint64_t> all_gather(const std::vector<std::uint64_t>& values) override
  {
    return team_.all_gather(values);
  }

private:
  TileTeam& team_;
};

/// `soup_topology ARGS...` (`args`: the arguments after the program's name): runs the command,
/// prints its report or the error, and gives the exit code.
int run_tool(std::vector<std::string> args);

/// `soup_topology_mpi ARGS...` on one rank of `team`. Help and bad arguments are answered by every
/// rank alike (rank 0 prints), with the exit code; an error of the repair itself throws, on the
/// rank that met it, for the caller to end the whole job.
int run_mpi_tool(const std::vector<std::string>& args, Tile_team& team);

/// `soup_topology_mpi ARGS...` before `MPI_Init`: under `--max-memory`, executes the program again
/// with its large blocks in huge pages, as `soup_topology repair --max-memory` does
/// (`memory_reuse.h`), so that every rank starts that way. Returns otherwise, and with arguments
/// that do not parse (`run_mpi_tool()` reports them, on every rank alike).
void restart_mpi_tool_for_its_memory_limit(const std::vector<std::string>& args);

} // namespace soup_topology_tool

#endif // SOUP_TOPOLOGY_TOOL_COMMANDS_H
