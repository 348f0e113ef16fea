// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// Tests of orient_triangle_soup() and triangle_soup_to_face_graph(): orientation policies,
// independence of the input order, non-manifold separation, the linear FaceGraph construction
// (compared with CGAL's polygon_soup_to_polygon_mesh), kernel conversion, refused input.

#include <Soup_topology/IO/read_triangle_soup.h>
#include <Soup_topology/orient_triangle_soup.h>
#include <Soup_topology/internal/orient_soup_in_parts.h>
#include <Soup_topology/soup_statistics.h>
#include <Soup_topology/parameters.h>
#include <Soup_topology/reconstruct_topology.h>
#include <Soup_topology/snap_vertices.h>
#include <Soup_topology/split_t_junctions.h>
#include <Soup_topology/triangle_soup_to_face_graph.h>

#include "soup_generators.h"
#include "test_utilities.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <ctime>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <utility>
#include <vector>

// The names of this file live in a namespace of its own: test/CMakeLists.txt compiles several
// test files as one translation unit.
namespace orient_triangle_soup_test {

namespace {

namespace ST = Soup_topology;
namespace PMP = CGAL::Polygon_mesh_processing;
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;
using Point = Epick::Point_3;
using Triangle = std::array<std::size_t, 3>;
using Mesh = CGAL::Surface_mesh<Point>;

struct Soup
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  std::map<std::array<double, 3>, std::size_t> index; // welds equal coordinates while building

  std::size_t point(double x, double y, double z)
  {
    const auto [it, inserted] = index.insert({{x, y, z}, points.size()});
    if(inserted) points.emplace_back(x, y, z);
    return it->second;
  }
  // An axis-aligned cube [o, o + s]^3, outward unless `inward`; `flip_one` reverses its first triangle.
  void add_cube(double ox, double oy, double oz, double s, bool inward = false, bool flip_one = false)
  {
    std::size_t v[8];
    for(int k = 0; k < 8; ++k) v[k] = point(ox + s * (k == 1 || k == 2 || k == 5 || k == 6), oy + s * (k == 2 || k == 3 || k == 6 || k == 7), oz + s * (k >= 4));
    const int faces[12][3] = {{0, 2, 1}, {0, 3, 2}, {4, 5, 6}, {4, 6, 7}, {0, 1, 5}, {0, 5, 4},
                              {3, 7, 6}, {3, 6, 2}, {0, 4, 7}, {0, 7, 3}, {1, 2, 6}, {1, 6, 5}};
    for(int f = 0; f < 12; ++f) {
      Triangle t = {v[faces[f][0]], v[faces[f][1]], v[faces[f][2]]};
      if(inward != (flip_one && f == 0)) std::swap(t[1], t[2]);
      triangles.push_back(t);
    }
  }
  // A Moebius strip of n quads (2 n triangles) around (cx, cy, 0).
  void add_moebius(double cx, double cy, int n)
  {
    std::vector<std::array<std::size_t, 2>> rung(static_cast<std::size_t>(n));
    const double pi = 3.14159265358979323846;
    for(int i = 0; i < n; ++i) {
      const double a = 2 * pi * i / n, h = a / 2;
      for(int side = 0; side < 2; ++side) {
        const double w = side ? 0.3 : -0.3;
        const double r = 2 + w * std::cos(h);
        rung[std::size_t(i)][std::size_t(side)] = point(cx + r * std::cos(a), cy + r * std::sin(a), w * std::sin(h));
      }
    }
    for(int i = 0; i < n; ++i) {
      const auto& p = rung[std::size_t(i)];
      // The last rung meets the first one upside down: the half twist.
      const std::array<std::size_t, 2> q = i + 1 < n ? rung[std::size_t(i + 1)] : std::array<std::size_t, 2>{rung[0][1], rung[0][0]};
      triangles.push_back({p[0], p[1], q[0]});
      triangles.push_back({p[1], q[1], q[0]});
    }
  }
};

// A soup with every kind of decision: two cubes sharing an edge, a book of three pages, two
// triangles meeting at one vertex, a Moebius strip, a triangle repeated in both orientations,
// an open sheet with one triangle reversed.
Soup hostile_soup()
{
  Soup s;
  s.add_cube(0, 0, 0, 1);
  s.add_cube(1, 1, 0, 1);
  const std::size_t a = s.point(10, 0, 0), b = s.point(10, 0, 1);
  s.triangles.push_back({a, b, s.point(11, 0, 0)});
  s.triangles.push_back({b, a, s.point(10, 1, 0)});
  s.triangles.push_back({a, b, s.point(9, -1, 0)});
  const std::size_t c = s.point(20, 0, 0);
  s.triangles.push_back({c, s.point(21, 0, 0), s.point(21, 1, 0)});
  s.triangles.push_back({c, s.point(19, 0, 0), s.point(19, -1, 0.5)});
  s.add_moebius(30, 0, 12);
  const std::size_t d = s.point(40, 0, 0), e = s.point(41, 0, 0), f = s.point(40, 1, 0);
  s.triangles.push_back({d, e, f});
  s.triangles.push_back({d, f, e});
  const std::size_t g = s.point(50, 0, 0), h = s.point(51, 0, 0), i = s.point(51, 1, 0), j = s.point(50, 1, 0),
                    k = s.point(52, 1, 0);
  s.triangles.push_back({g, h, i});
  s.triangles.push_back({g, i, j});
  s.triangles.push_back({h, i, k}); // reversed against its neighbour
  return s;
}

// The oriented triangles as a set, each rotated to start at its smallest index.
std::set<Triangle> oriented_set(const std::vector<Triangle>& triangles)
{
  std::set<Triangle> result;
  for(Triangle t : triangles) {
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    result.insert(t);
  }
  return result;
}

// The soup up to relabelling of its points: every triangle by the coordinates of its corners
// (rotated to start at the smallest), and every point by the corners it is the point of.
using Coordinates = std::array<double, 3>;
using Triangle_key = std::array<Coordinates, 3>;
std::pair<std::vector<Triangle_key>, std::vector<std::vector<std::pair<Triangle_key, int>>>>
relabelling_invariant(const std::vector<Point>& points, const std::vector<Triangle>& triangles)
{
  std::vector<Triangle_key> keys;
  std::vector<std::vector<std::pair<Triangle_key, int>>> corners_of(points.size());
  std::vector<Triangle_key> tri_keys;
  for(const Triangle& t : triangles) {
    Triangle_key k;
    for(int i = 0; i < 3; ++i) k[std::size_t(i)] = {points[t[std::size_t(i)]].x(), points[t[std::size_t(i)]].y(), points[t[std::size_t(i)]].z()};
    const int r = int(std::min_element(k.begin(), k.end()) - k.begin());
    std::rotate(k.begin(), k.begin() + r, k.end());
    keys.push_back(k);
    for(int i = 0; i < 3; ++i) corners_of[t[std::size_t((i + r) % 3)]].push_back({k, i});
  }
  for(auto& c : corners_of) std::sort(c.begin(), c.end());
  std::sort(keys.begin(), keys.end());
  std::sort(corners_of.begin(), corners_of.end());
  return {keys, corners_of};
}

// A face graph flattened: points in vertex order, faces in face order as vertex numbers from
// halfedge(f), and which vertices are on the border.
struct Flat_mesh
{
  std::vector<Coordinates> points;
  std::vector<std::vector<std::size_t>> faces;
  std::vector<bool> border;
  bool operator==(const Flat_mesh& o) const { return points == o.points && faces == o.faces && border == o.border; }
};

template <class PolygonMesh>
Flat_mesh flatten(const PolygonMesh& mesh)
{
  Flat_mesh flat;
  std::map<typename boost::graph_traits<PolygonMesh>::vertex_descriptor, std::size_t> number;
  for(auto v : vertices(mesh)) {
    number.insert({v, number.size()});
    const auto& p = get(CGAL::vertex_point, mesh, v);
    flat.points.push_back({CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())});
    flat.border.push_back(static_cast<bool>(is_border(v, mesh)));
  }
  for(auto f : faces(mesh)) {
    std::vector<std::size_t> face;
    for(auto v : vertices_around_face(halfedge(f, mesh), mesh)) face.push_back(number.at(v));
    flat.faces.push_back(face);
  }
  return flat;
}

