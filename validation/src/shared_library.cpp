// See attenuvis/validation/shared_library.hpp.
#include "attenuvis/validation/shared_library.hpp"

#include <dlfcn.h>

#include <stdexcept>

namespace attenuvis::validation {

SharedLibrary::SharedLibrary(const std::string& path, const std::string& what, const char* symbol,
                             const std::string& build_script)
    : path_(path) {
  handle_ = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (!handle_) throw std::runtime_error("cannot load " + what + " " + path + ": " + ::dlerror());
  entry_ = ::dlsym(handle_, symbol);
  if (!entry_) {
    ::dlclose(handle_);
    throw std::runtime_error(path + " has no " + symbol + " (build it with " + build_script + ")");
  }
}

SharedLibrary::~SharedLibrary() { ::dlclose(handle_); }

}  // namespace attenuvis::validation
