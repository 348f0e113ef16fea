// Copyright (c) 2026 The Soup_topology authors.
// SPDX-License-Identifier: LGPL-3.0-or-later
//
// The robustness experiment of issue 10, after Hoffmann, Hopcroft and Karasick (section 8: a cube
// intersected with rotated copies of itself, down to tiny angles). Our counterpart: a clean mesh
// is cut into patches whose shared borders are tessellated differently on the two sides
// (T-junctions) and whose border vertices are duplicated; then
//   - "rotation": every patch is rotated about its own random axis through the model's centre by
//     theta degrees (1e-1 down to 1e-12), so the copies of a shared vertex disagree by about
//     theta x their distance from the centre;
//   - "float32": every coordinate is rounded to float, as an STL export does.
// Each soup is repaired by `reconstruct_topology()` under four kernels and three tolerances
// (0.5, 2 and 10 times the largest displacement), twice (the second time with the triangles,
// their corners and the points shuffled), and the result is checked against the repair of the
// unperturbed soup.
//
// Usage: robustness_experiment [OUT.csv] [--quick] [--small-features collapse|refuse]
// One CSV row per mesh x perturbation (3 random rotations per theta, and float32) x kernel x
// tolerance; the runs that are not correct are listed on stdout. `--small-features` chooses the
// policy of `reconstruct_topology()` for two vertices of one triangle within the tolerance
// (default: collapse, the library's default); the last columns of the CSV name it and count the
// collapsed triangles and the welds refused because a collapse would leave the surface. A run is correct if the result
// has, in terms of the model's positions, exactly the oriented triangles of the reference (the
// unperturbed soup repaired with Epeck), no non-manifold edge, no degenerate or flipped triangle,
// and the same geometric triangles when the input is shuffled. A run is valid if it is all that
// but for the first condition, with the border edges of the reference: a closed, manifold,
// unflipped, order-independent result that may have fewer triangles (a collapse of features
// smaller than the tolerance). Times: the smaller of the two runs, in milliseconds, for
// `reconstruct_topology()` alone.

#include <Soup_topology/Adjacency_tables.h>
#include <Soup_topology/internal/exact_signs.h>
#include <Soup_topology/internal/tolerance.h>
#include <Soup_topology/reconstruct_topology.h>

#include "../test/soup_generators.h"
#include "../test/test_utilities.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Exact_rational.h>
#include <CGAL/Simple_cartesian.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <iostream>
#include <map>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace ST = Soup_topology;
using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;
using Double_kernel = CGAL::Simple_cartesian<double>;
using Rational_kernel = CGAL::Simple_cartesian<CGAL::Exact_rational>;
using Point = Epick::Point_3; // the soups are made in double coordinates
using Triangle = std::array<std::size_t, 3>;
using Coordinates = std::array<double, 3>;

// ---------------------------------------------------------------------------------------------
// The soups.

struct Model
{
  std::string name;
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  Coordinates centre{};
  double diagonal = 0;
};

/// the unperturbed soup of a model: patches, T-junctions, duplicated border vertices, and for
/// every soup point the id of the model position it is a copy of.
struct Base_soup
{
  std::vector<Point> points;
  std::vector<Triangle> triangles;
  std::vector<std::size_t> id;           // soup point -> position id
  std::vector<Point> position;           // position id -> unperturbed coordinates
  std::vector<int> piece_of_point;       // soup point -> rigid piece (a connected part of a patch)
  int pieces = 0;
};

Coordinates coordinates(const Point& p) { return {p.x(), p.y(), p.z()}; }

