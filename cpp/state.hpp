// Run settings and the dynamic state of the rail and its wheels (docs: Model § Wheel, § Contact, §
// Rolling and slip, § Equations of motion).
#pragma once

#include <Eigen/Core>
#include <vector>

namespace trackwheel {

enum class Integrator { GeneralizedAlpha = 0, ExplicitRK4 = 1 };
enum class SlipState { Free = 0, Stick = 1, Slip = 2 };

// The travelling window of a run (window.hpp; docs: Model § The travelling window).
struct WindowParams {
  double bay = 0.0;          // d_s [m]; 0: no window (a fixed rail)
  int elements_per_bay = 0;  // n_e,bay [-]
  double origin = 0.0;       // X_w at t = 0: the track coordinate of s = 0 [m]
  double hold = 0.0;         // s at which the rearmost wheel triggers a shift [m]
  bool active() const { return bay > 0.0; }
};

// Numerical settings of one run (the physics is in Model).
struct SimSettings {
  Integrator integrator = Integrator::GeneralizedAlpha;
  double speed = 0.0;          // v [m/s]
  double x_start = 0.0;        // X_0, reference position at t = 0 [m] (wheel w: + x_offset)
  double t_end = 0.0;          // duration [s]
  double dt = 1e-5;            // time step [s]
  double rho_inf = 0.8;        // generalized-alpha spectral radius at infinity [-], in [0, 1]
  double baumgarte = 0.0;      // explicit: Baumgarte alpha [1/s] (0 = off)
  bool rolling = true;         // rolling constraint with slip judgement (false: frictionless)
  int output_every = 1;        // keep every n-th step [-]
  int max_newton = 25;         // Newton iterations per step [-]
  double newton_tol = 1e-11;   // Newton tolerance on displacement corrections [m]
  bool record_energy = false;  // record the total mechanical energy per sample
  bool reuse_jacobian = true;  // modified Newton: keep the factorised matrix while it converges
  long progress_every = 2000;  // steps between progress callbacks [-]
  WindowParams window;         // the travelling window (inactive by default)
};

// Throws std::invalid_argument for settings no integrator can run (dt, t_end, output_every,
// rho_inf or speed out of range; the speed limit is limits::kMaxSpeed).
void check_settings(const SimSettings& settings);

struct WheelState {
  double y = 0.0, ydot = 0.0;          // wheel centre height [m] and velocity [m/s]
  double theta = 0.0, thetadot = 0.0;  // rolling angle [rad] and rate [rad/s]
  double s = 0.0;                      // contact parameter warm start [m]
  SlipState state = SlipState::Stick;
  double sigma = 1.0;  // sign of the sliding friction force on the wheel
  // the brake (WheelParams::brake_torque > 0): locked (theta' held at 0), or turning with the
  // brake torque brake_sign T_b on the wheel (brake_sign = -sign theta', set when it releases)
  bool locked = false;
  double brake_sign = -1.0;
};

struct SimState {
  Eigen::VectorXd e, edot;         // rail coordinates (full, n_dof) [m, m, -, -] and rates
  std::vector<WheelState> wheels;  // one per model wheel
  Eigen::VectorXd body, bodydot;   // (2 n_bodies,) [z_b, phi_b] per vehicle body [m, rad], rates
  Eigen::VectorXd z, zdot;         // sleeper heights [m] and rates (layered supports; else empty)
};

}  // namespace trackwheel
