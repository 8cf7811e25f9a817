// The reproduction report's document model: sections made of paragraphs,
// tables and figures, plus named key numbers that the summary and the
// regression test read.  Nothing here computes physics; the sections fill it
// with numbers computed in the same run, and html_report.cpp / report_csv.cpp
// turn it into files.
#pragma once

#include <map>
#include <string>
#include <variant>
#include <vector>

#include <nlohmann/json.hpp>

namespace attenuvis::validation {

// One table cell.  A numeric cell keeps the full double (written to CSV in
// shortest round-trip form) and how many significant digits the HTML shows.
struct Cell {
  std::string text;     // shown as is when !numeric
  double value = 0.0;   // the number when numeric
  bool numeric = false;
  int digits = 6;       // significant digits in the HTML view

  Cell() = default;
  Cell(const char* s) : text(s) {}
  Cell(std::string s) : text(std::move(s)) {}
  Cell(double v, int significant = 6) : value(v), numeric(true), digits(significant) {}
  Cell(int v) : value(v), numeric(true), digits(15) {}
  Cell(long v) : value(static_cast<double>(v)), numeric(true), digits(15) {}
  Cell(long long v) : value(static_cast<double>(v)), numeric(true), digits(15) {}
  Cell(unsigned long v) : value(static_cast<double>(v)), numeric(true), digits(15) {}
  Cell(unsigned long long v) : value(static_cast<double>(v)), numeric(true), digits(15) {}
  Cell(unsigned v) : value(v), numeric(true), digits(15) {}
};

// A table; it is also written as <id>.csv beside report.html.
struct Table {
  std::string id;       // file-name safe, unique in the report
  std::string caption;  // what the table compares
  std::vector<std::string> header;
  std::vector<std::vector<Cell>> rows;
  std::string source;   // provenance of any published values in it ("" if none)
  void add_row(std::vector<Cell> row) { rows.push_back(std::move(row)); }
};

// A figure drawn by validation/scripts/report_figures.py from `spec`
// (see that script for the kinds it understands); written as <id>.png.
struct Figure {
  std::string id;
  std::string caption;
  nlohmann::json spec;
};

// A paragraph of plain text (HTML-escaped when written).  `kind` styles it:
// "text", "source" (where a published value comes from), "agree",
// "disagree" (with the reason), "missing" (not available in this build),
// "data" (data files beside the report: `text` is "FILE|description" or
// "FILE FILE ...|description").
//
// The report's verdicts (Report::closing) are paragraphs of kind "agree",
// "disagree" or "missing" and open the page as a table, one row each.  A
// verdict may state its parts separately: `claim` (what the seed paper or the
// published source says, with where), `ours` (what this run gives) and
// `text` (the one-line reason); without a claim, the table shows `text`
// whole, its part before the first ": " as the subject.  `section` is the id
// of the section that made it (set by the reproduction job) for the link.
struct Paragraph {
  std::string kind = "text";
  std::string text;
  std::string claim;
  std::string ours;
  std::string section;

  Paragraph() = default;
  Paragraph(std::string k, std::string t) : kind(std::move(k)), text(std::move(t)) {}
};

// A verdict with its parts (see Paragraph): kind "agree", "disagree" or "missing".
inline Paragraph verdict(std::string kind, std::string claim, std::string ours, std::string reason) {
  Paragraph p(std::move(kind), std::move(reason));
  p.claim = std::move(claim);
  p.ours = std::move(ours);
  return p;
}

// One block of a section's body.
using Block = std::variant<Paragraph, Table, Figure>;

// One numbered section of the report: its blocks and its summary lines.
struct Section {
  std::string id;
  std::string title;
  bool available = true;               // false: the section says why it is missing
  std::vector<Block> blocks;
  std::vector<std::string> summary;    // lines for the one-screen stdout summary
  double seconds = 0.0;                // wall time spent computing it

  void text(std::string t) { blocks.push_back(Paragraph{"text", std::move(t)}); }
  void source(std::string t) { blocks.push_back(Paragraph{"source", std::move(t)}); }
  void agree(std::string t) { blocks.push_back(Paragraph{"agree", std::move(t)}); }
  void disagree(std::string t) { blocks.push_back(Paragraph{"disagree", std::move(t)}); }
  void missing(std::string t) {
    available = false;
    blocks.push_back(Paragraph{"missing", std::move(t)});
  }
  void data(const std::string& file, const std::string& description) {
    blocks.push_back(Paragraph{"data", file + "|" + description});
  }
  Table& table(Table t) {
    blocks.push_back(std::move(t));
    return std::get<Table>(blocks.back());
  }
  void figure(Figure f) { blocks.push_back(std::move(f)); }
};

// The whole report: its sections, in order, and how the run was made.
struct Report {
  std::string title;
  std::string preamble;                    // how the run was made (machine, options, time)
  std::vector<Paragraph> guide;            // how to read the page: the terms every section uses
  std::vector<Section> sections;           // in the order the page shows them
  std::vector<Paragraph> closing;          // the verdicts: what reproduces the seed, what does not and why
  std::map<std::string, double> key;       // named key numbers (summary.json, regression test)
};

// Formats v with `digits` significant digits, without trailing noise
// (e.g. 0.00015, 2424, 3.2e-12).
std::string format_number(double v, int digits);
// Shortest text that reads back to exactly v (CSV cells).
std::string exact_number(double v);

// Writers.  Each writes through a temporary file in the same directory and
// renames it, so a reader never sees half a file.
void write_table_csv(const Table& table, const std::string& path);
void write_report_html(const Report& report, const std::string& path);
void write_key_json(const Report& report, const std::string& path);
// Writes `text` to `path` atomically (temp file beside it, then rename).
void write_file_atomically(const std::string& path, const std::string& text);

}  // namespace attenuvis::validation
