// Small complex-arithmetic helpers of the Mie core (template implementation
// detail): the reciprocal and squared modulus without library calls, and the
// same operations written once for real and complex operands.
#pragma once

#include <cstddef>
#include <type_traits>

namespace attenuvis::mie::detail {

// |z|² of a complex number, without the square root.
template <class C>
inline auto norm2(const C& z) { return z.real() * z.real() + z.imag() * z.imag(); }

// 1/z for complex z by conj(z)/|z|²: one real division, no library call
// (std::complex division goes through __divdc3).  Safe here because every
// quantity inverted in the core stays within 1e±150.
template <class C>
inline C recip(const C& z) {
  const auto s = 1 / norm2(z);
  return C(z.real() * s, -z.imag() * s);
}

// z·w written out as (ac − bd) + i(ad + bc): the products and sums, in the
// order, that the compiler's complex multiplication rounds, without its
// NaN-recovery test (a compare and branch per product, and a call to
// __muldc3 when it fires).  Every quantity multiplied in the core is finite,
// so the result is the same bits; in the per-order recurrences the test was
// a tenth of the instructions at small x.
template <class C>
inline C cmul(const C& z, const C& w) {
  return C(z.real() * w.real() - z.imag() * w.imag(), z.real() * w.imag() + z.imag() * w.real());
}

// An order or coefficient index as a real number.  Through a signed integer:
// x86-64 converts that in one instruction, an unsigned one takes a test and
// a branch (the value is the same; indices stay far below 2^53).
template <class Real>
inline Real index_real(std::size_t k) {
  return Real(static_cast<long long>(k));
}

// 1/v and |v|² for T = Real or T = complex of Real.
template <class Real, class T>
inline T inv(const T& v) {
  if constexpr (std::is_same_v<T, Real>) return Real(1) / v;
  else return recip(v);
}
template <class Real, class T>
inline T mul(const T& a, const T& b) {
  if constexpr (std::is_same_v<T, Real>) return a * b;
  else return cmul(a, b);
}
template <class Real, class T>
inline Real mag2(const T& v) {
  if constexpr (std::is_same_v<T, Real>) return v * v;
  else return norm2(v);
}

}  // namespace attenuvis::mie::detail
