// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// A reader of STL files (binary and ASCII) that returns the explicit triangles, unwelded.
//
// Why not CGAL::IO::read_STL: it welds while reading, through a std::map of points, which makes
// it the slowest part of a repair of a large STL (see benchmark/index_triangles_benchmark.cpp);
// and it cannot say which facet or line of a broken file is wrong. Here the triangles are
// returned as they are, decoded from the file's bytes in memory (`read_STL_triangles()`) or from
// the file read by blocks (`read_STL_file()`), and `index_triangles()` welds them in expected
// linear time.

#ifndef SOUP_TOPOLOGY_IO_STL_H
#define SOUP_TOPOLOGY_IO_STL_H

#include <Soup_topology/IO/Read_error.h>
#include <Soup_topology/internal/parallel.h>
#include <Soup_topology/internal/reader_input.h>

#include <CGAL/Kernel_traits.h>
#include <CGAL/tags.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <string_view>
#include <type_traits>
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
  bool next(std::string_view& token)
  {
    while(p_ < e_ && is_stl_space(*p_)) advance();
    if(p_ == e_) return false;
    const char* s = p_;
    while(p_ < e_ && !is_stl_space(*p_)) ++p_;
    token = std::string_view(s, static_cast<std::size_t>(p_ - s));
    return true;
  }
  /// skips the rest of the current line (the name of a solid).
  void skip_rest_of_line()
  {
    while(p_ < e_ && *p_ != '\n' && *p_ != '\r') ++p_;
  }
  void expect(const char* keyword)
  {
    std::string_view t;
    if(!next(t)) fail(std::string("unexpected end of file, expected '") + keyword + "'");
    if(!equal_nocase(t, keyword)) fail(std::string("expected '") + keyword + "', found " + quoted(t));
  }
  double number()
  {
    std::string_view t;
    if(!next(t)) fail("unexpected end of file, expected a number");
    double x;
    if(!Soup_topology::internal::parse_double(t.data(), t.data() + t.size(), x)) fail(quoted(t) + " is not a number");
    return x;
  }
  [[noreturn]] void fail(const std::string& what) const
  { throw Read_error(name_ + ":" + std::to_string(line_) + ": " + what); }
  static std::string quoted(std::string_view t)
  { return "'" + Soup_topology::internal::printable(t.data(), t.data() + t.size()) + "'"; }
  static bool equal_nocase(std::string_view a, const char* b)
  {
    const std::size_t n = std::strlen(b);
    if(a.size() != n) return false;
    for(std::size_t i = 0; i < n; ++i)
      if(std::tolower(static_cast<unsigned char>(a[i])) != b[i]) return false;
    return true;
  }
  std::size_t line() const { return line_; }
private:
  // LF, CR LF and a lone CR end a line.
  void advance()
  {
    if(*p_ == '\n') ++line_;
    else if(*p_ == '\r' && (p_ + 1 == e_ || p_[1] != '\n')) ++line_;
    ++p_;
  }
  const char* p_;
  const char* e_;
  std::string name_;
  std::size_t line_ = 1;
};

/// `true` if `[b, e)` holds a byte that no ASCII STL holds (a NUL or another control character
/// than white space): then a file that starts with "solid" is a binary one (its header may say
/// "solid").
inline bool has_binary_byte(const char* b, const char* e)
{
  for(; b < e; ++b) {
    const unsigned char c = static_cast<unsigned char>(*b);
    if(c < 0x20 && !is_stl_space(*b)) return true;
    if(c == 0x7f) return true;
  }
  return false;
}

/// `true` if the binary STL of `size` bytes starting at `b` announces exactly its size (its
/// first 84 bytes, when it has them, are in memory at `b`).
inline bool binary_stl_size_matches(const char* b, std::size_t size)
{
  if(size < 84) return false;
  std::uint32_t n;
  std::memcpy(&n, b + 80, 4);
  return 84 + 50 * std::uint64_t(n) == size;
}

/// `true` if the binary STL held in `[b, e)` announces exactly its size.
inline bool binary_stl_size_matches(const char* b, const char* e)
{ return binary_stl_size_matches(b, static_cast<std::size_t>(e - b)); }

