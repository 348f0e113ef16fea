// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// libFuzzer target: OBJ, in memory through read_OBJ_polygons(), then the whole
// read_triangle_soup() path on a file (our reader, fan triangulation and exact weld).

#include "fuzz_common.h"

#include <Soup_topology/IO/OBJ.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  soup_fuzz::check_polygon_reader(
    [&](std::vector<soup_fuzz::Point>& points, std::vector<std::vector<std::size_t>>& polygons) {
      return Soup_topology::IO::read_OBJ_polygons(reinterpret_cast<const char*>(data), size, points, polygons,
                                                  "fuzz.obj");
    },
    "fuzz.obj:", "no line");
  soup_fuzz::read_through_file(data, size, "obj");
  return 0;
}
