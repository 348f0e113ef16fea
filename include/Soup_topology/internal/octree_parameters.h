// Copyright (c) 2024 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The octree's named parameters are declared with the others in `Soup_topology/parameters.h`.

#ifndef SOUP_TOPOLOGY_INTERNAL_OCTREE_PARAMETERS_H
#define SOUP_TOPOLOGY_INTERNAL_OCTREE_PARAMETERS_H

#include <Soup_topology/parameters.h>

#endif // SOUP_TOPOLOGY_INTERNAL_OCTREE_PARAMETERS_H
