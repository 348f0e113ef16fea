// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// libFuzzer target: binary STL, in memory through read_STL_triangles(), then the whole
// read_triangle_soup() path on a file. Inputs that the reader would take for ASCII are left to
// fuzz_stl_ascii.

#include "fuzz_common.h"

#include <Soup_topology/IO/STL.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string text(reinterpret_cast<const char*>(data), size);
  if(Soup_topology::IO::internal::looks_like_ascii_stl(text)) return 0;
  std::vector<std::array<soup_fuzz::Point, 3>> triangles(1);
  try {
    const auto r = Soup_topology::IO::read_STL_triangles(text, triangles, "fuzz.stl");
    SOUP_FUZZ_CHECK(r.binary, "binary file read as ASCII");
    SOUP_FUZZ_CHECK(triangles.size() == 1 + r.triangles, "facet count");
    SOUP_FUZZ_CHECK(size == 84 + 50 * r.triangles, "a binary file of the wrong size was accepted");
  } catch(const Soup_topology::IO::Read_error&) {
    SOUP_FUZZ_CHECK(triangles.size() == 1, "containers changed by a failed read");
  }
  soup_fuzz::read_through_file(data, size, "stl");
  return 0;
}
