// A netCDF-4 file that appears whole or not at all.
//
// A thin typed layer over Debian's libnetcdf C API (netcdf.h): dimensions,
// double, float, int and string variables, text and number attributes.  The file is
// created at a StagedFile's temporary path (staged_file.hpp) and renamed onto
// the destination by commit(); an object destroyed before commit() aborts the
// dataset and removes the temporary, so an error never leaves a partial file.
// Every libnetcdf failure throws std::runtime_error naming the destination,
// the call's object and nc_strerror's text.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "attenuvis/io/staged_file.hpp"

namespace attenuvis::io {

// A netCDF-4 dataset being written; it appears at its destination on commit().
class NetcdfFile {
 public:
  static constexpr int global = -1;  // NC_GLOBAL: the variable id of the global attributes

  // netcdf4: HDF5-based, string variables allowed (CF tables);
  // classic: the original format (CDF-1), what older readers such as
  // libRadtran's expect of their input tables; no string variables.
  enum class Format { netcdf4, classic };

  // Stages `path` and creates a dataset of `format` in define mode.
  explicit NetcdfFile(const std::string& path, Format format = Format::netcdf4);
  NetcdfFile(const NetcdfFile&) = delete;
  NetcdfFile& operator=(const NetcdfFile&) = delete;
  ~NetcdfFile();  // aborts the dataset and removes the temporary unless committed

  // Define mode.
  int add_dimension(const std::string& name, std::size_t length);
  int add_double_variable(const std::string& name, const std::vector<int>& dimensions);
  int add_float_variable(const std::string& name, const std::vector<int>& dimensions);
  int add_int_variable(const std::string& name, const std::vector<int>& dimensions);
  int add_string_variable(const std::string& name, const std::vector<int>& dimensions);
  void set_attribute(int variable, const std::string& name, const std::string& text);
  void set_attribute(int variable, const std::string& name, double value);
  void set_float_attribute(int variable, const std::string& name, float value);
  void set_int_attribute(int variable, const std::string& name, int value);
  void set_attribute(int variable, const std::string& name, const std::vector<double>& values);
  void end_definitions();

  // Data mode: the whole variable, in C (row-major) order.
  void write(int variable, const std::vector<double>& values);
  void write(int variable, const std::vector<float>& values);
  void write(int variable, const std::vector<int>& values);
  void write(int variable, const std::vector<std::string>& values);

  // Closes the dataset and renames it onto the destination.
  void commit();

 private:
  void check(int status, const std::string& what) const;
  // A variable of netCDF type `type` (NC_DOUBLE, NC_FLOAT, ...): what the typed adders share.
  int add_variable(const std::string& name, int type, const std::vector<int>& dimensions);
  StagedFile staged_;
  int id_ = -1;
  bool open_ = false;
};

}  // namespace attenuvis::io
