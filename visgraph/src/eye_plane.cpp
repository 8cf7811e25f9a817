// Sight lines in the eyes' plane (eye_plane.hpp).
#include "eye_plane.hpp"

#include "cull_math.hpp"
#include "lane_isa.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace attenuvis::visgraph::detail {

namespace {
constexpr int kBins = EyePlane::kBins;
constexpr double kBinsPerUnit = kBins / 4.0;  // the pseudo-angle runs over [0, 4)
// Bins are widened by this much on either side (in bins): ~6e-9 of a
// radian.  A partner the fan can block lies at least the margin (1 mm)
// away, so its direction is rounded by under 1e-10 (coordinates of a few
// km carry ~1e-13 m), and its pseudo-angle by ~1e-15 more.
constexpr double kWiden = 1e-6;
// A wall is used only where the sight lines cross it at least this sine
// of an angle (which bounds how far a tilted plane's trace moves along
// them); the farthest point of a bin beyond it is then finite.
constexpr double kMinSine = 1e-3;
// Squared distances are raised by this relative amount before they are
// rounded to the nearest float (a relative error under 6e-8), so the float
// stored is never below the distance; this also covers the partners'
// squared distances' rounding (~1e-16) and a bin's widening (which moves
// its farthest point by under 1e-9 / kMinSine relative).
constexpr double kRoundUp = 1e-6;
// Walls steeper than this |n_h| only (a roof or the ground is no wall).
constexpr double kMinHorizontalNormal = 0.5;
// The grid's cells, and how far from its eye a fan looks for walls:
// farther walls decide few pairs that the nearer ones leave, and cost as
// much to visit.  Measured on Delfshaven (four conditions): at 5 m on one
// thread, cells of 8, 16, 32 and 64 m with reaches of 100 to 2,000 m, the
// pass took 4.6-7.6 s, least with 32 m cells and 200-600 m; at the default
// 3 m on two threads, 23.6-27.2 s of CPU with 32 m cells and reaches of
// 200, 300 and 400 m (300 casting 7 % fewer pairs than 200 for the same
// time), and 28.4 and 25.6 s with 24 and 48 m cells at 300 m.
constexpr double kCell = 32.0;
constexpr double kReach = 300.0;

// A direction's pseudo-angle in [0, 4], monotone in its angle: the
// quadrant plus dy / (|dx| + |dy|) within it (4 only by rounding, for
// directions just below the x axis).
inline double pseudo_angle(double dx, double dy) {
  const double s = std::abs(dx) + std::abs(dy);
  const double r = dy / (s > 0 ? s : 1.0);
  return dx >= 0 ? (r < 0 ? 4.0 + r : r) : 2.0 - r;
}

// std::hypot guards against overflow at a cost that showed in profiles;
// a city's coordinates are far from it.
inline double distance(double dx, double dy) { return std::sqrt(dx * dx + dy * dy); }

// The unit direction at pseudo-angle p (any real; taken modulo 4).
void direction_at(double p, double& x, double& y) {
  p -= 4.0 * std::floor(p / 4.0);
  const int quadrant = std::min(3, static_cast<int>(p));
  const double f = p - quadrant;
  const double cx[4] = {1 - f, -f, -(1 - f), f}, cy[4] = {f, 1 - f, -f, -(1 - f)};
  const double l = std::hypot(cx[quadrant], cy[quadrant]);
  x = cx[quadrant] / l;
  y = cy[quadrant] / l;
}

// The largest of a fan's bins.  Sixteen running maxima, which the
// compiler keeps in vector registers: one chain through all 1,024 bins
// waited on each maximum in turn, and that took 4 % of a layout's run.
float largest_bin(const float* bins) {
  float most[16] = {};
  for (int b = 0; b < kBins; b += 16)
    for (int l = 0; l < 16; ++l) most[l] = std::max(most[l], bins[b + l]);
  for (int l = 1; l < 16; ++l) most[0] = std::max(most[0], most[l]);
  return most[0];
}

// Bins [begin, end) of a fan lowered by a wall: the farthest point of the
// bin beyond the wall's shifted line, k / min(n.d) over its two boundary
// directions (none where the line is met at too grazing an angle).
ATTENUVIS_CULL_CLONES
void lower_bins(float* beyond, const double* lo_x, const double* lo_y, const double* hi_x, const double* hi_y,
                std::size_t begin, std::size_t end, double nx, double ny, double k, double least) {
  for (std::size_t i = begin; i < end; ++i) {
    const double c = std::min(nx * lo_x[i] + ny * lo_y[i], nx * hi_x[i] + ny * hi_y[i]);
    const double r = k / c;
    const float d2 = c >= least ? static_cast<float>(r * r * (1 + kRoundUp)) : INFINITY;
    beyond[i] = std::min(beyond[i], d2);
  }
}
}  // namespace

