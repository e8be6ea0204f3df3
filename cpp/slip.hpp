// The slip state machine of one wheel's contact (docs: Model § Rolling and slip): no contact
// (lambda = 0), stick (lambda is the multiplier of the rolling constraint g = 0) or slide (lambda =
// sigma mu N, sigma opposing the slip velocity g). Beside it, the brake's: a braked wheel turns
// against the brake torque -T_b sign(theta') or is locked, theta' = 0 (docs: Model § Rolling and
// slip).
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

// Torque on the wheel's rotation except the brake's [N m]: T - rho lambda - N dDelta rho/dpsi
// (the last the moment of an out-of-round wheel's normal force).
double wheel_torque(const WheelParams& p, const WheelEval& ev, double lambda);
// The brake's torque on a turning wheel, brake_sign T_b [N m]; 0 when locked or unbraked.
double brake_torque(const WheelParams& p, const WheelState& ws);
// Lock a turning wheel whose spin reached zero (theta' brake_sign >= 0; theta' is set to 0),
// release a locked one whose holding torque |wheel_torque| exceeds T_b; true if it changed.
bool update_brake_state(const WheelParams& p, WheelState& ws, const WheelEval& ev, double lambda);

}  // namespace trackwheel