Base_soup make_base_soup(const Model& model, int slabs)
{
  Base_soup base;
  const auto soup = soup_test::t_junction_soup(model.points, model.triangles, slabs, 0.0, 1u);
  base.points = soup.points;
  base.triangles = soup.triangles;
  std::map<Coordinates, std::size_t> ids;
  base.id.resize(base.points.size());
  for(std::size_t i = 0; i < base.points.size(); ++i) {
    auto ins = ids.emplace(coordinates(base.points[i]), base.position.size());
    if(ins.second) base.position.push_back(base.points[i]);
    base.id[i] = ins.first->second;
  }
  // The pieces that move rigidly: the copies are made per patch, so no point is shared by two
  // patches; a connected piece (triangles sharing points) lies in one patch and is rotated as a
  // whole.
  std::vector<std::size_t> parent(base.points.size());
  std::iota(parent.begin(), parent.end(), std::size_t(0));
  auto find = [&](std::size_t x) { while(parent[x] != x) x = parent[x] = parent[parent[x]]; return x; };
  for(const Triangle& t : base.triangles)
    for(int k = 1; k < 3; ++k) {
      const std::size_t a = find(t[0]), b = find(t[static_cast<std::size_t>(k)]);
      if(a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  std::map<std::size_t, int> piece_of_root;
  base.piece_of_point.resize(base.points.size());
  for(std::size_t i = 0; i < base.points.size(); ++i) {
    auto ins = piece_of_root.emplace(find(i), static_cast<int>(piece_of_root.size()));
    base.piece_of_point[i] = ins.first->second;
  }
  base.pieces = static_cast<int>(piece_of_root.size());
  return base;
}

/// the perturbed coordinates of the soup, and the largest displacement.
struct Perturbed
{
  std::string kind;      // "rotation" or "float32"
  double theta = 0;      // degrees (0 for float32)
  unsigned seed = 0;     // which random rotation
  std::vector<Coordinates> points;
  double largest_displacement = 0;
};

Perturbed rotate_patches(const Base_soup& base, const Model& model, double theta_degrees, unsigned seed)
{
  Perturbed out;
  out.kind = "rotation";
  out.theta = theta_degrees;
  const double theta = theta_degrees * 3.14159265358979323846 / 180.0;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss(0.0, 1.0);
  // Per piece: R - I = sin(theta) K + (1 - cos(theta)) K^2, with 1 - cos = 2 sin^2(theta/2), so
  // that p' = p + (R - I)(p - c) moves p by about theta |p - c| without cancellation.
  std::vector<std::array<double, 9>> m(static_cast<std::size_t>(base.pieces));
  for(auto& mat : m) {
    double a[3] = {gauss(rng), gauss(rng), gauss(rng)};
    const double n = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for(double& x : a) x /= n;
    const double sign = (rng() & 1u) ? 1.0 : -1.0;
    const double s = sign * std::sin(theta), h = std::sin(theta / 2), c1 = 2 * h * h;
    const double k[9] = {0, -a[2], a[1], a[2], 0, -a[0], -a[1], a[0], 0};
    for(int i = 0; i < 3; ++i)
      for(int j = 0; j < 3; ++j) {
        double k2 = 0;
        for(int l = 0; l < 3; ++l) k2 += k[3 * i + l] * k[3 * l + j];
        mat[static_cast<std::size_t>(3 * i + j)] = s * k[3 * i + j] + c1 * k2;
      }
  }
  out.points.resize(base.points.size());
  for(std::size_t i = 0; i < base.points.size(); ++i) {
    const Coordinates p = coordinates(base.points[i]);
    const auto& mat = m[static_cast<std::size_t>(base.piece_of_point[i])];
    const double d[3] = {p[0] - model.centre[0], p[1] - model.centre[1], p[2] - model.centre[2]};
    Coordinates q;
    for(int r = 0; r < 3; ++r)
      q[static_cast<std::size_t>(r)] = p[static_cast<std::size_t>(r)] +
        (mat[static_cast<std::size_t>(3 * r)] * d[0] + mat[static_cast<std::size_t>(3 * r + 1)] * d[1] +
         mat[static_cast<std::size_t>(3 * r + 2)] * d[2]);
    out.points[i] = q;
    out.largest_displacement = std::max(out.largest_displacement,
      std::sqrt((q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]) + (q[2] - p[2]) * (q[2] - p[2])));
  }
  return out;
}

Perturbed round_to_float(const Base_soup& base)
{
  Perturbed out;
  out.kind = "float32";
  out.points.resize(base.points.size());
  for(std::size_t i = 0; i < base.points.size(); ++i) {
    const Coordinates p = coordinates(base.points[i]);
    Coordinates q;
    for(std::size_t k = 0; k < 3; ++k) q[k] = static_cast<double>(static_cast<float>(p[k]));
    out.points[i] = q;
    out.largest_displacement = std::max(out.largest_displacement,
      std::sqrt((q[0] - p[0]) * (q[0] - p[0]) + (q[1] - p[1]) * (q[1] - p[1]) + (q[2] - p[2]) * (q[2] - p[2])));
  }
  return out;
}

// ---------------------------------------------------------------------------------------------
// One run and its checks.

/// the output of one run, as double coordinates (exact: output points are input points).
struct Output
{
  std::vector<Coordinates> points;
  std::vector<Triangle> triangles;
  ST::Reconstruction_report report;
  double milliseconds = 0;
};

template <class Kernel>
Output run(const std::vector<Coordinates>& coordinates_in, const std::vector<Triangle>& triangles_in, double eps,
           ST::Small_features policy)
{
  using P = typename Kernel::Point_3;
  using FT = typename Kernel::FT;
  std::vector<P> points;
  points.reserve(coordinates_in.size());
  for(const Coordinates& c : coordinates_in) points.emplace_back(FT(c[0]), FT(c[1]), FT(c[2])); // exact conversion
  std::vector<Triangle> triangles = triangles_in;
  Output out;
  const auto start = std::chrono::steady_clock::now();
  out.report = ST::reconstruct_topology(
    points, triangles, ST::parameters::small_features(policy, CGAL::parameters::snapping_tolerance(FT(eps))));
  const auto stop = std::chrono::steady_clock::now();
  out.milliseconds = std::chrono::duration<double, std::milli>(stop - start).count();
  out.points.reserve(points.size());
  for(const P& p : points) out.points.push_back({CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())});
  out.triangles = std::move(triangles);
  return out;
}

