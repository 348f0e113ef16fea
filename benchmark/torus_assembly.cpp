// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Writes an assembly of exploded, jittered tori as binary STL files, one torus a file, streamed
// (memory does not grow with the size): the input of the scale experiment of the tiled repair
// (scripts/run_scale_experiment.sh, doc/Soup_topology/Tiled_repair.md).
//
// Each torus is the one of exploded_torus.py (major radius 1, minor radius 0.4, a grid of U x V
// quads cut into two triangles each, every triangle with its own copies of its corners, each
// coordinate moved by a uniform amount in [-J, J], J = jitter x the diagonal of the torus' box),
// the k-th moved by 3 k along x, so that the parts do not touch.
//
// Usage: torus_assembly FOLDER PARTS U V [JITTER] [SEED]
// writes FOLDER/part_0.stl ... FOLDER/part_{PARTS-1}.stl, 2 U V triangles each.

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <random>
#include <string>
#include <vector>

namespace {

struct Point
{
  double x, y, z;
};

void write_part(const std::string& file, unsigned part, unsigned u_count, unsigned v_count, double jitter,
                std::uint64_t seed)
{
  const double major = 1, minor = 0.4, pi = std::acos(-1.0);
  const double diagonal = std::sqrt(2 * std::pow(2 * (major + minor), 2) + std::pow(2 * minor, 2));
  const double amplitude = jitter * diagonal, shift = 3.0 * part;
  std::mt19937_64 random(seed + part);
  std::uniform_real_distribution<double> move(-amplitude, amplitude);
  const auto grid = [&](unsigned i, unsigned j) {
    const double a = 2 * pi * (i % u_count) / u_count, b = 2 * pi * (j % v_count) / v_count;
    const double w = major + minor * std::cos(b);
    return Point{w * std::cos(a) + shift, w * std::sin(a), minor * std::sin(b)};
  };
  std::ofstream out(file, std::ios::binary);
  char header[80];
  std::memset(header, ' ', sizeof header);
  std::memcpy(header, "torus assembly part", 19);
  out.write(header, sizeof header);
  const std::uint32_t triangles = 2u * u_count * v_count;
  out.write(reinterpret_cast<const char*>(&triangles), 4);
  std::vector<char> buffer;
  buffer.reserve(50 * 65536);
  const auto emit = [&](const Point& p, const Point& q, const Point& r) {
    float record[12] = {0, 0, 0};
    const Point* corners[3] = {&p, &q, &r};
    for(int k = 0; k < 3; ++k) {
      record[3 + 3 * k] = static_cast<float>(corners[k]->x + move(random));
      record[4 + 3 * k] = static_cast<float>(corners[k]->y + move(random));
      record[5 + 3 * k] = static_cast<float>(corners[k]->z + move(random));
    }
    const char* bytes = reinterpret_cast<const char*>(record);
    buffer.insert(buffer.end(), bytes, bytes + 48);
    buffer.push_back(0);
    buffer.push_back(0);
    if(buffer.size() >= 50 * 65536) {
      out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
      buffer.clear();
    }
  };
  for(unsigned i = 0; i < u_count; ++i)
    for(unsigned j = 0; j < v_count; ++j) {
      const Point a = grid(i, j), b = grid(i + 1, j), c = grid(i + 1, j + 1), d = grid(i, j + 1);
      emit(a, b, c);
      emit(a, c, d);
    }
  out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
  if(!out.flush()) throw std::runtime_error(file + ": write failed");
}

} // namespace

int main(int argc, char** argv)
{
  if(argc < 5) {
    std::cerr << "usage: torus_assembly FOLDER PARTS U V [JITTER (1e-6)] [SEED (17)]\n";
    return 2;
  }
  const std::string folder = argv[1];
  const unsigned parts = static_cast<unsigned>(std::strtoul(argv[2], nullptr, 10));
  const unsigned u = static_cast<unsigned>(std::strtoul(argv[3], nullptr, 10));
  const unsigned v = static_cast<unsigned>(std::strtoul(argv[4], nullptr, 10));
  const double jitter = argc > 5 ? std::strtod(argv[5], nullptr) : 1e-6;
  const std::uint64_t seed = argc > 6 ? std::strtoull(argv[6], nullptr, 10) : 17;
  if(parts == 0 || u < 3 || v < 3 || 2.0 * u * v > 4e9) {
    std::cerr << "torus_assembly: PARTS >= 1, U and V >= 3, 2 U V < 4e9\n";
    return 2;
  }
  try {
    for(unsigned k = 0; k < parts; ++k) write_part(folder + "/part_" + std::to_string(k) + ".stl", k, u, v, jitter, seed);
  } catch(const std::exception& e) {
    std::cerr << "torus_assembly: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
