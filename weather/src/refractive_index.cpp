// Refractive-index tables: loading, caching and interpolation in wavelength.
#include "attenuvis/weather/refractive_index.hpp"

#include "attenuvis/io/install_paths.hpp"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <sstream>
#include <stdexcept>

#include "attenuvis/io/number_text.hpp"
#include "registry_rows.hpp"

#include <dlfcn.h>  // dladdr: where the running program or module was loaded from

#ifndef ATTENUVIS_DATA_DIR
#define ATTENUVIS_DATA_DIR "data"
#endif

namespace attenuvis::weather {

const std::vector<WaterTableInfo>& water_tables() {
  static const std::vector<WaterTableInfo> tables = [] {
    std::vector<WaterTableInfo> t = {
        {WaterTable::hale_querry, "hale-querry", {"water"}, "water-hale-querry-1973", "water", "Hale & Querry 1973",
         "liquid water, 25 C, 0.2-200 um (the default table)",
         "G. M. Hale and M. R. Querry, \"Optical constants of water in the 200-nm to 200-um wavelength region\", "
         "Appl. Opt. 12, 555-563 (1973), doi:10.1364/AO.12.000555"},
        {WaterTable::segelstein, "segelstein", {}, "water-segelstein-1981", "water", "Segelstein 1981",
         "liquid water, 25 C, 0.01 um - 10 m",
         "D. J. Segelstein, \"The complex refractive index of water\", M.S. thesis, University of Missouri-Kansas "
         "City (1981), hdl:10355/11599"},
        {WaterTable::ice, "ice", {}, "ice-warren-brandt-2008", "ice", "Warren & Brandt 2008",
         "water ice, -7 C, 0.044 um - 2 m",
         "S. G. Warren and R. E. Brandt, \"Optical constants of ice from the ultraviolet to the microwave: A revised "
         "compilation\", J. Geophys. Res. 113, D14220 (2008), doi:10.1029/2007JD009744"},
    };
    detail::check_enum_order(t, &WaterTableInfo::id);
    return t;
  }();
  return tables;
}

const WaterTableInfo& info(WaterTable t) { return detail::row_of(water_tables(), t); }

const WaterTableInfo* find_water_table(const std::string& name) {
  if (const WaterTableInfo* t = detail::find_by_name(water_tables(), name)) return t;
  for (const auto& t : water_tables())
    for (const auto& alias : t.aliases)
      if (alias == name) return &t;
  return nullptr;
}

std::string to_string(WaterTable t) { return info(t).name; }

std::string water_table_names() { return detail::name_list(detail::names_of(water_tables())); }

RefractiveIndexTable RefractiveIndexTable::read(const std::string& path, const std::string& name) {
  std::ifstream in(path);
  if (!in)
    throw std::runtime_error("cannot open refractive-index table '" + path +
                             "' (set ATTENUVIS_DATA_DIR to the directory holding refractive-index/)");
  RefractiveIndexTable t;
  t.name_ = name;
  std::string line;
  int line_no = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    if (line[0] == '#') {
      if (line.rfind("# Source: ", 0) == 0) t.citation_ = line.substr(10);
      continue;
    }
    if (!header) {
      if (line != "wavelength_um,n,k")
        throw std::runtime_error(path + ":" + std::to_string(line_no) + ": expected header 'wavelength_um,n,k'");
      header = true;
      continue;
    }
    std::stringstream ss(line);
    std::string a, b, c;
    std::getline(ss, a, ',');
    std::getline(ss, b, ',');
    std::getline(ss, c, ',');
    std::string where = path + ":" + std::to_string(line_no);
    double w = io::parse_double(a, where + " wavelength") * 1e-6;
    double n = io::parse_double(b, where + " n"), k = io::parse_double(c, where + " k");
    if (!t.wavelength_m_.empty() && !(w > t.wavelength_m_.back()))
      throw std::runtime_error(where + ": wavelengths must increase");
    if (!(n > 0) || k < 0) throw std::runtime_error(where + ": need n > 0 and k >= 0");
    t.wavelength_m_.push_back(w);
    t.n_.push_back(n);
    t.k_.push_back(k);
  }
  if (t.wavelength_m_.size() < 2) throw std::runtime_error(path + ": fewer than two rows");
  return t;
}

std::complex<double> RefractiveIndexTable::at(double w) const {
  if (!(w >= wavelength_m_.front() && w <= wavelength_m_.back())) {
    std::ostringstream msg;
    msg << "wavelength " << w * 1e9 << " nm is outside the " << name_ << " table (" << wavelength_m_.front() * 1e9
        << " - " << wavelength_m_.back() * 1e9 << " nm)";
    throw std::invalid_argument(msg.str());
  }
  std::size_t hi = 1;
  while (hi + 1 < wavelength_m_.size() && wavelength_m_[hi] < w) ++hi;
  std::size_t lo = hi - 1;
  double t = std::log(w / wavelength_m_[lo]) / std::log(wavelength_m_[hi] / wavelength_m_[lo]);
  double n = n_[lo] + t * (n_[hi] - n_[lo]);
  double k = (k_[lo] > 0 && k_[hi] > 0) ? std::exp(std::log(k_[lo]) + t * std::log(k_[hi] / k_[lo]))
                                        : k_[lo] + t * (k_[hi] - k_[lo]);
  return {n, k};
}


std::string data_directory() {
  if (const char* env = std::getenv("ATTENUVIS_DATA_DIR"); env && *env) return env;
  // The installed tables (<prefix>/share/attenuvis/refractive-index), else the source tree's.
  const std::string installed = io::installed_or_source("refractive-index", "");
  if (!installed.empty()) return io::installed_share_directory();
  return ATTENUVIS_DATA_DIR;
}

namespace {

// A table by its name, alias or file name; nullptr for any other text.
const WaterTableInfo* table_named(const std::string& name) {
  if (const WaterTableInfo* t = find_water_table(name)) return t;
  for (const auto& t : water_tables())
    if (t.file == name) return &t;
  return nullptr;
}

// "water, hale-querry, segelstein, ice, ": the names and aliases, each followed by ", ".
std::string short_table_names() {
  std::string out;
  for (const auto& t : water_tables()) {
    for (const auto& alias : t.aliases) out += alias + ", ";
    out += t.name + ", ";
  }
  return out;
}

}  // namespace

const RefractiveIndexTable& refractive_index_table(const std::string& name) {
  const WaterTableInfo* table = table_named(name);
  if (!table)
    throw std::invalid_argument("unknown refractive-index table '" + name + "' (" + short_table_names() +
                                "or a full table name)");
  const std::string& file = table->file;
  static std::mutex mutex;
  static std::map<std::string, std::unique_ptr<RefractiveIndexTable>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = cache[file];
  if (!slot)
    slot = std::make_unique<RefractiveIndexTable>(
        RefractiveIndexTable::read(data_directory() + "/refractive-index/" + file + ".csv", file));
  return *slot;
}

}  // namespace attenuvis::weather
