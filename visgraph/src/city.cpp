// Synthetic city in the spirit of the seed paper's CityEngine scene: a
// hexagonal street network over smooth hills, sidewalks and crosswalks as
// their own groups, buildings of random height on the blocks.
//
// Plan view (pointy-top hexagons, corner k of a hexagon at angle 30 + 60 k
// degrees, unit vector e_k).  With street centre-line hexagons of side L and a
// road of width W between curbs:
//  - a block is the centre-line hexagon shrunk by W/2 (apothem L sqrt3/2 - W/2,
//    circumradius L - W/sqrt3);
//  - around every junction V the road is the triangle whose corners are the
//    three block corners V + (W/sqrt3) d, d pointing to the three hexagon
//    centres around V; it meets each street at W/(2 sqrt3) from V;
//  - each street is then a W-wide rectangle between two junction triangles;
//    where the street separates two blocks its first and last
//    `crosswalk_width` metres are crosswalks, whose long sides touch the two
//    blocks' sidewalks;
//  - each block is a sidewalk ring (trapezoid per side), a lot hexagon inside
//    it, and on the lot a ring of buildings (1 to 3 per side, sometimes with a
//    3 m alley) around an open courtyard, or nothing (a park).
// These pieces tile the city exactly in plan, so walkable_area of
// sidewalk+crosswalk equals city_walkable_area_estimate up to rounding.
#include <attenuvis/visgraph/city.hpp>
#include <attenuvis/visgraph/scene_spec.hpp>

#include <attenuvis/io/number_text.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <stdexcept>
#include <string>
#include <utility>

namespace attenuvis::visgraph {

namespace {

using Vec2 = Eigen::Vector2d;

const double kSqrt3 = std::sqrt(3.0);  // IEEE sqrt: correctly rounded, identical everywhere

// e_k, the unit vector to corner k of a pointy-top hexagon (exact constants:
// no sin/cos, for bit-identical output across platforms).
Vec2 corner_direction(int k) {
  const double h = kSqrt3 / 2;
  switch (((k % 6) + 6) % 6) {
    case 0: return {h, 0.5};
    case 1: return {0.0, 1.0};
    case 2: return {-h, 0.5};
    case 3: return {-h, -0.5};
    case 4: return {0.0, -1.0};
    default: return {h, -0.5};
  }
}

// Uniform in [0, 1) from the top 53 bits of one raw engine output: fixed by
// the standard's definition of mt19937_64, unlike std::uniform_real_distribution.
double uniform01(std::mt19937_64& engine) { return static_cast<double>(engine() >> 11) * 0x1.0p-53; }
double uniform(std::mt19937_64& engine, double lo, double hi) { return lo + (hi - lo) * uniform01(engine); }

double raw_height(const HeightField& f, double x, double y) {
  double z = f.tilt_x * x + f.tilt_y * y;
  for (const auto& b : f.bumps) {
    const double dx = x - b.x, dy = y - b.y;
    const double q = (dx * dx + dy * dy) / (b.radius * b.radius);
    if (q < 1.0) {
      const double s = 1.0 - q;
      z += b.amplitude * s * s * s;
    }
  }
  return z;
}

void check_options(const CityOptions& o) {
  auto require = [](bool ok, const std::string& what) {
    if (!ok) throw std::invalid_argument("city options: " + what);
  };
  require(o.rings >= 0 && o.rings <= 40, "rings must be in 0..40");
  // Upper bounds keep a city street-sized: beyond them the terrain grid and the
  // triangle counts (and, for relief, the coordinates) leave the ranges of limits.hpp.
  require(o.hex_size > 0 && o.hex_size <= 1000, "hex_size must be in (0, 1000] m, got " + io::shortest(o.hex_size));
  require(o.road_width > 0 && o.road_width <= 100, "road_width must be in (0, 100] m, got " + io::shortest(o.road_width));
  require(o.sidewalk_width > 0 && o.sidewalk_width <= 100,
          "sidewalk_width must be in (0, 100] m, got " + io::shortest(o.sidewalk_width));
  require(o.crosswalk_width > 0 && o.crosswalk_width <= 100,
          "crosswalk_width must be in (0, 100] m, got " + io::shortest(o.crosswalk_width));
  const double block_apothem = o.hex_size * kSqrt3 / 2 - o.road_width / 2;
  require(block_apothem - o.sidewalk_width > 5.0,
          "hex_size too small for road and sidewalk (the lot inside the sidewalk needs an apothem > 5 m)");
  require(2 * o.crosswalk_width < o.hex_size - o.road_width / kSqrt3, "crosswalks longer than their street");
  require(o.relief >= 0 && o.relief <= 1000, "relief must be in [0, 1000] m, got " + io::shortest(o.relief));
  require(o.margin >= 0 && std::isfinite(o.margin), "margin must be >= 0");
  require(o.building_height_min > 0 && o.building_height_max >= o.building_height_min &&
              std::isfinite(o.building_height_max),
          "building heights need 0 < min <= max");
  require(o.park_fraction >= 0 && o.park_fraction <= 1, "park_fraction must be in [0, 1], got " + io::shortest(o.park_fraction));
  require(o.paved_max_edge >= 0.1 && o.ground_max_edge >= 0.1 && o.terrain_spacing >= 0.5 &&
              std::isfinite(o.paved_max_edge + o.ground_max_edge + o.terrain_spacing),
          "triangle sizes too small (paved/ground >= 0.1 m, terrain >= 0.5 m)");
  require(o.subgrade >= 0 && o.foundation >= 0 && std::isfinite(o.subgrade + o.foundation),
          "subgrade and foundation must be >= 0");
}

int segments(double length, double max_edge) { return std::max(1, static_cast<int>(std::ceil(length / max_edge))); }

// Builds the mesh piece by piece; every vertex it makes is dropped onto the
// height field (minus `dz`), which is what makes surfaces follow the terrain.
class Builder {
 public:
  Builder(Mesh& mesh, const HeightField& terrain) : mesh_(mesh), terrain_(terrain) {}

