// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// libFuzzer target: ASCII STL, in memory through read_STL_triangles(), then the whole
// read_triangle_soup() path on a file. "solid " is put in front of inputs that do not start so.

#include "fuzz_common.h"

#include <Soup_topology/IO/STL.h>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  std::string text(reinterpret_cast<const char*>(data), size);
  if(!Soup_topology::IO::internal::looks_like_ascii_stl(text)) text = "solid " + text;
  if(!Soup_topology::IO::internal::looks_like_ascii_stl(text)) return 0; // a binary file after all
  std::vector<std::array<soup_fuzz::Point, 3>> triangles(1);
  try {
    const auto r = Soup_topology::IO::read_STL_triangles(text, triangles, "fuzz.stl");
    SOUP_FUZZ_CHECK(!r.binary, "ASCII file read as binary");
    SOUP_FUZZ_CHECK(triangles.size() == 1 + r.triangles, "facet count");
  } catch(const Soup_topology::IO::Read_error& e) {
    SOUP_FUZZ_CHECK(triangles.size() == 1, "containers changed by a failed read");
    SOUP_FUZZ_CHECK(std::string(e.what()).rfind("fuzz.stl:", 0) == 0, std::string("no line in ") + e.what());
  }
  soup_fuzz::read_through_file(reinterpret_cast<const std::uint8_t*>(text.data()), text.size(), "stl");
  return 0;
}
