// Small complex-arithmetic helpers of the Mie core (template implementation
// detail): the reciprocal and squared modulus without library calls, and the
// same operations written once for real and complex operands.
#pragma once

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

// 1/v and |v|² for T = Real or T = complex of Real.
template <class Real, class T>
inline T inv(const T& v) {
  if constexpr (std::is_same_v<T, Real>) return Real(1) / v;
  else return recip(v);
}
template <class Real, class T>
inline Real mag2(const T& v) {
  if constexpr (std::is_same_v<T, Real>) return v * v;
  else return norm2(v);
}

}  // namespace attenuvis::mie::detail
