// Terrain from a height raster (a DEM), as typed values: the GIS edge
// (visgraph/gis, GDAL) reads the raster; this turns it into the surface
// nodes stand on and lines of sight may meet.
//
// The surface is triangulated through the cell centres: each 2 x 2 block of
// neighbouring centres with data gives two triangles, split along the
// diagonal from (col, row) to (col + 1, row + 1), so that between centres the
// ground is the linear interpolation of the four heights on that split.  A
// block with a cell without data is left out: a hole, where nothing is known.
#pragma once

#include <attenuvis/visgraph/mesh.hpp>
#include <attenuvis/visgraph/scene.hpp>

#include <Eigen/Core>

#include <cstddef>
#include <string>
#include <vector>

namespace attenuvis::visgraph {

// The group and class of a DEM's triangles.
inline constexpr const char* kTerrainGroup = "dem-terrain";
inline constexpr const char* kTerrainClass = "DEMTerrain";

// A window of a north-up raster of heights.
struct HeightGrid {
  double x0 = 0, y0 = 0;    // world position of the centre of window cell (0, 0)
  double dx = 1, dy = -1;   // cell pitch along a row (x, > 0) and down a column (y; < 0 for north-up)
  std::size_t cols = 0, rows = 0;
  std::vector<double> z;    // row-major, m; NaN where the raster holds no data
  long col0 = 0, row0 = 0;  // the window's first cell in the source raster (for messages)

  double at(std::size_t col, std::size_t row) const { return z[row * cols + col]; }
  Eigen::Vector2d centre(std::size_t col, std::size_t row) const {
    return {x0 + static_cast<double>(col) * dx, y0 + static_cast<double>(row) * dy};
  }
  // The surface's height at (x, y) (see above); NaN outside the cell centres'
  // extent or in a block with a cell without data.
  double height_at(double x, double y) const;
  // The window cell without data that makes height_at(x, y) NaN, described as
  // "cell (column C, row R) at x = X, y = Y" in the source raster's
  // numbering; or "" when the surface has a height there or (x, y) is outside.
  std::string missing_cell(double x, double y) const;
  // True when (x, y) lies within the cell centres' extent.
  bool covers(double x, double y) const;
};

// Adds the surface's triangles (group kTerrainGroup; class kTerrainClass
// where the mesh has classes; facing up) and returns how many.
std::size_t add_terrain(Mesh& mesh, const HeightGrid& grid);

// The first grid cell without data that no building stands over (a vertical
// line through its centre meets nothing of `buildings`, a scene of the model
// without the terrain), described as HeightGrid::missing_cell does; "" when
// every cell without data lies under a building (DTMs often leave buildings
// out), where no node can stand.
std::string exposed_missing_cell(const HeightGrid& grid, const Scene& buildings);

// Throws std::invalid_argument naming the first eye (1-based) that stands
// outside the grid's cell centres or over a block with a cell without data
// (missing_cell), with `source` (the DEM's file name) in the message.
void check_nodes_on_terrain(const HeightGrid& grid, const std::vector<Eigen::Vector3d>& eyes,
                            const std::string& source);

}  // namespace attenuvis::visgraph
