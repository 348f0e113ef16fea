// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// A reader of OFF files (polygons, ASCII) that checks the counts of the header against the data.
//
// Why not CGAL::IO::read_OFF: it resizes its containers to the counts of the header before
// reading a single vertex, so a header that claims 4 billion vertices allocates about 100 GB; it
// asserts on a homogeneous coordinate of 0; and when it fails it only returns `false`, without
// the line. Here nothing is allocated from a count of the file, every error names the line, and
// the data must match the header exactly.

#ifndef SOUP_TOPOLOGY_IO_OFF_H
#define SOUP_TOPOLOGY_IO_OFF_H

#include <Soup_topology/IO/Read_error.h>
#include <Soup_topology/internal/reader_input.h>

#include <cerrno>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <iterator>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace Soup_topology {
namespace IO {

/// \ingroup PkgSoupTopologyIO
/// \brief what `read_OFF_polygons()` read.
struct OFF_read_result
{
  std::size_t vertices = 0;   ///< vertices read (as announced by the header)
  std::size_t faces = 0;      ///< faces read (as announced by the header)
};

namespace internal {

class OFF_scanner
{
public:
  OFF_scanner(const char* b, const char* e, const std::string& name)
    : p_(b + Soup_topology::internal::utf8_bom_size(b, e)), e_(e), name_(name) {}

  /// the next token, skipping white space and `#` comments; `false` at the end of the data.
  bool next(std::string_view& token)
  {
    skip_space_and_comments();
    if(p_ == e_) return false;
    const char* s = p_;
    while(p_ < e_ && !is_space(*p_) && *p_ != '#') ++p_;
    token = std::string_view(s, static_cast<std::size_t>(p_ - s));
    token_line_ = line_;
    return true;
  }
  /// skips what is left of the current line (the attributes that follow the numbers we read).
  void skip_rest_of_line()
  {
    while(p_ < e_ && *p_ != '\n' && *p_ != '\r') ++p_;
  }
  /// `true` if a token follows on the current line.
  bool more_on_line() const
  {
    const char* q = p_;
    while(q < e_ && is_space(*q) && *q != '\n' && *q != '\r') ++q;
    return q < e_ && *q != '\n' && *q != '\r' && *q != '#';
  }
  /// `true` if only white space and comments are left.
  bool at_end()
  {
    skip_space_and_comments();
    return p_ == e_;
  }
  std::size_t remaining_bytes() const { return static_cast<std::size_t>(e_ - p_); }