std::unique_ptr<EyePlane> EyePlane::build(const CullGeometry& geometry, const Points& nodes, double margin) {
  if (nodes.size() < 2) return nullptr;
  std::vector<double> z = nodes.z;
  const auto middle = z.begin() + static_cast<std::ptrdiff_t>(z.size() / 2);
  std::nth_element(z.begin(), middle, z.end());
  const double h = *middle, tolerance = 0.01 * margin;
  double delta = 0;
  std::size_t on = 0;
  for (const double v : nodes.z)
    if (std::abs(v - h) <= tolerance) delta = std::max(delta, std::abs(v - h)), ++on;
  if (2 * on < nodes.size()) return nullptr;
  std::unique_ptr<EyePlane> plane(new EyePlane());
  plane->h_ = h;
  plane->delta_ = delta;
  plane->z_lo_ = h - delta, plane->z_hi_ = h + delta;
  plane->margin_ = margin;
  // The longest sight line between nodes on the plane, bounded by their box.
  const auto [xlo, xhi] = std::minmax_element(nodes.x.begin(), nodes.x.end());
  const auto [ylo, yhi] = std::minmax_element(nodes.y.begin(), nodes.y.end());
  plane->longest_ = std::hypot(*xhi - *xlo, *yhi - *ylo, 2 * delta);
  for (const CullGeometry::Occluder& o : geometry.occluders()) plane->add_wall(o);
  if (plane->walls_.empty()) return nullptr;
  plane->build_grid();
  for (int b = 0; b < kBins; ++b) {
    double x = 0, y = 0;
    direction_at((b - kWiden) / kBinsPerUnit, x, y);
    plane->lo_x_.push_back(x), plane->lo_y_.push_back(y);
    direction_at((b + 1 + kWiden) / kBinsPerUnit, x, y);
    plane->hi_x_.push_back(x), plane->hi_y_.push_back(y);
  }
  return plane;
}

