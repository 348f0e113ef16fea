#!/usr/bin/env python3
# Copyright (c) 2026 The Soup_topology authors.
# SPDX-License-Identifier: LGPL-3.0-or-later
#
# Writes an exploded, jittered torus as an OFF file, or as a binary STL file when OUT ends in
# `.stl`: the input of the cost targets of the gap analysis (issue 17), where every vertex is a
# border vertex, and of the command-line repair (issue 13).
#
# The torus (major radius 1, minor radius 0.4) is a grid of U x V quads, each cut into two
# triangles, listed in grid order. Every triangle gets its own three copies of its corners
# (nothing is shared), and every coordinate of every copy is moved by a uniform random amount in
# [-J, J], J = jitter x the diagonal of the torus' bounding box. 2 U V triangles, 6 U V points.
#
# Usage: exploded_torus.py OUT.off|OUT.stl [--u 1000] [--v 500] [--jitter 1e-6] [--seed 17]
#                          [--shuffle none|triangles|both]
# (the defaults give 1,000,000 triangles). `--shuffle triangles` lists the triangles in a random
# order (seeded) with the points of an OFF file still in grid order; `both` numbers the points of
# an OFF file in the order of the shuffled triangles too (a binary STL has no numbering: both
# shuffle its facets).

import argparse
import math
import random
import struct


def main():
    parser = argparse.ArgumentParser(description="exploded, jittered torus soup (OFF or binary STL)")
    parser.add_argument("out")
    parser.add_argument("--u", type=int, default=1000, help="quads around the major circle")
    parser.add_argument("--v", type=int, default=500, help="quads around the minor circle")
    parser.add_argument("--jitter", type=float, default=1e-6, help="fraction of the diagonal")
    parser.add_argument("--seed", type=int, default=17)
    parser.add_argument("--shuffle", choices=("none", "triangles", "both"), default="none",
                        help="the order of the triangles (and of the points of an OFF file)")
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
    corner_lists = []
    for i in range(u_count):
        i1 = (i + 1) % u_count
        for j in range(v_count):
            j1 = (j + 1) % v_count
            for corners in ((grid[i][j], grid[i1][j], grid[i1][j1]), (grid[i][j], grid[i1][j1], grid[i][j1])):
                corner_lists.append([tuple(c + rng.uniform(-amplitude, amplitude) for c in p) for p in corners])
    # the triangle listed k-th is order[k]: its corners are points 3 order[k] ... of the grid order
    order = list(range(len(corner_lists)))
    if args.shuffle != "none":
        random.Random(args.seed + 1).shuffle(order)
    if args.out.lower().endswith(".stl"):
        write_binary_stl(args.out, [corner_lists[t] for t in order])
    elif args.shuffle == "both":
        write_off(args.out, [corner_lists[t] for t in order], list(range(len(order))))
    else:
        write_off(args.out, corner_lists, order)


def write_off(path, corner_lists, order):
    # the points of corner_lists in their order, then the triangles in `order`
    triangles = len(corner_lists)
    lines = ["OFF", "%d %d 0" % (3 * triangles, triangles)]
    for corners in corner_lists:
        for p in corners:
            lines.append("%.17g %.17g %.17g" % p)
    for t in order:
        lines.append("3 %d %d %d" % (3 * t, 3 * t + 1, 3 * t + 2))
    with open(path, "w") as out:
        out.write("\n".join(lines))
        out.write("\n")


def write_binary_stl(path, corner_lists):
    # an 80-byte header, the triangle count, then per triangle a zero normal, the three corners
    # as 32-bit floats and a zero attribute word
    record = struct.Struct("<12fH")
    with open(path, "wb") as out:
        out.write(b"exploded torus".ljust(80, b" "))
        out.write(struct.pack("<I", len(corner_lists)))
        for corners in corner_lists:
            out.write(record.pack(0.0, 0.0, 0.0, *corners[0], *corners[1], *corners[2], 0))

if __name__ == "__main__":
    main()
