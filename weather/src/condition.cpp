// Parsing the condition grammar (condition.hpp).
#include "attenuvis/weather/condition.hpp"

#include <cctype>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "attenuvis/weather/units.hpp"

namespace attenuvis::weather {
namespace {

const char* kGrammar =
    "conditions:\n"
    "  clear                          clear air, sigma = 0.00015 1/m (seed paper)\n"
    "  clear:DIST | visibility:DIST   from a visibility (Koschmieder), e.g. visibility:2km\n"
    "  sigma:VALUE[/m|/km|dB/km]      a given sigma, e.g. sigma:0.002\n"
    "  rain:RATE[:seed|carbonneau|p1814|mie]   RATE mm/h, e.g. rain:8, rain:8:mie\n"
    "  snow:wet:RATE | snow:dry:RATE  RATE mm/h, e.g. snow:dry:4\n"
    "  fog:advection | fog:radiation | fog:file=PATH   Mie over a size distribution\n"
    "  fog:kruse:DIST | fog:kim:DIST | fog:naboulsi-advection:DIST | fog:naboulsi-radiation:DIST\n"
    "  Mie options: :m=N+Ki  :water=hale-querry|segelstein  :N=PER_CM3  :lwc=G_PER_M3\n"
    "  DIST: 500m, 2km; in tables RATE/DIST may sweep: A..B or A..B/STEP (rain:1..100)";

[[noreturn]] void bad(const std::string& text, const std::string& why) {
  throw std::invalid_argument("bad condition '" + text + "': " + why + "\n" + kGrammar);
}

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : s) {
    if (c == sep) { out.push_back(cur); cur.clear(); }
    else cur += c;
  }
  out.push_back(cur);
  return out;
}

bool is_option(const std::string& tok) {
  for (const char* key : {"m=", "water=", "N=", "lwc="})
    if (tok.rfind(key, 0) == 0) return true;
  return false;
}

// "1.33+1e-8i", "1.33-0i", "1.5" -> complex; k must be >= 0 (absorbing).
std::complex<double> parse_index(const std::string& text, const std::string& cond) {
  std::string s = text;
  if (!s.empty() && (s.back() == 'i' || s.back() == 'j')) {
    s.pop_back();
    std::size_t split_at = std::string::npos;
    for (std::size_t i = 1; i < s.size(); ++i)
      if ((s[i] == '+' || s[i] == '-') && s[i - 1] != 'e' && s[i - 1] != 'E') split_at = i;
    if (split_at == std::string::npos) bad(cond, "refractive index '" + text + "' should look like 1.33+1e-8i");
    double n = parse_number(s.substr(0, split_at), "refractive index real part");
    double k = parse_number(s.substr(split_at), "refractive index imaginary part");
    if (k < 0) bad(cond, "refractive index imaginary part must be >= 0 (absorbing; m = n + ik)");
    if (!(n > 0)) bad(cond, "refractive index real part must be > 0");
    return {n, k};
  }
  double n = parse_number(s, "refractive index");
  if (!(n > 0)) bad(cond, "refractive index real part must be > 0");
  return {n, 0.0};
}

void parse_options(Condition& c, const std::vector<std::string>& toks, std::size_t from) {
  for (std::size_t i = from; i < toks.size(); ++i) {
    const std::string& t = toks[i];
    try {
      if (t.rfind("m=", 0) == 0) c.refractive_index = parse_index(t.substr(2), c.text);
      else if (t.rfind("water=", 0) == 0) {
        c.water_table = t.substr(6);
        if (c.water_table != "hale-querry" && c.water_table != "segelstein" && c.water_table != "water")
          bad(c.text, "water table '" + c.water_table + "' is not hale-querry or segelstein");
      } else if (t.rfind("N=", 0) == 0) {
        c.number_per_cm3 = parse_number(t.substr(2), "N");
        if (!(c.number_per_cm3 > 0)) bad(c.text, "N must be > 0 (per cm^3)");
      } else if (t.rfind("lwc=", 0) == 0) {
        c.lwc_g_m3 = parse_number(t.substr(4), "lwc");
        if (!(c.lwc_g_m3 > 0)) bad(c.text, "lwc must be > 0 (g/m^3)");
      } else {
        bad(c.text, "unexpected field '" + t + "'");
      }
    } catch (const std::invalid_argument& e) {
      std::string what = e.what();
      if (what.rfind("bad condition", 0) == 0) throw;
      bad(c.text, what);
    }
  }
  if (c.number_per_cm3 > 0 && c.lwc_g_m3 > 0) bad(c.text, "give N= or lwc=, not both");
}