/// the triangles as a sorted list of geometric triangles, each starting at its smallest corner
/// (orientation kept): equal lists mean the same surface, whatever the numbering.
std::vector<std::array<Coordinates, 3>> canonical_geometry(const Output& o)
{
  std::vector<std::array<Coordinates, 3>> result;
  result.reserve(o.triangles.size());
  for(const Triangle& t : o.triangles) {
    std::array<Coordinates, 3> g = {o.points[t[0]], o.points[t[1]], o.points[t[2]]};
    const auto smallest = std::min_element(g.begin(), g.end()) - g.begin();
    std::rotate(g.begin(), g.begin() + smallest, g.end());
    result.push_back(g);
  }
  std::sort(result.begin(), result.end());
  return result;
}

/// the triangles in position ids, each starting at its smallest id (orientation kept), sorted.
std::vector<Triangle> canonical_topology(const std::vector<Triangle>& triangles, const std::vector<std::size_t>& id_of_point)
{
  std::vector<Triangle> result;
  result.reserve(triangles.size());
  for(const Triangle& t : triangles) {
    Triangle g = {id_of_point[t[0]], id_of_point[t[1]], id_of_point[t[2]]};
    const auto smallest = std::min_element(g.begin(), g.end()) - g.begin();
    std::rotate(g.begin(), g.begin() + smallest, g.end());
    result.push_back(g);
  }
  std::sort(result.begin(), result.end());
  return result;
}

struct Checks
{
  std::size_t degenerate = 0;        // exactly collinear output triangles
  std::size_t flipped = 0;           // normal reversed (or zero) vs. the same corners unperturbed
  std::size_t inconsistent_edges = 0;
  std::size_t unknown_points = 0;    // output points that are no input point (must stay 0)
  bool same_as_reference = false;
};