  std::uint32_t vertex(const Vec2& p, double dz = 0.0) {
    mesh_.vertices.emplace_back(p.x(), p.y(), terrain_(p.x(), p.y()) - dz);
    return static_cast<std::uint32_t>(mesh_.vertices.size() - 1);
  }
  void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t group) {
    mesh_.triangles.push_back({a, b, c});
    mesh_.triangle_group.push_back(group);
  }

  // Quad a,b,c,d (counter-clockwise) as a bilinear nu x nv grid of cells.
  void quad(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, int nu, int nv, std::uint32_t group,
            double dz = 0.0) {
    const auto first = static_cast<std::uint32_t>(mesh_.vertices.size());
    for (int j = 0; j <= nv; ++j) {
      const double v = static_cast<double>(j) / nv;
      for (int i = 0; i <= nu; ++i) {
        const double u = static_cast<double>(i) / nu;
        vertex((1 - v) * ((1 - u) * a + u * b) + v * ((1 - u) * d + u * c), dz);
      }
    }
    auto at = [&](int i, int j) { return first + static_cast<std::uint32_t>(j * (nu + 1) + i); };
    for (int j = 0; j < nv; ++j)
      for (int i = 0; i < nu; ++i) {
        triangle(at(i, j), at(i + 1, j), at(i + 1, j + 1), group);
        triangle(at(i, j), at(i + 1, j + 1), at(i, j + 1), group);
      }
  }

  // Triangle a,b,c (counter-clockwise) split into m^2 similar triangles.
  void subdivided_triangle(const Vec2& a, const Vec2& b, const Vec2& c, int m, std::uint32_t group) {
    std::vector<std::uint32_t> index((m + 1) * (m + 2) / 2);
    auto slot = [m](int i, int j) { return static_cast<std::size_t>(j * (m + 1) - j * (j - 1) / 2 + i); };
    for (int j = 0; j <= m; ++j)
      for (int i = 0; i + j <= m; ++i)
        index[slot(i, j)] = vertex(a + (b - a) * (static_cast<double>(i) / m) + (c - a) * (static_cast<double>(j) / m));
    for (int j = 0; j < m; ++j)
      for (int i = 0; i + j < m; ++i) {
        triangle(index[slot(i, j)], index[slot(i + 1, j)], index[slot(i, j + 1)], group);
        if (i + j < m - 1) triangle(index[slot(i + 1, j)], index[slot(i + 1, j + 1)], index[slot(i, j + 1)], group);
      }
  }

