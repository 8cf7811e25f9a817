// Scene specs ("layout:N", "city", "city:SEED"), their group names and the
// groups pedestrians walk on.
#include <attenuvis/visgraph/scene_spec.hpp>

#include <charconv>
#include <stdexcept>
#include <string>

namespace attenuvis::visgraph {

std::vector<std::string> classic_layout_walkable_groups() { return {scene_group::floor}; }
std::vector<std::string> city_walkable_groups() { return {scene_group::sidewalk, scene_group::crosswalk}; }

namespace {

bool parse_integer(const std::string& text, long long& value) {
  if (text.empty()) return false;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  return ec == std::errc() && ptr == text.data() + text.size();
}

}  // namespace

bool is_scene_spec(const std::string& text) {
  return text == "city" || text.rfind("city:", 0) == 0 || text.rfind("layout:", 0) == 0;
}

Mesh scene_from_spec(const std::string& spec, const CityOptions& base) {
  const std::string grammar = "expected layout:N (N = 0.." + std::to_string(kClassicLayoutCount - 1) +
                              "), city or city:SEED";
  long long value = 0;
  if (spec.rfind("layout:", 0) == 0) {
    if (!parse_integer(spec.substr(7), value) || value < 0 || value >= kClassicLayoutCount)
      throw std::invalid_argument("bad scene '" + spec + "': " + grammar);
    return classic_layout(static_cast<int>(value));
  }
  if (spec == "city") return synthetic_city(base);
  if (spec.rfind("city:", 0) == 0) {
    if (!parse_integer(spec.substr(5), value) || value < 0)
      throw std::invalid_argument("bad scene '" + spec + "': the seed must be a non-negative integer; " + grammar);
    CityOptions options = base;
    options.seed = static_cast<std::uint64_t>(value);
    return synthetic_city(options);
  }
  throw std::invalid_argument("bad scene '" + spec + "': " + grammar);
}

std::vector<std::string> default_walkable_groups(const std::string& scene) {
  if (scene.rfind("layout:", 0) == 0) return classic_layout_walkable_groups();
  if (scene == "city" || scene.rfind("city:", 0) == 0) return city_walkable_groups();
  return {};
}

}  // namespace attenuvis::visgraph
