// `attenuvis vg --measures`: the space-syntax columns in the CSV, GeoJSON and
// summary, equal to the library's values on the same nodes; bad options end
// with a message and no output file.
#include "cli_test_support.hpp"

#include <attenuvis/visgraph/layouts.hpp>
#include <attenuvis/visgraph/nodes.hpp>
#include <attenuvis/visgraph/scene.hpp>
#include <attenuvis/visgraph/scene_spec.hpp>
#include <attenuvis/visgraph/space_syntax.hpp>

#include <nlohmann/json.hpp>

using namespace clitest;
using Catch::Matchers::Contains;
namespace vg = attenuvis::visgraph;

TEST_CASE("vg --measures: columns in every writer, equal to the library's", "[visgraph][cli][space_syntax]") {
  TempDir dir;
  const Run r = run("vg layout:2 --spacing 5 --conditions clear,sigma:0.05 --measures integration,clustering,component "
                    "--contrast-threshold 0.5 --radius 3 --quiet --out " + (dir / "s.csv") + " --geojson " +
                    (dir / "s.geojson") + " --summary " + (dir / "s.json"));
  INFO(r.output);
  REQUIRE(r.status == 0);
  const Csv csv = read_csv(dir / "s.csv");
  // The library on the same grid and sigma values.
  const vg::Scene scene(vg::classic_layout(2));
  vg::NodeGridOptions grid;
  grid.spacing = 5;
  grid.walkable = vg::classic_layout_walkable_groups();
  const std::vector<Eigen::Vector3d> eyes = vg::generate_nodes(scene, grid).eyes;
  REQUIRE(eyes.size() == csv.rows.size());
  vg::VisibilityOptions pass;
  pass.sigmas = {1.5e-4, 0.05};
  vg::SpaceSyntaxOptions o;
  o.sigmas = pass.sigmas;
  o.measures = vg::parse_measures("integration,clustering,component");
  o.contrast_threshold = 0.5;
  o.radius = 3;
  const vg::SpaceSyntaxResult lib = vg::space_syntax(scene, eyes, pass, o).measures;
  for (const char* m : {"integration_hh_r3", "clustering", "component_size"})
    for (std::size_t k = 0; k < 2; ++k) {
      const std::string name = std::string(m) + (k ? ":sigma:0.05" : ":clear");
      INFO(name);
      const std::size_t c = csv.column(name);
      for (std::size_t i = 0; i < eyes.size(); ++i) CHECK(csv.rows[i][c] == lib.values(m, k)[i]);
    }
  const nlohmann::json summary = nlohmann::json::parse(std::ifstream(dir / "s.json"));
  CHECK(summary["space_syntax"]["radius"] == 3);
  CHECK(summary["space_syntax"]["conditions"][1]["lines_of_sight"] == lib.edges[1]);
  CHECK(summary["scores"].contains("integration_hh_r3:sigma:0.05"));
  const nlohmann::json geojson = nlohmann::json::parse(std::ifstream(dir / "s.geojson"));
  CHECK(geojson["features"][0]["properties"].contains("clustering:clear"));
}

TEST_CASE("vg --measures bad input: message, non-zero exit, no output", "[visgraph][cli][space_syntax]") {
  TempDir dir;
  std::ofstream(dir / "nodes.csv") << "x,y,z\n1,1,1.7\n5,5,1.7\n10,1,1.7\n";
  const std::string out = " --out " + (dir / "out.csv");
  struct Case {
    std::string args, message;
  };
  const std::vector<Case> cases = {
      {"--measures integraton", "unknown measure 'integraton'"},
      {"--measures control --contrast-threshold 1", "--contrast-threshold"},
      {"--measures control --radius 0", "--radius"},
      {"--measures control --radius two", "--radius"},
      {"--measures control --graph dense", "--graph"},
      {"--measures control --target-point 1,1,1.7", "--target-point"},
      {"--measures control --prune-below 0.01", "--prune-below"},
      {"--measures step-depth", "--depth-from"},
      {"--depth-from 1,1,1.7", "step-depth"},
  };
  for (const Case& c : cases) {
    const Run r = run("vg layout:2 --spacing 5 --conditions clear " + c.args + out);
    INFO(c.args << "\n" << r.output);
    CHECK(r.status != 0);
    CHECK_THAT(r.output, Contains("attenuvis: error:") && Contains(c.message));
    CHECK(!fs::exists(dir / "out.csv"));
  }
  // Nodes from a file have no grid: through vision asks for its spacing.
  const Run r = run("vg layout:2 --conditions clear --measures through-vision --nodes " + (dir / "nodes.csv") + out);
  INFO(r.output);
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("attenuvis: error:") && Contains("--spacing"));
  CHECK(!fs::exists(dir / "out.csv"));
}
