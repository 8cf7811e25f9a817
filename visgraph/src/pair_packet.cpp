// Branch-free lane loops that GCC turns into SIMD code (versions for
// AVX-512, AVX2 and baseline x86-64, picked at run time).  Floating-point contraction
// is switched off for this file so that d = sqrt(dx^2 + dy^2 + dz^2) rounds
// the same way in every clone: the FMA-capable clones would otherwise fuse
// the products, and distances (hence C and the ray bounds) would depend on
// the CPU.
#pragma GCC optimize("fp-contract=off")

#include "pair_packet.hpp"

#include "lane_isa.hpp"

namespace attenuvis::visgraph::detail {

#ifdef ATTENUVIS_X86_DISPATCH
#define ATTENUVIS_LANE_CLONES __attribute__((target_clones("avx512f", "avx2", "default")))
#else
#define ATTENUVIS_LANE_CLONES
#endif

namespace {
// Excluded length at each end of a segment of length d (visibility.hpp):
// 1e-4 m + 1e-6 d, without FMA contraction (this file).  Internal linkage:
// an exported function may be interposed in a position-independent build,
// so GCC would call it lane by lane instead of vectorising the loop.
inline double end_gap(double d) { return 1e-4 + 1e-6 * d; }

// The body of build_packet, compiled once per instruction set: each
// target-specific wrapper below inlines it whole (flatten), so its loops are
// vectorised for that wrapper's target.
template <Isa isa>
inline void build_packet_lanes(double ox, double oy, double oz, const double* px, const double* py, const double* pz,
                               int n, double max_distance, PairPacket& p) {
  // Idle lanes read the origin itself (d = 0), never past the caller's data.
  alignas(64) double lx[kLanes], ly[kLanes], lz[kLanes];
  if (n == kLanes) {
    for (int l = 0; l < kLanes; ++l) lx[l] = px[l], ly[l] = py[l], lz[l] = pz[l];
  } else {
    for (int l = 0; l < kLanes; ++l) lx[l] = ox, ly[l] = oy, lz[l] = oz;
    for (int l = 0; l < n; ++l) lx[l] = px[l], ly[l] = py[l], lz[l] = pz[l];
  }
  // Masks as 0/1 doubles and selects of values computed on every lane: no
  // control flow, so each loop becomes straight SIMD code.
  alignas(64) double dx[kLanes], dy[kLanes], dz[kLanes], t_near[kLanes], active[kLanes];
  alignas(64) double cast[kLanes], coincident[kLanes];
  for (int l = 0; l < kLanes; ++l) active[l] = l < n ? 1.0 : 0.0;
  alignas(64) double d[kLanes];
  for (int l = 0; l < kLanes; ++l) {
    dx[l] = lx[l] - ox;
    dy[l] = ly[l] - oy;
    dz[l] = lz[l] - oz;
    d[l] = dx[l] * dx[l] + dy[l] * dy[l] + dz[l] * dz[l];
  }
  sqrt16<isa>(d);
  alignas(64) double gap[kLanes], ratio[kLanes];
  for (int l = 0; l < kLanes; ++l) {
    gap[l] = end_gap(d[l]);
    ratio[l] = gap[l] / d[l];     // inf for d = 0: never selected
  }
  for (int l = 0; l < kLanes; ++l) {
    const bool act = active[l] != 0.0;
    const bool apart = d[l] >= kCoincident;
    const bool candidate = act & apart & (d[l] <= max_distance);
    const bool close = d[l] <= 2 * gap[l];  // no room for geometry: visible without a ray
    const bool is_cast = candidate & !close;
    coincident[l] = (act & !apart) ? 1.0 : 0.0;
    cast[l] = is_cast ? 1.0 : 0.0;
    p.distance[l] = candidate ? d[l] : 0.0;
    p.visible[l] = (candidate & close) ? 1.0 : 0.0;
    t_near[l] = is_cast ? ratio[l] : 0.0;
  }
  double n_cast = 0, n_coincident = 0, n_visible = 0;
  for (int l = 0; l < kLanes; ++l) {
    n_cast += cast[l];
    n_coincident += coincident[l];
    n_visible += p.visible[l];
  }
  p.cast = static_cast<int>(n_cast);
  p.coincident = static_cast<int>(n_coincident);
  p.visible_count = static_cast<int>(n_visible);
  const float fx = static_cast<float>(ox), fy = static_cast<float>(oy), fz = static_cast<float>(oz);
  // Idle lanes get a valid unit ray so that Embree's ray checks never see a
  // zero direction, whatever it does with masked lanes.
  for (int l = 0; l < kLanes; ++l) {
    const double c = cast[l];
    p.ray.dir_x[l] = static_cast<float>(c * dx[l] + (1.0 - c));
    p.ray.dir_y[l] = static_cast<float>(c * dy[l]);
    p.ray.dir_z[l] = static_cast<float>(c * dz[l]);
    p.ray.tnear[l] = static_cast<float>(t_near[l]);
    p.ray.tfar[l] = static_cast<float>(1.0 - t_near[l]);  // 1 on idle lanes (t_near = 0)
  }
  for (int l = 0; l < kLanes; ++l) {
    p.valid[l] = -static_cast<int>(cast[l]);
    p.ray.org_x[l] = fx;
    p.ray.org_y[l] = fy;
    p.ray.org_z[l] = fz;
    p.ray.time[l] = 0.0f;
    p.ray.mask[l] = 0xFFFFFFFFu;
    p.ray.id[l] = 0;
    p.ray.flags[l] = 0;
  }
}

using BuildFunction = void (*)(double, double, double, const double*, const double*, const double*, int, double,
                              PairPacket&);
#ifdef ATTENUVIS_X86_DISPATCH
__attribute__((target("avx512f"), flatten)) void build_packet_avx512(double ox, double oy, double oz, const double* px,
                                                                    const double* py, const double* pz, int n,
                                                                    double max_distance, PairPacket& p) {
  build_packet_lanes<Isa::avx512>(ox, oy, oz, px, py, pz, n, max_distance, p);
}
__attribute__((target("avx2"), flatten)) void build_packet_avx2(double ox, double oy, double oz, const double* px,
                                                                const double* py, const double* pz, int n,
                                                                double max_distance, PairPacket& p) {
  build_packet_lanes<Isa::avx2>(ox, oy, oz, px, py, pz, n, max_distance, p);
}
#endif
__attribute__((flatten)) void build_packet_baseline(double ox, double oy, double oz, const double* px, const double* py,
                                                    const double* pz, int n, double max_distance, PairPacket& p) {
  build_packet_lanes<Isa::baseline>(ox, oy, oz, px, py, pz, n, max_distance, p);
}

BuildFunction pick_build_function() {
#ifdef ATTENUVIS_X86_DISPATCH
  const Isa isa = pick_isa();
  if (isa == Isa::avx512) return build_packet_avx512;
  if (isa == Isa::avx2) return build_packet_avx2;
#endif
  return build_packet_baseline;
}
}  // namespace

void build_packet(double ox, double oy, double oz, const double* px, const double* py, const double* pz, int n,
                  double max_distance, PairPacket& p) {
  static const BuildFunction chosen = pick_build_function();
  chosen(ox, oy, oz, px, py, pz, n, max_distance, p);
}

ATTENUVIS_LANE_CLONES
void resolve_packet(PairPacket& p) {
  // Arithmetic on 0/1 doubles and an integer count, which vectorise: a sum
  // of doubles (which the compiler may not reorder) and selects mixing
  // int, float and double lanes kept the loop scalar.
  alignas(64) double cast[kLanes], clear[kLanes];
  for (int l = 0; l < kLanes; ++l) cast[l] = static_cast<double>(-p.valid[l]);  // valid is -1 or 0
  for (int l = 0; l < kLanes; ++l) clear[l] = static_cast<double>(p.ray.tfar[l]) >= 0.0 ? 1.0 : 0.0;
  std::int32_t n_visible = 0;
  for (int l = 0; l < kLanes; ++l) {
    const double v = cast[l] * clear[l] + (1.0 - cast[l]) * p.visible[l];
    p.visible[l] = v;
    n_visible += static_cast<std::int32_t>(v);
  }
  p.visible_count = n_visible;
}

ATTENUVIS_LANE_CLONES
void accumulate_packet(const PairPacket& p, const std::int64_t* c_fixed, const std::int64_t* d_fixed, int K, int n,
                       std::int64_t* row_lanes, std::int64_t* acc, std::size_t N, std::size_t j0) {
  alignas(64) std::int64_t visible[kLanes];
  // A comparison, not a conversion: double to int64 has no vector
  // instruction below AVX-512DQ, and the loop stayed scalar.
  for (int l = 0; l < kLanes; ++l) visible[l] = p.visible[l] != 0.0 ? 1 : 0;
  // Lane-wise (vertical) adds; the row reduces its lanes once at its end.
  // Idle and invisible lanes hold zeros in every array.
  for (int l = 0; l < kLanes; ++l) row_lanes[l] += visible[l];
  for (int l = 0; l < kLanes; ++l) row_lanes[kLanes + l] += d_fixed[l];
  for (int k = 0; k < K; ++k)
    for (int l = 0; l < kLanes; ++l) row_lanes[(2 + k) * kLanes + l] += c_fixed[k * kLanes + l];
  if (!acc) return;
  // The same adds twice on purpose: a full packet (the common case) gets
  // loops of constant trip count, which the compiler vectorises without an
  // epilogue; the last packet of a row takes the general loops below.
  if (n == kLanes) {
    std::int64_t* a = acc + j0;
    for (int l = 0; l < kLanes; ++l) a[l] += visible[l];
    a = acc + N + j0;
    for (int l = 0; l < kLanes; ++l) a[l] += d_fixed[l];
    for (int k = 0; k < K; ++k) {
      a = acc + static_cast<std::size_t>(2 + k) * N + j0;
      const std::int64_t* c = c_fixed + k * kLanes;
      for (int l = 0; l < kLanes; ++l) a[l] += c[l];
    }
    return;
  }
  std::int64_t* a = acc + j0;
  for (int l = 0; l < n; ++l) a[l] += visible[l];
  a = acc + N + j0;
  for (int l = 0; l < n; ++l) a[l] += d_fixed[l];
  for (int k = 0; k < K; ++k) {
    a = acc + static_cast<std::size_t>(2 + k) * N + j0;
    const std::int64_t* c = c_fixed + k * kLanes;
    for (int l = 0; l < n; ++l) a[l] += c[l];
  }
}

}  // namespace attenuvis::visgraph::detail
