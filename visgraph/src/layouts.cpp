// The five classic 50x50 m visibility test layouts of the seed paper: a
// floor at z=0 and 10 m obstacles built from axis-aligned closed boxes.  On a
// 1 m grid of cell centres they leave 2424, 2000, 2400, 2000 and 2460 free
// cells (2500 minus the covered cells: 4 L-walls of 19 cells; 300 + 200; 100;
// 300 + 300 - 100 overlap; 20 + 20).
#include <attenuvis/visgraph/layouts.hpp>
#include <attenuvis/visgraph/scene_spec.hpp>

#include <stdexcept>
#include <string>

namespace attenuvis::visgraph {

namespace {

void check_index(int index) {
  if (index < 0 || index >= kClassicLayoutCount)
    throw std::invalid_argument("classic layout index " + std::to_string(index) + " is not in 0.." +
                                std::to_string(kClassicLayoutCount - 1));
}

// Appends an axis-aligned box [x0,x1]x[y0,y1]x[z0,z1] as 12 triangles wound
// counter-clockwise seen from outside (outward normals).
void add_box(Mesh& mesh, const Footprint& f, double z0, double z1, std::uint32_t group) {
  const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
  for (int k = 0; k < 8; ++k)
    mesh.vertices.emplace_back((k & 1) ? f.x1 : f.x0, (k & 2) ? f.y1 : f.y0, (k & 4) ? z1 : z0);
  // Corner k has bit 0 = x, bit 1 = y, bit 2 = z.  Each face as a quad
  // (a, b, c, d) counter-clockwise from outside.
  static constexpr std::uint32_t kFaces[6][4] = {
      {0, 2, 3, 1},  // bottom, -z
      {4, 5, 7, 6},  // top, +z
      {0, 1, 5, 4},  // -y
      {2, 6, 7, 3},  // +y
      {0, 4, 6, 2},  // -x
      {1, 3, 7, 5},  // +x
  };
  for (const auto& q : kFaces) {
    mesh.triangles.push_back({base + q[0], base + q[1], base + q[2]});
    mesh.triangles.push_back({base + q[0], base + q[2], base + q[3]});
    mesh.triangle_group.push_back(group);
    mesh.triangle_group.push_back(group);
  }
}

}  // namespace

const char* classic_layout_name(int index) {
  check_index(index);
  static constexpr const char* kNames[kClassicLayoutCount] = {"four-L-walls", "T-block", "single-block",
                                                              "plus-block", "two-walls"};
  return kNames[index];
}

std::vector<Footprint> classic_layout_obstacles(int index) {
  check_index(index);
  switch (index) {
    case 0:  // four 1 m thick L-walls around the centre
      return {{19, 20, 10, 20}, {10, 19, 19, 20}, {19, 20, 30, 40}, {10, 19, 30, 31},
              {30, 31, 30, 40}, {31, 40, 30, 31}, {30, 31, 10, 20}, {31, 40, 19, 20}};
    case 1:  // T block
      return {{10, 40, 30, 40}, {20, 30, 10, 30}};
    case 2:  // one block
      return {{25, 35, 15, 25}};
    case 3:  // plus block (the two arms overlap in the centre square)
      return {{10, 40, 20, 30}, {20, 30, 10, 40}};
    default:  // two parallel walls
      return {{15, 35, 19, 20}, {15, 35, 30, 31}};
  }
}

Mesh classic_layout(int index) {
  check_index(index);
  Mesh mesh;
  const auto floor = static_cast<std::uint32_t>(mesh.add_group(scene_group::floor));
  const double s = kClassicLayoutSize;
  mesh.vertices = {{0, 0, 0}, {s, 0, 0}, {s, s, 0}, {0, s, 0}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};  // normal +z
  mesh.triangle_group = {floor, floor};
  const auto obstacle = static_cast<std::uint32_t>(mesh.add_group(scene_group::obstacle));
  for (const Footprint& f : classic_layout_obstacles(index)) add_box(mesh, f, 0.0, kClassicObstacleHeight, obstacle);
  return mesh;
}

}  // namespace attenuvis::visgraph