Checks check(const Output& o, const std::map<Coordinates, std::size_t>& id_of_coordinates, const Base_soup& base,
             const std::vector<Triangle>& reference)
{
  Checks c;
  std::vector<std::size_t> id(o.points.size(), static_cast<std::size_t>(-1));
  for(std::size_t i = 0; i < o.points.size(); ++i) {
    const auto it = id_of_coordinates.find(o.points[i]);
    if(it == id_of_coordinates.end()) { ++c.unknown_points; continue; }
    id[i] = it->second;
  }
  if(c.unknown_points != 0) return c;
  const Epick k;
  const auto collinear = k.collinear_3_object();
  for(const Triangle& t : o.triangles) {
    const Point a(o.points[t[0]][0], o.points[t[0]][1], o.points[t[0]][2]);
    const Point b(o.points[t[1]][0], o.points[t[1]][1], o.points[t[1]][2]);
    const Point d(o.points[t[2]][0], o.points[t[2]][1], o.points[t[2]][2]);
    if(collinear(a, b, d)) ++c.degenerate;
    const Point& pa = base.position[id[t[0]]];
    const Point& pb = base.position[id[t[1]]];
    const Point& pd = base.position[id[t[2]]];
    if(ST::internal::sign_of_normal_dot(a, b, d, pa, pb, pd) != CGAL::POSITIVE) ++c.flipped;
  }
  c.inconsistent_edges = ST::Adjacency_tables(o.triangles, o.points.size()).inconsistently_oriented_edges().size();
  c.same_as_reference = canonical_topology(o.triangles, id) == reference;
  return c;
}

/// the same soup renumbered: points permuted, triangles shuffled, corners rotated.
void shuffle_soup(const std::vector<Coordinates>& points, const std::vector<Triangle>& triangles, unsigned seed,
                  std::vector<Coordinates>& points_out, std::vector<Triangle>& triangles_out)
{
  std::mt19937 rng(seed);
  std::vector<std::size_t> perm(points.size());
  std::iota(perm.begin(), perm.end(), std::size_t(0));
  std::shuffle(perm.begin(), perm.end(), rng);
  points_out.assign(points.size(), Coordinates{});
  for(std::size_t i = 0; i < points.size(); ++i) points_out[perm[i]] = points[i];
  triangles_out = triangles;
  std::shuffle(triangles_out.begin(), triangles_out.end(), rng);
  for(Triangle& t : triangles_out) {
    for(std::size_t& v : t) v = perm[v];
    std::rotate(t.begin(), t.begin() + static_cast<std::ptrdiff_t>(rng() % 3), t.end());
  }
}

// ---------------------------------------------------------------------------------------------

Model load_model(const std::string& file, const std::string& name, double repair_relative_tolerance)
{
  Model m;
  m.name = name;
  soup_test::read_data_mesh(file, m.points, m.triangles);
  if(repair_relative_tolerance > 0) {
    // A CAD part whose patches are not welded: its own repair is the clean model.
    ST::reconstruct_topology(m.points, m.triangles, ST::parameters::relative_tolerance(repair_relative_tolerance));
  }
  double lo[3], hi[3];
  for(int k = 0; k < 3; ++k) { lo[k] = std::numeric_limits<double>::infinity(); hi[k] = -lo[k]; }
  for(const Point& p : m.points)
    for(int k = 0; k < 3; ++k) { lo[k] = std::min(lo[k], p[k]); hi[k] = std::max(hi[k], p[k]); }
  for(std::size_t k = 0; k < 3; ++k) m.centre[k] = (lo[k] + hi[k]) / 2;
  m.diagonal = ST::internal::bounding_box_diagonal(m.points, CGAL::Identity_property_map<Point>());
  return m;
}

struct Row_writer
{
  std::ofstream csv;
  explicit Row_writer(const std::string& path) : csv(path)
  {
    csv << "mesh,input_triangles,perturbation,seed,theta_deg,kernel,tolerance_factor,relative_tolerance,"
           "relative_displacement,closed,border_edges,non_manifold_edges,components,degenerate,flipped,"
           "inconsistent_edges,ambiguous_sites,snapped,split_triangles,refused_welds,refused_splits,"
           "same_as_reference,order_independent,correct,time_ms,small_features,collapsed_triangles,"
           "refused_uncovered_collapse,valid\n";
  }
};

} // namespace

