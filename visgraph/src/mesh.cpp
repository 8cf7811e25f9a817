// Mesh bookkeeping and the small measures the `scene` command and the
// visibility-graph summary report (triangle count, bounding box, groups,
// projected areas).
#include <attenuvis/visgraph/mesh.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace attenuvis::visgraph {

namespace {
// Horizontal (xy-projected) area of triangle t: what a grid of nodes at 1 m
// spacing counts.  Absolute value so winding does not matter.
double projected_area(const Mesh& mesh, std::size_t t) {
  const auto& a = mesh.vertices[mesh.triangles[t][0]];
  const auto& b = mesh.vertices[mesh.triangles[t][1]];
  const auto& c = mesh.vertices[mesh.triangles[t][2]];
  return 0.5 * std::abs((b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x()));
}
}  // namespace

std::size_t Mesh::add_group(const std::string& name) {
  // Meshes have a handful of groups: a linear search is the simplest fast way.
  for (std::size_t i = 0; i < groups.size(); ++i)
    if (groups[i] == name) return i;
  groups.push_back(name);
  return groups.size() - 1;
}

std::size_t Mesh::add_class(const std::string& name) {
  for (std::size_t i = 0; i < classes.size(); ++i)
    if (classes[i] == name) return i;
  classes.push_back(name);
  return classes.size() - 1;
}

void add_ground_plane(Mesh& mesh, double margin) {
  if (mesh.triangles.empty()) return;
  add_ground_plane_at(mesh, mesh_stats(mesh).lower.z(), margin);
}

void add_ground_plane_at(Mesh& mesh, double z, double margin) {
  if (mesh.triangles.empty()) return;
  const MeshStats stats = mesh_stats(mesh);
  const double x0 = stats.lower.x() - margin, x1 = stats.upper.x() + margin;
  const double y0 = stats.lower.y() - margin, y1 = stats.upper.y() + margin;
  const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
  mesh.vertices.insert(mesh.vertices.end(), {{x0, y0, z}, {x1, y0, z}, {x1, y1, z}, {x0, y1, z}});
  mesh.triangles.push_back({base, base + 1, base + 2});  // counter-clockwise from above: normal +z
  mesh.triangles.push_back({base, base + 2, base + 3});
  const auto group = static_cast<std::uint32_t>(mesh.add_group(kGroundPlaneGroup));
  mesh.triangle_group.insert(mesh.triangle_group.end(), 2, group);
  if (!mesh.classes.empty()) {
    const auto cls = static_cast<std::uint32_t>(mesh.add_class(kGroundPlaneClass));
    mesh.triangle_class.insert(mesh.triangle_class.end(), 2, cls);
  }
}

std::string preview_names(const std::vector<std::string>& names, std::size_t shown, const std::string& more_hint) {
  std::string out;
  for (std::size_t i = 0; i < names.size() && i < shown; ++i) out += (i ? ", " : "") + names[i];
  if (names.size() > shown) {
    out += " ... and " + std::to_string(names.size() - shown) + " more";
    if (!more_hint.empty()) out += " " + more_hint;
  }
  return out;
}

double walkable_area(const Mesh& mesh, const std::vector<std::string>& groups) {
  std::vector<char> wanted(mesh.groups.size(), 0);
  for (std::size_t g = 0; g < mesh.groups.size(); ++g)
    wanted[g] = std::find(groups.begin(), groups.end(), mesh.groups[g]) != groups.end();
  double area = 0.0;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (wanted[mesh.triangle_group[t]]) area += projected_area(mesh, t);
  }
  return area;
}

MeshStats mesh_stats(const Mesh& mesh) {
  MeshStats stats;
  stats.vertices = mesh.vertices.size();
  stats.triangles = mesh.triangles.size();
  constexpr double inf = std::numeric_limits<double>::infinity();
  stats.lower = Eigen::Vector3d::Constant(inf);
  stats.upper = Eigen::Vector3d::Constant(-inf);
  for (const auto& tri : mesh.triangles)
    for (auto i : tri) {
      stats.lower = stats.lower.cwiseMin(mesh.vertices[i]);
      stats.upper = stats.upper.cwiseMax(mesh.vertices[i]);
    }
  stats.groups.resize(mesh.groups.size());
  for (std::size_t g = 0; g < mesh.groups.size(); ++g) stats.groups[g].name = mesh.groups[g];
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    auto& group = stats.groups[mesh.triangle_group[t]];
    ++group.triangles;
    group.projected_area += projected_area(mesh, t);
  }
  if (mesh.triangle_class.size() == mesh.triangles.size()) {
    stats.classes.resize(mesh.classes.size());
    for (std::size_t c = 0; c < mesh.classes.size(); ++c) stats.classes[c].name = mesh.classes[c];
    std::vector<std::vector<char>> has(mesh.groups.size(), std::vector<char>(mesh.classes.size(), 0));
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      auto& cls = stats.classes[mesh.triangle_class[t]];
      ++cls.triangles;
      cls.projected_area += projected_area(mesh, t);
      has[mesh.triangle_group[t]][mesh.triangle_class[t]] = 1;
    }
    for (std::size_t g = 0; g < mesh.groups.size(); ++g)
      for (std::size_t c = 0; c < mesh.classes.size(); ++c)
        if (has[g][c]) stats.groups[g].classes.push_back(mesh.classes[c]);
  }
  return stats;
}

}  // namespace attenuvis::visgraph
