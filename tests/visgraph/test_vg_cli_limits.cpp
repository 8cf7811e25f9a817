// `attenuvis vg` against hostile input: option values outside their ranges,
// devices given as files, runs far larger than the machine can do, and
// outputs that cannot all be written.  Each run must end within seconds in
// a clean error (non-zero exit, the value and range named, no output file)
// or in the right answer.
#include "cli_test_support.hpp"

#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <fstream>
#include <string>

using Catch::Matchers::Contains;
using namespace clitest;

TEST_CASE("vg refuses option values outside their ranges, naming option and range", "[visgraph][cli][limits]") {
  TempDir dir;
  const std::string tail = " --conditions clear --quiet --out " + (dir / "nodes.csv");
  struct Case {
    const char* args;
    const char* expect;
  };
  // 1e300: Embree's ray.valid() assertion aborted the process; 1e-300: one node, silently.
  for (const Case c : {Case{"--spacing 1e300", "--spacing: 1e+300 is outside [0.001, 10000] m"},
                       Case{"--spacing 1e-300", "--spacing: 1e-300 is outside [0.001, 10000] m"},
                       Case{"--eye-height 1e300", "--eye-height: 1e+300 is outside [0, 1000] m"},
                       Case{"--max-slope 91", "--max-slope: 91 is outside [0, 90] degrees"},
                       Case{"--prune-below 1", "--prune-below: 1 is outside [0, 1)"},
                       Case{"--max-distance -1", "--max-distance: -1 is not a positive"},
                       Case{"--threads 100000", "--threads: 100000 is outside [0, 1024]"},
                       Case{"--target-point 0,0,1e300", "[-1e7, 1e7]"}}) {
    const Run r = run(std::string("vg layout:2 ") + c.args + tail);
    INFO(c.args << ": " << r.output);
    CHECK(r.status != 0);
    CHECK_THAT(r.output, Contains(c.expect));
    CHECK(dir.files().empty());
  }
}

TEST_CASE("vg refuses devices as scene or node files instead of reading them for ever", "[visgraph][cli][limits]") {
  TempDir dir;
  const std::string tail = " --conditions clear --quiet --out " + (dir / "nodes.csv");
  for (const std::string args : {"/dev/zero", "layout:2 --nodes /dev/urandom", "layout:2 --targets /dev/zero"}) {
    const Run r = run("vg " + args + tail);
    INFO(args << ": " << r.output);
    CHECK(r.status != 0);
    CHECK_THAT(r.output, Contains("is not a regular file"));
    CHECK(dir.files().empty());
  }
}

TEST_CASE("vg estimates the work first and refuses runs above the caps", "[visgraph][cli][limits]") {
  TempDir dir;
  const std::string tail = " --conditions clear --quiet --out " + (dir / "nodes.csv");
  // A millimetre grid over layout 0's 50 x 50 m floor: 2.5e9 cells (was: 2 GB in 20 s and growing).
  Run r = run("vg layout:0 --spacing 1e-3" + tail);
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("2.5e+09 grid cells") && Contains("--spacing") && Contains("--allow-large"));
  // 1e5 given nodes: 5e9 pairs.  Within 0.5 m of each other the same nodes are a small run.
  {
    std::ofstream nodes(dir / "many.csv");
    for (int k = 0; k < 100000; ++k) nodes << (k % 316) * 0.15 << "," << (k / 316) * 0.15 << ",1.7\n";
  }
  r = run("vg layout:0 --nodes " + (dir / "many.csv") + tail);
  INFO(r.output);
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("100000 nodes = 5e+09 pairs") && Contains("--max-distance") &&
                           Contains("--prune-below") && Contains("--allow-large"));
  CHECK(!fs::exists(dir / "nodes.csv"));
  r = run("vg layout:0 --nodes " + (dir / "many.csv") + " --max-distance 0.5" + tail);
  INFO(r.output);
  CHECK(r.status == 0);
  CHECK(read_csv(dir / "nodes.csv").rows.size() == 100000);
  // A 500 km x 2 m strip at 1 m, asked for explicitly: 1e6 nodes, 5e11 pairs.  (Without --spacing the
  // grid would be coarsened until it fits, to 8 m.)
  std::ofstream(dir / "strip.obj") << "v 0 0 0\nv 500000 0 0\nv 500000 2 0\nv 0 2 0\nf 1 2 3\nf 1 3 4\n";
  r = run("vg " + (dir / "strip.obj") + " --spacing 1 --conditions clear --quiet --out " + (dir / "strip.csv"));
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("1000000 nodes = 5e+11 pairs"));
  CHECK(!fs::exists(dir / "strip.csv"));
}

TEST_CASE("vg writes all its outputs or none", "[visgraph][cli][limits]") {
  TempDir dir;
  const std::string base = "vg layout:2 --conditions clear --quiet --out " + (dir / "nodes.csv");
  // The summary's directory does not exist: the CSV, complete by then, used to stay behind.
  Run r = run(base + " --ply " + (dir / "nodes.ply") + " --summary " + (dir / "missing/summary.json"));
  INFO(r.output);
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("missing/summary.json"));
  CHECK(dir.files().empty());
  // An existing output that is not a regular file is refused and left as it is.
  REQUIRE(::mkfifo((dir / "fifo").c_str(), 0600) == 0);
  r = run(base + " --geojson " + (dir / "fifo"));
  CHECK(r.status != 0);
  CHECK_THAT(r.output, Contains("not a regular file"));
  CHECK(fs::is_fifo(dir / "fifo"));
  CHECK(dir.files() == std::vector<std::string>{"fifo"});
  // All outputs of a good run appear.
  r = run(base + " --ply " + (dir / "nodes.ply") + " --summary " + (dir / "summary.json") + " --geojson " +
          (dir / "nodes.geojson") + " --edges " + (dir / "edges.csv"));
  INFO(r.output);
  CHECK(r.status == 0);
  CHECK(dir.files().size() == 6);
  CHECK(read_csv(dir / "edges.csv").rows.size() > 0);
}
