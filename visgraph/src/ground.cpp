// Ground for models without terrain (ground.hpp): base points of buildings,
// the flat-or-not decision, the plane and the inferred TIN.
#include <attenuvis/visgraph/ground.hpp>

#include <attenuvis/io/number_text.hpp>

#include "planar.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>

namespace attenuvis::visgraph {

namespace {

// A wall: its normal within ~6 degrees of horizontal (|n_z| <= 0.1).
bool is_wall(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double length = n.norm();
  return length > 0 && std::abs(n.z()) <= 0.1 * length;
}

// The lower end of a vertical edge (ends within 1 mm in xy, at least 1 mm apart in z).
bool vertical_edge_foot(const Eigen::Vector3d& p, const Eigen::Vector3d& q, Eigen::Vector3d& foot) {
  if ((p.head<2>() - q.head<2>()).norm() > 1e-3 || std::abs(p.z() - q.z()) < 1e-3) return false;
  foot = p.z() < q.z() ? p : q;
  return true;
}

// Base points of each group, by the first rule that gives any (ground.hpp).
struct GroupBases {
  std::vector<std::vector<Eigen::Vector3d>> points;
  std::vector<char> rule;  // 'g' GroundSurface, 'w' walls, 'v' lowest vertex, 0 none
};

GroupBases bases_by_group(const Mesh& mesh) {
  GroupBases out;
  out.points.resize(mesh.groups.size());
  out.rule.assign(mesh.groups.size(), 0);
  const bool classed = mesh.triangle_class.size() == mesh.triangles.size();
  const auto ground = std::find(mesh.classes.begin(), mesh.classes.end(), "GroundSurface");
  const std::uint32_t ground_class =
      classed && ground != mesh.classes.end() ? static_cast<std::uint32_t>(ground - mesh.classes.begin()) : UINT32_MAX;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (mesh.triangle_class.empty() || mesh.triangle_class[t] != ground_class) continue;
    const std::uint32_t g = mesh.triangle_group[t];
    for (std::uint32_t v : mesh.triangles[t]) out.points[g].push_back(mesh.vertices[v]);
    out.rule[g] = 'g';
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const std::uint32_t g = mesh.triangle_group[t];
    if (out.rule[g] == 'g') continue;
    const auto& tri = mesh.triangles[t];
    const Eigen::Vector3d& a = mesh.vertices[tri[0]];
    const Eigen::Vector3d& b = mesh.vertices[tri[1]];
    const Eigen::Vector3d& c = mesh.vertices[tri[2]];
    if (!is_wall(a, b, c)) continue;
    Eigen::Vector3d foot;
    for (const auto& [p, q] : {std::make_pair(a, b), std::make_pair(b, c), std::make_pair(c, a)})
      if (vertical_edge_foot(p, q, foot)) {
        out.points[g].push_back(foot);
        out.rule[g] = 'w';
      }
  }
  // Neither: the group's lowest vertex.
  std::vector<double> lowest(mesh.groups.size(), std::numeric_limits<double>::infinity());
  std::vector<std::uint32_t> lowest_vertex(mesh.groups.size(), 0);
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (std::uint32_t v : mesh.triangles[t]) {
      const std::uint32_t g = mesh.triangle_group[t];
      if (mesh.vertices[v].z() < lowest[g]) lowest[g] = mesh.vertices[v].z(), lowest_vertex[g] = v;
    }
  for (std::size_t g = 0; g < mesh.groups.size(); ++g)
    if (!out.rule[g] && std::isfinite(lowest[g])) {
      out.points[g].push_back(mesh.vertices[lowest_vertex[g]]);
      out.rule[g] = 'v';
    }
  return out;
}

std::string metres(double value) { return io::significant(value, 6) + " m"; }

}  // namespace

BuildingBases building_bases(const Mesh& mesh) {
  const GroupBases by_group = bases_by_group(mesh);
  BuildingBases bases;
  // One point per footprint position (xy to 1 mm), the lowest base there:
  // neighbours sharing a party wall may give the same corner two heights.
  std::map<std::pair<std::int64_t, std::int64_t>, Eigen::Vector3d> by_position;
  for (std::size_t g = 0; g < by_group.points.size(); ++g) {
    if (by_group.points[g].empty()) continue;
    double base = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& p : by_group.points[g]) {
      base = std::min(base, p.z());
      const auto key = std::make_pair(std::llround(p.x() * 1e3), std::llround(p.y() * 1e3));
      const auto [it, added] = by_position.emplace(key, p);
      if (!added && p.z() < it->second.z()) it->second = p;
    }
    bases.building_base.push_back(base);
    bases.building_group.push_back(static_cast<std::uint32_t>(g));
    bases.from_ground_surface += by_group.rule[g] == 'g';
    bases.from_walls += by_group.rule[g] == 'w';
    bases.from_lowest_vertex += by_group.rule[g] == 'v';
  }
  bases.points.reserve(by_position.size());
  for (const auto& entry : by_position) bases.points.push_back(entry.second);
  if (!bases.points.empty()) {
    bases.lowest = bases.highest = bases.points.front().z();
    for (const Eigen::Vector3d& p : bases.points) {
      bases.lowest = std::min(bases.lowest, p.z());
      bases.highest = std::max(bases.highest, p.z());
    }
  }
  return bases;
}

