// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// A strict reader of the vertices and faces of PLY files (ASCII, binary little- and big-endian).
//
// Why not CGAL::IO::read_PLY: it accepts bytes after the last element, reads a negative index
// as a huge unsigned one (-1 is reported as 18446744073709551615), only returns `false` on an
// error, and needs the checks of internal/PLY_header.h not to misbehave. Here the data must
// match the header exactly, numbers must fit their declared types, and every error names the
// line (ASCII) or the element and item (binary).

#ifndef SOUP_TOPOLOGY_IO_PLY_H
#define SOUP_TOPOLOGY_IO_PLY_H

#include <Soup_topology/IO/Read_error.h>
#include <Soup_topology/internal/reader_input.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace Soup_topology {
namespace IO {

/// \ingroup PkgSoupTopologyIO
/// \brief what `read_PLY_polygons()` read.
struct PLY_read_result
{
  bool binary = false;          ///< the data was binary
  std::size_t vertices = 0;     ///< items of the element `vertex`
  std::size_t faces = 0;        ///< items of the element `face`
  std::size_t other_items = 0;  ///< items of other elements (edges, materials, ...), ignored
};

namespace internal {

enum class PLY_type { INT8, UINT8, INT16, UINT16, INT32, UINT32, FLOAT32, FLOAT64, NONE };

inline PLY_type PLY_type_of(const std::string& t)
{
  if(t == "char" || t == "int8") return PLY_type::INT8;
  if(t == "uchar" || t == "uint8") return PLY_type::UINT8;
  if(t == "short" || t == "int16") return PLY_type::INT16;
  if(t == "ushort" || t == "uint16") return PLY_type::UINT16;
  if(t == "int" || t == "int32") return PLY_type::INT32;
  if(t == "uint" || t == "uint32") return PLY_type::UINT32;
  if(t == "float" || t == "float32") return PLY_type::FLOAT32;
  if(t == "double" || t == "float64") return PLY_type::FLOAT64;
  return PLY_type::NONE;
}

inline std::size_t PLY_size_of(PLY_type t)
{
  switch(t) {
  case PLY_type::INT8: case PLY_type::UINT8: return 1;
  case PLY_type::INT16: case PLY_type::UINT16: return 2;
  case PLY_type::FLOAT64: return 8;
  default: return 4;
  }
}

inline bool PLY_is_integer(PLY_type t) { return t != PLY_type::FLOAT32 && t != PLY_type::FLOAT64; }

inline bool PLY_fits(PLY_type t, long long v)
{
  switch(t) {
  case PLY_type::INT8: return v >= -128 && v <= 127;
  case PLY_type::UINT8: return v >= 0 && v <= 255;
  case PLY_type::INT16: return v >= -32768 && v <= 32767;
  case PLY_type::UINT16: return v >= 0 && v <= 65535;
  case PLY_type::INT32: return v >= -2147483648LL && v <= 2147483647LL;
  case PLY_type::UINT32: return v >= 0 && v <= 4294967295LL;
  default: return true;
  }
}

struct PLY_property
{
  std::string name;
  PLY_type type = PLY_type::NONE;        // of the value, or of the elements of a list
  PLY_type count_type = PLY_type::NONE;  // NONE if not a list
  std::size_t line = 0;
};

struct PLY_element
{
  std::string name;
  std::size_t count = 0;
  std::size_t line = 0;
  std::vector<PLY_property> properties;
};

/// one value read from the data: an integer (`integer`) or a real number (`real`).
struct PLY_value
{
  long long integer = 0;
  double real = 0;
};

class PLY_data
{
public:
  PLY_data(const char* b, const char* e, std::size_t line, bool binary, bool big_endian, const std::string& name)
    : p_(b), e_(e), line_(line), token_line_(line), binary_(binary), big_endian_(big_endian), name_(name) {}

