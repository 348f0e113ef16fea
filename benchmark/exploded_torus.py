#!/usr/bin/env python3
# Copyright (c) 2026 The Soup_topology authors.
# SPDX-License-Identifier: LGPL-3.0-or-later
#
# Writes an exploded, jittered torus as an OFF file: the input of the cost targets of the gap
# analysis (issue 17), where every vertex is a border vertex.
#
# The torus (major radius 1, minor radius 0.4) is a grid of U x V quads, each cut into two
# triangles, listed in grid order. Every triangle gets its own three copies of its corners
# (nothing is shared), and every coordinate of every copy is moved by a uniform random amount in
# [-J, J], J = jitter x the diagonal of the torus' bounding box. 2 U V triangles, 6 U V points.
#
# Usage: exploded_torus.py OUT.off [--u 1000] [--v 500] [--jitter 1e-6] [--seed 17]
# (the defaults give 1,000,000 triangles).

import argparse
import math
import random


def main():
    parser = argparse.ArgumentParser(description="exploded, jittered torus soup (OFF)")
    parser.add_argument("out")
    parser.add_argument("--u", type=int, default=1000, help="quads around the major circle")
    parser.add_argument("--v", type=int, default=500, help="quads around the minor circle")
    parser.add_argument("--jitter", type=float, default=1e-6, help="fraction of the diagonal")
    parser.add_argument("--seed", type=int, default=17)
    args = parser.parse_args()

    major, minor = 1.0, 0.4
    u_count, v_count = args.u, args.v
    grid = []
    for i in range(u_count):
        a = 2 * math.pi * i / u_count
        row = []
        for j in range(v_count):
            b = 2 * math.pi * j / v_count
            w = major + minor * math.cos(b)
            row.append((w * math.cos(a), w * math.sin(a), minor * math.sin(b)))
        grid.append(row)
    # the bounding box of the torus: [-(R+r), R+r]^2 x [-r, r]
    diagonal = math.sqrt(2 * (2 * (major + minor)) ** 2 + (2 * minor) ** 2)
    amplitude = args.jitter * diagonal
    rng = random.Random(args.seed)

    triangles = 2 * u_count * v_count
    lines = ["OFF", "%d %d 0" % (3 * triangles, triangles)]
    for i in range(u_count):
        i1 = (i + 1) % u_count
        for j in range(v_count):
            j1 = (j + 1) % v_count
            for corners in ((grid[i][j], grid[i1][j], grid[i1][j1]), (grid[i][j], grid[i1][j1], grid[i][j1])):
                for p in corners:
                    lines.append("%.17g %.17g %.17g" % tuple(c + rng.uniform(-amplitude, amplitude) for c in p))
    for t in range(triangles):
        lines.append("3 %d %d %d" % (3 * t, 3 * t + 1, 3 * t + 2))
    with open(args.out, "w") as out:
        out.write("\n".join(lines))
        out.write("\n")


if __name__ == "__main__":
    main()
