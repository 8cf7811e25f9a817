// The command line's help as a reader meets it: a one-line summary per
// subcommand, grouped options and a pointer to the guide; the grammar and the
// file formats one command away (`attenuvis help TOPIC`), printed from the
// same registries as before; ranges in error messages as a person writes them.
#include <catch2/catch.hpp>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "../cli_run.hpp"
#include "attenuvis/weather/condition_grammar.hpp"

using Catch::Matchers::Contains;

namespace {

std::size_t line_count(const std::string& text) {
  std::size_t lines = 0;
  for (char c : text) lines += c == '\n';
  return lines;
}

}  // namespace

TEST_CASE("every subcommand's --help names its guide page and groups its options", "[weather][cli][help]") {
  const auto top = cli_run::run("--help");
  REQUIRE(top.status == 0);
  CHECK_THAT(top.output, Contains("Documentation: ") && Contains("attenuvis help"));
  // One line per subcommand in the list: the summaries are single lines.
  const std::string list = top.output.substr(top.output.find("Subcommands:"));
  std::vector<std::string> names{"mie", "sigma", "table", "distribution", "optics", "vg", "scene", "help"};
#ifndef ATTENUVIS_WITHOUT_REPRODUCE  // the sanitizer tree builds the program without `reproduce`
  names.push_back("reproduce");
#endif
  for (const std::string& name : names) {
    INFO(name);
    CHECK_THAT(list, Contains("\n  " + name + " "));
    const auto help = cli_run::run(name + " --help");
    REQUIRE(help.status == 0);
    // A one-line summary, then the usage; no grammar table follows it.
    const std::string summary = help.output.substr(0, help.output.find("Usage:"));
    CHECK(std::count(summary.begin(), summary.end(), '\n') == 1);
    CHECK_THAT(help.output, !Contains("OPTIONS after a Mie condition"));
  }
  // The guide page each one points to.
  CHECK_THAT(cli_run::run("mie --help").output, Contains("Guide: ") && Contains("guide/mie."));
  CHECK_THAT(cli_run::run("sigma --help").output, Contains("guide/conditions."));
  CHECK_THAT(cli_run::run("optics --help").output, Contains("guide/tables."));
#ifndef ATTENUVIS_WITHOUT_REPRODUCE
  CHECK_THAT(cli_run::run("reproduce --help").output, Contains("guide/reproducing."));
#endif
  const auto vg = cli_run::run("vg --help");
  CHECK_THAT(vg.output, Contains("guide/visibility-graphs.") && Contains("\nNodes:\n") &&
                            Contains("\nVisibility pass:\n") && Contains("\nOutputs:\n"));
  // The grammar moved out of sigma's and optics' help (42 and 45 lines, most of them
  // grammar): each fits a terminal screen now, options wrapped at 90 columns.
  CHECK(line_count(cli_run::run("sigma --help").output) < 40);
  CHECK(line_count(cli_run::run("optics --help").output) < 40);
}

TEST_CASE("attenuvis help prints the grammar, the file format and the ranges", "[weather][cli][help]") {
  const auto conditions = cli_run::run("help conditions");
  REQUIRE(conditions.status == 0);
  CHECK(conditions.output == attenuvis::weather::condition_grammar() + "\n");
  CHECK_THAT(cli_run::run("help distribution-files").output, Contains("radius_um,dNdr_per_cm3_per_um"));
  CHECK_THAT(cli_run::run("help ranges").output, Contains("rain rate"));
  const auto topics = cli_run::run("help");
  CHECK(topics.status == 0);
  CHECK_THAT(topics.output, Contains("conditions, distribution-files, ranges"));
  const auto unknown = cli_run::run("help nonsense");
  CHECK(unknown.status != 0);
  CHECK_THAT(unknown.output, Contains("attenuvis: error: help: unknown topic 'nonsense'"));
}

TEST_CASE("a number outside its range is refused with the range as a person writes it", "[weather][cli][help]") {
  // CLI11's own validators printed the largest double in full (309 digits).
  std::vector<std::string> outputs;
#ifndef ATTENUVIS_WITHOUT_REPRODUCE
  const auto threads = cli_run::run("reproduce --threads -1");
  CHECK(threads.status != 0);
  CHECK_THAT(threads.output, Contains("attenuvis: error: --threads: must be >= 0 (got -1)"));
  outputs.push_back(threads.output);
#endif
  const auto table = cli_run::run("table --conditions clear --out /nonexistent/t.csv --threads 2000");
  CHECK(table.status != 0);
  CHECK_THAT(table.output, Contains("--threads: must be in [0, 1024] (got 2000)"));
  const auto moments = cli_run::run("optics fog:radiation --moments -3");
  CHECK(moments.status != 0);
  CHECK_THAT(moments.output, Contains("--moments: must be in [0, 100000] (got -3)"));
  CHECK_THAT(cli_run::run("optics fog:radiation --moments many").output, Contains("'many' is not a number"));
  outputs.push_back(table.output);
  outputs.push_back(moments.output);
  for (const std::string& output : outputs) CHECK(output.size() < 200);
}
