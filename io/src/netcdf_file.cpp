// netCDF-4 output through the libnetcdf C API, staged for an atomic rename.
#include "attenuvis/io/netcdf_file.hpp"

#include <stdexcept>

#include <netcdf.h>

namespace attenuvis::io {

NetcdfFile::NetcdfFile(const std::string& path, Format format) : staged_(path) {
  // NC_CLOBBER: the StagedFile created the temporary (empty, O_EXCL); libnetcdf replaces it.
  const int mode = format == Format::netcdf4 ? NC_NETCDF4 | NC_CLOBBER : NC_CLOBBER;
  check(nc_create(staged_.temporary_path().c_str(), mode, &id_), "create");
  open_ = true;
}

NetcdfFile::~NetcdfFile() {
  if (open_) nc_abort(id_);  // the StagedFile's destructor then removes the temporary
}

void NetcdfFile::check(int status, const std::string& what) const {
  if (status != NC_NOERR)
    throw std::runtime_error("cannot write netCDF file '" + staged_.path() + "' (" + what + "): " + nc_strerror(status));
}

int NetcdfFile::add_dimension(const std::string& name, std::size_t length) {
  int dim = -1;
  check(nc_def_dim(id_, name.c_str(), length, &dim), "dimension " + name);
  return dim;
}

int NetcdfFile::add_variable(const std::string& name, int type, const std::vector<int>& dimensions) {
  int var = -1;
  check(nc_def_var(id_, name.c_str(), type, static_cast<int>(dimensions.size()), dimensions.data(), &var),
        "variable " + name);
  return var;
}

int NetcdfFile::add_double_variable(const std::string& name, const std::vector<int>& dimensions) {
  return add_variable(name, NC_DOUBLE, dimensions);
}

int NetcdfFile::add_float_variable(const std::string& name, const std::vector<int>& dimensions) {
  return add_variable(name, NC_FLOAT, dimensions);
}

int NetcdfFile::add_int_variable(const std::string& name, const std::vector<int>& dimensions) {
  return add_variable(name, NC_INT, dimensions);
}

int NetcdfFile::add_string_variable(const std::string& name, const std::vector<int>& dimensions) {
  return add_variable(name, NC_STRING, dimensions);
}

void NetcdfFile::set_attribute(int variable, const std::string& name, const std::string& text) {
  check(nc_put_att_text(id_, variable, name.c_str(), text.size(), text.c_str()), "attribute " + name);
}

void NetcdfFile::set_attribute(int variable, const std::string& name, double value) {
  check(nc_put_att_double(id_, variable, name.c_str(), NC_DOUBLE, 1, &value), "attribute " + name);
}

void NetcdfFile::set_float_attribute(int variable, const std::string& name, float value) {
  check(nc_put_att_float(id_, variable, name.c_str(), NC_FLOAT, 1, &value), "attribute " + name);
}

void NetcdfFile::set_int_attribute(int variable, const std::string& name, int value) {
  check(nc_put_att_int(id_, variable, name.c_str(), NC_INT, 1, &value), "attribute " + name);
}

void NetcdfFile::set_attribute(int variable, const std::string& name, const std::vector<double>& values) {
  check(nc_put_att_double(id_, variable, name.c_str(), NC_DOUBLE, values.size(), values.data()), "attribute " + name);
}

void NetcdfFile::end_definitions() { check(nc_enddef(id_), "end of definitions"); }

void NetcdfFile::write(int variable, const std::vector<double>& values) {
  check(nc_put_var_double(id_, variable, values.data()), "values of variable " + std::to_string(variable));
}

void NetcdfFile::write(int variable, const std::vector<float>& values) {
  check(nc_put_var_float(id_, variable, values.data()), "values of variable " + std::to_string(variable));
}

void NetcdfFile::write(int variable, const std::vector<int>& values) {
  check(nc_put_var_int(id_, variable, values.data()), "values of variable " + std::to_string(variable));
}

void NetcdfFile::write(int variable, const std::vector<std::string>& values) {
  std::vector<const char*> pointers;
  pointers.reserve(values.size());
  for (const auto& v : values) pointers.push_back(v.c_str());
  check(nc_put_var_string(id_, variable, pointers.data()), "values of variable " + std::to_string(variable));
}

void NetcdfFile::commit() {
  open_ = false;  // nc_close releases the dataset even when it fails
  check(nc_close(id_), "close");
  staged_.commit();
}

}  // namespace attenuvis::io
