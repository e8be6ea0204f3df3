// The wheel: a rigid disc (X_A, Y_A, theta) carried at constant forward speed (MODEL.md §3).
#pragma once

namespace trackwheel {

struct WheelParams {
  double mass = 10.0;       // M [kg]
  double inertia = 0.05;    // polar moment of inertia J [kg m^2]
  double radius = 0.1;      // undeformed radius rho0 [m]
  double load = 47040.0;    // vertical load F on the centre (car body weight) [N]
  double torque = 0.0;      // external torque about the centre, positive in rolling direction [N m]
  double gravity = 9.8;     // g acting on the wheel mass [m/s^2]
  double total_load() const { return load + mass * gravity; }  // P = F + M g [N]
};

}  // namespace trackwheel
