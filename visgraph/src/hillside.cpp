// The synthetic hillside town (hillside.hpp).
#include <attenuvis/visgraph/hillside.hpp>

#include <attenuvis/visgraph/footprints.hpp>

#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace attenuvis::visgraph {

namespace {
// As the synthetic city: uniform numbers from raw mt19937_64 output.
double uniform(std::mt19937_64& engine, double lo, double hi) {
  return lo + (hi - lo) * (static_cast<double>(engine() >> 11) * 0x1.0p-53);
}
}  // namespace

double hillside_ground(const HillsideOptions& o, double x, double y) {
  const double across = y - 0.5 * o.size;
  return o.slope * x - o.ridge_curvature * across * across;
}

double hillside_curvature_bound(const HillsideOptions& o) { return 2.0 * std::abs(o.ridge_curvature); }

Mesh hillside_town(const HillsideOptions& o) {
  std::mt19937_64 engine(o.seed);
  std::vector<BuildingFootprint> buildings;
  const int blocks = static_cast<int>(std::floor(o.size / o.block));
  const double lot = 0.5 * (o.block - o.street);  // each block holds 2 x 2 lots
  // Cosine and sine of up to 15 degrees without trigonometric functions: a
  // rotation by the unit vector (1, t) / sqrt(1 + t^2), |t| <= tan 15 deg.
  constexpr double kTan15 = 0.2679491924311227;
  for (int by = 0; by < blocks; ++by)
    for (int bx = 0; bx < blocks; ++bx)
      for (int q = 0; q < 4; ++q) {
        const double cx = bx * o.block + 0.5 * o.street + (q % 2 + 0.5) * lot;
        const double cy = by * o.block + 0.5 * o.street + (q / 2 + 0.5) * lot;
        const double w = uniform(engine, 7.0, 11.0), d = uniform(engine, 7.0, 11.0);
        const double t = uniform(engine, -kTan15, kTan15), norm = std::sqrt(1.0 + t * t);
        const double c = 1.0 / norm, s = t / norm;
        const double height = uniform(engine, o.height_min, o.height_max);
        BuildingFootprint b;
        b.id = "building-" + std::to_string(buildings.size());
        b.height = height;
        b.polygons.emplace_back();
        auto& ring = b.polygons.back().rings.emplace_back();
        for (const auto& [u, v] : {std::pair{-1, -1}, std::pair{1, -1}, std::pair{1, 1}, std::pair{-1, 1}}) {
          const double x = cx + 0.5 * (c * u * w - s * v * d), y = cy + 0.5 * (s * u * w + c * v * d);
          ring.emplace_back(x, y, hillside_ground(o, x, y));
        }
        buildings.push_back(std::move(b));
      }
  FootprintGround ground;
  ground.vertex_z = true;
  return extrude_footprints(buildings, ground, "hillside town");
}

}  // namespace attenuvis::visgraph
