// Accuracy and cost of the ground inferred under a hilly model published as
// buildings only (visgraph/ground.hpp), on the synthetic hillside town
// (hillside.hpp: a 20 % slope with a ridge, every building's base on the
// known ground) at each size asked for:
//  1. node heights against the true ground: largest and mean |error|, and
//     how many nodes lie within the interpolation bound M R^2 / 2 of the TIN
//     triangle under them;
//  2. lines of sight: random node pairs decided by the pass (Embree) against
//     the independent double-precision segment test the Catch2 tests use,
//     over every triangle (buildings and ground);
//  3. times, each against the same step on the flat plane the model used to
//     get (the baseline, in the same run, whose eyes stand under most
//     buildings): adding the ground, placing the nodes, the visibility pass.
//
// Usage: hillside_ground [--sizes 200,400] [--spacing 2] [--pass-spacing 4] [--pairs 2000]
#include <attenuvis/visgraph/ground.hpp>
#include <attenuvis/visgraph/hillside.hpp>
#include <attenuvis/visgraph/nodes.hpp>
#include <attenuvis/visgraph/scene.hpp>
#include <attenuvis/visgraph/visibility.hpp>

// The random lines of sight of the visgraph tests, shared so that the
// figures here come from the same independent check.
#include "../../tests/visgraph/sight_check.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

namespace vg = attenuvis::visgraph;

namespace {

struct Arguments {
  std::vector<double> sizes = {200, 400};
  double spacing = 2, pass_spacing = 4;
  int pairs = 2000;
};

Arguments parse(int argc, char** argv) {
  Arguments a;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string option = argv[i], value = argv[i + 1];
    if (option == "--sizes") {
      a.sizes.clear();
      std::stringstream in(value);
      for (std::string s; std::getline(in, s, ',');) a.sizes.push_back(std::stod(s));
    } else if (option == "--spacing") {
      a.spacing = std::stod(value);
    } else if (option == "--pass-spacing") {
      a.pass_spacing = std::stod(value);
    } else if (option == "--pairs") {
      a.pairs = std::stoi(value);
    } else {
      std::fprintf(stderr, "usage: hillside_ground [--sizes 200,400] [--spacing 2] [--pass-spacing 4] [--pairs 2000]\n");
      std::exit(2);
    }
  }
  return a;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Smallest enclosing circle radius of a triangle's xy.
double enclosing_radius(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& r) {
  const double a = (q - r).head<2>().norm(), b = (p - r).head<2>().norm(), c = (p - q).head<2>().norm();
  const double longest = std::max({a, b, c});
  if (2 * longest * longest >= a * a + b * b + c * c) return 0.5 * longest;
  const double area = 0.5 * std::abs((q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x()));
  return a * b * c / (4 * area);
}

// The interpolation bound under (x, y): M R^2 / 2 of the TIN triangle holding it.
double bound_at(const vg::Mesh& mesh, std::uint32_t tin_group, double M, double x, double y) {
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (mesh.triangle_group[t] != tin_group) continue;
    const auto& p = mesh.vertices[mesh.triangles[t][0]];
    const auto& q = mesh.vertices[mesh.triangles[t][1]];
    const auto& r = mesh.vertices[mesh.triangles[t][2]];
    const auto side = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
      return (b.x() - a.x()) * (y - a.y()) - (b.y() - a.y()) * (x - a.x());
    };
    if (side(p, q) >= -1e-9 && side(q, r) >= -1e-9 && side(r, p) >= -1e-9) return 0.5 * M * std::pow(enclosing_radius(p, q, r), 2);
  }
  return 0;
}

struct Timed {
  vg::Mesh mesh;
  double ground_s = 0, place_s = 0, pass_s = 0;
  std::size_t nodes = 0, pass_nodes = 0;
  double pairs = 0;
};

