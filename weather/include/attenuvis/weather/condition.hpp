// Weather conditions as text, and their extinction coefficient.
//
// CONDITION GRAMMAR (also printed by every parse error):
//
//   clear                        clear air, sigma = 0.00015 1/m (seed paper, Sec. Results)
//   clear:DIST                   clear air with visibility DIST (Koschmieder at Settings::contrast_threshold)
//   visibility:DIST              any atmosphere with visibility DIST (Koschmieder)
//   sigma:VALUE[UNIT]            a given sigma; UNIT /m (default), /km or dB/km  (sigma:0.002, sigma:3dB/km)
//   rain:RATE[:MODEL]            RATE in mm/h; MODEL = seed (default; k=1.17, alpha=0.65) | carbonneau |
//                                p1814 (power laws, read per Settings::convention) | mie (Mie over
//                                Marshall-Palmer drops)
//   snow:wet:RATE | snow:dry:RATE   P.1817-1 a(lambda) S^b, RATE in mm/h (read per Settings::convention)
//   fog:advection | fog:radiation   Mie over the P.1817-1 / seed modified-gamma presets
//   fog:file=PATH                Mie over a size-distribution CSV (distribution_file.hpp)
//   fog:kruse:DIST | fog:kim:DIST | fog:naboulsi-advection:DIST | fog:naboulsi-radiation:DIST
//                                empirical fog from a visibility DIST
//
//   Options after a Mie condition (fog:..., rain:RATE:mie), any order:
//     :m=N+Ki        constant refractive index instead of the water table (e.g. m=1.33+0.001i)
//     :water=NAME    water table: hale-querry (default) | segelstein
//     :N=VALUE       rescale to VALUE particles per cm^3;  :lwc=VALUE  rescale to VALUE g/m^3
//   DIST is a number with unit m or km (bare number: m): 500m, 2km.
//   In tables (expand_conditions), a RATE or DIST may be a sweep A..B (step 1) or A..B/STEP:
//   rain:1..100, snow:dry:0.5..4/0.5, fog:kim:200..1000/200m.
#pragma once

#include <complex>
#include <optional>
#include <string>
#include <vector>

#include "attenuvis/weather/empirical_models.hpp"

namespace attenuvis::weather {

enum class ConditionKind { clear, visibility, sigma, rain_power_law, rain_mie, snow, fog_mie, fog_visibility };

struct Condition {
  std::string text;
  ConditionKind kind = ConditionKind::clear;
  double value = 0;  // rate (mm/h), visibility (m) or sigma (1/m); 0 for the seed's clear air
  std::string model;  // rain preset, fog preset, or the file path of fog:file=
  SnowType snow = SnowType::dry;
  VisibilityFogModel fog_model = VisibilityFogModel::kim;
  std::optional<std::complex<double>> refractive_index;  // :m=
  std::string water_table;                               // :water= (empty: Settings)
  double number_per_cm3 = 0, lwc_g_m3 = 0;               // :N=, :lwc= (0: as given)

  bool needs_mie() const { return kind == ConditionKind::rain_mie || kind == ConditionKind::fog_mie; }
};

// The grammar above, for messages and --help.
const char* condition_grammar();

// Throws std::invalid_argument whose message names the problem and shows the grammar.
// A sweep (A..B) is an error here: use expand_conditions.
Condition parse_condition(const std::string& text);

// Like parse_condition but expands sweeps into one condition per value.
std::vector<Condition> expand_conditions(const std::string& text);

}  // namespace attenuvis::weather