// What CGAL builds from the same oriented soup.
// (A mesh with an isolated vertex is not valid for CGAL: `expect_valid` is false then.)
template <class PolygonMesh>
Flat_mesh cgal_reference(std::vector<Point> points, std::vector<Triangle> triangles, bool expect_valid)
{
  ST::orient_triangle_soup(points, triangles);
  std::vector<std::vector<std::size_t>> polygons;
  for(const Triangle& t : triangles) polygons.push_back({t[0], t[1], t[2]});
  EXPECT_TRUE(PMP::is_polygon_soup_a_polygon_mesh(polygons));
  PolygonMesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  EXPECT_EQ(CGAL::is_valid_polygon_mesh(mesh), expect_valid);
  return flatten(mesh);
}

// Six times the signed volume of the triangles whose corners are all in [first, last).
double signed_volume(const std::vector<Point>& points, const std::vector<Triangle>& triangles, std::size_t first, std::size_t last)
{
  double v = 0;
  for(const Triangle& t : triangles) {
    if(t[0] < first || t[0] >= last) continue;
    v += CGAL::to_double(CGAL::determinant(points[t[0]] - CGAL::ORIGIN, points[t[1]] - CGAL::ORIGIN, points[t[2]] - CGAL::ORIGIN));
  }
  return v;
}

double cpu_seconds_since(std::clock_t start) { return double(std::clock() - start) / CLOCKS_PER_SEC; }

// ---------------------------------------------------------------------------------------------
// Orientation policies

TEST(OrientTriangleSoup, Issue20CPRadialStillBoundsAVolume)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  ST::IO::read_triangle_soup(std::string(SOUP_TOPOLOGY_DATA_DIR) + "/cad/kicad/CP_Radial_D10.0mm_P5.00mm.wrl", points, triangles);
  {
    Mesh mesh;
    const ST::Reconstruction_report r = ST::reconstruct_topology(points, triangles, mesh);
    ASSERT_TRUE(CGAL::is_valid_polygon_mesh(mesh));
    ASSERT_TRUE(CGAL::is_closed(mesh));
    EXPECT_TRUE(PMP::does_bound_a_volume(mesh));
    EXPECT_EQ(r.orientation_flips, 0u);
  }
  ST::reconstruct_topology(points, triangles);
  for(ST::Orientation_policy policy : {ST::Orientation_policy::BOUND_VOLUME, ST::Orientation_policy::KEEP_INPUT}) {
    Mesh mesh;
    const ST::Face_graph_output_report r =
      ST::triangle_soup_to_face_graph(points, triangles, mesh, ST::parameters::orientation_policy(policy));
    EXPECT_TRUE(PMP::does_bound_a_volume(mesh)) << int(policy);
    EXPECT_EQ(r.orientation_flips, 0u);
  }
  // OUTWARD turns the inner shell (138 faces) outward: no longer a volume, as documented.
  Mesh outward;
  const ST::Face_graph_output_report r = ST::triangle_soup_to_face_graph(
    points, triangles, outward, ST::parameters::orientation_policy(ST::Orientation_policy::OUTWARD));
  EXPECT_EQ(r.orientation_flips, 138u);
  EXPECT_FALSE(PMP::does_bound_a_volume(outward));
  EXPECT_TRUE(PMP::is_outward_oriented(outward));
}

TEST(OrientTriangleSoup, Issue20NormalDirectionsBadIsOrientedInPlace)
{
  std::vector<Point> points, good_points;
  std::vector<Triangle> triangles, good;
  soup_test::read_data_mesh("real_defects/admesh/block/normal-directions-bad.stl", points, triangles);
  soup_test::read_data_mesh("real_defects/admesh/block/normal-directions-good.stl", good_points, good);
  ST::reconstruct_topology(points, triangles);
  ASSERT_EQ(ST::Adjacency_tables(triangles, points.size()).inconsistently_oriented_edges().size(), 3u);
  const std::size_t n = points.size();
  const ST::Orientation_report r = ST::orient_triangle_soup(points, triangles);
  EXPECT_GT(r.orientation_flips, 0u);
  EXPECT_EQ(points.size(), n);
  const ST::Adjacency_tables after(triangles, points.size());
  EXPECT_TRUE(after.inconsistently_oriented_edges().empty());
  EXPECT_TRUE(after.is_closed());
  // A closed block: outward by the default policy, the volume of the good file (which
  // triangulates and orients the block differently).
  const double volume = signed_volume(points, triangles, 0, points.size());
  EXPECT_GT(volume, 0);
  EXPECT_NEAR(volume, std::abs(signed_volume(good_points, good, 0, good_points.size())), 1e-9 * volume);
}

