// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The text of the HTML report page: the style, the data elements and the viewer script.

#ifndef SOUP_TOPOLOGY_INTERNAL_HTML_REPORT_PAGE_H
#define SOUP_TOPOLOGY_INTERNAL_HTML_REPORT_PAGE_H

#include <Soup_topology/internal/html_report_mesh.h>

#if defined(__has_include)
#  if __has_include(<Soup_topology/internal/html_report_viewer_script.h>)
#    include <Soup_topology/internal/html_report_viewer_script.h>
#    define SOUP_TOPOLOGY_HAS_HTML_REPORT_VIEWER_SCRIPT
#  endif
#endif

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <ostream>
#include <string>
#include <vector>

namespace Soup_topology {
namespace internal {

#ifndef SOUP_TOPOLOGY_HAS_HTML_REPORT_VIEWER_SCRIPT
// The generated header is missing (the package is used without its CMake configuration).
inline constexpr bool html_report_viewer_built = false;
inline constexpr const char* html_report_viewer_script[] = {
  "document.body.insertAdjacentHTML('afterbegin', '<p class=\"not-built\">The 3D viewer was not built into "
  "this report: the header html_report_viewer_script.h was not found.</p>');\n"
  "document.body.dataset.ready = 'true';\n"};
inline constexpr const char* html_report_viewer_license[] = {""};
#endif

/// `text` with every `</` written `<\/`: the same JSON value, and no end tag inside a script element.
inline std::string html_script_safe(const std::string& text)
{
  std::string out;
  out.reserve(text.size());
  for(std::size_t i = 0; i < text.size(); ++i) {
    out += text[i];
    if(text[i] == '<' && i + 1 < text.size() && text[i + 1] == '/') out += '\\';
  }
  return out;
}

/// `text` as HTML text (`&`, `<`, `>` and `"` escaped).
inline std::string html_escape(const std::string& text)
{
  std::string out;
  for(char c : text) {
    switch(c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

/// `text` as a JSON string.
inline std::string html_json_string(const std::string& text)
{
  std::string out = "\"";
  for(char c : text) {
    if(c == '"' || c == '\\') { out += '\\'; out += c; }
    else if(static_cast<unsigned char>(c) < 0x20) {
      static const char hex[] = "0123456789abcdef";
      out += "\\u00";
      out += hex[(static_cast<unsigned char>(c) >> 4) & 0xF];
      out += hex[static_cast<unsigned char>(c) & 0xF];
    } else out += c;
  }
  return out + "\"";
}

/// the shortest text that reads back as `x`; `null` for an infinite or NaN value.
inline std::string html_json_number(double x)
{
  if(!std::isfinite(x)) return "null";
  char buffer[64];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, x).ptr;
  return std::string(buffer, end);
}

/// the shortest text that reads back as the float `x`.
inline std::string html_json_float(float x)
{
  if(!std::isfinite(x)) return "null";
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, x).ptr;
  return std::string(buffer, end);
}

/// the bytes of `values` (little-endian on the machines that run the viewer) in base64.
template <class T>
std::string html_base64(const std::vector<T>& values)
{
  static const char alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* bytes = reinterpret_cast<const unsigned char*>(values.data());
  const std::size_t n = values.size() * sizeof(T);
  std::string out;
  out.reserve(4 * ((n + 2) / 3));
  std::size_t i = 0;
  for(; i + 2 < n; i += 3) {
    const std::uint32_t w = (std::uint32_t(bytes[i]) << 16) | (std::uint32_t(bytes[i + 1]) << 8) | bytes[i + 2];
    out += alphabet[(w >> 18) & 63]; out += alphabet[(w >> 12) & 63];
    out += alphabet[(w >> 6) & 63]; out += alphabet[w & 63];
  }
  if(i + 1 == n) {
    const std::uint32_t w = std::uint32_t(bytes[i]) << 16;
    out += alphabet[(w >> 18) & 63]; out += alphabet[(w >> 12) & 63]; out += "==";
  } else if(i + 2 == n) {
    const std::uint32_t w = (std::uint32_t(bytes[i]) << 16) | (std::uint32_t(bytes[i + 1]) << 8);
    out += alphabet[(w >> 18) & 63]; out += alphabet[(w >> 12) & 63]; out += alphabet[(w >> 6) & 63]; out += '=';
  }
  return out;
}

inline const char* html_report_style()
{
  return "html,body{margin:0;height:100%;background:#22262b;color:#dde3ea;font:13px/1.4 sans-serif}"
         "body{display:flex}"
         "#panel{width:360px;flex:none;overflow-y:auto;padding:8px 12px;box-sizing:border-box;background:#2b3036}"
         "#view{flex:1;min-width:0;height:100%;display:block}"
         "h1{font-size:15px;margin:4px 0 8px;word-break:break-all}h2{font-size:13px;margin:14px 0 4px;color:#9fc3e6}"
         "table{border-collapse:collapse;width:100%}td,th{padding:1px 6px;text-align:right;border-bottom:1px solid #3a4148}"
         "td:first-child,th:first-child{text-align:left}"
         ".note{color:#9aa5b1;font-size:12px}.not-built{padding:12px;background:#444;color:#fff}"
         ".marker-kind{display:block}.swatch{display:inline-block;width:10px;height:10px;margin:0 6px}"
         "ol.problems{padding-left:22px;margin:0}ol.problems li{cursor:pointer}ol.problems li:hover{color:#fff;text-decoration:underline}";
}

} // namespace internal
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INTERNAL_HTML_REPORT_PAGE_H
