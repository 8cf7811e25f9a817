// Node generation on walkable surfaces and node files.
#include <attenuvis/visgraph/nodes.hpp>
#include <attenuvis/visgraph/geojson.hpp>
#include <attenuvis/visgraph/ground.hpp>
#include <attenuvis/visgraph/limits.hpp>
#include <attenuvis/visgraph/mesh.hpp>
#include <attenuvis/visgraph/terrain.hpp>
#include <attenuvis/visgraph/work_estimate.hpp>

#include <attenuvis/io/input_file.hpp>
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

std::vector<std::string> default_walkable_classes() {
  return {"TINRelief", "Road", "TransportSquare", "Square", "LandUse", "TrafficArea", "AuxiliaryTrafficArea",
          "GroundSurface", kGroundPlaneClass, kInferredGroundClass, kTerrainClass};
}

namespace {

// Which surfaces count as walkable, and by which rule (nodes.hpp).
struct Walkable {
  bool lowest_surface = false;  // the rule for scenes without classes
  std::vector<char> group, cls;  // first-surface rule: walkable groups / classes
  std::string rule;
};

Walkable resolve_walkable(const Scene& scene, const std::vector<std::string>& names) {
  const auto& groups = scene.groups();
  const auto& classes = scene.classes();
  Walkable w;
  w.group.assign(groups.size(), 0);
  w.cls.assign(classes.size(), 0);
  if (names.empty() && classes.empty()) {
    w.lowest_surface = true;
    w.rule = "lowest surface under each cell, outside closed solids (the scene has no surface classes)";
    return w;
  }
  const bool by_default = names.empty();
  const std::vector<std::string> wanted = by_default ? default_walkable_classes() : names;
  std::vector<std::string> found;
  for (const std::string& name : wanted) {
    bool known = false;
    if (name == "*") {
      std::fill(w.group.begin(), w.group.end(), 1);
      known = true;
    }
    for (std::size_t g = 0; g < groups.size(); ++g)
      if (groups[g].name == name) w.group[g] = 1, known = true;
    for (std::size_t c = 0; c < classes.size(); ++c)
      if (classes[c].name == name) w.cls[c] = 1, known = true;
    if (known) found.push_back(name);
    if (!known && !by_default) {
      std::vector<std::string> group_names, class_names;
      for (const GroupInfo& g : groups) group_names.push_back(g.name);
      for (const GroupInfo& c : classes) class_names.push_back(c.name);
      throw std::invalid_argument(
          "node grid: walkable '" + name + "' is neither a group nor a class of the scene (" +
          std::to_string(groups.size()) + " groups: " +
          preview_names(group_names, 5, "(`attenuvis scene info SCENE --groups` lists them)") +
          (classes.empty() ? std::string() : "; classes: " + preview_names(class_names, 20)) + ")");
    }
  }
  w.rule = std::string(by_default ? "default walkable classes present: " : "walkable: ") + preview_names(found, 12) +
           "; first surface under each cell";
  return w;
}

// Every surface the vertical through a cell centre meets, top down.
struct Crossing {
  double z;  // local frame
  Eigen::Vector3d normal;
  std::uint32_t triangle;
};

std::vector<Crossing> crossings(const Scene& scene, const Eigen::Vector3d& start, double depth) {
  std::vector<Crossing> out;
  double t = 0.0;
  // Steps of 1 mm past each hit: coincident surfaces (a building's floor on
  // the ground) are met once, which is all the parity test needs.
  for (int k = 0; k < 256; ++k) {
    const Scene::Hit hit = scene.intersect(start, Eigen::Vector3d(0, 0, -1), t, depth);
    if (!hit.found) break;
    out.push_back({start.z() - hit.t, hit.normal, hit.triangle});
    t = hit.t + 1e-3;
  }
  return out;
}

enum class Outcome { node, no_surface, covered, too_steep, no_headroom };

struct Cell {
  Outcome outcome = Outcome::no_surface;
  Eigen::Vector2d cell_xy{0, 0};  // world
  Eigen::Vector3d eye;
  std::uint32_t triangle = 0;
  double elevation = 0;  // standing surface above the lowest surface
};

// The surface index (into `c`) people stand on, or -1 if the cell is covered.
std::ptrdiff_t standing_surface(const Walkable& w, const Scene& scene, const std::vector<Crossing>& c,
                                double eye_height) {
  if (!w.lowest_surface) {
    const std::uint32_t t = c.front().triangle;
    const std::uint32_t cls = scene.triangle_class(t);
    const bool ok = w.group[scene.triangle_group(t)] || (cls != Scene::kNoClass && w.cls[cls]);
    return ok ? 0 : -1;
  }
  // Lowest surface, then up through surfaces stacked within 0.5 m of it.
  std::size_t s = c.size() - 1;
  while (s > 0 && c[s - 1].z - c[s].z <= 0.5) --s;
  const double eye_z = c[s].z + eye_height;
  std::size_t above = 0;
  for (const Crossing& x : c) above += x.z > eye_z;
  return above % 2 == 0 ? static_cast<std::ptrdiff_t>(s) : -1;
}

Cell place(const Scene& scene, const Walkable& w, const NodeGridOptions& o, const Eigen::Vector3d& start,
           double depth, double cos_max_slope) {
  Cell cell;
  const std::vector<Crossing> c = crossings(scene, start, depth);
  if (c.empty()) return cell;
  const std::ptrdiff_t s = standing_surface(w, scene, c, o.eye_height);
  if (s < 0) {
    cell.outcome = Outcome::covered;
    return cell;
  }
  const Crossing& surface = c[static_cast<std::size_t>(s)];
  if (std::abs(surface.normal.z()) < cos_max_slope - 1e-12) {
    cell.outcome = Outcome::too_steep;
    return cell;
  }
  const Eigen::Vector3d ground(start.x(), start.y(), surface.z);
  const Eigen::Vector3d eye = ground + Eigen::Vector3d(0, 0, o.eye_height);
  // Headroom: nothing between 1 mm above the surface and the eye.
  if (o.eye_height > 2e-3 && scene.occluded(ground, eye, 1e-3)) {
    cell.outcome = Outcome::no_headroom;
    return cell;
  }
  cell.outcome = Outcome::node;
  cell.eye = scene.to_world(eye);
  cell.triangle = surface.triangle;
  cell.elevation = surface.z - c.back().z;
  return cell;
}

void check_grid_options(const NodeGridOptions& options) {
  check_range(options.spacing, kMinSpacing, kMaxSpacing, "node grid: spacing", "m");
  check_range(options.eye_height, 0.0, kMaxEyeHeight, "node grid: eye height", "m");
  check_range(options.max_slope_deg, 0.0, 90.0, "node grid: max slope", "degrees");
}

}  // namespace

