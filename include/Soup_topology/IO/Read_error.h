// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef SOUP_TOPOLOGY_IO_READ_ERROR_H
#define SOUP_TOPOLOGY_IO_READ_ERROR_H

#include <stdexcept>
#include <string>

namespace Soup_topology {
namespace IO {

/// \ingroup PkgSoupTopologyIO
/// \brief the exception thrown by the readers on a file that cannot be opened or is malformed;
/// the message starts with the file name and, where it applies, the line or facet number.
class Read_error : public std::runtime_error
{
public:
  explicit Read_error(const std::string& what) : std::runtime_error(what) {}
};

/// \ingroup PkgSoupTopologyIO
/// \brief the exception thrown by the writers when a file cannot be written (cannot be opened,
/// a failed write) or cannot represent the soup (float rounding in STL, indices too large for
/// the format). The message starts with the file name when the writer was given one.
class Write_error : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

} // namespace IO
} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_IO_READ_ERROR_H