std::size_t add_inferred_ground(Mesh& mesh, const BuildingBases& bases) {
  std::vector<Eigen::Vector2d> xy;
  xy.reserve(bases.points.size());
  for (const Eigen::Vector3d& p : bases.points) xy.push_back(p.head<2>());
  const auto triangles = detail::delaunay_triangles(xy);
  if (triangles.empty())
    throw std::invalid_argument("cannot infer the ground: the " + std::to_string(bases.points.size()) +
                                " building base points do not span an area (fewer than three, or all on one line)");
  const auto first = static_cast<std::uint32_t>(mesh.vertices.size());
  mesh.vertices.insert(mesh.vertices.end(), bases.points.begin(), bases.points.end());
  const auto group = static_cast<std::uint32_t>(mesh.add_group(kInferredGroundGroup));
  const bool classed = !mesh.classes.empty();
  const auto cls = classed ? static_cast<std::uint32_t>(mesh.add_class(kInferredGroundClass)) : 0u;
  for (const auto& t : triangles) {
    mesh.triangles.push_back({first + t[0], first + t[1], first + t[2]});  // counter-clockwise: facing up
    mesh.triangle_group.push_back(group);
    if (classed) mesh.triangle_class.push_back(cls);
  }
  return triangles.size();
}

namespace {

std::size_t floating_above(const BuildingBases& bases, double plane_z, double eye_height) {
  return static_cast<std::size_t>(std::count_if(bases.building_base.begin(), bases.building_base.end(),
                                                [&](double base) { return base - plane_z > eye_height; }));
}

std::string base_range(const BuildingBases& bases) {
  return "the bases of the " + std::to_string(bases.building_base.size()) + " buildings lie from " +
         metres(bases.lowest) + " to " + metres(bases.highest) + " (" + metres(bases.highest - bases.lowest) +
         " apart)";
}

GroundMade inferred(Mesh& mesh, const BuildingBases& bases) {
  GroundMade made;
  made.inferred = true;
  made.triangles = add_inferred_ground(mesh, bases);
  made.points = bases.points.size();
  made.description = "a TIN inferred from " + std::to_string(bases.building_base.size()) + " building bases (" +
                     std::to_string(bases.points.size()) + " footprint points at z = " + io::significant(bases.lowest, 6) +
                     " to " + metres(bases.highest) + "; Delaunay, over their convex hull)";
  return made;
}

}  // namespace

GroundMade add_ground(Mesh& mesh, const GroundRequest& request) {
  const BuildingBases bases = building_bases(mesh);
  const double lowest_z = mesh.triangles.empty() ? 0.0 : mesh_stats(mesh).lower.z();
  GroundMade made;
  switch (request.rule) {
    case GroundRule::automatic: {
      if (!bases.points.empty() && bases.highest - lowest_z > kFlatBaseTolerance) {
        made = inferred(mesh, bases);
        break;
      }
      add_ground_plane_at(mesh, lowest_z);
      made.plane_z = lowest_z;
      made.description = "a horizontal ground plane at z = " + metres(lowest_z) + ", the model's lowest (" +
                         (bases.points.empty() ? std::string("no building bases found")
                                               : "every building base within " + metres(kFlatBaseTolerance) + " of it") +
                         ")";
      break;
    }
    case GroundRule::lowest_plane: {
      made.floating = floating_above(bases, lowest_z, request.eye_height);
      if (made.floating > 0)
        throw std::invalid_argument(
            "a ground plane at the model's lowest z (" + metres(lowest_z) + ") would leave eye points below " +
            std::to_string(made.floating) + " buildings: " + base_range(bases) + ", and " +
            std::to_string(made.floating) + " of them stand more than the eye height (" +
            metres(request.eye_height) + ") above the plane");
      add_ground_plane_at(mesh, lowest_z);
      made.plane_z = lowest_z;
      made.description = "a horizontal ground plane at z = " + metres(lowest_z) + ", the model's lowest (as asked)";
      break;
    }
    case GroundRule::plane_at: {
      add_ground_plane_at(mesh, request.plane_z);
      made.plane_z = request.plane_z;
      made.floating = floating_above(bases, request.plane_z, request.eye_height);
      made.description = "a horizontal ground plane at z = " + metres(request.plane_z) + " (as asked)";
      break;
    }
  }
  made.buildings = bases.building_base.size();
  made.lowest = bases.lowest;
  made.highest = bases.highest;
  return made;
}

}  // namespace attenuvis::visgraph
