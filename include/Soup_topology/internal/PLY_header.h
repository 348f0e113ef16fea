// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// A check of the header of a PLY file before it is read (IO/PLY.h).
//
// It was written for CGAL 5.5's PLY reader, which has undefined behaviour on three kinds of
// headers, all found by fuzz/fuzz_ply: a `property` line before any `element` line
// (PLY_reader::init() calls back() on an empty vector); a vertex coordinate `x`, `y` or `z` of a
// type other than float or double (PLY_read_number::assign() dereferences the null result of a
// dynamic_cast); two properties of one element with the same name (the type is checked on one,
// the value read from the other). And it pushes one point per announced vertex even when a
// vertex has no property to read, and allocates the count of a list before reading its
// elements. Our reader has none of these problems, but the refusals are documented
// (doc/Soup_topology/Bad_input.md) and kept: coordinates of an integer type and list counts
// wider than 16 bits (rare: exporters write `list uchar int`) are refused. The header is read
// with the same tokenisation as CGAL's reader (std::getline, then >>).

#ifndef SOUP_TOPOLOGY_INTERNAL_PLY_HEADER_H
#define SOUP_TOPOLOGY_INTERNAL_PLY_HEADER_H

#include <Soup_topology/IO/Read_error.h>

#include <cstddef>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

namespace Soup_topology {
namespace internal {

/// the most bytes of a PLY header that are looked at: a header longer than this is not checked
/// further (its end is then refused by CGAL's reader or read as data).
constexpr std::size_t max_PLY_header_bytes = std::size_t(1) << 20;

/// throws `IO::Read_error` naming the line if the header of the PLY file held in `[data, data + size)` has a
/// `property` before any `element`, a vertex coordinate that is not a float or a double, or two
/// properties of the same name in one element, a list count wider than 16 bits, or if its
/// elements need more bytes than the
/// file holds (each property of each item takes at least its size in a binary file, 2 bytes in
/// an ASCII one).
inline void check_PLY_header(const char* data, std::size_t size, const std::string& filename)
{
  // Only the header is looked at: at most the first line that says end_header, or the whole.
  std::istringstream in(std::string(data, size < max_PLY_header_bytes ? size : max_PLY_header_bytes));
  const double file_size = double(size);
  std::string line, element;
  std::set<std::string> names;
  std::size_t number = 0, count = 0, element_line = 0;
  bool element_seen = false, binary = false;
  double bytes_per_item = 0, bytes_needed = 0; // lower bounds
  const auto fail = [&](std::size_t at, const std::string& what) {
    throw IO::Read_error(filename + ":" + std::to_string(at) + ": " + what);
  };
  const auto end_element = [&]() {
    if(!element_seen || count == 0) return;
    if(bytes_per_item == 0)
      fail(element_line, "PLY element '" + element + "' announces " + std::to_string(count) + " items with no property");
    bytes_needed += double(count) * bytes_per_item;
    if(bytes_needed > file_size)
      fail(element_line, "PLY element '" + element + "' announces " + std::to_string(count) +
                           " items, more than the file of " + std::to_string(size) + " bytes can hold");
  };
  const auto type_size = [](const std::string& t) -> double {
    if(t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
    if(t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
    if(t == "double" || t == "float64") return 8;
    return 4;
  };
  while(std::getline(in, line)) {
    ++number;
    if(number == 1) continue; // the signature: CGAL checks it
    std::istringstream words(line);
    if(number == 2) { // the format: CGAL checks it
      std::string tag, format;
      words >> tag >> format;
      binary = format != "ascii";
      continue;
    }
    std::string keyword;
    if(!(words >> keyword)) return; // CGAL refuses an empty header line
    if(keyword == "element") {
      end_element();
      element_seen = true;
      element.clear();
      count = 0;
      words >> element >> count;
      element_line = number;
      bytes_per_item = 0;
      names.clear();
    } else if(keyword == "property") {
      if(!element_seen) fail(number, "PLY 'property' before any 'element'");
      std::string type, name;
      words >> type >> name;
      std::string size_type = type;
      if(type == "list") {
        size_type = name;
        std::string index_type;
        words >> index_type >> name;
        if(type_size(size_type) > 2)
          fail(number, "PLY list '" + name + "' with a count of type '" + size_type +
                         "' is not supported (8 or 16 bits: CGAL's reader allocates the count before reading)");
      }
      bytes_per_item += binary ? type_size(size_type) : 2;
      if(!names.insert(name).second) fail(number, "PLY element '" + element + "' has two properties named '" + name + "'");
      if((element == "vertex" || element == "vertices") && (name == "x" || name == "y" || name == "z") &&
         type != "float" && type != "float32" && type != "double" && type != "float64")
        fail(number, "PLY vertex coordinate '" + name + "' of type '" + type + "' (expected float or double)");
    } else if(keyword == "end_header") {
      break;
    }
  }
  end_element(); // also without end_header: CGAL reads the elements then
}


} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_PLY_HEADER_H
