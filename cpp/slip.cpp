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

}  // namespace trackwheel
