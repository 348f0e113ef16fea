// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// libFuzzer target: VRML 2.0, through read_VRML() on a std::istringstream. Seeds and a dictionary
// of the grammar (DEF/USE, nested transforms, shared Coordinates, non-convex polygons):
// fuzz/corpus/vrml/ and fuzz/vrml.dict.

#include "fuzz_common.h"

#include <Soup_topology/IO/VRML.h>

#include <sstream>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  std::vector<soup_fuzz::Point> points(3);
  std::vector<soup_fuzz::Triangle> triangles{{0, 1, 2}};
  try {
    const auto r = Soup_topology::IO::read_VRML(in, points, triangles);
    SOUP_FUZZ_CHECK(points.size() == 3 + r.number_of_points, "point count");
    SOUP_FUZZ_CHECK(triangles.size() == 1 + r.number_of_triangles, "triangle count");
    SOUP_FUZZ_CHECK(r.triangle_shape_ids.size() == r.number_of_triangles, "shape ids");
    // the default budget bounds what a file of this size may expand to
    SOUP_FUZZ_CHECK(r.number_of_points + r.number_of_triangles
                      <= Soup_topology::IO::VRML_read_options::budget(std::size_t(1) << 21, 8, size),
                    "output beyond the budget");
    for(std::size_t t = 1; t < triangles.size(); ++t)
      for(std::size_t v : triangles[t]) SOUP_FUZZ_CHECK(v >= 3 && v < points.size(), "index out of range");
  } catch(const Soup_topology::IO::Read_error& e) {
    SOUP_FUZZ_CHECK(points.size() == 3 && triangles.size() == 1, "containers changed by a failed read");
    SOUP_FUZZ_CHECK(std::string(e.what()).rfind("VRML:", 0) == 0, std::string("no line in ") + e.what());
  }
  return 0;
}
