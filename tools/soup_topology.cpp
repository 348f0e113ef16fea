// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// soup_topology: the command-line face of the library (`soup_topology --help`; the commands are
// in tools/tool_commands.cpp).

#include "tool_commands.h"

int main(int argc, char** argv)
{
  return soup_topology_tool::run_tool(std::vector<std::string>(argv + 1, argv + argc));
}