/// `true` if `[b, e)` starts, after white space, with "solid" (any case).
inline bool starts_with_solid(const char* b, const char* e)
{
  while(b < e && is_stl_space(*b)) ++b;
  if(e - b < 5) return false;
  for(int i = 0; i < 5; ++i)
    if(std::tolower(static_cast<unsigned char>(b[i])) != "solid"[i]) return false;
  return true;
}

/// the bytes at the start of an STL file that decide whether it is ASCII or binary (with the
/// facet count of a binary header), unless they are all white space: a UTF-8 byte order mark,
/// the 84 bytes of a binary header and 4 facets.
constexpr std::size_t stl_deciding_bytes = 3 + 84 + 50 * 4;

/// `true` if the file of `size` bytes starting at `b` is an ASCII STL, seen from its first bytes
/// `[b, prefix_end)`: all of them for a short file, else at least the first
/// `stl_deciding_bytes`, and at least up to the end of the first word after white space.
inline bool looks_like_ascii_stl(const char* b, const char* prefix_end, std::size_t size)
{
  if(!starts_with_solid(b, prefix_end)) return false;
  // Some binary files also start with "solid": they are recognised by their exact size, or by
  // a byte that is not text in the header or the first facets.
  if(binary_stl_size_matches(b, size)) return false;
  const std::size_t look = size < 84 + 50 * 4 ? size : 84 + 50 * 4;
  return !has_binary_byte(b, b + look);
}

inline bool looks_like_ascii_stl(const char* b, const char* e)
{ return looks_like_ascii_stl(b, e, static_cast<std::size_t>(e - b)); }

inline bool looks_like_ascii_stl(const std::string& data)
{ return looks_like_ascii_stl(data.data(), data.data() + data.size()); }

/// the number of facets of the binary STL of `size` bytes starting at `data`, after checking
/// that the size is the one its header announces, seen from its first bytes `[data,
/// prefix_end)` (as for `looks_like_ascii_stl()`). `name` starts the messages.
/// \throws Read_error on a file shorter than its header, or a size that does not match.
inline std::uint32_t binary_STL_facet_count(const char* data, const char* prefix_end, std::size_t size,
                                            const std::string& name)
{
  const char* const end = prefix_end;
  if(size < 84)
    throw Read_error(name + ": binary STL shorter than its 84-byte header (" + std::to_string(size) + " bytes)");
  std::uint32_t n;
  std::memcpy(&n, data + 80, 4);
  const std::uint64_t expected = 84 + 50 * std::uint64_t(n);
  if(expected != size && !starts_with_solid(data, end) &&
     !has_binary_byte(data, data + (size < 84 + 50 * 4 ? size : 84 + 50 * 4)))
    throw Read_error(name + ": neither an ASCII STL (it does not start with 'solid') nor a binary STL (its size, " +
                     std::to_string(size) + " bytes, does not match the facet count of a binary header)");
  // Checked before any allocation: a header that claims 4 billion facets costs nothing.
  if(size < expected)
    throw Read_error(name + ": binary STL header announces " + std::to_string(n) + " facets, the file holds " +
                     std::to_string((size - 84) / 50) + " complete facets (truncated at facet " +
                     std::to_string((size - 84) / 50) + ")");
  if(size > expected)
    throw Read_error(name + ": binary STL header announces " + std::to_string(n) + " facets, the file holds " +
                     std::to_string(size - expected) + " bytes more than that");
  return n;
}

/// the number of facets of the binary STL held in `[data, data + size)`, see above.
inline std::uint32_t binary_STL_facet_count(const char* data, std::size_t size, const std::string& name)
{
  return binary_STL_facet_count(data, data + size, size, name);
}

/// the tag the facets of a binary STL are decoded with: `ConcurrencyTag` for points whose
/// coordinates are stored as `double`, sequential for the others (exact number types share
/// cached state between points).
template <class ConcurrencyTag, class Point>
using STL_decode_tag =
  std::conditional_t<Soup_topology::internal::runs_in_parallel<ConcurrencyTag>() &&
                       std::is_same<typename CGAL::Kernel_traits<Point>::Kernel::FT, double>::value,
                     ConcurrencyTag, CGAL::Sequential_tag>;

