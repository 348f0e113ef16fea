// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Helpers shared by the tests: locating and decompressing the real meshes, exploding an indexed
// mesh into an STL-like soup, and an independent (slow, obviously correct) edge count.

#ifndef SOUP_TOPOLOGY_TEST_UTILITIES_H
#define SOUP_TOPOLOGY_TEST_UTILITIES_H

#include <Soup_topology/IO/read_triangle_soup.h>
#include <Soup_topology/soup_statistics.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <random>
#include <tuple>
#include <system_error>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

namespace soup_test {

/// `p` with its coordinates rounded to float, as a binary STL file holds them. Through a volatile
/// float: GCC 12.2 at -O2 (x86-64) vectorizes the round trip of two neighbouring coordinates into
/// a plain copy, which leaves them unrounded (the package's STL writer rounds the same way).
template <class Point>
Point rounded_to_float(const Point& p)
{
  volatile float x = static_cast<float>(p.x()), y = static_cast<float>(p.y()), z = static_cast<float>(p.z());
  return Point(x, y, z);
}

/// the path of a readable copy of the file `path`: `path` itself, or, if it ends in `.xz`, its
/// decompressed copy in a temporary folder shared by the test and benchmark processes, made by
/// the first process that asks for it (written under a unique name, then renamed, so that
/// processes running in parallel never read a partial copy).
inline std::string decompressed_file(const std::string& path)
{
  if(path.size() < 3 || path.compare(path.size() - 3, 3, ".xz") != 0) return path;
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "soup_topology_test_data";
  fs::create_directories(dir);
  // The name of the copy: the path below the shared data folder (or the whole path), flattened.
  const std::string data_dir = std::string(SOUP_TOPOLOGY_DATA_DIR) + "/";
  std::string flat = path.compare(0, data_dir.size(), data_dir) == 0 ? path.substr(data_dir.size()) : path;
  flat.resize(flat.size() - 3);
  for(char& c : flat) if(c == '/') c = '_';
  const fs::path out = dir / flat;
  if(!fs::exists(out)) {
    const fs::path tmp = dir / (flat + ".part" + std::to_string(std::random_device{}()));
    const std::string cmd = "xz -dc '" + path + "' > '" + tmp.string() + "'";
    if(std::system(cmd.c_str()) != 0) {
      fs::remove(tmp);
      throw std::runtime_error("cannot decompress " + path);
    }
    fs::rename(tmp, out);
  }
  return out.string();
}

/// the path of a file of the shared data folder, decompressed by `decompressed_file()` if it ends
/// in `.xz`.
inline std::string data_file(const std::string& relative)
{
  return decompressed_file(std::string(SOUP_TOPOLOGY_DATA_DIR) + "/" + relative);
}

/// The folders made by `temporary_folder()` in this process, removed with their files when the
/// process exits normally (a test that fails, or returns early, leaves nothing behind). Set the
/// environment variable `SOUP_TOPOLOGY_KEEP_TEST_FILES` to keep them, for example to look at the
/// files of a failed test. A child process (`fork()`) that exits does not remove its parent's.
class Temporary_folders
{
public:
  Temporary_folders() : owner_(getpid()) {}
  Temporary_folders(const Temporary_folders&) = delete;
  Temporary_folders& operator=(const Temporary_folders&) = delete;
  ~Temporary_folders()
  {
    if(getpid() != owner_ || std::getenv("SOUP_TOPOLOGY_KEEP_TEST_FILES") != nullptr) return;
    for(const std::filesystem::path& folder : folders_) {
      std::error_code ignored; // (a folder the test removed itself is no error)
      std::filesystem::remove_all(folder, ignored);
    }
  }

