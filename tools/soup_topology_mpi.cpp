// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// soup_topology_mpi: `soup_topology repair --tiles N` shared by the ranks of an MPI job
// (`soup_topology_mpi --help`; the command is in tools/tool_commands.cpp).

#include "tool_commands.h"

#include <Soup_topology/Invalid_input.h>
#include <Soup_topology/Mpi_tile_team.h>

#include <exception>
#include <iostream>
#include <string>
#include <vector>

int main(int argc, char** argv)
{
  // (before MPI starts: the process may be executed again, as it was launched)
  soup_topology_tool::restart_mpi_tool_for_its_memory_limit(std::vector<std::string>(argv + 1, argv + argc));
  MPI_Init(&argc, &argv);
  Soup_topology::Mpi_tile_team ranks;
  soup_topology_tool::Tile_team_of<Soup_topology::Mpi_tile_team> team(ranks);
  int code = 0;
  try {
    code = soup_topology_tool::run_mpi_tool(std::vector<std::string>(argv + 1, argv + argc), team);
  } catch(const std::exception& e) {
    // The other ranks may wait for this one: the whole job ends.
    std::cerr << "soup_topology_mpi: rank " << ranks.rank() << ": "
              << (dynamic_cast<const Soup_topology::Invalid_input*>(&e) != nullptr ? "invalid input: " : "")
              << e.what() << "\n";
    MPI_Abort(MPI_COMM_WORLD, 2);
    return 2;
  }
  MPI_Finalize();
  return code;
}
