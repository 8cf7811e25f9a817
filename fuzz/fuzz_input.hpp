// What every fuzz target shares: the input as text, and the rule that a
// reader may reject input only with the exceptions its header documents
// (std::invalid_argument, std::runtime_error).  Anything else — another
// exception, a crash, a sanitizer report, a hang, a runaway allocation — is a
// finding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace attenuvis::fuzz {

inline std::string as_text(const std::uint8_t* data, std::size_t size) {
  return std::string(reinterpret_cast<const char*>(data), size);
}

template <typename F>
void expect_clean_rejection(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument&) {
  } catch (const std::runtime_error&) {
  }
}

}  // namespace attenuvis::fuzz
