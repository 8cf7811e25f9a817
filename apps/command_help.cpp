// --help's layout for every subcommand, `attenuvis help TOPIC`, and range
// validators (command_help.hpp).
#include "command_help.hpp"

#include <cmath>
#include <filesystem>
#include <limits>
#include <iostream>
#include <map>
#include <memory>
#include <sstream>
#include <utility>
#include <vector>

#include "attenuvis/io/install_paths.hpp"
#include "attenuvis/io/number_text.hpp"
#include "attenuvis/weather/condition_grammar.hpp"
#include "attenuvis/weather/distribution_file.hpp"
#include "attenuvis/weather/domains.hpp"

namespace attenuvis::cli {
namespace {

namespace fs = std::filesystem;
namespace w = attenuvis::weather;

struct OptionGroup {
  const char* title;
  std::vector<const char*> options;  // long names as given to add_option ("--out")
};

struct HelpLayout {
  const char* guide_page;  // page of the user guide, relative to the documentation root, without suffix
  std::vector<OptionGroup> groups;
};

// The weather options every sigma-computing subcommand shares (weather_options.hpp).
const OptionGroup& weather_group() {
  static const OptionGroup group{"Weather", {"--wavelength", "--convention", "--threshold", "--tolerance", "--water",
                                             "--units"}};
  return group;
}

// One entry per subcommand.  A new option joins a group by its name here.
const std::map<std::string, HelpLayout>& help_layouts() {
  static const std::map<std::string, HelpLayout> layouts{
      {"mie",
       {"guide/mie",
        {{"Sphere", {"--x", "--radius", "--wavelength", "--medium-index", "--m"}},
         {"Outputs", {"--angles", "--phase", "--moments", "--polarised", "--json"}},
         {"Method", {"--terms", "--working"}}}}},
      {"sigma", {"guide/conditions", {weather_group(), {"Output", {"--json"}}}}},
      {"distribution", {"guide/conditions", {{"Output", {"--bulk-density", "--json"}}}}},
      {"optics",
       {"guide/tables",
        {{"Quantities", {"--moments", "--polarised", "--angles"}}, weather_group(), {"Output", {"--json"}}}}},
      {"table",
       {"guide/tables",
        {{"Table", {"--conditions", "--wavelengths", "--quantities", "--angles"}},
         weather_group(),
         {"Output", {"--format", "--out"}},
         {"Run", {"--threads"}}}}},
      {"vg",
       {"guide/visibility-graphs",
        {{"Scene", {"--up-axis", "--lod", "--ground-plane"}},
         {"Nodes", {"--spacing", "--eye-height", "--walkable", "--max-slope", "--nodes", "--targets", "--target-point"}},
         {"Weather", {"--conditions", "--wavelength", "--convention", "--threshold", "--water"}},
         {"Visibility pass",
          {"--prune-below", "--tolerance", "--max-distance", "--no-culling", "--allow-large", "--threads"}},
         {"Outputs",
          {"--out", "--distances", "--ply", "--geojson", "--heatmap", "--color-by", "--summary", "--edges",
           "--quiet"}}}}},
      {"scene", {"guide/visibility-graphs", {{"Describe a file (info)", {"--groups", "--up-axis", "--lod"}},
                                             {"Write a shipped scene", {"--out"}}}}},
      {"reproduce", {"guide/reproducing", {}}},
      {"help", {"index", {}}},
  };
  return layouts;
}

// "file:///usr/local/share/doc/attenuvis/html/guide/mie.html", or the page's
// Markdown source when the HTML was never built.
std::string page_location(const std::string& page) {
  const std::string root = documentation_location();
  if (fs::path(root).filename() == "docs") return root + "/" + page + ".md";
  return "file://" + root + "/" + page + ".html";
}

// Help lines no wider than a terminal and a man page hold.
constexpr std::size_t kHelpWidth = 90;

// `text` broken at spaces into lines of at most `width` characters (a word
// longer than that stands alone); its own line breaks are kept.
std::string wrapped(const std::string& text, std::size_t width) {
  std::string out, line, word;
  const auto end_word = [&] {
    if (word.empty()) return;
    if (!line.empty() && line.size() + 1 + word.size() > width) {
      out += line + "\n";
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
    word.clear();
  };
  for (char c : text) {
    if (c == ' ') {
      end_word();
    } else if (c == '\n') {
      end_word();
      out += line + "\n";
      line.clear();
    } else {
      word += c;
    }
  }
  end_word();
  return out + line;
}

// CLI11's layout with one blank line between option groups, not two, and
// descriptions wrapped to kHelpWidth.
class GroupedFormatter : public CLI::Formatter {
 public:
  std::string make_group(std::string group, bool is_positional, std::vector<const CLI::Option*> opts) const override {
    const std::string text = CLI::Formatter::make_group(group, is_positional, opts);
    const bool first = is_positional || group == "Options";
    return first ? text : text.substr(1);
  }
  std::string make_option_desc(const CLI::Option* option) const override {
    return wrapped(CLI::Formatter::make_option_desc(option), kHelpWidth - get_column_width());
  }
  std::string make_subcommand(const CLI::App* sub) const override {
    std::stringstream out;
    CLI::detail::format_help(out, sub->get_display_name(true), wrapped(sub->get_description(), kHelpWidth - get_column_width()),
                             get_column_width());
    return out.str();
  }
  std::string make_description(const CLI::App* app) const override {
    return wrapped(CLI::Formatter::make_description(app), kHelpWidth);
  }
};

// 1024, 100000, 0.5, 1e-06: integers as a person writes them.
std::string plain_number(double value) {
  if (value == std::floor(value) && std::fabs(value) < 1e15) return std::to_string(static_cast<long long>(value));
  return io::shortest(value);
}

std::string validation_text(const std::string& text, double lo, double hi) {
  double value = 0;
  try {
    std::size_t used = 0;
    value = std::stod(text, &used);
    if (used != text.size()) return "'" + text + "' is not a number";
  } catch (const std::exception&) {
    return "'" + text + "' is not a number";
  }
  if (value >= lo && value <= hi) return {};
  if (hi == std::numeric_limits<double>::infinity()) return "must be >= " + plain_number(lo) + " (got " + text + ")";
  return "must be in [" + plain_number(lo) + ", " + plain_number(hi) + "] (got " + text + ")";
}

std::string distribution_file_help() {
  using namespace w::domain;
  return std::string(w::distribution_file_format()) + "\nvalid ranges: marshall-palmer R " +
         w::range_text(rain_rate) + ", gunn-marshall R " + w::range_text(snow_rate) +
         ";\n  file values in SI: radius " + w::range_text(drop_radius) + ", dN/dr " +
         w::range_text(density_per_radius) + ", dN/dln r and counts " + w::range_text(number_per_volume) + "\n";
}

// The topics of `attenuvis help`, each with the text it prints.
const std::vector<std::pair<std::string, std::string (*)()>>& help_topics() {
  static const std::vector<std::pair<std::string, std::string (*)()>> topics{
      {"conditions", [] { return w::condition_grammar() + "\n"; }},
      {"distribution-files", distribution_file_help},
      {"ranges", [] { return "valid ranges of the weather inputs:\n" + w::domains_help(); }},
  };
  return topics;
}

}  // namespace

std::string documentation_location() {
  const std::string installed = io::installed_documentation_directory();
  if (!installed.empty()) return installed;
  std::error_code ec;
  if (fs::exists(fs::path(ATTENUVIS_BUILD_DOCS_HTML) / "index.html", ec)) return ATTENUVIS_BUILD_DOCS_HTML;
  return ATTENUVIS_SOURCE_DOCS;
}

void apply_help_layout(CLI::App& app) {
  const auto formatter = std::make_shared<GroupedFormatter>();
  app.formatter(formatter);
  app.footer([] {
    return "Documentation: " + page_location("index") +
           "\n`attenuvis help` lists the help topics (the condition grammar among them); man attenuvis";
  });
  for (CLI::App* sub : app.get_subcommands({})) {
    sub->formatter(formatter);
    const auto found = help_layouts().find(sub->get_name());
    if (found == help_layouts().end()) continue;
    const HelpLayout& layout = found->second;
    for (const OptionGroup& group : layout.groups)
      for (const char* name : group.options)
        if (CLI::Option* option = sub->get_option_no_throw(name)) option->group(group.title);
    const std::string page = layout.guide_page;
    sub->footer([page] { return "Guide: " + page_location(page); });
  }
}

void register_help(CLI::App& app) {
  auto topic = std::make_shared<std::string>();
  std::string names;
  for (const auto& t : help_topics()) names += (names.empty() ? "" : ", ") + t.first;
  CLI::App* cmd = app.add_subcommand("help", "print a help topic: " + names);
  cmd->add_option("topic", *topic, "one of " + names + " (none: list them)");
  cmd->callback([topic, names] {
    if (topic->empty()) {
      std::cout << "help topics (attenuvis help TOPIC): " << names << "\n"
                << "every subcommand: attenuvis SUBCOMMAND --help\n"
                << "documentation: " << page_location("index") << "\n";
      return;
    }
    for (const auto& t : help_topics())
      if (t.first == *topic) {
        std::cout << t.second();
        return;
      }
    throw std::invalid_argument("help: unknown topic '" + *topic + "' (topics: " + names + ")");
  });
}

CLI::Validator at_least(double lo) {
  return CLI::Validator([lo](std::string& text) { return validation_text(text, lo, std::numeric_limits<double>::infinity()); },
                        ">= " + plain_number(lo), "at_least");
}

CLI::Validator in_range(double lo, double hi) {
  return CLI::Validator([lo, hi](std::string& text) { return validation_text(text, lo, hi); },
                        "in [" + plain_number(lo) + ", " + plain_number(hi) + "]", "in_range");
}

}  // namespace attenuvis::cli