  // Closed prism over a convex counter-clockwise footprint, from base_z to top_z.
  void prism(const std::array<Vec2, 4>& f, double base_z, double top_z, std::uint32_t group) {
    const auto first = static_cast<std::uint32_t>(mesh_.vertices.size());
    for (const Vec2& p : f) mesh_.vertices.emplace_back(p.x(), p.y(), base_z);
    for (const Vec2& p : f) mesh_.vertices.emplace_back(p.x(), p.y(), top_z);
    triangle(first + 0, first + 2, first + 1, group);  // bottom, facing down
    triangle(first + 0, first + 3, first + 2, group);
    triangle(first + 4, first + 5, first + 6, group);  // roof, facing up
    triangle(first + 4, first + 6, first + 7, group);
    for (std::uint32_t k = 0; k < 4; ++k) {  // walls, facing out
      const std::uint32_t n = (k + 1) % 4;
      triangle(first + k, first + n, first + 4 + n, group);
      triangle(first + k, first + 4 + n, first + 4 + k, group);
    }
  }

 private:
  Mesh& mesh_;
  const HeightField& terrain_;
};

struct Street {
  int from, to;            // junction indices, from < to
  std::vector<int> blocks; // 1 (rim) or 2
};

// Junctions are shared by up to three hexagons: identify them by position
// rounded to a micrometre (all arithmetic here is exact to far better).
struct JunctionIndex {
  std::map<std::pair<long long, long long>, int> ids;
  std::vector<Vec2> points;
  int find_or_add(const Vec2& p) {
    const std::pair<long long, long long> key{std::llround(p.x() * 1e6), std::llround(p.y() * 1e6)};
    const auto [it, added] = ids.emplace(key, static_cast<int>(points.size()));
    if (added) points.push_back(p);
    return it->second;
  }
};

// Samples the footprint on a grid of about 2 m for the extreme terrain
// heights under it.
std::pair<double, double> terrain_range(const HeightField& terrain, const std::array<Vec2, 4>& f) {
  const int nu = segments(std::max((f[1] - f[0]).norm(), (f[2] - f[3]).norm()), 2.0);
  const int nv = segments(std::max((f[3] - f[0]).norm(), (f[2] - f[1]).norm()), 2.0);
  double lo = INFINITY, hi = -INFINITY;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) {
      const double u = static_cast<double>(i) / nu, v = static_cast<double>(j) / nv;
      const Vec2 p = (1 - v) * ((1 - u) * f[0] + u * f[1]) + v * ((1 - u) * f[3] + u * f[2]);
      const double z = terrain(p.x(), p.y());
      lo = std::min(lo, z);
      hi = std::max(hi, z);
    }
  return {lo, hi};
}

// The street network of the centre-line hexagons: junctions (shared by up
// to three blocks), the streets between them, and each block's six corners
// as junction indices (corner k in direction e_k).
struct StreetNetwork {
  JunctionIndex junctions;
  std::map<std::pair<int, int>, Street> streets;
  std::vector<std::array<int, 6>> block_corners;
};

// The city's plan-view bounding box: its junctions grown by `grow` metres.
struct PlanBox {
  Vec2 lower, upper;
};

// Mesh group of each kind of surface (names in scene_spec.hpp).
struct CityGroups {
  std::uint32_t sidewalk, crosswalk, road, ground, building, terrain;
};

// Blocks: axial coordinates (q, r) within hex distance `rings` of the centre.
void place_blocks(const CityOptions& o, double block_apothem, City& city) {
  const double L = o.hex_size;
  for (int r = -o.rings; r <= o.rings; ++r)
    for (int q = -o.rings; q <= o.rings; ++q) {
      if (std::abs(q + r) > o.rings) continue;
      const Vec2 centre(L * kSqrt3 * (q + 0.5 * r), L * 1.5 * r);
      city.blocks.push_back({centre, block_apothem, block_apothem - o.sidewalk_width, false});
    }
}

StreetNetwork street_network(const std::vector<CityBlock>& blocks, double L) {
  StreetNetwork network;
  network.block_corners.resize(blocks.size());
  for (std::size_t b = 0; b < blocks.size(); ++b)
    for (int k = 0; k < 6; ++k)
      network.block_corners[b][k] = network.junctions.find_or_add(blocks[b].centre + L * corner_direction(k));
  for (std::size_t b = 0; b < blocks.size(); ++b)
    for (int k = 0; k < 6; ++k) {
      int u = network.block_corners[b][k], v = network.block_corners[b][(k + 1) % 6];
      if (u > v) std::swap(u, v);
      Street& s = network.streets[{u, v}];
      s.from = u;
      s.to = v;
      s.blocks.push_back(static_cast<int>(b));
    }
  return network;
}

