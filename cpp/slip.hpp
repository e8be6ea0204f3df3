// The slip state machine of one wheel's contact (docs: Model § Rolling and slip): no contact
// (lambda = 0), stick (lambda is the multiplier of the rolling constraint g = 0) or slide (lambda =
// sigma mu N, sigma opposing the slip velocity g).
#pragma once

#include "state.hpp"
#include "system.hpp"

namespace trackwheel {

// Multiplier prescribed by the slip state (slide, no contact), or NaN while sticking.
double prescribed_lambda(bool rolling, double friction, const WheelState& ws, const WheelEval& ev);
bool sticking(bool rolling, const WheelState& ws, const WheelEval& ev);

// Decide the contact/slip state from an evaluated state and the multiplier lambda [N] found
// in it; returns true if the state (or the sliding direction) changed.
bool update_slip_state(bool rolling, double friction, double speed, WheelState& ws,
                       const WheelEval& ev, double lambda);

}  // namespace trackwheel
