// Gauss-Kronrod product integration: see product_rule.hpp.
#include "product_rule.hpp"

#include <algorithm>
#include <limits>

#include <Eigen/Dense>
#include <boost/math/special_functions/legendre.hpp>

#include "attenuvis/io/check.hpp"

namespace attenuvis::weather::detail {
namespace {

// P_0(u) ... P_{count-1}(u) by Bonnet's recurrence (Boost.Math's legendre_next).
void legendre_values(double u, std::size_t count, double* p) {
  p[0] = 1;
  if (count > 1) p[1] = u;
  for (std::size_t l = 1; l + 1 < count; ++l)
    p[l + 1] = boost::math::legendre_next(static_cast<unsigned>(l), u, p[l], p[l - 1]);
}

// C = V^-1, V_jl = P_l(u_j) on the given nodes, row-major by degree l.
std::vector<double> legendre_inverse(const std::vector<double>& nodes) {
  const auto n = static_cast<Eigen::Index>(nodes.size());
  Eigen::MatrixXd v(n, n);
  std::vector<double> p(nodes.size());
  for (Eigen::Index j = 0; j < n; ++j) {
    legendre_values(nodes[static_cast<std::size_t>(j)], nodes.size(), p.data());
    for (Eigen::Index l = 0; l < n; ++l) v(j, l) = p[static_cast<std::size_t>(l)];
  }
  const Eigen::MatrixXd c = v.fullPivLu().inverse();
  std::vector<double> out(nodes.size() * nodes.size());
  for (Eigen::Index l = 0; l < n; ++l)
    for (Eigen::Index j = 0; j < n; ++j) out[static_cast<std::size_t>(l * n + j)] = c(l, j);
  return out;
}

// int_{-1}^{u} P_l for l = 0 ... count - 1: u + 1, and (P_{l+1} - P_{l-1}) / (2l + 1).
void legendre_antiderivatives(double u, std::size_t count, double* out) {
  std::vector<double> p(count + 1);
  legendre_values(u, count + 1, p.data());
  out[0] = u + 1;
  for (std::size_t l = 1; l < count; ++l) out[l] = (p[l + 1] - p[l - 1]) / static_cast<double>(2 * l + 1);
}

}  // namespace

ProductRule::ProductRule(const Rule& rule) {
  const OrderedNodes nodes = ordered_nodes(rule);
  node_ = nodes.u;
  std::vector<double> gauss_nodes;
  for (std::size_t j = 0; j < node_.size(); ++j)
    if (nodes.gauss_weight[j] != 0) gauss_slot_.push_back(j), gauss_nodes.push_back(node_[j]);
  kronrod_inverse_ = legendre_inverse(node_);
  gauss_inverse_ = legendre_inverse(gauss_nodes);
}

void ProductRule::weights(const std::vector<Segment>& segments, const std::vector<std::complex<double>>& x,
                          std::vector<std::complex<double>>& kronrod,
                          std::vector<std::complex<double>>& gauss) const {
  using Complex = std::complex<double>;
  const std::size_t count = node_.size(), ng = gauss_slot_.size();
  ATTENUVIS_CHECK_EQ(x.size(), count);
  // A_l and B_l: the segments' alpha and beta against int_s P_l du.
  std::vector<Complex> a(count), b(count);
  std::vector<double> lo(count), hi(count);
  double hi_at = std::numeric_limits<double>::quiet_NaN();  // where hi was taken: segments are usually contiguous
  for (const Segment& s : segments) {
    if (!(s.u1 > s.u0)) continue;
    const double u0 = std::max(s.u0, -1.0), u1 = std::min(s.u1, 1.0);
    if (u0 == hi_at) lo.swap(hi);
    else legendre_antiderivatives(u0, count, lo.data());
    legendre_antiderivatives(u1, count, hi.data());
    hi_at = u1;
    for (std::size_t l = 0; l < count; ++l) {
      const double d = hi[l] - lo[l];
      a[l] += s.alpha * d;
      b[l] += s.beta * d;
    }
  }
  // omega at node `slot`, column i of an inverse of size n (degrees 0 ... n - 1).
  const auto omega = [&](const std::vector<double>& inverse, std::size_t n, std::size_t i, std::size_t slot) {
    Complex w{};
    for (std::size_t l = 0; l < n; ++l) w += inverse[l * n + i] * (a[l] + x[slot] * b[l]);
    return w;
  };
  kronrod.assign(count, Complex{});
  gauss.assign(count, Complex{});
  for (std::size_t j = 0; j < count; ++j) kronrod[j] = omega(kronrod_inverse_, count, j, j);
  for (std::size_t g = 0; g < ng; ++g) gauss[gauss_slot_[g]] = omega(gauss_inverse_, ng, g, gauss_slot_[g]);
}

}  // namespace attenuvis::weather::detail
