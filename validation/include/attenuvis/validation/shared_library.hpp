// A shared library opened with dlopen for one C entry point: the other Mie
// cores the benchmarks time beside the current one (an earlier build of it,
// MIEV0).  Open for the object's lifetime; symbols stay local to it.
#pragma once

#include <string>

namespace attenuvis::validation {

// A shared library opened with dlopen and one symbol of it, closed on destruction.
class SharedLibrary {
 public:
  /// Opens `path` and finds `symbol`; throws std::runtime_error
  ///   "cannot load <what> <path>: <loader's message>", or
  ///   "<path> has no <symbol> (build it with <build_script>)".
  SharedLibrary(const std::string& path, const std::string& what, const char* symbol,
                const std::string& build_script);
  ~SharedLibrary();
  SharedLibrary(const SharedLibrary&) = delete;
  SharedLibrary& operator=(const SharedLibrary&) = delete;

  void* entry() const { return entry_; }
  const std::string& path() const { return path_; }

 private:
  void* handle_ = nullptr;
  void* entry_ = nullptr;
  std::string path_;
};

}  // namespace attenuvis::validation