TEST(OrientTriangleSoup, PoliciesOnNestedAndInsideOutCubes)
{
  // Cube 0 outward; cube 1 inside it, inward but with one triangle reversed; cube 2 alone,
  // consistently inside out.
  Soup s;
  s.add_cube(0, 0, 0, 10);
  s.add_cube(4, 4, 4, 1, true, true);
  s.add_cube(20, 0, 0, 1, true);
  auto volumes = [&](ST::Orientation_policy policy) {
    std::vector<Point> p = s.points;
    std::vector<Triangle> t = s.triangles;
    ST::orient_triangle_soup(p, t, ST::parameters::orientation_policy(policy));
    EXPECT_EQ(p.size(), s.points.size());
    return std::array<double, 3>{signed_volume(p, t, 0, 8), signed_volume(p, t, 8, 16), signed_volume(p, t, 16, 24)};
  };
  const std::array<double, 3> bound = volumes(ST::Orientation_policy::BOUND_VOLUME);
  EXPECT_GT(bound[0], 0);
  EXPECT_LT(bound[1], 0);
  EXPECT_GT(bound[2], 0);
  const std::array<double, 3> keep = volumes(ST::Orientation_policy::KEEP_INPUT);
  EXPECT_GT(keep[0], 0);
  EXPECT_LT(keep[1], 0);
  EXPECT_LT(keep[2], 0);
  const std::array<double, 3> outward = volumes(ST::Orientation_policy::OUTWARD);
  EXPECT_GT(outward[0], 0);
  EXPECT_GT(outward[1], 0);
  EXPECT_GT(outward[2], 0);
  // The default is BOUND_VOLUME, through both entry points.
  std::vector<Point> p = s.points;
  std::vector<Triangle> t = s.triangles;
  ST::orient_triangle_soup(p, t);
  EXPECT_LT(signed_volume(p, t, 8, 16), 0);
  EXPECT_GT(signed_volume(p, t, 16, 24), 0);
  Mesh mesh;
  ST::triangle_soup_to_face_graph(s.points, s.triangles, mesh);
  EXPECT_EQ(num_faces(mesh), 36u);
  EXPECT_TRUE(PMP::does_bound_a_volume(mesh));
}

TEST(OrientTriangleSoup, PigKeepsItsTriangles)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  soup_test::read_data_mesh("cgal_repair/pig.stl.xz", points, triangles);
  ST::reconstruct_topology(points, triangles, CGAL::parameters::snapping_tolerance(0.3));
  for(ST::Orientation_policy policy :
      {ST::Orientation_policy::BOUND_VOLUME, ST::Orientation_policy::KEEP_INPUT, ST::Orientation_policy::OUTWARD}) {
    std::vector<Point> p = points;
    std::vector<Triangle> t = triangles;
    const ST::Orientation_report r = ST::orient_triangle_soup(p, t, ST::parameters::orientation_policy(policy));
    EXPECT_EQ(t, triangles);
    EXPECT_EQ(p.size(), points.size());
    EXPECT_EQ(r.orientation_flips + r.duplicate_triangles + r.duplicated_points, 0u);
  }
  // Reversed as a whole, it comes back to the same triangles with every policy but KEEP_INPUT.
  std::vector<Triangle> reversed = triangles;
  for(Triangle& t : reversed) std::swap(t[1], t[2]);
  std::vector<Point> p = points;
  const ST::Orientation_report r = ST::orient_triangle_soup(p, reversed);
  EXPECT_EQ(reversed, triangles);
  EXPECT_EQ(r.orientation_flips, triangles.size());
}

// ---------------------------------------------------------------------------------------------
// Independence of the input order

TEST(OrientTriangleSoup, Issue21ShuffledAlstom)
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  soup_test::read_data_mesh("cad/ALSTOM_TEST4.off", points, triangles);
  std::mt19937 rng(7);
  Flat_mesh first;
  std::set<std::vector<std::size_t>> first_faces;
  for(int shuffle = 0; shuffle < 4; ++shuffle) {
    if(shuffle > 0) std::shuffle(triangles.begin(), triangles.end(), rng);
    Mesh mesh;
    ST::reconstruct_topology(points, triangles, mesh, ST::parameters::relative_tolerance(1e-2));
    ASSERT_TRUE(CGAL::is_valid_polygon_mesh(mesh));
    Flat_mesh flat = flatten(mesh);
    std::set<std::vector<std::size_t>> face_set;
    for(std::vector<std::size_t> f : flat.faces) {
      std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
      face_set.insert(f);
    }
    if(shuffle == 0) {
      first = flat;
      first_faces = face_set;
      continue;
    }
    EXPECT_EQ(flat.points, first.points) << "shuffle " << shuffle;
    EXPECT_EQ(flat.border, first.border) << "shuffle " << shuffle;
    EXPECT_EQ(face_set, first_faces) << "shuffle " << shuffle;
  }
}

TEST(OrientTriangleSoup, Issue21HostileSoupUnderPermutations)
{
  const Soup s = hostile_soup();
  std::vector<Point> reference_points = s.points;
  std::vector<Triangle> reference = s.triangles;
  const ST::Orientation_report r0 = ST::orient_triangle_soup(reference_points, reference);
  EXPECT_EQ(r0.duplicate_triangles, 1u);
  EXPECT_GT(r0.duplicated_points, 0u);
  {
    std::vector<std::vector<std::size_t>> polygons;
    for(const Triangle& t : reference) polygons.push_back({t[0], t[1], t[2]});
    EXPECT_TRUE(PMP::is_polygon_soup_a_polygon_mesh(polygons));
    Mesh mesh;
    ST::triangle_soup_to_face_graph(s.points, s.triangles, mesh);
    EXPECT_TRUE(CGAL::is_valid_polygon_mesh(mesh));
  }
  const std::set<Triangle> reference_set = oriented_set(reference);
  const auto reference_shape = relabelling_invariant(reference_points, reference);
  std::mt19937 rng(21);
  for(int trial = 0; trial < 20; ++trial) {
    // Triangles permuted (and rotated): the same points and the same oriented triangles.
    std::vector<Point> p = s.points;
    std::vector<Triangle> t = s.triangles;
    std::shuffle(t.begin(), t.end(), rng);
    for(Triangle& x : t) std::rotate(x.begin(), x.begin() + std::ptrdiff_t(rng() % 3), x.end());
    const ST::Orientation_report r = ST::orient_triangle_soup(p, t);
    EXPECT_EQ(p, reference_points) << "trial " << trial;
    EXPECT_EQ(oriented_set(t), reference_set) << "trial " << trial;
    EXPECT_EQ(r.orientation_flips, r0.orientation_flips);
    EXPECT_EQ(r.duplicated_points, r0.duplicated_points);
    // Points permuted too: the same soup up to relabelling.
    std::vector<std::size_t> perm(s.points.size());
    std::iota(perm.begin(), perm.end(), std::size_t(0));
    std::shuffle(perm.begin(), perm.end(), rng);
    std::vector<Point> q(s.points.size());
    for(std::size_t i = 0; i < perm.size(); ++i) q[perm[i]] = s.points[i];
    std::vector<Triangle> u = s.triangles;
    for(Triangle& x : u) for(std::size_t& v : x) v = perm[v];
    std::shuffle(u.begin(), u.end(), rng);
    ST::orient_triangle_soup(q, u);
    EXPECT_EQ(relabelling_invariant(q, u), reference_shape) << "trial " << trial;
  }
}

