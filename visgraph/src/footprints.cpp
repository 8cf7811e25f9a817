// Footprints extruded to prisms (footprints.hpp).
#include <attenuvis/visgraph/footprints.hpp>

#include <attenuvis/visgraph/detail/polygon.hpp>
#include <attenuvis/visgraph/limits.hpp>

#include <attenuvis/io/number_text.hpp>

#include "planar.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace attenuvis::visgraph {

namespace {

using Ring = std::vector<Eigen::Vector3d>;

// The ring without its closing repeat and consecutive repeats (xy), checked.
Ring clean_ring(const Ring& ring, const std::string& where) {
  if (ring.size() > kMaxPolygonVertices)
    throw std::invalid_argument(where + " has " + std::to_string(ring.size()) + " vertices, more than the " +
                                std::to_string(kMaxPolygonVertices) + " a ring may have: simplify it");
  Ring out;
  for (const Eigen::Vector3d& p : ring) {
    for (int c = 0; c < 3; ++c) check_coordinate(p[c], where);
    if (!out.empty() && p.head<2>() == out.back().head<2>()) continue;
    out.push_back(p);
  }
  while (out.size() > 1 && out.back().head<2>() == out.front().head<2>()) out.pop_back();
  if (out.size() < 3)
    throw std::invalid_argument(where + " has " + std::to_string(out.size()) +
                                " distinct vertices: a ring needs at least three");
  std::vector<Eigen::Vector2d> xy;
  xy.reserve(out.size());
  for (const Eigen::Vector3d& p : out) xy.push_back(p.head<2>());
  if (!detail::ring_is_simple(xy))
    throw std::invalid_argument(where + " intersects itself (or touches itself at a vertex): repair it, "
                                "e.g. with QGIS's Fix geometries or ogr2ogr -makevalid");
  return out;
}

double signed_area(const Ring& ring) {
  double a = 0;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Eigen::Vector3d& p = ring[i];
    const Eigen::Vector3d& q = ring[(i + 1) % ring.size()];
    a += p.x() * q.y() - q.x() * p.y();
  }
  return 0.5 * a;
}

// Builds one footprint's prism into the mesh.
class Extruder {
 public:
  Extruder(Mesh& mesh, const FootprintGround& ground, const std::string& source)
      : mesh_(mesh), ground_(ground), source_(source) {
    floor_ = static_cast<std::uint32_t>(mesh_.add_class("GroundSurface"));
    wall_ = static_cast<std::uint32_t>(mesh_.add_class("WallSurface"));
    roof_ = static_cast<std::uint32_t>(mesh_.add_class("RoofSurface"));
  }

  void add(const BuildingFootprint& f) {
    const std::string where = source_ + ": feature " + f.id;
    if (!(std::isfinite(f.height) && f.height > 0))
      throw std::invalid_argument(where + ": height " + io::significant(f.height, 6) + " is not a positive number of metres");
    std::vector<std::vector<Ring>> polygons;
    for (std::size_t p = 0; p < f.polygons.size(); ++p) {
      polygons.emplace_back();
      for (std::size_t r = 0; r < f.polygons[p].rings.size(); ++r) {
        Ring ring = clean_ring(f.polygons[p].rings[r], where + (f.polygons.size() > 1 ? ", polygon " + std::to_string(p) : "") +
                                                            (r == 0 ? ", outline" : ", hole " + std::to_string(r)));
        // Outline counter-clockwise, holes clockwise (seen from above): the
        // walls then face out of the building and the roof up.
        if ((signed_area(ring) > 0) != (r == 0)) std::reverse(ring.begin(), ring.end());
        polygons.back().push_back(std::move(ring));
      }
    }
    if (polygons.empty()) throw std::invalid_argument(where + ": no polygon");
    const double lowest = base_height(polygons, where);
    const double roof = lowest + f.height;
    group_ = static_cast<std::uint32_t>(mesh_.add_group(f.id));
    for (const auto& rings : polygons) {
      for (const Ring& ring : rings)
        for (const Eigen::Vector3d& p : ring)
          if (base_z(p) >= roof)
            throw std::invalid_argument(where + ": height " + io::significant(f.height, 6) + " m is less than the " +
                                        io::significant(base_z(p) - lowest, 4) + " m its base rises across the footprint");
      add_caps(rings, roof, where);
      for (const Ring& ring : rings) add_walls(ring, roof);
    }
  }