// The occluder's trace at height h, if it is a wall that the plane crosses
// with room for the margin (its trace at inside = margin, the widest, not
// empty).
void EyePlane::add_wall(const CullGeometry::Occluder& o) {
  if (o.edges == 0) return;
  const double nh = std::hypot(o.n[0], o.n[1]);
  if (!(nh >= kMinHorizontalNormal)) return;
  Wall w;
  w.nx = o.n[0], w.ny = o.n[1];
  w.g0 = o.n[2] * h_ - o.c;  // g = n.(x, y, h) - c
  w.slack = std::abs(o.n[2]) * delta_;
  // A point of the trace (g = 0), its direction, and the in-plane
  // direction that rises by one in z: (w_h, 1), w_h = -n_z n_h / |n_h|^2.
  const double mx = o.n[0] / nh, my = o.n[1] / nh;
  w.px = -mx * w.g0 / nh, w.py = -my * w.g0 / nh;
  w.tx = -my, w.ty = mx;
  const double wx = -o.n[2] * o.n[0] / (nh * nh), wy = -o.n[2] * o.n[1] / (nh * nh);
  for (int k = 0; k < 4; ++k) {
    const double* u = o.u[k];
    w.a[k] = u[0] * w.tx + u[1] * w.ty;
    const double rise = u[0] * wx + u[1] * wy + u[2];
    w.b[k] = u[0] * w.px + u[1] * w.py + u[2] * h_ - o.o[k] - delta_ * std::abs(rise);
  }
  w.depth = o.depth;
  w.shift = 2 * w.slack / (nh * kMinSine);
  w.least = kMinSine * nh;
  w.inside_sign = o.inside_sign;
  double s_lo = 0, s_hi = 0;
  if (!trace_ends(w, margin_, s_lo, s_hi) || !std::isfinite(s_lo) || !std::isfinite(s_hi)) return;
  // An eye at least `side` from the plane needs inside <= the bound below
  // (fill_wall): where that is within a margin of the least, one interval
  // serves every eye, a little shorter than the eye's own.
  const double side = margin_ + w.depth;
  const double most = margin_ + w.shift + (w.depth > 0 ? w.depth + w.depth * longest_ / (2 * side) : 0.0);
  w.fixed = most <= 2 * margin_ && trace_ends(w, most, w.s_lo, w.s_hi);
  w.cx = w.px + 0.5 * (s_lo + s_hi) * w.tx, w.cy = w.py + 0.5 * (s_lo + s_hi) * w.ty;
  w.radius = 0.5 * (s_hi - s_lo) * (1 + 1e-9);
  walls_.push_back(w);
}

bool EyePlane::trace_ends(const Wall& w, double inside, double& s_lo, double& s_hi) {
  s_lo = -INFINITY, s_hi = INFINITY;
  for (int k = 0; k < 4; ++k) {
    const double rhs = inside - w.b[k];
    if (w.a[k] > 0) s_lo = std::max(s_lo, rhs / w.a[k]);
    else if (w.a[k] < 0) s_hi = std::min(s_hi, rhs / w.a[k]);
    else if (rhs > 0) return false;
  }
  return s_hi > s_lo;
}

void EyePlane::build_grid() {
  // Each wall's widest trace (inside = margin) by its box: the trace is
  // the circle's diameter along t, so the box is (cx, cy) -+ radius |t|
  // (radius already rounded up).
  std::vector<double> box(4 * walls_.size());
  double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
  for (std::size_t i = 0; i < walls_.size(); ++i) {
    const Wall& w = walls_[i];
    const double hx = w.radius * std::abs(w.tx), hy = w.radius * std::abs(w.ty);
    double* b = &box[4 * i];
    b[0] = w.cx - hx, b[1] = w.cy - hy, b[2] = w.cx + hx, b[3] = w.cy + hy;
    lo[0] = std::min(lo[0], b[0]), lo[1] = std::min(lo[1], b[1]);
    hi[0] = std::max(hi[0], b[2]), hi[1] = std::max(hi[1], b[3]);
  }
  cell_ = kCell;
  x0_ = lo[0], y0_ = lo[1];
  nx_ = std::max(1, static_cast<int>(std::ceil((hi[0] - lo[0]) / cell_)));
  ny_ = std::max(1, static_cast<int>(std::ceil((hi[1] - lo[1]) / cell_)));
  cells_.assign(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_), Cell{0, 0});
  const auto cell_of = [&](double v, double origin, int cells) {
    return std::clamp(static_cast<int>(std::floor((v - origin) / cell_)), 0, cells - 1);
  };
  const auto each_cell = [&](std::size_t i, auto&& f) {
    const double* b = &box[4 * i];
    for (int cy = cell_of(b[1], y0_, ny_); cy <= cell_of(b[3], y0_, ny_); ++cy)
      for (int cx = cell_of(b[0], x0_, nx_); cx <= cell_of(b[2], x0_, nx_); ++cx)
        f(cells_[static_cast<std::size_t>(cy) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(cx)]);
  };
  // Counted, then laid out.
  for (std::size_t i = 0; i < walls_.size(); ++i) each_cell(i, [](Cell& c) { ++c.count; });
  std::uint32_t next = 0;
  for (Cell& c : cells_) c.first = next, next += c.count, c.count = 0;
  wall_index_.resize(next);
  for (std::size_t i = 0; i < walls_.size(); ++i)
    each_cell(i, [&](Cell& c) { wall_index_[c.first + c.count++] = static_cast<std::uint32_t>(i); });
}

