// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later

#ifndef SOUP_TOPOLOGY_INVALID_INPUT_H
#define SOUP_TOPOLOGY_INVALID_INPUT_H

#include <stdexcept>
#include <string>

namespace Soup_topology {

/// \ingroup PkgSoupTopologyRef
/// \brief the exception thrown by every function of the package on invalid input: an index out
/// of range, a face that is not a triangle, a repeated index in a face, a non-finite coordinate,
/// a negative or non-finite tolerance, adjacency tables that do not match the soup, a result
/// that would exceed 32-bit indices. It derives from `std::invalid_argument`, so code catching
/// the standard type catches it too. The message names the offending face, point or parameter.
/// When it is thrown, the caller's containers are left as they were.
class Invalid_input : public std::invalid_argument
{
public:
  /// \param what the message: the function and the offending face, point or parameter
  explicit Invalid_input(const std::string& what) : std::invalid_argument(what) {}
};

} // namespace Soup_topology

#endif // SOUP_TOPOLOGY_INVALID_INPUT_H
