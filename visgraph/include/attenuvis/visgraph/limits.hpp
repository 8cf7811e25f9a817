// The ranges every visibility-graph input must lie in, in one place, and the
// checks that apply them where text becomes a value (readers, CLI options).
//
// Why these bounds:
//  - |coordinate| <= 1e7 m holds every projected CRS in use (UTM northings
//    reach 1e7 m, Web Mercator 2e7 m only at its edge: shift such data) and
//    bounds every distance by sqrt(3) * 2e7 m < 3.5e7 m, which keeps the
//    fixed-point sums of the visibility pass far from 2^63 (see
//    check_fixed_point_range in src/pass_input.cpp) and Embree's rays finite.
//  - spacing in [1e-3, 1e4] m, eye height in [0, 1e3] m: a millimetre grid or a
//    kilometre eye is already beyond any street-level analysis; outside them
//    the grid arithmetic (cells = extent / spacing) and Embree's ray bounds
//    lose meaning.
//  - files: scene files up to 2 GiB, node files up to 512 MiB, text lines up
//    to 1 MiB, polygons up to 10,000 vertices (ear clipping is quadratic).
#pragma once

#include <cstddef>
#include <string>

namespace attenuvis::visgraph {

constexpr double kMaxCoordinate = 1e7;          // m, |x|, |y|, |z| of any vertex or node
constexpr double kMinSpacing = 1e-3;            // m
constexpr double kMaxSpacing = 1e4;             // m
constexpr double kMaxEyeHeight = 1e3;           // m
constexpr std::size_t kMaxSceneFileBytes = std::size_t{2} << 30;  // 2 GiB
constexpr std::size_t kMaxNodeFileBytes = std::size_t{512} << 20;  // 512 MiB
constexpr std::size_t kMaxLineBytes = std::size_t{1} << 20;       // 1 MiB
// The most vertices of one OBJ face or CityJSON surface: ear clipping is quadratic.
constexpr std::size_t kMaxPolygonVertices = 10000;

// Throws std::invalid_argument "WHERE: coordinate VALUE is outside
// [-1e7, 1e7] m ..." when |value| > kMaxCoordinate or value is not finite.
void check_coordinate(double value, const std::string& where);

// Throws std::invalid_argument "WHAT: VALUE is outside [LO, HI] UNIT" when
// value is not finite or lies outside [lo, hi].
void check_range(double value, double lo, double hi, const std::string& what, const std::string& unit);

}  // namespace attenuvis::visgraph
