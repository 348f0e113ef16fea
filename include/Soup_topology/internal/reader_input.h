// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// What the readers share: reading a whole input into memory with a bound when its size is not
// known in advance (pipes, devices, streams), strict parsing of numbers (a token is a number only
// if all of it is), and quoting a token in a message (cut, with its unprintable bytes escaped).
//
// Why a bound: a regular file has a size, and the readers compare every count of a header with
// it before allocating. A pipe or a device has none: `/dev/zero` or `/dev/urandom` behind a
// `.stl` link would be read until memory runs out.

#ifndef SOUP_TOPOLOGY_INTERNAL_READER_INPUT_H
#define SOUP_TOPOLOGY_INTERNAL_READER_INPUT_H

#include <Soup_topology/IO/Read_error.h>

#include <sys/stat.h>

#include <cerrno>
#include <charconv>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <istream>
#include <iterator>
#include <string>
#include <system_error>
#include <type_traits>
#include <utility>
#include <vector>

namespace Soup_topology {
namespace internal {

/// appends what a reader read (`read_points`, `read_polygons`) to the caller's containers, moved
/// rather than copied. The readers call it once the whole file is read, so that the caller's
/// containers are unchanged when a file is refused.
template <class Point>
void append_read_polygons(std::vector<Point>& read_points, std::vector<std::vector<std::size_t>>& read_polygons,
                          std::vector<Point>& points, std::vector<std::vector<std::size_t>>& polygons)
{
  if(points.empty()) points.swap(read_points);
  else points.insert(points.end(), read_points.begin(), read_points.end());
  if(polygons.empty()) polygons.swap(read_polygons);
  else polygons.insert(polygons.end(), std::make_move_iterator(read_polygons.begin()),
                       std::make_move_iterator(read_polygons.end()));
}

/// the token `[b, e)` as it can be shown in a message: at most `max` bytes, then "...", with
/// the bytes that are not printable ASCII written `\xNN`.
inline std::string printable(const char* b, const char* e, std::size_t max = 40)
{
  std::string s;
  const std::size_t n = static_cast<std::size_t>(e - b);
  for(std::size_t i = 0; i < n && i < max; ++i) {
    const unsigned char c = static_cast<unsigned char>(b[i]);
    if(c >= 0x20 && c < 0x7f) s += static_cast<char>(c);
    else {
      char hex[8];
      std::snprintf(hex, sizeof hex, "\\x%02X", c);
      s += hex;
    }
  }
  if(n > max) s += "...";
  return s;
}
inline std::string printable(const std::string& t, std::size_t max = 40)
{ return printable(t.data(), t.data() + t.size(), max); }

/// `what`, a string or a function that returns one: the description of a value being read,
/// only built when a message needs it.
template <class What>
std::string describe(const What& what)
{
  if constexpr(std::is_invocable<const What&>::value) return what();
  else return std::string(what);
}

/// parses `[b, e)` as a whole real number of type `Real` (`float` or `double`), correctly
/// rounded: `std::from_chars` reads the usual decimal forms without allocating; what it does not
/// take (a leading `+`, hexadecimal, a value out of range) is read by `std::strtod` /
/// `std::strtof`, so that the accepted texts and their values are those of the C library.
template <class Real>
bool parse_real(const char* b, const char* e, Real& x)
{
  const std::size_t n = static_cast<std::size_t>(e - b);
  if(n == 0 || static_cast<unsigned char>(*b) <= ' ') return false;
  Real value;
  const std::from_chars_result r = std::from_chars(b, e, value);
  if(r.ec == std::errc() && r.ptr == e) {
    x = value;
    return true;
  }
  char local[64];
  std::string heap;
  const char* s;
  if(n < sizeof local) {
    std::memcpy(local, b, n);
    local[n] = '\0';
    s = local;
  } else {
    heap.assign(b, e);
    s = heap.c_str();
  }
  // A NUL inside the token ends strtod early and is caught by the length check.
  char* end = nullptr;
  if constexpr(std::is_same<Real, float>::value) x = std::strtof(s, &end);
  else x = std::strtod(s, &end);
  return end == s + n;
}

/// `true` if `[b, e)` is entirely a decimal floating-point number (as `strtod` reads it: also
/// `inf`, `nan` and hexadecimal, which the callers refuse or accept as they document); its
/// value in `x`.
inline bool parse_double(const char* b, const char* e, double& x)
{
  return parse_real(b, e, x);
}

/// parses `[b, e)` as a whole `float`, rounded once from the text (as `std::strtof` does).
inline bool parse_float(const char* b, const char* e, float& x)
{
  return parse_real(b, e, x);
}

/// how `parse_integer()` ended.
enum class Integer_parse { OK, NOT_AN_INTEGER, TOO_LARGE };

/// parses `[b, e)` as a whole decimal integer with an optional sign, into `x`.
inline Integer_parse parse_integer(const char* b, const char* e, long long& x)
{
  const char* p = b;
  bool negative = false;
  if(p < e && (*p == '+' || *p == '-')) negative = (*p++ == '-');
  if(p == e) return Integer_parse::NOT_AN_INTEGER;
  unsigned long long v = 0;
  bool overflow = false;
  const unsigned long long limit = negative ? 9223372036854775808ULL : 9223372036854775807ULL;
  for(; p < e; ++p) {
    if(*p < '0' || *p > '9') return Integer_parse::NOT_AN_INTEGER;
    const unsigned d = static_cast<unsigned>(*p - '0');
    if(v > (limit - d) / 10) overflow = true;
    else v = 10 * v + d;
  }
  if(overflow) return Integer_parse::TOO_LARGE;
  x = negative ? (v == 9223372036854775808ULL ? (-9223372036854775807LL - 1) : -static_cast<long long>(v))
               : static_cast<long long>(v);
  return Integer_parse::OK;
}

/// the number of bytes of a UTF-8 byte order mark at the start of `[b, e)` (0 or 3).
inline std::size_t utf8_bom_size(const char* b, const char* e)
{
  return (e - b >= 3 && static_cast<unsigned char>(b[0]) == 0xEF && static_cast<unsigned char>(b[1]) == 0xBB &&
          static_cast<unsigned char>(b[2]) == 0xBF) ? 3 : 0;
}

/// what a reader learns from the first bytes of an input whose size is not known: the size the
/// input must have (a binary STL announces it in its header), `what` says so in the messages.
struct Input_size
{
  std::size_t expected = static_cast<std::size_t>(-1); ///< unknown
  std::string what;
};

/// a check of the first bytes that accepts everything.
struct No_prefix_check
{
  Input_size operator()(const char*, const char*) const { return Input_size(); }
};

/// the number of bytes that `read_bounded()` gives to the prefix check (or all, if fewer).
constexpr std::size_t prefix_check_bytes = 4096;

/// reads what is left of `in` into a string, refusing more than `limit` bytes; `name` names the
/// input in the messages. `check(b, e)` sees the first bytes once (at most
/// `prefix_check_bytes`, all of them for a shorter input) and throws to refuse the input at
/// once (random or zero bytes behind a text extension), or returns the size the input must have
/// (then an input that announces more than `limit`, or holds more than it announces, is refused
/// without reading on). The memory used is at most about twice the bytes read.
template <class Prefix_check = No_prefix_check>
std::string read_bounded(std::istream& in, const std::string& name, std::size_t limit,
                         const Prefix_check& check = Prefix_check())
{
  const std::string not_regular = " bytes for an input that is not a regular file (a pipe, a device or a stream)";
  // Chunks, joined at the end: no copy of a growing buffer on the way.
  std::vector<std::string> chunks;
  std::size_t total = 0;
  bool checked = false;
  Input_size size;
  std::string prefix;
  for(std::size_t chunk_size = prefix_check_bytes;; chunk_size = std::size_t(1) << 20) {
    std::string chunk(chunk_size, '\0');
    in.read(&chunk[0], static_cast<std::streamsize>(chunk.size()));
    chunk.resize(static_cast<std::size_t>(in.gcount()));
    total += chunk.size();
    const bool end = !in;
    if(!checked) {
      checked = true;
      size = check(chunk.data(), chunk.data() + chunk.size());
      if(size.expected != static_cast<std::size_t>(-1) && size.expected > limit)
        throw IO::Read_error(name + ": " + size.what + ", more than the limit of " + std::to_string(limit) + not_regular);
    }
    if(total > size.expected) throw IO::Read_error(name + ": " + size.what + ", the input holds more than that");
    if(total > limit)
      throw IO::Read_error(name + ": more than " + std::to_string(limit) + not_regular + ", the limit for such inputs");
    chunks.push_back(std::move(chunk));
    if(end) break;
  }
  if(in.bad()) throw IO::Read_error(name + ": cannot read the input");
  if(chunks.size() == 1) return std::move(chunks[0]);
  std::string data;
  data.reserve(total);
  for(std::string& c : chunks) {
    data += c;
    std::string().swap(c);
  }
  return data;
}

/// opens `filename` for binary reading into `in`; `true` if it is a regular file (one with a
/// size), `false` for anything else that can be opened (a pipe, a device).
/// \throws IO::Read_error if it does not exist, is a folder or cannot be opened.
inline bool open_input_file(const std::string& filename, std::ifstream& in)
{
  struct stat st;
  if(::stat(filename.c_str(), &st) != 0) {
    const int error = errno;
    throw IO::Read_error(filename + ": cannot open the file for reading (" + std::strerror(error) + ")");
  }
  if(S_ISDIR(st.st_mode)) throw IO::Read_error(filename + ": is a folder, not a file");
  in.open(filename, std::ios::binary);
  if(!in) throw IO::Read_error(filename + ": cannot open the file for reading");
  return S_ISREG(st.st_mode);
}

/// the size of the regular file open in `in`, which is left at its start.
inline std::size_t regular_file_size(std::ifstream& in, const std::string& filename)
{
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if(size < 0) throw IO::Read_error(filename + ": cannot read the file");
  in.seekg(0, std::ios::beg);
  return static_cast<std::size_t>(size);
}

/// reads the whole file `filename`: a regular file whole, anything else that can be opened
/// (a pipe, a device) up to `limit` bytes, through `check` (see `read_bounded()`).
template <class Prefix_check = No_prefix_check>
std::string read_file_bounded(const std::string& filename, std::size_t limit,
                              const Prefix_check& check = Prefix_check())
{
  std::ifstream in;
  if(!open_input_file(filename, in)) return read_bounded(in, filename, limit, check);
  const std::size_t size = regular_file_size(in, filename);
  std::string data(size, '\0');
  if(size > 0 && !in.read(&data[0], static_cast<std::streamsize>(size))) throw IO::Read_error(filename + ": cannot read the file");
  // A file that grew while it was read is read as it was when its size was taken.
  return data;
}

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_READER_INPUT_H
