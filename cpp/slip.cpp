#include "slip.hpp"

#include <algorithm>
#include <cmath>

namespace trackwheel {

double prescribed_lambda(bool rolling, double friction, const WheelState& ws, const WheelEval& ev) {
  if (!rolling || ws.state == SlipState::Free || !ev.cf.active) return 0.0;
  if (ws.state == SlipState::Slip) return ws.sigma * friction * ev.cf.N;
  return NAN;
}

bool sticking(bool rolling, const WheelState& ws, const WheelEval& ev) {
  return rolling && ws.state == SlipState::Stick && ev.cf.active;
}

bool update_slip_state(bool rolling, double friction, double speed, WheelState& ws,
                       const WheelEval& ev, double lambda) {
  const SlipState old = ws.state;
  const double old_sigma = ws.sigma;
  if (!ev.cf.active) {
    ws.state = SlipState::Free;
  } else if (!rolling) {
    ws.state = SlipState::Slip;  // frictionless: prescribed_lambda gives 0 without rolling
  } else if (ws.state == SlipState::Free) {
    // landing: slide until the slip velocity changes sign (stick at once if it is ~0)
    if (std::abs(ev.rk.g) < 1e-9 * std::max(1.0, std::abs(speed))) {
      ws.state = SlipState::Stick;
    } else {
      ws.state = SlipState::Slip;
      ws.sigma = ev.rk.g > 0 ? -1.0 : 1.0;
    }
  } else if (ws.state == SlipState::Stick) {
    if (std::abs(lambda) > friction * ev.cf.N) {
      ws.state = SlipState::Slip;
      ws.sigma = lambda > 0 ? 1.0 : -1.0;
    }
  } else {  // slide: the friction force opposes the slip velocity; stick when it reverses
    if (ev.rk.g * ws.sigma > 0.0) ws.state = SlipState::Stick;
  }
  return ws.state != old || ws.sigma != old_sigma;
}

double wheel_torque(const WheelParams& p, const WheelEval& ev, double lambda) {
  // the normal force of an out-of-round wheel has a moment: -dV/dtheta = -N dDelta rho/dpsi
  return p.torque + lambda * ev.rk.b(10) - ev.cf.N * ev.drho.rx;
}

double brake_torque(const WheelParams& p, const WheelState& ws) {
  return p.brake_torque > 0.0 && !ws.locked ? ws.brake_sign * p.brake_torque : 0.0;
}

bool update_brake_state(const WheelParams& p, WheelState& ws, const WheelEval& ev, double lambda) {
  if (!(p.brake_torque > 0.0)) return false;
  if (ws.locked) {
    // stiction: the brake holds any torque up to T_b; beyond it the wheel turns that way
    const double hold = wheel_torque(p, ev, lambda);
    if (std::abs(hold) <= p.brake_torque) return false;
    ws.locked = false;
    ws.brake_sign = hold > 0.0 ? -1.0 : 1.0;
    return true;
  }
  if (ws.thetadot * ws.brake_sign < 0.0) return false;  // still turning against the brake
  ws.locked = true;
  ws.thetadot = 0.0;
  return true;
}

}  // namespace trackwheel
