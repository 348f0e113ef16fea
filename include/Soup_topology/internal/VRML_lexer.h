// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// This file is part of Soup_topology, a header-only C++17 library that rebuilds the topology
// of triangle soups.

// The tokens of VRML 2.0 text (words, numbers, brackets, strings, comments), with line numbers
// for the messages; the base of the parser in internal/VRML_parser.h.

#ifndef SOUP_TOPOLOGY_INTERNAL_VRML_LEXER_H
#define SOUP_TOPOLOGY_INTERNAL_VRML_LEXER_H

#include <Soup_topology/IO/Read_error.h>

#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

namespace Soup_topology {
namespace internal {
namespace VRML {

inline bool is_delimiter(char c)
{
  return static_cast<unsigned char>(c) <= ' ' || c == ',' || c == '#' || c == '{' || c == '}'
      || c == '[' || c == ']' || c == '"';
}

inline bool starts_number(char c)
{
  return (c >= '0' && c <= '9') || c == '-' || c == '+' || c == '.';
}

class Lexer
{
protected:
  using Read_error = Soup_topology::IO::Read_error;

  Lexer(const char* begin, const char* end, const std::string& name) : p_(begin), end_(end), name_(name) {}

  // ------------------------------------------------------------------ errors

  [[noreturn]] void fail(const std::string& description, std::size_t line) const
  {
    throw Read_error(name_ + ":" + std::to_string(line) + ": " + printable(description));
  }

  // the bytes of the file quoted in a message, with control and non-ASCII bytes as \xNN
  static std::string printable(const std::string& text)
  {
    static const char* const hex = "0123456789abcdef";
    std::string r;
    for(const char ch : text)
    {
      const unsigned char c = static_cast<unsigned char>(ch);
      if(c < 0x20 || c >= 0x7F)
      {
        r += "\\x";
        r += hex[c >> 4];
        r += hex[c & 15];
      }
      else
        r += ch;
    }
    return r;
  }

  [[noreturn]] void fail_eof(const char* what, std::size_t open_line) const
  {
    std::string d = std::string("unexpected end of file while reading ") + what;
    if(open_line != 0)
      d += " (opened at line " + std::to_string(open_line) + ")";
    fail(d, line_);
  }

  std::string quote_here() const
  {
    if(p_ == end_)
      return "end of file";
    const char* q = p_;
    if(is_delimiter(*q))
      return std::string("'") + *q + "'";
    while(q != end_ && !is_delimiter(*q) && q - p_ < 40)
      ++q;
    return "'" + std::string(p_, q) + "'";
  }

  // ------------------------------------------------------------------ tokens

  void read_header()
  {
    if(end_ - p_ >= 2 && static_cast<unsigned char>(p_[0]) == 0x1F && static_cast<unsigned char>(p_[1]) == 0x8B)
      fail("the file is gzip-compressed (a .wrl or .wrz file often is): decompress it first, e.g. "
           "'gunzip -c file.wrl > plain.wrl', and read the result",
           1);
    if(end_ - p_ >= 3 && std::memcmp(p_, "\xEF\xBB\xBF", 3) == 0) // UTF-8 byte order mark
      p_ += 3;
    if(end_ - p_ >= 5 && std::memcmp(p_, "#VRML", 5) == 0)
    {
      const char* q = p_ + 5;
      while(q != end_ && (*q == ' ' || *q == '\t'))
        ++q;
      if(!(end_ - q >= 4 && std::memcmp(q, "V2.0", 4) == 0))
        fail("unsupported VRML version (only VRML 2.0 / VRML97 is read)", 1);
    }
  }

  void skip_space()
  {
    while(p_ != end_)
    {
      const char c = *p_;
      if(c == '\n')
      {
        ++line_;
        ++p_;
      }
      else if(c == ' ' || c == '\t' || c == '\r' || c == ',')
        ++p_;
      else if(static_cast<unsigned char>(c) < ' ' || c == '\x7F')
        fail_control_byte(c);
      else if(c == '#')
      {
        while(p_ != end_ && *p_ != '\n')
          ++p_;
      }
      else
        return;
    }
  }

  [[noreturn]] void fail_control_byte(char c) const
  {
    fail("control byte " + printable(std::string(1, c))
           + " outside comments and strings: not VRML text (a binary or damaged file?)",
         line_);
  }

  // next non-space character, 0 at the end
  char peek()
  {
    skip_space();
    return p_ == end_ ? '\0' : *p_;
  }

  std::string_view read_word(const char* what, std::size_t open_line = 0)
  {
    skip_space();
    if(p_ == end_)
      fail_eof(what, open_line);
    const char* b = p_;
    while(p_ != end_ && !is_delimiter(*p_))
      ++p_;
    if(p_ == b)
      fail(std::string("expected ") + what + ", found " + quote_here(), line_);
    return std::string_view(b, static_cast<std::size_t>(p_ - b));
  }

  // the next word, not consumed (empty if the next token is not a word)
  std::string_view peek_word()
  {
    skip_space();
    const char* q = p_;
    while(q != end_ && !is_delimiter(*q))
      ++q;
    return std::string_view(p_, static_cast<std::size_t>(q - p_));
  }

