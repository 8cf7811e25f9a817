// Node generation on walkable surfaces and node files.
#include <attenuvis/visgraph/nodes.hpp>

#include <attenuvis/io/number_text.hpp>

#include <boost/math/constants/constants.hpp>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace attenuvis::visgraph {

namespace {
// A CSV field as a finite double (surrounding blanks allowed); false if it
// is not one.
bool parse_double(const std::string& field, double& value) {
  const auto first = field.find_first_not_of(" \t");
  if (first == std::string::npos) return false;
  const auto last = field.find_last_not_of(" \t");
  try {
    value = io::parse_double(std::string_view(field).substr(first, last - first + 1), "coordinate");
  } catch (const std::invalid_argument&) {
    return false;
  }
  return true;
}

std::vector<std::string> split_commas(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}
}  // namespace

NodeSet generate_nodes(const Scene& scene, const NodeGridOptions& options) {
  if (!(options.spacing > 0) || !std::isfinite(options.spacing))
    throw std::invalid_argument("node grid: spacing must be a positive number of metres");
  if (!(options.eye_height >= 0) || !std::isfinite(options.eye_height))
    throw std::invalid_argument("node grid: eye height must be a non-negative number of metres");
  const auto& groups = scene.groups();
  std::vector<char> walkable(groups.size(), options.walkable.empty() ? 1 : 0);
  for (const std::string& name : options.walkable) {
    auto it = std::find_if(groups.begin(), groups.end(), [&](const GroupInfo& g) { return g.name == name; });
    if (it == groups.end()) {
      std::string known;
      for (const GroupInfo& g : groups) known += (known.empty() ? "" : ", ") + g.name;
      throw std::invalid_argument("node grid: walkable group '" + name + "' is not in the scene (groups: " + known +
                                  ")");
    }
    walkable[static_cast<std::size_t>(it - groups.begin())] = 1;
  }
  const double cos_max_slope = std::cos(std::min(options.max_slope_deg, 90.0) * boost::math::constants::pi<double>() / 180.0);

  const BoundingBox& box = scene.bounds();
  const Eigen::Vector3d extent = box.extent();
  // Cells of pitch `spacing` covering the footprint; the tiny allowance keeps
  // 50 m / 1 m at exactly 50 cells despite rounding.
  const auto cells_along = [&](double length) {
    return std::max<long>(1, static_cast<long>(std::ceil(length / options.spacing - 1e-9)));
  };
  const long nx = cells_along(extent.x()), ny = cells_along(extent.y());
  const double top = scene.to_local(box.max).z() + 1.0;
  const double depth = extent.z() + 2.0;

  struct Row {
    std::vector<Eigen::Vector3d> eyes;
    std::size_t no_surface = 0, covered = 0, too_steep = 0, no_headroom = 0;
  };
  std::vector<Row> rows(static_cast<std::size_t>(ny));
  tbb::parallel_for(0L, ny, [&](long iy) {
    Row& row = rows[static_cast<std::size_t>(iy)];
    for (long ix = 0; ix < nx; ++ix) {
      const Eigen::Vector3d cell_world(box.min.x() + (ix + 0.5) * options.spacing,
                                       box.min.y() + (iy + 0.5) * options.spacing, 0.0);
      Eigen::Vector3d start = scene.to_local(cell_world);
      start.z() = top;
      const Scene::Hit hit = scene.intersect(start, Eigen::Vector3d(0, 0, -1), 0.0, depth);
      if (!hit.found) {
        ++row.no_surface;
        continue;
      }
      if (!walkable[scene.triangle_group(hit.triangle)]) {
        ++row.covered;
        continue;
      }
      if (std::abs(hit.normal.z()) < cos_max_slope - 1e-12) {
        ++row.too_steep;
        continue;
      }
      const Eigen::Vector3d surface = start - Eigen::Vector3d(0, 0, hit.t);
      const Eigen::Vector3d eye = surface + Eigen::Vector3d(0, 0, options.eye_height);
      // Headroom: nothing between 1 mm above the surface and the eye.
      if (options.eye_height > 2e-3 && scene.occluded(surface, eye, 1e-3)) {
        ++row.no_headroom;
        continue;
      }
      row.eyes.push_back(scene.to_world(eye));
    }
  });
  NodeSet set;
  set.cells = static_cast<std::size_t>(nx * ny);
  for (const Row& row : rows) {
    set.eyes.insert(set.eyes.end(), row.eyes.begin(), row.eyes.end());
    set.no_surface += row.no_surface;
    set.covered += row.covered;
    set.too_steep += row.too_steep;
    set.no_headroom += row.no_headroom;
  }
  return set;
}

std::vector<Eigen::Vector3d> read_nodes_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read node file '" + path + "'");
  std::vector<Eigen::Vector3d> nodes;
  std::string line;
  std::size_t number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos || line[line.find_first_not_of(" \t")] == '#') continue;
    const std::vector<std::string> fields = split_commas(line);
    double v[3];
    bool ok = fields.size() >= 3;
    for (int c = 0; ok && c < 3; ++c) ok = parse_double(fields[static_cast<std::size_t>(c)], v[c]);
    if (!ok) {
      if (nodes.empty() && number == 1) continue;  // header line
      throw std::runtime_error(path + ":" + std::to_string(number) + ": expected x,y,z, got '" + line + "'");
    }
    if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
      throw std::runtime_error(path + ":" + std::to_string(number) + ": coordinate is not finite");
    nodes.emplace_back(v[0], v[1], v[2]);
  }
  if (nodes.empty()) throw std::runtime_error("node file '" + path + "' holds no x,y,z rows");
  return nodes;
}

Eigen::Vector3d parse_point(const std::string& text) {
  const std::vector<std::string> fields = split_commas(text);
  double v[3];
  bool ok = fields.size() == 3;
  for (int c = 0; ok && c < 3; ++c) ok = parse_double(fields[static_cast<std::size_t>(c)], v[c]) && std::isfinite(v[c]);
  if (!ok) throw std::invalid_argument("expected a point 'x,y,z' of finite numbers, got '" + text + "'");
  return {v[0], v[1], v[2]};
}

}  // namespace attenuvis::visgraph
