// End-to-end tests of `attenuvis vg` (apps/cmd_visgraph.cpp): the CSV, PLY,
// PNG heatmap, JSON summary and edge list it writes, the two ways of giving
// nodes and targets, and bad input (non-zero exit, a message naming the
// problem, no output file).  Scene: classic layout 2, one 10 m block over
// [25,35] x [15,25] on a 50 x 50 m floor (visgraph/layouts.hpp).
#include "cli_test_support.hpp"

#include <catch2/catch.hpp>

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

namespace fs = std::filesystem;
using Catch::Matchers::Contains;

namespace {
using namespace clitest;

std::string data(const std::string& name) { return std::string(ATTENUVIS_TEST_DATA_DIR) + "/visgraph/" + name; }

}  // namespace

TEST_CASE("vg writes CSV, PLY, heatmap, summary and edges for layout 2", "[visgraph][cli]") {
  TempDir dir;
  const Run r = run("vg layout:2 --conditions clear,rain:8,sigma:0.05 --threads 2 --out " + (dir / "nodes.csv") +
                    " --ply " + (dir / "nodes.ply") + " --heatmap " + (dir / "map.png") + " --summary " +
                    (dir / "summary.json") + " --edges " + (dir / "edges.csv"));
  INFO(r.output);
  REQUIRE(r.status == 0);

  // CSV: conditions as written, each condition's sum and avg side by side.
  const Csv csv = read_csv(dir / "nodes.csv");
  CHECK(csv.header == std::vector<std::string>{"x", "y", "z", "degree", "sum:clear", "avg:clear", "sum:rain:8",
                                               "avg:rain:8", "sum:sigma:0.05", "avg:sigma:0.05"});
  // Layout 2 on a 1 m grid of cell centres gives 2400 nodes (2500 cells
  // less the 10 x 10 under the block).
  REQUIRE(csv.rows.size() == 2400);
  const std::size_t degree = csv.column("degree");
  for (const auto& row : csv.rows) {
    CHECK(row[2] == Approx(1.7));  // floor z = 0 plus the default eye height
    // S_A = S_S / degree, and C <= 1 so S_S <= degree.
    for (const char* c : {"clear", "rain:8", "sigma:0.05"}) {
      CHECK(row[csv.column(std::string("avg:") + c)] ==
            Approx(row[csv.column(std::string("sum:") + c)] / row[degree]).epsilon(1e-14));
      CHECK(row[csv.column(std::string("sum:") + c)] <= row[degree]);
    }
  }

  // PLY: ASCII, one vertex per node, each with x y z r g b value.
  {
    std::ifstream ply(dir / "nodes.ply");
    std::string line;
    std::getline(ply, line);
    CHECK(line == "ply");
    std::getline(ply, line);
    CHECK(line == "format ascii 1.0");
    long vertices = -1;
    int properties = 0;
    while (std::getline(ply, line) && line != "end_header") {
      if (line.rfind("element vertex ", 0) == 0) vertices = std::stol(line.substr(15));
      if (line.rfind("property ", 0) == 0) ++properties;
    }
    CHECK(line == "end_header");
    CHECK(vertices == 2400);
    long body = 0, malformed = 0;
    while (std::getline(ply, line)) {
      malformed += static_cast<int>(split(line, ' ').size()) != properties;
      ++body;
    }
    CHECK(body == vertices);
    CHECK(malformed == 0);
  }

  // PNG: the 8-byte signature of the PNG specification (ISO/IEC 15948, 5.2).
  {
    std::ifstream png(dir / "map.png", std::ios::binary);
    std::array<unsigned char, 8> signature{};
    png.read(reinterpret_cast<char*>(signature.data()), signature.size());
    CHECK(signature == std::array<unsigned char, 8>{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'});
  }

  // Summary: nodes, pairs, visible fraction, sigma with units and convention,
  // time and pairs/s.
  std::ifstream summary_file(dir / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(summary_file);
  CHECK(summary["nodes"] == 2400);
  CHECK(summary["pairs"]["considered"] == 2400 * 2399 / 2);
  // Every pair is cast or decided by the exact culling.
  CHECK(summary["pairs"]["cast"].get<std::uint64_t>() + summary["pairs"]["culled_in_sight"].get<std::uint64_t>() +
            summary["pairs"]["culled_blocked"].get<std::uint64_t>() ==
        2400u * 2399u / 2u);
  const auto visible = summary["pairs"]["visible"].get<std::uint64_t>();
  CHECK(summary["pairs"]["visible_fraction_of_considered"].get<double>() ==
        Approx(visible / (2400.0 * 2399.0 / 2)).epsilon(1e-12));
  double degree_sum = 0;
  for (const auto& row : csv.rows) degree_sum += row[degree];
  CHECK(degree_sum == 2.0 * visible);  // each visible pair credits both ends
  REQUIRE(summary["conditions"].size() == 3);
  CHECK(summary["conditions"][0]["label"] == "clear");
  // Seed paper, Sec. Results: clear air sigma = 0.00015 1/m.
  CHECK(summary["conditions"][0]["sigma_per_m"].get<double>() == 0.00015);
  CHECK(summary["conditions"][2]["sigma_per_m"].get<double>() == 0.05);  // given as written
  for (const auto& c : summary["conditions"]) {
    CHECK(c["units"] == "1/m");
    CHECK(c.contains("convention"));
  }
  CHECK(summary["conditions"][1]["convention"] == "itu");  // the default --convention
  CHECK(summary["time_s"]["visibility"].get<double>() > 0);
  CHECK(summary["pairs_per_s"].get<double>() > 0);

  // Edges: every visible pair once, i < j, with the distance between the
  // nodes of the CSV.
  const Csv edges = read_csv(dir / "edges.csv");
  CHECK(edges.header == std::vector<std::string>{"i", "j", "distance"});
  CHECK(edges.rows.size() == visible);
  for (std::size_t e = 0; e < edges.rows.size(); e += 997) {
    const auto i = static_cast<std::size_t>(edges.rows[e][0]), j = static_cast<std::size_t>(edges.rows[e][1]);
    REQUIRE(i < j);
    REQUIRE(j < csv.rows.size());
    const double d = std::hypot(csv.rows[i][0] - csv.rows[j][0], csv.rows[i][1] - csv.rows[j][1]);
    CHECK(edges.rows[e][2] == Approx(d).epsilon(1e-12));
  }
  // Nothing but the requested files (no temporaries left behind).
  CHECK(dir.files().size() == 5);
}

TEST_CASE("vg with --nodes and --target-point: degrees known by geometry", "[visgraph][cli]") {
  TempDir dir;
  {
    std::ofstream nodes(dir / "nodes.csv");
    nodes << "x,y,z\n10,20,1.7\n40,20,1.7\n10,5,1.7\n";
  }
  // Block [25,35] x [15,25], 10 m tall: the line y = 20 from x = 10 to 40
  // crosses it; (10,20)-(10,5) stays at x = 10; (40,20)-(10,5) has
  // y = 17.5 at x = 35, inside the block.  Degrees 1, 0, 1; nodes 0 and 2
  // are 15 m apart, so S_S = exp(-0.1 * 15) for sigma 0.1.
  Run r = run("vg layout:2 --nodes " + (dir / "nodes.csv") + " --conditions sigma:0.1 --quiet --out " +
              (dir / "out.csv"));
  INFO(r.output);
  REQUIRE(r.status == 0);
  Csv csv = read_csv(dir / "out.csv");
  REQUIRE(csv.rows.size() == 3);
  CHECK(csv.rows[0][0] == 10);  // nodes are taken as given, in order
  CHECK(csv.rows[0][2] == 1.7);
  CHECK(csv.rows[0][csv.column("degree")] == 1);
  CHECK(csv.rows[1][csv.column("degree")] == 0);
  CHECK(csv.rows[2][csv.column("degree")] == 1);
  // Fixed-point accumulation rounds each C to 2^-41 (visibility.hpp).
  CHECK(csv.rows[0][csv.column("sum:sigma:0.1")] == Approx(std::exp(-1.5)).margin(1e-12));
  CHECK(csv.rows[2][csv.column("avg:sigma:0.1")] == Approx(std::exp(-1.5)).margin(1e-12));
  CHECK(std::isnan(csv.rows[1][csv.column("avg:sigma:0.1")]));  // degree 0: no average

  // The seed's single-point analysis: all grid nodes against one target.
  // From (0.25, 0.25): the node at (20.5, 40.5) never reaches the block's
  // x range (x <= 20.5 < 25); the segment to (40.5, 20.5) has y = 15.2 at
  // x = 30, inside the block.
  r = run("vg layout:2 --target-point 0.25,0.25,1.7 --conditions clear --quiet --out " + (dir / "target.csv") +
          " --summary " + (dir / "target.json"));
  INFO(r.output);
  REQUIRE(r.status == 0);
  csv = read_csv(dir / "target.csv");
  REQUIRE(csv.rows.size() == 2400);
  const auto degree_at = [&](double x, double y) {
    for (const auto& row : csv.rows)
      if (row[0] == x && row[1] == y) return row[csv.column("degree")];
    FAIL("no node at " << x << "," << y);
    return -1.0;
  };
  CHECK(degree_at(20.5, 40.5) == 1);
  CHECK(degree_at(40.5, 20.5) == 0);
  std::size_t not_0_or_1 = 0;
  for (const auto& row : csv.rows) not_0_or_1 += row[csv.column("degree")] != 0 && row[csv.column("degree")] != 1;
  CHECK(not_0_or_1 == 0);  // one target: each node sees it or not
  std::ifstream summary_file(dir / "target.json");
  const nlohmann::json summary = nlohmann::json::parse(summary_file);
  CHECK(summary["mode"] == "to-targets");
  CHECK(summary["pairs"]["considered"] == 2400);
}

TEST_CASE("vg bad input: non-zero exit, the problem named, no output file", "[visgraph][cli]") {
  TempDir dir;
  const std::string out = " --out " + (dir / "out.csv") + " --summary " + (dir / "out.json");
  struct Case {
    std::string args, message;
  };
  const std::vector<Case> cases = {
      {"vg " + (dir / "missing.obj") + " --conditions clear", "missing.obj"},
      {"vg " + data("bad_nan_vertex.obj") + " --conditions clear", "bad_nan_vertex.obj:5:"},
      {"vg " + data("empty_mesh.obj") + " --conditions clear", "empty mesh"},
      {"vg layout:2 --conditions clear,hail:2", "hail:2"},
      {"vg layout:2 --conditions rain:-8", "rain:-8"},
      {"vg layout:2 --conditions sigma:-0.1", "sigma:-0.1"},
      {"vg layout:2 --conditions clear --nodes " + (dir / "no_nodes.csv"), "no_nodes.csv"},
      {"vg layout:2 --conditions clear --tolerance -1", "tolerance"},
      {"vg layout:2 --conditions clear --ply " + (dir / "out.ply") + " --color-by nope", "nope"},
  };
  for (const Case& c : cases) {
    const Run r = run(c.args + out);
    INFO(c.args << "\n" << r.output);
    CHECK(r.status != 0);
    CHECK_THAT(r.output, Contains("attenuvis: error:") && Contains(c.message));
    CHECK(dir.files().empty());
  }
}