double parse_rate(const std::string& tok, const std::string& cond) {
  double r = 0;
  try {
    r = parse_number(tok, "rate (mm/h)");
  } catch (const std::invalid_argument& e) {
    bad(cond, e.what());
  }
  if (!(r > 0)) bad(cond, "rate must be > 0 mm/h");
  return r;
}

double parse_dist(const std::string& tok, const std::string& cond) {
  try {
    return parse_distance(tok);
  } catch (const std::invalid_argument& e) {
    bad(cond, e.what());
  }
}

// Finds the one field of `text` that holds a sweep A..B[/STEP][unit].
bool find_sweep(const std::vector<std::string>& toks, std::size_t& index) {
  for (std::size_t i = 0; i < toks.size(); ++i)
    if (toks[i].find("..") != std::string::npos && toks[i].rfind("file=", 0) != 0) { index = i; return true; }
  return false;
}

}  // namespace

const char* condition_grammar() { return kGrammar; }

Condition parse_condition(const std::string& text) {
  Condition c;
  c.text = text;
  if (text.empty()) bad(text, "empty condition");
  auto toks = split(text, ':');
  std::size_t sweep_at = 0;
  if (find_sweep(toks, sweep_at)) bad(text, "a sweep (A..B) is only allowed in tables");
  const std::string& head = toks[0];
  auto need = [&](std::size_t n) {
    if (toks.size() < n) bad(text, "missing field after '" + toks.back() + "'");
  };
  if (head == "clear") {
    c.kind = ConditionKind::clear;
    if (toks.size() == 2) c.value = parse_dist(toks[1], text);
    else if (toks.size() > 2) bad(text, "clear takes at most a visibility");
  } else if (head == "visibility") {
    need(2);
    if (toks.size() > 2) bad(text, "visibility takes one distance");
    c.kind = ConditionKind::visibility;
    c.value = parse_dist(toks[1], text);
  } else if (head == "sigma") {
    need(2);
    if (toks.size() > 2) bad(text, "sigma takes one value");
    std::string v = toks[1];
    SigmaUnit unit = SigmaUnit::per_m;
    for (auto [suffix, u] : {std::pair<const char*, SigmaUnit>{"dB/km", SigmaUnit::dB_per_km},
                             {"/km", SigmaUnit::per_km}, {"/m", SigmaUnit::per_m}}) {
      std::string s = suffix;
      if (v.size() > s.size() && v.compare(v.size() - s.size(), s.size(), s) == 0) {
        unit = u;
        v = v.substr(0, v.size() - s.size());
        break;
      }
    }
    double x = 0;
    try { x = parse_number(v, "sigma"); } catch (const std::invalid_argument& e) { bad(text, e.what()); }
    if (x < 0) bad(text, "sigma must be >= 0");
    c.kind = ConditionKind::sigma;
    c.value = convert_to_per_m(x, unit);
  } else if (head == "rain") {
    need(2);
    c.value = parse_rate(toks[1], text);
    std::string model = toks.size() >= 3 ? toks[2] : "seed";
    if (model == "mie") {
      c.kind = ConditionKind::rain_mie;
      parse_options(c, toks, 3);
    } else {
      if (toks.size() > 3) bad(text, "options (m=, N=...) apply only to rain:RATE:mie");
      try { rain_power_law(model); } catch (const std::invalid_argument& e) { bad(text, e.what()); }
      c.kind = ConditionKind::rain_power_law;
      c.model = model;
    }
  } else if (head == "snow") {
    need(3);
    if (toks[1] == "wet") c.snow = SnowType::wet;
    else if (toks[1] == "dry") c.snow = SnowType::dry;
    else bad(text, "snow type must be wet or dry");
    if (toks.size() > 3) bad(text, "snow takes a type and a rate");
    c.kind = ConditionKind::snow;
    c.value = parse_rate(toks[2], text);
  } else if (head == "fog") {
    need(2);
    const std::string& what = toks[1];
    if (what == "advection" || what == "radiation") {
      c.kind = ConditionKind::fog_mie;
      c.model = what;
      parse_options(c, toks, 2);
    } else if (what.rfind("file=", 0) == 0) {
      // A path may itself contain ':'; it runs up to the first option field.
      std::string path = what.substr(5);
      std::size_t i = 2;
      while (i < toks.size() && !is_option(toks[i])) path += ":" + toks[i++];
      if (path.empty()) bad(text, "fog:file= needs a path");
      c.kind = ConditionKind::fog_mie;
      c.model = "file=" + path;
      parse_options(c, toks, i);
    } else if (what == "kruse" || what == "kim" || what == "naboulsi-advection" || what == "naboulsi-radiation") {
      need(3);
      if (toks.size() > 3) bad(text, "empirical fog takes one visibility");
      c.kind = ConditionKind::fog_visibility;
      c.fog_model = what == "kruse" ? VisibilityFogModel::kruse
                    : what == "kim" ? VisibilityFogModel::kim
                    : what == "naboulsi-advection" ? VisibilityFogModel::naboulsi_advection
                                                   : VisibilityFogModel::naboulsi_radiation;
      c.value = parse_dist(toks[2], text);
    } else {
      bad(text, "unknown fog '" + what + "'");
    }
  } else {
    bad(text, "unknown weather '" + head + "'");
  }
  return c;
}

