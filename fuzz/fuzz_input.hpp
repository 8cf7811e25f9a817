// What every fuzz target shares: the input as text, and the rule that a
// reader may reject input only with the exceptions its header documents
// (std::invalid_argument, std::runtime_error).  Anything else — another
// exception, a crash, a sanitizer report, a hang, a runaway allocation — is a
// finding.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
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

#include <cstdio>
#include <string>

#include <unistd.h>

namespace attenuvis::fuzz {

// Readers that take a path get the input through a file of this process's own.
class InputFile {
 public:
  InputFile(const std::uint8_t* data, std::size_t size, const char* extension)
      : path_("/tmp/attenuvis_fuzz_" + std::to_string(::getpid()) + extension) {
    std::FILE* f = std::fopen(path_.c_str(), "wb");
    if (!f) std::abort();
    if (size) std::fwrite(data, 1, size, f);
    std::fclose(f);
  }
  ~InputFile() { std::remove(path_.c_str()); }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace attenuvis::fuzz