 private:
  // The floor's height under footprint vertex p.
  double base_z(const Eigen::Vector3d& p) const {
    if (ground_.terrain) return base_;
    return ground_.vertex_z ? p.z() : ground_.plane_z;
  }

  // The lowest ground under the footprint (sets base_ for terrain).
  double base_height(const std::vector<std::vector<Ring>>& polygons, const std::string& where) {
    double lowest = std::numeric_limits<double>::infinity();
    for (const auto& rings : polygons)
      for (const Ring& ring : rings)
        for (const Eigen::Vector3d& p : ring) {
          const double z = ground_.terrain ? ground_.terrain->height_at(p.x(), p.y())
                                           : ground_.vertex_z ? p.z() : ground_.plane_z;
          if (!std::isnan(z)) lowest = std::min(lowest, z);
        }
    if (!std::isfinite(lowest))
      throw std::invalid_argument(where + ": the terrain has no height under any of its vertices");
    base_ = lowest;
    return lowest;
  }

  std::uint32_t vertex(const Eigen::Vector3d& p) {
    mesh_.vertices.push_back(p);
    return static_cast<std::uint32_t>(mesh_.vertices.size() - 1);
  }

  void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t cls) {
    mesh_.triangles.push_back({a, b, c});
    mesh_.triangle_group.push_back(group_);
    mesh_.triangle_class.push_back(cls);
  }

  // Floor and roof: the polygon's ear-clipped triangulation in the plane,
  // at the base (facing down) and at the roof (facing up).
  void add_caps(const std::vector<Ring>& rings, double roof, const std::string& where) {
    std::vector<std::vector<Eigen::Vector3d>> flat;
    std::vector<Eigen::Vector3d> corners;
    for (const Ring& ring : rings) {
      flat.emplace_back();
      for (const Eigen::Vector3d& p : ring) {
        flat.back().emplace_back(p.x(), p.y(), 0.0);
        corners.push_back(p);
      }
    }
    const PolygonTriangles caps = triangulate_polygon(flat);
    if (caps.status != PolygonStatus::ok)
      throw std::invalid_argument(where + (caps.status == PolygonStatus::degenerate
                                               ? " has no area"
                                               : " cannot be triangulated: a hole outside its outline or crossing it?"));
    const auto floor_first = static_cast<std::uint32_t>(mesh_.vertices.size());
    for (const Eigen::Vector3d& p : corners) vertex({p.x(), p.y(), base_z(p)});
    const auto roof_first = static_cast<std::uint32_t>(mesh_.vertices.size());
    for (const Eigen::Vector3d& p : corners) vertex({p.x(), p.y(), roof});
    for (const auto& t : caps.triangles) {
      triangle(floor_first + t[0], floor_first + t[2], floor_first + t[1], floor_);
      triangle(roof_first + t[0], roof_first + t[1], roof_first + t[2], roof_);
    }
  }

  void add_walls(const Ring& ring, double roof) {
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Eigen::Vector3d& p = ring[i];
      const Eigen::Vector3d& q = ring[(i + 1) % ring.size()];
      const std::uint32_t a = vertex({p.x(), p.y(), base_z(p)}), b = vertex({q.x(), q.y(), base_z(q)});
      const std::uint32_t c = vertex({q.x(), q.y(), roof}), d = vertex({p.x(), p.y(), roof});
      // Counter-clockwise along the outline: (a, b, c) faces out.
      triangle(a, b, c, wall_);
      triangle(a, c, d, wall_);
    }
  }

  Mesh& mesh_;
  const FootprintGround& ground_;
  const std::string& source_;
  std::uint32_t floor_ = 0, wall_ = 0, roof_ = 0, group_ = 0;
  double base_ = 0;
};

}  // namespace

Mesh extrude_footprints(const std::vector<BuildingFootprint>& footprints, const FootprintGround& ground,
                        const std::string& source) {
  Mesh mesh;
  Extruder extruder(mesh, ground, source);
  for (const BuildingFootprint& f : footprints) extruder.add(f);
  return mesh;
}

}  // namespace attenuvis::visgraph