std::vector<Condition> expand_conditions(const std::string& text) {
  auto toks = split(text, ':');
  std::size_t at = 0;
  if (!find_sweep(toks, at)) return {parse_condition(text)};
  const std::string& field = toks[at];
  auto dots = field.find("..");
  std::string lo_text = field.substr(0, dots), rest = field.substr(dots + 2), step_text = "1", unit;
  // Optional unit suffix (m, km) after the upper bound or the step.
  while (!rest.empty() && std::isalpha(static_cast<unsigned char>(rest.back()))) {
    unit.insert(unit.begin(), rest.back());
    rest.pop_back();
  }
  auto slash = rest.find('/');
  std::string hi_text = rest.substr(0, slash);
  if (slash != std::string::npos) step_text = rest.substr(slash + 1);
  double lo = 0, hi = 0, step = 0;
  try {
    lo = parse_number(lo_text, "sweep start");
    hi = parse_number(hi_text, "sweep end");
    step = parse_number(step_text, "sweep step");
  } catch (const std::invalid_argument& e) {
    bad(text, e.what());
  }
  if (!(step > 0) || !(hi >= lo)) bad(text, "sweep A..B/STEP needs A <= B and STEP > 0");
  double count = std::floor((hi - lo) / step + 1e-9) + 1;
  if (count > 10000) bad(text, "sweep has more than 10000 values");
  std::vector<Condition> out;
  for (int i = 0; i < static_cast<int>(count); ++i) {
    std::ostringstream v;
    v.precision(12);
    v << lo + i * step << unit;
    auto t = toks;
    t[at] = v.str();
    std::string joined = t[0];
    for (std::size_t j = 1; j < t.size(); ++j) joined += ":" + t[j];
    out.push_back(parse_condition(joined));
  }
  return out;
}

}  // namespace attenuvis::weather
