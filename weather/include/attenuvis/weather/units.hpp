// Units of the extinction coefficient and the quantities that feed it.
//
// sigma is a natural-log (neper) attenuation coefficient: a beam's power falls
// as exp(-sigma d).  Three spellings are used in practice:
//   1/m            (SI; what this library returns),
//   1/km           (nepers per km; the seed paper's tables),
//   dB/km          (ITU-R P.1817-1 "specific attenuation"),
// related by 10 log10(e) = 4.342944819... dB per neper.
//
// ITU-R P.1817-1 gives its rain and snow power laws in dB/km.  The seed paper
// (Schwartz, Vinnikov, Federici, SimAUD 2021, Sec. "Attenuation Coefficients")
// reads the same numbers as 1/km, which makes its rain and snow sigma 4.3429x
// larger; Convention names the two readings so every output can say which.
#pragma once

#include <string>

namespace attenuvis::weather {

// 10 log10(e): decibels per neper of power attenuation.
inline constexpr double kDecibelPerNeper = 4.342944819032518;

// How ITU-R P.1817-1's rain and snow power laws are read.
enum class Convention {
  itu,   // P.1817 power laws are dB/km (as the Recommendation states); default
  seed,  // P.1817 power laws read as 1/km, as the seed paper does
};

// The convention's name, and the convention of a name.
std::string to_string(Convention c);
Convention parse_convention(const std::string& text);  // "itu" | "seed"

// The units sigma is written in.
enum class SigmaUnit { per_m, per_km, dB_per_km };

std::string to_string(SigmaUnit u);                    // "1/m", "1/km", "dB/km"
SigmaUnit parse_sigma_unit(const std::string& text);   // "m", "1/m", "km", "1/km", "dB/km"

// Conversions of sigma between 1/m, 1/km and dB/km (kDecibelPerNeper).
inline double per_m_to_per_km(double s) { return s * 1e3; }
inline double per_km_to_per_m(double s) { return s * 1e-3; }
inline double per_m_to_dB_per_km(double s) { return s * 1e3 * kDecibelPerNeper; }
inline double dB_per_km_to_per_m(double s) { return s * 1e-3 / kDecibelPerNeper; }
double convert_from_per_m(double sigma_per_m, SigmaUnit to);
double convert_to_per_m(double value, SigmaUnit from);

// "550nm", "0.55um", "0.55µm", "5.5e-7m", "10.6um".  A bare number is an error
// (a wavelength without a unit is ambiguous).  Returns metres; throws
// std::invalid_argument outside domain::wavelength (domains.hpp).
double parse_wavelength(const std::string& text);
// A positive length with a unit nm, um, mm or m, in metres, not range-checked
// (a wavelength step); `what` names it in messages.
double parse_length(const std::string& text, const std::string& what);
// "500m", "2km", "2.5 km", "1mi".  A bare number means metres.  Returns metres.
double parse_distance(const std::string& text);
// Metres per distance unit: "" or "m" (1), "km", "mi" (international mile);
// throws std::invalid_argument listing the units for any other.
double distance_unit_m(const std::string& unit);
// The distance units as a list for messages and help: "m, km or mi".
const std::string& distance_units();

}  // namespace attenuvis::weather
