// Conditions as text: the grammar every command line and table accepts.
//
// Each kind of condition (condition.hpp) owns one line of the grammar and its
// help text, in one table (condition_grammar.cpp); condition_grammar() prints
// that table, and every parse error shows it.  The names of models, presets
// and tables come from their registries (registry.hpp).  In short:
//
//   clear | clear:DIST | visibility:DIST | sigma:VALUE[/m|/km|dB/km]
//   rain:RATE[:seed|carbonneau|p1814] | rain:RATE:mie | snow:wet|dry:RATE
//   fog:advection | fog:radiation | fog:file=PATH        (Mie, with options)
//   fog:kruse|kim|naboulsi-advection|naboulsi-radiation:DIST
//
// RATE in mm/h, DIST a distance (units.hpp).  In tables (expand_conditions) a
// RATE, DIST or VALUE may sweep: A..B (step 1) or A..B/STEP, with one unit at
// the end (rain:1..100, snow:dry:0.5..4/0.5, fog:kim:200..1000/200m).
#pragma once

#include <string>
#include <vector>

#include "attenuvis/weather/condition.hpp"

namespace attenuvis::weather {

// The grammar and help of every kind, for messages and --help.
const std::string& condition_grammar();

// Throws std::invalid_argument "bad condition 'TEXT': WHY" followed by the
// grammar.  A sweep (A..B) is an error here: use expand_conditions.
Condition parse_condition(const std::string& text);

// A comma-separated list of conditions ("clear,rain:8,fog:advection") cut
// into its conditions, empty ones dropped.  A comma followed by a digit, '.',
// '+' or '-' (where no condition can start) stays inside the condition, so
// that ":m=1.33,0.001" survives in a list.
std::vector<std::string> split_condition_list(const std::string& text);

// Like parse_condition, but a sweep gives one condition per value, each
// labelled with the text as written with the sweep replaced by its value
// (rain:1..3 -> rain:1, rain:2, rain:3).  The swept numbers are A + i STEP
// below B, then B itself (rain:1..100/10 ends 91, 100; a grid point within
// 1e-6 STEP of B is B), set directly in the typed value.
std::vector<LabelledCondition> expand_conditions(const std::string& text);

}  // namespace attenuvis::weather