PlanBox plan_box(const std::vector<Vec2>& junctions, double grow) {
  PlanBox box{junctions.front(), junctions.front()};
  for (const Vec2& p : junctions) {
    box.lower = box.lower.cwiseMin(p);
    box.upper = box.upper.cwiseMax(p);
  }
  box.lower -= Vec2::Constant(grow);
  box.upper += Vec2::Constant(grow);
  return box;
}

// Terrain: random bumps and tilt over the box (the engine's first draws),
// then scaled so that its range on a 10 m grid over the box is `relief`,
// with minimum 0.
HeightField random_terrain(std::mt19937_64& engine, const PlanBox& box, double relief) {
  const Vec2& lower = box.lower;
  const Vec2& upper = box.upper;
  const double half_extent = 0.5 * (upper - lower).maxCoeff();
  HeightField terrain;
  for (int k = 0; k < 6; ++k) {
    HeightField::Bump bump;
    bump.x = uniform(engine, lower.x(), upper.x());
    bump.y = uniform(engine, lower.y(), upper.y());
    bump.radius = uniform(engine, 0.3, 0.7) * half_extent;
    bump.amplitude = uniform(engine, -1.0, 1.0);
    terrain.bumps.push_back(bump);
  }
  terrain.tilt_x = uniform(engine, -0.5, 0.5) / half_extent;
  terrain.tilt_y = uniform(engine, -0.5, 0.5) / half_extent;
  double lo = INFINITY, hi = -INFINITY;
  const int nx = segments(upper.x() - lower.x(), 10.0), ny = segments(upper.y() - lower.y(), 10.0);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double z = raw_height(terrain, lower.x() + (upper.x() - lower.x()) * i / nx,
                                  lower.y() + (upper.y() - lower.y()) * j / ny);
      lo = std::min(lo, z);
      hi = std::max(hi, z);
    }
  terrain.scale = hi > lo ? relief / (hi - lo) : 0.0;
  terrain.offset = -terrain.scale * lo;
  return terrain;
}

CityGroups add_city_groups(Mesh& mesh) {
  CityGroups g;
  g.sidewalk = static_cast<std::uint32_t>(mesh.add_group(scene_group::sidewalk));
  g.crosswalk = static_cast<std::uint32_t>(mesh.add_group(scene_group::crosswalk));
  g.road = static_cast<std::uint32_t>(mesh.add_group(scene_group::road));
  g.ground = static_cast<std::uint32_t>(mesh.add_group(scene_group::ground));
  g.building = static_cast<std::uint32_t>(mesh.add_group(scene_group::building));
  g.terrain = static_cast<std::uint32_t>(mesh.add_group(scene_group::terrain));
  return g;
}

// Junctions: the road triangle around each.  Its corners point to the
// three hexagon centres around V: e_{k+1}, e_{k+3}, e_{k+5} for a junction
// that is corner k of some block (the parity of k fixes the set).
void add_junctions(const CityOptions& o, const StreetNetwork& network, std::uint32_t g_road, Builder& build,
                   City& city) {
  const double W = o.road_width;
  const std::vector<Vec2>& points = network.junctions.points;
  std::vector<int> degree(points.size(), 0);
  for (const auto& [key, s] : network.streets) {
    ++degree[s.from];
    ++degree[s.to];
  }
  std::vector<int> junction_parity(points.size(), -1);
  for (const std::array<int, 6>& corners : network.block_corners)
    for (int k = 0; k < 6; ++k) junction_parity[corners[k]] = k % 2;
  for (std::size_t j = 0; j < points.size(); ++j) {
    const Vec2& V = points[j];
    const int k = junction_parity[j];
    const double reach = W / kSqrt3;
    build.subdivided_triangle(V + reach * corner_direction(k + 1), V + reach * corner_direction(k + 3),
                              V + reach * corner_direction(k + 5), segments(W, o.paved_max_edge), g_road);
    city.intersections.push_back({Eigen::Vector3d(V.x(), V.y(), city.terrain(V.x(), V.y())), degree[j]});
  }
}

