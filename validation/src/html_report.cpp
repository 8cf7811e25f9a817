// report.html: one self-contained page (inline CSS, no scripts, no network),
// with the PNG figures and CSV tables referenced beside it.
#include <sstream>
#include <string>
#include <variant>

#include "attenuvis/validation/report.hpp"

namespace attenuvis::validation {
namespace {

std::string escape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

const char* kStyle = R"(
body{font-family:system-ui,-apple-system,"Segoe UI",Roboto,sans-serif;max-width:1150px;margin:1.5em auto;padding:0 1em;color:#1d1d1f;line-height:1.45}
h1{font-size:1.6em;margin-bottom:.3em} h2{border-bottom:2px solid #ddd;padding-bottom:.2em;margin-top:2em}
nav ol{columns:2;column-gap:2em} nav li{break-inside:avoid}
@media (max-width:900px){nav ol{columns:1}}
.scroll{overflow-x:auto;max-width:100%;margin:.6em 0}
table{border-collapse:collapse;font-size:.88em}
th,td{border:1px solid #ccc;padding:.25em .55em;text-align:right;vertical-align:top} th{background:#f1f1f4;text-align:left}
td.n{white-space:nowrap} td.t{text-align:left}
caption{caption-side:top;text-align:left;font-weight:600;padding:.3em 0}
details{margin:.6em 0;border:1px solid #ddd;border-radius:4px;padding:.3em .6em;background:#fafafc}
summary{cursor:pointer;font-weight:600} summary .rows{font-weight:400;color:#555}
p.source{color:#444;font-size:.9em;border-left:3px solid #88a;padding-left:.6em}
p.agree{border-left:4px solid #2a8a3a;padding-left:.6em;background:#f0f8f1}
p.disagree{border-left:4px solid #c0392b;padding-left:.6em;background:#fbf0ef}
p.missing{border-left:4px solid #999;padding:.4em .6em;background:#eee;font-weight:600}
p.meta{color:#555;font-size:.85em}
figure{margin:1.2em 0} figure img{max-width:100%;height:auto;border:1px solid #eee}
figcaption{font-size:.9em;color:#333;max-width:60em}
.csv{font-size:.85em;font-weight:400;margin-left:.6em} .secs{color:#777;font-size:.8em;font-weight:400}
table.verdict{font-size:.9em;width:100%;min-width:640px} table.verdict td{text-align:left}
table.verdict td.v{white-space:nowrap;font-weight:600}
td.v.agree{background:#e3f3e6;color:#1d6b2b} td.v.disagree{background:#f8e1de;color:#a02a1e} td.v.missing{background:#eee;color:#555}
pre{background:#f6f6f8;padding:.6em;overflow-x:auto}
)";

// Tables longer than this are folded (their CSV is linked either way).
constexpr std::size_t kFoldRows = 15;

// Numbers tables and figures in page order, for the captions.
struct Counters {
  int table = 0, figure = 0;
};

void write_paragraph(std::ostringstream& os, const Paragraph& p) {
  if (p.kind == "data") {
    // "FILE|description", or "FILE FILE ...|description" for a set of files.
    const auto bar = p.text.find('|');
    std::istringstream files(p.text.substr(0, bar));
    const std::string what = bar == std::string::npos ? "" : p.text.substr(bar + 1);
    os << "<p class=\"source\"><b>Data:</b>";
    for (std::string file; files >> file;) os << " <a href=\"" << escape(file) << "\">" << escape(file) << "</a>";
    os << " " << escape(what) << "</p>\n";
    return;
  }
  os << "<p class=\"" << escape(p.kind) << "\">";
  if (p.kind == "source") os << "<b>Source:</b> ";
  if (p.kind == "agree") os << "<b>Agrees:</b> ";
  if (p.kind == "disagree") os << "<b>Differs:</b> ";
  if (p.kind == "missing") os << "Not available in this build: ";
  os << escape(p.text) << "</p>\n";
}

void write_table_body(std::ostringstream& os, const Table& t) {
  os << "<div class=\"scroll\"><table id=\"" << escape(t.id) << "\">\n<tr>";
  for (const auto& h : t.header) os << "<th>" << escape(h) << "</th>";
  os << "</tr>\n";
  for (const auto& row : t.rows) {
    os << "<tr>";
    for (const auto& c : row) {
      if (c.numeric) os << "<td class=\"n\">" << escape(format_number(c.value, c.digits)) << "</td>";
      else os << "<td class=\"t\">" << escape(c.text) << "</td>";
    }
    os << "</tr>\n";
  }
  os << "</table></div>\n";
}

// A short table is shown; a long one is folded behind its caption, so the
// figures and the text around it stay close together.
void write_table(std::ostringstream& os, const Table& t, Counters& n) {
  const std::string label = "Table " + std::to_string(++n.table) + ". ";
  const std::string csv = " <a class=\"csv\" href=\"" + escape(t.id) + ".csv\">CSV</a>";
  if (t.rows.size() > kFoldRows) {
    os << "<details><summary>" << escape(label + t.caption) << " <span class=\"rows\">(" << t.rows.size()
       << " rows, click to show)</span>" << csv << "</summary>\n";
    write_table_body(os, t);
    if (!t.source.empty()) write_paragraph(os, Paragraph{"source", t.source});
    os << "</details>\n";
    return;
  }
  os << "<p class=\"caption\"><b>" << escape(label + t.caption) << "</b>" << csv << "</p>\n";
  write_table_body(os, t);
  if (!t.source.empty()) write_paragraph(os, Paragraph{"source", t.source});
}

void write_figure(std::ostringstream& os, const Figure& f, Counters& n) {
  const std::string label = "Figure " + std::to_string(++n.figure) + ". ";
  // The image links to itself: on a narrow screen a reader opens it at full size.
  os << "<figure id=\"fig-" << escape(f.id) << "\"><a href=\"" << escape(f.id) << ".png\"><img src=\"" << escape(f.id)
     << ".png\" alt=\"" << escape(f.caption) << "\" loading=\"lazy\"></a><figcaption><b>" << escape(label) << "</b>"
     << escape(f.caption) << "</figcaption></figure>\n";
}

const Section* find_section(const Report& report, const std::string& id) {
  for (const auto& s : report.sections)
    if (s.id == id) return &s;
  return nullptr;
}

// The verdict table: one row per verdict of the closing list, with a link
// to the section that made it.
void write_verdicts(std::ostringstream& os, const Report& report) {
  os << "<section id=\"verdict\"><h2>Verdict</h2>\n";
  for (const auto& p : report.closing)
    if (p.kind == "text") os << "<p><b>" << escape(p.text) << "</b></p>\n";
  os << "<div class=\"scroll\"><table class=\"verdict\">\n<tr><th>Verdict</th><th>The seed paper (or published "
        "source)</th><th>This run</th><th>Why</th><th>Section</th></tr>\n";
  for (const auto& p : report.closing) {
    if (p.kind != "agree" && p.kind != "disagree" && p.kind != "missing") continue;
    const char* word = p.kind == "agree" ? "agrees" : p.kind == "disagree" ? "differs" : "not made";
    os << "<tr><td class=\"v " << escape(p.kind) << "\">" << word << "</td>";
    if (!p.claim.empty()) {
      os << "<td>" << escape(p.claim) << "</td><td>" << escape(p.ours) << "</td><td>" << escape(p.text) << "</td>";
    } else {
      // Unstructured verdict: "subject: sentence".
      const auto colon = p.text.find(": ");
      const std::string subject = colon == std::string::npos ? "" : p.text.substr(0, colon);
      const std::string rest = colon == std::string::npos ? p.text : p.text.substr(colon + 2);
      os << "<td>" << escape(subject) << "</td><td colspan=\"2\">" << escape(rest) << "</td>";
    }
    const Section* s = find_section(report, p.section);
    // The link reads as the section's number and name ("3. The city").
    if (s) os << "<td><a href=\"#" << escape(s->id) << "\">" << escape(s->title.substr(0, s->title.find(':')))
              << "</a></td>";
    else os << "<td></td>";
    os << "</tr>\n";
  }
  os << "</table></div>\n</section>\n";
}

}  // namespace

void write_report_html(const Report& report, const std::string& path) {
  std::ostringstream os;
  os << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
        "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>"
     << escape(report.title) << "</title>\n<style>" << kStyle << "</style></head><body>\n";
  os << "<h1>" << escape(report.title) << "</h1>\n";
  write_verdicts(os, report);
  os << "<p class=\"meta\">" << escape(report.preamble) << "</p>\n";
  if (!report.guide.empty()) {
    os << "<section id=\"guide\"><h2>How to read this report</h2>\n";
    for (const auto& p : report.guide) write_paragraph(os, p);
    os << "</section>\n";
  }
  os << "<nav><h2>Contents</h2><ol>";
  for (const auto& s : report.sections) {
    const auto dot = s.title.find(". ");
    os << "<li><a href=\"#" << escape(s.id) << "\">" << escape(dot == std::string::npos ? s.title : s.title.substr(dot + 2))
       << "</a>" << (s.available ? "" : " (not available in this build)") << "</li>";
  }
  os << "</ol></nav>\n";
  Counters counters;
  for (const auto& s : report.sections) {
    os << "<section id=\"" << escape(s.id) << "\"><h2>" << escape(s.title) << " <span class=\"secs\">("
       << format_number(s.seconds, 3) << " s)</span></h2>\n";
    for (const auto& b : s.blocks) {
      if (auto p = std::get_if<Paragraph>(&b)) write_paragraph(os, *p);
      else if (auto t = std::get_if<Table>(&b)) write_table(os, *t, counters);
      else if (auto f = std::get_if<Figure>(&b)) write_figure(os, *f, counters);
    }
    os << "</section>\n";
  }
  os << "<section id=\"files\"><h2>Files</h2>\n<p class=\"source\">Every table is beside this page as CSV (linked "
        "at its caption), every figure as PNG; the named key numbers of this run are in <a "
        "href=\"key.json\">key.json</a>.</p>\n</section>\n</body></html>\n";
  write_file_atomically(path, os.str());
}

}  // namespace attenuvis::validation
