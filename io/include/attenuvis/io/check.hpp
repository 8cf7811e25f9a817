// Internal invariants, stated where the code relies on them (as pbrt's CHECK
// and CHECK_EQ): an enum whose order a table follows, a length two arrays
// must share, a count a loop has promised.  They are not input checks (bad
// input throws with a message for the user); a failed check is a bug in
// attenuvis and stops the program with the expression, both values, the file
// and the line.
//
// Active where ATTENUVIS_CHECKS is defined: Debug builds and the sanitizer
// tree (CMakeLists.txt).  In Release they compile to nothing, so they may sit
// on paths that must stay fast; the operands are still type-checked.
//
//   ATTENUVIS_CHECK(i < n);
//   ATTENUVIS_CHECK_EQ(names.size(), std::size_t(Component::count));
#pragma once

#include <sstream>
#include <string>

namespace attenuvis::io {

// The text a failed check prints: "attenuvis: internal check failed at
// FILE:LINE: EXPR (VALUES)", VALUES "a = 3, b = 4" for a comparison, empty
// for a plain condition.
std::string check_failure_text(const char* file, int line, const char* expression, const std::string& values);

// Prints check_failure_text to stderr and aborts.
[[noreturn]] void check_failed(const char* file, int line, const char* expression, const std::string& values);

namespace detail {
template <class A, class B>
std::string check_values(const char* a_text, const A& a, const char* b_text, const B& b) {
  std::ostringstream out;
  out.precision(17);
  out << a_text << " = " << a << ", " << b_text << " = " << b;
  return out.str();
}
}  // namespace detail

}  // namespace attenuvis::io

#if defined(ATTENUVIS_CHECKS)
#define ATTENUVIS_CHECK(condition) \
  ((condition) ? (void)0 : ::attenuvis::io::check_failed(__FILE__, __LINE__, #condition, std::string()))
#define ATTENUVIS_CHECK_OP(a, op, b)                                                                     \
  do {                                                                                                   \
    const auto& attenuvis_check_a = (a);                                                                 \
    const auto& attenuvis_check_b = (b);                                                                 \
    if (!(attenuvis_check_a op attenuvis_check_b))                                                       \
      ::attenuvis::io::check_failed(                                                                     \
          __FILE__, __LINE__, #a " " #op " " #b,                                                         \
          ::attenuvis::io::detail::check_values(#a, attenuvis_check_a, #b, attenuvis_check_b));          \
  } while (false)
#else
#define ATTENUVIS_CHECK(condition) ((void)sizeof(static_cast<bool>(condition)))
#define ATTENUVIS_CHECK_OP(a, op, b) ((void)sizeof((a)op(b)))
#endif

#define ATTENUVIS_CHECK_EQ(a, b) ATTENUVIS_CHECK_OP(a, ==, b)
#define ATTENUVIS_CHECK_NE(a, b) ATTENUVIS_CHECK_OP(a, !=, b)
#define ATTENUVIS_CHECK_LT(a, b) ATTENUVIS_CHECK_OP(a, <, b)
#define ATTENUVIS_CHECK_LE(a, b) ATTENUVIS_CHECK_OP(a, <=, b)
#define ATTENUVIS_CHECK_GT(a, b) ATTENUVIS_CHECK_OP(a, >, b)
#define ATTENUVIS_CHECK_GE(a, b) ATTENUVIS_CHECK_OP(a, >=, b)