// The repeated triangles of `triangles` removed as a comparison sort of their sorted corners
// finds them: triangles on the same three vertices are grouped, the orientation most of a group
// has is kept (on a tie, the rotation increasing in the lexicographic ranks of the points is
// decisive, compared with the first triangle of the group), from its first occurrence. Returns
// the number removed.
std::size_t remove_repeated_triangles_by_sorting(const std::vector<Point>& points, std::vector<Triangle>& triangles)
{
  const std::size_t n = triangles.size();
  std::vector<std::pair<Triangle, std::size_t>> keys(n);
  for(std::size_t t = 0; t < n; ++t) {
    Triangle k = triangles[t];
    std::sort(k.begin(), k.end());
    keys[t] = {k, t};
  }
  std::sort(keys.begin(), keys.end());
  std::vector<std::size_t> order(points.size()), rank(points.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return points[a] < points[b]; });
  for(std::size_t r = 0; r < order.size(); ++r) rank[order[r]] = r;
  auto increasing_by = [](const Triangle& t, const std::vector<std::size_t>* key) {
    auto k = [&](std::size_t v) { return key ? (*key)[v] : v; };
    return int(k(t[0]) < k(t[1])) + int(k(t[1]) < k(t[2])) + int(k(t[2]) < k(t[0])) == 2;
  };
  std::vector<char> drop(n, 0);
  std::size_t removed = 0;
  for(std::size_t g = 0; g < n;) {
    std::size_t e = g + 1;
    while(e < n && keys[e].first == keys[g].first) ++e;
    std::size_t up = 0;
    for(std::size_t k = g; k < e; ++k) up += increasing_by(triangles[keys[k].second], nullptr) ? 1u : 0u;
    bool keep_increasing = 2 * up > e - g;
    if(2 * up == e - g) {
      const Triangle& first = triangles[keys[g].second];
      keep_increasing = increasing_by(first, nullptr) == increasing_by(first, &rank);
    }
    bool kept = false;
    for(std::size_t k = g; k < e; ++k) {
      const std::size_t t = keys[k].second;
      if(!kept && increasing_by(triangles[t], nullptr) == keep_increasing) kept = true;
      else { drop[t] = 1; ++removed; }
    }
    g = e;
  }
  std::vector<Triangle> kept;
  for(std::size_t t = 0; t < n; ++t)
    if(!drop[t]) kept.push_back(triangles[t]);
  triangles.swap(kept);
  return removed;
}

TEST(OrientTriangleSoup, Issue13RepeatedTrianglesFoundByHashingAsBySorting)
{
  // Triangles drawn among few points, so that most of them repeat, in both orientations and
  // with ties; the points in random places, so that their ranks are not their indices.
  std::mt19937 rng(13);
  for(int trial = 0; trial < 20; ++trial) {
    const std::size_t number_of_points = 5 + rng() % 6;
    std::vector<Point> points;
    std::uniform_real_distribution<double> coordinate(-1, 1);
    for(std::size_t i = 0; i < number_of_points; ++i) points.emplace_back(coordinate(rng), coordinate(rng), coordinate(rng));
    std::vector<Triangle> triangles;
    const std::size_t count = 1 + rng() % 400;
    while(triangles.size() < count) {
      const Triangle t = {rng() % number_of_points, rng() % number_of_points, rng() % number_of_points};
      if(t[0] != t[1] && t[1] != t[2] && t[2] != t[0]) triangles.push_back(t);
    }
    std::vector<Point> p1 = points, p2 = points;
    std::vector<Triangle> t1 = triangles, t2 = triangles;
    const std::size_t removed = remove_repeated_triangles_by_sorting(points, t2);
    const ST::Orientation_report r1 = ST::orient_triangle_soup(p1, t1);
    const ST::Orientation_report r2 = ST::orient_triangle_soup(p2, t2);
    EXPECT_EQ(r1.duplicate_triangles, removed) << "trial " << trial;
    EXPECT_EQ(r2.duplicate_triangles, 0u) << "trial " << trial;
    EXPECT_EQ(t1, t2) << "trial " << trial;
    EXPECT_EQ(p1, p2) << "trial " << trial;
    EXPECT_EQ(r1.orientation_flips, r2.orientation_flips) << "trial " << trial;
    EXPECT_EQ(r1.duplicated_points, r2.duplicated_points) << "trial " << trial;
  }
}

TEST(OrientTriangleSoup, NonManifoldPiecesAreSeparatedIntoValidMeshes)
{
  // Two cubes sharing an edge: two closed cubes, the edge's two points duplicated once each.
  Soup s;
  s.add_cube(0, 0, 0, 1);
  s.add_cube(1, 1, 0, 1);
  ASSERT_EQ(s.points.size(), 14u);
  Mesh mesh;
  const ST::Face_graph_output_report r = ST::triangle_soup_to_face_graph(s.points, s.triangles, mesh);
  EXPECT_EQ(r.duplicated_points, 2u);
  EXPECT_TRUE(CGAL::is_valid_polygon_mesh(mesh));
  EXPECT_TRUE(CGAL::is_closed(mesh));
  EXPECT_TRUE(PMP::does_bound_a_volume(mesh));
  // A Moebius strip: one edge given up, a valid open mesh.
  Soup m;
  m.add_moebius(0, 0, 12);
  Mesh strip;
  ST::triangle_soup_to_face_graph(m.points, m.triangles, strip);
  EXPECT_TRUE(CGAL::is_valid_polygon_mesh(strip));
  EXPECT_EQ(num_faces(strip), 24u);
}

// The pairs of boxes of which one holds the other, against every pair tested: random boxes,
// nested chains, equal boxes, boxes sharing sides and degenerate (flat or point) boxes.
TEST(OrientTriangleSoup, BoxesInsideBoxesAsByTestingEveryPair)
{
  std::mt19937_64 rng(6);
  std::uniform_int_distribution<int> coordinate(0, 12); // few values: many equal bounds
  for(std::size_t round = 0; round < 40; ++round) {
    std::vector<ST::internal::Box_bounds> boxes;
    const std::size_t m = 1 + round * 7;
    for(std::size_t c = 0; c < m; ++c) {
      ST::internal::Box_bounds b;
      for(std::size_t i = 0; i < 3; ++i) {
        const int x = coordinate(rng), y = coordinate(rng);
        b[i] = std::min(x, y) * 0.5;
        b[i + 3] = std::max(x, y) * 0.5;
      }
      boxes.push_back(b);
      if(c % 5 == 0) boxes.push_back(b); // an equal box
    }
    for(std::size_t c = 0; c < 30; ++c) // a nested chain
      boxes.push_back({-double(c), -double(c), -double(c), 100.0 + double(c), 100.0 + double(c), 100.0 + double(c)});
    std::set<std::pair<std::size_t, std::size_t>> expected, found;
    for(std::size_t a = 0; a < boxes.size(); ++a)
      for(std::size_t b = 0; b < boxes.size(); ++b) {
        bool inside = a != b;
        for(std::size_t i = 0; i < 3; ++i)
          inside = inside && boxes[a][i] <= boxes[b][i] && boxes[b][i + 3] <= boxes[a][i + 3];
        if(inside) expected.insert({a, b});
      }
    ST::internal::for_each_box_inside_another(boxes, [&](std::size_t outer, std::size_t inner) {
      EXPECT_TRUE(found.insert({outer, inner}).second) << "pair listed twice";
    });
    ASSERT_EQ(found, expected) << "round " << round;
  }
}