  /// reads a value of type `t`; `what` names it in the messages (a string or a function that
  /// returns one, see `describe()`).
  template <class What>
  PLY_value read(PLY_type t, const What& what)
  {
    using Soup_topology::internal::describe;
    PLY_value v;
    if(binary_) {
      const std::size_t n = PLY_size_of(t);
      if(static_cast<std::size_t>(e_ - p_) < n) fail("the binary data ends inside " + describe(what));
      unsigned char bytes[8];
      std::memcpy(bytes, p_, n);
      p_ += n;
      if(big_endian_ != host_is_big_endian())
        for(std::size_t i = 0; i < n / 2; ++i) std::swap(bytes[i], bytes[n - 1 - i]);
      switch(t) {
      case PLY_type::INT8: { std::int8_t x; std::memcpy(&x, bytes, 1); v.integer = x; break; }
      case PLY_type::UINT8: { std::uint8_t x; std::memcpy(&x, bytes, 1); v.integer = x; break; }
      case PLY_type::INT16: { std::int16_t x; std::memcpy(&x, bytes, 2); v.integer = x; break; }
      case PLY_type::UINT16: { std::uint16_t x; std::memcpy(&x, bytes, 2); v.integer = x; break; }
      case PLY_type::INT32: { std::int32_t x; std::memcpy(&x, bytes, 4); v.integer = x; break; }
      case PLY_type::UINT32: { std::uint32_t x; std::memcpy(&x, bytes, 4); v.integer = x; break; }
      case PLY_type::FLOAT32: { float x; std::memcpy(&x, bytes, 4); v.real = double(x); break; }
      default: { double x; std::memcpy(&x, bytes, 8); v.real = x; break; }
      }
      if(PLY_is_integer(t)) v.real = double(v.integer);
      return v;
    }
    const std::string_view token = next_token();
    if(token.empty()) fail("unexpected end of file, expected " + describe(what));
    if(PLY_is_integer(t)) {
      const Soup_topology::internal::Integer_parse r =
        Soup_topology::internal::parse_integer(token.data(), token.data() + token.size(), v.integer);
      if(r != Soup_topology::internal::Integer_parse::OK || !PLY_fits(t, v.integer))
        fail(quoted(token) + " is not an integer of the declared type (" + describe(what) + ")");
      v.real = double(v.integer);
    } else {
      if(!Soup_topology::internal::parse_double(token.data(), token.data() + token.size(), v.real))
        fail(quoted(token) + " is not a number (" + describe(what) + ")");
      if(t == PLY_type::FLOAT32) { // read as a float, as a binary file would hold it (no double rounding)
        float x = 0;
        Soup_topology::internal::parse_float(token.data(), token.data() + token.size(), x);
        v.real = double(x);
      }
    }
    return v;
  }
  std::size_t remaining_bytes() const { return static_cast<std::size_t>(e_ - p_); }
  /// the line of the last token read (ASCII).
  std::size_t line() const { return token_line_; }
  /// fails if anything but white space (ASCII) or anything at all (binary) is left.
  void expect_end()
  {
    if(binary_) {
      if(p_ != e_) fail(std::to_string(e_ - p_) + " bytes after the last element the header announces");
      return;
    }
    const std::string_view token = next_token();
    if(!token.empty())
      fail("data after the last element the header announces (" + quoted(token) + "): is a count of the header wrong?");
  }
  [[noreturn]] void fail(const std::string& what) const
  {
    if(binary_) throw Read_error(name_ + ": " + what);
    throw Read_error(name_ + ":" + std::to_string(token_line_) + ": " + what);
  }
  static std::string quoted(std::string_view t)
  { return "'" + Soup_topology::internal::printable(t.data(), t.data() + t.size()) + "'"; }

private:
  static bool host_is_big_endian()
  {
    const std::uint16_t one = 1;
    unsigned char first;
    std::memcpy(&first, &one, 1);
    return first == 0;
  }
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }
  std::string_view next_token()
  {
    while(p_ < e_ && is_space(*p_)) {
      if(*p_ == '\n' || (*p_ == '\r' && (p_ + 1 == e_ || p_[1] != '\n'))) ++line_;
      ++p_;
    }
    token_line_ = line_;
    const char* s = p_;
    while(p_ < e_ && !is_space(*p_)) ++p_;
    return std::string_view(s, static_cast<std::size_t>(p_ - s));
  }
  const char* p_;
  const char* e_;
  std::size_t line_;
  std::size_t token_line_;
  bool binary_;
  bool big_endian_;
  std::string name_;
};

/// the header of a PLY file: its format, its elements, where its data starts and on which line.
struct Parsed_PLY_header
{
  bool binary = false;
  bool big_endian = false;
  std::vector<PLY_element> elements;
  const char* data = nullptr;
  std::size_t line = 0;  // the line of `end_header`
};

/// reads the header of the PLY file held in `[data, end)`; `name` starts the messages.
inline Parsed_PLY_header read_PLY_header(const char* data, const char* end, const std::string& name)
{
  const char* p = data;
  std::size_t line = 0;
  const auto fail = [&](std::size_t at, const std::string& what) {
    throw Read_error(name + ":" + std::to_string(at) + ": " + what);
  };
  // The header: lines of words.
  const auto next_line = [&](std::vector<std::string>& words) -> bool {
    if(p == end) return false;
    ++line;
    const char* b = p;
    while(p < end && *p != '\n') ++p;
    const char* e = p;
    if(p < end) ++p;
    if(e > b && e[-1] == '\r') --e;
    words.clear();
    const char* q = b;
    while(q < e) {
      while(q < e && (*q == ' ' || *q == '\t')) ++q;
      const char* s = q;
      while(q < e && *q != ' ' && *q != '\t') ++q;
      if(q > s) words.emplace_back(s, q);
    }
    return true;
  };
  std::vector<std::string> w;
  if(!next_line(w) || w.size() != 1 || w[0] != "ply") fail(1, "not a PLY file (it does not start with the line 'ply')");
  bool binary = false, big_endian = false, format_seen = false, header_ended = false;
  std::vector<PLY_element> elements;
  while(next_line(w)) {
    if(w.empty()) fail(line, "empty line in the PLY header");
    const std::string& k = w[0];
    if(k == "comment" || k == "obj_info") continue;
    if(k == "end_header") { header_ended = true; break; }
    if(k == "format") {
      if(w.size() != 3 || w[2] != "1.0") fail(line, "expected 'format ascii 1.0' (or binary_little_endian, binary_big_endian)");
      if(w[1] == "ascii") binary = false;
      else if(w[1] == "binary_little_endian") { binary = true; big_endian = false; }
      else if(w[1] == "binary_big_endian") { binary = true; big_endian = true; }
      else fail(line, "unknown PLY format '" + Soup_topology::internal::printable(w[1]) + "'");
      format_seen = true;
    } else if(k == "element") {
      if(w.size() != 3) fail(line, "expected 'element <name> <count>'");
      long long count = 0;
      if(Soup_topology::internal::parse_integer(w[2].data(), w[2].data() + w[2].size(), count) !=
           Soup_topology::internal::Integer_parse::OK || count < 0)
        fail(line, "'" + Soup_topology::internal::printable(w[2]) + "' is not a count of items");
      PLY_element el;
      el.name = w[1];
      el.count = static_cast<std::size_t>(count);
      el.line = line;
      elements.push_back(el);
    } else if(k == "property") {
      if(elements.empty()) fail(line, "PLY 'property' before any 'element'");
      PLY_property prop;
      prop.line = line;
      if(w.size() == 5 && w[1] == "list") {
        prop.count_type = PLY_type_of(w[2]);
        prop.type = PLY_type_of(w[3]);
        prop.name = w[4];
        if(prop.count_type == PLY_type::NONE || !PLY_is_integer(prop.count_type))
          fail(line, "the count of list '" + Soup_topology::internal::printable(prop.name) + "' is not of an integer type");
      } else if(w.size() == 3) {
        prop.type = PLY_type_of(w[1]);
        prop.name = w[2];
      } else {
        fail(line, "expected 'property <type> <name>' or 'property list <type> <type> <name>'");
      }
      if(prop.type == PLY_type::NONE) fail(line, "unknown PLY type in '" + Soup_topology::internal::printable(w[1] + " ...") + "'");
      elements.back().properties.push_back(prop);
    } else {
      fail(line, "unknown PLY header statement '" + Soup_topology::internal::printable(k) + "'");
    }
  }
  if(!header_ended) fail(line, "the PLY header has no 'end_header'");
  if(!format_seen) fail(line, "the PLY header has no 'format' line");
  Parsed_PLY_header header;
  header.binary = binary;
  header.big_endian = big_endian;
  header.elements = std::move(elements);
  header.data = p;
  header.line = line;
  return header;
}

/// refuses, before anything is allocated, a header whose elements cannot fit in the data left:
/// an item takes at least its bytes (binary) or 2 bytes per value (ASCII).
inline void check_PLY_element_sizes(const Parsed_PLY_header& header, const char* end, const std::string& name)
{
  const auto fail = [&](std::size_t at, const std::string& what) {
    throw Read_error(name + ":" + std::to_string(at) + ": " + what);
  };
  const bool binary = header.binary;
  const char* const p = header.data;
  double needed = 0;
  for(const PLY_element& el : header.elements) {
    double per_item = 0;
    for(const PLY_property& prop : el.properties)
      per_item += binary ? double(PLY_size_of(prop.count_type != PLY_type::NONE ? prop.count_type : prop.type)) : 2.0;
    if(el.count > 0 && per_item == 0)
      fail(el.line, "PLY element '" + Soup_topology::internal::printable(el.name) + "' announces " +
                      std::to_string(el.count) + " items with no property");
    needed += per_item * double(el.count);
    if(needed > double(end - p) + 1)
      fail(el.line, "PLY element '" + Soup_topology::internal::printable(el.name) + "' announces " +
                      std::to_string(el.count) + " items, more than the remaining " + std::to_string(end - p) +
                      " bytes can hold");
  }
}

} // namespace internal

