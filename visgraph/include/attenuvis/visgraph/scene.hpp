// A ray-traceable scene: a Mesh handed to Embree.
//
// Embree stores vertices in single precision.  Coordinates of real sites are
// often UTM-sized (~5e5 m), where a float's spacing is 3 cm; the scene
// therefore subtracts the bounding-box centre from every vertex IN DOUBLE
// before converting to float, so float spacing is set by the scene's extent
// (1 km scene: ~6e-5 m) and not by its distance from the origin.  Every
// position the visgraph library returns is in the original (world) frame;
// `to_local`/`to_world` convert where the caller needs the Embree frame.
#pragma once

#include <attenuvis/visgraph/mesh.hpp>

#include <Eigen/Core>

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

namespace attenuvis::visgraph {

namespace detail {
struct SceneAccess;  // the library's own kernels reach Embree through it (src/scene_access.hpp)
}

// An axis-aligned box.
struct BoundingBox {
  Eigen::Vector3d min, max;
  Eigen::Vector3d centre() const { return 0.5 * (min + max); }
  Eigen::Vector3d extent() const { return max - min; }
};

// Per-group triangle count, for the report of what a scene holds.
struct GroupInfo {
  std::string name;
  std::size_t triangles = 0;
};

// A mesh made ready for Embree's ray queries, in a frame centred on it.
class Scene {
 public:
  // Builds the BVH (robust, high quality) on the process's one Embree device.
  // Throws std::invalid_argument for an empty mesh, a non-finite vertex or an
  // out-of-range index; std::runtime_error with Embree's own message when
  // Embree fails (out of memory, ...).
  explicit Scene(const Mesh& mesh);
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  std::size_t triangle_count() const;
  const BoundingBox& bounds() const;          // world frame
  const Eigen::Vector3d& origin() const;      // world point mapped to local 0
  const std::vector<GroupInfo>& groups() const;
  // Group index of each triangle (as in Mesh::triangle_group).
  std::uint32_t triangle_group(std::size_t triangle) const;
  // Surface classes (Mesh::classes, with triangle counts); empty when the mesh
  // has none, and then triangle_class is kNoClass for every triangle.
  const std::vector<GroupInfo>& classes() const;
  static constexpr std::uint32_t kNoClass = 0xFFFFFFFFu;
  std::uint32_t triangle_class(std::size_t triangle) const;

  Eigen::Vector3d to_local(const Eigen::Vector3d& world) const { return world - origin(); }
  Eigen::Vector3d to_world(const Eigen::Vector3d& local) const { return local + origin(); }

  // First surface hit along a ray (local frame, unit or non-unit direction,
  // parameter range [t_near, t_far] in units of |dir|).
  struct Hit {
    bool found = false;
    double t = 0;
    Eigen::Vector3d normal{0, 0, 0};  // geometric normal, unit length
    std::uint32_t triangle = 0;
  };
  Hit intersect(const Eigen::Vector3d& origin_local, const Eigen::Vector3d& dir, double t_near,
                double t_far) const;
  // True if anything lies on the open segment a→b (local frame), excluding
  // `end_gap` metres at both ends.
  bool occluded(const Eigen::Vector3d& a_local, const Eigen::Vector3d& b_local, double end_gap) const;

 private:
  friend struct detail::SceneAccess;
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Human-readable report: triangles, bounding box, groups.
std::string describe(const Scene& scene);

}  // namespace attenuvis::visgraph
