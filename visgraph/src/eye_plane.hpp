// Sight lines in the eyes' plane: on flat ground the nodes stand at one
// height h (to within delta), so every sight line between two of them lies
// within delta of the horizontal plane z = h, where the walls' planar
// occluders are segments.  Nodes elsewhere (a few on a raised ground
// surface) take no part: their sight lines are left to the other tests.
// Internal to the visgraph library (packet_culling.cpp).
//
// For one eye, a fan of bins around it (uniform in a pseudo-angle) holds,
// per bin, the horizontal distance beyond which every node in the bin is
// blocked: the least, over the wall segments that span the whole bin as
// seen from the eye, of the farthest point of the bin beyond the segment by
// the margin.  A partner in bin b farther than that is blocked by the
// segment's occluder with the margins of lanes_blocked (cull_geometry.hpp):
//   - the eye lies at least margin + depth from the occluder's plane (with
//     the nodes' spread in height, |n_z| delta, added), and the partner
//     beyond the segment by as much on the other side, because the ray from
//     the eye through the partner meets the segment's line shifted by that
//     amount before the bin's boundary rays do (the distance to a line is
//     largest at the ends of any wedge that it crosses whole);
//   - the crossing lies within the segment, whose ends are the points of
//     the occluder's plane at least `inside` within all its edges at both
//     heights h - delta and h + delta (so at every height between: the
//     occluder is convex), shrunk further by how far a tilted plane's trace
//     moves over those heights along a sight line that meets it at no
//     less than kMinSine.
// Bins are widened by kWiden of pseudo-angle on both sides and distances
// rounded up, well beyond the rounding of the partner's bin and distance,
// so the test is exact in the sense of the culling: a lane it blocks, the
// lane's own ray finds blocked.  The fan only blocks; it never decides a
// lane in sight (docs/guide/visgraph-engine.md: proving lanes in sight this
// way cost more than casting them).
#pragma once

#include "cull_geometry.hpp"
#include "node_points.hpp"

#include <cstdint>
#include <memory>
#include <vector>

namespace attenuvis::visgraph::detail {

class EyePlane {
 public:
  static constexpr int kBins = 1024;
  // Per bin, the squared horizontal distance beyond which a node is
  // blocked (infinity: none is); `eye` the row it was filled for.
  struct Fan {
    alignas(64) float beyond_squared[kBins];
    std::size_t eye = ~std::size_t{0};
  };

  // The eyes' plane of `nodes`: h their median height, and the nodes
  // within a hundredth of the margin of it on the plane (delta their
  // largest distance from h).  Null when fewer than half of the nodes are
  // on it, or no wall crosses it.  `margin` as PairCulling's.
  static std::unique_ptr<EyePlane> build(const CullGeometry& geometry, const Points& nodes, double margin);

  // Is a node at height z on the plane?
  bool holds(double z) const { return z >= z_lo_ && z <= z_hi_; }
  // Fills `fan` for the eye at (x, y) (a node on the plane).
  void fill(double x, double y, Fan& fan) const;
  // The bit mask of the partners (x[l], y[l], z[l]), l < n <= 16, that
  // the fan of `eye` (a node on the plane) blocks: partners on the plane only.
  std::uint32_t lanes_blocked(const Fan& fan, const double* eye, const double* x, const double* y, const double* z,
                              int n) const;

 private:
  // A planar occluder's trace at height h: points p + s t (t a horizontal
  // unit vector), the plane's value g = nx x + ny y + g0 there (heights
  // folded into `slack` = |n_z| delta), and its edges' constraints
  // a_k s + b_k >= inside, the worst of the two heights.
  struct Wall {
    double px, py, tx, ty;
    double nx, ny, g0, slack;
    double a[4], b[4];
    double depth, shift;  // shift: the tilted trace's movement along a sight line (see above)
    double least;         // kMinSine |n_h|: the least |n.d| of a bin's boundary direction d
    // Where the quad's depth term is small for every eye (or nil), the
    // trace's ends for the largest `inside` any eye needs, [s_lo, s_hi],
    // so that no eye computes them; otherwise fixed is false.
    bool fixed;
    // Occluder::inside_sign: a face of a convex solid.  Beside `fixed`, in
    // the cache line fill_wall reads anyway (at the record's end it cost
    // every wall of every eye one more line).
    int inside_sign;
    double s_lo, s_hi;
    double cx, cy, radius;  // a circle around its widest trace
  };
  struct Cell {
    std::uint32_t first, count;  // wall_index_[first, first + count)
  };

  EyePlane() = default;
  void add_wall(const CullGeometry::Occluder& o);
  // The trace's ends [s_lo, s_hi] at least `inside` within the occluder's
  // edges at both heights; false when there are none.
  static bool trace_ends(const Wall& w, double inside, double& s_lo, double& s_hi);
  void build_grid();
  void fill_wall(const Wall& w, double ex, double ey, Fan& fan) const;
  // The largest squared distance in the bins that cell (i, j) can lie in
  // as seen from (ex, ey): a wall in the cell nearer than it may lower one.
  float cell_bound(int i, int j, double ex, double ey, const Fan& fan) const;
  double cell_near_squared(int i, int j, double ex, double ey) const;

  double h_ = 0, delta_ = 0, margin_ = 0, longest_ = 0;
  double z_lo_ = 0, z_hi_ = 0;  // h -+ delta
  std::vector<Wall> walls_;
  // The walls in a uniform grid of square cells of side cell_, by the box
  // of their widest trace.
  double cell_ = 0, x0_ = 0, y0_ = 0;
  int nx_ = 0, ny_ = 0;
  std::vector<Cell> cells_;
  std::vector<std::uint32_t> wall_index_;
  // The bins' boundary directions, widened: unit vectors at pseudo-angles
  // b - kWiden and b + 1 + kWiden (in bins).
  std::vector<double> lo_x_, lo_y_, hi_x_, hi_y_;
};

}  // namespace attenuvis::visgraph::detail
