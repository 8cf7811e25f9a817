// Small vector helpers of the culling geometry (cull_geometry.cpp,
// cull_solids.cpp), in double precision on plain arrays.  Internal to the
// visgraph library.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <utility>

#include "cull_geometry.hpp"

// The lane loops of the culling (planar occluders, convex solids) are
// compiled per instruction set and picked at run time.  Not under clang or
// the sanitizers, whose builds take the baseline loop.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && !defined(__SANITIZE_ADDRESS__)
#define ATTENUVIS_CULL_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define ATTENUVIS_CULL_CLONES
#endif

namespace attenuvis::visgraph::detail::cull_math {

using V3 = std::array<double, 3>;
inline double dot(const double* a, const double* b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline V3 cross(const double* a, const double* b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline V3 sub(const double* a, const double* b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline double norm(const V3& a) { return std::sqrt(dot(a.data(), a.data())); }

// The distinct corners of a box (a flat box has 4, a point 1): every
// segment between two boxes is a convex combination of the segments
// between their corners, and the tests below need each corner once.
inline int distinct_corners(const Box3& b, double (*out)[3]) {
  int count = 1;
  for (int c = 0; c < 3; ++c) out[0][c] = b.lo[c];
  for (int c = 0; c < 3; ++c) {
    if (!(b.hi[c] > b.lo[c])) continue;
    for (int k = 0; k < count; ++k) {
      for (int e = 0; e < 3; ++e) out[count + k][e] = out[k][e];
      out[count + k][c] = b.hi[c];
    }
    count *= 2;
  }
  return count;
}

// A triangle's unit normal (v1 - v0) x (v2 - v0) / |...| and that length
// (twice its area); the normal is left unnormalised when the length is 0.
inline std::pair<V3, double> unit_normal(const double (*v)[3]) {
  const V3 e1 = sub(v[1], v[0]), e2 = sub(v[2], v[0]);
  V3 n = cross(e1.data(), e2.data());
  const double l = norm(n);
  if (l > 0) n = {n[0] / l, n[1] / l, n[2] / l};
  return std::make_pair(n, l);
}

// An undirected edge between two vertex indices, as one key.
inline std::uint64_t edge_key(unsigned a, unsigned b) {
  return (std::uint64_t{std::min(a, b)} << 32) | std::max(a, b);
}

}  // namespace attenuvis::visgraph::detail::cull_math