  void expect(char c, const char* what, std::size_t open_line)
  {
    skip_space();
    if(p_ == end_)
      fail_eof(what, open_line);
    if(*p_ != c)
      fail(std::string("expected '") + c + "' in " + what + ", found " + quote_here(), line_);
    ++p_;
  }

  void skip_string()
  {
    const std::size_t open_line = line_;
    ++p_; // opening quote
    while(p_ != end_ && *p_ != '"')
    {
      if(*p_ == '\\' && p_ + 1 != end_)
        ++p_;
      if(*p_ == '\n')
        ++line_;
      ++p_;
    }
    if(p_ == end_)
      fail_eof("a string", open_line);
    ++p_;
  }

  double read_double(const char* what)
  {
    skip_space();
    if(p_ == end_)
      fail_eof(what, 0);
    const char* b = p_;
    if(*b == '+')
      ++b;
    double v = 0;
    const auto r = std::from_chars(b, end_, v);
    if(r.ec == std::errc::result_out_of_range && (r.ptr == end_ || is_delimiter(*r.ptr)))
      fail(std::string("number out of the range of a double (") + what + "): " + quote_here(), line_);
    if(r.ec != std::errc() || (r.ptr != end_ && !is_delimiter(*r.ptr)) || !std::isfinite(v))
      fail(std::string("cannot read a number (") + what + ") from " + quote_here(), line_);
    p_ = r.ptr;
    return v;
  }

  std::int32_t read_int32(const char* what)
  {
    skip_space();
    if(p_ == end_)
      fail_eof(what, 0);
    const char* b = p_;
    bool negative = false;
    if(*b == '+' || *b == '-')
    {
      negative = (*b == '-');
      ++b;
    }
    int base = 10;
    if(end_ - b > 2 && b[0] == '0' && (b[1] == 'x' || b[1] == 'X'))
    {
      base = 16;
      b += 2;
    }
    std::int64_t v = 0;
    const auto r = std::from_chars(b, end_, v, base);
    if(r.ec != std::errc() || (r.ptr != end_ && !is_delimiter(*r.ptr)))
      fail(std::string("cannot read an integer (") + what + ") from " + quote_here(), line_);
    if(negative)
      v = -v;
    if(v < std::numeric_limits<std::int32_t>::min() || v > std::numeric_limits<std::int32_t>::max())
      fail(std::string("integer out of the 32-bit range (") + what + "): " + quote_here(), line_);
    p_ = r.ptr;
    return static_cast<std::int32_t>(v);
  }

  bool read_bool(const char* what)
  {
    skip_space();
    const std::size_t line = line_;
    const std::string_view w = read_word(what);
    if(w == "TRUE")
      return true;
    if(w == "FALSE")
      return false;
    fail(std::string("expected TRUE or FALSE for ") + what + ", found '" + std::string(w) + "'", line);
  }

  // inside a list of numbers opened at `open_line`: a bracket here is an error
  void check_list_item(std::size_t open_line) const
  {
    const char c = *p_;
    if(c == '{' || c == '}' || c == '[')
      fail(std::string("unbalanced '") + c + "' in a list of numbers ('[' opened at line "
             + std::to_string(open_line) + ")",
           line_);
  }

  // reads the bracketed value `[ item ... ]` of a multiple-valued field if one starts here:
  // `read_item(open_line)` reads each item, `open_line` being the line of the `[`. Returns that
  // line, or 0 (and reads nothing) when the value is not bracketed.
  template <typename ItemReader>
  std::size_t read_bracketed_list(const char* what, const ItemReader& read_item)
  {
    skip_space();
    if(p_ == end_ || *p_ != '[')
      return 0;
    const std::size_t open_line = line_;
    ++p_;
    for(;;)
    {
      skip_space();
      if(p_ == end_)
        fail_eof(what, open_line);
      if(*p_ == ']')
      {
        ++p_;
        return open_line;
      }
      read_item(open_line);
    }
  }

  // reads an MFFloat-like field of `tuple`-sized values: `[ a b c, ... ]` or a single value
  void read_mf_double(std::vector<double>& out, std::size_t tuple, const char* what)
  {
    const std::size_t start = out.size();
    const std::size_t open_line = read_bracketed_list(what, [&](std::size_t list_line) {
      check_list_item(list_line);
      out.push_back(read_double(what));
    });
    if(open_line == 0)
    {
      for(std::size_t i = 0; i < tuple; ++i)
        out.push_back(read_double(what));
    }
    else if((out.size() - start) % tuple != 0)
      fail(std::string(what) + ": " + std::to_string(out.size() - start)
             + " numbers, not a multiple of " + std::to_string(tuple),
           open_line);
  }

  void read_sf_doubles(double* out, std::size_t n, const char* what)
  {
    for(std::size_t i = 0; i < n; ++i)
      out[i] = read_double(what);
  }

  const char* p_;
  const char* end_;
  const std::string& name_;
  std::size_t line_ = 1;
};

} // namespace VRML
} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_VRML_LEXER_H
