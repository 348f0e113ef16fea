// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// libFuzzer target: PLY, through read_triangle_soup() on a file (CGAL's reader, then our
// checks, fan triangulation and exact weld).

#include "fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  soup_fuzz::read_through_file(data, size, "ply");
  return 0;
}
