// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// A reader of STL files (binary and ASCII) that returns the explicit triangles, unwelded.
//
// Why not CGAL::IO::read_STL: it welds while reading, through a std::map of points, which makes
// it the slowest part of a repair of a large STL (see benchmark/index_triangles_benchmark.cpp);
// and it cannot say which facet or line of a broken file is wrong. Here the file is read once
// into memory, the triangles are returned as they are, and `index_triangles()` welds them in
// expected linear time.

#ifndef SOUP_TOPOLOGY_IO_STL_H
#define SOUP_TOPOLOGY_IO_STL_H

#include <Soup_topology/IO/Read_error.h>

#include <array>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace Soup_topology {
namespace IO {

/// \ingroup PkgSoupTopologyIO
/// \brief what `read_STL_triangles()` read.
struct STL_read_result
{
  bool binary = false;          ///< the file was binary
  std::size_t triangles = 0;    ///< facets read
};

namespace internal {

inline bool is_stl_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

class STL_ascii_scanner
{
public:
  STL_ascii_scanner(const char* b, const char* e, const std::string& name) : p_(b), e_(e), name_(name) {}
  bool next(std::string& token)
  {
    while(p_ < e_ && is_stl_space(*p_)) { if(*p_ == '\n') ++line_; ++p_; }
    if(p_ == e_) return false;
    const char* s = p_;
    while(p_ < e_ && !is_stl_space(*p_)) ++p_;
    token.assign(s, p_);
    return true;
  }
  void expect(const char* keyword)
  {
    std::string t;
    if(!next(t)) fail(std::string("unexpected end of file, expected '") + keyword + "'");
    if(!equal_nocase(t, keyword)) fail(std::string("expected '") + keyword + "', found '" + t + "'");
  }
  double number()
  {
    std::string t;
    if(!next(t)) fail("unexpected end of file, expected a number");
    char* end = nullptr;
    const double x = std::strtod(t.c_str(), &end);
    if(end == t.c_str() || *end != '\0') fail("'" + t + "' is not a number");
    return x;
  }
  [[noreturn]] void fail(const std::string& what) const
  { throw Read_error(name_ + ":" + std::to_string(line_) + ": " + what); }
  static bool equal_nocase(const std::string& a, const char* b)
  {
    const std::size_t n = std::strlen(b);
    if(a.size() != n) return false;
    for(std::size_t i = 0; i < n; ++i)
      if(std::tolower(static_cast<unsigned char>(a[i])) != b[i]) return false;
    return true;
  }
  std::size_t line() const { return line_; }
private:
  const char* p_;
  const char* e_;
  std::string name_;
  std::size_t line_ = 1;
};

inline bool looks_like_ascii_stl(const std::string& data)
{
  std::size_t i = 0;
  while(i < data.size() && is_stl_space(data[i])) ++i;
  if(data.size() - i < 5) return false;
  std::string head = data.substr(i, 5);
  for(char& c : head) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if(head != "solid") return false;
  // Some binary files also start with "solid": they are recognised by their exact size.
  if(data.size() >= 84) {
    std::uint32_t n;
    std::memcpy(&n, data.data() + 80, 4);
    if(84 + 50 * std::uint64_t(n) == data.size()) return false;
  }
  return true;
}

} // namespace internal

/// \ingroup PkgSoupTopologyIO
/// \brief reads the triangles of an STL file held in `data` (the whole file), binary or ASCII,
/// appending each facet as 3 points to `triangles`. `name` is used in error messages.
/// \tparam Point a `Point_3` constructible from three `double`
/// \throws Read_error naming the line (ASCII) or the facet (binary) on malformed input: a
/// truncated binary file, a triangle count that does not match the size, a missing keyword, a
/// number that does not parse. `triangles` is left unchanged then.
template <class Point>
STL_read_result read_STL_triangles(const std::string& data, std::vector<std::array<Point, 3>>& triangles,
                                   const std::string& name = "STL")
{
  STL_read_result result;
  std::vector<std::array<Point, 3>> read;
  if(internal::looks_like_ascii_stl(data)) {
    internal::STL_ascii_scanner in(data.data(), data.data() + data.size(), name);
    in.expect("solid");
    std::string t;
    // The name of the solid: the rest of the first line.
    bool in_solid = true;
    while(in.next(t)) {
      if(internal::STL_ascii_scanner::equal_nocase(t, "facet")) break;
      if(internal::STL_ascii_scanner::equal_nocase(t, "endsolid")) { in_solid = false; break; }
    }
    while(in_solid) {
      if(internal::STL_ascii_scanner::equal_nocase(t, "endsolid")) break;
      if(!internal::STL_ascii_scanner::equal_nocase(t, "facet"))
        in.fail("expected 'facet' or 'endsolid', found '" + t + "'");
      in.expect("normal");
      in.number(); in.number(); in.number();
      in.expect("outer");
      in.expect("loop");
      std::array<Point, 3> tri;
      for(int k = 0; k < 3; ++k) {
        in.expect("vertex");
        const double x = in.number(), y = in.number(), z = in.number();
        tri[static_cast<std::size_t>(k)] = Point(x, y, z);
      }
      in.expect("endloop");
      in.expect("endfacet");
      read.push_back(tri);
      if(!in.next(t)) in.fail("unexpected end of file, expected 'endsolid'");
    }
  } else {
    result.binary = true;
    if(data.size() < 84)
      throw Read_error(name + ": binary STL shorter than its 84-byte header (" + std::to_string(data.size()) +
                       " bytes)");
    std::uint32_t n;
    std::memcpy(&n, data.data() + 80, 4);
    const std::uint64_t expected = 84 + 50 * std::uint64_t(n);
    // Checked before any allocation: a header that claims 4 billion facets costs nothing.
    if(data.size() < expected)
      throw Read_error(name + ": binary STL header announces " + std::to_string(n) + " facets, the file holds " +
                       std::to_string((data.size() - 84) / 50) + " complete facets (truncated at facet " +
                       std::to_string((data.size() - 84) / 50) + ")");
    if(data.size() > expected)
      throw Read_error(name + ": binary STL header announces " + std::to_string(n) + " facets, the file holds " +
                       std::to_string(data.size() - expected) + " bytes more than that");
    read.resize(n);
    const char* p = data.data() + 84;
    for(std::uint32_t f = 0; f < n; ++f, p += 50) {
      float c[12];
      std::memcpy(c, p, sizeof c);
      for(int k = 0; k < 3; ++k)
        read[f][static_cast<std::size_t>(k)] = Point(double(c[3 + 3 * k]), double(c[4 + 3 * k]), double(c[5 + 3 * k]));
    }
  }
  result.triangles = read.size();
  triangles.insert(triangles.end(), read.begin(), read.end());
  return result;
}

/// \ingroup PkgSoupTopologyIO
/// \brief reads the whole file `filename` into a string.
/// \throws Read_error if it cannot be opened or read.
inline std::string read_file_contents(const std::string& filename)
{
  std::ifstream in(filename, std::ios::binary);
  if(!in) throw Read_error(filename + ": cannot open the file for reading");
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if(size < 0) throw Read_error(filename + ": cannot read the file (is it a folder?)");
  std::string data(static_cast<std::size_t>(size), '\0');
  in.seekg(0, std::ios::beg);
  if(size > 0 && !in.read(&data[0], size)) throw Read_error(filename + ": cannot read the file");
  return data;
}

} // namespace IO
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_IO_STL_H
