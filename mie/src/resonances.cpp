// The poles of aₙ, bₙ near the real axis: see attenuvis/mie/resonances.hpp.
#include "attenuvis/mie/resonances.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "attenuvis/mie/detail/complex_ops.hpp"
#include "attenuvis/mie/detail/lentz.hpp"

namespace attenuvis::mie {
namespace {

using Complex = std::complex<double>;

// Dₙ(z) = ψₙ'(z)/ψₙ(z) from Lentz's continued fraction for ψ_{n−1}/ψₙ = Dₙ + n/z.
template <class T>
T reciprocal(const T& z) {
  if constexpr (std::is_same_v<T, double>) return 1 / z;
  else return detail::recip(z);  // one real division, not the library's complex one
}
template <class T>
T log_derivative_at(int n, T z) {
  const T inv_z = reciprocal(z);
  const auto k_over_z = [inv_z](double k) { return k * inv_z; };
  return detail::riccati_psi_ratio<T, double>(static_cast<std::size_t>(n), k_over_z) - double(n) * inv_z;
}

// The real functions of one order at a real x (lossless index n_r): F_r of
// either mode, their derivatives, the sign of ψₙ(n_r x) (which branch of
// Dₙ(n_r x) x lies on) and the width estimate of resonances.hpp.
struct RealOrder {
  double c = 0, dc = 0;             // Cₙ(x), Cₙ'(x)
  double d_inner = 0, dd_inner = 0; // Dₙ(n_r x), its derivative in z
  double d_outer = 0;               // Dₙ(x)
  int psi_sign = 1;                 // sign of ψₙ(n_r x)
  double log_tunnelling = 0;        // ln |ψₙ(x)/χₙ(x)|
};

double riccati_slope(int n, double z, double d) { return n * (n + 1.0) / (z * z) - 1 - d * d; }

double f_real(const RealOrder& o, ResonanceMode mode, double index) {
  return mode == ResonanceMode::electric ? index * o.c - o.d_inner : o.c - index * o.d_inner;
}
double f_real_slope(const RealOrder& o, ResonanceMode mode, double index) {
  return mode == ResonanceMode::electric ? index * (o.dc - o.dd_inner) : o.dc - index * index * o.dd_inner;
}

// The radiative half-width a resonance of this order would have at x, from
// the tunnelling factor and the smooth functions alone: Dₙ(n_r x) replaced by
// its value at the zero of F_r (n_r Cₙ for aₙ, Cₙ/n_r for bₙ), so that the
// estimate does not depend on where on its branch x lies.
double width_at(int n, double x, const RealOrder& o, ResonanceMode mode, double index) {
  const double z = index * x;
  const double d_root = mode == ResonanceMode::electric ? index * o.c : o.c / index;
  const double slope_root = riccati_slope(n, z, d_root);
  const double numerator = mode == ResonanceMode::electric ? index * (o.d_outer - d_root) : o.d_outer - index * d_root;
  const double denominator =
      mode == ResonanceMode::electric ? index * (o.dc - slope_root) : o.dc - index * index * slope_root;
  return std::exp(o.log_tunnelling) * std::abs(numerator) / std::max(std::abs(denominator), 1e-300);
}

// Every order up to `top` at one real x: Dₖ(n_r x) and Dₖ(x) downward from
// Lentz's start at `top`, χₖ(x) upward (rescaled, its logarithm kept), and
// the sign of ψₖ(n_r x) as the product of the signs of ψₖ/ψₖ₋₁ = 1/(Dₖ + k/z).
std::vector<RealOrder> orders_at(double x, double index, int top) {
  std::vector<RealOrder> out(static_cast<std::size_t>(top) + 1);
  const double z = index * x;
  double d_in = log_derivative_at<double>(top, z), d_out = log_derivative_at<double>(top, x);
  std::vector<double> ratio_in(out.size()), ratio_out(out.size());
  for (int k = top; k >= 1; --k) {
    out[k].d_inner = d_in;
    out[k].d_outer = d_out;
    ratio_in[k] = d_in + k / z;   // ψ_{k−1}/ψ_k at z
    ratio_out[k] = d_out + k / x; // at x
    d_in = k / z - 1 / ratio_in[k];
    d_out = k / x - 1 / ratio_out[k];
  }
  int sign = std::sin(z) >= 0 ? 1 : -1;
  double log_psi = std::log(std::abs(std::sin(x)));
  double chi_prev = std::cos(x), chi = std::cos(x) / x + std::sin(x), log_scale = 0;
  for (int k = 1; k <= top; ++k) {
    if (k > 1) {
      const double next = (2 * k - 1) / x * chi - chi_prev;
      chi_prev = chi;
      chi = next;
    }
    if (std::abs(chi) > 1e200) {  // keep the values in range, their ratio is what matters
      chi /= 1e200;
      chi_prev /= 1e200;
      log_scale += std::log(1e200);
    }
    sign *= ratio_in[k] >= 0 ? 1 : -1;
    log_psi -= std::log(std::abs(ratio_out[k]));
    RealOrder& o = out[k];
    o.psi_sign = sign;
    o.c = chi_prev / chi - k / x;
    o.dc = riccati_slope(k, x, o.c);
    o.dd_inner = riccati_slope(k, z, o.d_inner);
    o.log_tunnelling = log_psi - (std::log(std::abs(chi)) + log_scale);
  }
  return out;
}

// One order at one real x, for the zero search: what orders_at gives for
// order n, without the tunnelling factor and without tables.
RealOrder order_at(double x, double index, int n) {
  RealOrder o;
  const double z = index * x;
  double d = log_derivative_at<double>(n, z);
  o.d_inner = d;
  int sign = 1;
  for (int k = n; k >= 1; --k) {
    const double ratio = d + k / z;  // ψ_{k−1}/ψ_k at z
    if (ratio < 0) sign = -sign;
    d = k / z - 1 / ratio;
  }
  o.psi_sign = std::sin(z) >= 0 ? sign : -sign;
  double chi_prev = std::cos(x), chi = std::cos(x) / x + std::sin(x);
  for (int k = 2; k <= n; ++k) {
    const double next = (2 * k - 1) / x * chi - chi_prev;
    chi_prev = chi;
    chi = next;
    if (std::abs(chi) > 1e200) chi /= 1e200, chi_prev /= 1e200;
  }
  o.c = chi_prev / chi - n / x;
  o.dc = riccati_slope(n, x, o.c);
  o.dd_inner = riccati_slope(n, z, o.d_inner);
  return o;
}

std::string describe(const ResonanceBracket& b) {
  std::ostringstream os;
  os.precision(17);
  os << (b.mode == ResonanceMode::electric ? "a_" : "b_") << b.order << " in [" << b.x_lo << ", " << b.x_hi << "]";
  return os.str();
}

// The zero of F_r in the bracket: bisection on the branch the bracket names
// (a point where ψₙ(n_r x) has the other sign lies beyond the branch's end,
// past the jump of F_r from +∞ to −∞), with Newton steps where they stay inside.
double real_zero(const ResonanceBracket& b, double index) {
  const double eps = std::numeric_limits<double>::epsilon();
  double lo = b.x_lo, hi = b.x_hi;
  double x = 0.5 * (lo + hi);
  for (int it = 0; it < 200 && hi - lo > 4 * eps * hi; ++it) {
    const RealOrder o = order_at(x, index, b.order);
    double next = 0;
    if (o.psi_sign != b.branch_sign) {
      (b.branch_holds_lo ? hi : lo) = x;
      next = 0.5 * (lo + hi);
    } else {
      const double f = f_real(o, b.mode, index);
      (f > 0 ? hi : lo) = x;
      next = 0.5 * (lo + hi);
      const double newton = x - f / f_real_slope(o, b.mode, index);
      if (std::abs(newton - x) <= 2 * eps * x) return x;
      if (newton > lo && newton < hi) next = newton;
    }
    x = next;
  }
  return x;
}

// The complex functions of one order at complex x for the index m: Gₙ(x) by
// the upward ratio recurrence of ξ (stable for the outgoing wave), Dₙ(mx) and
// Dₙ(x) from Lentz's continued fraction.
struct ComplexOrder {
  Complex g, d_inner, d_outer;
};
ComplexOrder complex_order_at(Complex x, Complex m, int n) {
  const Complex inv_x = detail::recip(x);
  Complex ratio = inv_x - Complex(0.0, 1.0);  // ξ₁/ξ₀, ξ₀ = −i e^{ix}
  for (int k = 1; k < n; ++k) ratio = (2.0 * k + 1.0) * inv_x - detail::recip(ratio);
  return {detail::recip(ratio) - double(n) * inv_x, log_derivative_at<Complex>(n, m * x),
          log_derivative_at<Complex>(n, x)};
}
Complex f_complex(const ComplexOrder& o, ResonanceMode mode, Complex m) {
  return mode == ResonanceMode::electric ? m * o.g - o.d_inner : o.g - m * o.d_inner;
}
Complex f_complex_slope(const ComplexOrder& o, ResonanceMode mode, Complex m, Complex x, int n) {
  const Complex nn = n * (n + 1.0);
  const Complex dg = nn / (x * x) - 1.0 - o.g * o.g;
  const Complex dd = nn / (m * x * m * x) - 1.0 - o.d_inner * o.d_inner;
  return mode == ResonanceMode::electric ? m * (dg - dd) : dg - m * m * dd;
}

// ψₙ(x)/ξₙ(x) at complex x as a running product of (ψₖ/ψₖ₋₁)/(ξₖ/ξₖ₋₁),
// from ψ₀/ξ₀ = i sin(x) e^{−ix}; Dₖ(x) downward from Lentz's start at n.
Complex psi_over_xi(Complex x, int n) {
  std::vector<Complex> psi_ratio(static_cast<std::size_t>(n) + 1);  // ψₖ/ψₖ₋₁
  const Complex inv_x = detail::recip(x);
  Complex d = log_derivative_at<Complex>(n, x);
  for (int k = n; k >= 1; --k) {
    psi_ratio[k] = detail::recip(d + double(k) * inv_x);
    d = double(k) * inv_x - psi_ratio[k];
  }
  Complex product = Complex(0.0, 1.0) * std::sin(x) * std::exp(Complex(0.0, -1.0) * x);
  Complex xi_ratio = inv_x - Complex(0.0, 1.0);
  for (int k = 1; k <= n; ++k) {
    if (k > 1) xi_ratio = (2.0 * k - 1.0) * inv_x - detail::recip(xi_ratio);
    product *= psi_ratio[k] * detail::recip(xi_ratio);
  }
  return product;
}

void check_range(double index, double x_lo, double x_hi) {
  if (!(index > 1 && index <= 10 && x_lo > 0 && x_lo <= x_hi && x_hi <= 1e5)) {
    std::ostringstream os;
    os.precision(17);
    os << "mie::resonance_brackets: needs 1 < index <= 10 and 0 < x_lo <= x_hi <= 1e5; got index " << index
       << ", x in [" << x_lo << ", " << x_hi << "]";
    throw std::invalid_argument(os.str());
  }
}

// The brackets between two grid points for one order (orders_at's rows at
// x_prev and x): F_r rises on each branch of Dₙ(n_r x), so with no zero of
// ψₙ(n_r x) between them a zero of F_r lies there iff F_r went from − to +;
// with one, the left branch holds a zero iff F_r(x_prev) < 0 and the right
// one iff F_r(x) > 0.
void brackets_between(int n, double x_prev, const RealOrder& before, double x, const RealOrder& after, double index,
                      std::vector<ResonanceBracket>& out) {
  for (ResonanceMode mode : {ResonanceMode::electric, ResonanceMode::magnetic}) {
    const double f0 = f_real(before, mode, index), f1 = f_real(after, mode, index);
    const double width = width_at(n, x, after, mode, index);
    auto add = [&](int sign, bool holds_lo) {
      out.push_back({n, mode, x_prev, x, width, sign, holds_lo});
    };
    if (before.psi_sign == after.psi_sign) {
      if (f0 < 0 && f1 >= 0) add(after.psi_sign, true);
    } else {
      if (f0 < 0) add(before.psi_sign, true);
      if (f1 > 0) add(after.psi_sign, false);
    }
  }
}

}  // namespace

std::vector<ResonanceBracket> resonance_brackets(double index, double x_lo, double x_hi) {
  check_range(index, x_lo, x_hi);
  const double step = std::min(0.5, 1.0 / index);
  std::vector<ResonanceBracket> out;
  double x_prev = std::max(x_lo - step, 0.5 * step);
  std::vector<RealOrder> prev = orders_at(x_prev, index, static_cast<int>(index * x_prev) + 2);
  for (double x = x_prev + step; x_prev < x_hi; x_prev = x, x += step) {
    const int top = static_cast<int>(index * x) + 2;
    std::vector<RealOrder> rows = orders_at(x, index, top);
    // Orders whose barrier holds both grid points (x < n), up to those whose
    // ψₙ(n_r x) has not reached its first zero (n >= n_r x: F_r < 0 there).
    for (int n = std::max(1, static_cast<int>(std::ceil(x))); n < static_cast<int>(prev.size()); ++n)
      if (static_cast<double>(n) > x) brackets_between(n, x_prev, prev[n], x, rows[n], index, out);
    prev.swap(rows);
  }
  return out;
}

Resonance locate_resonance(const ResonanceBracket& b, Complex m) {
  if (!(m.imag() >= 0 && m.imag() <= 1e-2)) throw std::invalid_argument("mie::locate_resonance: needs 0 <= Im m <= 1e-2");
  const int n = b.order;
  Complex x = real_zero(b, m.real());
  const double eps = std::numeric_limits<double>::epsilon();
  bool converged = false;
  for (int it = 0; it < 60 && !converged; ++it) {
    const ComplexOrder o = complex_order_at(x, m, n);
    const Complex step = f_complex(o, b.mode, m) / f_complex_slope(o, b.mode, m, x, n);
    x -= step;
    converged = std::abs(step) <= 8 * eps * std::abs(x);
  }
  if (!converged || !(x.imag() < 0) || x.real() < b.x_lo - 1 || x.real() > b.x_hi + 1)
    throw std::runtime_error("mie::locate_resonance: Newton did not reach the pole of " + describe(b));
  const ComplexOrder o = complex_order_at(x, m, n);
  const Complex numerator = b.mode == ResonanceMode::electric ? m * o.d_outer - o.d_inner : o.d_outer - m * o.d_inner;
  Resonance r;
  r.order = n;
  r.mode = b.mode;
  r.pole = x;
  r.residue = psi_over_xi(x, n) * numerator / f_complex_slope(o, b.mode, m, x, n);
  return r;
}

}  // namespace attenuvis::mie
