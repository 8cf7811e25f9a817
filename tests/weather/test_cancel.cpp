// Settings::cancel: a set flag stops sigma(), the bulk optics and sigma
// tables with Cancelled (cancel.hpp); a flag that stays clear changes no bit
// of any result.  Parametric drops are never memoised (sigma.cpp), so every
// call below integrates afresh: log-normal drops take the contour route
// (contour_extinction.hpp), power-law drops the segmented contour
// (segmented_contour.hpp), and condition_optics() the real axis
// (bulk_optics.hpp).
#include <catch2/catch.hpp>

#include <atomic>
#include <cstring>
#include <string>
#include <vector>

#include "attenuvis/weather.hpp"

using namespace attenuvis::weather;

namespace {

const char* const kLogNormal = "drops:lognormal:r=2um:sg=1.5:N=100";
const char* const kPowerLaw = "drops:powerlaw:nu=4:rmin=0.1um:rmax=10um:N=1000";

MieCondition mie(const char* text) { return std::get<MieCondition>(parse_condition(text)); }

// Same bits, not merely close: the flag is only ever read.
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST_CASE("a set cancel flag stops sigma, optics and tables with Cancelled", "[weather][cancel]") {
  std::atomic<bool> cancel{true};
  Settings s;
  s.cancel = &cancel;
  CHECK_THROWS_AS(sigma(parse_condition(kLogNormal), 550e-9, s), Cancelled);
  CHECK_THROWS_AS(sigma(parse_condition(kPowerLaw), 550e-9, s), Cancelled);
  CHECK_THROWS_AS(condition_optics(mie(kLogNormal), 550e-9, s, {}), Cancelled);
  CHECK_THROWS_AS(condition_bulk_optics(mie(kLogNormal), 550e-9, s), Cancelled);
  // A table is cancelled as a whole, not reported as failing cells; the
  // check per cell stops power-law rows too, which have no quadrature.
  const std::vector<LabelledCondition> rows{{"rain", parse_condition("rain:8")},
                                            {"drops", parse_condition(kLogNormal)}};
  CHECK_THROWS_AS(sigma_table(rows, {550e-9, 1550e-9}, s, 1), Cancelled);
  CHECK_THROWS_AS(sigma_table({rows[0]}, {550e-9}, s, 1), Cancelled);
}

TEST_CASE("a cancel flag left clear changes no bit of the results", "[weather][cancel]") {
  std::atomic<bool> cancel{false};
  // Any tolerance shows it; 1e-3 spares the phase function the resonances'
  // work that tighter ones ask at 550 nm (20 s under ASan at 1e-6).
  Settings plain;
  plain.rel_tolerance = 1e-3;
  Settings flagged = plain;
  flagged.cancel = &cancel;
  for (const char* text : {kLogNormal, kPowerLaw}) {
    INFO(text);
    const Sigma a = sigma(parse_condition(text), 550e-9, plain);
    const Sigma b = sigma(parse_condition(text), 550e-9, flagged);
    CHECK(same_bits(a.per_m, b.per_m));
    CHECK(same_bits(a.error_per_m, b.error_per_m));
  }
  OpticsRequest request;
  request.angles_deg = {0, 90, 180};
  const ConditionOptics a = condition_optics(mie(kLogNormal), 550e-9, plain, request);
  const ConditionOptics b = condition_optics(mie(kLogNormal), 550e-9, flagged, request);
  CHECK(same_bits(a.bulk.extinction.value, b.bulk.extinction.value));
  CHECK(same_bits(a.bulk.scattering.value, b.bulk.scattering.value));
  CHECK(same_bits(a.bulk.asymmetry, b.bulk.asymmetry));
  CHECK(same_bits(a.bulk.backscatter.value, b.bulk.backscatter.value));
  REQUIRE(a.bulk.phase.size() == 3);
  REQUIRE(b.bulk.phase.size() == 3);
  for (std::size_t i = 0; i < 3; ++i) CHECK(same_bits(a.bulk.phase[i], b.bulk.phase[i]));

  const std::vector<LabelledCondition> rows{{"rain", parse_condition("rain:8")},
                                            {"drops", parse_condition(kPowerLaw)}};
  const SigmaTable ta = sigma_table(rows, {550e-9, 1550e-9}, plain, 1);
  const SigmaTable tb = sigma_table(rows, {550e-9, 1550e-9}, flagged, 1);
  REQUIRE(ta.cells.size() == tb.cells.size());
  for (std::size_t i = 0; i < ta.cells.size(); ++i) CHECK(same_bits(ta.cells[i].sigma.per_m, tb.cells[i].sigma.per_m));
  CHECK(tb.settings.cancel == nullptr);  // the table does not keep the caller's flag
}
