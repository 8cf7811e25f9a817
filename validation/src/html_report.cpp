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
body{font-family:system-ui,-apple-system,"Segoe UI",Roboto,sans-serif;max-width:1150px;margin:2em auto;padding:0 1em;color:#1d1d1f;line-height:1.45}
h1{font-size:1.7em;margin-bottom:.2em} h2{border-bottom:2px solid #ddd;padding-bottom:.2em;margin-top:2em}
nav ol{columns:2} table{border-collapse:collapse;margin:.6em 0;font-size:.9em}
th,td{border:1px solid #ccc;padding:.25em .55em;text-align:right} th{background:#f1f1f4}
td.t{text-align:left} caption{caption-side:top;text-align:left;font-weight:600;padding:.3em 0}
p.source{color:#444;font-size:.9em;border-left:3px solid #88a;padding-left:.6em}
p.agree{border-left:4px solid #2a8a3a;padding-left:.6em;background:#f0f8f1}
p.disagree{border-left:4px solid #c0392b;padding-left:.6em;background:#fbf0ef}
p.missing{border-left:4px solid #999;padding:.4em .6em;background:#eee;font-weight:600}
figure{margin:1em 0} figure img{max-width:100%;border:1px solid #eee} figcaption{font-size:.9em;color:#333}
.csv{font-size:.8em;font-weight:400;margin-left:.6em} .secs{color:#777;font-size:.8em;font-weight:400}
pre{background:#f6f6f8;padding:.6em;overflow-x:auto}
)";

void write_paragraph(std::ostringstream& os, const Paragraph& p) {
  if (p.kind == "data") {
    const auto bar = p.text.find('|');
    const std::string file = p.text.substr(0, bar);
    const std::string what = bar == std::string::npos ? "" : p.text.substr(bar + 1);
    os << "<p class=\"source\"><b>Data:</b> <a href=\"" << escape(file) << "\">" << escape(file) << "</a> "
       << escape(what) << "</p>\n";
    return;
  }
  os << "<p class=\"" << escape(p.kind) << "\">";
  if (p.kind == "source") os << "<b>Source:</b> ";
  if (p.kind == "agree") os << "<b>Agrees:</b> ";
  if (p.kind == "disagree") os << "<b>Differs:</b> ";
  if (p.kind == "missing") os << "Not available in this build: ";
  os << escape(p.text) << "</p>\n";
}

void write_table(std::ostringstream& os, const Table& t) {
  os << "<table id=\"" << escape(t.id) << "\"><caption>" << escape(t.caption)
     << " <a class=\"csv\" href=\"" << escape(t.id) << ".csv\">CSV</a></caption>\n<tr>";
  for (const auto& h : t.header) os << "<th>" << escape(h) << "</th>";
  os << "</tr>\n";
  for (const auto& row : t.rows) {
    os << "<tr>";
    for (const auto& c : row) {
      if (c.numeric) os << "<td>" << escape(format_number(c.value, c.digits)) << "</td>";
      else os << "<td class=\"t\">" << escape(c.text) << "</td>";
    }
    os << "</tr>\n";
  }
  os << "</table>\n";
  if (!t.source.empty()) write_paragraph(os, Paragraph{"source", t.source});
}

void write_figure(std::ostringstream& os, const Figure& f) {
  os << "<figure><img src=\"" << escape(f.id) << ".png\" alt=\"" << escape(f.caption)
     << "\"><figcaption>" << escape(f.caption) << "</figcaption></figure>\n";
}

}  // namespace

void write_report_html(const Report& report, const std::string& path) {
  std::ostringstream os;
  os << "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>" << escape(report.title)
     << "</title>\n<style>" << kStyle << "</style></head><body>\n";
  os << "<h1>" << escape(report.title) << "</h1>\n";
  os << "<p>" << escape(report.preamble) << "</p>\n";
  os << "<nav><ol>";
  for (const auto& s : report.sections) {
    os << "<li><a href=\"#" << escape(s.id) << "\">" << escape(s.title) << "</a>"
       << (s.available ? "" : " (not available in this build)") << "</li>";
  }
  os << "<li><a href=\"#closing\">Closing note</a></li></ol></nav>\n";
  for (const auto& s : report.sections) {
    os << "<section id=\"" << escape(s.id) << "\"><h2>" << escape(s.title) << " <span class=\"secs\">("
       << format_number(s.seconds, 3) << " s)</span></h2>\n";
    for (const auto& b : s.blocks) {
      if (auto p = std::get_if<Paragraph>(&b)) write_paragraph(os, *p);
      else if (auto t = std::get_if<Table>(&b)) write_table(os, *t);
      else if (auto f = std::get_if<Figure>(&b)) write_figure(os, *f);
    }
    os << "</section>\n";
  }
  os << "<section id=\"closing\"><h2>Closing note</h2>\n";
  for (const auto& p : report.closing) write_paragraph(os, p);
  os << "<p class=\"source\">The named key numbers of this run are in <a href=\"key.json\">key.json</a>.</p>\n";
  os << "</section>\n</body></html>\n";
  write_file_atomically(path, os.str());
}

}  // namespace attenuvis::validation
