// OPAC's size distributions and refractive indices from data/opac (opac_data.hpp).
#include "attenuvis/weather/opac_data.hpp"

#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include "attenuvis/io/input_file.hpp"
#include "attenuvis/io/number_text.hpp"
#include "attenuvis/weather/refractive_index.hpp"
#include "index_text.hpp"

namespace attenuvis::weather {
namespace {

constexpr std::size_t kMaxOpacFileBytes = 1u << 20;  // the files are a few kB

std::string opac_directory() { return data_directory() + "/opac"; }

}  // namespace

std::vector<OpacSizeRow> parse_opac_size_table(const std::string& text, const std::string& source) {
  std::vector<OpacSizeRow> rows;
  std::istringstream in(text);
  std::string line;
  int line_no = 0;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string t = detail::trimmed(line);
    if (t.empty() || t[0] == '#') continue;
    const std::string where = source + ":" + std::to_string(line_no);
    const auto f = detail::fields(t);
    if (f.size() != 7)
      throw std::runtime_error(where + ": " + std::to_string(f.size()) +
                               " columns; a size row has seven: no, RH, Rmin, Rmax, Rmod, rho, sigma");
    double v[7];
    const char* names[7] = {"component number", "RH", "Rmin", "Rmax", "Rmod", "rho", "sigma"};
    for (int i = 0; i < 7; ++i) v[i] = detail::number(f[i], where, names[i]);
    // The number is checked before it becomes an int (a cast out of range is undefined).
    if (!(v[0] >= 1 && v[0] <= 10 && v[0] == std::floor(v[0])))
      throw std::runtime_error(where + ": component number " + f[0] + " is not 1..10");
    OpacSizeRow r{static_cast<int>(v[0]), v[1], v[2], v[3], v[4], v[5], v[6], line_no};
    if (!(r.rh_percent >= 0 && r.rh_percent <= 100)) throw std::runtime_error(where + ": RH " + f[1] + " is not 0..100 %");
    if (!(r.r_min_um > 0 && r.r_min_um < r.r_mod_um && r.r_mod_um < r.r_max_um))
      throw std::runtime_error(where + ": needs 0 < Rmin < Rmod < Rmax (um)");
    if (!(r.density_g_cm3 > 0) || !(r.sigma_g > 1 && r.sigma_g <= 20))
      throw std::runtime_error(where + ": needs rho > 0 and sigma in (1, 20]");
    rows.push_back(r);
  }
  return rows;
}

std::string opac_index_path(AerosolComponent c, double rh_percent) {
  const int rh = static_cast<int>(std::lround(rh_percent));
  return opac_directory() + "/refractive_indices/" + to_string(c) + (rh < 10 ? "0" : "") + std::to_string(rh) +
         "_refr.dat";
}

namespace {

// The component's states from the size table and its index files, checked
// against the humidities OPAC tabulates.
OpacComponentData load_component(AerosolComponent c, const std::vector<OpacSizeRow>& rows, const std::string& source) {
  OpacComponentData out{c, {}};
  const AerosolComponentInfo& ci = info(c);
  for (const OpacSizeRow& r : rows) {
    if (r.component != ci.opac_number) continue;
    const std::size_t i = out.states.size();
    const std::vector<double>& expected = opac_humidities();
    if (i >= expected.size() || r.rh_percent != expected[i])
      throw std::runtime_error(source + ":" + std::to_string(r.line) + ": " + ci.name + " at RH " +
                               io::shortest(r.rh_percent) + " %: OPAC tabulates 0, 50, 70, 80, 90, 95, 98, 99 % in order");
    const std::string path = opac_index_path(c, r.rh_percent);
    out.states.push_back({r.rh_percent, r.r_min_um * 1e-6, r.r_max_um * 1e-6, r.r_mod_um * 1e-6, r.sigma_g,
                          r.density_g_cm3 * 1e3,
                          parse_index_columns(io::read_input_file(path, kMaxOpacFileBytes), path,
                                              ImaginarySign::n_minus_ik)});
  }
  const std::size_t want = ci.hygroscopic ? opac_humidities().size() : 1;
  if (out.states.size() != want)
    throw std::runtime_error(source + ": " + ci.name + " has " + std::to_string(out.states.size()) +
                             " humidity rows; OPAC gives it " + std::to_string(want));
  return out;
}

}  // namespace

const OpacComponentData& opac_component(AerosolComponent c) {
  static std::mutex mutex;
  static std::map<AerosolComponent, std::unique_ptr<OpacComponentData>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = cache[c];
  if (!slot) {
    const std::string source = opac_directory() + "/size_distr.cfg";
    std::string text;
    try {
      text = io::read_input_file(source, kMaxOpacFileBytes);
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(std::string(e.what()) +
                               " (the OPAC data: set ATTENUVIS_DATA_DIR to the directory holding opac/)");
    }
    slot = std::make_unique<OpacComponentData>(load_component(c, parse_opac_size_table(text, source), source));
  }
  return *slot;
}

}  // namespace attenuvis::weather