/// corner `k` of the 50-byte binary STL facet that starts at `facet` (its normal first).
template <class Point>
Point binary_STL_facet_corner(const char* facet, std::size_t k)
{
  float c[3];
  std::memcpy(c, facet + 12 * (1 + k), sizeof c);
  return Point(double(c[0]), double(c[1]), double(c[2]));
}

/// corner `i` (corner `i % 3` of facet `i / 3`) of a checked binary STL held from `data` on.
template <class Point>
Point binary_STL_corner(const char* data, std::size_t i)
{
  return binary_STL_facet_corner<Point>(data + 84 + 50 * (i / 3), i % 3);
}

/// appends the facets of the ASCII solids in `[b, e)` (from the first `solid`) to `triangles`;
/// throws `Read_error` naming the line on malformed input, with the facets read so far appended.
template <class Point>
void read_ascii_STL_solids(const char* b, const char* e, const std::string& name,
                           std::vector<std::array<Point, 3>>& triangles)
{
  using S = STL_ascii_scanner;
  S in(b, e, name);
  std::string_view t;
  bool more = in.next(t); // "solid", checked by looks_like_ascii_stl
  while(more) {
    if(!S::equal_nocase(t, "solid")) in.fail("expected 'solid' after 'endsolid', found " + S::quoted(t));
    in.skip_rest_of_line(); // the name of the solid, which may be a keyword
    for(;;) {
      if(!in.next(t)) in.fail("unexpected end of file, expected 'endsolid'");
      if(S::equal_nocase(t, "endsolid")) break;
      if(!S::equal_nocase(t, "facet")) in.fail("expected 'facet' or 'endsolid', found " + S::quoted(t));
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
      triangles.push_back(tri);
    }
    in.skip_rest_of_line(); // the name after endsolid
    more = in.next(t);
  }
}

/// the check of the first bytes of an STL input of unknown size (see `read_bounded()`): a
/// binary header announces the size, beyond which the input is refused without reading on.
struct STL_prefix_check
{
  Soup_topology::internal::Input_size operator()(const char* b, const char* e) const
  {
    Soup_topology::internal::Input_size s;
    if(starts_with_solid(b, e) && !has_binary_byte(b, e)) return s;
    if(e - b < 84) return s;
    std::uint32_t n;
    std::memcpy(&n, b + 80, 4);
    const std::uint64_t expected = 84 + 50 * std::uint64_t(n);
    if(expected < static_cast<std::uint64_t>(s.expected)) s.expected = static_cast<std::size_t>(expected);
    s.what = "binary STL header announces " + std::to_string(n) + " facets (" + std::to_string(expected) + " bytes)";
    return s;
  }
};

} // namespace internal

