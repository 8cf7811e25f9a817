// The Legendre moments and the generalised-spherical-function expansion
// (attenuvis/mie/legendre_moments.hpp) run in 50-digit arithmetic on the
// referee's Mie coefficients: the same template code, compiled in its own
// translation unit (mie/src/legendre_moments_referee.cpp).  For tests and
// benchmarks; about 5 s at x = 100 and several minutes at x = 1000 (O(N²)
// multiprecision operations).
#pragma once

#include <cstddef>
#include <vector>

#include "attenuvis/mie/legendre_moments.hpp"
#include "attenuvis/mie/referee.hpp"

namespace attenuvis::mie {

// phase_function_moments() and scattering_matrix_expansion() at 50 digits, from
// the referee's coefficients (the tests' reference for the double versions).
std::vector<Referee> phase_function_moments_referee(const Scattering<Referee>& s,
                                                    std::size_t max_order = all_orders);
ScatteringMatrixExpansion<Referee> scattering_matrix_expansion_referee(const Scattering<Referee>& s,
                                                                       std::size_t max_order = all_orders);

// Nodes θ (radians, μ >= 0 half, ascending) and weights of the Gauss–Legendre rule
// of the given order, as the moment code uses them, in double and in 50 digits:
// lets the tests measure the accuracy of the double rule.
void gauss_legendre_half_rule(std::size_t order, std::vector<double>& theta, std::vector<double>& weight);
void gauss_legendre_half_rule_referee(std::size_t order, std::vector<Referee>& theta,
                                      std::vector<Referee>& weight);

}  // namespace attenuvis::mie
