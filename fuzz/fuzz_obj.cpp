// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// libFuzzer target: OBJ, in memory through read_OBJ_polygons(), then the whole
// read_triangle_soup() path on a file (our reader, fan triangulation and exact weld).
#include "fuzz_common.h"
#include <Soup_topology/IO/OBJ.h>
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  std::vector<soup_fuzz::Point> points(2);
  std::vector<std::vector<std::size_t>> polygons(1);
  try {
    const auto r = Soup_topology::IO::read_OBJ_polygons(reinterpret_cast<const char*>(data), size, points, polygons,
                                                       "fuzz.obj");
    SOUP_FUZZ_CHECK(points.size() == 2 + r.vertices && polygons.size() == 1 + r.faces, "counts");
    for(std::size_t f = 1; f < polygons.size(); ++f)
      for(std::size_t v : polygons[f]) SOUP_FUZZ_CHECK(v >= 2 && v < points.size(), "index out of range");
    for(const auto& p : points)
      SOUP_FUZZ_CHECK(std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()), "non-finite point");
  } catch(const Soup_topology::IO::Read_error& e) {
    SOUP_FUZZ_CHECK(points.size() == 2 && polygons.size() == 1, "containers changed by a failed read");
    SOUP_FUZZ_CHECK(std::string(e.what()).rfind("fuzz.obj:", 0) == 0, std::string("no line in ") + e.what());
  }
  soup_fuzz::read_through_file(data, size, "obj");
  return 0;
}