// Streets: road rectangle between the junction triangles, crosswalks at
// both ends where the street separates two blocks.
void add_streets(const CityOptions& o, const StreetNetwork& network, const CityGroups& groups, Builder& build,
                 City& city) {
  const double W = o.road_width, edge = o.paved_max_edge;
  for (const auto& [key, s] : network.streets) {
    const Vec2 A = network.junctions.points[s.from], B = network.junctions.points[s.to];
    const Vec2 t = (B - A).normalized();
    const Vec2 n(-t.y(), t.x());
    const double start = W / (2 * kSqrt3), end = (B - A).norm() - start;
    auto piece = [&](double s0, double s1, std::uint32_t group) {
      build.quad(A + s0 * t - 0.5 * W * n, A + s1 * t - 0.5 * W * n, A + s1 * t + 0.5 * W * n,
                 A + s0 * t + 0.5 * W * n, segments(s1 - s0, edge), segments(W, edge), group);
    };
    if (s.blocks.size() < 2) {
      piece(start, end, groups.road);
      continue;
    }
    const double cw = o.crosswalk_width;
    piece(start, start + cw, groups.crosswalk);
    piece(start + cw, end - cw, groups.road);
    piece(end - cw, end, groups.crosswalk);
    for (const auto& [along, junction] : {std::pair<double, int>{start + 0.5 * cw, s.from},
                                          std::pair<double, int>{end - 0.5 * cw, s.to}}) {
      const Vec2 c = A + along * t;
      city.crosswalks.push_back({Eigen::Vector3d(c.x(), c.y(), city.terrain(c.x(), c.y())), n, W, cw,
                                 {s.blocks[0], s.blocks[1]}, junction});
    }
  }
}

// Block b's sidewalk ring (one trapezoid per side) and lot (six triangles
// from the centre), and the sidewalk corners where pedestrians wait.
void add_block_surface(const CityOptions& o, const StreetNetwork& network, std::size_t b, double block_radius,
                       double lot_radius, const CityGroups& groups, Builder& build, City& city) {
  const double w = o.sidewalk_width, edge = o.paved_max_edge;
  const double mid_radius = block_radius - w / kSqrt3;  // sidewalk mid-line corner
  const Vec2 c = city.blocks[b].centre;
  for (int k = 0; k < 6; ++k) {
    const Vec2 e0 = corner_direction(k), e1 = corner_direction(k + 1);
    build.quad(c + block_radius * e0, c + block_radius * e1, c + lot_radius * e1, c + lot_radius * e0,
               segments(block_radius, edge), segments(w, edge), groups.sidewalk);
    build.subdivided_triangle(c, c + lot_radius * e0, c + lot_radius * e1, segments(lot_radius, o.ground_max_edge),
                              groups.ground);
    const Vec2 p = c + mid_radius * e0;
    city.sidewalk_corners.push_back({Eigen::Vector3d(p.x(), p.y(), city.terrain(p.x(), p.y())), e0,
                                     static_cast<int>(b), network.block_corners[b][k]});
  }
}

// The buildings of block b: a ring between apothems a1 (after a setback
// from the sidewalk) and a2 (courtyard side), at least 5 m of courtyard
// apothem left; 1 to 3 buildings per side, sometimes with a 3 m alley
// between them.  The engine's draws, in this order, make the city's
// fingerprint: keep it.
void add_buildings(const CityOptions& o, std::mt19937_64& engine, std::size_t b, std::uint32_t g_building,
                   Builder& build, City& city) {
  const CityBlock& block = city.blocks[b];
  const Vec2 c = block.centre;
  const double setback = uniform(engine, 0.0, 3.0);
  const double a1 = block.lot_apothem - setback;
  const double a2 = std::max(5.0, a1 - uniform(engine, 10.0, 18.0));
  const double r1 = 2 * a1 / kSqrt3, r2 = 2 * a2 / kSqrt3;
  for (int k = 0; k < 6; ++k) {
    const Vec2 o0 = c + r1 * corner_direction(k), o1 = c + r1 * corner_direction(k + 1);
    const Vec2 i0 = c + r2 * corner_direction(k), i1 = c + r2 * corner_direction(k + 1);
    const int count = 1 + static_cast<int>(3 * uniform01(engine));
    const double gap = 3.0 / (o1 - o0).norm();  // alley width as a fraction of the side
    std::vector<double> cuts{0.0};
    for (int i = 1; i < count; ++i) cuts.push_back((i + uniform(engine, -0.15, 0.15)) / count);
    cuts.push_back(1.0);
    std::vector<bool> alley(count + 1, false);
    for (int i = 1; i < count; ++i) alley[i] = uniform01(engine) < 0.4;
    for (int i = 0; i < count; ++i) {
      const double t0 = cuts[i] + (alley[i] ? 0.5 * gap : 0.0);
      const double t1 = cuts[i + 1] - (alley[i + 1] ? 0.5 * gap : 0.0);
      const std::array<Vec2, 4> f{(1 - t0) * o0 + t0 * o1, (1 - t1) * o0 + t1 * o1, (1 - t1) * i0 + t1 * i1,
                                  (1 - t0) * i0 + t0 * i1};
      const double u = uniform01(engine);
      const double height = o.building_height_min + (o.building_height_max - o.building_height_min) * u * u;
      const auto [lo, hi] = terrain_range(city.terrain, f);
      const CityBuilding building{f, lo - o.foundation, hi + height, static_cast<int>(b)};
      build.prism(f, building.base_z, building.top_z, g_building);
      city.buildings.push_back(building);
    }
  }
}

