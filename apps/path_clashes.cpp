// Refusing outputs that would overwrite another output or an input.
#include "path_clashes.hpp"

#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace attenuvis::cli {
namespace {

std::filesystem::path resolved(const std::string& path) {
  std::error_code ec;
  const auto p = std::filesystem::weakly_canonical(path, ec);
  return ec ? std::filesystem::absolute(path).lexically_normal() : p;
}

}  // namespace

void refuse_path_clashes(const std::vector<NamedPath>& outputs, const std::vector<NamedPath>& inputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    if (outputs[i].path.empty()) continue;
    const auto out = resolved(outputs[i].path);
    for (std::size_t j = 0; j < i; ++j)
      if (!outputs[j].path.empty() && resolved(outputs[j].path) == out)
        throw std::invalid_argument(outputs[j].what + " and " + outputs[i].what + " both name '" + outputs[i].path +
                                    "': give each output its own file");
    for (const NamedPath& in : inputs)
      if (!in.path.empty() && resolved(in.path) == out)
        throw std::invalid_argument(outputs[i].what + " '" + outputs[i].path + "' is also the input " + in.what +
                                    " '" + in.path + "': writing it would destroy the input; choose another path");
  }
}

}  // namespace attenuvis::cli