  /// the description of a value, a string or a function that returns one (see `describe()`).
  template <class What>
  static std::string describe(const What& what)
  {
    return Soup_topology::internal::describe(what);
  }
  template <class What>
  std::string_view token_or_fail(const What& expected)
  {
    std::string_view t;
    if(!next(t)) fail("unexpected end of file, expected " + describe(expected));
    return t;
  }
  static std::string quoted(std::string_view t)
  { return "'" + Soup_topology::internal::printable(t.data(), t.data() + t.size()) + "'"; }
  template <class What>
  double number(const What& what)
  {
    const std::string_view t = token_or_fail(what);
    double x;
    if(!Soup_topology::internal::parse_double(t.data(), t.data() + t.size(), x))
      fail(quoted(t) + " is not a number (" + describe(what) + ")");
    if(!std::isfinite(x)) fail("non-finite coordinate " + quoted(t) + " (" + describe(what) + ")");
    return x;
  }
  /// a signed integer; `what` names it in the error messages.
  template <class What>
  long long integer(const What& what) { return integer(token_or_fail(what), what); }
  template <class What>
  long long integer(std::string_view t, const What& what)
  {
    long long x = 0;
    switch(Soup_topology::internal::parse_integer(t.data(), t.data() + t.size(), x)) {
    case Soup_topology::internal::Integer_parse::NOT_AN_INTEGER: fail(quoted(t) + " is not an integer (" + describe(what) + ")");
    case Soup_topology::internal::Integer_parse::TOO_LARGE: fail(quoted(t) + " is too large (" + describe(what) + ")");
    default: break;
    }
    return x;
  }
  /// an integer >= 0.
  template <class What>
  std::size_t count(const What& what)
  {
    const long long x = integer(what);
    if(x < 0) fail("negative " + describe(what) + " (" + std::to_string(x) + ")");
    return static_cast<std::size_t>(x);
  }
  [[noreturn]] void fail(const std::string& what) const
  { throw Read_error(name_ + ":" + std::to_string(token_line_) + ": " + what); }

private:
  static bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }
  // A line ends with LF, CR LF or a lone CR (old Mac files).
  void skip_space_and_comments()
  {
    while(p_ < e_) {
      if(*p_ == '\n') { ++line_; ++p_; }
      else if(*p_ == '\r') { ++p_; if(p_ == e_ || *p_ != '\n') ++line_; }
      else if(is_space(*p_)) ++p_;
      else if(*p_ == '#') { while(p_ < e_ && *p_ != '\n' && *p_ != '\r') ++p_; }
      else break;
    }
  }
  const char* p_;
  const char* e_;
  std::string name_;
  std::size_t line_ = 1;
  std::size_t token_line_ = 1; // the line of the last token read: errors, also at the end of the file, name it
};

/// parses an OFF keyword: `[ST][C][N][4][n]OFF`; returns false if `t` is not one.
inline bool parse_OFF_keyword(std::string_view t, bool& texture, bool& colour, bool& normal, bool& homogeneous,
                              bool& dimension)
{
  std::size_t i = 0;
  texture = colour = normal = homogeneous = dimension = false;
  if(t.substr(0, 2) == "ST") { texture = true; i += 2; }
  if(i < t.size() && t[i] == 'C') { colour = true; ++i; }
  if(i < t.size() && t[i] == 'N') { normal = true; ++i; }
  if(i < t.size() && t[i] == '4') { homogeneous = true; ++i; }
  if(i < t.size() && t[i] == 'n') { dimension = true; ++i; }
  return t.substr(i) == "OFF";
}

} // namespace internal