// Natural terrain under and around the city, `subgrade` below the pavement.
void add_natural_terrain(const CityOptions& o, const PlanBox& box, std::uint32_t g_terrain, Builder& build) {
  const Vec2& lower = box.lower;
  const Vec2& upper = box.upper;
  const double extent_x = upper.x() - lower.x(), extent_y = upper.y() - lower.y();
  const int nx = segments(extent_x, o.terrain_spacing), ny = segments(extent_y, o.terrain_spacing);
  if (static_cast<double>(nx) * ny > 4e6) throw std::invalid_argument("city options: terrain grid over 4e6 cells");
  build.quad(lower, {upper.x(), lower.y()}, upper, {lower.x(), upper.y()}, nx, ny, g_terrain, o.subgrade);
}

}  // namespace

double HeightField::operator()(double x, double y) const { return scale * raw_height(*this, x, y) + offset; }

double city_walkable_area_estimate(const CityOptions& o) {
  check_options(o);
  const double blocks = 1.0 + 3.0 * o.rings * (o.rings + 1);
  // Hexagonal patch: 6 N edge sides, 6 (2 rings + 1) of them on the rim, the
  // rest shared by two blocks.
  const double interior_streets = 3.0 * blocks - 3.0 * (2 * o.rings + 1);
  const double a = o.hex_size * kSqrt3 / 2 - o.road_width / 2;
  const double w = o.sidewalk_width;
  return blocks * 2 * kSqrt3 * w * (2 * a - w) + interior_streets * 2 * o.road_width * o.crosswalk_width;
}

// The pieces in a fixed order (the mesh's vertex and triangle order, and the
// engine's draws: terrain first, then block by block), which the fingerprint
// test in tests/visgraph/test_generators.cpp holds to.
City make_city(const CityOptions& o) {
  check_options(o);
  City city;
  std::mt19937_64 engine(o.seed);
  const double L = o.hex_size, W = o.road_width, w = o.sidewalk_width;
  const double block_radius = L - W / kSqrt3;                   // block circumradius
  const double lot_radius = block_radius - 2 * w / kSqrt3;      // inside the sidewalk
  place_blocks(o, block_radius * kSqrt3 / 2, city);
  const StreetNetwork network = street_network(city.blocks, L);
  const PlanBox box = plan_box(network.junctions.points, W + o.margin);
  city.terrain = random_terrain(engine, box, o.relief);
  const CityGroups groups = add_city_groups(city.mesh);
  Builder build(city.mesh, city.terrain);
  add_junctions(o, network, groups.road, build, city);
  add_streets(o, network, groups, build, city);
  for (std::size_t b = 0; b < city.blocks.size(); ++b) {
    add_block_surface(o, network, b, block_radius, lot_radius, groups, build, city);
    city.blocks[b].park = uniform01(engine) < o.park_fraction;
    if (!city.blocks[b].park) add_buildings(o, engine, b, groups.building, build, city);
  }
  add_natural_terrain(o, box, groups.terrain, build);
  return city;
}

Mesh synthetic_city(const CityOptions& options) { return make_city(options).mesh; }

}  // namespace attenuvis::visgraph
