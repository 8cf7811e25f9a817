// Terrain surfaces from height grids (terrain.hpp).
#include <attenuvis/visgraph/terrain.hpp>

#include <attenuvis/io/check.hpp>
#include <attenuvis/io/number_text.hpp>

#include <cmath>
#include <stdexcept>

namespace attenuvis::visgraph {

namespace {

// The block (col, row)..(col + 1, row + 1) holding (x, y), and where in it:
// fractions fu along the row, fv down the column, both in [0, 1].
struct Block {
  std::size_t col = 0, row = 0;
  double fu = 0, fv = 0;
};

bool locate(const HeightGrid& g, double x, double y, Block& b) {
  if (g.cols < 2 || g.rows < 2) return false;
  const double u = (x - g.x0) / g.dx, v = (y - g.y0) / g.dy;
  const double last_u = static_cast<double>(g.cols - 1), last_v = static_cast<double>(g.rows - 1);
  if (!(u >= 0 && u <= last_u && v >= 0 && v <= last_v)) return false;
  // A point on the last centre belongs to the block before it.
  b.col = std::min(static_cast<std::size_t>(u), g.cols - 2);
  b.row = std::min(static_cast<std::size_t>(v), g.rows - 2);
  b.fu = u - static_cast<double>(b.col);
  b.fv = v - static_cast<double>(b.row);
  return true;
}

std::string describe_cell(const HeightGrid& g, std::size_t col, std::size_t row) {
  const Eigen::Vector2d c = g.centre(col, row);
  return "cell (column " + std::to_string(g.col0 + static_cast<long>(col)) + ", row " +
         std::to_string(g.row0 + static_cast<long>(row)) + ") at x = " + io::significant(c.x(), 10) +
         ", y = " + io::significant(c.y(), 10);
}

}  // namespace

bool HeightGrid::covers(double x, double y) const {
  Block b;
  return locate(*this, x, y, b);
}

double HeightGrid::height_at(double x, double y) const {
  Block b;
  if (!locate(*this, x, y, b)) return std::nan("");
  const double z00 = at(b.col, b.row), z10 = at(b.col + 1, b.row);
  const double z01 = at(b.col, b.row + 1), z11 = at(b.col + 1, b.row + 1);
  // The two triangles of the block, split along (col, row)-(col + 1, row + 1)
  // as add_terrain makes them; a NaN corner of the block makes a NaN height.
  if (std::isnan(z00) || std::isnan(z10) || std::isnan(z01) || std::isnan(z11)) return std::nan("");
  if (b.fu >= b.fv) return z00 + b.fu * (z10 - z00) + b.fv * (z11 - z10);
  return z00 + b.fv * (z01 - z00) + b.fu * (z11 - z01);
}

std::string HeightGrid::missing_cell(double x, double y) const {
  Block b;
  if (!locate(*this, x, y, b)) return "";
  for (const auto& [c, r] : {std::make_pair(b.col, b.row), std::make_pair(b.col + 1, b.row),
                             std::make_pair(b.col, b.row + 1), std::make_pair(b.col + 1, b.row + 1)})
    if (std::isnan(at(c, r))) return describe_cell(*this, c, r);
  return "";
}

std::size_t add_terrain(Mesh& mesh, const HeightGrid& grid) {
  ATTENUVIS_CHECK_EQ(grid.z.size(), grid.cols * grid.rows);
  if (grid.cols < 2 || grid.rows < 2) return 0;
  // One vertex per cell with data.
  std::vector<std::uint32_t> vertex(grid.z.size(), UINT32_MAX);
  for (std::size_t row = 0; row < grid.rows; ++row)
    for (std::size_t col = 0; col < grid.cols; ++col) {
      const double z = grid.at(col, row);
      if (std::isnan(z)) continue;
      vertex[row * grid.cols + col] = static_cast<std::uint32_t>(mesh.vertices.size());
      const Eigen::Vector2d c = grid.centre(col, row);
      mesh.vertices.emplace_back(c.x(), c.y(), z);
    }
  const auto group = static_cast<std::uint32_t>(mesh.add_group(kTerrainGroup));
  const bool classed = !mesh.classes.empty();
  const auto cls = classed ? static_cast<std::uint32_t>(mesh.add_class(kTerrainClass)) : 0u;
  // Columns run along +x; rows along +y when dy > 0: counter-clockwise seen
  // from above is (00, 10, 11) then; for north-up rasters (dy < 0) the
  // opposite order faces up.
  const bool flip = grid.dy < 0;
  std::size_t added = 0;
  const auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    mesh.triangles.push_back(flip ? std::array<std::uint32_t, 3>{a, c, b} : std::array<std::uint32_t, 3>{a, b, c});
    mesh.triangle_group.push_back(group);
    if (classed) mesh.triangle_class.push_back(cls);
    ++added;
  };
  for (std::size_t row = 0; row + 1 < grid.rows; ++row)
    for (std::size_t col = 0; col + 1 < grid.cols; ++col) {
      const std::uint32_t v00 = vertex[row * grid.cols + col], v10 = vertex[row * grid.cols + col + 1];
      const std::uint32_t v01 = vertex[(row + 1) * grid.cols + col], v11 = vertex[(row + 1) * grid.cols + col + 1];
      if (v00 == UINT32_MAX || v10 == UINT32_MAX || v01 == UINT32_MAX || v11 == UINT32_MAX) continue;
      add(v00, v10, v11);
      add(v00, v11, v01);
    }
  return added;
}

std::string exposed_missing_cell(const HeightGrid& grid, const Scene& buildings) {
  const BoundingBox& box = buildings.bounds();
  const double top = box.max.z() + 1.0, depth = box.extent().z() + 2.0;
  for (std::size_t row = 0; row < grid.rows; ++row)
    for (std::size_t col = 0; col < grid.cols; ++col) {
      if (!std::isnan(grid.at(col, row))) continue;
      const Eigen::Vector2d c = grid.centre(col, row);
      const Eigen::Vector3d start = buildings.to_local(Eigen::Vector3d(c.x(), c.y(), top));
      if (!buildings.intersect(start, Eigen::Vector3d(0, 0, -1), 0.0, depth).found) return describe_cell(grid, col, row);
    }
  return "";
}

void check_nodes_on_terrain(const HeightGrid& grid, const std::vector<Eigen::Vector3d>& eyes,
                            const std::string& source) {
  for (std::size_t i = 0; i < eyes.size(); ++i) {
    const double x = eyes[i].x(), y = eyes[i].y();
    const std::string where = "node " + std::to_string(i + 1) + " (x = " + io::significant(x, 10) +
                              ", y = " + io::significant(y, 10) + ")";
    if (!grid.covers(x, y))
      throw std::invalid_argument(where + " lies outside the terrain read from " + source);
    const std::string cell = grid.missing_cell(x, y);
    if (!cell.empty()) throw std::invalid_argument(source + " has no data at " + cell + ", under " + where);
  }
}

}  // namespace attenuvis::visgraph