/// \ingroup PkgSoupTopologyIO
/// \brief reads the OFF file held in `[data, data + size)` (the whole file, ASCII) into `points` and
/// `polygons` (appended; polygons index `points` from the size it had on entry).
///
/// Accepted: the keywords `OFF`, `COFF`, `NOFF`, `CNOFF`, `STOFF`, `4OFF`, `nOFF` (dimension 3)
/// and their combinations, `#` comments anywhere, the counts on the keyword's line or on the
/// next, a UTF-8 byte order mark before the keyword, lines ended by LF, CR LF or CR alone. One vertex or face per line: what follows the coordinates of a vertex or the indices of
/// a face on its line (normals, colours, texture coordinates) is ignored. Faces of any size are
/// returned as they are (also those with fewer than 3 corners or a repeated index).
///
/// Rejected with a `Read_error` whose message reads `"<name>:<line>: <what>"`: a missing or
/// unknown keyword, binary OFF, a count line that is not three integers >= 0 (a token is a number
/// only if all of it is: `4x` or `1` followed by a NUL byte are not), counts that the
/// data does not match (fewer vertices or faces than announced, or data after the last face), a
/// number that does not parse, a NaN or infinite coordinate, a homogeneous coordinate of 0, a
/// negative or out-of-range vertex index. Nothing is allocated from a count of the file: a
/// header that announces more elements than the file can hold is rejected at once.
/// `points` and `polygons` are unchanged when an exception is thrown.
/// \tparam Point a `Point_3` constructible from three `double`
template <class Point>
OFF_read_result read_OFF_polygons(const char* data, std::size_t size, std::vector<Point>& points,
                                  std::vector<std::vector<std::size_t>>& polygons, const std::string& name = "OFF")
{
  internal::OFF_scanner in(data, data + size, name);
  std::string_view t;
  if(!in.next(t)) in.fail("empty file, expected the OFF header");
  bool texture, colour, normal, homogeneous, dimension;
  if(!internal::parse_OFF_keyword(t, texture, colour, normal, homogeneous, dimension))
    in.fail("expected the keyword OFF (or COFF, NOFF, ...), found " + in.quoted(t));
  (void)texture; (void)colour; (void)normal; // their data is on the vertex lines, skipped
  if(dimension) {
    const std::size_t d = in.count("dimension");
    if(d != 3) in.fail("dimension " + std::to_string(d) + " is not supported (only 3)");
  }
  {
    // "BINARY" after the keyword reads where the number of vertices is expected.
    std::string_view first;
    if(!in.next(first)) in.fail("unexpected end of file, expected the count line (vertices faces edges)");
    if(first == "BINARY") in.fail("binary OFF is not supported");
    const long long nv_signed = in.integer(first, "number of vertices in the count line");
    if(nv_signed < 0) in.fail("negative number of vertices (" + std::to_string(nv_signed) + ") in the count line");
    const std::size_t nv = static_cast<std::size_t>(nv_signed);
    const std::size_t nf = in.count("number of faces in the count line");
    if(in.more_on_line()) in.count("number of edges in the count line"); // optional, unused
    in.skip_rest_of_line();

    // Fail fast on counts the file cannot hold: a vertex takes at least 6 bytes ("0 0 0\n"),
    // a face at least 2 ("0\n").
    const std::size_t room = in.remaining_bytes() + 1;
    if(nv > room / 6 || nf > room / 2 || (nv > 0 && nf > (room - 6 * nv) / 2))
      in.fail("the header announces " + std::to_string(nv) + " vertices and " + std::to_string(nf) +
              " faces, more than the remaining " + std::to_string(in.remaining_bytes()) + " bytes can hold");

    const std::size_t base = points.size();
    std::vector<Point> pts;
    std::vector<std::vector<std::size_t>> polys;
    for(std::size_t v = 0; v < nv; ++v) {
      const auto what = [&]() { return "vertex " + std::to_string(v) + " of " + std::to_string(nv); };
      double c[4] = {0, 0, 0, 1};
      for(int k = 0; k < (homogeneous ? 4 : 3); ++k) c[k] = in.number(what);
      if(homogeneous) {
        if(c[3] == 0) in.fail("homogeneous coordinate 0 (" + what() + ")");
        for(int k = 0; k < 3; ++k) {
          c[k] /= c[3];
          if(!std::isfinite(c[k])) in.fail("non-finite coordinate after the division by w (" + what() + ")");
        }
      }
      pts.push_back(Point(c[0], c[1], c[2]));
      in.skip_rest_of_line();
    }
    for(std::size_t f = 0; f < nf; ++f) {
      const auto what = [&]() { return "face " + std::to_string(f) + " of " + std::to_string(nf); };
      const long long n = in.integer([&]() { return "number of corners of " + what(); });
      if(n < 0) in.fail("negative number of corners (" + std::to_string(n) + ") of " + what());
      if(static_cast<unsigned long long>(n) > in.remaining_bytes() / 2 + 1)
        in.fail(what() + " announces " + std::to_string(n) + " corners, more than the rest of the file holds");
      std::vector<std::size_t> poly;
      poly.reserve(static_cast<std::size_t>(n));
      for(long long k = 0; k < n; ++k) {
        const long long i = in.integer([&]() { return "corner " + std::to_string(k) + " of " + what(); });
        if(i < 0) in.fail(what() + " has a negative vertex index (" + std::to_string(i) + ")");
        if(static_cast<unsigned long long>(i) >= nv)
          in.fail(what() + " has vertex index " + std::to_string(i) + ", out of range (" + std::to_string(nv) +
                  " vertices)");
        poly.push_back(base + static_cast<std::size_t>(i));
      }
      polys.push_back(std::move(poly));
      in.skip_rest_of_line();
    }
    if(!in.at_end()) {
      in.next(t);
      in.fail("data after the " + std::to_string(nf) + " faces the header announces (" + in.quoted(t) +
              "): is the count line wrong?");
    }
    Soup_topology::internal::append_read_polygons(pts, polys, points, polygons);
    OFF_read_result result;
    result.vertices = nv;
    result.faces = nf;
    return result;
  }
}

/// \ingroup PkgSoupTopologyIO
/// \brief reads the OFF file held in `data`, see above.
template <class Point>
OFF_read_result read_OFF_polygons(const std::string& data, std::vector<Point>& points,
                                  std::vector<std::vector<std::size_t>>& polygons, const std::string& name = "OFF")
{
  return read_OFF_polygons(data.data(), data.size(), points, polygons, name);
}

} // namespace IO
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_IO_OFF_H