// k tetrahedra (A, B, C_i, D_i) around one edge AB, in thin wedges that do not overlap, half of
// the triangles reversed, all shuffled: 2k triangles on one non-manifold edge. `closed`: the four
// faces of each; else without the face B D_i C_i (open wedges).
struct Wedges_around_one_edge
{
  std::vector<Point> points = {Point(0, 0, 0), Point(0, 0, 1)};
  std::vector<Triangle> triangles;

  Wedges_around_one_edge(std::size_t k, bool closed)
  {
    const double two_pi = 2 * 3.14159265358979323846;
    for(std::size_t i = 0; i < k; ++i) {
      const double a = two_pi * double(i) / double(k), b = two_pi * (double(i) + 0.5) / double(k);
      const std::size_t c = points.size(), d = c + 1;
      points.emplace_back(std::cos(a), std::sin(a), 0.25);
      points.emplace_back(std::cos(b), std::sin(b), 0.75);
      std::vector<Triangle> faces = {Triangle{0, 1, c}, Triangle{1, 0, d}, Triangle{0, c, d}};
      if(closed) faces.push_back(Triangle{1, d, c});
      for(const Triangle& t : faces) triangles.push_back(triangles.size() % 2 == 0 ? t : Triangle{t[0], t[2], t[1]});
    }
    std::mt19937_64 rng(k);
    std::shuffle(triangles.begin(), triangles.end(), rng);
  }
};

// The directed edges of `triangles`, each expected once, and how many have no reverse (border edges).
std::size_t border_edges_of_consistent_soup(const std::vector<Triangle>& triangles)
{
  std::set<std::pair<std::size_t, std::size_t>> directed;
  for(const Triangle& t : triangles)
    for(std::size_t i = 0; i < 3; ++i) EXPECT_TRUE(directed.insert({t[i], t[(i + 1) % 3]}).second);
  std::size_t border = 0;
  for(const auto& [u, v] : directed) border += directed.count({v, u}) == 0 ? 1 : 0;
  return border;
}

// Whether an edge is shared once the fans are separated was decided, on a non-manifold edge, by
// reading for each of its triangles every other one: k^2 (30 s for the open wedges below, k =
// 25,000). It is now one sort of the edge's triangles. Closed tetrahedra: each gets its own copies
// of A and B, is closed and is oriented outward by its volume; their nesting looked at every pair
// of overlapping boxes, here all k^2 pairs (16.5 s for the tool on the same soup as an STL), and
// now at the pairs of boxes of which one holds the other (none here).
TEST(OrientTriangleSoup, WedgesAroundOneEdgeAreSeparatedClosedWhereTheyCloseAndLinear)
{
  {
    const std::size_t k = 25000;
    Wedges_around_one_edge s(k, true);
    const std::clock_t start = std::clock();
    const ST::Orientation_report r = ST::orient_triangle_soup(s.points, s.triangles);
    const double seconds = cpu_seconds_since(start);
    EXPECT_LT(seconds, 2.0);
    RecordProperty("closed_cpu_seconds", std::to_string(seconds));
    EXPECT_EQ(r.duplicate_triangles, 0u);
    EXPECT_EQ(r.duplicated_points, 2 * (k - 1));
    ASSERT_EQ(s.points.size(), 4 * k);
    ASSERT_EQ(s.triangles.size(), 4 * k);
    EXPECT_EQ(border_edges_of_consistent_soup(s.triangles), 0u);
    // Outward: every tetrahedron (known by its points C_i, D_i) has a positive volume.
    std::vector<double> volume(k, 0.0);
    for(const Triangle& t : s.triangles) {
      std::size_t apex = 0;
      for(std::size_t v : t)
        if(v >= 2 && v < 2 + 2 * k) apex = v;
      ASSERT_GE(apex, 2u);
      const Point& p = s.points[t[0]];
      const Point& q = s.points[t[1]];
      const Point& u = s.points[t[2]];
      volume[(apex - 2) / 2] += CGAL::determinant(p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), u.x(), u.y(), u.z());
    }
    for(std::size_t i = 0; i < k; ++i) ASSERT_GT(volume[i], 0.0) << "tetrahedron " << i;
  }
  const std::size_t k = 25000;
  Wedges_around_one_edge s(k, false);
  const std::clock_t start = std::clock();
  const ST::Orientation_report r = ST::orient_triangle_soup(s.points, s.triangles);
  const double seconds = cpu_seconds_since(start);
  // At A a fan per wedge (its faces meet along A C_i and A D_i); at B two, its faces on A B meeting
  // along nothing but the non-manifold edge: k - 1 copies of A, 2k - 1 of B.
  EXPECT_EQ(r.duplicated_points, 3 * k - 2);
  ASSERT_EQ(s.points.size(), 5 * k);
  ASSERT_EQ(s.triangles.size(), 3 * k);
  // So each wedge's two faces on A B end on different copies of B: with B C_i, B D_i and C_i D_i,
  // five border edges a wedge.
  EXPECT_EQ(border_edges_of_consistent_soup(s.triangles), 5 * k);
  EXPECT_LT(seconds, 2.0);
  RecordProperty("cpu_seconds", std::to_string(seconds));
}

// ---------------------------------------------------------------------------------------------
// The orientation with the tables at hand (a pipeline's), and its results pinned: the values
// below are those of the orientation before it read repeated triangles and fans from the tables
// (an open-addressing hash of every triangle, a search of the fans of every vertex).

// A 64-bit FNV-1a fingerprint of an oriented soup: the bits of the coordinates, the triangles in
// their order and the report.
std::uint64_t fingerprint(const std::vector<Point>& points, const std::vector<Triangle>& triangles,
                          const ST::Orientation_report& r)
{
  std::uint64_t h = 1469598103934665603ULL;
  auto add = [&](std::uint64_t x) {
    for(int i = 0; i < 8; ++i) {
      h ^= (x >> (8 * i)) & 0xff;
      h *= 1099511628211ULL;
    }
  };
  add(points.size());
  add(triangles.size());
  for(const Point& p : points)
    for(int i = 0; i < 3; ++i) {
      const double c = p[i];
      std::uint64_t b;
      std::memcpy(&b, &c, sizeof b);
      add(b);
    }
  for(const Triangle& t : triangles)
    for(std::size_t v : t) add(v);
  add(r.duplicate_triangles);
  add(r.orientation_flips);
  add(r.duplicated_points);
  return h;
}

// A deterministic scramble (a xorshift generator, no library distribution): every triangle
// rotated, a third of them reversed, one in 40 repeated (in either orientation), one in 200
// three more times (in both), then all shuffled.
std::vector<Triangle> scrambled(const std::vector<Triangle>& triangles, std::uint64_t seed)
{
  std::uint64_t x = seed * 0x9e3779b97f4a7c15ULL + 1;
  auto next = [&] {
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    return x;
  };
  std::vector<Triangle> out;
  for(const Triangle& t0 : triangles) {
    Triangle t = t0;
    std::rotate(t.begin(), t.begin() + std::ptrdiff_t(next() % 3), t.end());
    if(next() % 3 == 0) std::swap(t[1], t[2]);
    out.push_back(t);
    if(next() % 40 == 0) out.push_back(next() % 2 ? t : Triangle{t[0], t[2], t[1]});
    if(next() % 200 == 0)
      for(int k = 0; k < 3; ++k) out.push_back(k % 2 ? t : Triangle{t[0], t[2], t[1]});
  }
  for(std::size_t i = out.size(); i > 1; --i) std::swap(out[i - 1], out[next() % i]);
  return out;
}

