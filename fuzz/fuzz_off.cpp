// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// libFuzzer target: OFF, in memory through read_OFF_polygons(), then the whole
// read_triangle_soup() path on a file.

#include "fuzz_common.h"

#include <Soup_topology/IO/OFF.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string text(reinterpret_cast<const char*>(data), size);
  soup_fuzz::check_polygon_reader(
    [&](std::vector<soup_fuzz::Point>& points, std::vector<std::vector<std::size_t>>& polygons) {
      return Soup_topology::IO::read_OFF_polygons(text, points, polygons, "fuzz.off");
    },
    "fuzz.off:", "no line");
  soup_fuzz::read_through_file(data, size, "off");
  return 0;
}
