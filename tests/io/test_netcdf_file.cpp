// netCDF-4 files staged like every output: whole on commit, nothing otherwise.
#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <netcdf.h>
#include <unistd.h>

#include "attenuvis/io/netcdf_file.hpp"

namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {
fs::path fresh_directory(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("attenuvis_netcdf_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}
}  // namespace

TEST_CASE("netCDF file: appears on commit with its values, attributes and strings", "[io][netcdf]") {
  const fs::path dir = fresh_directory("commit");
  const std::string path = (dir / "t.nc").string();
  {
    attenuvis::io::NetcdfFile f(path);
    const int dim = f.add_dimension("x", 3);
    const int var = f.add_double_variable("v", {dim});
    const int str = f.add_string_variable("s", {dim});
    f.set_attribute(var, "units", "km-1");
    f.set_attribute(var, "_FillValue", std::nan(""));
    f.set_attribute(attenuvis::io::NetcdfFile::global, "Conventions", "CF-1.8");
    f.end_definitions();
    f.write(var, std::vector<double>{1.5, std::nan(""), -2.0});
    f.write(str, std::vector<std::string>{"a", "", "ccc"});
    CHECK(!fs::exists(path));  // nothing at the destination before commit
    f.commit();
  }
  REQUIRE(fs::exists(path));
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator{}) == 1);  // no temporary left
  // Read back with libnetcdf itself.
  int id = -1, var = -1, str = -1;
  REQUIRE(nc_open(path.c_str(), NC_NOWRITE, &id) == NC_NOERR);
  REQUIRE(nc_inq_varid(id, "v", &var) == NC_NOERR);
  REQUIRE(nc_inq_varid(id, "s", &str) == NC_NOERR);
  double v[3];
  REQUIRE(nc_get_var_double(id, var, v) == NC_NOERR);
  CHECK(v[0] == 1.5);
  CHECK(std::isnan(v[1]));
  CHECK(v[2] == -2.0);
  char* s[3];
  REQUIRE(nc_get_var_string(id, str, s) == NC_NOERR);
  CHECK(std::string(s[2]) == "ccc");
  nc_free_string(3, s);
  char units[16] = {};
  REQUIRE(nc_get_att_text(id, var, "units", units) == NC_NOERR);
  CHECK(std::string(units) == "km-1");
  nc_close(id);
  fs::remove_all(dir);
}

TEST_CASE("netCDF file: an error names the file and leaves nothing behind", "[io][netcdf]") {
  const fs::path dir = fresh_directory("abort");
  const std::string path = (dir / "t.nc").string();
  {
    attenuvis::io::NetcdfFile f(path);
    f.add_dimension("x", 3);
    // A second dimension of the same name is libnetcdf's NC_ENAMEINUSE.
    CHECK_THROWS_WITH(f.add_dimension("x", 4), Contains("t.nc") && Contains("dimension x"));
  }  // destroyed without commit
  CHECK(fs::is_empty(dir));
  CHECK_THROWS_WITH(attenuvis::io::NetcdfFile((dir / "no-such-dir" / "t.nc").string()), Contains("no-such-dir"));
  fs::remove_all(dir);
}