// The soups whose orientation is pinned: three real meshes as read (the pig has non-manifold
// vertices), bunny00 cut into 8 patches with T-junctions and repaired, and each scrambled.
std::vector<std::pair<std::string, Soup>> pinned_soups()
{
  std::vector<std::pair<std::string, Soup>> soups;
  for(const char* file : {"cgal_repair/pig.stl.xz", "cad/ALSTOM_TEST4.off", "clean/elephant.off"}) {
    Soup s;
    soup_test::read_data_mesh(file, s.points, s.triangles);
    soups.emplace_back(file, s);
  }
  Soup bunny;
  soup_test::read_data_mesh("clean/bunny00.off.xz", bunny.points, bunny.triangles);
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for(const Point& q : bunny.points)
    for(int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], q[i]);
      hi[i] = std::max(hi[i], q[i]);
    }
  const double diag = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                (hi[2] - lo[2]) * (hi[2] - lo[2]));
  const auto generated = soup_test::t_junction_soup(bunny.points, bunny.triangles, 8, 1e-7 * diag, 17);
  Soup repaired;
  repaired.points = generated.points;
  repaired.triangles = generated.triangles;
  ST::reconstruct_topology(repaired.points, repaired.triangles, CGAL::parameters::snapping_tolerance(1e-6 * diag));
  soups.emplace_back("bunny00 T-junction soup, repaired", repaired);
  const std::size_t number_of_sources = soups.size();
  for(std::size_t k = 0; k < number_of_sources; ++k) {
    Soup s;
    s.points = soups[k].second.points;
    s.triangles = scrambled(soups[k].second.triangles, k + 1 == number_of_sources ? 9 : 5);
    soups.emplace_back(soups[k].first + ", scrambled", s);
  }
  return soups;
}

TEST(OrientTriangleSoup, PinnedOnRealMeshesWithAndWithoutTheirTables)
{
  // per soup of pinned_soups(), per policy (BOUND_VOLUME, KEEP_INPUT, OUTWARD): the report and the fingerprint
  struct Pinned
  {
    std::size_t duplicate_triangles, orientation_flips, duplicated_points;
    std::uint64_t fingerprint;
  };
  const Pinned pinned[][3] = {
    // cgal_repair/pig.stl.xz
    {{0, 0, 443, 0x51cc3bfc3dca99ccULL}, {0, 0, 443, 0x51cc3bfc3dca99ccULL}, {0, 0, 443, 0x51cc3bfc3dca99ccULL}},
    // cad/ALSTOM_TEST4.off
    {{0, 0, 0, 0xc2ab8807c7267a25ULL}, {0, 0, 0, 0xc2ab8807c7267a25ULL}, {0, 0, 0, 0xc2ab8807c7267a25ULL}},
    // clean/elephant.off
    {{0, 0, 0, 0x972e9cc310c4f3f0ULL}, {0, 0, 0, 0x972e9cc310c4f3f0ULL}, {0, 0, 0, 0x972e9cc310c4f3f0ULL}},
    // t_junction repaired
    {{0, 0, 0, 0x87cff6fd4658fd6fULL}, {0, 0, 0, 0x87cff6fd4658fd6fULL}, {0, 0, 0, 0x87cff6fd4658fd6fULL}},
    // cgal_repair/pig.stl.xz, scrambled
    {{690, 5598, 443, 0x736711394fbec0fdULL}, {690, 5598, 443, 0x736711394fbec0fdULL}, {690, 5598, 443, 0x736711394fbec0fdULL}},
    // cad/ALSTOM_TEST4.off, scrambled
    {{78, 666, 0, 0x0daf34490ec89357ULL}, {78, 666, 0, 0x0daf34490ec89357ULL}, {78, 666, 0, 0x0daf34490ec89357ULL}},
    // clean/elephant.off, scrambled
    {{219, 1888, 0, 0x2b68c475dccde962ULL}, {219, 1888, 0, 0x2b68c475dccde962ULL}, {219, 1888, 0, 0x2b68c475dccde962ULL}},
    // t_junction repaired, scrambled
    {{3214, 26352, 0, 0xb1435c43aa1b3aabULL}, {3214, 26352, 0, 0xb1435c43aa1b3aabULL}, {3214, 26352, 0, 0xb1435c43aa1b3aabULL}},
  };
  const ST::Orientation_policy policies[] = {ST::Orientation_policy::BOUND_VOLUME, ST::Orientation_policy::KEEP_INPUT,
                                             ST::Orientation_policy::OUTWARD};
  const std::vector<std::pair<std::string, Soup>> soups = pinned_soups();
  ASSERT_EQ(soups.size(), sizeof pinned / sizeof pinned[0]);
  for(std::size_t k = 0; k < soups.size(); ++k)
    for(int i = 0; i < 3; ++i) {
      SCOPED_TRACE(soups[k].first + ", policy " + std::to_string(i));
      const Pinned& expected = pinned[k][i];
      const auto np = ST::parameters::orientation_policy(policies[i]);
      std::vector<Point> p = soups[k].second.points;
      std::vector<Triangle> t = soups[k].second.triangles;
      const ST::Orientation_report r = ST::orient_triangle_soup(p, t, np);
      EXPECT_EQ(r.duplicate_triangles, expected.duplicate_triangles);
      EXPECT_EQ(r.orientation_flips, expected.orientation_flips);
      EXPECT_EQ(r.duplicated_points, expected.duplicated_points);
      EXPECT_EQ(fingerprint(p, t, r), expected.fingerprint);
      // the same with the tables of the soup given (they are not changed)
      std::vector<Point> q = soups[k].second.points;
      std::vector<Triangle> u = soups[k].second.triangles;
      const ST::Adjacency_tables tables(u, q.size());
      const ST::Adjacency_tables::Triangle_vector before = tables.triangles();
      const ST::Orientation_report w = ST::internal::orient_triangle_soup_with_tables(q, u, &tables, np);
      EXPECT_EQ(fingerprint(q, u, w), expected.fingerprint);
      EXPECT_EQ(tables.triangles(), before);
      // oriented again, nothing changes
      const ST::Orientation_report again = ST::orient_triangle_soup(q, u, np);
      EXPECT_EQ(again.duplicate_triangles + again.orientation_flips + again.duplicated_points, 0u);
      EXPECT_EQ(u, t);
      EXPECT_EQ(q.size(), p.size());
    }
}

