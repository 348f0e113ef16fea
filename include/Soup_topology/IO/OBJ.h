// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// A strict reader of the geometry of Wavefront OBJ files: vertices and faces.
//
// Why not CGAL::IO::read_OBJ: it reads numbers with `>>`, so `4x` reads as 4 and a face
// `f 1 two 3` or an index of 20 digits ends the face early without an error; an index of 0 is
// reported as another one; and a failure only returns `false`. Here every token of a `v` or `f`
// statement must be entirely a number, and every error names the line.

#ifndef SOUP_TOPOLOGY_IO_OBJ_H
#define SOUP_TOPOLOGY_IO_OBJ_H

#include <Soup_topology/IO/Read_error.h>
#include <Soup_topology/internal/reader_input.h>

#include <cmath>
#include <cstddef>
#include <iterator>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace Soup_topology {
namespace IO {

/// \ingroup PkgSoupTopologyIO
/// \brief what `read_OBJ_polygons()` read.
struct OBJ_read_result
{
  std::size_t vertices = 0;            ///< `v` statements
  std::size_t faces = 0;               ///< `f` statements
  std::size_t ignored_statements = 0;  ///< other statements (`vt`, `vn`, `g`, `usemtl`, `l`, ...), ignored
};

namespace internal {

class OBJ_line_scanner
{
public:
  OBJ_line_scanner(const char* b, const char* e) : p_(b), e_(e) {}
  /// the next token of the line, `false` at its end (a `#` starts a comment).
  bool next(std::string_view& token)
  {
    while(p_ < e_ && (*p_ == ' ' || *p_ == '\t' || *p_ == '\f' || *p_ == '\v')) ++p_;
    if(p_ == e_ || *p_ == '#') return false;
    const char* s = p_;
    while(p_ < e_ && *p_ != ' ' && *p_ != '\t' && *p_ != '\f' && *p_ != '\v' && *p_ != '#') ++p_;
    token = std::string_view(s, static_cast<std::size_t>(p_ - s));
    return true;
  }
private:
  const char* p_;
  const char* e_;
};

inline std::string quoted_token(std::string_view t)
{ return "'" + Soup_topology::internal::printable(t.data(), t.data() + t.size()) + "'"; }

} // namespace internal

/// \ingroup PkgSoupTopologyIO
/// \brief reads the vertices and faces of the OBJ file held in `[data, data + size)` into
/// `points` and `polygons` (appended; polygons index `points` from the size it had on entry).
///
/// Read: `v x y z` (an optional fourth number, the weight, and three more, a colour that some
/// exporters write, are checked to be numbers and ignored); `f` with corners written `v`,
/// `v/vt`, `v//vn` or `v/vt/vn`, where `v` counts from 1, or from the end when negative (-1 is
/// the last vertex read so far); the texture and normal indices are checked to be integers and
/// ignored. `#` starts a comment. Every other statement (`vt`, `vn`, `vp`, `g`, `o`, `s`,
/// `usemtl`, `mtllib`, `l`, `p`, free-form geometry, ...) is ignored and counted. Lines end with
/// LF, CR LF or CR; a backslash at the end of a line does not continue it. Faces are returned as
/// they are (also those with fewer than 3 corners or a repeated index).
///
/// Rejected with a `Read_error` whose message reads `"<name>:<line>: <what>"`: a coordinate that
/// is not entirely a number, or is NaN or infinite; a `v` with fewer than 3 or more than 7
/// numbers; a corner that is not an integer (`two`, `4x`) or does not fit in 64 bits; a vertex
/// index of 0 or out of range (reported as written in the file); a NUL byte in a statement.
/// `points` and `polygons` are unchanged when an exception is thrown. The memory used is
/// bounded by a small multiple of `size`.
/// \tparam Point a `Point_3` constructible from three `double`
template <class Point>
OBJ_read_result read_OBJ_polygons(const char* data, std::size_t size, std::vector<Point>& points,
                                  std::vector<std::vector<std::size_t>>& polygons, const std::string& name = "OBJ")
{
  OBJ_read_result result;
  const std::size_t base = points.size();
  std::vector<Point> pts;
  std::vector<std::vector<std::size_t>> polys;
  const char* p = data + Soup_topology::internal::utf8_bom_size(data, data + size);
  const char* const end = data + size;
  std::size_t line = 0;
  // Positive indices may refer to vertices given later in the file: the largest one is checked
  // at the end, against the number of vertices, with its line.
  long long largest_index = 0;
  std::size_t largest_index_line = 0;
  std::size_t largest_index_face = 0;
  std::string_view largest_index_token;
  const auto fail = [&](std::size_t at, const std::string& what) {
    throw Read_error(name + ":" + std::to_string(at) + ": " + what);
  };
  while(p < end) {
    ++line;
    const char* b = p;
    while(p < end && *p != '\n' && *p != '\r') ++p;
    const char* e = p;
    if(p < end) {
      if(*p == '\r' && p + 1 < end && p[1] == '\n') ++p;
      ++p;
    }
    internal::OBJ_line_scanner in(b, e);
    std::string_view keyword;
    if(!in.next(keyword)) continue;
    for(const char* q = b; q < e; ++q)
      if(*q == '\0') fail(line, "a NUL byte in the line: not a text file?");
    if(keyword == "v") {
      double c[3];
      std::string_view t;
      int n = 0;
      while(in.next(t)) {
        double x;
        if(!Soup_topology::internal::parse_double(t.data(), t.data() + t.size(), x))
          fail(line, internal::quoted_token(t) + " is not a number (vertex " + std::to_string(pts.size() + 1) + ")");
        if(n < 3) {
          if(!std::isfinite(x))
            fail(line, "non-finite coordinate " + internal::quoted_token(t) + " (vertex " + std::to_string(pts.size() + 1) + ")");
          c[n] = x;
        }
        if(++n > 7) fail(line, "more than 7 numbers in vertex " + std::to_string(pts.size() + 1));
      }
      if(n < 3)
        fail(line, "vertex " + std::to_string(pts.size() + 1) + " has " + std::to_string(n) + " coordinates, expected 3");
      pts.push_back(Point(c[0], c[1], c[2]));
    } else if(keyword == "f") {
      std::vector<std::size_t> poly;
      const std::size_t face = polys.size() + 1;
      std::string_view t;
      while(in.next(t)) {
        // v, v/vt, v//vn, v/vt/vn
        std::string_view parts[3];
        int n = 0;
        std::size_t start = 0;
        for(;;) {
          const std::size_t slash = t.find('/', start);
          if(n == 3) fail(line, "corner " + internal::quoted_token(t) + " of face " + std::to_string(face) +
                                  " has more than three parts");
          parts[n++] = t.substr(start, slash == std::string_view::npos ? std::string_view::npos : slash - start);
          if(slash == std::string_view::npos) break;
          start = slash + 1;
        }
        long long v = 0;
        const std::string_view vt = parts[0];
        const Soup_topology::internal::Integer_parse parsed =
          Soup_topology::internal::parse_integer(vt.data(), vt.data() + vt.size(), v);
        if(parsed == Soup_topology::internal::Integer_parse::NOT_AN_INTEGER)
          fail(line, internal::quoted_token(t) + " is not a vertex index (face " + std::to_string(face) + ")");
        if(parsed == Soup_topology::internal::Integer_parse::TOO_LARGE)
          fail(line, "vertex index " + internal::quoted_token(vt) + " of face " + std::to_string(face) +
                       " is too large");
        for(int k = 1; k < n; ++k) {
          long long ignored;
          if(parts[k].empty() && k == 1 && n == 3) continue; // v//vn
          if(Soup_topology::internal::parse_integer(parts[k].data(), parts[k].data() + parts[k].size(), ignored) !=
             Soup_topology::internal::Integer_parse::OK)
            fail(line, "corner " + internal::quoted_token(t) + " of face " + std::to_string(face) +
                         ": " + (k == 1 ? "texture" : "normal") + " index " + internal::quoted_token(parts[k]) +
                         " is not an integer");
        }
        if(v == 0) fail(line, "vertex index 0 in face " + std::to_string(face) + " (OBJ indices start at 1)");
        if(v < 0) {
          if(static_cast<unsigned long long>(-(v + 1)) >= pts.size())
            fail(line, "vertex index " + std::to_string(v) + " of face " + std::to_string(face) + " refers to before the first vertex (" +
                         std::to_string(pts.size()) + " vertices so far)");
          poly.push_back(base + pts.size() - static_cast<std::size_t>(-(v + 1)) - 1);
        } else {
          if(v > largest_index) {
            largest_index = v;
            largest_index_line = line;
            largest_index_face = face;
            largest_index_token = vt;
          }
          poly.push_back(base + static_cast<std::size_t>(v - 1));
        }
      }
      polys.push_back(std::move(poly));
    } else {
      for(const char c : keyword)
        if(static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) >= 0x7f)
          fail(line, "unknown statement " + internal::quoted_token(keyword) + ": not a text file?");
      ++result.ignored_statements;
    }
  }
  if(static_cast<unsigned long long>(largest_index) > pts.size())
    fail(largest_index_line, "vertex index " + std::string(largest_index_token) + " of face " +
                               std::to_string(largest_index_face) + " is out of range (" + std::to_string(pts.size()) +
                               " vertices)");
  result.vertices = pts.size();
  result.faces = polys.size();
  Soup_topology::internal::append_read_polygons(pts, polys, points, polygons);
  return result;
}

/// \ingroup PkgSoupTopologyIO
/// \brief reads the OBJ file held in `data`, see above.
template <class Point>
OBJ_read_result read_OBJ_polygons(const std::string& data, std::vector<Point>& points,
                                  std::vector<std::vector<std::size_t>>& polygons, const std::string& name = "OBJ")
{
  return read_OBJ_polygons(data.data(), data.size(), points, polygons, name);
}

} // namespace IO
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_IO_OBJ_H
