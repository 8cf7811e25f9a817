// Complex refractive index m = n + i k (k >= 0 absorbing) of water and ice
// from tables, interpolated in wavelength.
//
// Tables (data/refractive-index/*.csv, each carrying its citation), listed
// once in water_tables() below:
//   water-hale-querry-1973   Hale & Querry, Appl. Opt. 12, 555 (1973), 25 C, 0.2-200 um
//   water-segelstein-1981    Segelstein, M.S. thesis UMKC (1981), 25 C, 0.01 um - 10 m
//   ice-warren-brandt-2008   Warren & Brandt, J. Geophys. Res. 113, D14220 (2008), -7 C, 0.044 um - 2 m
//
// Interpolation scheme: between neighbouring table wavelengths, n is linear in
// ln(lambda) and ln(k) is linear in ln(lambda) (k spans 10 decades across the
// visible and infrared, so it is interpolated as a power law; where either
// neighbour has k = 0, k is linear in ln(lambda)).  Outside the table's range
// is an error, never an extrapolation.
//
// The data directory is searched in this order: $ATTENUVIS_DATA_DIR if set;
// <prefix>/share/attenuvis of an installed copy (found from the file the
// library was loaded from, the program or the Python extension module, going
// up at most four directories); else the source tree's data/ compiled in by
// CMake.  Tables are read once and cached (thread-safe).
#pragma once

#include <complex>
#include <string>
#include <vector>

namespace attenuvis::weather {

// The tables by name: the one list that the condition grammar (water=),
// the --water option, Settings::water_table and the Python layer read.
enum class WaterTable { hale_querry, segelstein, ice };
struct WaterTableInfo {
  WaterTable id;
  std::string name;                  // "hale-querry": as the grammar, --water and Python spell it
  std::vector<std::string> aliases;  // further names of the same table: "water" (the default table)
  std::string file;                  // "water-hale-querry-1973": data/refractive-index/<file>.csv
  std::string substance;             // "water" or "ice"
  std::string source;                // authors and year: "Hale & Querry 1973"
  std::string help;                  // temperature and wavelength range
  std::string citation;              // as the table's file states it ("# Source: ")
};
// Every table, in the order of the enum.
const std::vector<WaterTableInfo>& water_tables();
const WaterTableInfo& info(WaterTable t);
// By name or alias; nullptr for any other text.
const WaterTableInfo* find_water_table(const std::string& name);
std::string to_string(WaterTable t);  // its name: "hale-querry" | "segelstein" | "ice"
// The names for messages: "hale-querry, segelstein or ice".
std::string water_table_names();

// A refractive-index table over wavelength, interpolated in ln(wavelength).
class RefractiveIndexTable {
 public:
  // Reads a "wavelength_um,n,k" CSV whose '#' lines hold the citation.
  static RefractiveIndexTable read(const std::string& path, const std::string& name);

  std::complex<double> at(double wavelength_m) const;  // throws outside the table
  const std::string& name() const { return name_; }
  const std::string& citation() const { return citation_; }
  double min_wavelength_m() const { return wavelength_m_.front(); }
  double max_wavelength_m() const { return wavelength_m_.back(); }

 private:
  std::string name_, citation_;
  std::vector<double> wavelength_m_, n_, k_;
};

// Directory holding refractive-index/, searched as described above.
std::string data_directory();

// A table by its name or alias in water_tables() ("water" = Hale & Querry
// 1973, the default), or by its file name ("water-segelstein-1981"); throws
// std::invalid_argument listing them for any other.
const RefractiveIndexTable& refractive_index_table(const std::string& name);

}  // namespace attenuvis::weather
