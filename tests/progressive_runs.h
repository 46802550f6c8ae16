// Running the progressive solver in tests to a stop of the test's choice.
#pragma once

#include <cstdint>

#include "radiosity/progressive/progressive.h"

namespace bounce::test_support {

// Shoots until the point lights have shot and the unshot fraction is at
// most `fraction` (0: no limit), after `max_shots` shots (0: no limit), or
// when nothing is left.
inline void run_until(progressive_state& state, double fraction, std::uint64_t max_shots = 0) {
  while (!(fraction > 0.0 && state.lights_shot && state.stats.unshot_fraction <= fraction) &&
         !(max_shots > 0 && state.stats.shots >= max_shots) && step_progressive(state)) {
  }
}

}  // namespace bounce::test_support