  void add(const std::filesystem::path& folder)
  {
    const std::lock_guard<std::mutex> hold(mutex_);
    folders_.push_back(folder);
  }

private:
  pid_t owner_;
  std::mutex mutex_;
  std::vector<std::filesystem::path> folders_;
};

inline Temporary_folders& temporary_folders()
{
  static Temporary_folders folders;
  return folders;
}

/// a fresh temporary folder for a test, removed when the process exits (`Temporary_folders`).
inline std::string temporary_folder(const std::string& name)
{
  namespace fs = std::filesystem;
  Temporary_folders& folders = temporary_folders();
  const fs::path dir = fs::temp_directory_path() /
                       ("soup_topology_" + name + "_" + std::to_string(std::random_device{}()));
  fs::create_directories(dir);
  folders.add(dir);
  return dir.string();
}

/// reads a mesh of the shared data folder as an exactly welded indexed soup.
template <class Point>
Soup_topology::IO::Soup_read_report read_data_mesh(const std::string& relative, std::vector<Point>& points,
                                                   std::vector<std::array<std::size_t, 3>>& triangles)
{
  return Soup_topology::IO::read_triangle_soup(data_file(relative), points, triangles);
}

/// every triangle written with its own three corners, as an STL export does.
template <class Point>
std::vector<std::array<Point, 3>> explode(const std::vector<Point>& points,
                                          const std::vector<std::array<std::size_t, 3>>& triangles)
{
  std::vector<std::array<Point, 3>> soup;
  soup.reserve(triangles.size());
  for(const auto& t : triangles) soup.push_back({points[t[0]], points[t[1]], points[t[2]]});
  return soup;
}

/// counts, with a std::map over sorted vertex pairs, the edges used by 1 triangle and by more than 2.
inline std::pair<std::size_t, std::size_t>
count_border_and_non_manifold_edges(const std::vector<std::array<std::size_t, 3>>& triangles)
{
  std::map<std::pair<std::size_t, std::size_t>, int> uses;
  for(const auto& t : triangles)
    for(int i = 0; i < 3; ++i) {
      std::size_t a = t[i], b = t[(i + 1) % 3];
      if(a > b) std::swap(a, b);
      ++uses[{a, b}];
    }
  std::size_t border = 0, non_manifold = 0;
  for(const auto& kv : uses) {
    if(kv.second == 1) ++border;
    if(kv.second > 2) ++non_manifold;
  }
  return {border, non_manifold};
}

/// counts edge-connected components with a union-find over a std::map of edges.
inline std::size_t count_components(const std::vector<std::array<std::size_t, 3>>& triangles)
{
  std::vector<std::size_t> parent(triangles.size());
  for(std::size_t i = 0; i < parent.size(); ++i) parent[i] = i;
  auto find = [&](std::size_t x) { while(parent[x] != x) x = parent[x] = parent[parent[x]]; return x; };
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> first_user;
  std::size_t count = triangles.size();
  for(std::size_t t = 0; t < triangles.size(); ++t)
    for(int i = 0; i < 3; ++i) {
      std::size_t a = triangles[t][i], b = triangles[t][(i + 1) % 3];
      if(a > b) std::swap(a, b);
      auto ins = first_user.emplace(std::make_pair(a, b), t);
      if(!ins.second) {
        const std::size_t x = find(t), y = find(ins.first->second);
        if(x != y) { parent[x] = y; --count; }
      }
    }
  return count;
}

/// every count of `s` in one comparable value: two statistics compared field by field with one
/// `EXPECT_EQ` (and printed whole when they differ)
inline auto statistics_fields(const Soup_topology::Soup_statistics& s)
{
  return std::make_tuple(s.vertices, s.triangles, s.border_edges, s.non_manifold_edges, s.non_manifold_vertices,
                         s.inconsistent_edges, s.components, s.zero_area_triangles, s.closed);
}

/// runs a shell command and returns its standard output and exit code.
inline std::pair<std::string, int> run_command(const std::string& command)
{
  std::string output;
  FILE* pipe = popen(command.c_str(), "r");
  if(pipe == nullptr) throw std::runtime_error("cannot run " + command);
  char buffer[4096];
  std::size_t n;
  while((n = fread(buffer, 1, sizeof buffer, pipe)) > 0) output.append(buffer, n);
  const int status = pclose(pipe);
  return {output, WIFEXITED(status) ? WEXITSTATUS(status) : -1};
}

/// the integer value of `"key": N` in a one-line JSON object (-1 if absent).
inline long long json_integer(const std::string& json, const std::string& key)
{
  const std::string pattern = "\"" + key + "\": ";
  const std::size_t at = json.find(pattern);
  if(at == std::string::npos) return -1;
  return std::atoll(json.c_str() + at + pattern.size());
}

/// `true`/`false` value of `"key": ...` in a one-line JSON object.
inline bool json_bool(const std::string& json, const std::string& key)
{
  const std::string pattern = "\"" + key + "\": ";
  const std::size_t at = json.find(pattern);
  return at != std::string::npos && json.compare(at + pattern.size(), 4, "true") == 0;
}

/// a mapping of this process's memory, as `/proc/self/smaps` lists it: its address range and
/// whether its `VmFlags` hold `hg` (advised for transparent huge pages).
struct Memory_mapping
{
  std::uintptr_t begin = 0, end = 0;
  bool advised_for_huge_pages = false;
};

/// the mappings of this process (empty where `/proc/self/smaps` cannot be read).
inline std::vector<Memory_mapping> memory_mappings()
{
  std::vector<Memory_mapping> mappings;
  std::ifstream smaps("/proc/self/smaps");
  for(std::string line; std::getline(smaps, line);) {
    unsigned long long begin = 0, end = 0;
    // a mapping's first line starts with its range; the lines of its fields have a colon first
    if(std::sscanf(line.c_str(), "%llx-%llx ", &begin, &end) == 2 && line.find(':') > line.find(' '))
      mappings.push_back(Memory_mapping{static_cast<std::uintptr_t>(begin), static_cast<std::uintptr_t>(end), false});
    else if(!mappings.empty() && line.rfind("VmFlags:", 0) == 0)
      mappings.back().advised_for_huge_pages = (line + " ").find(" hg ") != std::string::npos;
  }
  return mappings;
}

} // namespace soup_test

#endif // SOUP_TOPOLOGY_TEST_UTILITIES_H