// Adds the ground asked for, places nodes at `spacing`, and runs the pass at `pass_spacing`.
Timed run(const vg::HillsideOptions& town, const vg::GroundRequest& request, const Arguments& a,
          std::vector<Eigen::Vector3d>& eyes) {
  Timed t;
  t.mesh = vg::hillside_town(town);
  auto start = std::chrono::steady_clock::now();
  vg::add_ground(t.mesh, request);
  t.ground_s = seconds_since(start);
  const vg::Scene scene(t.mesh);
  vg::NodeGridOptions grid;
  grid.spacing = a.spacing;
  start = std::chrono::steady_clock::now();
  eyes = vg::generate_nodes(scene, grid).eyes;
  t.place_s = seconds_since(start);
  t.nodes = eyes.size();
  grid.spacing = a.pass_spacing;
  const std::vector<Eigen::Vector3d> pass_eyes = vg::generate_nodes(scene, grid).eyes;
  vg::VisibilityOptions options;
  options.sigmas = {0.0, 0.01};
  start = std::chrono::steady_clock::now();
  const vg::VisibilityResult r = vg::all_to_all(scene, pass_eyes, options);
  t.pass_s = seconds_since(start);
  t.pass_nodes = pass_eyes.size();
  t.pairs = static_cast<double>(r.pairs_total);
  return t;
}

void one_size(double size, const Arguments& a) {
  vg::HillsideOptions town;
  town.size = size;
  std::vector<Eigen::Vector3d> eyes, plane_eyes;
  const Timed tin = run(town, {}, a, eyes);
  vg::GroundRequest plane_request;  // the plane at the lowest z
  plane_request.rule = vg::GroundRule::plane_at;
  plane_request.plane_z = vg::mesh_stats(vg::hillside_town(town)).lower.z();
  const Timed plane = run(town, plane_request, a, plane_eyes);
  std::printf("\nhillside town %.0f x %.0f m: %zu buildings, %zu triangles with the TIN\n", size, size,
              vg::building_bases(vg::hillside_town(town)).building_base.size(), tin.mesh.triangles.size());

  // 1. Heights against the true ground.
  const auto tin_group = static_cast<std::uint32_t>(
      std::find(tin.mesh.groups.begin(), tin.mesh.groups.end(), vg::kInferredGroundGroup) - tin.mesh.groups.begin());
  const double M = vg::hillside_curvature_bound(town);
  double worst = 0, sum = 0;
  std::size_t within = 0;
  for (const Eigen::Vector3d& e : eyes) {
    const double error = std::abs(e.z() - 1.7 - vg::hillside_ground(town, e.x(), e.y()));
    worst = std::max(worst, error);
    sum += error;
    within += error <= bound_at(tin.mesh, tin_group, M, e.x(), e.y()) + 1e-3;
  }
  std::printf("  nodes at %.3g m: %zu; |node ground - true ground|: max %.4f m, mean %.4f m; within M R^2/2 + 1 mm: %zu of %zu\n",
              a.spacing, eyes.size(), worst, sum / eyes.size(), within, eyes.size());

  // 2. Random lines of sight, pass against segment test.
  const vg::Scene scene(tin.mesh);
  const vgtest::SightCheck sight = vgtest::random_sight_lines(scene, tin.mesh, vg::hillside_town(town), eyes,
                                                               std::max(1, a.pairs / 780), 40, 30);
  std::printf("  lines of sight: %zu random pairs, %zu visible, %zu hidden by the ground alone; the pass agrees with "
              "the segment test on %zu (%.2f %%)\n",
              sight.pairs, sight.visible, sight.hidden_by_ground, sight.agree, 100.0 * sight.agree / sight.pairs);

  // 3. Times against the flat plane (baseline).
  std::printf("  %-28s %10s %10s %8s\n", "step", "TIN (s)", "plane (s)", "ratio");
  std::printf("  %-28s %10.4f %10.4f %8.2f\n", "add the ground", tin.ground_s, plane.ground_s, tin.ground_s / plane.ground_s);
  std::printf("  %-28s %10.4f %10.4f %8.2f\n", ("place nodes (" + std::to_string(tin.nodes) + " / " +
                                                 std::to_string(plane.nodes) + ")").c_str(),
              tin.place_s, plane.place_s, tin.place_s / plane.place_s);
  std::printf("  %-28s %10.4f %10.4f %8.2f\n", ("pass at " + std::to_string(static_cast<int>(a.pass_spacing)) + " m (" +
                                                 std::to_string(tin.pass_nodes) + " / " + std::to_string(plane.pass_nodes) + ")").c_str(),
              tin.pass_s, plane.pass_s, tin.pass_s / plane.pass_s);
}

}  // namespace

int main(int argc, char** argv) {
  const Arguments a = parse(argc, argv);
  std::printf("ground inferred under buildings-only hillside towns (20 %% slope, ridge curvature M = %.1e 1/m)\n",
              vg::hillside_curvature_bound({}));
  for (double size : a.sizes) one_size(size, a);
  return 0;
}