// Lowers the fan's bins that wall w spans as seen from (ex, ey).
void EyePlane::fill_wall(const Wall& w, double ex, double ey, Fan& fan) const {
  const double g_eye = w.nx * ex + w.ny * ey + w.g0;
  // A face of a convex solid seen from behind is left out: a sight line
  // that crosses it entered the solid through a face the eye sees, which
  // blocks it too, except within the margin of that face's edges or in
  // the bins that face spans only in part.  On the five layouts (one
  // thread, best of 60, the same output): 46.9, 17.9, 28.2, 22.1, 35.6 ms
  // -> 47.2, 16.7, 27.8, 20.8, 35.4 ms, with 0.2-1.7 % more pairs cast.
  if (w.inside_sign != 0 && (g_eye > 0) == (w.inside_sign > 0)) return;
  const double side = margin_ + w.depth;
  const double reach = std::abs(g_eye) - w.slack;  // the eye's least distance from the plane
  if (!(reach >= side)) return;
  // A quad's second triangle stands off the plane by `depth`
  // (CullGeometry::lanes_blocked); the longest sight line bounds its term.
  double s_lo = w.s_lo, s_hi = w.s_hi;
  if (!w.fixed) {
    const double inside = margin_ + w.shift + (w.depth > 0 ? w.depth + w.depth * longest_ / (reach + side) : 0.0);
    if (!trace_ends(w, inside, s_lo, s_hi)) return;
  }
  double ax = w.px + s_lo * w.tx - ex, ay = w.py + s_lo * w.ty - ey;
  double bx = w.px + s_hi * w.tx - ex, by = w.py + s_hi * w.ty - ey;
  const double turn = ax * by - ay * bx;
  if (turn == 0) return;
  if (turn < 0) std::swap(ax, bx), std::swap(ay, by);  // a to b counter-clockwise
  const double pa = pseudo_angle(ax, ay);
  double pb = pseudo_angle(bx, by);
  if (pb < pa) pb += 4.0;
  const long first = static_cast<long>(std::ceil(pa * kBinsPerUnit + kWiden));
  const long last = static_cast<long>(std::floor(pb * kBinsPerUnit - kWiden)) - 1;
  // The partner must lie beyond the plane by `side` on the far side, with
  // the heights' slack: g = toward * (side + slack).
  const double toward = g_eye > 0 ? -1.0 : 1.0;
  // Along direction d the line g = toward (side + slack) lies at
  // k / (toward n.d), k = side + slack + |g_eye|, largest where toward n.d
  // is least.
  const double k = side + w.slack + std::abs(g_eye);
  const double nx = toward * w.nx, ny = toward * w.ny;
  if (first > last) return;
  // Over [first, last] modulo kBins, in at most two contiguous runs.
  for (long run = first; run <= last;) {
    const std::size_t begin = static_cast<std::size_t>(run) & (kBins - 1);
    const std::size_t end = std::min<std::size_t>(kBins, begin + static_cast<std::size_t>(last - run + 1));
    lower_bins(fan.beyond_squared, lo_x_.data(), lo_y_.data(), hi_x_.data(), hi_y_.data(), begin, end, nx, ny, k,
               w.least);
    run += static_cast<long>(end - begin);
  }
}