GridEstimate estimate_grid(const Scene& scene, double spacing) {
  check_range(spacing, kMinSpacing, kMaxSpacing, "node grid: spacing", "m");
  const Eigen::Vector3d extent = scene.bounds().extent();
  // The tiny allowance keeps 50 m / 1 m at exactly 50 cells despite rounding.
  const auto cells_along = [&](double length) { return std::max(1.0, std::ceil(length / spacing - 1e-9)); };
  GridEstimate e;
  e.nx = cells_along(extent.x());
  e.ny = cells_along(extent.y());
  e.cells = e.nx * e.ny;
  e.bytes = e.cells * static_cast<double>(sizeof(Cell) + sizeof(Eigen::Vector3d));
  return e;
}

NodeSet generate_nodes(const Scene& scene, const NodeGridOptions& options) {
  check_grid_options(options);
  const GridEstimate estimate = estimate_grid(scene, options.spacing);
  if (options.max_cells > 0 && estimate.cells > options.max_cells)
    throw std::invalid_argument("node grid: spacing " + io::shortest(options.spacing) + " m gives " +
                                io::significant(estimate.nx, 3) + " x " + io::significant(estimate.ny, 3) + " = " +
                                io::significant(estimate.cells, 3) + " cells (" +
                                io::significant(estimate.bytes / 1e9, 3) + " GB), more than the limit of " +
                                io::significant(options.max_cells, 3) + ": choose a larger spacing");
  // No limit lifts the machine's memory: a grid that cannot fit is refused
  // here rather than by a terabyte allocation (std::bad_alloc, or an abort
  // under AddressSanitizer).
  const double memory = physical_memory_bytes();
  if (memory > 0 && estimate.bytes > memory)
    throw std::invalid_argument("node grid: spacing " + io::shortest(options.spacing) + " m gives " +
                                io::significant(estimate.cells, 3) + " cells needing " +
                                io::significant(estimate.bytes / 1e9, 3) + " GB, more than this machine's " +
                                io::significant(memory / 1e9, 3) + " GB: choose a larger spacing");
  const Walkable walkable = resolve_walkable(scene, options.walkable);
  const double cos_max_slope =
      std::cos(std::min(options.max_slope_deg, 90.0) * boost::math::constants::pi<double>() / 180.0);
  const BoundingBox& box = scene.bounds();
  const Eigen::Vector3d extent = box.extent();
  // Cells of pitch `spacing` covering the footprint (estimate_grid).
  const long nx = static_cast<long>(estimate.nx), ny = static_cast<long>(estimate.ny);
  const double top = scene.to_local(box.max).z() + 1.0;
  const double depth = extent.z() + 2.0;
  std::vector<std::vector<Cell>> rows(static_cast<std::size_t>(ny));
  tbb::parallel_for(0L, ny, [&](long iy) {
    auto& row = rows[static_cast<std::size_t>(iy)];
    for (long ix = 0; ix < nx; ++ix) {
      Eigen::Vector3d start = scene.to_local(Eigen::Vector3d(box.min.x() + (ix + 0.5) * options.spacing,
                                                             box.min.y() + (iy + 0.5) * options.spacing, 0.0));
      start.z() = top;
      row.push_back(place(scene, walkable, options, start, depth, cos_max_slope));
      row.back().cell_xy = scene.to_world(start).head<2>();
    }
  });
  NodeSet set;
  set.spacing = options.spacing;
  set.cells = static_cast<std::size_t>(nx * ny);
  set.rule = walkable.rule;
  const bool by_class = !scene.classes().empty();
  std::vector<std::size_t> per(by_class ? scene.classes().size() : scene.groups().size(), 0);
  for (const auto& row : rows)
    for (const Cell& c : row) {
      switch (c.outcome) {
        case Outcome::no_surface: ++set.no_surface; break;
        case Outcome::covered:
          ++set.covered;
          set.covered_cells.push_back(c.cell_xy);
          break;
        case Outcome::too_steep: ++set.too_steep; break;
        case Outcome::no_headroom: ++set.no_headroom; break;
        case Outcome::node:
          set.eyes.push_back(c.eye);
          ++per[by_class ? scene.triangle_class(c.triangle) : scene.triangle_group(c.triangle)];
          if (c.elevation > options.elevated_height) ++set.elevated;
          set.max_elevation = std::max(set.max_elevation, c.elevation);
          break;
      }
    }
  const auto& names = by_class ? scene.classes() : scene.groups();
  for (std::size_t k = 0; k < per.size(); ++k)
    if (per[k]) set.by_surface.push_back({names[k].name, per[k]});
  std::stable_sort(set.by_surface.begin(), set.by_surface.end(),
                   [](const SurfaceCount& a, const SurfaceCount& b) { return a.nodes > b.nodes; });
  return set;
}

