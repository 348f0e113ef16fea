// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The version of the package. The build reads its project version from this file, so the two
// cannot disagree.

#ifndef SOUP_TOPOLOGY_VERSION_H
#define SOUP_TOPOLOGY_VERSION_H

/// \ingroup PkgSoupTopologyRef
/// the major version: incremented on incompatible changes of the interface.
#define SOUP_TOPOLOGY_VERSION_MAJOR 0
/// \ingroup PkgSoupTopologyRef
/// the minor version: incremented when functionality is added compatibly.
#define SOUP_TOPOLOGY_VERSION_MINOR 1
/// \ingroup PkgSoupTopologyRef
/// the patch version: incremented on compatible fixes.
#define SOUP_TOPOLOGY_VERSION_PATCH 0
/// \ingroup PkgSoupTopologyRef
/// the version as a string, "MAJOR.MINOR.PATCH".
#define SOUP_TOPOLOGY_VERSION "0.1.0"

#endif // SOUP_TOPOLOGY_VERSION_H