/// \ingroup PkgSoupTopologyIO
/// \brief reads the triangles of an STL file held in `[data, data + size)` (the whole file),
/// binary or ASCII, appending each facet as 3 points to `triangles`. `name` is used in error
/// messages.
///
/// A file is ASCII if it starts with `solid` (any case, after white space) and holds only text
/// in its first facets' worth of bytes; else it is binary, also when its 80-byte header starts
/// with `solid`. An ASCII file is `solid` and a name (the rest of that line: `solid facet` names
/// the solid "facet"), facets, `endsolid` and a name on its line; several solids follow each
/// other; keywords are case-insensitive; lines end with LF, CR LF or CR; a UTF-8 byte order
/// mark before `solid` is skipped.
/// \tparam Point a `Point_3` constructible from three `double`
/// \throws Read_error naming the line (ASCII) or the facet (binary) on malformed input: a
/// truncated binary file, a triangle count that does not match the size, a missing keyword, a
/// token that is not entirely a number, anything but a new solid after `endsolid`, a file that
/// is neither (no `solid` and a size that no binary count explains). `triangles` is left
/// unchanged then. NaN and infinite coordinates are read (`read_triangle_soup()` refuses them).
/// With `CGAL::Parallel_tag` the facets of a binary file are decoded on TBB's threads (for points
/// whose coordinates are stored as `double`), with the same result.
/// \tparam ConcurrencyTag `CGAL::Sequential_tag` (the default), `CGAL::Parallel_tag` (needs TBB)
///         or `CGAL::Parallel_if_available_tag`
/// \param data the bytes of the file
/// \param size the number of bytes
/// \param triangles receives the triangles read (appended)
/// \param name the name of the input in error messages
template <class ConcurrencyTag = CGAL::Sequential_tag, class Point>
STL_read_result read_STL_triangles(const char* data, std::size_t size, std::vector<std::array<Point, 3>>& triangles,
                                   const std::string& name = "STL")
{
  using Decode_tag = internal::STL_decode_tag<ConcurrencyTag, Point>;
  STL_read_result result;
  // The facets are decoded straight into `triangles`, after what it held: no temporary copy of
  // the soup (at 72 bytes a facet with `double` points, that copy was the larger part of the
  // parse). On a malformed file the facets appended so far are erased before the error leaves.
  const std::size_t held = triangles.size();
  const char* const end = data + size;
  // A UTF-8 byte order mark before "solid" is skipped (a binary header may start with anything).
  const std::size_t bom = Soup_topology::internal::utf8_bom_size(data, end);
  if(internal::looks_like_ascii_stl(data + bom, end)) {
    try {
      internal::read_ascii_STL_solids(data + bom, end, name, triangles);
    } catch(...) {
      triangles.erase(triangles.begin() + static_cast<std::ptrdiff_t>(held), triangles.end());
      throw;
    }
  } else {
    result.binary = true;
    const std::uint32_t n = internal::binary_STL_facet_count(data, size, name); // throws before any change
    triangles.resize(held + n);
    std::array<Point, 3>* const read = triangles.data() + held;
    Soup_topology::internal::for_each_index<Decode_tag>(n, [&](std::size_t f) {
      for(std::size_t k = 0; k < 3; ++k) read[f][k] = internal::binary_STL_corner<Point>(data, 3 * f + k);
    });
  }
  result.triangles = triangles.size() - held;
  return result;
}

/// \ingroup PkgSoupTopologyIO
/// \brief reads the triangles of an STL file held in `data`, see above.
template <class ConcurrencyTag = CGAL::Sequential_tag, class Point>
STL_read_result read_STL_triangles(const std::string& data, std::vector<std::array<Point, 3>>& triangles,
                                   const std::string& name = "STL")
{
  return read_STL_triangles<ConcurrencyTag>(data.data(), data.size(), triangles, name);
}

/// \ingroup PkgSoupTopologyIO
/// \brief the most bytes read from an input whose size is not known in advance (a pipe, a
/// device such as `/dev/stdin`, a `std::istream`): 256 MiB. A regular file is read whole.
constexpr std::size_t default_stream_size_limit = std::size_t(256) << 20;

/// \ingroup PkgSoupTopologyIO
/// \brief reads the whole file `filename` into a string: a regular file whole, another input
/// (a pipe, a device) up to `limit` bytes.
/// \throws Read_error if it cannot be opened or read, is a folder, or is not a regular file
/// and holds more than `limit` bytes.
inline std::string read_file_contents(const std::string& filename, std::size_t limit = default_stream_size_limit)
{
  return Soup_topology::internal::read_file_bounded(filename, limit);
}

/// \ingroup PkgSoupTopologyIO
/// \brief the facets that `read_STL_file()` reads from a binary file in one block: 8,192 (400 KiB of
/// the file, in a buffer reused from block to block).
constexpr std::size_t STL_facets_per_block = std::size_t(1) << 13;