void EyePlane::fill(double x, double y, Fan& fan) const {
  std::fill(std::begin(fan.beyond_squared), std::end(fan.beyond_squared), std::numeric_limits<float>::infinity());
  const int cx = static_cast<int>(std::floor((x - x0_) / cell_)), cy = static_cast<int>(std::floor((y - y0_) / cell_));
  // The rings within reach that hold cells of the grid.
  const int outermost = std::max({cx, nx_ - 1 - cx, cy, ny_ - 1 - cy});
  const int rings = std::min(outermost, static_cast<int>(std::ceil(kReach / cell_)));
  for (int ring = 0; ring <= rings; ++ring) {
    // A wall of ring + 1 or beyond lies at least ring * cell_ away: once
    // every bin is decided nearer than that, no farther wall lowers one.
    if (ring > 0) {
      const double near = static_cast<double>(ring - 1) * cell_;
      if (largest_bin(fan.beyond_squared) <= static_cast<float>(near * near)) break;
    }
    for (int j = cy - ring; j <= cy + ring; ++j) {
      if (j < 0 || j >= ny_) continue;
      const bool edge_row = j == cy - ring || j == cy + ring;
      for (int i = cx - ring; i <= cx + ring; i += edge_row ? 1 : 2 * ring) {
        // A cell nearer than none of the bins it spans is left out, and so
        // is a wall whose circle lies beyond all of them (its parts in
        // other cells are tried with theirs).
        const float bound = i >= 0 && i < nx_ && ring >= 2 ? cell_bound(i, j, x, y, fan) : INFINITY;
        if (i >= 0 && i < nx_ && bound > cell_near_squared(i, j, x, y)) {
          const Cell& c =
              cells_[static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) + static_cast<std::size_t>(i)];
          for (std::uint32_t k = 0; k < c.count; ++k) {
            const Wall& w = walls_[wall_index_[c.first + k]];
            const double least = std::max(0.0, distance(w.cx - x, w.cy - y) - w.radius);
            if (least * least < bound) fill_wall(w, x, y, fan);
          }
        }
        if (ring == 0) break;
      }
    }
  }
}

// The squared distance from (ex, ey) to the nearest point of cell (i, j).
double EyePlane::cell_near_squared(int i, int j, double ex, double ey) const {
  const double x0 = x0_ + i * cell_ - ex, y0 = y0_ + j * cell_ - ey;
  const double dx = std::max({x0, 0.0, -(x0 + cell_)}), dy = std::max({y0, 0.0, -(y0 + cell_)});
  return dx * dx + dy * dy;
}

float EyePlane::cell_bound(int i, int j, double ex, double ey, const Fan& fan) const {
  // The cell does not hold the eye (ring >= 2), so it spans under a half
  // turn: its corners' pseudo-angles, unwrapped around the first, bound it
  // (with a bin to spare for rounding).
  const double x0 = x0_ + i * cell_ - ex, y0 = y0_ + j * cell_ - ey;
  const double cx[4] = {x0, x0 + cell_, x0, x0 + cell_}, cy[4] = {y0, y0, y0 + cell_, y0 + cell_};
  const double p0 = pseudo_angle(cx[0], cy[0]);
  double lo = p0, hi = p0;
  for (int c = 1; c < 4; ++c) {
    double p = pseudo_angle(cx[c], cy[c]);
    if (p - p0 > 2) p -= 4;
    if (p0 - p > 2) p += 4;
    lo = std::min(lo, p), hi = std::max(hi, p);
  }
  float bound = 0;
  const long first = static_cast<long>(std::floor(lo * kBinsPerUnit)) - 1;
  const long last = static_cast<long>(std::floor(hi * kBinsPerUnit)) + 1;
  for (long b = first; b <= last; ++b)
    bound = std::max(bound, fan.beyond_squared[static_cast<std::size_t>(b) & (kBins - 1)]);
  return bound;
}

