// Run settings and the dynamic state of the rail and its wheels (docs: Model § Wheel, § Contact, §
// Rolling and slip, § Equations of motion).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "rail.hpp"

namespace trackwheel {

enum class Integrator { GeneralizedAlpha = 0, ExplicitRK4 = 1 };
enum class SlipState { Free = 0, Stick = 1, Slip = 2 };

// The travelling window of a run (window.hpp; docs: Model § The travelling window).
struct WindowParams {
  double bay = 0.0;          // d_s [m]; 0: no window (a fixed rail)
  int elements_per_bay = 0;  // n_e,bay [-]
  double origin = 0.0;       // X_w at t = 0: the track coordinate of s = 0 [m]
  double hold = 0.0;         // s at which the rearmost wheel triggers a shift [m]
  // The track's supports along the run, one per physical sleeper k at X_k = X_0 + k bay from
  // the start window's rear support on (every per-support field, for_each_support_property):
  // streamed into the window's supports as it moves. Empty: the supports of the rail, every
  // bay alike.
  SupportParams supports;
  bool active() const { return bay > 0.0; }
  bool streams() const { return active() && !supports.position.empty(); }
  // The stream has a sleeper that can lose its ballast (a void, tensionless): the run's
  // sleepers are unilateral from the start (Sleepers' unilateral).
  bool streams_unilateral() const { return streams() && supports.any_unilateral(); }
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
  // With reuse_jacobian, the contact block (system.hpp's split iteration matrix): 1 new at every
  // Newton iteration, 0 kept with the whole matrix, -1 by the run (new with a rail profile, an
  // out-of-round wheel, generalized_alpha.hpp).
  int fresh_contact = -1;
  long progress_every = 2000;  // steps between progress callbacks [-]
  WindowParams window;         // the travelling window (inactive by default)
  // record each support's forces and sleeper displacement per kept sample (output.hpp; a fixed
  // rail: the window keeps the envelope along the track only)
  bool record_supports = false;
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

// The dynamic state of a run, on either path: the full path's rail coordinates are the ANCF
// vector, the linear path's the linear track's generalised coordinates q (linear_rail.hpp: the
// y coordinates, or modal); the wheels, the vehicle's bodies and the sleepers are the same.
struct SimState {
  Eigen::VectorXd e, edot;  // rail coordinates (full: n_dof [m, m, -, -]; linear: q) and rates
  std::vector<WheelState> wheels;  // one per model wheel
  Eigen::VectorXd body, bodydot;   // (2 n_bodies,) [z_b, phi_b] per vehicle body [m, rad], rates
  Eigen::VectorXd z, zdot;         // sleeper heights [m] and rates (layered supports; else empty)
};

// True if every coordinate and rate of the state is finite (the watchdog's first check).
inline bool finite_state(const SimState& st) {
  if (!st.e.allFinite() || !st.edot.allFinite() || !st.z.allFinite() || !st.zdot.allFinite())
    return false;
  if (!st.body.allFinite() || !st.bodydot.allFinite()) return false;
  for (const WheelState& w : st.wheels)
    if (!std::isfinite(w.y) || !std::isfinite(w.ydot) || !std::isfinite(w.theta) ||
        !std::isfinite(w.thetadot))
      return false;
  return true;
}

// Accelerations and multipliers that go with a SimState: the rail's e'' (over the state's rail
// coordinates), the border x (each wheel's unknowns, then [z_b'', phi_b''] per vehicle body, as
// BorderLayout places them) and the sleepers' z''. A stepper also keeps its generalized-alpha
// algorithmic accelerations in one (ga_scheme.hpp).
struct Accel {
  Eigen::VectorXd edd;
  Eigen::VectorXd x;
  Eigen::VectorXd zdd;  // sleepers (layered supports; else empty)
};

// Where a path's border keeps each wheel's and each vehicle body's unknowns: per_wheel entries
// per wheel (the wheel's Y_A'' first, its theta'' at `theta` if the path integrates the
// rotation, its contact multiplier at `multiplier`), then [z_b'', phi_b''] per body. The full
// path: [Y'', theta'', lambda]; the linear path: [Y'', N].
struct BorderLayout {
  int n_wheels = 0, n_bodies = 0;
  int per_wheel = 3;
  int theta = 1;       // -1: the rotation is not integrated
  int multiplier = 2;  // lambda (full) or N (linear)
  int y(int w) const { return per_wheel * w; }
  int body(int k) const { return per_wheel * n_wheels + k; }  // k in [0, 2 n_bodies)
  int size() const { return per_wheel * n_wheels + 2 * n_bodies; }
  // the border index of vehicle coordinate i (vehicle.hpp: wheel heights, then bodies)
  int vehicle(int i) const { return i < n_wheels ? y(i) : body(i - n_wheels); }
};

}  // namespace trackwheel