/// \ingroup PkgSoupTopologyIO
/// \brief reads the STL file `filename` (binary or ASCII), appending each facet as 3 points to
/// `triangles`: the triangles, the result and the errors of
/// `read_STL_triangles(read_file_contents(filename, limit), triangles, filename)`, without the
/// copy of the whole file in memory for a binary one.
///
/// A binary regular file is read by blocks of `STL_facets_per_block` facets into one buffer,
/// each block decoded into `triangles` before the next is read: the memory used is that of the
/// triangles and of the buffer, and the file's bytes are copied once, from the system's cache
/// to the buffer. (Holding the whole file, as `read_file_contents()` does, costs a fresh block
/// of memory as large as the file, whose first touch cost more than the copy on the machines
/// measured; see `doc/Soup_topology/Performance.md`.) An ASCII file, and an input that is not a regular file
/// (a pipe, a device, read up to `limit` bytes), are read whole first.
/// \tparam ConcurrencyTag as for `read_STL_triangles()`: with `CGAL::Parallel_tag` every block
///         is decoded on TBB's threads, with the same result
/// \tparam Point a `Point_3` constructible from three `double`
/// \param filename the file; it names the input in the messages
/// \param triangles receives the triangles read (appended)
/// \param limit the most bytes read from an input that is not a regular file
/// \throws Read_error as `read_file_contents()` and `read_STL_triangles()` do, and when a binary
/// file is shorter, when read, than when its size was taken. `triangles` is left unchanged then.
template <class ConcurrencyTag = CGAL::Sequential_tag, class Point>
STL_read_result read_STL_file(const std::string& filename, std::vector<std::array<Point, 3>>& triangles,
                              std::size_t limit = default_stream_size_limit)
{
  const auto read_whole = [&]() {
    return read_STL_triangles<ConcurrencyTag>(read_file_contents(filename, limit), triangles, filename);
  };
  std::ifstream in;
  if(!Soup_topology::internal::open_input_file(filename, in)) return read_whole();
  const std::size_t size = Soup_topology::internal::regular_file_size(in, filename);
  // The first bytes decide between ASCII and binary as read_STL_triangles() decides on the whole
  // file, unless the white space at the start (after a byte order mark) leaves no room in them
  // for "solid": then the whole file is read.
  static_assert(50 * STL_facets_per_block >= internal::stl_deciding_bytes, "a block holds the bytes that decide");
  // (no larger than the file, so that a small part of an assembly does not take a whole block;
  // one byte at least, so that its data is never null)
  std::vector<char> buffer(std::max<std::size_t>(std::min(size, 50 * STL_facets_per_block), 1));
  const std::size_t prefix = std::min(size, buffer.size());
  if(prefix > 0 && !in.read(buffer.data(), static_cast<std::streamsize>(prefix)))
    throw Read_error(filename + ": cannot read the file");
  const char* const b = buffer.data();
  const std::size_t bom = Soup_topology::internal::utf8_bom_size(b, b + prefix);
  const char* const text = std::find_if(b + bom, b + prefix, [](char c) { return !internal::is_stl_space(c); });
  if((prefix < size && text + 5 > b + prefix) || internal::looks_like_ascii_stl(b + bom, b + prefix, size - bom))
    return read_whole();

  using Decode_tag = internal::STL_decode_tag<ConcurrencyTag, Point>;
  const std::uint32_t n = internal::binary_STL_facet_count(b, b + prefix, size, filename); // throws before any change
  const std::size_t held = triangles.size();
  triangles.resize(held + n);
  try {
    in.seekg(84, std::ios::beg);
    for(std::size_t first = 0; first < n; first += STL_facets_per_block) {
      const std::size_t count = std::min<std::size_t>(STL_facets_per_block, n - first);
      if(!in.read(buffer.data(), static_cast<std::streamsize>(50 * count)))
        throw Read_error(filename + ": cannot read the file (it is shorter than when its size was taken)");
      std::array<Point, 3>* const read = triangles.data() + held + first;
      const char* const facets = buffer.data();
      Soup_topology::internal::for_each_index<Decode_tag>(count, [&](std::size_t f) {
        for(std::size_t k = 0; k < 3; ++k) read[f][k] = internal::binary_STL_facet_corner<Point>(facets + 50 * f, k);
      });
    }
  } catch(...) {
    triangles.erase(triangles.begin() + static_cast<std::ptrdiff_t>(held), triangles.end());
    throw;
  }
  STL_read_result result;
  result.binary = true;
  result.triangles = n;
  return result;
}

} // namespace IO
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_IO_STL_H