bool found_ground(const Scene& scene, const NodeSet& grid) {
  if (scene.classes().empty()) return grid.eyes.size() > grid.no_surface;
  const std::vector<std::string> ground = default_walkable_classes();
  for (const GroupInfo& c : scene.classes())
    if (c.triangles > 0 && c.name != "GroundSurface" && std::find(ground.begin(), ground.end(), c.name) != ground.end())
      return true;
  return false;
}

std::vector<Eigen::Vector3d> read_nodes_csv(const std::string& path) {
  std::istringstream in(io::read_input_file(path, kMaxNodeFileBytes));
  std::vector<Eigen::Vector3d> nodes;
  std::string line;
  std::size_t number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.size() > kMaxLineBytes)
      throw std::runtime_error(path + ":" + std::to_string(number) + ": line of " + std::to_string(line.size()) +
                               " bytes, longer than the " + std::to_string(kMaxLineBytes) + " a node line may have");
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
    for (int c = 0; c < 3; ++c) check_coordinate(v[c], path + ":" + std::to_string(number));
    nodes.emplace_back(v[0], v[1], v[2]);
  }
  if (nodes.empty()) throw std::runtime_error("node file '" + path + "' holds no x,y,z rows");
  return nodes;
}

std::vector<Eigen::Vector3d> read_nodes(const std::string& path, std::string* crs) {
  if (crs) crs->clear();
  io::require_readable_input(path, kMaxNodeFileBytes);
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read node file '" + path + "'");
  char first = ' ';
  while (in.get(first) && std::isspace(static_cast<unsigned char>(first))) {
  }
  if (first != '{') return read_nodes_csv(path);
  GeoJsonPoints points = read_geojson_points(path);
  if (crs) *crs = points.crs;
  return std::move(points.points);
}

Eigen::Vector3d parse_point(const std::string& text) {
  const std::vector<std::string> fields = split_commas(text);
  double v[3];
  bool ok = fields.size() == 3;
  for (int c = 0; ok && c < 3; ++c) ok = parse_double(fields[static_cast<std::size_t>(c)], v[c]) && std::isfinite(v[c]);
  if (!ok) throw std::invalid_argument("expected a point 'x,y,z' of finite numbers, got '" + text + "'");
  for (int c = 0; c < 3; ++c) check_coordinate(v[c], "point '" + text + "'");
  return {v[0], v[1], v[2]};
}

}  // namespace attenuvis::visgraph