/// \ingroup PkgSoupTopologyIO
/// \brief reads the vertices and faces of the PLY file held in `[data, data + size)` into
/// `points` and `polygons` (appended; polygons index `points` from the size it had on entry).
///
/// Read: the formats `ascii`, `binary_little_endian` and `binary_big_endian` 1.0; the element
/// `vertex` (or `vertices`) with the properties `x`, `y`, `z`; the element `face` (or `faces`)
/// with the list `vertex_indices` (or `vertex_index`). Other properties and elements are read
/// (to check them and to find the next element) and ignored; `comment` and `obj_info` lines too.
/// Float coordinates are read as floats (an ASCII `0.1` of a `float` property is the float
/// nearest to 0.1, as in a binary file). Faces are returned as they are (also those with fewer
/// than 3 corners or a repeated index). The header lines end with LF or CR LF.
///
/// Rejected with a `Read_error` whose message starts with `name` and, for ASCII data, the line:
/// a missing `ply` line or `format`, an unknown type or statement in the header, an ASCII
/// token that is not entirely a number or does not fit its declared type, an element that
/// announces more items than the data can hold (checked before anything is allocated),
/// data that ends early, bytes after the last element, a vertex index that is negative or
/// out of range (reported as written).
/// `points` and `polygons` are unchanged when an exception is thrown.
/// \tparam Point a `Point_3` constructible from three `double`
template <class Point>
PLY_read_result read_PLY_polygons(const char* data, std::size_t size, std::vector<Point>& points,
                                  std::vector<std::vector<std::size_t>>& polygons, const std::string& name = "PLY")
{
  using namespace internal;
  PLY_read_result result;
  const char* const end = data + size;
  const Parsed_PLY_header header = read_PLY_header(data, end, name);
  check_PLY_element_sizes(header, end, name);
  const bool binary = header.binary;
  const std::vector<PLY_element>& elements = header.elements;
  result.binary = binary;
  const auto fail = [&](std::size_t at, const std::string& what) {
    throw Read_error(name + ":" + std::to_string(at) + ": " + what);
  };

  PLY_data in(header.data, end, header.line + 1, binary, header.big_endian, name);
  const std::size_t base = points.size();
  std::vector<Point> pts;
  std::vector<std::vector<std::size_t>> polys;
  // Indices are checked at the end: a face element may come before the vertex element.
  long long largest = -1;
  std::size_t largest_face = 0;
  std::size_t largest_line = 0;
  bool vertex_element_seen = false;
  for(const PLY_element& el : elements) {
    const bool is_vertex = (el.name == "vertex" || el.name == "vertices") && !vertex_element_seen;
    const bool is_face = el.name == "face" || el.name == "faces";
    int xyz[3] = {-1, -1, -1};
    int indices = -1;
    for(std::size_t k = 0; k < el.properties.size(); ++k) {
      const PLY_property& prop = el.properties[k];
      if(is_vertex && prop.count_type == PLY_type::NONE)
        for(int c = 0; c < 3; ++c)
          if(prop.name == std::string(1, char('x' + c))) xyz[c] = int(k);
      if(is_face && prop.count_type != PLY_type::NONE && (prop.name == "vertex_indices" || prop.name == "vertex_index"))
        indices = int(k);
    }
    if(is_vertex) {
      vertex_element_seen = true;
      for(int c = 0; c < 3; ++c)
        if(xyz[c] < 0 && el.count > 0)
          fail(el.line, std::string("PLY element 'vertex' has no property '") + char('x' + c) + "'");
    }
    if(is_face && indices >= 0 && !PLY_is_integer(el.properties[std::size_t(indices)].type))
      fail(el.properties[std::size_t(indices)].line, "PLY vertex indices of a non-integer type");
    for(std::size_t item = 0; item < el.count; ++item) {
      double c[3] = {0, 0, 0};
      std::vector<std::size_t> poly;
      for(std::size_t k = 0; k < el.properties.size(); ++k) {
        const PLY_property& prop = el.properties[k];
        const auto what = [&]() { return el.name + " " + std::to_string(item) + ", property '" + prop.name + "'"; };
        if(prop.count_type == PLY_type::NONE) {
          const PLY_value v = in.read(prop.type, what);
          for(int d = 0; d < 3; ++d)
            if(xyz[d] == int(k)) c[d] = v.real;
          continue;
        }
        const PLY_value n = in.read(prop.count_type, [&]() { return "the count of " + what(); });
        if(n.integer < 0) in.fail("negative count " + std::to_string(n.integer) + " (" + what() + ")");
        const std::size_t count = static_cast<std::size_t>(n.integer);
        if(count > in.remaining_bytes()) in.fail("list of " + std::to_string(count) + " values, more than the data holds (" + what() + ")");
        const bool wanted = int(k) == indices;
        if(wanted) poly.reserve(count);
        for(std::size_t j = 0; j < count; ++j) {
          const PLY_value v = in.read(prop.type, [&]() { return "value " + std::to_string(j) + " of " + what(); });
          if(!wanted) continue;
          if(v.integer < 0) in.fail(el.name + " " + std::to_string(item) + " has a negative vertex index (" + std::to_string(v.integer) + ")");
          if(v.integer > largest) {
            largest = v.integer;
            largest_face = item;
            largest_line = binary ? 0 : in.line();
          }
          poly.push_back(base + static_cast<std::size_t>(v.integer));
        }
      }
      if(is_vertex) {
        for(int d = 0; d < 3; ++d)
          if(!std::isfinite(c[d]))
            in.fail("non-finite coordinate in vertex " + std::to_string(item));
        pts.push_back(Point(c[0], c[1], c[2]));
      } else if(is_face && indices >= 0) {
        polys.push_back(std::move(poly));
      } else {
        ++result.other_items;
      }
    }
  }
  in.expect_end();
  if(largest >= 0 && static_cast<unsigned long long>(largest) >= pts.size()) {
    const std::string what = "face " + std::to_string(largest_face) + " has vertex index " + std::to_string(largest) +
                             ", out of range (" + std::to_string(pts.size()) + " vertices)";
    if(binary) throw Read_error(name + ": " + what);
    fail(largest_line, what);
  }
  result.vertices = pts.size();
  result.faces = polys.size();
  Soup_topology::internal::append_read_polygons(pts, polys, points, polygons);
  return result;
}

/// \ingroup PkgSoupTopologyIO
/// \brief reads the PLY file held in `data`, see above.
template <class Point>
PLY_read_result read_PLY_polygons(const std::string& data, std::vector<Point>& points,
                                  std::vector<std::vector<std::size_t>>& polygons, const std::string& name = "PLY")
{
  return read_PLY_polygons(data.data(), data.size(), points, polygons, name);
}

} // namespace IO
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_IO_PLY_H
