// Refractive-index tables: loading, caching and interpolation in wavelength.
#include "attenuvis/weather/refractive_index.hpp"

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

#include <dlfcn.h>  // dladdr: where the running program or module was loaded from

#ifndef ATTENUVIS_DATA_DIR
#define ATTENUVIS_DATA_DIR "data"
#endif

namespace attenuvis::weather {

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

namespace {

bool has_tables(const std::string& dir) {
  std::error_code ec;
  return std::filesystem::is_directory(dir + "/refractive-index", ec);
}

// <prefix>/share/attenuvis above `file`, at most four directories up.
std::string share_above(const std::string& file) {
  std::error_code ec;
  std::filesystem::path dir = std::filesystem::canonical(file, ec).parent_path();
  if (ec) return {};
  for (int up = 0; up < 5 && !dir.empty(); ++up, dir = dir.parent_path()) {
    const std::string candidate = (dir / "share" / "attenuvis").string();
    if (has_tables(candidate)) return candidate;
    if (dir == dir.root_path()) break;
  }
  return {};
}

// <prefix>/share/attenuvis for the file this library was loaded from: the
// installed Python extension module (lib/python3.X/dist-packages/attenuvis/,
// four levels below the prefix), which dladdr names; or the installed program
// (the static library lives inside it), for which dladdr gives only argv[0]
// (a bare name when the program was found on PATH), so its own path is read
// from /proc/self/exe.
std::string installed_data_directory() {
  Dl_info info{};
  if (dladdr(reinterpret_cast<void*>(&installed_data_directory), &info) && info.dli_fname &&
      std::string(info.dli_fname).find('/') != std::string::npos)
    if (std::string dir = share_above(info.dli_fname); !dir.empty()) return dir;
  return share_above("/proc/self/exe");
}

}  // namespace

std::string data_directory() {
  if (const char* env = std::getenv("ATTENUVIS_DATA_DIR"); env && *env) return env;
  static const std::string installed = installed_data_directory();
  if (!installed.empty()) return installed;
  return ATTENUVIS_DATA_DIR;
}

const RefractiveIndexTable& refractive_index_table(const std::string& name) {
  std::string file = name;
  if (name == "water" || name == "hale-querry") file = "water-hale-querry-1973";
  else if (name == "segelstein") file = "water-segelstein-1981";
  else if (name == "ice") file = "ice-warren-brandt-2008";
  if (file != "water-hale-querry-1973" && file != "water-segelstein-1981" && file != "ice-warren-brandt-2008")
    throw std::invalid_argument("unknown refractive-index table '" + name +
                                "' (water, hale-querry, segelstein, ice, or a full table name)");
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