int main(int argc, char** argv)
{
  std::string out_path = "results.csv";
  bool quick = false;
  ST::Small_features policy = ST::Small_features::COLLAPSE;
  for(int i = 1; i < argc; ++i) {
    if(std::strcmp(argv[i], "--quick") == 0) {
      quick = true;
    } else if(std::strcmp(argv[i], "--small-features") == 0 && i + 1 < argc) {
      const std::string value = argv[++i];
      if(value != "collapse" && value != "refuse") {
        std::fprintf(stderr, "robustness_experiment: --small-features takes collapse or refuse\n");
        return 2;
      }
      policy = value == "collapse" ? ST::Small_features::COLLAPSE : ST::Small_features::REFUSE;
    } else {
      out_path = argv[i];
    }
  }
  const char* policy_name = policy == ST::Small_features::COLLAPSE ? "collapse" : "refuse";
  try {
    std::vector<Model> models;
    models.push_back(load_model("clean/elephant.off", "elephant", 0));
    models.push_back(load_model("clean/fandisk.off.xz", "fandisk", 0));
    models.push_back(load_model("cad/ALSTOM_TEST4.off", "ALSTOM_TEST4", 1e-4));
    if(quick) models.resize(1);
    std::vector<double> thetas;
    for(int e = -1; e >= -12; --e) thetas.push_back(std::pow(10.0, e));
    unsigned seeds = 3;
    if(quick) { thetas = {1e-1, 1e-6, 1e-12}; seeds = 1; }
    const double factors[] = {0.5, 2.0, 10.0};
    const char* kernels[] = {"Simple_cartesian<double>", "Epick", "Epeck", "Simple_cartesian<Exact_rational>"};
    Row_writer writer(out_path);
    const auto start = std::chrono::steady_clock::now();

    for(const Model& model : models) {
      const int slabs = 6;
      const Base_soup base = make_base_soup(model, slabs);
      // The reference: the unperturbed soup repaired with exact constructions and a tiny tolerance.
      std::vector<Coordinates> base_coordinates;
      for(const Point& p : base.points) base_coordinates.push_back(coordinates(p));
      const Output ref = run<Epeck>(base_coordinates, base.triangles, 1e-9 * model.diagonal, policy);
      std::map<Coordinates, std::size_t> base_ids;
      for(std::size_t i = 0; i < base_coordinates.size(); ++i) base_ids.emplace(base_coordinates[i], base.id[i]);
      std::vector<std::size_t> ref_id(ref.points.size());
      for(std::size_t i = 0; i < ref.points.size(); ++i) ref_id[i] = base_ids.at(ref.points[i]);
      const std::vector<Triangle> reference = canonical_topology(ref.triangles, ref_id);
      const std::size_t reference_inconsistent_edges =
        ST::Adjacency_tables(ref.triangles, ref.points.size()).inconsistently_oriented_edges().size();
      std::printf("%s: %zu triangles, %zu soup points in %d pieces -> reference: %zu triangles, %zu border, "
                  "%zu non-manifold, %zu components\n",
                  model.name.c_str(), base.triangles.size(), base.points.size(), base.pieces, ref.triangles.size(),
                  ref.report.border_edges_after, ref.report.non_manifold_edges_after, ref.report.components);

      std::vector<Perturbed> perturbations;
      for(unsigned seed = 0; seed < seeds; ++seed)
        for(std::size_t k = 0; k < thetas.size(); ++k) {
          perturbations.push_back(rotate_patches(base, model, thetas[k], 1000u * (seed + 1) + static_cast<unsigned>(k)));
          perturbations.back().seed = seed;
        }
      perturbations.push_back(round_to_float(base));

      for(const Perturbed& pert : perturbations) {
        std::map<Coordinates, std::size_t> ids;
        for(std::size_t i = 0; i < pert.points.size(); ++i) ids.emplace(pert.points[i], base.id[i]);
        std::vector<Coordinates> shuffled_points;
        std::vector<Triangle> shuffled_triangles;
        shuffle_soup(pert.points, base.triangles, 7u, shuffled_points, shuffled_triangles);
        for(int kernel = 0; kernel < 4; ++kernel)
          for(double factor : factors) {
            const double eps = factor * pert.largest_displacement;
            Output a, b;
            switch(kernel) {
              case 0: a = run<Double_kernel>(pert.points, base.triangles, eps, policy);
                      b = run<Double_kernel>(shuffled_points, shuffled_triangles, eps, policy); break;
              case 1: a = run<Epick>(pert.points, base.triangles, eps, policy);
                      b = run<Epick>(shuffled_points, shuffled_triangles, eps, policy); break;
              case 2: a = run<Epeck>(pert.points, base.triangles, eps, policy);
                      b = run<Epeck>(shuffled_points, shuffled_triangles, eps, policy); break;
              default: a = run<Rational_kernel>(pert.points, base.triangles, eps, policy);
                       b = run<Rational_kernel>(shuffled_points, shuffled_triangles, eps, policy); break;
            }
            const Checks c = check(a, ids, base, reference);
            const bool order_independent = canonical_geometry(a) == canonical_geometry(b);
            const ST::Reconstruction_report& r = a.report;
            // The inconsistently oriented edges of the reference are the model's own (ALSTOM_TEST4's
            // CAD patches are not all oriented alike); the comparison with the reference checks the
            // orientation of every triangle anyway.
            const bool correct = c.same_as_reference && order_independent && c.degenerate == 0 && c.flipped == 0 &&
                                 c.inconsistent_edges == reference_inconsistent_edges &&
                                 r.non_manifold_edges_after == 0 && c.unknown_points == 0;
            const bool valid = order_independent && c.degenerate == 0 && c.flipped == 0 &&
                               c.inconsistent_edges == reference_inconsistent_edges &&
                               r.non_manifold_edges_after == 0 && c.unknown_points == 0 &&
                               r.border_edges_after == ref.report.border_edges_after;
            std::ostringstream row;
            row.precision(3);
            row << model.name << ',' << base.triangles.size() << ',' << pert.kind << ',' << pert.seed << ','
                << pert.theta << ',' << kernels[kernel] << ',' << factor << ',' << eps / model.diagonal << ','
                << pert.largest_displacement / model.diagonal << ',' << (r.closed() ? 1 : 0) << ','
                << r.border_edges_after << ',' << r.non_manifold_edges_after << ',' << r.components << ','
                << c.degenerate << ',' << c.flipped << ',' << c.inconsistent_edges << ',' << r.ambiguous_sites << ','
                << r.snapped_vertices << ',' << r.split_triangles << ',' << r.refused_welds() << ','
                << r.refused_splits << ',' << (c.same_as_reference ? 1 : 0) << ',' << (order_independent ? 1 : 0)
                << ',' << (correct ? 1 : 0) << ',';
            row.precision(4);
            row << std::min(a.milliseconds, b.milliseconds) << ',' << policy_name << ','
                << r.small_feature_collapsed_triangles << ',' << r.refused_uncovered_collapse << ',' << (valid ? 1 : 0)
                << '\n';
            writer.csv << row.str();
            writer.csv.flush();
            if(!correct)
              std::printf("  not correct: %s %s seed %u theta=%g %s x%g: border %zu, nm %zu, degenerate %zu, flipped %zu, "
                          "inconsistent %zu, same %d, order-independent %d, collapsed %zu, valid %d\n",
                          model.name.c_str(), pert.kind.c_str(), pert.seed, pert.theta, kernels[kernel], factor,
                          r.border_edges_after, r.non_manifold_edges_after, c.degenerate, c.flipped,
                          c.inconsistent_edges, c.same_as_reference ? 1 : 0, order_independent ? 1 : 0,
                          r.small_feature_collapsed_triangles, valid ? 1 : 0);
          }
      }
      std::printf("  %s done after %.1f s\n", model.name.c_str(),
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      std::fflush(stdout);
    }
  } catch(const std::exception& e) {
    std::fprintf(stderr, "robustness_experiment: %s\n", e.what());
    return 2;
  }
  return 0;
}
