// The installed share directory (see install_paths.hpp).
#include "attenuvis/io/install_paths.hpp"

#include <dlfcn.h>

#include <filesystem>
#include <system_error>

namespace attenuvis::io {
namespace {

namespace fs = std::filesystem;

// <prefix>/share/attenuvis above `file`: the program in <prefix>/bin is one
// level down, the extension in <prefix>/lib/python3.X/dist-packages/attenuvis
// four.
std::string share_above(const std::string& file) {
  std::error_code ec;
  fs::path dir = fs::canonical(file, ec).parent_path();
  if (ec) return {};
  for (int up = 0; up < 5 && !dir.empty(); ++up, dir = dir.parent_path()) {
    const fs::path candidate = dir / "share" / "attenuvis";
    if (fs::is_directory(candidate, ec)) return candidate.string();
    if (dir == dir.root_path()) break;
  }
  return {};
}

// dladdr names the shared object holding this function: the extension module
// when loaded by Python; for the program (static libraries linked in) it gives
// only argv[0], a bare name when found on PATH, so the program's own path is
// read from /proc/self/exe.
std::string find_installed_share() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&find_installed_share), &info) && info.dli_fname &&
      std::string(info.dli_fname).find('/') != std::string::npos)
    if (std::string dir = share_above(info.dli_fname); !dir.empty()) return dir;
  return share_above("/proc/self/exe");
}

}  // namespace

const std::string& installed_share_directory() {
  static const std::string dir = find_installed_share();
  return dir;
}

std::string installed_documentation_directory() {
  const std::string& share = installed_share_directory();
  if (share.empty()) return {};
  std::error_code ec;
  const fs::path html = fs::path(share).parent_path() / "doc" / "attenuvis" / "html";
  return fs::exists(html / "index.html", ec) ? html.string() : std::string();
}

std::string installed_or_source(const std::string& relative, const std::string& source_path) {
  const std::string& share = installed_share_directory();
  if (!share.empty()) {
    std::error_code ec;
    const fs::path p = fs::path(share) / relative;
    if (fs::exists(p, ec)) return p.string();
  }
  return source_path;
}

}  // namespace attenuvis::io