TEST(OrientTriangleSoup, WithThePipelinesTablesAsWithoutThem)
{
  // The tables as the pipeline holds them after a round: built, then updated in place by the
  // weld and the splits (rows with room to grow, triangles appended). The orientation that reads
  // them gives what the orientation that builds its own gives, in every order of the triangles.
  Soup bunny;
  soup_test::read_data_mesh("clean/bunny00.off.xz", bunny.points, bunny.triangles);
  const auto generated = soup_test::t_junction_soup(bunny.points, bunny.triangles, 6, 1e-7, 3);
  const auto np = ST::parameters::small_features(ST::Small_features::COLLAPSE, CGAL::parameters::snapping_tolerance(1e-5));
  for(int order = 0; order < 3; ++order) {
    SCOPED_TRACE("order " + std::to_string(order));
    std::vector<Point> p = generated.points;
    std::vector<Triangle> t = order == 0 ? generated.triangles : scrambled(generated.triangles, 100 + order);
    ST::Adjacency_tables tables(t, p.size());
    const ST::Snap_report snap = ST::snap_vertices(p, t, tables, np);
    const ST::Split_report split = ST::split_t_junctions(p, t, tables, np);
    ASSERT_GT(snap.merged_vertices, 0u);
    ASSERT_GT(split.split_triangles, 0u);
    std::vector<Point> q = p;
    std::vector<Triangle> u = t;
    const ST::Orientation_report expected = ST::orient_triangle_soup(q, u);
    const ST::Orientation_report r = ST::internal::orient_triangle_soup_with_tables(p, t, &tables);
    EXPECT_EQ(fingerprint(p, t, r), fingerprint(q, u, expected));
    if(order > 0) {
      EXPECT_GT(r.duplicate_triangles, 0u);
    }
  }
  // tables of another soup are refused
  std::vector<Point> p = generated.points;
  std::vector<Triangle> t = generated.triangles;
  const ST::Adjacency_tables other(std::vector<Triangle>(t.begin(), t.end() - 1), p.size());
  EXPECT_THROW(ST::internal::orient_triangle_soup_with_tables(p, t, &other), ST::Invalid_input);
}

// ---------------------------------------------------------------------------------------------
// The orientation in parts (the output of a tiled repair under a memory limit)

// Closed shells nested across components: a cube holding a cube holding a cube, a cube inside
// out beside them holding another, two cubes with a face in common (their samples on each other's
// surface), each shell its own component, and the hostile soup's pieces.
Soup nested_shells()
{
  Soup s = hostile_soup();
  s.add_cube(100, 0, 0, 10);
  s.add_cube(102, 2, 2, 6);
  s.add_cube(104, 4, 4, 2, true);
  s.add_cube(120, 0, 0, 10, true);
  s.add_cube(121, 1, 1, 8, false, true);
  s.add_cube(140, 0, 0, 4);
  s.add_cube(140, 0, 0, 4, true); // the same cube again, inside out: every triangle repeated
  s.add_cube(160, 0, 0, 4);
  s.add_cube(160, 1, 1, 2);       // a face in the plane of the outer cube's face
  return s;
}

TEST(OrientTriangleSoup, InPartsAsWhole)
{
  std::vector<std::pair<std::string, Soup>> soups = pinned_soups();
  soups.emplace_back("hostile", hostile_soup());
  soups.emplace_back("nested shells", nested_shells());
  {
    Soup s = nested_shells();
    s.triangles = scrambled(s.triangles, 3);
    soups.emplace_back("nested shells, scrambled", s);
    // the points renumbered at random: the vertices separated in different parts interleave
    std::vector<std::size_t> new_index(s.points.size());
    std::iota(new_index.begin(), new_index.end(), std::size_t(0));
    std::mt19937 shuffle(11);
    std::shuffle(new_index.begin(), new_index.end(), shuffle);
    Soup r;
    r.points.resize(s.points.size());
    for(std::size_t v = 0; v < s.points.size(); ++v) r.points[new_index[v]] = s.points[v];
    for(const Triangle& t : s.triangles) r.triangles.push_back({new_index[t[0]], new_index[t[1]], new_index[t[2]]});
    soups.emplace_back("nested shells, scrambled, points renumbered", r);
  }
  const ST::Orientation_policy policies[] = {ST::Orientation_policy::BOUND_VOLUME, ST::Orientation_policy::KEEP_INPUT,
                                             ST::Orientation_policy::OUTWARD};
  std::size_t turned_across_parts = 0;
  for(const auto& [name, soup] : soups)
    for(const ST::Orientation_policy policy : policies) {
      const auto np = ST::parameters::orientation_policy(policy);
      std::vector<Point> p = soup.points;
      std::vector<Triangle> t = soup.triangles;
      const ST::Orientation_report whole = ST::orient_triangle_soup(p, t, np);
      const ST::Soup_statistics measured = ST::compute_statistics(p, ST::Adjacency_tables(t, p.size()));
      for(const std::size_t part_triangles : {std::size_t(1), std::size_t(20), std::size_t(5000),
                                              std::numeric_limits<std::size_t>::max()}) {
        SCOPED_TRACE(name + ", policy " + std::to_string(int(policy)) + ", parts of " + std::to_string(part_triangles));
        std::vector<Point> q = soup.points;
        std::vector<Triangle> u = soup.triangles;
        const ST::internal::Oriented_in_parts r = ST::internal::orient_triangle_soup_in_parts(q, u, part_triangles, np);
        EXPECT_EQ(u, t);
        ASSERT_EQ(q.size(), p.size());
        EXPECT_TRUE(std::equal(q.begin(), q.end(), p.begin()));
        EXPECT_EQ(r.report.duplicate_triangles, whole.duplicate_triangles);
        EXPECT_EQ(r.report.orientation_flips, whole.orientation_flips);
        EXPECT_EQ(r.report.duplicated_points, whole.duplicated_points);
        EXPECT_EQ(soup_test::statistics_fields(r.statistics), soup_test::statistics_fields(measured));
        if(part_triangles == std::numeric_limits<std::size_t>::max()) {
          EXPECT_EQ(r.parts, 1u);
        }
        if(part_triangles == 1 && name.rfind("nested shells", 0) == 0) {
          EXPECT_GT(r.parts, 10u);
          turned_across_parts += r.turned_across_parts;
        }
        // on threads, the same
        std::vector<Point> pp = soup.points;
        std::vector<Triangle> tt = soup.triangles;
        const auto r2 =
          ST::internal::orient_triangle_soup_in_parts<CGAL::Parallel_if_available_tag>(pp, tt, part_triangles, np);
        EXPECT_EQ(tt, t);
        EXPECT_EQ(r2.report.orientation_flips, whole.orientation_flips);
      }
    }
  // the inner shells turned by shells of other parts (a test that reaches that step)
  EXPECT_GT(turned_across_parts, 0u);
}

// ---------------------------------------------------------------------------------------------
// The FaceGraph construction

