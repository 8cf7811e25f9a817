// The arithmetic a Mie routine runs its recurrences in: one choice shared by
// sphere()/scatter() (attenuvis/mie.hpp) and forward_amplitude()
// (attenuvis/mie/forward_amplitude.hpp).
#pragma once

namespace attenuvis::mie {

// Working precision of the recurrences (Options::precision in attenuvis/mie.hpp).
enum class Precision {
  double_precision,  // IEEE double throughout (fast; the error grows with x)
  extended,          // x87 extended (long double, 64-bit significand) where errors accumulate
};

}  // namespace attenuvis::mie