namespace {
// The lane test in portable code (one clone per instruction set below
// AVX-512, which takes fan_lanes_avx512).
#ifdef ATTENUVIS_X86_DISPATCH
__attribute__((target_clones("avx2", "default")))
#endif
std::uint32_t fan_lanes(const float* beyond, double ex, double ey, const double* x, const double* y, const double* z,
                        double z_lo, double z_hi, int n) {
  std::uint32_t blocked = 0;
  for (int l = 0; l < n; ++l) {
    const double dx = x[l] - ex, dy = y[l] - ey;
    const int b = std::min(kBins - 1, static_cast<int>(pseudo_angle(dx, dy) * kBinsPerUnit));
    const bool on = z[l] >= z_lo && z[l] <= z_hi;
    blocked |= static_cast<std::uint32_t>(on && dx * dx + dy * dy > static_cast<double>(beyond[b])) << l;
  }
  return blocked;
}

#ifdef ATTENUVIS_X86_DISPATCH
// The same test on AVX-512, eight lanes a step: the bins gathered and the
// comparisons kept in mask registers (GCC gathers the portable loop's bins
// one by one and builds its mask with shifts, and that loop took a sixth of
// a city's run).  The same operations as pseudo_angle, so the same bins;
// the maskz forms because GCC 12 warns that the plain forms' undefined
// pass-through operand is uninitialised.
__attribute__((target("avx512f"))) std::uint32_t fan_lanes_avx512(const float* beyond, double ex, double ey,
                                                                  const double* x, const double* y, const double* z,
                                                                  double z_lo, double z_hi, int n) {
  const __m512d eye_x = _mm512_set1_pd(ex), eye_y = _mm512_set1_pd(ey), zero = _mm512_setzero_pd();
  const __m512d one = _mm512_set1_pd(1.0), two = _mm512_set1_pd(2.0), four = _mm512_set1_pd(4.0);
  const __m512d scale = _mm512_set1_pd(kBinsPerUnit);
  const __m512d low = _mm512_set1_pd(z_lo), high = _mm512_set1_pd(z_hi);
  const __m256i last = _mm256_set1_epi32(kBins - 1);
  std::uint32_t blocked = 0;
  for (int h = 0; h < n; h += 8) {
    __mmask8 live = static_cast<__mmask8>(n - h >= 8 ? 0xFF : (1u << (n - h)) - 1u);
    const __m512d height = _mm512_maskz_loadu_pd(live, z + h);
    live = _mm512_mask_cmp_pd_mask(_mm512_mask_cmp_pd_mask(live, height, low, _CMP_GE_OQ), height, high, _CMP_LE_OQ);
    const __m512d dx = _mm512_sub_pd(_mm512_maskz_loadu_pd(live, x + h), eye_x);
    const __m512d dy = _mm512_sub_pd(_mm512_maskz_loadu_pd(live, y + h), eye_y);
    __m512d s = _mm512_add_pd(_mm512_abs_pd(dx), _mm512_abs_pd(dy));
    s = _mm512_mask_blend_pd(_mm512_cmp_pd_mask(s, zero, _CMP_GT_OQ), one, s);
    const __m512d r = _mm512_div_pd(dy, s);
    __m512d p = _mm512_mask_add_pd(r, _mm512_cmp_pd_mask(r, zero, _CMP_LT_OQ), four, r);
    p = _mm512_mask_sub_pd(p, _mm512_cmp_pd_mask(dx, zero, _CMP_LT_OQ), two, r);
    const __m256i bin = _mm256_min_epi32(_mm512_maskz_cvttpd_epi32(0xFF, _mm512_mul_pd(p, scale)), last);
    const __m512d far = _mm512_maskz_cvtps_pd(0xFF, _mm256_i32gather_ps(beyond, bin, 4));
    const __m512d d2 = _mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy));
    blocked |= static_cast<std::uint32_t>(_mm512_mask_cmp_pd_mask(live, d2, far, _CMP_GT_OQ)) << h;
  }
  return blocked;
}
#endif

using FanLanes = std::uint32_t (*)(const float*, double, double, const double*, const double*, const double*, double,
                                   double, int);
FanLanes pick_fan_lanes() {
#ifdef ATTENUVIS_X86_DISPATCH
  if (pick_isa() == Isa::avx512) return fan_lanes_avx512;
#endif
  return fan_lanes;
}
}  // namespace

std::uint32_t EyePlane::lanes_blocked(const Fan& fan, const double* eye, const double* x, const double* y,
                                      const double* z, int n) const {
  static const FanLanes lanes = pick_fan_lanes();
  return lanes(fan.beyond_squared, eye[0], eye[1], x, y, z, z_lo_, z_hi_, n);
}

}  // namespace attenuvis::visgraph::detail