TEST(TriangleSoupToFaceGraph, SameMeshAsPolygonSoupToPolygonMesh)
{
  std::vector<std::pair<std::vector<Point>, std::vector<Triangle>>> inputs;
  {
    const Soup s = hostile_soup();
    inputs.push_back({s.points, s.triangles});
    Soup c;
    c.add_cube(0, 0, 0, 1);
    c.points.emplace_back(5, 5, 5); // isolated: kept as a vertex, as CGAL does
    inputs.push_back({c.points, c.triangles});
    std::vector<Point> p;
    std::vector<Triangle> t;
    soup_test::read_data_mesh("cad/ALSTOM_TEST4.off", p, t);
    ST::reconstruct_topology(p, t, ST::parameters::relative_tolerance(1e-2));
    inputs.push_back({p, t});
  }
  for(std::size_t k = 0; k < inputs.size(); ++k) {
    const auto& [points, triangles] = inputs[k];
    const bool valid = (k != 1);
    std::vector<Point> p = points;
    std::vector<Triangle> t = triangles;
    ST::orient_triangle_soup(p, t);
    {
      Mesh ours;
      const ST::Face_graph_output_report r = ST::triangle_soup_to_face_graph(p, t, ours);
      EXPECT_EQ(r.orientation_flips + r.duplicated_points + r.duplicate_triangles, 0u) << "input " << k;
      EXPECT_EQ(CGAL::is_valid_polygon_mesh(ours), valid) << "input " << k;
      EXPECT_TRUE(flatten(ours) == cgal_reference<Mesh>(points, triangles, valid)) << "input " << k;
      Mesh direct;
      ST::triangle_soup_to_face_graph(points, triangles, direct);
      EXPECT_TRUE(flatten(direct) == flatten(ours)) << "input " << k;
    }
    {
      CGAL::Polyhedron_3<Epick> ours;
      ST::triangle_soup_to_face_graph(points, triangles, ours);
      EXPECT_EQ(CGAL::is_valid_polygon_mesh(ours), valid) << "input " << k;
      EXPECT_TRUE(flatten(ours) == cgal_reference<CGAL::Polyhedron_3<Epick>>(points, triangles, valid)) << "input " << k;
    }
  }
  // What the mesh held before stays.
  Soup c;
  c.add_cube(0, 0, 0, 1);
  Mesh twice;
  ST::triangle_soup_to_face_graph(c.points, c.triangles, twice);
  ST::triangle_soup_to_face_graph(c.points, c.triangles, twice);
  EXPECT_TRUE(CGAL::is_valid_polygon_mesh(twice));
  EXPECT_EQ(num_vertices(twice), 16u);
  EXPECT_EQ(num_faces(twice), 24u);
  EXPECT_TRUE(CGAL::is_closed(twice));
}

// Euler::add_face() per triangle is quadratic in the degree of a vertex: 20.8 s for this fan.
TEST(TriangleSoupToFaceGraph, Issue21FanOf100000TrianglesIsLinear)
{
  const std::size_t n = 100000;
  std::vector<Point> points = {Point(0, 0, 0)};
  std::vector<Triangle> triangles;
  for(std::size_t i = 0; i < n; ++i) {
    const double a = 2 * 3.14159265358979323846 * double(i) / double(n);
    points.emplace_back(std::cos(a), std::sin(a), 0);
    triangles.push_back({0, i + 1, (i + 1) % n + 1});
  }
  Mesh mesh;
  const std::clock_t start = std::clock();
  ST::triangle_soup_to_face_graph(points, triangles, mesh);
  const double seconds = cpu_seconds_since(start);
  EXPECT_LT(seconds, 2.0);
  EXPECT_TRUE(CGAL::is_valid_polygon_mesh(mesh));
  EXPECT_EQ(num_faces(mesh), n);
  EXPECT_EQ(degree(*vertices(mesh).begin(), mesh), n);
  RecordProperty("cpu_seconds", std::to_string(seconds));
}

// One 40,000-corner polygon triangulated as a fan from its first corner: 3.4 s with add_face().
TEST(TriangleSoupToFaceGraph, Issue21FanPolygonOf40000CornersIsLinear)
{
  const std::size_t n = 40000;
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  for(std::size_t i = 0; i < n; ++i) {
    const double a = 2 * 3.14159265358979323846 * double(i) / double(n);
    points.emplace_back(std::cos(a), std::sin(a), 0);
  }
  for(std::size_t i = 1; i + 1 < n; ++i) triangles.push_back({0, i, i + 1});
  CGAL::Polyhedron_3<Epick> poly;
  Mesh mesh;
  const std::clock_t start = std::clock();
  ST::triangle_soup_to_face_graph(points, triangles, mesh);
  ST::triangle_soup_to_face_graph(points, triangles, poly);
  const double seconds = cpu_seconds_since(start);
  EXPECT_LT(seconds, 2.0);
  EXPECT_TRUE(CGAL::is_valid_polygon_mesh(mesh));
  EXPECT_TRUE(CGAL::is_valid_polygon_mesh(poly));
  EXPECT_EQ(num_faces(mesh), n - 2);
  EXPECT_EQ(num_faces(poly), n - 2);
  RecordProperty("cpu_seconds", std::to_string(seconds));
}

TEST(TriangleSoupToFaceGraph, Issue20EpickPointsIntoAnEpeckPolyhedron)
{
  Soup s;
  s.add_cube(0.5, 0.25, 0.125, 3);
  CGAL::Polyhedron_3<Epeck> poly;
  ST::triangle_soup_to_face_graph(s.points, s.triangles, poly);
  EXPECT_TRUE(CGAL::is_valid_polygon_mesh(poly));
  EXPECT_TRUE(CGAL::is_closed(poly));
  EXPECT_TRUE(PMP::is_outward_oriented(poly));
  EXPECT_EQ(num_vertices(poly), 8u);
  EXPECT_EQ(PMP::volume(poly), Epeck::FT(27));
  CGAL::Surface_mesh<Epeck::Point_3> exact;
  ST::triangle_soup_to_face_graph(s.points, s.triangles, exact);
  EXPECT_TRUE(flatten(exact) == flatten(poly));
}

TEST(TriangleSoupToFaceGraph, Issue20NonFinitePointIsRefused)
{
  Soup s;
  s.add_cube(0, 0, 0, 1);
  s.points[3] = Point(0, std::numeric_limits<double>::quiet_NaN(), 0);
  Mesh mesh;
  try {
    ST::triangle_soup_to_face_graph(s.points, s.triangles, mesh);
    ADD_FAILURE() << "a NaN point was written";
  } catch(const ST::Invalid_input& e) {
    EXPECT_NE(std::string(e.what()).find("point 3"), std::string::npos) << e.what();
  }
  EXPECT_EQ(num_vertices(mesh), 0u);
  s.points[3] = Point(0, 1, std::numeric_limits<double>::infinity());
  std::vector<Triangle> t = s.triangles;
  EXPECT_THROW(ST::orient_triangle_soup(s.points, t), ST::Invalid_input);
  EXPECT_EQ(t, s.triangles);
}

} // namespace

} // namespace orient_triangle_soup_test
